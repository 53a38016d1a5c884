"""Low-poly meshes for the catalog models, their export, and whole scenes as trimesh scenes.

Every model is put together by its category's builder from primitives in the package's
object frame (front towards +x, width along y, depth along x, origin at the centre of the
footprint on the floor) and mapped onto the variant's box, so the axis-aligned bounds of every
mesh are exactly ``x in [-depth/2, depth/2]``, ``y in [-width/2, width/2]``,
``z in [0, height]``. Each part carries a material name (see ``MATERIALS``). Coordinates are
the package's (REP-103): metres, z up.

The modules: ``materials`` (the palette), ``builder`` (primitives, ``Part``, ``Builder``, the
``builds`` declaration), ``furniture`` (one module of builders per family of categories),
``registry`` (category -> builder, ``build_parts``, ``build_mesh``), ``export`` (GLB and
OBJ files), ``assembly`` (whole scenes) and ``preview`` (pictures for people). This package
re-exports the public API so callers need not know the layout.
"""
from __future__ import annotations

from .assembly import object_transform, scene_mesh, variant_for
from .builder import Builder, Part, builds
from .export import export_catalog, export_model, material_meshes, mesh_path, model_scene
from .materials import BOOK_COVERS, MATERIALS, Material
from .preview import render_image, render_preview, save_contact_sheet
from .registry import BUILDERS, build_mesh, build_parts, builder_for

__all__ = [
    'BOOK_COVERS', 'BUILDERS', 'MATERIALS', 'Builder', 'Material', 'Part', 'build_mesh',
    'build_parts', 'builder_for', 'builds', 'export_catalog', 'export_model',
    'material_meshes', 'mesh_path', 'model_scene', 'object_transform', 'render_image',
    'render_preview', 'save_contact_sheet', 'scene_mesh', 'variant_for',
]
