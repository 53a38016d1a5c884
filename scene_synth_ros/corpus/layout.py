"""The placement engine of the procedural corpus: where an object may go (off the others,
the doors, the windows and the floor they keep clear, see ``clearance``), and the ways an
interior designer puts one there (against a wall, beside, facing, in a corner, on top)."""
from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import LineString, Polygon
from shapely.prepared import prep

from ..catalog import ModelVariant
from ..geometry import (
    door_zone,
    doors_connected,
    free_space,
    free_space_less,
    support_fraction,
)
from ..scene import PlacedObject, Room, Scene, Wall, rotation
from ..thresholds import MIN_SUPPORT, WINDOW_ZONE_DEPTH
from .clearance import Zone, zones

TOUCH = 0.002           # footprints may touch: 2 mm of numerical slack
# Furniture taller than a window's sill keeps this far from the glass: the design rule's zone
# (``windows_clear``) and 10 cm more, so that curtains draw and the window opens.
WINDOW_CLEARANCE = WINDOW_ZONE_DEPTH + 0.10


def wrap_half_open(yaw: float) -> float:
    """``yaw`` in [-pi, pi), the corpus's convention.

    Not ``scene.wrap_angle``: rounding through ``yaw + pi`` this differs from it in the last
    bits (and maps pi to -pi), so using that would change every corpus room, and with them
    the training data of the shipped weights."""
    return (yaw + math.pi) % (2 * math.pi) - math.pi


class Layout:
    """A room being furnished: the scene so far and the rules every placement must keep."""

    def __init__(self, room: Room, rng: np.random.Generator, meta: dict | None = None):
        self.room = room
        self.rng = rng
        self.scene = Scene(room, [], dict(meta or {}))
        self._floor = prep(room.polygon.buffer(TOUCH, join_style='mitre'))
        self._door_zones = [door_zone(room, d) for d in room.doors]
        self._windows = []
        for w in room.windows:
            wall = room.wall_of(w)
            a = np.asarray(w.position) - wall.direction * w.width / 2
            b = np.asarray(w.position) + wall.direction * w.width / 2
            self._windows.append((LineString([a, b]), w.sill))
        self._first: list[tuple[PlacedObject, Polygon]] = []
        self._shrunk: dict[str, Polygon] = {}   # first-tier footprints less TOUCH, by id
        self._zones: list[Zone] = []      # floor reserved by the pieces placed (``clearance``)
        self.seated: set[str] = set()     # ids of the desks, tables, pianos given a seat
        # The reference robot's free space with the first-tier pieces placed so far (None:
        # not known), so that a piece's path check removes only its own grown footprint
        # instead of growing the union of every footprint again.
        self._robot_free = None

    # ---- the rules --------------------------------------------------------------------
    def fits(self, obj: PlacedObject) -> bool:
        """A first-tier object stays on the floor, off the door zones, off the other
        objects and the floor they keep clear, (if taller than a window sill) away from the
        window, and where the floor it needs kept clear is free."""
        return self._placement(obj) is not None

    def _placement(self, obj: PlacedObject) -> list[Zone] | None:
        """The zones ``obj`` would reserve where it ``fits``, else None."""
        fp = obj.footprint()
        if not self._floor.contains(fp):
            return None
        inner = obj.footprint(TOUCH)
        if any(z.intersects(inner) for z in self._door_zones):
            return None
        if self._first:
            others = [p for _, p in self._first]
            if shapely.intersects(inner, others).any():
                return None
        kept = [z.polygon for z in self._zones if obj.category not in z.allowed]
        if kept and shapely.intersects(inner, kept).any():
            return None
        for line, sill in self._windows:
            if obj.height > sill - 0.05 and fp.distance(line) < WINDOW_CLEARANCE:
                return None
        return self.claim(obj)

    def claim(self, obj: PlacedObject) -> list[Zone] | None:
        """The zones ``obj`` would reserve: the first free alternative of each of its needs
        (``clearance.zones``); None when a need has no free alternative."""
        chosen = []
        for need in zones(obj):
            for zone in need:
                if self._free(zone, obj.category):
                    chosen.append(zone)
                    break
            else:
                return None
        return chosen

    def _free(self, zone: Zone, category: str) -> bool:
        if not self._floor.contains(zone.polygon):
            return False
        # Floor kept for a piece to come (a seat, a nightstand) is not also floor to keep
        # empty, the two would exclude each other; but for the piece it is kept for.
        spots = [z.polygon for z in self._zones
                 if (z.allowed or zone.allowed) and category not in z.allowed]
        if spots and shapely.intersects(zone.polygon.buffer(-TOUCH), spots).any():
            return False
        if zone.walls_only:
            return True
        if zone.allowed and any(z.intersects(zone.polygon) for z in self._door_zones):
            return False
        others = [self._shrunk[o.id] for o, _ in self._first
                  if o.category not in zone.allowed and o.id != zone.owner]
        return not (others and shapely.intersects(zone.polygon, others).any())

    def keeps_path(self, new: PlacedObject | None = None) -> bool:
        """Every door can still be reached from every other for the reference robot
        (``new``: the piece added last, after which the free space is the one before less
        that piece)."""
        if not self.room.doors:
            return True
        if new is not None and self._robot_free is not None:
            free = free_space_less(self._robot_free, new)
        else:
            free = free_space(self.scene)
        self._robot_free = free
        return doors_connected(self.scene, free=free)

    def add(self, obj: PlacedObject, check_path: bool = True,
            zones: list[Zone] | None = None) -> bool:
        """Add a first-tier object that ``fits``, reserving ``zones`` (default: what it
        claims); undone if it cuts the path between doors."""
        kept = self.claim(obj) if zones is None else zones
        before = self._robot_free
        self.scene.objects.append(obj)
        self._first.append((obj, obj.footprint()))
        self._shrunk[obj.id] = obj.footprint(TOUCH)
        self._zones += kept or []
        if not check_path:
            self._robot_free = None
        elif not self.keeps_path(obj):
            self.remove(obj)
            self._robot_free = before
            return False
        return True

    def remove(self, obj: PlacedObject) -> None:
        for child in self.scene.children_of(obj.id):
            self.scene.objects.remove(child)
        self.scene.objects.remove(obj)
        self._first = [(o, p) for o, p in self._first if o is not obj]
        self._zones = [z for z in self._zones if z.owner != obj.id]
        self._shrunk.pop(obj.id, None)
        self._robot_free = None

    def first_tier(self, *categories: str) -> list[PlacedObject]:
        return [o for o, _ in self._first if not categories or o.category in categories]

    def make(self, variant: ModelVariant, xy, yaw: float, z: float = 0.0,
             support: str | None = None) -> PlacedObject:
        return PlacedObject(self.scene.new_id(variant.category), variant.category,
                            variant.model_id, (float(xy[0]), float(xy[1]), float(z)),
                            wrap_half_open(yaw), variant.size, support)

    def try_place(self, variant: ModelVariant, xy, yaw: float) -> PlacedObject | None:
        obj = self.make(variant, xy, yaw)
        kept = self._placement(obj)
        if kept is not None and self.add(obj, zones=kept):
            return obj
        return None

    # ---- ways to place a first-tier object -------------------------------------------
    def open_floor(self, margin: float = 0.0) -> list:
        """The floor no piece, door zone or reserved floor takes, shrunk by ``margin``: its
        pieces, largest first (where a free-standing table goes)."""
        taken = [p for _, p in self._first] + [z.polygon for z in self._zones] \
            + list(self._door_zones)
        free = self.room.polygon.difference(shapely.union_all(taken)) if taken \
            else self.room.polygon
        free = free.buffer(-margin) if margin else free
        parts = list(getattr(free, 'geoms', [free]))
        return sorted((p for p in parts if not p.is_empty), key=lambda p: -p.area)

    def walls_by_length(self, min_length: float) -> list[Wall]:
        walls = [w for w in self.room.walls if w.length >= min_length]
        if not walls:
            return []
        p = np.array([w.length for w in walls])
        order = self.rng.choice(len(walls), size=len(walls), replace=False, p=p / p.sum())
        return [walls[i] for i in order]

    def against_wall(self, variant: ModelVariant, where: str = 'any',
                     tries: int = 6, yaw_jitter: float = 0.0) -> PlacedObject | None:
        """Back to a wall, front into the room. ``where``: 'corner' (side against the
        next wall), 'centre' (middle of the wall) or 'any'."""
        w, d = variant.width, variant.depth
        for wall in self.walls_by_length(w + 0.02):
            lo, hi = w / 2 + 0.005, wall.length - w / 2 - 0.005
            if where == 'corner':
                offsets = [lo, hi] if self.rng.random() < 0.5 else [hi, lo]
            elif where == 'centre':
                offsets = [wall.length / 2 + self.rng.normal(0, 0.05)]
            else:
                offsets = list(self.rng.uniform(lo, hi, size=tries))
            gap = self.rng.uniform(0.0, 0.02)
            for off in offsets:
                xy = wall.point_at(off) + wall.normal * (d / 2 + gap)
                yaw = wall.inward_yaw + (self.rng.normal(0, yaw_jitter) if yaw_jitter else 0)
                obj = self.try_place(variant, xy, yaw)
                if obj is not None:
                    return obj
        return None

    def relative(self, anchor: PlacedObject, variant: ModelVariant, local_xy,
                 yaw_offset: float = 0.0) -> PlacedObject | None:
        """Place at ``local_xy`` in the anchor's frame, turned by ``yaw_offset`` from it."""
        xy = np.asarray(anchor.position[:2]) + rotation(anchor.yaw) @ np.asarray(local_xy, float)
        return self.try_place(variant, xy, anchor.yaw + yaw_offset)

    def beside(self, anchor: PlacedObject, variant: ModelVariant, side: int,
               gap: float = 0.03) -> PlacedObject | None:
        """Next to the anchor, backs aligned (a nightstand by a bed)."""
        x = -anchor.depth / 2 + variant.depth / 2
        y = side * (anchor.width / 2 + gap + variant.width / 2)
        return self.relative(anchor, variant, (x, y))

    def facing(self, anchor: PlacedObject, variant: ModelVariant, distance: float,
               lateral: float = 0.0, yaw_jitter: float = 0.0) -> PlacedObject | None:
        """In front of the anchor, turned towards it (a chair at a desk)."""
        x = anchor.depth / 2 + distance + variant.depth / 2
        return self.relative(anchor, variant, (x, lateral),
                             math.pi + self.rng.normal(0, yaw_jitter) if yaw_jitter else math.pi)

    def ahead(self, anchor: PlacedObject, variant: ModelVariant, distance: float,
              lateral: float = 0.0) -> PlacedObject | None:
        """In front of the anchor, turned the same way (a coffee table before a sofa)."""
        x = anchor.depth / 2 + distance + variant.depth / 2
        return self.relative(anchor, variant, (x, lateral))

    def at_side_facing(self, anchor: PlacedObject, variant: ModelVariant, side: int,
                       gap: float, yaw_jitter: float = 0.0) -> PlacedObject | None:
        """Beside the anchor's end, turned towards its centre (an armchair at the end of a
        coffee table)."""
        y = side * (anchor.width / 2 + gap + variant.depth / 2)
        x = self.rng.uniform(-0.1, 0.1)
        yaw = -side * math.pi / 2 + (self.rng.normal(0, yaw_jitter) if yaw_jitter else 0.0)
        return self.relative(anchor, variant, (x, y), yaw)

    def opposite(self, anchor: PlacedObject, variant: ModelVariant,
                 min_distance: float = 1.2, max_distance: float = 5.0) -> PlacedObject | None:
        """Against the wall the anchor faces, centred on its line of sight (a TV stand
        across from a sofa or the foot of a bed)."""
        origin = np.asarray(anchor.position[:2])
        front = anchor.front
        best = None
        for wall in self.room.walls:
            if np.dot(wall.normal, front) > -0.95:
                continue
            # distance along the line of sight to the wall line
            denom = np.dot(front, -wall.normal)
            t = np.dot(np.asarray(wall.start) - origin, -wall.normal) / denom
            if not (min_distance <= t <= max_distance):
                continue
            off = wall.offset_of(origin + front * t)
            if variant.width / 2 <= off <= wall.length - variant.width / 2:
                if best is None or t < best[0]:
                    best = (t, wall, off)
        if best is None:
            return None
        _, wall, off = best
        for shift in (0.0, 0.3, -0.3, 0.6, -0.6):
            xy = wall.point_at(off + shift) + wall.normal * (variant.depth / 2 + 0.01)
            obj = self.try_place(variant, xy, wall.inward_yaw)
            if obj is not None:
                return obj
        return None

    def in_corner(self, variant: ModelVariant, diagonal: bool, tries: int = 4,
                  yaw_jitter: float = 0.0) -> PlacedObject | None:
        """In a convex corner of the room; ``diagonal`` turns it to face out along the
        corner's bisector (an armchair), otherwise it backs onto one of the two walls."""
        pts = np.asarray(self.room.floor)
        n = len(pts)
        corners = []
        for i in range(n):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % n]
            u, v = a - b, c - b
            if u[0] * v[1] - u[1] * v[0] < 0:      # convex for a counter-clockwise outline
                bis = u / np.linalg.norm(u) + v / np.linalg.norm(v)
                corners.append((i, b, bis / np.linalg.norm(bis)))
        order = self.rng.permutation(len(corners))[:tries]
        for k in order:
            i, b, bis = corners[k]
            if diagonal:
                half_diag = math.hypot(variant.width, variant.depth) / 2
                xy = b + bis * (half_diag + 0.05 + self.rng.uniform(0, 0.15))
                yaw = math.atan2(bis[1], bis[0]) + self.rng.normal(0, yaw_jitter)
            else:
                # back to one wall, side to the other
                along = (pts[(i + 1) % n] - b) if self.rng.random() < 0.5 else (pts[i - 1] - b)
                along = along / np.linalg.norm(along)
                inward = bis - along * np.dot(bis, along)
                inward /= np.linalg.norm(inward)
                xy = (b + along * (variant.width / 2 + 0.02)
                      + inward * (variant.depth / 2 + 0.02))
                yaw = math.atan2(inward[1], inward[0])
            obj = self.try_place(variant, xy, yaw)
            if obj is not None:
                return obj
        return None

    def free(self, variant: ModelVariant, near: PlacedObject | None = None,
             radius: float = 1.2, tries: int = 12, face_anchor: bool = False,
             yaw_jitter: float = 0.0) -> PlacedObject | None:
        """Anywhere on the floor (or within ``radius`` of ``near``), square to the room."""
        x0, y0, x1, y1 = self.room.bounds
        for _ in range(tries):
            if near is not None:
                ang = self.rng.uniform(0, 2 * math.pi)
                r = (max(near.width, near.depth) / 2 + max(variant.width, variant.depth) / 2
                     + self.rng.uniform(0.05, radius))
                xy = np.asarray(near.position[:2]) + r * np.array([math.cos(ang), math.sin(ang)])
            else:
                xy = np.array([self.rng.uniform(x0, x1), self.rng.uniform(y0, y1)])
            if face_anchor and near is not None:
                d = np.asarray(near.position[:2]) - xy
                yaw = math.atan2(d[1], d[0])
            else:
                yaw = self.rng.integers(4) * math.pi / 2
            if yaw_jitter:
                yaw += self.rng.normal(0, yaw_jitter)
            obj = self.try_place(variant, xy, yaw)
            if obj is not None:
                return obj
        return None

    # ---- second tier -----------------------------------------------------------------
    def on_top(self, parent: PlacedObject, variant: ModelVariant, tries: int = 8,
               free_yaw: bool = False, margin: float = 0.02) -> PlacedObject | None:
        """On the parent's top, fully supported and clear of what already stands there."""
        hx = (parent.depth - variant.depth) / 2 - margin
        hy = (parent.width - variant.width) / 2 - margin
        if hx < 0 or hy < 0:
            return None
        siblings = [c.footprint() for c in self.scene.children_of(parent.id)]
        for _ in range(tries):
            local = (self.rng.uniform(-hx, hx), self.rng.uniform(-hy, hy))
            xy = np.asarray(parent.position[:2]) + rotation(parent.yaw) @ np.asarray(local)
            yaw = parent.yaw + (self.rng.uniform(-math.pi, math.pi) if free_yaw
                                else self.rng.normal(0, 0.05))
            obj = self.make(variant, xy, yaw, z=parent.top, support=parent.id)
            fp = obj.footprint()
            if support_fraction(obj, parent) < max(MIN_SUPPORT, 0.98):
                continue
            if siblings and shapely.intersects(fp, siblings).any():
                continue
            self.scene.objects.append(obj)
            return obj
        return None
