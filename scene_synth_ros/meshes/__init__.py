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
OBJ files), ``shipped`` (the OBJ files installed with the package, which RViz markers refer
to as ``package://`` URIs), ``assembly`` (whole scenes) and ``preview`` (pictures for
people). This package re-exports the public API so callers need not know the layout; each name is
imported from its module when first asked for (PEP 562), so that the node, which reads
the shipped meshes' names for its markers, does not import trimesh to start.
"""
from __future__ import annotations

from ..lazy import lazy_names

# Where each public name is defined.
_MODULES = {name: module for module, defined in (
    ('assembly', ('object_transform', 'scene_mesh', 'variant_for')),
    ('builder', ('Builder', 'Part', 'builds')),
    ('export', ('export_catalog', 'export_model', 'material_meshes', 'mesh_path',
                'model_scene', 'mtl_text', 'obj_text')),
    ('materials', ('BOOK_COVERS', 'MATERIALS', 'Material')),
    ('preview', ('render_image', 'render_preview', 'save_contact_sheet')),
    ('registry', ('BUILDERS', 'build_mesh', 'build_parts', 'builder_for')),
    ('shipped', ('file_uri', 'mesh_scale', 'package_uri', 'shipped_files', 'shipped_name',
                 'shipped_variant', 'user_marker', 'write_shipped_meshes')),
) for name in defined}

__all__ = sorted(_MODULES)


__getattr__ = lazy_names(__name__, _MODULES)
