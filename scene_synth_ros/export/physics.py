"""The physical model of every exported object: collision pieces, mass and inertia.

One definition for every format (SDF, MJCF, URDF, USD): each placed object becomes a rigid
``Body`` at its pose, made of convex collision pieces, all boxes in the object's own frame
(front +x, width along y, z up from the object's bottom).

Collision pieces
    Most categories collide as their box: case furniture, beds, sofas, appliances, bathroom
    fittings and everything second tier. A box is wrong where the model is an open frame
    whose empty space matters to a robot or to other furniture, so these collide as a few
    boxes fitted to the model's parts (``OPEN_FRAME``): tables and desks (the knee space
    under the top, where chairs tuck in and a robot's laser sees legs, not a wall), seats on
    legs (the space under the seat and in front of the back), things on a pole or a stand
    (floor lamps, fans, coat stands and racks, whiteboards: a thin pole, not a solid column),
    a kitchen island (the overhang that bar stools tuck under) and a kitchen sink (a worktop
    to set things on, and a tap above it). Their
    pieces are the bounding boxes of the mesh's parts, merged greedily while a merge adds
    little empty space (``MergeRule``) and until at most ``max_pieces`` remain: a desk keeps
    its top and legs, a chair its seat, back and legs.

Clearance
    Every piece is clipped to the object's box moved in by ``clearance`` on each side
    (5 mm, half the 1 cm by which synthesis and the corpus let two footprints
    interpenetrate: ``thresholds.COLLISION_TOLERANCE``), and further in on a side whose
    corners stand outside where the object may be: through a wall for a first-tier object
    (``thresholds.FLOOR_TOLERANCE`` allows 1 cm), beyond its parent's top (less the clearance)
    for a second-tier one, which may overhang by 30 % and would otherwise reach into a
    taller neighbour of its parent. So the exported poses start without interpenetration and
    rest as they are; the visual mesh keeps the full size. Heights are never clipped: a
    first-tier body stands on the floor (z = 0) and a second-tier one on its parent's top.

Tucked objects
    A room may tuck one object under another (a chair's seat under a table's top, as a data
    set's allowance permits: ``allowance.Allowance``). Where two first-tier footprints
    overlap by more than the collision tolerance at overlapping heights, the smaller
    object's pieces are cut back out of the larger's (``untucked_pieces``): each piece that
    would start inside one of the host's loses its top, its bottom (if it does not stand on
    the floor) or the side towards the host, whichever keeps the most of it. A chair's front
    legs end under the table's apron, its arms stop at the apron's face; both bodies start
    apart and rest.

Things inside their parent
    A data set's rooms stand things inside their parent (a book on a shelf board, a bottle
    in a fridge: ``allowance.Allowance.inside``), below its top. The parent's pieces are then
    hollowed where the child stands (``hollowed_pieces``): the child's box, ``clearance``
    wider on each side and above, is cut out of them down to the child's base, so the child
    rests on the solid left below it, a board at that height, and the walls left around it
    keep it there.

Mounted objects
    A first-tier object whose base is above the floor (a data set's wall cabinet or shelf,
    which the room keeps by height) has nothing under it to stand on: it is exported fixed,
    as the walls it hangs on are (``Body.fixed``).

Mass and inertia
    mass = the object's box volume x a bulk density per category group (``DENSITIES``, kg
    per cubic metre of bounding box, set from typical masses: a 1.4 m desk 30 kg, a double
    bed 90 kg, a washing machine 60 kg, a cup 0.2 kg). The mass is spread uniformly over
    the collision pieces, which gives the centre of mass and the inertia tensor (boxes and
    the parallel-axis theorem), so a chair's mass sits in its legs, seat and back.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache
import math

import numpy as np
from shapely.geometry import LineString, Point, Polygon

from ..catalog import Catalog, ModelVariant
from ..files import safe_name
from ..geometry import collisions, raised
from ..house import HouseScene
from ..meshes import build_parts, variant_for
from ..scene import PlacedObject, Room, Scene, box_corners, rotation
from ..thresholds import COLLISION_TOLERANCE

GRAVITY = 9.81            # m/s^2, along -z

# kg per cubic metre of the object's bounding box, by group (see the module docstring).
DENSITIES: dict[str, tuple[float, tuple[str, ...]]] = {
    'beds': (27.0, ('double bed', 'single bed', 'bunker bed', 'baby bed', 'daybed')),
    'case furniture': (60.0, ('wardrobe', 'stand', 'dresser', 'dressing table', 'tv stand',
                              'shelving', 'shoes cabinet', 'cabinet', 'sideboard',
                              'shoe bench')),
    'tables': (40.0, ('desk', 'coffee table', 'dining table', 'console table')),
    'seats': (30.0, ('office chair', 'straight chair', 'chair', 'stool', 'bench chair',
                     'dining chair', 'bar stool')),
    'upholstered': (40.0, ('sofa', 'sofa chair', 'armchair', 'ottoman')),
    'stands': (20.0, ('floor lamp', 'pedestal fan', 'hanger', 'whiteboard', 'trash can',
                      'coat rack')),
    # base cabinets under a worktop: a 0.6 m unit with its top about 40 kg
    'kitchen units': (110.0, ('counter', 'kitchen sink', 'kitchen island')),
    # a fridge-freezer 70 to 100 kg, a dishwasher 45 kg, a cooker 50 kg
    'kitchen appliances': (140.0, ('fridge', 'dishwasher', 'stove')),
    # a microwave 12 kg, an espresso machine 8 kg, a toaster 2 kg
    'small appliances': (200.0, ('microwave', 'coffee machine', 'toaster')),
    'appliances': (200.0, ('washer', 'water machine', 'piano', 'fireplace')),
    'ceramics': (150.0, ('toilet', 'bidet', 'sink')),
    'bath and shower': (50.0, ('bathtub', 'shower')),
    'electronics': (150.0, ('television', 'laptop', 'console', 'loudspeaker')),
    'paper': (600.0, ('book',)),
    'tableware': (250.0, ('cup', 'glass', 'bottle', 'fruit bowl', 'fishbowl', 'vase')),
    'decor': (60.0, ('table lamp', 'plant', 'toy')),
}
DEFAULT_DENSITY = 100.0   # a category of someone else's data set
OPEN_FRAME = frozenset(DENSITIES['tables'][1] + DENSITIES['seats'][1]
                       + ('floor lamp', 'pedestal fan', 'hanger', 'whiteboard', 'coat rack',
                          'kitchen island', 'kitchen sink'))


def density(category: str) -> float:
    """Bulk density (kg per m^3 of bounding box) of ``category``."""
    for value, members in DENSITIES.values():
        if category in members:
            return value
    return DEFAULT_DENSITY


@dataclass(frozen=True)
class MergeRule:
    """When two collision pieces of an open-frame model become one box: while the merge
    adds less than ``waste`` of the model's box volume in empty space, and then, cheapest
    first, until no more than ``max_pieces`` remain. Parts smaller than ``min_part`` of the
    box volume (handles, badges, markers) are dropped first, unless they touch the floor
    (casters and feet are what the model stands on)."""

    waste: float = 0.02
    max_pieces: int = 8
    min_part: float = 2e-4


@dataclass(frozen=True)
class PhysicsConfig:
    """How objects are modelled; the defaults are what every exporter uses."""

    clearance: float = COLLISION_TOLERANCE / 2    # metres each side of a piece moves in
    merge: MergeRule = field(default_factory=MergeRule)
    friction: float = 0.6                       # sliding friction, wood and fabric on floors


DEFAULT_PHYSICS = PhysicsConfig()


@dataclass(frozen=True)
class Piece:
    """One convex collision piece: a box in the object's frame."""

    centre: tuple[float, float, float]
    size: tuple[float, float, float]            # along the object's x (depth), y, z


@dataclass(frozen=True, eq=False)
class Body:
    """A placed object as a rigid body."""

    id: str
    category: str
    variant: ModelVariant                       # the catalog model its visual mesh shows
    position: tuple[float, float, float]
    yaw: float
    pieces: tuple[Piece, ...]
    mass: float
    com: tuple[float, float, float]             # centre of mass, object frame
    inertia: np.ndarray                         # 3x3 about the centre of mass, object frame
    support: str | None = None
    fixed: bool = False                         # mounted: held by the wall, not by physics

    def principal_inertia(self) -> tuple[np.ndarray, np.ndarray]:
        """Principal moments (ascending) and the rotation whose columns are their axes, a
        proper rotation (determinant +1), for formats that take a diagonal inertia."""
        moments, axes = np.linalg.eigh(self.inertia)
        if np.linalg.det(axes) < 0:
            axes[:, 0] = -axes[:, 0]
        return moments, axes


# ---- collision pieces ---------------------------------------------------------------------
def _volume(lo: np.ndarray, hi: np.ndarray) -> float:
    return float(np.prod(np.maximum(hi - lo, 0.0)))


def _merged_waste(a, b) -> tuple[float, tuple[np.ndarray, np.ndarray]]:
    lo, hi = np.minimum(a[0], b[0]), np.maximum(a[1], b[1])
    overlap = _volume(np.maximum(a[0], b[0]), np.minimum(a[1], b[1]))
    filled = _volume(*a) + _volume(*b) - overlap
    return _volume(lo, hi) - filled, (lo, hi)


def _merge(boxes: list, rule: MergeRule, total: float) -> list:
    boxes = list(boxes)
    while len(boxes) > 1:
        best = None
        for i in range(len(boxes)):
            for j in range(i + 1, len(boxes)):
                waste, merged = _merged_waste(boxes[i], boxes[j])
                if best is None or waste < best[0]:
                    best = (waste, i, j, merged)
        waste, i, j, merged = best
        if waste > rule.waste * total and len(boxes) <= rule.max_pieces:
            break
        boxes = [b for k, b in enumerate(boxes) if k not in (i, j)] + [merged]
    return boxes


@lru_cache(maxsize=2048)
def model_pieces(variant: ModelVariant, rule: MergeRule = MergeRule()) -> tuple[Piece, ...]:
    """The collision pieces of a catalog model, before any clearance: its box, or for an
    ``OPEN_FRAME`` category the merged bounding boxes of its parts."""
    w, d, h = variant.size
    if variant.category not in OPEN_FRAME:
        return (Piece((0.0, 0.0, h / 2), (d, w, h)),)
    total = w * d * h
    boxes = [(p.bounds[0].copy(), p.bounds[1].copy()) for p in build_parts(variant)]
    # Small parts go, except those the model stands on (casters, feet).
    boxes = [b for b in boxes if _volume(*b) >= rule.min_part * total or b[0][2] < 1e-6]
    # A part inside another adds nothing to the collision shape.
    boxes = [b for i, b in enumerate(boxes)
             if not any(k != i and np.all(o[0] <= b[0] + 1e-9) and np.all(b[1] <= o[1] + 1e-9)
                        and (_volume(*o) > _volume(*b) or k < i)
                        for k, o in enumerate(boxes))]
    boxes = _merge(boxes, rule, total)
    boxes.sort(key=lambda b: (float(b[0][2]), float(b[0][0]), float(b[0][1])))
    return tuple(Piece(tuple(float(v) for v in (lo + hi) / 2),
                       tuple(float(v) for v in hi - lo)) for lo, hi in boxes)


# Corners of a footprint (back-right, front-right, front-left, back-left) and, for each, the
# sides it lies on (front +x = 0, back -x = 1, left +y = 2, right -y = 3) with the unit step,
# in the object's frame, that moving each of those sides in gives it.
_CORNERS = ((-1, -1), (1, -1), (1, 1), (-1, 1))
_SIDES = (((1, (1.0, 0.0)), (3, (0.0, 1.0))), ((0, (-1.0, 0.0)), (3, (0.0, 1.0))),
          ((0, (-1.0, 0.0)), (2, (0.0, -1.0))), ((1, (1.0, 0.0)), (2, (0.0, -1.0))))


def _shift_into(corner: np.ndarray, step: np.ndarray, reach: float, region: Polygon) -> float:
    """How far ``corner`` must move along ``step`` to enter ``region`` (inf if it does not
    within ``reach``)."""
    ray = LineString([corner, corner + step * reach])
    inside = ray.intersection(region)
    return math.inf if inside.is_empty else Point(corner).distance(inside)


def outside_insets(obj: PlacedObject, region: Polygon, rounds: int = 4) -> np.ndarray:
    """How far each side of ``obj``'s footprint (front +x, back -x, left +y, right -y) must
    move in so that no corner stands outside ``region``. A corner outside moves the one of
    its two sides that brings it in with the shorter move (a footprint through a wall along
    one side only moves that side); where neither does alone, both move by its distance from
    the region, which brings a corner into a convex region. A corner of the region inside
    the footprint moves the side nearest to it. Repeated, as moving one side moves two
    corners."""
    half = np.array([obj.depth / 2, obj.width / 2])
    turn = rotation(obj.yaw)
    centre = np.asarray(obj.position[:2], dtype=float)
    insets = np.zeros(4)
    for _ in range(rounds):
        lo = -half + (insets[1], insets[3])
        hi = half - (insets[0], insets[2])
        delta = np.zeros(4)
        for (sx, sy), sides in zip(_CORNERS, _SIDES, strict=True):
            local = np.where([sx > 0, sy > 0], hi, lo)
            corner = turn @ local + centre
            if region.covers(Point(corner)):
                continue
            reach = (hi - lo).max()
            moves = [(_shift_into(corner, turn @ np.asarray(step), reach, region), side)
                     for side, step in sides]
            need, side = min(moves)
            if math.isfinite(need):
                delta[side] = max(delta[side], need)
            else:
                far = region.exterior.distance(Point(corner))
                for _, side in moves:
                    delta[side] = max(delta[side], far)
        # A corner of the region (an L-shaped room's inner corner) inside the footprint
        # moves the side nearest to it.
        for vertex in np.asarray(region.exterior.coords)[:-1]:
            local = turn.T @ (vertex - centre)
            if np.all(local > lo + 1e-9) and np.all(local < hi - 1e-9):
                gaps = (hi[0] - local[0], local[0] - lo[0], hi[1] - local[1], local[1] - lo[1])
                side = int(np.argmin(gaps))
                delta[side] = max(delta[side], gaps[side])
        if not delta.any():
            break
        insets += delta
    return insets


def clipped_pieces(pieces: tuple[Piece, ...], size: tuple[float, float, float],
                   insets: np.ndarray) -> tuple[Piece, ...]:
    """``pieces`` cut to the object's footprint moved in by ``insets`` (front, back, left,
    right); a piece left thinner than 1 mm across is dropped. Never more than half the
    object's width or depth in all, so a small object keeps a body."""
    w, d, _ = size
    fx, bx, ly, ry = (float(v) for v in insets)
    scale_x = min(1.0, 0.5 * d / max(fx + bx, 1e-12))
    scale_y = min(1.0, 0.5 * w / max(ly + ry, 1e-12))
    lo_lim = np.array([-d / 2 + bx * scale_x, -w / 2 + ry * scale_y, -np.inf])
    hi_lim = np.array([d / 2 - fx * scale_x, w / 2 - ly * scale_y, np.inf])
    out = []
    for p in pieces:
        c, s = np.asarray(p.centre), np.asarray(p.size)
        lo, hi = np.maximum(c - s / 2, lo_lim), np.minimum(c + s / 2, hi_lim)
        if np.all(hi - lo > 1e-3):
            out.append(Piece(tuple(float(v) for v in (lo + hi) / 2),
                             tuple(float(v) for v in hi - lo)))
    if not out:                       # every part cut away: the region itself, floor to top
        lo = np.array([lo_lim[0], lo_lim[1], min(p.centre[2] - p.size[2] / 2 for p in pieces)])
        hi = np.array([hi_lim[0], hi_lim[1], max(p.centre[2] + p.size[2] / 2 for p in pieces)])
        out.append(Piece(tuple(float(v) for v in (lo + hi) / 2),
                         tuple(float(v) for v in hi - lo)))
    return tuple(out)


# ---- mass and inertia ---------------------------------------------------------------------
def mass_properties(pieces: tuple[Piece, ...], mass: float
                    ) -> tuple[tuple[float, float, float], np.ndarray]:
    """Centre of mass and inertia tensor about it of ``mass`` spread uniformly over the
    pieces' volume (overlaps counted twice, which only shifts weight towards them)."""
    vols = np.array([float(np.prod(p.size)) for p in pieces])
    masses = mass * vols / vols.sum()
    centres = np.array([p.centre for p in pieces])
    com = (masses[:, None] * centres).sum(axis=0) / mass
    inertia = np.zeros((3, 3))
    for m, p, c in zip(masses, pieces, centres, strict=True):
        sx, sy, sz = p.size
        inertia += np.diag([sy * sy + sz * sz, sx * sx + sz * sz, sx * sx + sy * sy]) * m / 12
        r = c - com
        inertia += m * (np.dot(r, r) * np.eye(3) - np.outer(r, r))
    return tuple(float(v) for v in com), inertia


def body_of(obj: PlacedObject, room: Room, parent: PlacedObject | None = None,
            config: PhysicsConfig = DEFAULT_PHYSICS, catalog: Catalog | None = None) -> Body:
    """``obj`` as a rigid body in ``room``, standing on the floor or on ``parent``. Its
    pieces keep inside the floor, or inside the parent's footprint (less the clearance):
    an overhanging second-tier object would otherwise reach into the parent's neighbour,
    as a plant on a nightstand does into a taller desk beside it. ``catalog``: the user's
    models the object may show (``meshes.variant_for``)."""
    variant = variant_for(obj, catalog)
    region = room.polygon if parent is None else parent.footprint(config.clearance)
    insets = np.full(4, config.clearance) + outside_insets(obj, region)
    pieces = clipped_pieces(model_pieces(variant, config.merge), obj.size, insets)
    mass = density(obj.category) * obj.width * obj.depth * obj.height
    com, inertia = mass_properties(pieces, mass)
    mounted = parent is None and raised(obj)
    return Body(obj.id, obj.category, variant, tuple(float(v) for v in obj.position),
                float(obj.yaw), pieces, float(mass), com, inertia, obj.support, mounted)


def _world_box(piece: Piece, body: Body) -> tuple[np.ndarray, float, float]:
    """A piece's footprint corners in the world and its bottom and top heights."""
    c, s = np.asarray(piece.centre), np.asarray(piece.size)
    x, y = c[:2] @ rotation(body.yaw).T + np.asarray(body.position[:2])
    world = box_corners(x, y, body.yaw, width=s[1], depth=s[0])    # x is a piece's depth
    z = body.position[2] + c[2]
    return world, z - s[2] / 2, z + s[2] / 2


def _cut(piece: Piece, tucked: Body, host_piece: Piece, host: Body, gap: float
         ) -> tuple[Piece, ...] | None:
    """``piece`` of ``tucked`` cut out of ``host``'s ``host_piece`` (None: they are apart)."""
    corners, bottom, top = _world_box(host_piece, host)
    lo, hi = (np.asarray(piece.centre) - np.asarray(piece.size) / 2,
              np.asarray(piece.centre) + np.asarray(piece.size) / 2)
    # the host piece in the tucked object's frame: its bounds there (around it when turned)
    local = (corners - np.asarray(tucked.position[:2])) @ rotation(tucked.yaw)
    qlo = np.array([*local.min(axis=0), bottom - tucked.position[2]])
    qhi = np.array([*local.max(axis=0), top - tucked.position[2]])
    if np.any(np.minimum(hi, qhi) - np.maximum(lo, qlo) <= 0):
        return None
    mine = Polygon(_world_box(piece, tucked)[0])
    if not mine.intersects(Polygon(corners)) or mine.intersection(Polygon(corners)).area <= 0:
        return None
    options = []
    for axis in range(3):
        low_side, high_side = hi.copy(), lo.copy()
        low_side[axis] = qlo[axis] - gap            # keep what lies below the host's piece
        high_side[axis] = qhi[axis] + gap           # keep what lies above it
        options.append((lo, low_side))
        if axis < 2 or lo[2] > 1e-6:                # a piece on the floor keeps its foot
            options.append((high_side, hi))
    kept = [(float(np.prod(b - a)), a, b) for a, b in options if np.all(b - a > 1e-3)]
    if not kept:
        return ()
    _, a, b = max(kept, key=lambda k: k[0])
    return (Piece(tuple(float(v) for v in (a + b) / 2), tuple(float(v) for v in b - a)),)


def untucked_pieces(tucked: Body, host: Body, gap: float) -> tuple[Piece, ...]:
    """``tucked``'s pieces cut back until none starts inside one of ``host``'s, ``gap``
    apart (see the module docstring); its pieces as they are where nothing needs cutting."""
    pieces = list(tucked.pieces)
    for q in host.pieces:
        out = []
        for p in pieces:
            cut = _cut(p, tucked, q, host, gap)
            out += [p] if cut is None else list(cut)
        pieces = out or pieces[:1]
    return tuple(pieces)


def _local_bounds(inner: Body, host: Body) -> tuple[np.ndarray, np.ndarray]:
    """The box around ``inner``'s pieces in ``host``'s frame (axis-aligned there)."""
    corners, bottoms, tops = [], [], []
    for p in inner.pieces:
        world, bottom, top = _world_box(p, inner)
        corners.append(world)
        bottoms.append(bottom)
        tops.append(top)
    local = (np.vstack(corners) - np.asarray(host.position[:2])) @ rotation(host.yaw)
    lo = np.array([*local.min(axis=0), min(bottoms) - host.position[2]])
    hi = np.array([*local.max(axis=0), max(tops) - host.position[2]])
    return lo, hi


def _box_less(piece: Piece, lo: np.ndarray, hi: np.ndarray) -> tuple[Piece, ...]:
    """``piece`` less the box [``lo``, ``hi``], as up to six boxes: the slabs below and above
    it, then beside it along x, then along y."""
    a = np.asarray(piece.centre) - np.asarray(piece.size) / 2
    b = np.asarray(piece.centre) + np.asarray(piece.size) / 2
    c, d = np.maximum(a, lo), np.minimum(b, hi)
    if np.any(d - c <= 0):
        return (piece,)
    slabs = []
    inner_lo, inner_hi = a.copy(), b.copy()
    for axis in (2, 0, 1):
        below, above = (inner_lo.copy(), inner_hi.copy()), (inner_lo.copy(), inner_hi.copy())
        below[1][axis] = c[axis]
        above[0][axis] = d[axis]
        slabs += [below, above]
        inner_lo[axis], inner_hi[axis] = c[axis], d[axis]
    return tuple(Piece(tuple(float(v) for v in (p + q) / 2), tuple(float(v) for v in q - p))
                 for p, q in slabs if np.all(q - p > 1e-3))


def hollowed_pieces(host: Body, inner: Body, gap: float) -> tuple[Piece, ...]:
    """``host``'s pieces less the space ``inner`` stands in inside it: its box, ``gap`` wider
    on each side and above, from its base up (see the module docstring)."""
    lo, hi = _local_bounds(inner, host)
    lo = np.array([lo[0] - gap, lo[1] - gap, lo[2]])
    hi = hi + gap
    pieces = tuple(q for p in host.pieces for q in _box_less(p, lo, hi))
    return pieces or host.pieces


def scene_bodies(scene: Scene, config: PhysicsConfig = DEFAULT_PHYSICS,
                 catalog: Catalog | None = None) -> list[Body]:
    """Every object of ``scene`` as a rigid body, in the scene's order (tucked ones cut out
    of their hosts, parents hollowed where a child stands inside them)."""
    by_id = {o.id: o for o in scene.objects}
    bodies = {o.id: body_of(o, scene.room, by_id.get(o.support) if o.support else None,
                            config, catalog)
              for o in scene.objects}
    for pair in collisions(scene):
        tucked, host = sorted(pair, key=lambda i: by_id[i].width * by_id[i].depth)
        body = bodies[tucked]
        pieces = untucked_pieces(body, bodies[host], config.clearance)
        com, inertia = mass_properties(pieces, body.mass)
        bodies[tucked] = replace(body, pieces=pieces, com=com, inertia=inertia)
    for o in scene.objects:
        parent = by_id.get(o.support) if o.support else None
        if parent is not None and o.position[2] < parent.top - config.clearance:
            host = bodies[parent.id]
            pieces = hollowed_pieces(host, bodies[o.id], config.clearance)
            com, inertia = mass_properties(pieces, host.mass)
            bodies[parent.id] = replace(host, pieces=pieces, com=com, inertia=inertia)
    return [bodies[o.id] for o in scene.objects]


def world_bodies(scene: Scene | HouseScene, config: PhysicsConfig = DEFAULT_PHYSICS,
                 catalog: Catalog | None = None) -> list[Body]:
    """``scene_bodies`` of a room, or of every room of a house, room by room, each body's
    id (and its support's) then ``body_id(ROOM_ID, OBJECT_ID)``: one world's names, whatever
    ids the rooms share."""
    if not isinstance(scene, HouseScene):
        return scene_bodies(scene, config, catalog)
    return [replace(b, id=body_id(rid, b.id), support=b.support and body_id(rid, b.support))
            for rid, room in scene.scenes.items()
            for b in scene_bodies(room, config, catalog)]


def body_id(room_id: str, object_id: str) -> str:
    """An object's name in the world of a house: ``ROOM/OBJECT``, the room's id as
    ``files.safe_name`` writes it (no ``/`` then), so that no two objects share a name."""
    return f'{safe_name(room_id)}/{object_id}'


def quat_wxyz(yaw: float) -> tuple[float, float, float, float]:
    """The unit quaternion (w, x, y, z) of a turn by ``yaw`` about +z."""
    return (math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2))
