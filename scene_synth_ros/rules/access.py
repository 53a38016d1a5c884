"""Access rules: whether what a person (or the robot) uses in a room can be got at.

Clearances are measured on *clear strips*: the floor strip that starts at one side of an
object's footprint and runs ``depth`` metres out from it, as wide as that side is long. A
strip is blocked along the stretch of the side where another first-tier footprint, shrunk
by ``CLEARANCE_TOLERANCE`` on every side, or the outside of the floor, grown by it, enters
it (an obstacle blocks the whole depth of the stretch it covers: one cannot stand behind
it). ``clear_stretch`` is the longest unblocked stretch; a side "has ``depth`` clear" when
that stretch is the whole side less ``CLEARANCE_TOLERANCE`` at each end. Second-tier objects never
block: they stand on their parents.

storage_clearance
    Case: a first-tier wardrobe, dresser, dressing table, shelving, shoes cabinet, cabinet or
    washer. Kept when the whole front has ``STORAGE_CLEARANCE`` (0.5 m) clear, so that doors
    and drawers open and someone can stand before them; the seat of a dressing table (a
    chair, stool, ottoman or bench) does not block it, since it is pulled out to be used.

fixture_clearance
    Case: a first-tier toilet, bidet, sink, shower or bathtub. Kept when its activity space
    in front is clear: the whole front of a toilet or bidet has 0.6 m clear and that of a
    sink 0.5 m (``FIXTURE_CLEARANCE``); a shower's entry side (its front: the corpus backs a
    shower onto one wall of a corner) has 0.6 m clear over at least the 0.6 m of its door,
    and a bathtub's front long side has 0.5 m clear over at least 0.6 m, where one steps in
    (``ENTRY_STRETCH``).

bed_access
    Case: a first-tier bed (double, single, bunker, baby bed, daybed). Kept for a double
    bed when both long sides (left and right) have ``BED_CLEARANCE`` (0.4 m, the robot's
    width) clear over at least ``BED_STRETCH`` (0.6 m): each sleeper gets in on their own
    side, and a nightstand at the head takes only part of a side. Kept for the others when
    the foot (the front) or one long side has the same (for a daybed, whose long side is its
    front, the front or an end). A bench or ottoman at the foot blocks the foot.

front_not_to_wall
    Case: a first-tier object whose front a person uses (``USED_FRONT``: storage, the
    nightstand, TV stand, desk, beds, seats with a back, bathroom fixtures, piano,
    fireplace, whiteboard, water machine). Kept when the whole front has ``WALL_CLEARANCE``
    (0.3 m) of floor before any wall: only walls count here; other furniture in front is the
    business of the clearance rules.

front_reachable
    Case: a first-tier object in a room with at least one door. Kept when a round robot of
    ``thresholds.ROBOT_WIDTH`` (0.4 m) driving in from a door can bring its body within
    ``ROBOT_REACH`` (0.15 m) of the object: straight in front of its front side (its centre
    within the strip as wide as the front and robot radius plus reach deep) for the objects
    operated at the front (``OPERATED_FRONT``: storage, nightstand, TV stand, desk, bathroom
    fixtures, piano, fireplace, whiteboard, water machine), anywhere around its footprint
    for the others (beds, seats, tables, lamps: used from a side, or moved to be used).
    This is ``robot.state`` for that robot (``RULE_ROBOT``): where its centre can be
    is ``geometry.free_space``, computed once per room, and it can drive to the pieces of it
    that hold a door's ``geometry.door_entry_point``. Reaching a front corner from the side
    does not count: a wardrobe behind a bed with a 0.3 m gap is not reached.

room_fully_reachable
    Case: a room with at least one door. Kept when every first-tier object of the room
    keeps ``front_reachable`` (a room without furniture keeps it).
"""
from __future__ import annotations

from functools import cached_property

import numpy as np
import shapely
from shapely.geometry import Polygon
from shapely.prepared import prep

from ..categories import members
from ..scene import PlacedObject, Scene
from ..thresholds import (
    BED_CLEARANCE,
    BED_STRETCH,
    CLEARANCE_TOLERANCE,
    ENTRY_STRETCH,
    FIXTURE_CLEARANCE,
    STORAGE_CLEARANCE,
    WALL_CLEARANCE,
)
from . import robot
from .robot import OPERATED_FRONT, Robot
from .rule import BEDS, Outcome, Rule
from .spatial import changed_by, side

STORAGE = members('storage')
# The seat of a dressing table is pulled out to use it, so it does not block the table.
SEATS = members('loose seat')


assert set(FIXTURE_CLEARANCE) == set(members('fixture'))
USED_FRONT = OPERATED_FRONT + BEDS + members('armchair') + members('chair') + ('sofa',)

RULE_ROBOT = Robot()

# ---- clear strips ------------------------------------------------------------------------
def _strip(obj: PlacedObject, which: str, depth: float) -> tuple[Polygon, np.ndarray, float]:
    """The strip ``depth`` deep outside one side, the side's start and its unit direction
    folded into (start, direction), and the side's length (shared: not to be modified)."""
    return obj.remembered(('strip', which, depth), lambda: _make_strip(obj, which, depth))


def _make_strip(obj: PlacedObject, which: str, depth: float
                ) -> tuple[Polygon, np.ndarray, float]:
    a, b = (np.asarray(p) for p in side(obj, which).coords)
    length = float(np.linalg.norm(b - a))
    along = (b - a) / length
    out = np.array([along[1], -along[0]])       # sides run counter-clockwise: out is right
    strip = Polygon([a, b, b + out * depth, a + out * depth])
    return strip, np.stack([a, along]), length


class _Obstacles:
    """What blocks a strip in one room: its first-tier footprints shrunk by the tolerance,
    and the outside of its floor grown by it."""

    def __init__(self, scene: Scene):
        self.objects = scene.first_tier
        room = scene.room
        self.floor = room.remembered(
            ('floor grown', CLEARANCE_TOLERANCE),
            lambda: room.polygon.buffer(CLEARANCE_TOLERANCE, join_style='mitre'))
        self._floor = room.remembered(('floor grown, prepared', CLEARANCE_TOLERANCE),
                                      lambda: prep(self.floor))

    @cached_property
    def _shrunk(self) -> list[Polygon]:
        return [o.footprint(CLEARANCE_TOLERANCE) for o in self.objects]

    @cached_property
    def _tree(self) -> shapely.STRtree:
        return shapely.STRtree(self._shrunk)

    def outside(self, strip: Polygon) -> list:
        """The pieces of ``strip`` beyond the walls."""
        if self._floor.covers(strip):
            return []
        return list(shapely.get_parts(strip.difference(self.floor)))

    def blocking(self, obj: PlacedObject, strip: Polygon, ignore=()) -> list:
        """The pieces of ``strip`` that the walls and objects other than ``obj`` (and not of
        the ``ignore`` categories) cover."""
        parts = self.outside(strip)
        for k in self._tree.query(strip, predicate='intersects'):
            other = self.objects[k]
            if other is not obj and other.category not in ignore:
                parts.append(strip.intersection(self._shrunk[k]))    # both convex: one piece
        return parts

    def clear_stretch(self, obj: PlacedObject, which: str, depth: float,
                      ignore=(), walls_only: bool = False) -> tuple[float, float]:
        """The longest stretch of a side with ``depth`` clear before it, and the side's
        length."""
        strip, (start, along), length = _strip(obj, which, depth)
        parts = self.outside(strip) if walls_only else self.blocking(obj, strip, ignore)
        spans = []
        for part in parts:
            coords = shapely.get_coordinates(part)
            if len(coords):
                t = (coords - start) @ along
                spans.append((max(float(t.min()), 0.0), min(float(t.max()), length)))
        return _longest_gap(spans, length), length


def _longest_gap(spans: list[tuple[float, float]], length: float) -> float:
    """The longest part of [0, length] that no span covers."""
    best, reached = 0.0, 0.0
    for lo, hi in sorted(spans):
        best = max(best, lo - reached)
        reached = max(reached, hi)
    return max(best, length - reached)


def _whole(stretch_and_length: tuple[float, float]) -> bool:
    stretch, length = stretch_and_length
    return stretch >= length - 2 * CLEARANCE_TOLERANCE


# ---- the rules ---------------------------------------------------------------------------
def _cases(scene: Scene, categories) -> tuple[list[PlacedObject], _Obstacles | None]:
    cases = [o for o in scene.first_tier if o.category in categories]
    return cases, (_Obstacles(scene) if cases else None)


def _entered_by(new: PlacedObject | None, obj: PlacedObject, depth: float) -> bool:
    """Whether ``new`` can have changed ``obj``'s clear front ``depth`` deep
    (``spatial.changed_by``; lying within the tolerance of the strip does not enter it)."""
    return changed_by(new, obj, _strip(obj, 'front', depth)[0], CLEARANCE_TOLERANCE)


def storage_verdicts(scene: Scene, new: PlacedObject | None = None) -> dict[int, bool]:
    """Whether each first-tier piece of storage (by its index in ``scene.first_tier``) keeps
    ``storage_clearance``. With ``new`` (a first-tier piece of ``scene`` just added), only the
    pieces whose verdict it can have changed: itself, and those whose front it blocks."""
    first = scene.first_tier
    cases = [k for k, o in enumerate(first)
             if o.category in STORAGE and _entered_by(new, o, STORAGE_CLEARANCE)]
    if not cases:
        return {}
    room = _Obstacles(scene)
    return {k: _whole(room.clear_stretch(
        first[k], 'front', STORAGE_CLEARANCE,
        SEATS if first[k].category == 'dressing table' else ())) for k in cases}


def storage_clearance(scene: Scene) -> Outcome:
    verdicts = storage_verdicts(scene)
    return sum(verdicts.values()), len(verdicts)


def _fixture_clear(room: _Obstacles, obj: PlacedObject) -> bool:
    found = room.clear_stretch(obj, 'front', FIXTURE_CLEARANCE[obj.category])
    if obj.category in ENTRY_STRETCH:
        return found[0] >= min(ENTRY_STRETCH[obj.category], found[1] - 2 * CLEARANCE_TOLERANCE)
    return _whole(found)


def fixture_verdicts(scene: Scene, new: PlacedObject | None = None) -> dict[str, bool]:
    """Whether each fixture (by id) keeps ``fixture_clearance``; with ``new``, only those
    whose verdict it can have changed (as ``storage_verdicts``)."""
    cases, room = _cases(scene, FIXTURE_CLEARANCE)
    return {o.id: _fixture_clear(room, o) for o in cases
            if _entered_by(new, o, FIXTURE_CLEARANCE[o.category])}


def fixture_clearance(scene: Scene) -> Outcome:
    verdicts = fixture_verdicts(scene)
    return sum(verdicts.values()), len(verdicts)


def _side_usable(room: _Obstacles, bed: PlacedObject, which: str) -> bool:
    stretch, length = room.clear_stretch(bed, which, BED_CLEARANCE)
    return stretch >= min(BED_STRETCH, length - 2 * CLEARANCE_TOLERANCE)


def _bed_accessible(room: _Obstacles, bed: PlacedObject) -> bool:
    if bed.category == 'double bed':
        return _side_usable(room, bed, 'left') and _side_usable(room, bed, 'right')
    return any(_side_usable(room, bed, s) for s in ('front', 'left', 'right'))


def bed_access(scene: Scene) -> Outcome:
    cases, room = _cases(scene, BEDS)
    return sum(_bed_accessible(room, b) for b in cases), len(cases)


def front_not_to_wall(scene: Scene) -> Outcome:
    cases, room = _cases(scene, USED_FRONT)
    kept = sum(_whole(room.clear_stretch(o, 'front', WALL_CLEARANCE, walls_only=True))
               for o in cases)
    return kept, len(cases)


# ---- the robot ---------------------------------------------------------------------------
def unreachable(scene: Scene) -> list[PlacedObject]:
    """First-tier objects the rule's robot cannot reach from a door (see
    ``front_reachable``)."""
    objects = scene.first_tier
    key = [(o.category, o.position, o.yaw, o.size) for o in objects]
    last = _last_room.get('unreachable')
    if last is None or last[0] is not scene.room or last[1] != key:
        reached = robot.state(scene, RULE_ROBOT).reached
        missed = [k for k in range(len(objects)) if k not in reached]
        last = _last_room['unreachable'] = (scene.room, key, missed)
    return [objects[k] for k in last[2]]


# front_reachable and room_fully_reachable ask about the same room one after the other: the
# free space, the costly part, is computed once for both.
_last_room: dict = {}


def front_reachable(scene: Scene) -> Outcome:
    if not scene.room.doors:
        return 0, 0
    cases = len(scene.first_tier)
    return cases - len(unreachable(scene)), cases


def room_fully_reachable(scene: Scene) -> Outcome:
    if not scene.room.doors:
        return 0, 0
    return int(not unreachable(scene)), 1


RULES: tuple[Rule, ...] = (
    Rule('storage_clearance', 'access',
         'Storage (wardrobe, dresser, dressing table, shelving, shoes cabinet, cabinet, '
         'washer): is there 0.5 m of clear floor in front of its whole front?',
         storage_clearance),
    Rule('fixture_clearance', 'access',
         'Toilet, bidet, sink, shower, bathtub: is the floor before its front clear, 0.6 m '
         'deep for a toilet or bidet and 0.5 m for a sink over the whole front, 0.6 m for a '
         'shower and 0.5 m for a bath over at least 0.6 m of it?',
         fixture_clearance),
    Rule('bed_access', 'access',
         'Bed: do both long sides (double bed), or its foot or one long side (other beds), '
         'have 0.4 m of clear floor along at least 0.6 m?',
         bed_access),
    Rule('front_not_to_wall', 'access',
         'Object with a front in use (storage, nightstand, desk, bed, seat with a back, '
         'fixture, TV stand...): is there at least 0.3 m of floor between its whole front and '
         'any wall?',
         front_not_to_wall),
    Rule('front_reachable', 'access',
         'First-tier object in a room with a door: can a 0.4 m robot from a door get within '
         '0.15 m of it, straight in front of its front for storage, desks, fixtures and the '
         'like, on any side for beds, seats, tables and lamps?',
         front_reachable),
    Rule('room_fully_reachable', 'access',
         'Room with a door: does every first-tier object in it keep front_reachable (a 0.4 m '
         'robot from a door gets within 0.15 m of its front, or of any side where it has none '
         'in use)?',
         room_fully_reachable),
)
