"""Design rules of the ``home`` family: what the rooms of a home beyond the paper's four
(kitchens, dining rooms, hallways) must be to work. Every case is an object or a room of
those types, so a paper room has none.

``work_triangle``: the case is a kitchen holding a kitchen sink, a stove or a fridge; it
keeps the rule when it holds all three within reach of each other as kitchen planning asks
(the NKBA's guidelines): each leg of the triangle between their footprints' centres is
``TRIANGLE_LEG`` (1.2 to 2.7 m) long and the three legs together at most
``TRIANGLE_TOTAL`` (7.9 m); with several of one, the best triangle counts.

``counter_run``: the case is a unit of a kitchen's counter run (counter, kitchen sink,
stove, dishwasher) in a kitchen with two or more; it keeps the rule when it joins another
unit side by side, backs on one wall line (within ``RUN_GAP``, 5 cm, of each other): the
units form runs along the walls, not islands of cabinets (that they stand against a wall is
``wall_contact``'s question).

``fronts_open``: the case is a piece whose doors, drawers or flap swing out at its front
(counter, kitchen sink, stove, fridge, dishwasher, sideboard); it keeps the rule when the
strip ``DOOR_SWING`` (0.6 m) deep before its whole front is floor, clear of every other
first-tier piece.

``dining_seats``: the case is a dining chair or a bar stool; it keeps the rule when it is
seated at a dining table or kitchen island (``groups.seated_at``; a bar stool at a counter
too) with room to pull it out: the strip ``PULL_OUT`` (0.3 m) deep behind it, over its width,
is floor clear of every other first-tier piece.

``hallway_path``: the case is a hallway with two doors or more; it keeps the rule when a
path ``HALLWAY_PATH`` (0.9 m) wide joins every door to every other through its furniture
(a disc of that diameter drives between them: ``robot.state``).
"""
from __future__ import annotations

import itertools
import math

from shapely.geometry import Polygon

from ..categories import members
from ..geometry import local_box, local_xy
from ..scene import PlacedObject, Scene
from ..thresholds import (
    DOOR_SWING,
    HALLWAY_PATH,
    PULL_OUT,
    RUN_GAP,
    TRIANGLE_LEG,
    TRIANGLE_TOTAL,
)
from . import robot
from .groups import on_one_line, seated_at
from .rule import Outcome, Rule

SINKS, STOVES, FRIDGES = (('kitchen sink',), ('stove',), ('fridge',))
RUN_UNITS = members('counter run')
DOOR_FRONTS = members('door front')
DINING_SEATS = members('dining seat')
DINING_SURFACES = members('dining surface')


def _first_tier(scene: Scene, categories) -> list[PlacedObject]:
    return [o for o in scene.first_tier if o.category in categories]


def _clear(scene: Scene, strip: Polygon, owner: PlacedObject) -> bool:
    """Whether ``strip`` is on the floor and clear of every first-tier piece but ``owner``."""
    if not scene.room.polygon.buffer(1e-6).contains(strip):
        return False
    inner = strip.buffer(-1e-3)
    return not any(o.id != owner.id and o.footprint().intersects(inner)
                   for o in scene.first_tier)


def triangle_ok(sink: PlacedObject, stove: PlacedObject, fridge: PlacedObject) -> bool:
    """Whether the three make a working triangle (see ``work_triangle``)."""
    lo, hi = TRIANGLE_LEG
    legs = [math.dist(a.position[:2], b.position[:2])
            for a, b in ((sink, stove), (stove, fridge), (fridge, sink))]
    return all(lo <= leg <= hi for leg in legs) and sum(legs) <= TRIANGLE_TOTAL


def work_triangle(scene: Scene) -> Outcome:
    if scene.room.room_type != 'kitchen':
        return 0, 0
    trio = [_first_tier(scene, c) for c in (SINKS, STOVES, FRIDGES)]
    if not any(trio):
        return 0, 0
    return int(any(triangle_ok(*t) for t in itertools.product(*trio))), 1


def joins_run(unit: PlacedObject, other: PlacedObject) -> bool:
    """Whether ``other`` stands beside ``unit`` in one run (see ``counter_run``)."""
    if not on_one_line(unit, other):
        return False
    _, y = local_xy(unit, other.position)
    return abs(abs(y) - (unit.width + other.width) / 2) <= RUN_GAP


def run_verdicts(scene: Scene) -> dict[str, bool]:
    units = _first_tier(scene, RUN_UNITS)
    if scene.room.room_type != 'kitchen' or len(units) < 2:
        return {}
    return {u.id: any(joins_run(u, o) for o in units if o.id != u.id) for u in units}


def counter_run(scene: Scene) -> Outcome:
    v = run_verdicts(scene)
    return sum(v.values()), len(v)


def front_verdicts(scene: Scene) -> dict[str, bool]:
    return {o.id: _clear(scene, local_box(o, o.depth / 2, o.depth / 2 + DOOR_SWING,
                                     -o.width / 2, o.width / 2), o)
            for o in _first_tier(scene, DOOR_FRONTS)}


def fronts_open(scene: Scene) -> Outcome:
    v = front_verdicts(scene)
    return sum(v.values()), len(v)


def seat_verdicts(scene: Scene) -> dict[str, bool]:
    surfaces = _first_tier(scene, DINING_SURFACES)
    counters = _first_tier(scene, ('counter',))
    out = {}
    for seat in _first_tier(scene, DINING_SEATS):
        at = surfaces + (counters if seat.category == 'bar stool' else [])
        behind = local_box(seat, -seat.depth / 2 - PULL_OUT, -seat.depth / 2,
                      -seat.width / 2, seat.width / 2)
        out[seat.id] = any(seated_at(seat, t) for t in at) and _clear(scene, behind, seat)
    return out


def dining_seats(scene: Scene) -> Outcome:
    v = seat_verdicts(scene)
    return sum(v.values()), len(v)


PATH_ROBOT = robot.Robot(radius=HALLWAY_PATH / 2)


def hallway_path(scene: Scene) -> Outcome:
    if scene.room.room_type != 'hallway' or len(scene.room.doors) < 2:
        return 0, 0
    return int(robot.state(scene, PATH_ROBOT).doors_connected), 1


RULES = (
    Rule('work_triangle', 'home',
         'A kitchen with a sink, a stove or a fridge has all three, 1.2 to 2.7 m apart pair '
         'by pair (footprint centres), 7.9 m at most all round.', work_triangle),
    Rule('counter_run', 'home',
         'A kitchen unit (counter, sink, stove, dishwasher) joins another side by side, '
         'backs on one line, within 5 cm: the units form runs.', counter_run),
    Rule('fronts_open', 'home',
         'The 0.6 m before the front of a piece with doors or a flap (counter, kitchen sink, '
         'stove, fridge, dishwasher, sideboard) is floor clear of other furniture.',
         fronts_open),
    Rule('dining_seats', 'home',
         'A dining chair or bar stool is seated at a dining table or kitchen island (a bar '
         'stool at a counter too) with 0.3 m clear floor behind it to pull it out.',
         dining_seats),
    Rule('hallway_path', 'home',
         'A hallway with two doors or more has a path 0.9 m wide from every door to every '
         'other.', hallway_path),
)
