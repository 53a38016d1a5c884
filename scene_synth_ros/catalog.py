"""The model catalog: for every category a few 3D model variants of fixed dimensions.

The procedural catalog (the default): variants span the category's size ranges on a Latin
hypercube, so that small, large, low, tall, narrow and deep models all exist. Their
dimensions are a pure function of the category's ranges (no randomness at run time), which
keeps model ids stable across machines. A room type a data set's vocabulary defines
(``categories.Vocabulary``) has variants of its own categories, spanning the data's size
ranges, with ids that name the room type (``kitchen__fridge_03``); the functions that take
a ``vocabulary`` know them (default: the paper's table alone). Meshes are built
on demand by ``scene_synth_ros.meshes``. The module-level functions (``variants``, ``get``,
``nearest``, ``ranked``) are this catalog's.

A ``Catalog`` is the procedural catalog with the user's own models (``UserModel``, measured
by ``scene_synth_ros.user_catalog``) in place of the procedural models of the categories
they cover; a category without a user model keeps the procedural ones. ``load`` gives the
catalog of a file written by ``scene-synth catalog build`` (or the procedural one for None).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Iterable
import zlib

import numpy as np

from .categories import CATEGORIES, PAPER, CategoryInfo, RoomTypeSpec, Vocabulary
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


DATA_SET_MARK = '__'          # between the room type and the category in a data set's ids


def variants(category: str, room_type: str | None = None,
             vocabulary: Vocabulary = PAPER) -> tuple[ModelVariant, ...]:
    """The catalog models of ``category``, from smallest to largest width: those of the
    data set whose ``vocabulary`` defines ``room_type`` if it does, else the paper's
    category."""
    if room_type is not None and vocabulary.defines(room_type):
        spec = vocabulary.spec(room_type)
        return _variants(spec.info(category), _prefix(spec))
    return _variants(CATEGORIES[category], '')


@lru_cache(maxsize=512)
def _variants(info: CategoryInfo, prefix: str) -> tuple[ModelVariant, ...]:
    category = info.name
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
        out.append(ModelVariant(f'{prefix}{slug(category)}_{k:02d}', category, size, k % 3))
    return tuple(out)


@lru_cache(maxsize=None)
def _by_id() -> dict[str, ModelVariant]:
    return {v.model_id: v for c in CATEGORIES for v in variants(c)}


def get(model_id: str, vocabulary: Vocabulary = PAPER) -> ModelVariant:
    """The model of ``model_id``: a paper category's, or one of a room type ``vocabulary``
    defines. ``KeyError`` if neither has it."""
    try:
        return _by_id()[model_id]
    except KeyError:
        pass
    for spec in vocabulary.specs:
        if model_id.startswith(_prefix(spec)):
            v = _data_set_ids(spec).get(model_id)
            if v is not None:
                return v
    raise KeyError(f'unknown model id {model_id[:80]!r}')


def _prefix(spec: RoomTypeSpec) -> str:
    return f'{slug(spec.room_type)}{DATA_SET_MARK}'


@lru_cache(maxsize=16)
def _data_set_ids(spec: RoomTypeSpec) -> dict[str, ModelVariant]:
    """The variants of a data set's room type by id."""
    return {v.model_id: v for name in spec.names for v in _variants(spec.info(name), _prefix(spec))}


def all_variants() -> list[ModelVariant]:
    return list(_by_id().values())


def nearest(category: str, width: float, depth: float,
            candidates: tuple[ModelVariant, ...] | None = None,
            room_type: str | None = None, vocabulary: Vocabulary = PAPER) -> ModelVariant:
    """The variant whose footprint is closest to ``width`` x ``depth`` (relative error, so
    that a 5 cm miss counts more on a cup than on a bed)."""
    pool = candidates if candidates is not None else variants(category, room_type, vocabulary)
    return min(pool, key=lambda v: footprint_distance(v, width, depth))


def footprint_distance(v: ModelVariant, width: float, depth: float) -> float:
    return abs(np.log(v.width / width)) + abs(np.log(v.depth / depth))


def ranked(category: str, width: float, depth: float,
           candidates: tuple[ModelVariant, ...] | None = None,
           room_type: str | None = None, vocabulary: Vocabulary = PAPER
           ) -> list[ModelVariant]:
    """All variants of ``category`` (or ``candidates``) from the best footprint fit to the
    worst."""
    pool = candidates if candidates is not None else variants(category, room_type, vocabulary)
    return sorted(pool, key=lambda v: footprint_distance(v, width, depth))


@dataclass(frozen=True)
class UserModel(ModelVariant):
    """One of the user's models: a mesh file and the transform that puts it in the
    package's object frame (front +x, width along y, z up, footprint centred on the origin,
    standing on z = 0) at its measured ``size``. A copy with another ``size`` (and id) shows
    the same mesh stretched onto that box."""

    source: str = ''                                  # absolute path of the mesh file
    transform: tuple[float, ...] = (1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0,
                                    0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0)  # 4x4, row-major
    # Absolute path of the mesh already in the object frame at ``size`` (binary STL), for
    # RViz, which cannot apply ``transform`` to a mesh resource; '' when the catalog has none.
    marker: str = ''

    @property
    def matrix(self) -> np.ndarray:
        return np.asarray(self.transform, float).reshape(4, 4)


class Catalog:
    """The models synthesis retrieves from and exports show: the user's models for the
    categories they cover, the procedural ones for every other category."""

    def __init__(self, user_models: Iterable[UserModel] = (), source: str | None = None):
        self.source = source                          # the catalog file, if read from one
        self.user: dict[str, UserModel] = {}
        by_category: dict[str, list[UserModel]] = {}
        for m in user_models:
            if m.model_id in self.user:
                raise ValueError(f'two user models with the id {m.model_id!r}')
            self.user[m.model_id] = m
            by_category.setdefault(m.category, []).append(m)
        self._by_category = {c: tuple(sorted(ms, key=lambda m: (m.width, m.model_id)))
                             for c, ms in by_category.items()}

    def __repr__(self) -> str:
        return f'Catalog({len(self.user)} user models, source={self.source!r})'

    @property
    def user_categories(self) -> list[str]:
        """The categories the user's models cover, in the package's category order."""
        return [c for c in CATEGORIES if c in self._by_category]

    def fallback(self, categories: Iterable[str]) -> list[str]:
        """Those of ``categories`` that no user model covers (procedural models there)."""
        return [c for c in categories if c not in self._by_category]

    def variants(self, category: str, room_type: str | None = None,
                 vocabulary: Vocabulary = PAPER) -> tuple[ModelVariant, ...]:
        return self._by_category.get(category) or variants(category, room_type, vocabulary)

    def user_model(self, model_id: str) -> UserModel | None:
        return self.user.get(model_id)

    def get(self, model_id: str, vocabulary: Vocabulary = PAPER) -> ModelVariant:
        """A user model by id, else a procedural one (objects placed before may keep them)."""
        return self.user.get(model_id) or get(model_id, vocabulary)

    def all_variants(self) -> list[ModelVariant]:
        return [v for c in CATEGORIES for v in self.variants(c)]

    def nearest(self, category: str, width: float, depth: float,
                room_type: str | None = None, vocabulary: Vocabulary = PAPER) -> ModelVariant:
        return nearest(category, width, depth, self.variants(category, room_type, vocabulary))

    def ranked(self, category: str, width: float, depth: float,
               room_type: str | None = None, vocabulary: Vocabulary = PAPER
               ) -> list[ModelVariant]:
        return ranked(category, width, depth, self.variants(category, room_type, vocabulary))


PROCEDURAL = Catalog()
