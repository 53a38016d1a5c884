"""Which builder draws which category, and the parts and meshes that come out of it.

The lookup table is built once, when this module is imported, from the ``@builds``
declarations of every furniture module; importing them here (rather than relying on whoever
imported them first) means a lookup can never miss a builder. A category without a builder
gets a plain labelled block, so a scene with an unknown category still renders.
``build_parts`` and ``build_mesh`` are the entry points the exporters, scene assembly and
previews use.
"""
from __future__ import annotations

from functools import lru_cache
from types import ModuleType

import numpy as np
import trimesh

from ..catalog import ModelVariant, UserModel
from .builder import Builder, BuildFn, Part
from .furniture import (
    bathroom,
    beds,
    case_furniture,
    dining_and_hall,
    kitchen,
    lamps_electronics_appliances,
    living_room_and_office,
    seating,
    small_things,
    tables_and_desks,
)
from .materials import MATERIALS
from .user import user_parts

FURNITURE_MODULES = (beds, case_furniture, tables_and_desks, seating,
                     lamps_electronics_appliances, bathroom, living_room_and_office,
                     small_things, kitchen, dining_and_hall)


def _collect(modules: tuple[ModuleType, ...]) -> dict[str, BuildFn]:
    table: dict[str, BuildFn] = {}
    for module in modules:
        for fn in vars(module).values():
            for category in getattr(fn, 'builds_categories', ()):
                if table.setdefault(category, fn) is not fn:
                    raise ValueError(f'two builders for {category!r}: '
                                     f'{table[category].__qualname__} and {fn.__qualname__}')
    return table


BUILDERS: dict[str, BuildFn] = _collect(FURNITURE_MODULES)


def plain_box(b: Builder):
    """Fallback for a category without a builder: a grey block with a darker top."""
    b.box('body', 'paint_grey', b.x0, b.x1, b.y0, b.y1, 0.0, b.H * 0.9)
    b.box('top', 'plastic_black', b.x0, b.x1, b.y0, b.y1, b.H * 0.9, b.H)
    b.box('front_mark', 'plastic_white', b.x1 - 0.01, b.x1, -b.W * 0.1, b.W * 0.1, b.H * 0.4,
          b.H * 0.6)


def builder_for(category: str) -> BuildFn:
    """The function that draws ``category`` (``plain_box`` for an unknown one)."""
    return BUILDERS.get(category, plain_box)


@lru_cache(maxsize=1024)
def build_parts(variant: ModelVariant) -> tuple[Part, ...]:
    """The named parts of ``variant``'s mesh, already fitted to its box (read-only arrays)."""
    if min(variant.size) <= 0:
        raise ValueError(f'{variant.model_id}: sizes must be positive, got {variant.size}')
    if isinstance(variant, UserModel):          # the user's mesh, not a builder's sketch
        return user_parts(variant)
    b = Builder(variant)
    builder_for(variant.category)(b)
    return b.finish()


def build_mesh(variant: ModelVariant) -> trimesh.Trimesh:
    """One mesh for ``variant`` with per-vertex colours; bounds are exactly its box
    (x: depth, y: width, z: 0..height). ``metadata['parts']`` lists the part names, one per
    connected body, in order."""
    parts = build_parts(variant)
    verts, faces, colours = [], [], []
    offset = 0
    for p in parts:
        verts.append(p.vertices)
        faces.append(p.faces + offset)
        colours.append(np.tile(MATERIALS[p.material].rgba, (len(p.vertices), 1)))
        offset += len(p.vertices)
    mesh = trimesh.Trimesh(np.vstack(verts), np.vstack(faces), process=False,
                           vertex_colors=np.vstack(colours).astype(np.uint8))
    mesh.metadata['model_id'] = variant.model_id
    mesh.metadata['category'] = variant.category
    mesh.metadata['parts'] = [p.name for p in parts]
    return mesh
