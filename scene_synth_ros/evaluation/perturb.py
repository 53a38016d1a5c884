"""The paper's perturbed-corpus baseline: every object moved by Gaussian noise whose
standard deviation is a fraction of its bounding box.

The noise is drawn in the object's own frame (depth along its facing, width across it) and
turned into the room's axes; heights and orientations are kept. Second-tier objects move
independently of their parents, as in the paper ("every object is perturbed").
"""
from __future__ import annotations

from dataclasses import replace
import math

import numpy as np

from ..scene import Scene


def perturb_scene(scene: Scene, scale: float, rng: np.random.Generator) -> Scene:
    """A copy of ``scene`` with each object's position moved by N(0, (scale * depth)^2)
    along its facing and N(0, (scale * width)^2) across it."""
    if scale < 0:
        raise ValueError(f'a perturbation scale must be non-negative, got {scale}')
    objects = []
    for o in scene.objects:
        along, across = rng.normal(0.0, 1.0, 2) * scale * np.array([o.depth, o.width])
        c, s = math.cos(o.yaw), math.sin(o.yaw)
        x = o.position[0] + c * along - s * across
        y = o.position[1] + s * along + c * across
        objects.append(replace(o, position=(float(x), float(y), o.position[2])))
    meta = dict(scene.meta, perturbation=scale)
    return Scene(scene.room, objects, meta)


def perturbation_key(level: float) -> str:
    """The results' name of the baseline perturbed by ``level`` (``perturbed_5`` for 0.05)."""
    return f'perturbed_{100 * level:g}'


def perturb_all(scenes, scale: float, seed) -> list[Scene]:
    """Every scene perturbed with one generator seeded by ``seed`` (an int or a sequence)."""
    rng = np.random.default_rng(seed)
    return [perturb_scene(s, scale, rng) for s in scenes]
