"""The data sets' model tables: which category a model is, and how big it is.

* ``ModelCategories``: model id -> category, read from a CSV with a ``model_id`` column and
  a ``category`` (3D-FUTURE's category mapping) or ``fine_grained_class`` (SUNCG's
  ``ModelCategoryMapping.csv``) column, or from 3D-FUTURE's ``model_info.json`` (a list of
  ``{"model_id", "category", ...}``). SUNCG's ``empty_struct_obj`` column marks the
  architecture (walls, columns, partitions) that is not furniture.
* ``AssetBoxes``: AI2-THOR asset id -> object type and bounding box (x, y, z in the
  asset's own Unity frame), ProcTHOR's asset database reduced to those two fields.
* ``ModelBoxes``: a model folder read with trimesh, for the model's own bounding box
  (3D-FUTURE ``DIR/<jid>/raw_model.obj``; SUNCG ``DIR/object/<id>/<id>.obj``).
"""
from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import lru_cache
import json
from pathlib import Path

import numpy as np

from ..errors import DatasetError
from ..files import read_json

CATEGORY_COLUMNS = ('category', 'fine_grained_class')


@dataclass(frozen=True)
class ModelCategory:
    category: str            # as the table writes it ('' when the table leaves it empty)
    structure: bool = False  # SUNCG architecture (wall, column, partition, ...)


class ModelCategories:
    """Model id -> ``ModelCategory`` of one mapping file."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        try:
            text = self.path.read_text(encoding='utf-8')
        except (OSError, UnicodeDecodeError) as e:
            raise DatasetError(f'cannot read the category mapping {self.path}: '
                               f'{getattr(e, "strerror", None) or e}') from None
        if self.path.suffix.lower() == '.json':
            self.table = self._from_json(text)
        else:
            self.table = self._from_csv(text)

    def _from_csv(self, text: str) -> dict[str, ModelCategory]:
        rows = csv.DictReader(text.splitlines())
        names = rows.fieldnames or []
        column = next((c for c in CATEGORY_COLUMNS if c in names), None)
        if 'model_id' not in names or column is None:
            raise DatasetError(f'the category mapping {self.path} needs a model_id column and '
                               f'one of {", ".join(CATEGORY_COLUMNS)}; its columns are '
                               f'{", ".join(names) or "none"}')
        out = {}
        for row in rows:
            structure = (row.get('empty_struct_obj') or '').strip() == '1'
            out[(row['model_id'] or '').strip()] = ModelCategory(
                (row[column] or '').strip(), structure)
        return out

    def _from_json(self, text: str) -> dict[str, ModelCategory]:
        try:
            items = json.loads(text)
        except json.JSONDecodeError as e:
            raise DatasetError(f'the category mapping {self.path} is not valid JSON: {e.msg} '
                               f'at line {e.lineno}') from None
        if not isinstance(items, list) or not all(
                isinstance(i, dict) and 'model_id' in i for i in items):
            raise DatasetError(f'the category mapping {self.path} must be a list of objects '
                               f'with model_id and category, as model_info.json is')
        return {str(i['model_id']): ModelCategory(str(i.get('category') or '').strip())
                for i in items}

    def get(self, model_id: str) -> ModelCategory | None:
        return self.table.get(model_id)


@dataclass(frozen=True)
class AssetBox:
    object_type: str
    size: tuple[float, float, float]     # x, y, z extents in the asset's frame, metres


class AssetBoxes:
    """AI2-THOR asset id -> ``AssetBox`` (``procthor_asset_boxes.json``)."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        data = read_json(self.path, 'the asset table', DatasetError)
        if not isinstance(data, dict):
            raise DatasetError(f'the asset sizes {self.path} must map asset ids to '
                               f'{{objectType, boundingBox}}')
        self.table = {}
        for asset, entry in data.items():
            try:
                box = entry['boundingBox']
                self.table[asset] = AssetBox(str(entry['objectType']),
                                             (float(box['x']), float(box['y']), float(box['z'])))
            except (KeyError, TypeError, ValueError):
                continue        # an unreadable entry is a missing model for the report

    def get(self, asset_id: str) -> AssetBox | None:
        return self.table.get(asset_id)


class ModelBoxes:
    """Bounding boxes (min, max corners in the model's own frame) of the models of a
    folder, measured with trimesh; None for a model that is not there or not a mesh."""

    def __init__(self, root: str | Path, layout: str):
        self.root = Path(root)
        if not self.root.is_dir():
            raise DatasetError(f'the model folder {self.root} does not exist')
        self.layout = layout

    def path(self, model_id: str) -> Path:
        if self.layout == 'suncg':
            return self.root / 'object' / model_id / f'{model_id}.obj'
        return self.root / model_id / 'raw_model.obj'

    def get(self, model_id: str) -> tuple[np.ndarray, np.ndarray] | None:
        if not model_id or '/' in model_id or model_id.startswith('.'):
            return None
        return _mesh_bounds(str(self.path(model_id)))


@lru_cache(maxsize=4096)
def _mesh_bounds(path: str) -> tuple[np.ndarray, np.ndarray] | None:
    import trimesh  # heavy: only an import given a model folder reads meshes
    if not Path(path).is_file():
        return None
    try:
        mesh = trimesh.load(path, force='mesh', process=False)
    except Exception:          # a broken file is a missing model for the report
        return None
    bounds = getattr(mesh, 'bounds', None)
    if bounds is None or not np.all(np.isfinite(bounds)):
        return None
    lo, hi = np.asarray(bounds[0], float), np.asarray(bounds[1], float)
    return (lo, hi) if np.all(hi - lo > 0) else None
