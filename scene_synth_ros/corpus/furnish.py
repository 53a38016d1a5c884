"""Interior-design rules that furnish a room shell.

A room is furnished in two steps. First a *plan*: which objects the room gets, drawn so
that every category's mean count per room is the paper's table frequency (times a
calibration factor that makes up for objects that did not fit; see ``calibration``). Then
each object is placed by the rule of its category, anchors first: beds and sofas go against
walls, nightstands beside beds, chairs at desks, coffee tables before sofas, TV stands across
from what faces them, and so on; second-tier objects go on a valid supporting surface.
"""
from __future__ import annotations

import math
from typing import Callable

import numpy as np

from .. import catalog
from ..catalog import ModelVariant
from ..categories import CATEGORIES, room_spec
from ..scene import PlacedObject
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
}

# Categories that usually come in pairs (a nightstand each side, a speaker each side).
PAIRED = {'stand', 'loudspeaker'}

# The beds of a bedroom: one main bed, sometimes a second one.
MAIN_BEDS = ('double bed', 'single bed', 'bunker bed', 'daybed')

# Where second-tier objects prefer to stand; unlisted parents that can support the child
# get weight 1.
PARENT_WEIGHT = {
    'table lamp': {'stand': 8, 'desk': 2, 'dresser': 1.5, 'dressing table': 1.5},
    'television': {'tv stand': 12, 'dresser': 2, 'desk': 0.5},
    'console': {'tv stand': 10},
    'laptop': {'desk': 10, 'dressing table': 1, 'coffee table': 2},
    'book': {'shelving': 4, 'desk': 3, 'stand': 2},
    'plant': {'shelving': 2, 'desk': 2, 'tv stand': 2, 'sink': 3, 'coffee table': 2},
    'vase': {'coffee table': 3, 'dresser': 2, 'tv stand': 2, 'fireplace': 2},
    'toy': {'shelving': 3, 'bathtub': 4, 'single bed': 2},
    'fishbowl': {'dresser': 2, 'shelving': 2, 'desk': 2},
    'cup': {'coffee table': 5, 'desk': 3},
    'glass': {'coffee table': 5},
    'bottle': {'coffee table': 5},
    'fruit bowl': {'coffee table': 5},
}
ONE_PER_PARENT = {'television', 'console', 'laptop', 'table lamp', 'fishbowl', 'fruit bowl'}
SYMMETRIC = {'plant', 'vase', 'cup', 'glass', 'bottle', 'fruit bowl', 'fishbowl', 'toy'}
SEATED_BY = ('desk', 'dressing table', 'piano')


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
    spec = room_spec(room_type)
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
    first = sorted((n for n in plan if CATEGORIES[n].tier == 'first'),
                   key=lambda n: (PHASE.get(n, 1), -spec[n].importance))
    second = [n for n in plan if CATEGORIES[n].tier == 'second']
    return first + second


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
             jitter: float = 0.12) -> PlacedObject | None:
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
    # A nightstand on a free side of a bed, else any wall.
    return _first(lambda: _beside_any(lay, v, ('double bed', 'single bed'), (0.02, 0.06)),
                  lambda: lay.against_wall(v, 'any'))


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
    return _first(lambda: _seat_at(lay, v, SEATED_BY), at_table_end,
                  lambda: lay.against_wall(v, 'any', yaw_jitter=0.08))


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
        for table in lay.first_tier('coffee table'):
            for side in lay.rng.permutation([-1, 1]):
                obj = lay.at_side_facing(table, v, int(side), lay.rng.uniform(0.2, 0.45),
                                         yaw_jitter=0.15)
                if obj is not None:
                    return obj
        return None
    return _first(at_table, lambda: lay.in_corner(v, diagonal=True, yaw_jitter=0.15),
                  lambda: lay.against_wall(v, 'any', yaw_jitter=0.1))


def _rule_floor_lamp(lay, v):
    return _first(lambda: _beside_any(lay, v, ('sofa', 'sofa chair', 'armchair', 'double bed',
                                               'desk')),
                  lambda: lay.in_corner(v, diagonal=False))


def _rule_loudspeaker(lay, v):
    return _first(lambda: _beside_any(lay, v, ('tv stand',), (0.05, 0.2)),
                  lambda: lay.in_corner(v, diagonal=False))


def _rule_corner_item(lay, v):
    return _first(lambda: lay.in_corner(v, diagonal=False), lambda: lay.against_wall(v, 'any'))


def _rule_bidet(lay, v):
    return _first(lambda: _beside_any(lay, v, ('toilet',), (0.15, 0.3)),
                  lambda: lay.against_wall(v, 'any'))


def _rule_trash_can(lay, v):
    return _first(lambda: _beside_any(lay, v, ('toilet', 'sink', 'desk'), (0.05, 0.15)),
                  lambda: lay.in_corner(v, diagonal=False))


def _rule_sofa(lay, v):
    return _first(lambda: lay.against_wall(v, 'centre'), lambda: lay.against_wall(v, 'any'),
                  lambda: lay.free(v, tries=16))


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
    'bidet': _rule_bidet, 'trash can': _rule_trash_can, 'bathtub': _rule_wall_corner,
    'shower': _rule_corner_item, 'shelving': _rule_wall_corner,
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
    spec = room_spec(lay.room.room_type)
    parents = [p for p in lay.first_tier(*spec.supports(category))]
    if category in ONE_PER_PARENT:
        parents = [p for p in parents
                   if not any(c.category == category for c in lay.scene.children_of(p.id))]
    if not parents:
        return None
    weights = PARENT_WEIGHT.get(category, {})
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
