"""Importers of real scene data sets (3D-FRONT, SUNCG, ProcTHOR) into our Scene JSON, one
room per scene, with a report of what was kept and dropped, and the data-set description.

Modules, one job each:

* ``frames``: the data sets' frames -> REP-103 (the y-up conversions, the mirror, yaw);
* ``front3d``, ``suncg``, ``procthor``: one reader per format, file -> ``records.RawRoom``;
* ``models``: the formats' model tables (categories, asset boxes, model meshes);
* ``assemble``: ``RawRoom`` -> a schema-valid Scene dict (filters, openings, supports);
* ``config``: the filters (``ImportConfig``) and the room-type mapping
  (``room_types.yaml``, shipped with the package);
* ``report``: what was kept and dropped, and why (``report.txt``, ``report.json``);
* ``description``: ``dataset.yaml``, what the imported rooms hold per room type;
* ``importer``: ``import_dataset``, all of the above for a list of files or folders.

Command line: ``scene-synth import {3dfront,suncg,procthor} INPUT... --out DIR``.
"""
from ..lazy import lazy_names

__all__ = ['FORMATS', 'ImportConfig', 'ImportResult', 'import_dataset', 'load_room_types']

# Loaded on first use: the command line reads ``config`` for its defaults when it builds
# its parser, and should not pay for shapely and the readers then.
_LAZY = {'FORMATS': 'config', 'ImportConfig': 'config', 'load_room_types': 'config',
         'ImportResult': 'importer', 'import_dataset': 'importer'}


__getattr__ = lazy_names(__name__, _LAZY)
