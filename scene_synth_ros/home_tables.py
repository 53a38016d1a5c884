"""Category tables of the room types of real homes beyond the paper's four (kitchen, dining
room, hallway), and the sizes of real rooms of every type.

``categories.TABLE_COUNTS`` holds the paper's appendix table (SUNCG); this module holds the
same kind of table for the new types, each counted from a named data set or, where no data
exists, from cited design references (said so at the table), and the quantiles of real rooms'
sides and floor areas. ``benchmarks/home_tables.py`` derives every data-derived figure here
again from ``../shared/data/real`` with the package's importers and exits 1 when one
differs; ``docs/datasets.md`` shows the tables.

Category names are the package's (``categories.CATEGORIES`` and the new ones of issue 35);
the data sets' names, as ``datasets.records.normalise_category`` writes them, are mapped
here, every one that occurs decided: mapped, or dropped with the reason.
"""
from __future__ import annotations

from dataclasses import dataclass

# ----------------------------------------------------------------------------- kitchen
# ProcTHOR's object types in its kitchens -> ours (procthor_1room_train.jsonl.gz, the 500
# one-room houses of Ram81/procthor-1k train.jsonl.gz at 5922e52; object types from
# allenai/procthor's asset database). Chairs in ProcTHOR kitchens stand at its dining
# tables (docs/datasets.md), hence dining chair; a mug is a cup and a wine bottle a bottle to
# the paper's tableware categories.
PROCTHOR_KITCHEN = {
    'fridge': 'fridge', 'microwave': 'microwave', 'coffee machine': 'coffee machine',
    'toaster': 'toaster', 'dining table': 'dining table', 'chair': 'dining chair',
    'garbage can': 'trash can', 'house plant': 'plant',
    'shelving unit': 'shelving', 'vase': 'vase',
    'side table': 'stand', 'book': 'book', 'cup': 'cup', 'mug': 'cup', 'bottle': 'bottle',
    'wine bottle': 'bottle',
}
# ProcTHOR's stools come in two heights: a seat for a 0.9 m counter is about 0.65 m high or
# more (a bar stool), a low stool is the paper's stool. Data category -> (the height in m
# from which it is the tall one, the low one's name, the tall one's).
PROCTHOR_KITCHEN_BY_HEIGHT = {'stool': (0.65, 'stool', 'bar stool')}
# ProcTHOR's counter is one asset per kitchen whose id names its shape
# (Countertop_<shape>_<w>x<d>): a straight run (I), an L of two runs along two walls, a U (C)
# of three, or a free-standing island. Our counter is one straight run along a wall.
PROCTHOR_COUNTER_TYPES = ('counter top',)
PROCTHOR_COUNTER_SHAPES = {'I': ('counter', 1), 'L': ('counter', 2), 'C': ('counter', 3),
                           'Island': ('kitchen island', 1)}
# Left out of the kitchen table: paintings and televisions hang on the walls of ProcTHOR's
# kitchens (out of the pipeline, as datasets.training leaves out 'mounted' categories); the
# rest are food, utensils, small items and props the package does not model.
PROCTHOR_KITCHEN_DROPPED = (
    'painting', 'television', 'egg', 'tomato', 'potato', 'lettuce', 'apple', 'bread',
    'spray bottle', 'soap bottle', 'butter knife', 'knife', 'spatula', 'fork', 'spoon', 'ladle',
    'salt shaker', 'pepper shaker', 'plate', 'bowl', 'pot', 'pan', 'kettle', 'dish sponge',
    'paper towel roll', 'garbage bag', 'statue', 'pencil', 'pen', 'cell phone', 'credit card',
    'safe',
)
# ProcTHOR's kitchens hold no sink, stove or dishwasher among their objects, so those come as
# a share of the kitchens from references:
# - kitchen sink: one per kitchen; every dwelling's kitchen has a sink (International
#   Residential Code 2021, R306.2);
# - stove: one per kitchen; the NKBA Kitchen Planning Guidelines' work triangle joins the
#   sink, the cooking surface and the refrigerator of every kitchen;
# - dishwasher: 80.1 of 118.2 million US homes have one, 67.8 % (US EIA, Residential Energy
#   Consumption Survey 2015, published June 2017).
KITCHEN_REFERENCE = {'kitchen sink': 1.0, 'stove': 1.0, 'dishwasher': 0.678}

# ----------------------------------------------------------------------------- dining
# 3D-FRONT (Fu et al., ICCV 2021) categories of a dining group -> ours (3D-FUTURE's category
# names). Counted over 3D-FRONT's dining rooms (room type DiningRoom, all their furniture
# must be decided here) and the dining group of its living-dining rooms (the other furniture
# of those is the living room's). A side cabinet in a living-dining room is counted as the
# dining group's sideboard; a wine cabinet stores for the table, so it is a sideboard too.
FRONT_DINING = {
    'dining table': 'dining table', 'dining chair': 'dining chair',
    'sideboard / side cabinet / console table': 'sideboard',
    'sideboard / side cabinet / console': 'sideboard', 'wine cabinet': 'sideboard',
}
FRONT_DINING_GROUP_ROOMS = ('LivingDiningRoom',)

# ----------------------------------------------------------------------------- the tables
# Objects per room type and the rooms they were counted over, as categories.TABLE_COUNTS.
TABLE_COUNTS = {
    # ProcTHOR kitchens of procthor_1room_train.jsonl.gz through PROCTHOR_KITCHEN,
    # PROCTHOR_KITCHEN_BY_HEIGHT and PROCTHOR_COUNTER_SHAPES, plus KITCHEN_REFERENCE's shares
    # of those kitchens.
    'kitchen': {
        'dining chair': 245, 'counter': 236, 'cup': 157, 'kitchen sink': 147, 'stove': 147,
        'fridge': 146, 'bottle': 111, 'plant': 104, 'dishwasher': 100, 'shelving': 98,
        'dining table': 79, 'trash can': 59, 'vase': 58, 'book': 56, 'stool': 46,
        'bar stool': 45, 'coffee machine': 36, 'toaster': 35, 'microwave': 26,
        'kitchen island': 24, 'stand': 8,
    },
    # 3D-FRONT: the DiningRoom rooms and the dining groups of the LivingDiningRoom rooms of
    # the houses in ../shared/data/real/3dfront (two houses, 3dfront_0a17c68b.json and
    # 3dfront_1d481334.json, with the 3D-FUTURE category mapping), through FRONT_DINING. Two
    # rooms is a small sample: run benchmarks/home_tables.py on the full 3D-FRONT to count
    # its dining rooms. No published table of 3D-FRONT's categories per dining room was
    # found (the 3D-FRONT paper gives no categories per room type).
    'dining': {'dining chair': 8, 'dining table': 2, 'sideboard': 1},
    # No data set here has furnished hallways (3D-FRONT's one aisle here is empty), so this
    # table is a DESIGN ESTIMATE, not a measurement: objects per 100 hallways, from the
    # furniture an entrance hall holds in Neufert, Architects' Data (4th ed., 2012,
    # on entrance halls): a place to hang coats, to keep and to put on shoes, and a surface
    # for keys and post. Coats: a coat rack in most halls; shoes: a shoe bench or a shoe
    # cabinet in most; a console table in under half (a narrow hall leaves no room for it);
    # a plant or vase on the console table in some.
    'hallway': {'coat rack': 70, 'shoe bench': 45, 'shoes cabinet': 40, 'console table': 35,
                'plant': 15, 'vase': 10},
}
ROOMS_IN_TABLE = {'kitchen': 147, 'dining': 2, 'hallway': 100}

# Doors and windows per room, as categories.ARCHITECTURE_COUNTS gives the paper's. Kitchens:
# doors from the two 3D-FRONT kitchens here (a ProcTHOR one-room house has its one outside
# door only), windows from ProcTHOR's 147 kitchens. Dining rooms: ESTIMATE (no dining room
# with its doors here), a door to the kitchen and one to the hall or living room, a window.
# Hallways: doors from the 3D-FRONT aisle here (four: it joins the rooms), no window.
OPENINGS_PER_ROOM = {'kitchen': {'door': 1.5, 'window': 1.32},
                     'dining': {'door': 2.0, 'window': 1.0},
                     'hallway': {'door': 4.0, 'window': 0.0}}


# ----------------------------------------------------------------------------- room sizes
SIZE_QUANTILES = (0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0)


@dataclass(frozen=True)
class RoomSizes:
    """Real rooms of one type: how many (and from which data set), and the quantiles
    ``SIZE_QUANTILES`` of their longer and shorter side along their own axes
    (``render.room_axis_yaw``; m) and of their floor area (m²)."""

    rooms: int
    sources: dict[str, int]
    longer: tuple[float, ...]
    shorter: tuple[float, ...]
    area: tuple[float, ...]


# Every room of ../shared/data/real (ProcTHOR's 500 one-room houses, the two 3D-FRONT houses,
# the SUNCG house) whose type datasets/room_types.yaml maps to ours.
ROOM_SIZES = {
    'bathroom': RoomSizes(2, {'3dfront': 2},
                          longer=(1.73, 1.77, 1.83, 1.94, 2.04, 2.1, 2.14),
                          shorter=(1.69, 1.71, 1.73, 1.77, 1.81, 1.83, 1.85),
                          area=(2.93, 3.03, 3.18, 3.44, 3.7, 3.86, 3.96)),
    'bedroom': RoomSizes(161, {'3dfront': 3, 'procthor': 157, 'suncg': 1},
                         longer=(3.22, 3.96, 5.25, 6.54, 7.61, 8.39, 8.79),
                         shorter=(1.66, 3.25, 3.59, 4.12, 5.58, 6.41, 8.7),
                         area=(5.53, 12.24, 18.41, 24.4, 35.44, 45.57, 57.35)),
    'hallway': RoomSizes(1, {'3dfront': 1},
                         longer=(2.14, 2.14, 2.14, 2.14, 2.14, 2.14, 2.14),
                         shorter=(1.03, 1.03, 1.03, 1.03, 1.03, 1.03, 1.03),
                         area=(2.2, 2.2, 2.2, 2.2, 2.2, 2.2, 2.2)),
    'kitchen': RoomSizes(149, {'3dfront': 2, 'procthor': 147},
                         longer=(3.17, 4.23, 5.45, 6.51, 7.87, 8.36, 8.77),
                         shorter=(1.6, 3.38, 3.76, 4.3, 5.6, 6.42, 8.77),
                         area=(5.17, 13.28, 18.62, 26.82, 36.06, 48.61, 65.12)),
    'living': RoomSizes(198, {'3dfront': 2, 'procthor': 196},
                        longer=(3.21, 4.07, 5.52, 6.7, 7.86, 8.4, 8.78),
                        shorter=(1.74, 3.38, 3.76, 4.26, 6.07, 6.83, 8.7),
                        area=(6.03, 15.56, 19.82, 27.06, 37.25, 52.85, 75.6)),
}
