"""Interior-design rules that furnish a room shell.

A room is furnished in three steps. First a *plan*: which objects the room gets, drawn so
that every category's mean count per room is the paper's table frequency (times a
calibration factor that makes up for objects that did not fit; see ``calibration``), with the
partners its pieces need (``with_partners``). Then each object is placed by the rule of its
category, anchors first: beds and sofas go against walls, nightstands at the head of beds,
chairs at desks and tables, coffee tables before sofas, TV stands across from what faces
them, and so on, each keeping off the floor the pieces before it keep clear and finding the
floor it needs itself (``clearance``). Last, ``tidy`` does what a designer would on a walk
through the room: it takes out what the robot cannot reach and what stands outside its group.
Second-tier objects then go on a surface that can hold them and where a designer expects
them, by the weights of their category's description (``categories.PLAUSIBLE_PARENTS``).
"""
from __future__ import annotations

from collections import Counter
import math
from typing import Callable

import numpy as np

from .. import catalog
from ..catalog import ModelVariant
from ..categories import CATEGORIES, members, paper_spec
from ..rules import access, groups, home
from ..scene import PlacedObject
from ..thresholds import TRIANGLE_LEG
from .layout import Layout

# Placement phase of each first-tier category: anchors before what is arranged around them.
PHASE = {
    'double bed': 0, 'single bed': 0, 'bunker bed': 0, 'baby bed': 0, 'daybed': 0,
    'sofa': 0, 'bathtub': 0, 'shower': 0, 'desk': 0, 'piano': 0, 'fireplace': 0,
    'wardrobe': 1, 'dresser': 1, 'dressing table': 1, 'tv stand': 1, 'shelving': 1,
    'shoes cabinet': 1, 'sink': 1, 'toilet': 1, 'washer': 1, 'cabinet': 1,
    'whiteboard': 1, 'water machine': 1,
    'coffee table': 2, 'stand': 2, 'bidet': 2,
    'office chair': 3, 'straight chair': 3, 'chair': 3, 'stool': 3, 'bench chair': 3,
    'ottoman': 3, 'sofa chair': 3, 'armchair': 3,
    'floor lamp': 4, 'loudspeaker': 4, 'pedestal fan': 4, 'hanger': 4, 'trash can': 4,
    # the rooms of a home: the sink fixes the kitchen's run, the rest of the triangle
    # follows it; the dining table is the dining room's anchor
    'kitchen sink': 0, 'dining table': 0, 'coat rack': 0,
    'stove': 0.5, 'fridge': 0.7, 'counter': 1, 'sideboard': 1, 'shoe bench': 1,
    'console table': 1,
    'dishwasher': 2, 'kitchen island': 2,
    'dining chair': 3, 'bar stool': 3,
}

# A kitchen is planned around its units: its dining table takes the floor they leave.
ROOM_PHASE = {'kitchen': {'dining table': 2.5}}

# Categories that usually come in pairs (a nightstand each side, a speaker each side).
PAIRED = {'stand', 'loudspeaker'}

# The beds of a bedroom: one main bed, sometimes a second one.
MAIN_BEDS = members('main bed')

ONE_PER_PARENT = {'television', 'console', 'laptop', 'table lamp', 'fishbowl', 'fruit bowl'}
SYMMETRIC = {'plant', 'vase', 'cup', 'glass', 'bottle', 'fruit bowl', 'fishbowl', 'toy'}
SEATED_BY = members('worktop')
RUN_UNITS = members('counter run')
TRIANGLE = members('work triangle')


def draw_count(rate: float, rng: np.random.Generator, paired: bool = False) -> int:
    """An instance count with mean ``rate``; paired categories come mostly in twos."""
    if paired and rate <= 1.6:
        u = rng.random()
        return 2 if u < 0.4 * rate else (1 if u < 0.6 * rate else 0)
    base = math.floor(rate)
    return base + int(rng.random() < rate - base)


def draw_plan(room_type: str, rng: np.random.Generator,
              calibration: dict[str, float]) -> list[str]:
    """The categories a room gets, with repetitions, first tier then second tier."""
    spec = paper_spec(room_type)
    rate = {c.name: c.frequency * calibration.get(c.name, 1.0) for c in spec.categories}
    plan: list[str] = []
    if room_type == 'bedroom':
        # One main bed, drawn so each bed type keeps its mean; the leftover rate of a type
        # becomes a second bed of that type (twin rooms, a cot beside a double bed).
        p_double = min(rate['double bed'], 1.0)
        others = [b for b in MAIN_BEDS if b != 'double bed']
        rest = sum(rate[b] for b in others)
        p_main = {'double bed': p_double}
        for b in others:
            p_main[b] = (1 - p_double) * rate[b] / rest if rest > 0 else 0.0
        names = list(p_main)
        probs = np.array([p_main[b] for b in names])
        plan.append(names[rng.choice(len(names), p=probs / probs.sum())])
        for b in MAIN_BEDS + ('baby bed',):
            extra = max(0.0, rate[b] - p_main.get(b, 0.0))
            plan += [b] * draw_count(extra, rng)
        skip = set(MAIN_BEDS) | {'baby bed'}
    else:
        skip = set()
    for c in spec.categories:
        if c.name not in skip:
            plan += [c.name] * draw_count(rate[c.name], rng, paired=c.name in PAIRED)
    plan = with_partners(room_type, plan, rate, rng)
    phase = {**PHASE, **ROOM_PHASE.get(room_type, {})}
    first = sorted((n for n in plan if CATEGORIES[n].tier == 'first'),
                   key=lambda n: (phase.get(n, 1), -spec[n].importance))
    second = [n for n in plan if CATEGORIES[n].tier == 'second']
    return first + second


def with_partners(room_type: str, plan: list[str], rate: dict[str, float],
                  rng: np.random.Generator) -> list[str]:
    """The plan with the partners its pieces need and without pieces that have none: seating
    for a coffee table, a nightstand for a double bed; no bidet without a toilet, no
    loudspeakers without a TV stand or a desk. (Calibration brings the categories' rates back
    to the table's.) Desks and sofas are not given a seat or a coffee table: the table has
    fewer of those than of them (bedrooms: 0.69 desks and dressing tables a room, 0.47
    seats), so that every desk seated would take the categories away from the table's."""
    plan = list(plan)
    count = Counter(plan)

    def add(options) -> None:
        options = [c for c in options if rate.get(c, 0.0) > 0]
        if options:
            p = np.array([rate[c] for c in options])
            plan.append(options[rng.choice(len(options), p=p / p.sum())])

    if count['coffee table'] and not any(count[c] for c in groups.LOUNGE_SEATS):
        add(groups.LOUNGE_SEATS)
    # Dining seats come with their table (an island's with the island), as many a table as
    # the table's rates give: a seat without one is not drawn at all.
    for seat, surface in (('dining chair', 'dining table'), ('bar stool', 'kitchen island')):
        if rate.get(seat, 0.0) and rate.get(surface, 0.0):
            per = rate[seat] / rate[surface]
            plan = [c for c in plan if c != seat]
            for _ in range(count[surface]):
                plan += [seat] * max(1, draw_count(per, rng))
    if room_type == 'bedroom' and count['double bed'] and not count['stand']:
        add(('stand',))
    drop = {'bidet'} if not count['toilet'] else set()
    if not count['tv stand'] and not count['desk']:
        drop.add('loudspeaker')
    return [c for c in plan if c not in drop]


def pick_variant(category: str, rng: np.random.Generator,
                 exclude: set[str] = frozenset()) -> ModelVariant | None:
    pool = [v for v in catalog.variants(category) if v.model_id not in exclude]
    return pool[rng.integers(len(pool))] if pool else None


# ---- placement rules of first-tier categories ------------------------------------------
Rule = Callable[[Layout, ModelVariant], 'PlacedObject | None']


def _first(*attempts):
    for attempt in attempts:
        obj = attempt()
        if obj is not None:
            return obj
    return None


def _unseated(lay: Layout, categories) -> list[PlacedObject]:
    return [o for o in lay.first_tier(*categories) if o.id not in lay.seated]


def _seat_at(lay: Layout, v: ModelVariant, anchors, distance=(0.02, 0.2),
             jitter: float = 0.06) -> PlacedObject | None:
    for anchor in _unseated(lay, anchors):
        lateral = lay.rng.uniform(-0.15, 0.15) * anchor.width
        obj = lay.facing(anchor, v, lay.rng.uniform(*distance), lateral, yaw_jitter=jitter)
        if obj is not None:
            lay.seated.add(anchor.id)
            return obj
    return None


def _beside_any(lay: Layout, v: ModelVariant, anchors, gap=(0.02, 0.1)) -> PlacedObject | None:
    options = lay.first_tier(*anchors)
    lay.rng.shuffle(options)
    for anchor in options:
        for side in lay.rng.permutation([-1, 1]):
            obj = lay.beside(anchor, v, int(side), lay.rng.uniform(*gap))
            if obj is not None:
                return obj
    return None


def _ahead_of_any(lay, v, anchors, distance, lateral_sd: float = 0.0):
    for anchor in lay.first_tier(*anchors):
        gap = lay.rng.uniform(*distance)
        lateral = lay.rng.normal(0, lateral_sd) if lateral_sd else 0.0
        obj = lay.ahead(anchor, v, gap, lateral)
        if obj is not None:
            return obj
    return None



def _rule_main_bed(lay, v):
    return _first(lambda: lay.against_wall(v, 'centre'), lambda: lay.against_wall(v, 'any'))


def _rule_corner_bed(lay, v):
    return _first(lambda: lay.against_wall(v, 'corner'), lambda: lay.against_wall(v, 'any'))


def _rule_wall(lay, v):
    return lay.against_wall(v, 'any')


def _rule_wall_corner(lay, v):
    return _first(lambda: lay.against_wall(v, 'corner'), lambda: lay.against_wall(v, 'any'))


def _rule_stand(lay, v):
    # In a bedroom a nightstand stands at the head of a bed or not at all; double beds are
    # served first, those without one before those with one. Elsewhere it is a side table.
    if lay.room.room_type != 'bedroom':
        return lay.against_wall(v, 'any')
    beds = lay.first_tier('double bed', 'single bed', 'bunker bed')
    served = {s.id: _stands_at(lay, s) for s in beds}
    beds.sort(key=lambda b: (served[b.id], b.category != 'double bed'))
    for bed in beds:
        for side in lay.rng.permutation([-1, 1]):
            obj = lay.beside(bed, v, int(side), lay.rng.uniform(0.02, 0.06))
            if obj is not None:
                return obj
    return None


def _stands_at(lay: Layout, bed: PlacedObject) -> int:
    return sum(1 for s in lay.first_tier('stand') if groups.at_head_of(s, bed))


def _rule_tv_stand(lay, v):
    def across():
        viewers = lay.first_tier('sofa', 'double bed', 'single bed', 'daybed')
        for viewer in viewers:
            obj = lay.opposite(viewer, v)
            if obj is not None:
                return obj
        return None
    return _first(across, lambda: lay.against_wall(v, 'any'))


def _rule_coffee_table(lay, v):
    return _first(lambda: _ahead_of_any(lay, v, ('sofa', 'daybed'), (0.35, 0.5), 0.05),
                  lambda: lay.free(v, tries=20))


def _rule_office_chair(lay, v):
    # Only at a desk: an office chair alone in the middle of a room reads as clutter.
    return _first(lambda: _seat_at(lay, v, ('desk',)),
                  lambda: _seat_at(lay, v, ('dressing table',)))


def _rule_chair(lay, v):
    def at_table_end():
        for table in lay.first_tier('coffee table'):
            for side in lay.rng.permutation([-1, 1]):
                obj = lay.at_side_facing(table, v, int(side), lay.rng.uniform(0.3, 0.5), 0.1)
                if obj is not None:
                    return obj
        return None
    # A chair is placed to be sat at a table, never lined along a wall.
    return _first(lambda: _seat_at(lay, v, SEATED_BY), at_table_end)


def _rule_stool(lay, v):
    return _first(lambda: _seat_at(lay, v, ('dressing table', 'piano', 'desk')),
                  lambda: lay.against_wall(v, 'any'))



def _rule_bench(lay, v):
    return _first(lambda: _ahead_of_any(lay, v, ('double bed', 'single bed'), (0.03, 0.15)),
                  lambda: _seat_at(lay, v, ('piano',)),
                  lambda: lay.against_wall(v, 'any'))


def _rule_ottoman(lay, v):
    return _first(
        lambda: _ahead_of_any(lay, v, ('double bed', 'single bed', 'daybed'), (0.05, 0.2)),
        lambda: _ahead_of_any(lay, v, ('sofa chair', 'armchair', 'sofa'), (0.1, 0.3)),
        lambda: lay.against_wall(v, 'any'))


def _rule_easy_chair(lay, v):
    def at_table():
        # Coffee tables nobody sits at first: each needs its seating.
        tables = sorted(lay.first_tier('coffee table'), key=lambda t: _has_seating(lay, t))
        for table in tables:
            for side in lay.rng.permutation([-1, 1]):
                obj = lay.at_side_facing(table, v, int(side), lay.rng.uniform(0.2, 0.45),
                                         yaw_jitter=0.04)
                if obj is not None:
                    return obj
        return None
    # Square to the walls: a seat turned across a corner reads as left askew.
    return _first(at_table, lambda: lay.in_corner(v, diagonal=False),
                  lambda: lay.against_wall(v, 'any', yaw_jitter=0.04))


def _has_seating(lay: Layout, table: PlacedObject) -> bool:
    return any(groups.lounges_at(s, table) for s in lay.first_tier(*groups.LOUNGE_SEATS))


def _rule_floor_lamp(lay, v):
    return _first(lambda: _beside_any(lay, v, ('sofa', 'sofa chair', 'armchair', 'double bed',
                                               'desk')),
                  lambda: lay.in_corner(v, diagonal=False))


def _rule_loudspeaker(lay, v):
    # Speakers flank what they play: a TV stand, else a desk's computer, or nothing.
    return _first(lambda: _beside_any(lay, v, ('tv stand',), (0.05, 0.2)),
                  lambda: _beside_any(lay, v, ('desk',), (0.05, 0.2)))


def _rule_corner_item(lay, v):
    return _first(lambda: lay.in_corner(v, diagonal=False), lambda: lay.against_wall(v, 'any'))


def _rule_bidet(lay, v):
    # On the toilet's plumbing wall, beside it, or not at all.
    return _beside_any(lay, v, ('toilet',), (0.15, 0.3))


def _rule_bath(lay, v):
    # A bath fills a corner, or the room has none.
    return lay.against_wall(v, 'corner')


def _rule_shower(lay, v):
    return lay.in_corner(v, diagonal=False)


def _rule_trash_can(lay, v):
    return _first(lambda: _beside_any(lay, v, ('toilet', 'sink', 'desk'), (0.05, 0.15)),
                  lambda: lay.in_corner(v, diagonal=False))


def _rule_sofa(lay, v):
    return _first(lambda: lay.against_wall(v, 'centre'), lambda: lay.against_wall(v, 'any'),
                  lambda: lay.free(v, tries=16))


def _rule_kitchen_sink(lay, v):
    # Under a window where there is one, as kitchens are planned; else on the longest wall.
    def under_window():
        for window in lay.rng.permutation(len(lay.room.windows)):
            w = lay.room.windows[int(window)]
            wall = min(lay.room.walls, key=lambda wl: wl.distance_to(w.position))
            off = wall.offset_of(w.position)
            if not v.width / 2 <= off <= wall.length - v.width / 2:
                continue
            xy = wall.point_at(off) + wall.normal * (v.depth / 2 + 0.01)
            obj = lay.try_place(v, xy, wall.inward_yaw)
            if obj is not None:
                return obj
        return None
    return _first(under_window, lambda: lay.against_wall(v, 'any'))


def _run_units(lay):
    return lay.first_tier(*RUN_UNITS)


def _in_triangle(lay, obj) -> bool:
    """Whether ``obj`` (a sink, stove or fridge) keeps the work triangle possible: within a
    leg's reach of those of the three already placed."""
    return _triangle_spot(lay, obj.category, obj.position[:2])


def _triangle_spot(lay, category: str, xy) -> bool:
    lo, hi = TRIANGLE_LEG
    others = lay.first_tier(*(c for c in TRIANGLE if c != category))
    return all(lo <= math.dist(xy, o.position[:2]) <= hi for o in others)


def _on_wall_where(lay, v, ok, step: float = 0.1):
    """Back to a wall where ``ok(xy)`` holds for the centre: the walls scanned in steps."""
    for wall in lay.walls_by_length(v.width + 0.02):
        lo, hi = v.width / 2 + 0.005, wall.length - v.width / 2 - 0.005
        offsets = np.arange(lo, hi + 1e-9, step)
        lay.rng.shuffle(offsets)
        for off in offsets:
            xy = wall.point_at(off) + wall.normal * (v.depth / 2 + 0.005)
            if ok(xy):
                obj = lay.try_place(v, xy, wall.inward_yaw)
                if obj is not None:
                    return obj
    return None


def _along_run(lay, v, anchors, gap=(0.0, 0.01), keep=None):
    """Beside one of ``anchors``, backs in one line (the next unit of a run), where ``keep``
    (a test of the placed piece) holds."""
    options = lay.first_tier(*anchors)
    lay.rng.shuffle(options)
    for anchor in options:
        for side in lay.rng.permutation([-1, 1]):
            obj = lay.beside(anchor, v, int(side), lay.rng.uniform(*gap))
            if obj is None:
                continue
            if keep is None or keep(obj):
                return obj
            lay.remove(obj)
    return None


def _rule_counter(lay, v):
    return _first(lambda: _along_run(lay, v, RUN_UNITS),
                  lambda: lay.against_wall(v, 'corner'), lambda: lay.against_wall(v, 'any'))


def _rule_triangle_unit(lay, v):
    # A stove along the run with a counter between it and the sink where one stands; a
    # fridge at a run's end; both within the triangle's legs of what is placed.
    def kept(obj):
        return _in_triangle(lay, obj)

    def on_wall():
        return _on_wall_where(lay, v, lambda xy: _triangle_spot(lay, v.category, xy))
    if v.category == 'stove':
        # a counter's width from the sink (its landing), the counter to come between
        return _first(lambda: _along_run(lay, v, ('kitchen sink',), (0.3, 0.9), kept),
                      lambda: _along_run(lay, v, ('counter',), (0.0, 0.02), kept), on_wall)
    return _first(lambda: _along_run(lay, v, RUN_UNITS, (0.3, 0.9), kept), on_wall)


def _rule_dishwasher(lay, v):
    return _first(lambda: _along_run(lay, v, ('kitchen sink',)),
                  lambda: _along_run(lay, v, ('counter',)))


def _rule_island(lay, v):
    return lay.free(v, tries=24)


def _rule_dining_table(lay, v):
    # In the middle of the open floor (a dining room's, or what a kitchen's units leave),
    # its length along that floor's.
    for part in lay.open_floor(min(v.width, v.depth) / 2)[:2]:
        x0, y0, x1, y1 = part.bounds
        along = math.pi / 2 if (x1 - x0) > (y1 - y0) else 0.0   # width (local y) along it
        c = part.centroid if part.contains(part.centroid) else part.representative_point()
        for yaw in (along, along + math.pi / 2):
            obj = lay.try_place(v, (c.x, c.y), yaw)
            if obj is not None:
                return obj
    return lay.free(v, tries=24)


def _seat_slots(table, seat, gap):
    """Where seats go around ``table`` in its frame: along both long sides, then the ends."""
    d, w = table.depth / 2, table.width / 2
    x = d + gap + seat.depth / 2
    n = max(1, int(table.width // 0.6))
    ys = [(k + 0.5) * table.width / n - w for k in range(n)]
    slots = [((x, y), math.pi) for y in ys] + [((-x, y), 0.0) for y in ys]
    if table.depth >= 0.7:
        e = w + gap + seat.depth / 2
        slots += [((0.0, e), -math.pi / 2), ((0.0, -e), math.pi / 2)]
    return slots


def _rule_dining_seat(lay, v):
    surfaces = ('kitchen island',) if v.category == 'bar stool' else ('dining table',)
    for table in lay.first_tier(*surfaces):
        slots = _seat_slots(table, v, lay.rng.uniform(0.02, 0.1))
        if v.category == 'bar stool':      # at the island's front overhang only
            slots = [s for s in slots if s[1] == math.pi]
        for (x, y), yaw in slots:
            obj = lay.relative(table, v, (x, y), yaw)
            if obj is not None:
                return obj
    return None


def _hall_piece(rule):
    # In a hallway a piece stays only where the walking path stays 0.9 m wide.
    def placed(lay, v):
        obj = rule(lay, v)
        if obj is not None and lay.room.room_type == 'hallway' and \
                not home.hallway_path(lay.scene)[0] and len(lay.room.doors) > 1:
            lay.remove(obj)
            return None
        return obj
    return placed


RULES: dict[str, Rule] = {
    'double bed': _rule_main_bed, 'single bed': _rule_corner_bed,
    'bunker bed': _rule_corner_bed, 'baby bed': _rule_corner_bed, 'daybed': _rule_wall,
    'wardrobe': _rule_wall_corner, 'stand': _rule_stand, 'tv stand': _rule_tv_stand,
    'coffee table': _rule_coffee_table, 'office chair': _rule_office_chair,
    'straight chair': _rule_chair, 'chair': _rule_chair, 'stool': _rule_stool,
    'bench chair': _rule_bench, 'ottoman': _rule_ottoman, 'sofa': _rule_sofa,
    'sofa chair': _rule_easy_chair, 'armchair': _rule_easy_chair,
    'floor lamp': _rule_floor_lamp, 'loudspeaker': _rule_loudspeaker,
    'pedestal fan': _rule_corner_item, 'hanger': _rule_corner_item,
    'bidet': _rule_bidet, 'trash can': _rule_trash_can, 'bathtub': _rule_bath,
    'shower': _rule_shower, 'shelving': _rule_wall_corner,
    'kitchen sink': _rule_kitchen_sink, 'counter': _rule_counter,
    'stove': _rule_triangle_unit, 'fridge': _rule_triangle_unit,
    'dishwasher': _rule_dishwasher, 'kitchen island': _rule_island,
    'dining table': _rule_dining_table, 'dining chair': _rule_dining_seat,
    'bar stool': _rule_dining_seat, 'sideboard': _rule_wall,
    'coat rack': _hall_piece(_rule_wall), 'shoe bench': _hall_piece(_rule_wall),
    'console table': _hall_piece(_rule_wall),
}


def place_first_tier(lay: Layout, category: str, variant: ModelVariant) -> PlacedObject | None:
    """Place one object by its category's rule, trying up to two smaller models if the
    chosen one does not fit."""
    rule = RULES.get(category, _rule_wall if CATEGORIES[category].against_wall
                     else _rule_corner_item)
    tried = {variant.model_id}
    current = variant
    for _ in range(3):
        obj = rule(lay, current)
        if obj is not None:
            return obj
        smaller = [v for v in catalog.variants(category)
                   if v.model_id not in tried and v.width <= current.width]
        if not smaller:
            return None
        current = smaller[lay.rng.integers(len(smaller))]
        tried.add(current.model_id)
    return None


def place_second_tier(lay: Layout, category: str, variant: ModelVariant) -> PlacedObject | None:
    """Put a second-tier object on a parent that can support it, preferred ones first."""
    spec = paper_spec(lay.room.room_type)
    weights = dict(spec.info(category).parents)
    parents = [p for p in lay.first_tier(*spec.supports(category))
               if not weights or p.category in weights]
    if category in ONE_PER_PARENT:
        parents = [p for p in parents
                   if not any(c.category == category for c in lay.scene.children_of(p.id))]
    if not parents:
        return None
    w = np.array([weights.get(p.category, 1.0) for p in parents])
    order = lay.rng.choice(len(parents), size=len(parents), replace=False, p=w / w.sum())
    pool = sorted(catalog.variants(category), key=lambda m: m.width * m.depth)
    for k in order:
        parent = parents[k]
        candidates = [variant] + [m for m in pool if m.model_id != variant.model_id
                                  and m.width * m.depth < variant.width * variant.depth]
        for m in candidates[:3]:
            obj = lay.on_top(parent, m, free_yaw=category in SYMMETRIC)
            if obj is not None:
                return obj
    return None


# ---- what a designer takes out again ------------------------------------------------------
def _belongs(lay: Layout, obj: PlacedObject) -> bool:
    """Whether a piece that only makes sense in a group is in it."""
    if obj.category == 'stand' and lay.room.room_type == 'bedroom':
        return any(groups.at_head_of(obj, b) for b in lay.first_tier(*groups.BEDS_WITH_HEAD))
    if obj.category in groups.CHAIRS:
        return any(groups.seated_at(obj, t) for t in lay.first_tier(*groups.TABLES))
    if obj.category == 'coffee table':
        return _has_seating(lay, obj)
    if obj.category == 'bidet':
        return any(groups.beside_toilet(obj, t) for t in lay.first_tier('toilet'))
    if obj.category in home.DINING_SEATS:
        return any(groups.seated_at(obj, t) for t in lay.first_tier(*home.DINING_SURFACES))
    return True


def _complete(lay: Layout) -> None:
    """Give a double bed that did not get a nightstand from the plan one, where it fits."""
    if lay.room.room_type != 'bedroom':
        return
    for bed in lay.first_tier('double bed'):
        if not _stands_at(lay, bed):
            v = pick_variant('stand', lay.rng)
            for side in lay.rng.permutation([-1, 1]):
                if v is not None and lay.beside(bed, v, int(side), 0.03) is not None:
                    break


def tidy(lay: Layout) -> None:
    """Give double beds their nightstand (``_complete``), take out the first-tier
    pieces a robot driving in from a door cannot reach (see
    ``design_rules.access.front_reachable``), then, until none is left, those outside the
    group they belong to (a chair at no table, a coffee table nobody sits at)."""
    _complete(lay)
    for obj in access.unreachable(lay.scene):
        lay.remove(obj)
    while True:
        loners = [o for o in lay.first_tier() if not _belongs(lay, o)]
        if not loners:
            return
        for obj in loners:
            lay.remove(obj)
