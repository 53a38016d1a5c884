"""The floor a designer keeps clear around a piece, reserved when the piece is placed.

A placed piece *reserves* the floor its use needs, as the access rules of
``rules`` measure it: the 0.5 m before storage, the activity space before a
WC, a basin, a shower or a bath, the 0.4 m beside a bed where one gets in, the chair's place
before a desk. Whatever is placed later keeps off those zones (but the seat a zone is kept
for), and a piece fits only where its own zones are on the floor and free. Each zone is a
little deeper than the rule asks (``MARGIN``), so the corpus keeps the rules with room to
spare, not by millimetres.

``zones(obj)`` gives a piece's needs: each need a list of alternative zones of which one must
be free (a single bed is got into from its foot or either long side); the layout reserves the
first free alternative of each.
"""
from __future__ import annotations

from dataclasses import dataclass

from shapely.geometry import Polygon

from ..categories import CATEGORIES, members
from ..geometry import local_box
from ..rules.access import SEATS as TABLE_SEATS
from ..rules.access import STORAGE, USED_FRONT
from ..scene import PlacedObject
from ..thresholds import (
    BED_CLEARANCE,
    DINING_CLEARANCE,
    ENTRY_STRETCH,
    FIXTURE_CLEARANCE,
    HEAD_END,
    KITCHEN_AISLE,
    STORAGE_CLEARANCE,
    WALL_CLEARANCE,
)

MARGIN = 0.05
BED_SLACK = 0.2
# The largest nightstand of the catalog's category, across and along the bed, with the gap
# the corpus leaves between them.
NIGHTSTAND = (CATEGORIES['stand'].width[1] + 0.06, CATEGORIES['stand'].depth[1])
# A desk's, a dressing table's or a piano's seat stands in front of it: the place is kept for
# the seat alone, as deep as a chair pulled up to it (design guides ask 0.75-0.9 m).
SEATED_FRONT = members('worktop')
SEAT_SPOT = 0.8
# A kitchen's units and appliances keep the work aisle before them.
KITCHEN_FRONTS = members('counter run') + ('fridge',)
DINING_SEATS = members('dining seat')


@dataclass(frozen=True)
class Zone:
    """Floor kept clear for ``owner``: of the walls always, of other furniture unless
    ``walls_only``; pieces of the ``allowed`` categories may stand in it (it is kept for
    them, so it must also be clear of the doors' zones)."""

    polygon: Polygon
    owner: str
    walls_only: bool = False
    allowed: tuple[str, ...] = ()


def _front(obj: PlacedObject, depth: float, stretch: float | None = None,
           where: float = 0.0) -> Polygon:
    """The strip ``depth`` deep before the front, over its whole width or over ``stretch``
    metres of it centred ``where`` (-1 right end, 0 middle, 1 left end)."""
    d, w = obj.depth / 2, obj.width / 2
    if stretch is None or stretch >= obj.width:
        return local_box(obj, d, d + depth, -w, w)
    centre = where * (w - stretch / 2)
    return local_box(obj, d, d + depth, centre - stretch / 2, centre + stretch / 2)


def _long_side(obj: PlacedObject, side: int, depth: float) -> Polygon:
    """Beside a bed (side 1 left, -1 right) from ``HEAD_END`` past the headboard, where a
    nightstand stands, to the foot."""
    d, w = obj.depth / 2, obj.width / 2
    x0 = -d + min(HEAD_END, obj.depth / 2)
    y = (w, w + depth) if side > 0 else (-w - depth, -w)
    return local_box(obj, x0, d, *y)


def _head(obj: PlacedObject, side: int) -> Polygon:
    """Beside the head of a bed, where the largest nightstand stands."""
    d, w = obj.depth / 2, obj.width / 2
    return local_box(obj, -d, -d + NIGHTSTAND[1], *((w, w + NIGHTSTAND[0]) if side > 0
                                              else (-w - NIGHTSTAND[0], -w)))


def _end(obj: PlacedObject, side: int, depth: float) -> Polygon:
    """Beyond one end of a piece whose front is a long side (a daybed)."""
    d, w = obj.depth / 2, obj.width / 2
    return local_box(obj, -d, d, *((w, w + depth) if side > 0 else (-w - depth, -w)))


def _around(obj: PlacedObject, depth: float, open_sides: str = 'xXyY') -> Polygon:
    """The box ``depth`` wider than the piece on each of ``open_sides`` ('X' front, 'x'
    back, 'Y' left end, 'y' right end), flush with it on the others."""
    d, w = obj.depth / 2, obj.width / 2
    return local_box(obj, -d - depth * ('x' in open_sides), d + depth * ('X' in open_sides),
                -w - depth * ('y' in open_sides), w + depth * ('Y' in open_sides))


def _home_zones(obj: PlacedObject) -> list[list[Zone]] | None:
    """The needs of the pieces of the rooms of a home (None for the paper's): the work
    aisle before a kitchen's units (those of units at a corner may overlap); the seats' floor
    around a
    dining table, on every side or on all but one (a table against a wall); around an island
    the aisle on every side, its stools' at its front."""
    cat, own = obj.category, obj.id
    if cat in KITCHEN_FRONTS:
        return [[Zone(_front(obj, KITCHEN_AISLE + MARGIN), own)]]
    if cat == 'dining table':
        return [[Zone(_around(obj, DINING_CLEARANCE + MARGIN, sides), own,
                      allowed=DINING_SEATS)
                 for sides in ('xXyY', 'XyY', 'xyY', 'xXY', 'xXy')]]
    if cat == 'kitchen island':
        return [[Zone(_around(obj, KITCHEN_AISLE + MARGIN), own, allowed=DINING_SEATS)]]
    if cat == 'sideboard':
        return [[Zone(_front(obj, STORAGE_CLEARANCE + MARGIN), own)]]
    return None


def zones(obj: PlacedObject) -> list[list[Zone]]:
    """What ``obj`` needs kept clear: needs, each a list of alternatives."""
    cat, own = obj.category, obj.id
    home = _home_zones(obj)
    if home is not None:
        return home
    if cat in SEATED_FRONT:
        return [[Zone(_front(obj, SEAT_SPOT), own, allowed=TABLE_SEATS)]]
    if cat in STORAGE:
        return [[Zone(_front(obj, STORAGE_CLEARANCE + MARGIN), own)]]
    if cat in FIXTURE_CLEARANCE:
        depth = FIXTURE_CLEARANCE[cat] + MARGIN
        if cat in ENTRY_STRETCH:
            stretch = ENTRY_STRETCH[cat] + 2 * MARGIN
            return [[Zone(_front(obj, depth, stretch, where), own) for where in (0, -1, 1)]]
        return [[Zone(_front(obj, depth), own)]]
    # Beside a bed the robot itself must pass, to the bed and to the nightstand's front:
    # its width and 20 cm of slack (design guides ask 0.6-0.75 m there).
    depth = BED_CLEARANCE + BED_SLACK
    if cat == 'double bed':
        # Room for a nightstand at the head of at least one side.
        head = [Zone(_head(obj, side), own, allowed=('stand',)) for side in (1, -1)]
        return [[Zone(_long_side(obj, 1, depth), own)], [Zone(_long_side(obj, -1, depth), own)],
                head]
    if cat == 'daybed':
        return [[Zone(_front(obj, depth), own), Zone(_end(obj, 1, depth), own),
                 Zone(_end(obj, -1, depth), own)]]
    if cat in ('single bed', 'bunker bed', 'baby bed'):
        return [[Zone(_long_side(obj, 1, depth), own), Zone(_long_side(obj, -1, depth), own),
                 Zone(_front(obj, depth), own)]]
    if cat in USED_FRONT:
        return [[Zone(_front(obj, WALL_CLEARANCE + MARGIN), own, walls_only=True)]]
    return []
