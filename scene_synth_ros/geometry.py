"""Physical validity of a furnished room: collisions, floor, door zones, support, and a path
for a robot between the doors.

These are the checks the procedural corpus is held to, the rejection rules of insertion,
and the plausibility metrics of the evaluation: one definition for all three. Footprints are
shapely polygons (``PlacedObject.footprint``) where a room's floor, walls and zones take part;
between two boxes, the box questions at the end of the module are answered exactly in plain
floats, as the design rules ask them of many small pairs.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import math

import numpy as np
import shapely
from shapely.geometry import Point, Polygon

from .allowance import STRICT, Allowance
from .scene import Opening, PlacedObject, Room, Scene, box_corners
from .thresholds import (
    COLLISION_TOLERANCE,
    DOOR_ZONE_LEAST_DEPTH,
    DOOR_ZONE_MIN_DEPTH,
    DOOR_ZONE_SIDE_MARGIN,
    FLOOR_TOLERANCE,
    MIN_SUPPORT,
    ROBOT_WIDTH,
)


def door_zone(room: Room, door: Opening, allowance: Allowance = STRICT) -> Polygon:
    """The area inside a door that must stay clear: the door's swing and a step beyond it
    (no deeper than the ``allowance``'s ``door_depth``)."""
    wall = room.wall_of(door)
    if wall is None:
        raise ValueError(f'the door at {door.position} is not on a wall of the room')
    depth = door_zone_depth(door)
    if allowance.door_depth is not None:
        depth = max(min(depth, allowance.door_depth), DOOR_ZONE_LEAST_DEPTH)
    half = door.width / 2 + DOOR_ZONE_SIDE_MARGIN
    centre = np.asarray(door.position) + wall.normal * depth / 2
    return Polygon(box_corners(centre[0], centre[1], wall.inward_yaw, 2 * half, depth))


def door_zone_depth(door: Opening) -> float:
    """How deep the strict clear zone inside ``door`` reaches into the room."""
    return max(DOOR_ZONE_MIN_DEPTH, door.width + 0.1)


def door_entry_point(room: Room, door: Opening, robot_width: float = ROBOT_WIDTH) -> Point:
    """Where a robot stands just inside a door."""
    wall = room.wall_of(door)
    p = np.asarray(door.position) + wall.normal * (robot_width / 2 + 0.1)
    return Point(p)


def overlaps_any(obj: PlacedObject, others, tol: float = COLLISION_TOLERANCE,
                 allowance: Allowance = STRICT) -> bool:
    """Whether ``obj`` interpenetrates any of ``others`` by more than ``tol`` (the pairwise
    rule of ``collisions``)."""
    mine = obj.footprint(tol / 2)
    return any(mine.intersects(o.footprint(tol / 2)) and _counts(obj, o, tol, allowance)
               for o in others)


def enters_zone(obj: PlacedObject, zone: Polygon, tol: float = COLLISION_TOLERANCE) -> bool:
    """Whether ``obj`` enters a door's clear ``zone`` by more than ``tol`` (the rule of
    ``blocked_doors``)."""
    return zone.intersects(obj.footprint(tol))


def heights_overlap(a: PlacedObject, b: PlacedObject, tol: float = COLLISION_TOLERANCE) -> bool:
    """Whether the heights of ``a`` and ``b`` overlap by more than ``tol``: a picture hung
    above a bed does not collide with it."""
    return (min(a.top, b.top) - max(a.position[2], b.position[2])) > tol


def overlap_depth(a: PlacedObject, b: PlacedObject) -> float:
    """How deep two footprints overlap: the shorter side of the smallest rectangle around
    their intersection (a chair's seat pushed 0.3 m under a table's edge: 0.3)."""
    common = a.footprint().intersection(b.footprint())
    if common.is_empty or common.area <= 0:
        return 0.0
    ring = np.asarray(common.minimum_rotated_rectangle.exterior.coords)
    sides = np.hypot(*np.diff(ring[:3], axis=0).T)
    return float(sides.min())


def collisions(scene: Scene, tol: float = COLLISION_TOLERANCE,
               allowance: Allowance = STRICT) -> list[tuple[str, str]]:
    """Pairs of first-tier objects that interpenetrate by more than ``tol``, at heights that
    overlap, except pairs the ``allowance`` lets one tuck under the other that far."""
    return sorted({(a.id, b.id) for a, b in overlapping(scene.first_tier, tol)
                   if not _tucked(a, b, tol, allowance)})


def overlapping(objs: list[PlacedObject], tol: float = COLLISION_TOLERANCE
                ) -> list[tuple[PlacedObject, PlacedObject]]:
    """The pairs of ``objs`` (in their order) whose footprints interpenetrate by more than
    ``tol`` at heights that overlap by more than ``tol``."""
    if len(objs) < 2:
        return []
    shrunk = [o.footprint(tol / 2) for o in objs]
    a, b = shapely.STRtree(shrunk).query(shrunk, predicate='intersects')
    return [(objs[i], objs[j]) for i, j in zip(a, b, strict=True)
            if i < j and heights_overlap(objs[i], objs[j], tol)]


def _counts(a: PlacedObject, b: PlacedObject, tol: float, allowance: Allowance) -> bool:
    """Whether two footprints found to interpenetrate are a collision: their heights overlap
    and the ``allowance`` does not let one tuck under the other that far."""
    return heights_overlap(a, b, tol) and not _tucked(a, b, tol, allowance)


def _tucked(a: PlacedObject, b: PlacedObject, tol: float, allowance: Allowance) -> bool:
    """Whether the ``allowance`` lets one of two overlapping footprints tuck under the other
    as far as they overlap."""
    allowed = allowance.tuck_depth(a.category, b.category)
    return bool(allowed) and overlap_depth(a, b) <= allowed + tol


def off_floor(scene: Scene, tol: float = FLOOR_TOLERANCE) -> list[str]:
    """Objects whose footprint leaves the floor polygon by more than ``tol``."""
    floor = scene.room.polygon.buffer(tol, join_style='mitre')
    return [o.id for o in scene.objects if not floor.covers(o.footprint())]


def door_swing(room: Room, door: Opening) -> Polygon:
    """Where the door's leaf swings: a square of the door's width inside it."""
    wall = room.wall_of(door)
    if wall is None:
        raise ValueError(f'the door at {door.position} is not on a wall of the room')
    centre = np.asarray(door.position) + wall.normal * door.width / 2
    return Polygon(box_corners(centre[0], centre[1], wall.inward_yaw, door.width, door.width))


def raised(obj: PlacedObject, tol: float = FLOOR_TOLERANCE) -> bool:
    """Whether a first-tier object hangs above the floor (a picture, a wall cabinet)."""
    return obj.position[2] > tol


def blocks_door(room: Room, door: Opening, obj: PlacedObject,
                tol: float = COLLISION_TOLERANCE, allowance: Allowance = STRICT) -> bool:
    """Whether first-tier ``obj`` stands in ``door``'s way: on the floor, in its clear zone;
    hung on the wall, in its leaf's swing below the door's top (a picture beside a door, or
    above it, leaves it free)."""
    if not raised(obj):
        return enters_zone(obj, door_zone(room, door, allowance), tol)
    return obj.position[2] < door.height - tol and enters_zone(obj, door_swing(room, door), tol)


def blocked_doors(scene: Scene, tol: float = COLLISION_TOLERANCE,
                  allowance: Allowance = STRICT) -> list[int]:
    """Indices of doors that a first-tier object blocks (``blocks_door``) by more than
    ``tol``."""
    first = scene.first_tier
    return [k for k, door in enumerate(scene.room.doors)
            if any(blocks_door(scene.room, door, o, tol, allowance) for o in first)]


def support_fraction(child: PlacedObject, parent: PlacedObject) -> float:
    fp = child.footprint()
    return fp.intersection(parent.footprint()).area / fp.area


def rests_on(child: PlacedObject, parent: PlacedObject, allowance: Allowance = STRICT,
             tol: float = 0.01) -> bool:
    """Whether ``child``'s base is where ``parent`` holds things: its top (up to the
    allowance's ``settle`` above it), or inside it no lower than the allowance lets that
    category hold them."""
    base = child.position[2]
    if -tol <= base - parent.top <= tol + allowance.settle:
        return True
    low = allowance.lowest_inside(parent.category)
    return (low is not None
            and parent.position[2] + low * parent.size[2] - tol <= base < parent.top)


def under_supported(scene: Scene, minimum: float = MIN_SUPPORT,
                    allowance: Allowance = STRICT) -> list[str]:
    """Second-tier objects less than ``minimum`` on their parent, or not resting on it
    (``rests_on``)."""
    by_id = {o.id: o for o in scene.objects}
    out = []
    for o in scene.second_tier:
        parent = by_id.get(o.support)
        if (parent is None or not rests_on(o, parent, allowance)
                or support_fraction(o, parent) < minimum):
            out.append(o.id)
    return out


def free_space(scene: Scene, robot_width: float = ROBOT_WIDTH):
    """Where the centre of a round robot of ``robot_width`` can be."""
    r = robot_width / 2
    room = scene.room
    free = room.remembered(('floor shrunk', r),
                           lambda: room.polygon.buffer(-r, join_style='mitre'))
    obstacles = [o.footprint() for o in scene.first_tier]
    if obstacles:
        free = free.difference(shapely.union_all(obstacles).buffer(r))
    return free


def free_space_less(free, obj: PlacedObject, robot_width: float = ROBOT_WIDTH):
    """``free`` (a room's ``free_space``) less where first-tier ``obj`` keeps the robot's
    centre away: the free space of the room with ``obj`` in it, as a set, without the union
    of every footprint (it can differ from ``free_space`` in the last bits of a vertex)."""
    return free.difference(obj.footprint().buffer(robot_width / 2))


def door_parts(room: Room, free, robot_width: float = ROBOT_WIDTH):
    """The pieces of the free space ``free`` and, per door, the index of the piece that holds
    its entry point (None where the robot cannot stand inside that door)."""
    parts = [p for p in getattr(free, 'geoms', [free]) if not p.is_empty]
    owners = []
    for door in room.doors:
        p = room.remembered(('door entry', door, robot_width),
                            lambda door=door: door_entry_point(room, door, robot_width))
        owners.append(next((i for i, part in enumerate(parts) if part.distance(p) < 1e-6),
                           None))
    return parts, owners


def owners_connected(owners) -> bool:
    """Whether the robot stands inside every door (``door_parts``'s owners) and all of them
    lie in one piece of free space."""
    return None not in owners and len(set(owners)) == 1


def doors_connected(scene: Scene, robot_width: float = ROBOT_WIDTH, free=None) -> bool:
    """Whether the robot can stand inside every door and drive between all of them
    (``free``: the room's ``free_space``, when the caller has it)."""
    if not scene.room.doors:
        return True
    if free is None:
        free = free_space(scene, robot_width)
    return owners_connected(door_parts(scene.room, free, robot_width)[1])


@dataclass
class ValidityReport:
    """Everything physically wrong with a scene; ``ok`` when nothing is."""

    collisions: list[tuple[str, str]] = field(default_factory=list)
    off_floor: list[str] = field(default_factory=list)
    blocked_doors: list[int] = field(default_factory=list)
    under_supported: list[str] = field(default_factory=list)
    doors_connected: bool = True

    @property
    def ok(self) -> bool:
        return not (self.collisions or self.off_floor or self.blocked_doors
                    or self.under_supported) and self.doors_connected

    def summary(self) -> str:
        if self.ok:
            return 'valid'
        parts = []
        if self.collisions:
            parts.append(f'{len(self.collisions)} colliding pairs {self.collisions}')
        if self.off_floor:
            parts.append(f'off the floor: {self.off_floor}')
        if self.blocked_doors:
            parts.append(f'blocked doors: {self.blocked_doors}')
        if self.under_supported:
            parts.append(f'under-supported: {self.under_supported}')
        if not self.doors_connected:
            parts.append(f'doors not connected for a {ROBOT_WIDTH} m robot')
        return '; '.join(parts)


def check_scene(scene: Scene, allowance: Allowance = STRICT) -> ValidityReport:
    """Every check, with what ``allowance`` lets a room do (``allowance.STRICT``: nothing)."""
    return ValidityReport(collisions(scene, allowance=allowance), off_floor(scene),
                          blocked_doors(scene, allowance=allowance),
                          under_supported(scene, allowance=allowance),
                          doors_connected(scene))


# ---- footprints as exact boxes --------------------------------------------------------
# The design rules compare many small pairs of boxes, where shapely's and numpy's per-call
# overhead dominates: these answer box questions in plain floats, exactly.

def local_xy(obj: PlacedObject, xy) -> tuple[float, float]:
    """A world point in ``obj``'s frame: x towards its front, y to its left."""
    dx, dy = float(xy[0]) - obj.position[0], float(xy[1]) - obj.position[1]
    c, s = math.cos(obj.yaw), math.sin(obj.yaw)
    return c * dx + s * dy, c * dy - s * dx


def local_box(obj: PlacedObject, x0: float, x1: float, y0: float, y1: float) -> Polygon:
    """The rectangle [x0, x1] x [y0, y1] of ``obj``'s frame (x to its front, y to its left)
    in the world: a strip before its front, beside it, behind it."""
    c, s = math.cos(obj.yaw), math.sin(obj.yaw)
    ox, oy = obj.position[0], obj.position[1]
    return Polygon([(ox + c * x - s * y, oy + s * x + c * y)
                    for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))])


def nearest_point(obj: PlacedObject, xy) -> tuple[float, float]:
    """The point of ``obj``'s footprint nearest to ``xy`` (``xy`` itself when inside)."""
    x, y = local_xy(obj, xy)
    x = min(max(x, -obj.depth / 2), obj.depth / 2)
    y = min(max(y, -obj.width / 2), obj.width / 2)
    c, s = math.cos(obj.yaw), math.sin(obj.yaw)
    return obj.position[0] + c * x - s * y, obj.position[1] + s * x + c * y


def corners(obj: PlacedObject) -> list[tuple[float, float]]:
    """The footprint's corners, as ``PlacedObject.corners`` but without numpy (these rules
    compare many small pairs, where array overhead dominates)."""
    c, s = math.cos(obj.yaw), math.sin(obj.yaw)
    x0, y0 = obj.position[0], obj.position[1]
    hx, hy = obj.depth / 2, obj.width / 2
    return [(x0 + c * x - s * y, y0 + s * x + c * y)
            for x, y in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]


def _half_extent(obj: PlacedObject, ux: float, uy: float) -> float:
    c, s = math.cos(obj.yaw), math.sin(obj.yaw)
    return abs(c * ux + s * uy) * obj.depth / 2 + abs(c * uy - s * ux) * obj.width / 2


def overlap(a: PlacedObject, b: PlacedObject) -> bool:
    """Whether two footprints touch or overlap (separating-axis test on their four axes)."""
    dx, dy = b.position[0] - a.position[0], b.position[1] - a.position[1]
    for o in (a, b):
        c, s = math.cos(o.yaw), math.sin(o.yaw)
        for ux, uy in ((c, s), (-s, c)):
            if abs(dx * ux + dy * uy) > _half_extent(a, ux, uy) + _half_extent(b, ux, uy):
                return False
    return True


def footprint_gap(a: PlacedObject, b: PlacedObject) -> float:
    """Metres between two footprints, 0 when they overlap: shapely's distance computed for
    rectangles directly (apart, two convex polygons are nearest at a corner of one)."""
    if overlap(a, b):
        return 0.0
    return min(min(math.dist(v, nearest_point(q, v)) for v in corners(p))
               for p, q in ((a, b), (b, a)))


def within_reach(a: PlacedObject, b: PlacedObject, reach: float) -> bool:
    """Whether the footprints of ``a`` and ``b`` are at most ``reach`` apart (checked first on
    the circles around them, which rules out most pairs at once)."""
    bound = (math.hypot(a.width, a.depth) + math.hypot(b.width, b.depth)) / 2 + reach
    if math.dist(a.position[:2], b.position[:2]) > bound:
        return False
    return footprint_gap(a, b) <= reach
