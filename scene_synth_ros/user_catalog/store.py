"""The catalog file ``scene-synth catalog build`` writes, and reading it back.

JSON, so that using a catalog never re-reads its meshes::

    {"format": "scene_synth_ros user catalog", "version": 1,
     "models": [{"model_id": "red_chair", "category": "straight chair",
                 "file": "meshes/red_chair.glb", "size": [0.45, 0.52, 0.9],
                 "up": "+y", "front": "+z", "scale": 1.0, "offset": [0.01, 0.0, 0.0],
                 "marker": "markers/red_chair.stl"}],
     "report": ["models[3] 'lamp.obj': no such file"]}

``file`` is relative to the catalog file's folder (the two move together); ``size`` is
(width, depth, height) in metres; ``offset`` centres the turned and scaled model
(``measure.placement``). A catalog file that is not what it should be is a
``CatalogError`` naming the first problem.

``marker`` (optional, relative like ``file``) is the model's mesh already in the package's
object frame at ``size``, as a binary STL that ``write_catalog`` writes into ``markers/``
beside the catalog file: RViz shows a mesh resource as it is, with a pose and a scale but
no other transform. Catalogs written before it existed lack it and still read (version 1):
their RViz markers show the nearest procedural model instead.
"""
from __future__ import annotations

from dataclasses import replace
from functools import lru_cache
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from .. import catalog
from ..catalog import Catalog, UserModel
from ..categories import PAPER, Vocabulary
from ..errors import CatalogError, quoted
from ..files import read_json, safe_name, write_atomic
from ..schema import format_json
from .axes import parse_axis
from .measure import placement
from .spec import MAX_ID, category_of

FORMAT = 'scene_synth_ros user catalog'
VERSION = 1
MARKERS = 'markers'            # the folder of the RViz meshes, beside the catalog file


def model_record(m: UserModel, folder: Path) -> dict[str, Any]:
    """``m`` as the catalog file keeps it, its file relative to ``folder``."""
    t = m.matrix
    scale = float(np.linalg.norm(t[:3, 0]))
    rows = t[:3, :3] / scale
    up, front = _axis(rows.T @ (0, 0, 1)), _axis(rows.T @ (1, 0, 0))
    return {'model_id': m.model_id, 'category': m.category,
            'file': Path(os.path.relpath(m.source, folder.resolve())).as_posix(),
            'size': [round(float(v), 6) for v in m.size], 'up': up, 'front': front,
            'scale': scale, 'offset': [round(float(v), 6) + 0.0 for v in t[:3, 3]],
            **({'marker': Path(os.path.relpath(m.marker, folder.resolve())).as_posix()}
               if m.marker else {})}


def _axis(v: np.ndarray) -> str:
    k = int(np.argmax(np.abs(v)))
    return f'{"+" if v[k] > 0 else "-"}{"xyz"[k]}'


def write_catalog(path: str | Path, models: list[UserModel], report: list[str]) -> Path:
    """Write the catalog file, and each model's RViz mesh (``write_marker``) beside it."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    models = [replace(m, marker=write_marker(m, path.parent) or '') for m in models]
    data = {'format': FORMAT, 'version': VERSION,
            'models': [model_record(m, path.parent) for m in models],
            'report': list(report)}
    write_atomic(path, format_json(data) + '\n')
    return path


def write_marker(m: UserModel, folder: Path) -> str | None:
    """Write ``m``'s mesh in the package's object frame at its size (the box the
    exporters fit it to) as ``folder/markers/<id>.stl``; its absolute path, or None when the
    mesh cannot be read any more (the markers fall back to a procedural model then)."""
    import trimesh  # writing a marker only: reading a catalog does not need it

    from ..meshes.registry import build_parts  # trimesh, as above
    try:
        parts = build_parts(m)
    except CatalogError:
        return None
    mesh = trimesh.util.concatenate([trimesh.Trimesh(p.vertices, p.faces, process=False)
                                     for p in parts])
    stl = trimesh.exchange.stl.export_stl(mesh)
    out = (folder / MARKERS / f'{safe_name(m.model_id)}.stl').resolve()
    out.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(out, stl)
    return str(out)


def read_catalog(path: str | Path, vocabulary: Vocabulary = PAPER) -> Catalog:
    """The Catalog of a catalog file (the procedural catalog under the user's models), whose
    categories are those of ``vocabulary``."""
    path = Path(path)
    name = quoted(str(path), 80)
    data = read_json(path, 'the catalog', CatalogError,
                     ' (`scene-synth catalog build` writes one)')
    if not isinstance(data, dict) or data.get('format') != FORMAT:
        raise CatalogError(f'{name} is not a catalog written by `scene-synth catalog build`')
    if data.get('version') != VERSION or not isinstance(data.get('models'), list):
        raise CatalogError(f'the catalog {name} is of version {quoted(data.get("version"))}; '
                           f'this package reads version {VERSION}: build it again')
    models, seen = [], set()
    for i, record in enumerate(data['models']):
        try:
            m = _model(record, path.parent, vocabulary)
        except (KeyError, TypeError, ValueError) as e:
            raise CatalogError(f'the catalog {name}: models[{i}] is broken ({e}); build it '
                               f'again') from None
        if m.model_id in seen:
            raise CatalogError(f'the catalog {name}: models[{i}] repeats the id '
                               f'{quoted(m.model_id)}')
        seen.add(m.model_id)
        models.append(m)
    return Catalog(models, source=str(path))


def _numbers(value: Any, n: int, positive: bool = False) -> tuple[float, ...]:
    if not isinstance(value, list) or len(value) != n:
        raise ValueError(f'expected a list of {n} numbers')
    out = tuple(float(v) for v in value)
    if not all(math.isfinite(v) and (v > 0 or not positive) for v in out):
        raise ValueError(f'expected {"positive " if positive else ""}finite numbers')
    return out


def _model(record: dict[str, Any], folder: Path, vocabulary: Vocabulary) -> UserModel:
    model_id = record['model_id']
    if not isinstance(model_id, str) or not 0 < len(model_id) <= MAX_ID or '@' in model_id:
        raise ValueError('a bad model_id')
    try:
        catalog.get(model_id, vocabulary)
    except KeyError:
        pass
    else:
        raise ValueError(f'model_id {model_id!r} is a procedural model\'s')
    category = category_of(record['category'], vocabulary)
    if category is None or category != record['category']:
        raise ValueError(f'category {record["category"]!r} is not one of ours')
    up, front = record['up'], record['front']
    if parse_axis(up) is None or parse_axis(front) is None or \
            abs(float(parse_axis(up) @ parse_axis(front))) > 0.5:
        raise ValueError('up and front must be two different axes')
    scale = _numbers([record['scale']], 1, positive=True)[0]
    size = _numbers(record['size'], 3, positive=True)
    offset = _numbers(record['offset'], 3)
    source = (folder / str(record['file'])).resolve()
    marker = record.get('marker')
    if marker is not None and not isinstance(marker, str):
        raise ValueError('marker must be a path')
    m = placement(up, front, scale, offset)
    return UserModel(model_id, category, size, 0, str(source),
                     tuple(float(v) for v in m.ravel()),
                     str((folder / marker).resolve()) if marker else '')


def load_catalog(source: str | os.PathLike | Catalog | None,
                 vocabulary: Vocabulary = PAPER) -> Catalog:
    """The catalog of ``source``: the procedural one for None, a Catalog as it is, else the
    file ``scene-synth catalog build`` wrote, of the categories of ``vocabulary`` (read once
    per file version; ``errors.CatalogError`` names what is wrong with it)."""
    if source is None:
        return catalog.PROCEDURAL
    if isinstance(source, Catalog):
        return source
    path = os.path.abspath(os.fspath(source))
    try:
        st = os.stat(path)
        stamp = (st.st_mtime_ns, st.st_size)
    except OSError:
        stamp = None                  # the reader says what is wrong with the path
    return _load_file(path, stamp, vocabulary)


@lru_cache(maxsize=8)
def _load_file(path: str, stamp, vocabulary: Vocabulary) -> Catalog:
    return read_catalog(path, vocabulary)
