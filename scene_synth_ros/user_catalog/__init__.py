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

from .build import BuildReport, build_catalog
from .store import load_catalog, read_catalog, write_catalog

__all__ = ['BuildReport', 'build_catalog', 'load_catalog', 'read_catalog', 'write_catalog']
