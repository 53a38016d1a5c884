"""Physical plausibility of rooms, per room, with the definitions of ``geometry.py`` (the
same checks the corpus is held to and insertion rejects by).

Per room: the fraction of first-tier object pairs that collide, of objects off the floor,
of doors whose clear zone is entered, of second-tier objects under-supported, and whether a
0.4 m robot can drive between all doors. A fraction whose denominator is zero in a room
(fewer than two first-tier objects, no doors, no second-tier objects) is left out of that
metric's mean.
"""
from __future__ import annotations

import math
from typing import Iterable

import numpy as np

from ..allowance import STRICT, Allowance
from ..geometry import check_scene
from ..scene import Scene

METRICS = ('colliding_pairs', 'off_floor', 'blocked_doors', 'under_supported',
           'doors_connected', 'valid', 'against_wall', 'near_wall')
# Not a validity check but the tell of a coarse location grid: training rooms put wall
# furniture 0-2 cm from the wall and almost nothing a few centimetres further.
AGAINST_WALL = 0.02
NEAR_WALL = 0.15


def _fraction(count: int, total: int) -> float:
    return count / total if total else math.nan


def room_metrics(scene: Scene, allowance: Allowance = STRICT) -> dict[str, float]:
    """The plausibility metrics of one room (NaN where undefined), with what ``allowance``
    lets it do."""
    r = check_scene(scene, allowance)
    first = len(scene.first_tier)
    ring = scene.room.polygon.exterior
    gaps = [ring.distance(o.footprint()) for o in scene.first_tier]
    return {
        'against_wall': _fraction(sum(g <= AGAINST_WALL for g in gaps), first),
        'near_wall': _fraction(sum(AGAINST_WALL < g < NEAR_WALL for g in gaps), first),
        'colliding_pairs': _fraction(len(r.collisions), first * (first - 1) // 2),
        'off_floor': _fraction(len(r.off_floor), len(scene.objects)),
        'blocked_doors': _fraction(len(r.blocked_doors), len(scene.room.doors)),
        'under_supported': _fraction(len(r.under_supported), len(scene.second_tier)),
        'doors_connected': float(r.doors_connected),
        'valid': float(r.ok),
    }


def summarize(rows: Iterable[dict[str, float]]) -> dict[str, float]:
    """Mean of every metric over the rooms where it is defined, and the room count."""
    rows = list(rows)
    out: dict[str, float] = {'rooms': len(rows)}
    for m in METRICS:
        values = np.array([r[m] for r in rows], dtype=float)
        values = values[~np.isnan(values)]
        out[m] = float(values.mean()) if len(values) else 0.0
    return out


def evaluate(scenes: Iterable[Scene], allowance: Allowance = STRICT) -> dict[str, float]:
    return summarize(room_metrics(s, allowance) for s in scenes)
