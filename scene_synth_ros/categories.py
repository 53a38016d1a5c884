"""Per-room-type category sets of the paper's appendix table, with what the rest of the
package needs to know about each category.

Counts come from Table 'category_counts' of Ritchie et al. (CVPR 2019); the number of rooms
per type from section 4 of the paper. Doors and windows are architecture: they come with the
room layout, so they are kept apart (``ARCHITECTURE_COUNTS``) and are not categories here.

Sizes follow the package convention (see ``scene.PlacedObject``): ``width`` across the
object's front (local y), ``depth`` from back to front (local x, the front faces +x), and
``height``, all in metres.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property, lru_cache
import math
from typing import Any, Iterable

from . import home_tables
from .errors import RoomTypeConflict, UnknownRoomType

# The paper's room types (its appendix table), then the rooms of real homes beyond them
# (``home_tables``). The corpus makes and the design rules judge them all
# (``CORPUS_ROOM_TYPES``); ``ROOM_TYPES``, those the shipped weights furnish, are the
# layouts' room types: a new type joins them with its trained bundle (all have).
PAPER_ROOM_TYPES = ('bedroom', 'living', 'office', 'bathroom')
HOME_ROOM_TYPES = ('kitchen', 'dining', 'hallway')
CORPUS_ROOM_TYPES = PAPER_ROOM_TYPES + HOME_ROOM_TYPES
ROOM_TYPES = PAPER_ROOM_TYPES + HOME_ROOM_TYPES
# Room types that are passages first: one too narrow for any of its furniture is furnished
# empty rather than refused (a corridor of a real home often holds nothing).
PASSAGE_ROOM_TYPES = ('hallway',)

# Rooms per type after the paper's filtering (section 4).
ROOMS_IN_TABLE = {'bedroom': 6300, 'living': 1400, 'office': 1200, 'bathroom': 6800}

# Side of the square area, in metres, that a top-down image of each room type covers at the
# networks' resolution, and so its pixels' size: at 64 px 9.4 cm (bedroom), 12.5 cm (living),
# 10.9 cm (office), 7.8 cm (bathroom) a pixel. A larger room (up to
# ``thresholds.MAX_ROOM_SIDE``) is seen in a larger image of the same pixels
# (``render.Frame.for_room``).
ROOM_SIZE_CAP = {'bedroom': 6.0, 'living': 8.0, 'office': 7.0, 'bathroom': 5.0,
                 # at the bedroom's 9.4 cm a pixel: a hallway's 0.9 m path is ten pixels
                 'kitchen': 6.0, 'dining': 7.0, 'hallway': 6.0}

# Doors and windows per room type, from the same table (architecture, not furniture).
ARCHITECTURE_COUNTS = {
    'bedroom': {'door': 8335, 'window': 7104},
    'living': {'door': 2286, 'window': 1789},
    'office': {'door': 1572, 'window': 1307},
    'bathroom': {'door': 7448, 'window': 4299},
}

# Object counts per room type, as printed in the paper (doors and windows removed).
TABLE_COUNTS = {
    'bedroom': {
        'wardrobe': 6690, 'stand': 6508, 'double bed': 4230, 'table lamp': 2844, 'desk': 2586,
        'dresser': 2222, 'office chair': 2077, 'single bed': 2032, 'dressing table': 1730,
        'tv stand': 1432, 'floor lamp': 1387, 'plant': 1341, 'television': 1252,
        'ottoman': 1142, 'coffee table': 1048, 'laptop': 1010, 'shelving': 901, 'book': 858,
        'sofa chair': 727, 'armchair': 703, 'shoes cabinet': 619, 'straight chair': 595,
        'bunker bed': 593, 'hanger': 540, 'loudspeaker': 438, 'vase': 395, 'sofa': 393,
        'console': 368, 'pedestal fan': 320, 'baby bed': 266, 'toy': 231, 'daybed': 181,
        'stool': 178, 'bench chair': 134, 'whiteboard': 105, 'piano': 102, 'chair': 98,
        'fishbowl': 59,
    },
    'living': {
        'sofa': 1661, 'coffee table': 1336, 'plant': 1059, 'sofa chair': 983, 'tv stand': 696,
        'floor lamp': 651, 'television': 447, 'loudspeaker': 384, 'ottoman': 314,
        'shelving': 309, 'vase': 282, 'fireplace': 257, 'armchair': 204, 'console': 187,
        'wardrobe': 172, 'stand': 101, 'piano': 85, 'laptop': 72, 'book': 69,
        'table lamp': 68, 'dresser': 64, 'cup': 59, 'toy': 56, 'straight chair': 51,
        'pedestal fan': 40, 'hanger': 34, 'stool': 33, 'shoes cabinet': 31, 'bench chair': 26,
        'fishbowl': 21, 'fruit bowl': 17, 'glass': 16, 'bottle': 15,
    },
    'office': {
        'desk': 1616, 'office chair': 1577, 'shelving': 764, 'plant': 557, 'laptop': 377,
        'book': 356, 'wardrobe': 319, 'sofa': 313, 'armchair': 300, 'table lamp': 297,
        'sofa chair': 290, 'straight chair': 274, 'floor lamp': 256, 'tv stand': 137,
        'coffee table': 137, 'vase': 132, 'loudspeaker': 113, 'ottoman': 112, 'stand': 102,
        'whiteboard': 100, 'dresser': 84, 'television': 84, 'piano': 75, 'stool': 56,
        'toy': 52, 'hanger': 51, 'pedestal fan': 49, 'shoes cabinet': 39, 'fireplace': 38,
        'bench chair': 37, 'water machine': 32, 'console': 30, 'cup': 27, 'fishbowl': 5,
    },
    'bathroom': {
        'toilet': 6437, 'bathtub': 5441, 'shower': 5308, 'sink': 4627, 'shelving': 3963,
        'bidet': 1753, 'washer': 1428, 'plant': 1045, 'wardrobe': 459, 'trash can': 409,
        'stand': 315, 'floor lamp': 231, 'toy': 126, 'hanger': 111, 'ottoman': 95,
        'dresser': 89, 'cabinet': 57, 'vase': 31, 'coffee table': 31, 'straight chair': 20,
    },
}


@dataclass(frozen=True)
class CategoryInfo:
    """What is known about one category, whatever the room type."""

    name: str
    tier: str                                    # 'first' (on the floor) or 'second'
    width: tuple[float, float]                   # (min, max) across the front, metres
    depth: tuple[float, float]                   # (min, max) back to front, metres
    height: tuple[float, float]                  # (min, max), metres
    supported_by: tuple[str, ...] = ()           # second tier: first-tier parents
    against_wall: bool = False                   # back normally touches a wall
    description: str = ''
    roles: frozenset[str] = frozenset()          # what it is for (``ROLES``)
    # second tier: where a designer expects it, each parent with the weight the corpus
    # prefers it by (``PLAUSIBLE_PARENTS``); a subset of ``supported_by``
    parents: tuple[tuple[str, float], ...] = ()

    @property
    def mean_footprint(self) -> float:
        """Mean footprint area in m^2 of a size drawn uniformly from the ranges."""
        return (sum(self.width) / 2.0) * (sum(self.depth) / 2.0)

    def size_is_plausible(self, width: float, depth: float, height: float,
                          slack: float = 0.5) -> bool:
        """Whether a size is within the ranges widened by ``slack`` (a fraction)."""
        for value, (lo, hi) in ((width, self.width), (depth, self.depth),
                                (height, self.height)):
            if not (lo * (1.0 - slack) <= value <= hi * (1.0 + slack)):
                return False
        return True


# The home's categories beyond the paper's table in roles the paper's categories have too;
# they come last in those roles, so that the corpus draws among the paper's categories as
# before (a paper room holds none of them).
_HOME_SEATS = ('dining chair', 'bar stool')
_HOME_OPERATED = ('counter', 'kitchen sink', 'stove', 'fridge', 'dishwasher', 'sideboard',
                  'shoe bench', 'coat rack')

# What a category is for, as the design rules, the corpus and insertion ask it: the one
# definition of each role, which a category's description carries (``CategoryInfo.roles``).
# Members are listed in the order the corpus draws among them.
ROLES: dict[str, tuple[str, ...]] = {
    'bed': ('double bed', 'single bed', 'bunker bed', 'baby bed', 'daybed'),
    # one per bedroom (a cot comes beside one)
    'main bed': ('double bed', 'single bed', 'bunker bed', 'daybed'),
    # a head end against the wall, with nightstands beside it
    'headboard bed': ('double bed', 'single bed', 'bunker bed'),
    'lounge seat': ('sofa', 'sofa chair', 'armchair', 'daybed'),
    'armchair': ('sofa chair', 'armchair'),
    # a chair needs a table to sit at
    'chair': ('office chair', 'straight chair', 'chair'),
    # what people sit on at a table or a desk
    'table seat': ('office chair', 'straight chair', 'chair', 'stool') + _HOME_SEATS,
    'bench': ('bench chair',),
    # seats light enough to be pulled out of the way of what they stand before
    'loose seat': ('office chair', 'straight chair', 'chair', 'stool', 'ottoman', 'bench chair')
    + _HOME_SEATS,
    # used seated, from the front
    'worktop': ('desk', 'dressing table', 'piano'),
    # a worktop that is not complete without its seat
    'desk': ('desk', 'dressing table'),
    'table': ('desk', 'dressing table', 'piano', 'coffee table'),
    # doors or drawers open at the front
    'storage': ('wardrobe', 'dresser', 'dressing table', 'shelving', 'shoes cabinet', 'cabinet',
                'washer'),
    'fixture': ('toilet', 'bidet', 'sink', 'shower', 'bathtub'),
    # one must stand before it to use it (open a door or drawer, sit on a WC, work at a desk)
    'operated front': ('wardrobe', 'dresser', 'dressing table', 'shelving', 'shoes cabinet',
                       'cabinet', 'washer', 'toilet', 'bidet', 'sink', 'shower', 'bathtub',
                       'stand', 'tv stand', 'desk', 'piano', 'fireplace', 'whiteboard',
                       'water machine') + _HOME_OPERATED,
    # the rooms of a home beyond the paper's four (kitchen, dining room, hallway)
    # the kitchen's work triangle: the cook walks between these three
    'work triangle': ('kitchen sink', 'stove', 'fridge'),
    # units that stand side by side along a wall under one continuous worktop
    'counter run': ('counter', 'kitchen sink', 'stove', 'dishwasher'),
    # doors, drawers or an oven's drop-down flap swing out into the floor before the front
    'door front': ('counter', 'kitchen sink', 'stove', 'fridge', 'dishwasher', 'sideboard'),
    # tables people sit at for a meal (a kitchen island's seats face its front overhang)
    'dining surface': ('dining table', 'kitchen island'),
    # what people sit on at a dining surface
    'dining seat': ('dining chair', 'bar stool'),
    # small appliances that stand on a worktop, near a socket on the wall behind it
    'worktop appliance': ('microwave', 'coffee machine', 'toaster'),
    # what one uses on coming in by a home's entrance door
    'entrance': ('shoe bench', 'coat rack', 'console table'),
}


def members(role: str) -> tuple[str, ...]:
    """The package's categories (``CATEGORIES``) that have ``role``, in ``ROLES``'s order."""
    return ROLES[role]


def roles_of(name: str) -> frozenset[str]:
    """The roles the package gives category ``name`` (none for a name it lacks)."""
    return frozenset(r for r, names in ROLES.items() if name in names)


# Where a designer expects each second-tier object, among the parents that can hold it, and
# the weight the corpus gives each (a parent's share of its placements is its weight over the
# sum of those present): no TV on a desk or table lamp on a shoe cabinet (a design review
# flagged both), a game console by the TV, a laptop where one sits (or charges it at the
# bedside), tableware where one eats or drinks; nothing on a washing machine that vibrates,
# and no vase in the way on a washbasin (a small plant there is usual).
_DECOR = {'stand': 1, 'desk': 1, 'dresser': 1, 'dressing table': 1, 'tv stand': 1,
          'coffee table': 1, 'shelving': 1, 'shoes cabinet': 1, 'fireplace': 1, 'cabinet': 1}
PLAUSIBLE_PARENTS: dict[str, dict[str, float]] = {
    'table lamp': {'stand': 8, 'desk': 2, 'dresser': 1.5, 'dressing table': 1.5, 'tv stand': 1},
    'television': {'tv stand': 12, 'dresser': 2},
    'console': {'tv stand': 10},
    'laptop': {'desk': 10, 'dressing table': 1, 'coffee table': 2, 'stand': 1},
    'book': {'desk': 3, 'stand': 2, 'shelving': 4, 'coffee table': 1, 'dresser': 1,
             'double bed': 1, 'single bed': 1},
    'plant': {**_DECOR, 'shelving': 2, 'desk': 2, 'tv stand': 2, 'coffee table': 2, 'sink': 3},
    'vase': {**_DECOR, 'coffee table': 3, 'dresser': 2, 'tv stand': 2, 'fireplace': 2},
    'toy': {'shelving': 3, 'desk': 1, 'stand': 1, 'dresser': 1, 'coffee table': 1, 'bathtub': 4,
            'cabinet': 1, 'double bed': 1, 'single bed': 2, 'bunker bed': 1, 'daybed': 1},
    'fishbowl': {'desk': 2, 'dresser': 2, 'shelving': 2, 'tv stand': 1, 'coffee table': 1,
                 'stand': 1},
    'cup': {'coffee table': 5, 'desk': 3, 'stand': 1},
    'glass': {'coffee table': 5, 'desk': 1, 'stand': 1},
    'bottle': {'coffee table': 5, 'desk': 1, 'stand': 1},
    'fruit bowl': {'coffee table': 5, 'desk': 1},
    # at the back of a worktop, by a socket; seldom on an island, whose top is where people
    # eat. Not on a kitchen sink: its box rises to the top of its tap.
    'microwave': {'counter': 6, 'kitchen island': 1},
    'coffee machine': {'counter': 6, 'kitchen island': 1, 'sideboard': 1},
    'toaster': {'counter': 6, 'kitchen island': 1},
}

# In the rooms of a home beyond the paper's, the paper's small things stand on that room's
# surfaces too, by these weights beside their ``PLAUSIBLE_PARENTS``: tableware and a vase on
# the dining table or the worktop, a plant or a vase on a sideboard or a console table, books
# on a shelf. Only those rooms' categories get them (``paper_spec``), so the paper's rooms
# and the weights trained on them are as they were.
HOME_PARENTS: dict[str, dict[str, float]] = {
    'cup': {'dining table': 5, 'counter': 3, 'kitchen island': 3},
    'bottle': {'dining table': 3, 'counter': 4, 'kitchen island': 2},
    'vase': {'dining table': 4, 'sideboard': 4, 'console table': 5, 'counter': 1},
    'plant': {'sideboard': 3, 'console table': 3, 'counter': 2, 'dining table': 1,
              'shoe bench': 1},
    'book': {'shelving': 4, 'dining table': 1, 'counter': 1},
}

_SURFACES_LAMP = ('stand', 'desk', 'dresser', 'dressing table', 'shoes cabinet', 'tv stand')
_SURFACES_DECOR = ('stand', 'desk', 'dresser', 'dressing table', 'tv stand', 'coffee table',
                   'shelving', 'shoes cabinet', 'fireplace', 'sink', 'washer', 'cabinet')
_SURFACES_TABLEWARE = ('coffee table', 'desk', 'tv stand', 'dresser', 'stand')
_BEDS = ROLES['main bed']


def _c(name, tier, width, depth, height, supported_by=(), against_wall=False, description=''):
    return CategoryInfo(name, tier, width, depth, height, tuple(supported_by), against_wall,
                        description, roles_of(name), _parents_of(name))


def _parents_of(name: str) -> tuple[tuple[str, float], ...]:
    return tuple((p, float(w)) for p, w in PLAUSIBLE_PARENTS.get(name, {}).items())


CATEGORIES: dict[str, CategoryInfo] = {c.name: c for c in (
    # first tier: stands on the floor
    _c('wardrobe', 'first', (0.8, 2.2), (0.5, 0.65), (1.8, 2.3), against_wall=True,
       description='clothes wardrobe, doors at the front'),
    _c('stand', 'first', (0.4, 0.6), (0.35, 0.5), (0.45, 0.65), against_wall=True,
       description='nightstand / small side cabinet'),
    _c('double bed', 'first', (1.4, 2.0), (1.95, 2.2), (0.8, 1.2), against_wall=True,
       description='double bed, headboard at the back, foot at the front'),
    _c('single bed', 'first', (0.9, 1.2), (1.9, 2.1), (0.6, 1.0), against_wall=True),
    _c('bunker bed', 'first', (0.9, 1.2), (1.95, 2.1), (1.5, 1.8), against_wall=True,
       description='bunk bed with two decks and a ladder'),
    _c('baby bed', 'first', (0.65, 0.8), (1.2, 1.45), (0.85, 1.05), against_wall=True,
       description='cot with barred sides'),
    _c('daybed', 'first', (1.95, 2.1), (0.9, 1.1), (0.7, 0.95), against_wall=True,
       description='daybed, long side against the wall'),
    _c('desk', 'first', (1.0, 1.8), (0.55, 0.8), (0.72, 0.78), against_wall=True),
    _c('dresser', 'first', (0.8, 1.6), (0.42, 0.55), (0.75, 1.2), against_wall=True,
       description='chest of drawers'),
    _c('dressing table', 'first', (0.8, 1.3), (0.4, 0.5), (1.2, 1.6), against_wall=True,
       description='vanity table with a mirror'),
    _c('tv stand', 'first', (1.0, 2.0), (0.35, 0.5), (0.4, 0.6), against_wall=True),
    _c('shelving', 'first', (0.6, 1.6), (0.28, 0.4), (0.8, 2.0), against_wall=True,
       description='open shelves / bookcase'),
    _c('shoes cabinet', 'first', (0.6, 1.2), (0.25, 0.4), (0.8, 1.2), against_wall=True),
    _c('office chair', 'first', (0.55, 0.7), (0.55, 0.7), (0.9, 1.25),
       description='swivel chair on a five-star base'),
    _c('straight chair', 'first', (0.42, 0.5), (0.45, 0.55), (0.8, 1.0)),
    _c('chair', 'first', (0.45, 0.6), (0.5, 0.6), (0.8, 1.0)),
    _c('stool', 'first', (0.35, 0.45), (0.35, 0.45), (0.45, 0.75)),
    _c('bench chair', 'first', (0.9, 1.5), (0.35, 0.45), (0.42, 0.48),
       description='bench without a back'),
    _c('ottoman', 'first', (0.45, 1.0), (0.4, 0.6), (0.38, 0.46)),
    _c('sofa', 'first', (1.6, 2.6), (0.8, 1.0), (0.75, 0.95), against_wall=True),
    _c('sofa chair', 'first', (0.7, 0.95), (0.75, 0.95), (0.75, 0.95),
       description='upholstered club chair'),
    _c('armchair', 'first', (0.65, 0.85), (0.7, 0.85), (0.8, 1.05)),
    _c('coffee table', 'first', (0.8, 1.4), (0.45, 0.8), (0.35, 0.48)),
    _c('floor lamp', 'first', (0.3, 0.5), (0.3, 0.5), (1.4, 1.8)),
    _c('loudspeaker', 'first', (0.2, 0.35), (0.22, 0.35), (0.8, 1.1)),
    _c('pedestal fan', 'first', (0.35, 0.5), (0.3, 0.45), (1.0, 1.4)),
    _c('hanger', 'first', (0.4, 0.9), (0.35, 0.5), (1.6, 1.9),
       description='coat stand / clothes rack'),
    _c('whiteboard', 'first', (1.0, 1.8), (0.45, 0.6), (1.6, 1.9),
       description='whiteboard on a mobile stand'),
    _c('piano', 'first', (1.4, 1.55), (0.55, 0.65), (1.1, 1.3), against_wall=True,
       description='upright piano'),
    _c('fireplace', 'first', (1.0, 1.8), (0.35, 0.6), (1.0, 1.3), against_wall=True),
    _c('water machine', 'first', (0.3, 0.4), (0.3, 0.4), (0.95, 1.1), against_wall=True,
       description='water cooler with a bottle on top'),
    _c('toilet', 'first', (0.36, 0.42), (0.6, 0.75), (0.7, 0.85), against_wall=True),
    _c('bidet', 'first', (0.36, 0.4), (0.53, 0.6), (0.38, 0.42), against_wall=True),
    _c('bathtub', 'first', (1.5, 1.8), (0.7, 0.85), (0.5, 0.62), against_wall=True,
       description='bathtub, long side at the front'),
    _c('shower', 'first', (0.8, 1.0), (0.8, 1.0), (2.0, 2.1), against_wall=True,
       description='shower cabin with a tray'),
    _c('sink', 'first', (0.5, 1.2), (0.42, 0.55), (0.8, 0.9), against_wall=True,
       description='washbasin on a vanity unit'),
    _c('washer', 'first', (0.595, 0.6), (0.55, 0.65), (0.82, 0.86), against_wall=True,
       description='washing machine'),
    _c('trash can', 'first', (0.22, 0.35), (0.22, 0.35), (0.3, 0.5)),
    _c('cabinet', 'first', (0.35, 0.6), (0.3, 0.4), (0.8, 1.8), against_wall=True,
       description='bathroom cabinet'),
    # second tier: stands on the top surface of a first-tier object
    _c('table lamp', 'second', (0.2, 0.45), (0.2, 0.45), (0.35, 0.65), _SURFACES_LAMP),
    _c('plant', 'second', (0.15, 0.4), (0.15, 0.4), (0.25, 0.7), _SURFACES_DECOR,
       description='potted plant'),
    _c('television', 'second', (0.8, 1.5), (0.18, 0.3), (0.5, 0.9),
       ('tv stand', 'dresser', 'desk')),
    _c('laptop', 'second', (0.3, 0.38), (0.22, 0.26), (0.2, 0.25),
       ('desk', 'coffee table', 'dressing table', 'stand')),
    _c('book', 'second', (0.15, 0.3), (0.2, 0.3), (0.03, 0.2),
       ('desk', 'stand', 'shelving', 'coffee table', 'dresser') + _BEDS[:2],
       description='a book or a small stack of books'),
    _c('vase', 'second', (0.1, 0.25), (0.1, 0.25), (0.2, 0.5), _SURFACES_DECOR),
    _c('console', 'second', (0.25, 0.4), (0.2, 0.3), (0.05, 0.1), ('tv stand', 'desk'),
       description='game console'),
    _c('toy', 'second', (0.15, 0.4), (0.15, 0.4), (0.1, 0.35),
       ('shelving', 'desk', 'stand', 'dresser', 'coffee table', 'bathtub', 'cabinet')
       + _BEDS),
    _c('fishbowl', 'second', (0.2, 0.35), (0.2, 0.35), (0.18, 0.3),
       ('desk', 'dresser', 'shelving', 'tv stand', 'coffee table', 'stand')),
    _c('cup', 'second', (0.07, 0.1), (0.07, 0.1), (0.08, 0.12), _SURFACES_TABLEWARE),
    _c('glass', 'second', (0.06, 0.09), (0.06, 0.09), (0.1, 0.16), _SURFACES_TABLEWARE),
    _c('bottle', 'second', (0.07, 0.1), (0.07, 0.1), (0.25, 0.35), _SURFACES_TABLEWARE),
    _c('fruit bowl', 'second', (0.2, 0.3), (0.2, 0.3), (0.08, 0.15), _SURFACES_TABLEWARE),
    # The rooms of a home beyond the paper's four: kitchen, dining room, hallway. Sizes from
    # manufacturers' standard ranges (docs/catalog.md lists them); last, so that the paper's
    # categories keep their places (plot colours, model previews). Kitchen units stand at
    # one worktop height, 0.86 to 0.92 m (0.9 m in Europe, 36 in in the USA).
    _c('counter', 'first', (0.6, 3.6), (0.6, 0.65), (0.86, 0.92), against_wall=True,
       description='a run of kitchen base cabinets under one worktop, doors and drawers at '
                   'the front'),
    _c('kitchen sink', 'first', (0.6, 1.2), (0.6, 0.65), (1.1, 1.25), against_wall=True,
       description='sink base unit: a basin in a worktop of counter height, its tap at the '
                   'back the highest point (as the washbasin\'s)'),
    _c('stove', 'first', (0.5, 1.0), (0.6, 0.65), (0.86, 0.92), against_wall=True,
       description='free-standing cooker: a hob on top, the oven door at the front'),
    _c('fridge', 'first', (0.55, 0.91), (0.6, 0.75), (0.82, 2.0), against_wall=True,
       description='refrigerator, under-counter (about 0.85 m) to tall fridge-freezer or '
                   'side-by-side (up to 2 m), doors at the front'),
    _c('dishwasher', 'first', (0.45, 0.6), (0.57, 0.62), (0.82, 0.87), against_wall=True,
       description='free-standing dishwasher, slimline (0.45 m) or full size (0.6 m), its '
                   'door drops open at the front'),
    _c('kitchen island', 'first', (1.2, 2.8), (0.8, 1.2), (0.88, 0.94),
       description='free-standing worktop block: cabinets at the back, at the front an '
                   'overhang that bar stools tuck under'),
    _c('bar stool', 'first', (0.36, 0.48), (0.36, 0.48), (0.62, 1.05),
       description='tall stool for a counter or an island, a footrest ring; a low back on '
                   'the taller ones'),
    _c('dining table', 'first', (0.9, 2.8), (0.8, 1.2), (0.72, 0.77),
       description='dining table for 4 to 10 seats, rectangular, or round (oval when long): '
                   'the top inscribed in the box'),
    _c('dining chair', 'first', (0.42, 0.55), (0.48, 0.6), (0.8, 1.02),
       description='dining chair with a back, seat front at +x'),
    _c('sideboard', 'first', (1.2, 2.2), (0.4, 0.5), (0.7, 0.95), against_wall=True,
       description='low dining-room storage: doors and drawers at the front'),
    _c('shoe bench', 'first', (0.6, 1.2), (0.3, 0.4), (0.42, 0.5), against_wall=True,
       description='hallway bench to sit on, a shelf of shoes below the seat'),
    _c('console table', 'first', (0.8, 1.6), (0.25, 0.4), (0.72, 0.85), against_wall=True,
       description='narrow table on legs against a wall'),
    _c('coat rack', 'first', (0.6, 1.4), (0.25, 0.4), (1.7, 2.0), against_wall=True,
       description='hallway coat rack standing against the wall: a frame with a row of '
                   'hooks and a hat shelf (a coat stand in the open is a hanger)'),
    _c('microwave', 'second', (0.44, 0.62), (0.32, 0.45), (0.25, 0.36),
       tuple(PLAUSIBLE_PARENTS['microwave']),
       description='microwave oven, door at the front'),
    _c('coffee machine', 'second', (0.18, 0.32), (0.28, 0.45), (0.3, 0.45),
       tuple(PLAUSIBLE_PARENTS['coffee machine']),
       description='espresso machine, spout and drip tray at the front'),
    _c('toaster', 'second', (0.26, 0.4), (0.15, 0.22), (0.18, 0.22),
       tuple(PLAUSIBLE_PARENTS['toaster']),
       description='pop-up toaster, slots along its width'),
)}


@dataclass(frozen=True)
class RoomCategorySpec:
    """One category as it appears in one room type."""

    info: CategoryInfo
    count: int                    # instances in the paper's table
    frequency: float              # mean instances per room
    importance: float             # mean footprint area x frequency (paper, section 4)

    @property
    def name(self) -> str:
        return self.info.name

    @property
    def tier(self) -> str:
        return self.info.tier


@dataclass(frozen=True)
class RoomTypeSpec:
    """The category set of one room type, in the table's order."""

    room_type: str
    rooms: int
    size_cap: float
    categories: tuple[RoomCategorySpec, ...] = field(repr=False)
    doors_per_room: float = 0.0
    windows_per_room: float = 0.0

    # Cached: synthesis asks for names and indices tens of thousands of times per room
    # (a profile of 20 bedrooms: 6 % of the time spent rebuilding this tuple).
    @cached_property
    def names(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.categories)

    @cached_property
    def _positions(self) -> dict[str, int]:
        return {name: k for k, name in enumerate(self.names)}

    def index(self, name: str) -> int:
        try:
            return self._positions[name]
        except KeyError:
            raise ValueError(f'{name!r} is not a category of {self.room_type}') from None

    def __getitem__(self, name: str) -> RoomCategorySpec:
        return self.categories[self.index(name)]

    def __contains__(self, name: str) -> bool:
        return name in self._positions

    @property
    def mean_objects_per_room(self) -> float:
        return sum(c.frequency for c in self.categories)

    def distribution(self) -> dict[str, float]:
        """Category distribution of the table (fractions of all objects)."""
        total = sum(c.count for c in self.categories)
        return {c.name: c.count / total for c in self.categories}

    def importance_order(self) -> tuple[str, ...]:
        """Categories by decreasing importance, the paper's order for the category module."""
        return tuple(c.name for c in sorted(self.categories, key=lambda c: -c.importance))

    def info(self, name: str) -> CategoryInfo:
        """What this room type knows of category ``name`` (its tier, sizes, parents)."""
        return self[name].info

    def supports(self, child: str) -> tuple[str, ...]:
        """First-tier categories of this room type that can hold ``child``."""
        return tuple(p for p in self.info(child).supported_by if p in self)

    def to_dict(self) -> dict[str, Any]:
        """The spec as plain JSON data (what a weights bundle carries); ``from_dict``
        reads it back equal."""
        return {'room_type': self.room_type, 'rooms': self.rooms, 'size_cap': self.size_cap,
                'doors_per_room': self.doors_per_room,
                'windows_per_room': self.windows_per_room,
                'categories': [{'name': c.name, 'count': c.count, 'frequency': c.frequency,
                                'importance': c.importance, 'tier': c.info.tier,
                                'width': list(c.info.width), 'depth': list(c.info.depth),
                                'height': list(c.info.height),
                                'supported_by': list(c.info.supported_by),
                                'against_wall': c.info.against_wall,
                                'description': c.info.description,
                                'roles': sorted(c.info.roles),
                                'parents': [[p, w] for p, w in c.info.parents]}
                               for c in self.categories]}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> 'RoomTypeSpec':
        cats = tuple(RoomCategorySpec(
            CategoryInfo(str(c['name']), str(c['tier']), _pair(c['width']), _pair(c['depth']),
                         _pair(c['height']), tuple(map(str, c['supported_by'])),
                         bool(c['against_wall']), str(c.get('description', '')),
                         _roles(c), _weighted_parents(c)),
            int(c['count']), float(c['frequency']), float(c['importance']))
            for c in d['categories'])
        return cls(str(d['room_type']), int(d['rooms']), float(d['size_cap']), cats,
                   float(d['doors_per_room']), float(d['windows_per_room']))


def _roles(d: dict[str, Any]) -> frozenset[str]:
    """A category's roles as a spec's dict gives them; a dict written before categories had
    roles (a bundle of an older release) has the paper's roles of the category's name."""
    if 'roles' in d:
        return frozenset(map(str, d['roles']))
    return roles_of(str(d['name']))


def _weighted_parents(d: dict[str, Any]) -> tuple[tuple[str, float], ...]:
    """A category's weighted parents as a spec's dict gives them (the paper's for a dict
    written before categories had them)."""
    if 'parents' in d:
        return tuple((str(p), float(w)) for p, w in d['parents'])
    return _parents_of(str(d['name']))


def _pair(v) -> tuple[float, float]:
    lo, hi = v
    return (float(lo), float(hi))


# Other names accepted for a room type (after lower-casing, '_' read as ' ').
ROOM_TYPE_ALIASES = {
    'living room': 'living', 'livingroom': 'living', 'bed room': 'bedroom',
    'master bedroom': 'bedroom', 'masterbedroom': 'bedroom',
    'living dining room': 'living', 'livingdiningroom': 'living',     # open plan
    'dining room': 'dining', 'diningroom': 'dining',
    'hall': 'hallway', 'corridor': 'hallway', 'entrance': 'hallway', 'entrance hall': 'hallway',
    'entryway': 'hallway', 'aisle': 'hallway',
}


@dataclass(frozen=True)
class Vocabulary:
    """The room types and categories one call knows: the package's (``ROOM_TYPES``), with
    the category sets of the data set a model was trained on (``specs``) in place of, or
    beside, them. Weights carry theirs (``networks.served.weights_vocabulary``), a data set its
    own (``dataset.yaml``); ``PAPER`` knows the package's tables alone (the paper's, and
    ``home_tables``' for the rooms of a home beyond it). The paper's table stays the
    description of the embedded corpus whatever a vocabulary defines.

    Immutable and hashable: a value passed to the parser, the catalog, the renderer and the
    synthesizer, so that two models in one process know each their own room types."""

    # The data set's category sets, one per room type, in the order they were given; a spec
    # equal to the paper's own is left out (it defines nothing).
    specs: tuple[RoomTypeSpec, ...] = ()

    @classmethod
    def paper(cls) -> 'Vocabulary':
        return cls()

    def with_specs(self, specs: Iterable[RoomTypeSpec]) -> 'Vocabulary':
        """This vocabulary with the category sets of ``specs`` as their room types' ones.
        A spec equal to the paper's changes nothing; a type this vocabulary defines already
        with another category set is refused (``RoomTypeConflict``): two data sets cannot
        share a room type's name in one vocabulary."""
        own = {s.room_type: s for s in self.specs}
        added = []
        for spec in specs:
            current = own.get(spec.room_type)
            if current is not None and current != spec:
                raise RoomTypeConflict(f'room type {spec.room_type!r} is already defined by '
                                       f'another data set; load the weights of one data set '
                                       f'at a time')
            if current is None and not (spec.room_type in ROOM_TYPES
                                        and spec == paper_spec(spec.room_type)):
                own[spec.room_type] = spec
                added.append(spec)
        return self if not added else Vocabulary(self.specs + tuple(added))

    # Hashed once: a vocabulary keys caches that are asked at every insertion.
    def __hash__(self) -> int:
        return self._hash

    @cached_property
    def _hash(self) -> int:
        return hash(self.specs)

    @cached_property
    def _defined(self) -> dict[str, RoomTypeSpec]:
        return {s.room_type: s for s in self.specs}

    @cached_property
    def room_types(self) -> tuple[str, ...]:
        """Every room type known: the package's, then those the data set adds."""
        return ROOM_TYPES + tuple(rt for rt in self._defined if rt not in ROOM_TYPES)

    def resolve(self, name: str) -> str:
        """Canonical room type for a user-given name ('living room' -> 'living')."""
        key = name.strip().lower().replace('_', ' ')
        key = ROOM_TYPE_ALIASES.get(key, key)
        if key not in ROOM_TYPES and key not in self._defined:
            raise UnknownRoomType(f'unknown room type {name[:80]!r}; expected one of '
                                  f'{", ".join(self.room_types)}')
        return key

    def spec(self, room_type: str) -> RoomTypeSpec:
        """The category set of ``room_type``: the data set's where it defines one, else the
        package's table (also for the rooms of a home whose weights are still to come, which
        the corpus makes and the rules judge, though no layout may name them yet)."""
        key = room_type.strip().lower().replace('_', ' ')
        if key in CORPUS_ROOM_TYPES and key not in self._defined:
            return paper_spec(key)
        room_type = self.resolve(room_type)
        return self._defined.get(room_type) or paper_spec(room_type)

    def defines(self, room_type: str) -> bool:
        """Whether ``room_type``'s category set is a data set's rather than the paper's."""
        return room_type in self._defined

    def info(self, name: str, room_type: str | None = None) -> CategoryInfo:
        """What is known of category ``name``: in ``room_type``'s category set when given
        (a data set's categories live there), else in the paper's table, else in the data
        set's types. ``KeyError`` if none has it."""
        if room_type is not None:
            spec = self.spec(room_type)
            if name in spec:
                return spec.info(name)
        if name in CATEGORIES:
            return CATEGORIES[name]
        for spec in self.specs:
            if name in spec:
                return spec.info(name)
        raise KeyError(name)


@lru_cache(maxsize=None)
def paper_spec(room_type: str) -> RoomTypeSpec:
    """The category set of one of the package's room types, from its table: the paper's,
    or for the rooms of a home beyond it ``home_tables``' (whose small things may stand on
    that room's surfaces, ``HOME_PARENTS``)."""
    home = room_type in HOME_ROOM_TYPES
    rooms = (home_tables.ROOMS_IN_TABLE if home else ROOMS_IN_TABLE)[room_type]
    table = (home_tables.TABLE_COUNTS if home else TABLE_COUNTS)[room_type]
    cats = []
    for name, count in table.items():
        info = CATEGORIES[name]
        if home and name in HOME_PARENTS:
            extra = {p: w for p, w in HOME_PARENTS[name].items() if p in table}
            info = replace(info, supported_by=info.supported_by + tuple(
                p for p in extra if p not in info.supported_by),
                parents=info.parents + tuple((p, float(w)) for p, w in extra.items()))
        freq = count / rooms
        cats.append(RoomCategorySpec(info, count, freq, info.mean_footprint * freq))
    if home:
        per_room = home_tables.OPENINGS_PER_ROOM[room_type]
    else:
        per_room = {k: n / rooms for k, n in ARCHITECTURE_COUNTS[room_type].items()}
    return RoomTypeSpec(room_type, rooms, ROOM_SIZE_CAP[room_type], tuple(cats),
                        per_room['door'], per_room['window'])


PAPER = Vocabulary.paper()
# The room types the corpus makes, the rooms of a home among them: what training on the
# corpus knows. A home's type not yet among ``ROOM_TYPES`` is defined as a data set's is, so
# that its bundle carries its category set and the weights describe themselves.
CORPUS = PAPER.with_specs(paper_spec(rt) for rt in CORPUS_ROOM_TYPES if rt not in ROOM_TYPES)


# ``PAPER``'s methods unless a ``vocabulary`` is given, for the code that knows the paper's
# room types only (the corpus, the paper's evaluation).
def resolve_room_type(name: str, vocabulary: Vocabulary = PAPER) -> str:
    """Canonical room type for a user-given name ('living room' -> 'living')."""
    return vocabulary.resolve(name)


def room_spec(room_type: str, vocabulary: Vocabulary = PAPER) -> RoomTypeSpec:
    """The category set of ``room_type`` in ``vocabulary`` (``Vocabulary.spec``)."""
    return vocabulary.spec(room_type)


def kl_divergence(p: dict[str, float], q: dict[str, float], eps: float = 1e-6) -> float:
    """KL(p || q) over the union of keys, both normalised; ``eps`` keeps it finite where q
    has a zero, as the paper's synthesized-vs-dataset comparison needs."""
    keys = sorted(set(p) | set(q))
    ps = [max(p.get(k, 0.0), 0.0) for k in keys]
    qs = [max(q.get(k, 0.0), 0.0) + eps for k in keys]
    sp, sq = sum(ps), sum(qs)
    if sp <= 0:
        raise ValueError('KL divergence of an empty distribution is undefined')
    return sum((a / sp) * math.log((a / sp) / (b / sq)) for a, b in zip(ps, qs, strict=True)
               if a > 0)
