"""The model catalog: for every category a few 3D model variants of fixed dimensions.

Variants span the category's size ranges on a Latin hypercube, so that small, large, low,
tall, narrow and deep models all exist. Their dimensions are a pure function of the
category's ranges (no randomness at run time), which keeps model ids stable across
machines. Meshes are built on demand by ``scene_synth_ros.meshes``.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
import zlib

import numpy as np

from .categories import CATEGORIES
from .scene import Sized

VARIANTS_PER_CATEGORY = 8


@dataclass(frozen=True)
class ModelVariant(Sized):
    """One catalog model: a category, an id and its fixed dimensions."""

    model_id: str
    category: str
    size: tuple[float, float, float]   # (width, depth, height), as PlacedObject.size
    style: int                         # which of the category's shape styles the mesh uses


def slug(category: str) -> str:
    return category.replace(' ', '_')


@lru_cache(maxsize=None)
def variants(category: str) -> tuple[ModelVariant, ...]:
    """The catalog models of ``category``, from smallest to largest width."""
    info = CATEGORIES[category]
    n = VARIANTS_PER_CATEGORY
    # A per-category permutation pairs widths with depths and heights so that the set
    # covers the box of ranges instead of its diagonal; crc32 keeps it stable everywhere.
    rng = np.random.default_rng(zlib.crc32(category.encode()))
    t_w = (np.arange(n) + 0.5) / n
    t_d = rng.permutation(n)
    t_h = rng.permutation(n)
    out = []
    for k in range(n):
        size = tuple(round(float(lo + (hi - lo) * t), 3) for (lo, hi), t in (
            (info.width, t_w[k]), (info.depth, (t_d[k] + 0.5) / n),
            (info.height, (t_h[k] + 0.5) / n)))
        out.append(ModelVariant(f'{slug(category)}_{k:02d}', category, size, k % 3))
    return tuple(out)


@lru_cache(maxsize=None)
def _by_id() -> dict[str, ModelVariant]:
    return {v.model_id: v for c in CATEGORIES for v in variants(c)}


def get(model_id: str) -> ModelVariant:
    try:
        return _by_id()[model_id]
    except KeyError:
        raise KeyError(f'unknown model id {model_id!r}') from None


def all_variants() -> list[ModelVariant]:
    return list(_by_id().values())


def nearest(category: str, width: float, depth: float,
            candidates: tuple[ModelVariant, ...] | None = None) -> ModelVariant:
    """The variant whose footprint is closest to ``width`` x ``depth`` (relative error, so
    that a 5 cm miss counts more on a cup than on a bed)."""
    pool = candidates if candidates is not None else variants(category)
    return min(pool, key=lambda v: footprint_distance(v, width, depth))


def footprint_distance(v: ModelVariant, width: float, depth: float) -> float:
    return abs(np.log(v.width / width)) + abs(np.log(v.depth / depth))


def ranked(category: str, width: float, depth: float) -> list[ModelVariant]:
    """All variants of ``category`` from the best footprint fit to the worst."""
    return sorted(variants(category), key=lambda v: footprint_distance(v, width, depth))
