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

Synthesis keeps all but ``counter_run`` at insertion (``rules.insertion``), in the form a room
being furnished can be judged: a sink, stove or fridge must make a working triangle with
those of the other two kinds already there (``triangle_verdicts``), and a kitchen that stops
without one of the three is owed it (``owed_corners``); a piece's front, a seat's pull-out
strip and a hallway's path must stay clear; and the pieces of a triangle and the seats are
drawn only where their partners leave them room (``partner_zone``). Counter units are slid
along their wall to join a neighbouring unit (``into_run``) rather than refused.
"""
from __future__ import annotations

from dataclasses import replace
import itertools
import math

import shapely
from shapely.geometry import Point, Polygon

from ..categories import CATEGORIES, PAPER, Vocabulary, members
from ..geometry import local_box, local_xy
from ..scene import PlacedObject, Scene
from ..thresholds import (
    DOOR_SWING,
    HALLWAY_PATH,
    PULL_OUT,
    RUN_GAP,
    RUN_SNAP,
    SEAT_REACH,
    TRIANGLE_LEG,
    TRIANGLE_TOTAL,
)
from . import robot
from .groups import on_one_line, seated_at, zone_beside
from .rule import Outcome, Rule, category_of
from .spatial import changed_by

SINKS, STOVES, FRIDGES = (('kitchen sink',), ('stove',), ('fridge',))
TRIANGLE_KINDS = (SINKS, STOVES, FRIDGES)
# Every kitchen has a sink and a stove (``home_tables.KITCHEN_REFERENCE``) and a fridge (146
# of ProcTHOR's 147 kitchens): a kitchen that stops without one of them is owed it, as a
# coffee table is owed seating (``owed_corners``).
KITCHEN_ESSENTIALS = SINKS + STOVES + FRIDGES
RUN_UNITS = members('counter run')
DOOR_FRONTS = members('door front')
DINING_SEATS = members('dining seat')
DINING_SURFACES = members('dining surface')



def _clear(scene: Scene, strip: Polygon, owner: PlacedObject) -> bool:
    """Whether ``strip`` is on the floor and clear of every first-tier piece but ``owner``."""
    if not scene.room.polygon.buffer(1e-6).contains(strip):
        return False
    inner = strip.buffer(-1e-3)
    return not any(o.id != owner.id and o.footprint().intersects(inner)
                   for o in scene.first_tier)


def corners_ok(pieces) -> bool:
    """Whether ``pieces``, at most one of each kind of ``TRIANGLE_KINDS``, stand as corners
    of a working triangle: every leg between them ``TRIANGLE_LEG`` long, and the three legs
    together at most ``TRIANGLE_TOTAL`` (see ``work_triangle``)."""
    lo, hi = TRIANGLE_LEG
    legs = [math.dist(a.position[:2], b.position[:2])
            for a, b in itertools.combinations(pieces, 2)]
    return all(lo <= leg <= hi for leg in legs) and (len(legs) < 3 or sum(legs) <= TRIANGLE_TOTAL)


def triangle_ok(sink: PlacedObject, stove: PlacedObject, fridge: PlacedObject) -> bool:
    """Whether the three make a working triangle (see ``work_triangle``)."""
    return corners_ok((sink, stove, fridge))


def work_triangle(scene: Scene) -> Outcome:
    if scene.room.room_type != 'kitchen':
        return 0, 0
    trio = [scene.first_tier_of(c) for c in (SINKS, STOVES, FRIDGES)]
    if not any(trio):
        return 0, 0
    return int(any(triangle_ok(*t) for t in itertools.product(*trio))), 1


def triangle_verdicts(scene: Scene) -> dict[str, bool]:
    """Whether each sink, stove and fridge of a kitchen (by id) makes a working triangle with
    one of each other kind the room holds so far (``corners_ok``): what insertion keeps, so
    that a kitchen that gets all three has them within reach of each other."""
    if scene.room.room_type != 'kitchen':
        return {}
    kinds = [scene.first_tier_of(c) for c in TRIANGLE_KINDS]
    out = {}
    for k, own in enumerate(kinds):
        others = [kind for j, kind in enumerate(kinds) if j != k and kind]
        for piece in own:
            out[piece.id] = any(corners_ok((piece, *combo))
                                for combo in itertools.product(*others))
    return out


def owed_corners(scene: Scene) -> tuple[str, ...]:
    """The essentials a kitchen still lacks (``KITCHEN_ESSENTIALS``, the work triangle's
    corners)."""
    if scene.room.room_type != 'kitchen':
        return ()
    return tuple(c for c in KITCHEN_ESSENTIALS if not scene.first_tier_of((c,)))


def owed(scene: Scene, rules) -> tuple[int, frozenset[str]]:
    """What a finished ``scene`` still owes for ``rules`` (names in ``OWED_PARTNERS``), as
    ``groups.owed`` says it: the cases broken and the categories that could mend them (for
    ``work_triangle``, one case per missing corner, ``owed_corners``)."""
    missing = owed_corners(scene) if 'work_triangle' in rules else ()
    return len(missing), frozenset(missing)


# The rules a finished room may be owed partners for (``owed``), and the partners' categories.
OWED_PARTNERS: dict[str, tuple[str, ...]] = {'work_triangle': KITCHEN_ESSENTIALS}


def joins_run(unit: PlacedObject, other: PlacedObject) -> bool:
    """Whether ``other`` stands beside ``unit`` in one run (see ``counter_run``)."""
    if not on_one_line(unit, other):
        return False
    _, y = local_xy(unit, other.position)
    return abs(abs(y) - (unit.width + other.width) / 2) <= RUN_GAP


def run_verdicts(scene: Scene) -> dict[str, bool]:
    units = scene.first_tier_of(RUN_UNITS)
    if scene.room.room_type != 'kitchen' or len(units) < 2:
        return {}
    return {u.id: any(joins_run(u, o) for o in units if o.id != u.id) for u in units}


def counter_run(scene: Scene) -> Outcome:
    v = run_verdicts(scene)
    return sum(v.values()), len(v)


def into_run(scene: Scene, unit: PlacedObject) -> PlacedObject:
    """``unit``, a new kitchen unit, slid sideways to stand beside the nearest unit on its
    line (``on_one_line``) whose side is at most ``RUN_SNAP`` away, leaving a gap of half
    ``RUN_GAP``; ``unit`` itself where none is. The location module sees a kitchen at about
    9 cm a pixel, so a unit meant to join a run lands a few centimetres off it, or into it."""
    if scene.room.room_type != 'kitchen' or unit.category not in RUN_UNITS:
        return unit
    best = None
    for other in scene.first_tier_of(RUN_UNITS):
        if not on_one_line(unit, other):
            continue
        _, y = local_xy(other, unit.position)
        side = (other.width + unit.width) / 2 + RUN_GAP / 2
        gap = abs(y) - side
        if abs(gap) <= RUN_SNAP and (best is None or abs(gap) < abs(best[0])):
            best = (gap, other, math.copysign(side, y) - y)
    if best is None:
        return unit
    _, other, shift = best
    c, s = math.cos(other.yaw), math.sin(other.yaw)
    # Along the other unit's width: its local y axis.
    x, y, z = unit.position
    return replace(unit, position=(x - s * shift, y + c * shift, z))


def _front(o: PlacedObject) -> Polygon:
    return local_box(o, o.depth / 2, o.depth / 2 + DOOR_SWING, -o.width / 2, o.width / 2)


def front_verdicts(scene: Scene, new: PlacedObject | None = None) -> dict[str, bool]:
    """Whether each piece with a door front (by id) keeps ``fronts_open``; with ``new`` (a
    first-tier piece of ``scene`` just added), only those whose verdict it can have
    changed: itself, and those whose front it enters."""
    out = {}
    for o in scene.first_tier_of(DOOR_FRONTS):
        strip = _front(o)
        if changed_by(new, o, strip):
            out[o.id] = _clear(scene, strip, o)
    return out


def fronts_open(scene: Scene) -> Outcome:
    v = front_verdicts(scene)
    return sum(v.values()), len(v)


def _surfaces(scene: Scene, seat_category: str) -> list[PlacedObject]:
    """What a seat of ``seat_category`` is seated at: a dining table or kitchen island, and
    for a bar stool a counter too."""
    return scene.first_tier_of(DINING_SURFACES + (('counter',) if seat_category == 'bar stool'
                                                 else ()))


def seat_verdicts(scene: Scene, new: PlacedObject | None = None) -> dict[str, bool]:
    """Whether each dining seat (by id) keeps ``dining_seats``; with ``new``, only those
    whose verdict it can have changed: itself, those whose pull-out strip it enters, and
    every seat where it is something to sit at."""
    at = new is not None and (new.category in DINING_SURFACES or new.category == 'counter')
    out = {}
    for seat in scene.first_tier_of(DINING_SEATS):
        behind = local_box(seat, -seat.depth / 2 - PULL_OUT, -seat.depth / 2,
                           -seat.width / 2, seat.width / 2)
        if at or changed_by(new, seat, behind):
            out[seat.id] = (any(seated_at(seat, t) for t in _surfaces(scene, seat.category))
                            and _clear(scene, behind, seat))
    return out


def dining_seats(scene: Scene) -> Outcome:
    v = seat_verdicts(scene)
    return sum(v.values()), len(v)


PATH_ROBOT = robot.Robot(radius=HALLWAY_PATH / 2)


# The rules kept at insertion whose pieces are drawn only where a partner leaves them room
# (``partner_zone``), and those pieces.
PARTNER_RULES: dict[str, tuple[str, ...]] = {
    'work_triangle': SINKS + STOVES + FRIDGES,
    'dining_seats': DINING_SEATS,
}


def partner_zone(scene: Scene, rule: str, category: str, vocabulary: Vocabulary = PAPER):
    """As ``groups.partner_zone``, for the home rules of ``PARTNER_RULES``: a corner of the
    work triangle within ``TRIANGLE_LEG`` of one piece of each other kind the kitchen holds
    (anywhere while it holds none: the legs join centres, so the rings are the rule's own,
    and a stove drawn beside the sink is drawn along the run instead), a seat within reach
    of what it is seated at (generous by the seat's largest half-extent)."""
    if category not in PARTNER_RULES.get(rule, ()):
        return None
    if rule == 'work_triangle':
        if scene.room.room_type != 'kitchen':
            return None
        lo, hi = TRIANGLE_LEG
        rings = [shapely.union_all([Point(o.position[:2]).buffer(hi).difference(
                     Point(o.position[:2]).buffer(lo)) for o in kind])
                 for kind in (scene.first_tier_of(c) for c in TRIANGLE_KINDS
                              if category not in c) if kind]
        return shapely.intersection_all(rings) if rings else None
    info = category_of(category, scene.room.room_type, vocabulary) or CATEGORIES[category]
    m = max(info.width[1], info.depth[1]) / 2
    partners = _surfaces(scene, category)
    return zone_beside([p.footprint().buffer(SEAT_REACH + m, join_style='mitre')
                        for p in partners], partners, info)


def path_verdicts(scene: Scene) -> dict[str, bool]:
    """``hallway_path``'s one case, the room, with its verdict (none but in a hallway with
    two doors or more)."""
    if scene.room.room_type != 'hallway' or len(scene.room.doors) < 2:
        return {}
    return {'path': robot.state(scene, PATH_ROBOT).doors_connected}


def hallway_path(scene: Scene) -> Outcome:
    v = path_verdicts(scene)
    return sum(v.values()), len(v)


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
