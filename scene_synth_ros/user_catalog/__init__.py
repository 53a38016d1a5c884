"""A catalog of the user's own furniture: a folder of meshes (glTF/GLB, OBJ, STL, PLY, OFF:
what trimesh reads) measured into ``catalog.UserModel``s that synthesis retrieves by
footprint and the exports draw, in place of the procedural models of the categories they
cover (``catalog.Catalog``; a category without a user model keeps the procedural ones).

The modules, in the order a build runs them:

- ``sources``: which models a folder offers (a manifest, 3D-FUTURE's ``model_info.json``,
  or a sub-folder per category) as ``spec.ModelSpec``s, with report lines for bad entries;
- ``spec``: one model's file, category, id, up and front axes (``axes``), units and scale,
  with the defaults of its file format (glTF: y up, front +z; others: z up, front +x);
- ``measure``: the mesh read with trimesh, turned into the package's object frame (front
  +x, width along y, z up), its box measured and centred (the offset recorded), and checked:
  unreadable, empty, non-finite, flat or implausibly sized models are report lines;
- ``build``: the whole folder into a ``BuildReport``;
- ``store``: the catalog file (JSON) written and read back, so that using a catalog does
  not read the meshes again, with each model's mesh for RViz markers beside it (an STL
  already in the object frame: ``markers/<id>.stl``);
- ``mesh``: a user model's mesh as the exporters draw it, stretched onto an object's box.

Command line: ``scene-synth catalog build DIR --out CATALOG.json``, then ``--catalog
CATALOG.json`` on ``generate``, ``complete`` and ``export``.
"""
from __future__ import annotations

from ..lazy import lazy_names

# Where each public name is defined; imported when first asked for (PEP 562), so that using a
# catalog file does not import the mesh readers that building one needs.
_MODULES = {'BuildReport': 'build', 'build_catalog': 'build', 'load_catalog': 'store',
            'read_catalog': 'store', 'write_catalog': 'store'}

__all__ = sorted(_MODULES)


__getattr__ = lazy_names(__name__, _MODULES)
