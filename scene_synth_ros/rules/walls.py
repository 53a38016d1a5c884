"""Design rules of the walls family: furniture against its walls, and windows left clear.

Distances are measured to the floor outline, its collinear vertices merged so that a wall is
one straight run however the outline was drawn. *Wall furniture* is every first-tier category
marked ``against_wall`` in the room type's category set (``categories.CATEGORIES`` for the
paper's room types, ``WALL_FURNITURE``; a data set's own flags for its room types, so that
its beds and dressers are held to their walls too), and for all of them the side meant to
touch the wall is the back (``spatial.side(obj, 'back')``): a bed's headboard, the long back
of a sofa, a daybed or a bathtub, a wardrobe's carcass; the corpus puts every one of them
there. An object's *back gap* is how far its back stands from the wall it backs onto: for
each wall, the larger of the two back corners' distances to that wall's segment; the least
of these over the walls. A piece in a corner has its back to one wall and its side to the
other and its back gap is the gap to the first; a piece with only its side to a wall, or with
one back corner touching and the back running off at an angle, is not backed onto it.

``wall_contact``: a case is a piece of wall furniture; it keeps the rule when its back gap is
at most ``WALL_CONTACT_GAP`` (10 cm).

``wall_near_miss``: the same cases; a piece keeps the rule unless its back gap is more than
``WALL_CONTACT_GAP`` and less than ``NEAR_MISS`` (10 to 40 cm): a slot behind it that neither
reads as against the wall nor is wide enough to use.

``no_floating_large_pieces``: a case is a piece of a *large* wall category, one whose mean
footprint is at least ``LARGE_FOOTPRINT`` (0.35 m^2); of the paper's (``LARGE_PIECES``): beds
of every kind, sofas, wardrobes, desks, dressers, dressing tables, TV stands, shelving, pianos,
fireplaces, bathtubs, showers, sinks and washers (not nightstands, shoe cabinets, bathroom
cabinets, water machines, WC pans or bidets). It floats, and breaks the rule, when its
footprint is more than ``FLOAT_WALL_GAP`` (0.4 m) from every wall and more than ``GROUP_GAP``
(0.5 m) from every first-tier piece it forms a group with (``PARTNERS``): a seat turned to
within ``GROUPED_SEAT_FACING`` (60 degrees) of facing the desk, dressing table or piano it serves;
another desk; a nightstand, bench or ottoman by a bed; a coffee table, easy chair, ottoman or
side table by a sofa. The other large pieces have no partner that excuses them from a wall.

``windows_clear``: a case is a window on a wall of the room. Its *zone* is the strip of floor
in front of it, as wide as the window and ``WINDOW_ZONE_DEPTH`` (20 cm) deep. A first-tier
object taller than the window's sill whose footprint enters the zone hides the part of the
window that its share of the zone spans along the wall; the window keeps the rule when the
union of the hidden parts is at most ``WINDOW_SHARE`` (a quarter) of its width.

``beds_not_across_windows``: a case is a bed (``BEDS``). A bed taller than a window's sill
lies across that window when its headboard (the back) or one of its long sides other than
the front (left and right; a daybed's only long side to count is its back) runs through the
window's zone, as above, over more than ``WINDOW_SHARE`` of the window's width measured
along the wall. The bed keeps the rule when it lies across no window.

Doors have no rule here: the validity check (``geometry.blocked_doors``) already keeps a zone
at least 0.8 m deep and 10 cm wider than the door on each side clear of every first-tier
object, tall or low, in every room the corpus or the synthesizer makes.
"""
from __future__ import annotations

from typing import Sequence

import numpy as np
import shapely
from shapely.geometry import Polygon

from ..categories import CATEGORIES, PAPER, RoomTypeSpec, Vocabulary, members
from ..errors import UnknownRoomType
from ..scene import Opening, PlacedObject, Room, Scene, Wall, box_corners
from ..thresholds import (
    FLOAT_WALL_GAP,
    GROUP_GAP,
    GROUPED_SEAT_FACING,
    LARGE_FOOTPRINT,
    NEAR_MISS,
    WALL_CONTACT_GAP,
    WINDOW_SHARE,
    WINDOW_ZONE_DEPTH,
)
from .rule import BEDS, Rule
from .spatial import bearing

# The paper's wall furniture and large pieces. The rules ask ``wall_categories``, which gives
# these for the paper's room types and reads a data set's own category set for its types.
WALL_FURNITURE = frozenset(c.name for c in CATEGORIES.values()
                           if c.tier == 'first' and c.against_wall)

LARGE_PIECES = frozenset(c for c in WALL_FURNITURE
                         if CATEGORIES[c].mean_footprint >= LARGE_FOOTPRINT)

# id of a room type's category set -> (the set, its wall furniture, its large pieces): the
# rules run inside insertion, too often to look every object's category up anew.
_WALL_SETS: dict[int, tuple[RoomTypeSpec, frozenset[str], frozenset[str]]] = {}


def wall_categories(room_type: str, vocabulary: Vocabulary = PAPER
                    ) -> tuple[frozenset[str], frozenset[str]]:
    """The wall furniture and the large pieces among it in a room of ``room_type``: by the
    room type's category set in ``vocabulary`` for its categories, by the paper's table for
    the others (``rules.category_of``); the paper's sets for a room type it does not know."""
    try:
        spec = vocabulary.spec(room_type)
    except UnknownRoomType:
        return WALL_FURNITURE, LARGE_PIECES
    hit = _WALL_SETS.get(id(spec))
    if hit is None or hit[0] is not spec:
        own = [c.info for c in spec.categories if c.info.tier == 'first' and c.info.against_wall]
        wall = (WALL_FURNITURE - set(spec.names)) | {i.name for i in own}
        large = (LARGE_PIECES - set(spec.names)) | {
            i.name for i in own if i.mean_footprint >= LARGE_FOOTPRINT}
        hit = _WALL_SETS[id(spec)] = (spec, frozenset(wall), frozenset(large))
    return hit[1], hit[2]


_SEATS = frozenset(members('table seat') + members('bench'))
SEATED = frozenset(members('worktop'))    # their seat partners face them
PARTNERS: dict[str, frozenset[str]] = {
    **{bed: frozenset({'stand', 'bench chair', 'ottoman'}) for bed in BEDS},
    'desk': _SEATS | {'desk'},
    'dressing table': _SEATS | {'ottoman'},
    'piano': _SEATS,
    'sofa': frozenset({'coffee table', 'sofa chair', 'armchair', 'ottoman', 'stand'}),
}


# ---- geometry of walls and windows ------------------------------------------------------
def wall_runs(room: Room) -> tuple[np.ndarray, np.ndarray]:
    """Start and end points (each n x 2) of the room's straight walls, collinear pieces of
    the outline merged into one run."""
    ring = room.polygon.exterior.simplify(1e-4)
    pts = np.asarray(ring.coords)[:-1]
    return pts, np.roll(pts, -1, axis=0)


def corner_wall_distances(points: np.ndarray, runs: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Distance of every point (p x 2) to every wall run (the segments): p x n metres."""
    a, b = runs
    ab = b - a
    rel = points[:, None, :] - a[None]
    t = np.clip((rel * ab).sum(-1) / (ab * ab).sum(-1), 0.0, 1.0)
    return np.linalg.norm(rel - t[..., None] * ab, axis=-1)


def corner_array(objects: Sequence[PlacedObject]) -> np.ndarray:
    """Footprint corners of many objects at once (k x 4 x 2), in ``scene.box_corners``'
    order: back-right, front-right, front-left, back-left."""
    a = np.array([(o.position[0], o.position[1], o.yaw, o.width, o.depth) for o in objects],
                 dtype=float).reshape(-1, 5)
    cos, sin = np.cos(a[:, 2:3]), np.sin(a[:, 2:3])
    lx = np.array([-1.0, 1.0, 1.0, -1.0]) * a[:, 4:5] / 2      # along the front
    ly = np.array([-1.0, -1.0, 1.0, 1.0]) * a[:, 3:4] / 2      # across it
    return np.stack([a[:, 0:1] + lx * cos - ly * sin, a[:, 1:2] + lx * sin + ly * cos], axis=-1)


def back_gaps(objects: Sequence[PlacedObject], runs: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Metres between each object's back and the wall it backs onto (see the module
    docstring): the larger of the back corners' distances to the wall that minimises it."""
    back = corner_array(objects)[:, [3, 0]]
    d = corner_wall_distances(back.reshape(-1, 2), runs).reshape(len(objects), 2, -1)
    return d.max(axis=1).min(axis=1)


def window_zone(room: Room, window: Opening) -> tuple[Wall, Polygon] | None:
    """The window's wall and the strip of floor in front of it (None off every wall)."""
    return room.remembered(('window zone', window), lambda: _window_zone(room, window))


def _window_zone(room: Room, window: Opening) -> tuple[Wall, Polygon] | None:
    wall = room.wall_of(window)
    if wall is None:
        return None
    centre = np.asarray(window.position) + wall.normal * WINDOW_ZONE_DEPTH / 2
    return wall, Polygon(box_corners(centre[0], centre[1], wall.inward_yaw, window.width,
                                     WINDOW_ZONE_DEPTH))


def window_zones(room: Room) -> list[tuple[Opening, Wall, Polygon]]:
    """Every window on a wall of the room, with its wall and zone."""
    return [(w, *z) for w in room.windows if (z := window_zone(room, w)) is not None]


def along_wall(wall: Wall, shape) -> tuple[float, float]:
    """The interval, in metres along ``wall``, that a non-empty shape spans."""
    coords = shapely.get_coordinates(shape)
    offsets = (coords - np.asarray(wall.start)) @ wall.direction
    return float(offsets.min()), float(offsets.max())


def union_length(intervals: list[tuple[float, float]]) -> float:
    """Total length covered by a set of intervals, overlaps counted once."""
    total, end = 0.0, -np.inf
    for lo, hi in sorted(intervals):
        if hi > end:
            total += hi - max(lo, end)
            end = hi
    return total


# ---- the rules ---------------------------------------------------------------------------
def _back_gaps(scene: Scene, vocabulary: Vocabulary = PAPER
               ) -> tuple[list[PlacedObject], np.ndarray]:
    """The room's pieces of wall furniture and each one's back gap."""
    wall, _ = wall_categories(scene.room.room_type, vocabulary)
    pieces = [o for o in scene.first_tier if o.category in wall]
    if not pieces:
        return pieces, np.zeros(0)
    return pieces, back_gaps(pieces, wall_runs(scene.room))


def wall_contact_verdicts(scene: Scene, vocabulary: Vocabulary = PAPER) -> dict[str, bool]:
    """Whether each piece of wall furniture (by id) keeps ``wall_contact``."""
    pieces, gaps = _back_gaps(scene, vocabulary)
    return {o.id: bool(g <= WALL_CONTACT_GAP) for o, g in zip(pieces, gaps, strict=True)}


def measure_wall_contact(scene: Scene, vocabulary: Vocabulary = PAPER) -> tuple[int, int]:
    verdicts = wall_contact_verdicts(scene, vocabulary)
    return sum(verdicts.values()), len(verdicts)


def measure_wall_near_miss(scene: Scene, vocabulary: Vocabulary = PAPER) -> tuple[int, int]:
    _, gaps = _back_gaps(scene, vocabulary)
    return int(np.sum((gaps <= WALL_CONTACT_GAP) | (gaps >= NEAR_MISS))), len(gaps)


def is_partner(piece: PlacedObject, other: PlacedObject) -> bool:
    """Whether ``other`` can form a group with ``piece``: a partner category, and a seat
    turned towards the desk, dressing table or piano it serves."""
    if other is piece or other.category not in PARTNERS.get(piece.category, ()):
        return False
    return not (piece.category in SEATED and other.category in _SEATS
                and bearing(other, piece) > GROUPED_SEAT_FACING)


def floating(scene: Scene, vocabulary: Vocabulary = PAPER) -> list[PlacedObject]:
    """The large pieces off every wall and away from every partner."""
    first = scene.first_tier
    _, pieces = wall_categories(scene.room.room_type, vocabulary)
    large = [k for k, o in enumerate(first) if o.category in pieces]
    if not large:
        return []
    fps = shapely.polygons(corner_array(first))
    off_wall = shapely.distance(scene.room.polygon.exterior, fps[large]) > FLOAT_WALL_GAP
    out = []
    for k in np.asarray(large)[off_wall]:
        partners = [j for j, o in enumerate(first) if is_partner(first[k], o)]
        if not partners or shapely.distance(fps[k], fps[partners]).min() > GROUP_GAP:
            out.append(first[k])
    return out


def measure_floating(scene: Scene, vocabulary: Vocabulary = PAPER) -> tuple[int, int]:
    _, pieces = wall_categories(scene.room.room_type, vocabulary)
    cases = sum(o.category in pieces for o in scene.first_tier)
    return cases - len(floating(scene, vocabulary)), cases


def covered_width(window: Opening, wall: Wall, zone: Polygon,
                  objects: Sequence[PlacedObject], footprints: np.ndarray) -> float:
    """Metres of the window's width hidden by those ``objects`` (first tier, with their
    ``footprints``) that rise above its sill."""
    tall = np.array([o.top > window.sill for o in objects], dtype=bool)
    if not tall.any():
        return 0.0
    parts = shapely.intersection(zone, footprints[tall])
    # a footprint that only touches the zone hides nothing
    return union_length([along_wall(wall, p) for p in parts[shapely.area(parts) > 0]])


def window_verdicts(scene: Scene, new: PlacedObject | None = None) -> dict[int, bool]:
    """Whether each window on a wall (by its index in ``room.windows``) keeps
    ``windows_clear``. With ``new`` (a first-tier piece of ``scene`` just added), only the
    windows whose verdict it can have changed: those whose zone it enters."""
    first = scene.first_tier
    zones = [(k, w, z) for k, w in enumerate(scene.room.windows)
             if (z := window_zone(scene.room, w)) is not None
             and (new is None or z[1].intersects(new.footprint()))]
    if not zones:
        return {}
    fps = shapely.polygons(corner_array(first)) if first else np.empty(0, dtype=object)
    return {k: covered_width(w, *z, first, fps) <= WINDOW_SHARE * w.width
            for k, w, z in zones}


def measure_windows_clear(scene: Scene) -> tuple[int, int]:
    verdicts = window_verdicts(scene)
    return sum(verdicts.values()), len(verdicts)


# Corner pairs of ``corner_array`` making a side, as ``spatial.side`` names them.
_SIDES = {'back': (3, 0), 'right': (0, 1), 'left': (2, 3)}


def bed_sides(beds: Sequence[PlacedObject]) -> list[np.ndarray]:
    """Each bed's headboard and long sides but the front, as an array of segments."""
    corners = corner_array(beds)
    out = []
    for bed, c in zip(beds, corners, strict=True):
        names = ('back', 'left', 'right') if bed.depth > bed.width else ('back',)
        out.append(shapely.linestrings([c[list(_SIDES[n])] for n in names]))
    return out


def across_window(bed: PlacedObject, sides: np.ndarray, window: Opening, wall: Wall,
                  zone: Polygon) -> bool:
    """Whether the bed (with its ``bed_sides``) rises above the window's sill with its
    headboard or a long side across it."""
    if bed.top <= window.sill:
        return False
    for part in shapely.intersection(zone, sides):
        if not part.is_empty:
            lo, hi = along_wall(wall, part)
            if hi - lo > WINDOW_SHARE * window.width:
                return True
    return False


def measure_beds_not_across_windows(scene: Scene) -> tuple[int, int]:
    beds = [o for o in scene.first_tier if o.category in BEDS]
    if not beds:
        return 0, 0
    zones = window_zones(scene.room)
    kept = sum(not any(across_window(b, sides, *z) for z in zones)
               for b, sides in zip(beds, bed_sides(beds), strict=True))
    return kept, len(beds)


RULES: tuple[Rule, ...] = (
    Rule('wall_contact', 'walls',
         'Each piece of wall furniture (a first-tier category meant to stand against a wall) has '
         f'both back corners within {WALL_CONTACT_GAP * 100:.0f} cm of the same wall.',
         measure_wall_contact, reads_vocabulary=True),
    Rule('wall_near_miss', 'walls',
         'Each piece of wall furniture has its back either within '
         f'{WALL_CONTACT_GAP * 100:.0f} cm of a wall or at least {NEAR_MISS * 100:.0f} cm from '
         'every wall, not a near miss in between.',
         measure_wall_near_miss, reads_vocabulary=True),
    Rule('no_floating_large_pieces', 'walls',
         'Each large piece of wall furniture (a wall category of '
         f'{LARGE_FOOTPRINT:.2f} m^2 or more: beds, sofas, storage, desks, TV stands, pianos, '
         'fireplaces, baths, showers, sinks, washers) stands within '
         f'{FLOAT_WALL_GAP * 100:.0f} cm of a wall or {GROUP_GAP * 100:.0f} cm of a partner '
         '(a seat turned to its desk, a nightstand by its bed, a coffee table by its sofa).',
         measure_floating, reads_vocabulary=True),
    Rule('windows_clear', 'walls',
         f'Each window has at most {WINDOW_SHARE:.0%} of its width hidden by first-tier '
         f'furniture taller than its sill standing within {WINDOW_ZONE_DEPTH * 100:.0f} cm of '
         'the glass.',
         measure_windows_clear),
    Rule('beds_not_across_windows', 'walls',
         'Each bed keeps its headboard and long sides (not its foot) out of the '
         f'{WINDOW_ZONE_DEPTH * 100:.0f} cm strip in front of every window whose sill it rises '
         f'above, but for at most {WINDOW_SHARE:.0%} of the window\'s width.',
         measure_beds_not_across_windows),
)
