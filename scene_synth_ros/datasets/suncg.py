"""SUNCG houses (``house.json``) with ``ModelCategoryMapping.csv``.

What is read, in the file's own words:

* ``levels[].nodes[]``: nodes of ``type`` ``Room`` (``modelId``, ``roomTypes``,
  ``nodeIndices`` into the level's nodes, ``bbox``) and ``Object`` (``modelId``,
  ``transform``: a 4x4 matrix in column-major order, ``bbox``: the world box, ``valid``);
* categories: the ``fine_grained_class`` of ``modelId``; rows with ``empty_struct_obj`` = 1
  (walls, columns, partitions) are architecture; ``door`` and ``window`` objects of the
  level are openings, put on the wall of the room they cut;
* the floor: with a SUNCG folder (``--models``), the room's floor mesh
  ``room/<house id>/<modelId>f.obj`` (unioned triangles, exterior); without it, the room's
  ``bbox`` rectangle (a report note says so); the wall height is the room box's height.

Frames: y up, right-handed (``frames.RH_YUP_TO_ZUP``); a model faces its +z. An object's
footprint centre and bottom come from its world ``bbox``; its size from its model's box
times the transform's scale when the model folder has ``object/<id>/<id>.obj``, else from
the world box and the yaw (the footprint whose rotated box is the world box; near 45
degrees that is ambiguous and a square is assumed, with a note).
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, Iterator

import numpy as np
import shapely
from shapely.geometry import Polygon, box

from . import frames
from .models import ModelBoxes, ModelCategories
from .records import RawObject, RawOpening, RawRoom, normalise_category

C = frames.RH_YUP_TO_ZUP
OPENING_CLASSES = {'door': 'door', 'window': 'window'}


def read(path: Path, categories: ModelCategories, models: ModelBoxes | None,
         known_types: set[str], data: dict[str, Any] | None = None) -> Iterator[RawRoom]:
    """The rooms of one house file; a room with several ``roomTypes`` takes the first one
    the room-type mapping knows (``known_types``)."""
    data = data if data is not None else json.loads(path.read_text(encoding='utf-8'))
    if not isinstance(data, dict) or not isinstance(data.get('levels'), list):
        raise ValueError('it has no "levels" list, so it is not a SUNCG house')
    house = str(data.get('id') or path.stem)
    for li, level in enumerate(_dicts(data['levels'])):
        nodes = level.get('nodes') if isinstance(level.get('nodes'), list) else []
        openings = [op for op in (_opening(n, categories) for n in nodes
                                  if isinstance(n, dict)) if op is not None]
        for n in nodes:
            if isinstance(n, dict) and n.get('type') == 'Room':
                yield _room(path, house, li, n, nodes, openings, categories, models,
                            known_types)


def _dicts(value: Any) -> list[dict]:
    return [v for v in value if isinstance(v, dict)] if isinstance(value, list) else []


def _bbox(node: dict) -> tuple[np.ndarray, np.ndarray] | None:
    try:
        lo = np.asarray(node['bbox']['min'], dtype=float)
        hi = np.asarray(node['bbox']['max'], dtype=float)
    except (TypeError, KeyError, ValueError):
        return None
    if lo.shape != (3,) or hi.shape != (3,) or not np.all(np.isfinite(lo + hi)) \
            or np.any(hi < lo):
        return None
    return lo, hi


def _footprint(lo: np.ndarray, hi: np.ndarray) -> Polygon:
    a, b = C @ lo, C @ hi
    return box(min(a[0], b[0]), min(a[1], b[1]), max(a[0], b[0]), max(a[1], b[1]))


def _class(node: dict, categories: ModelCategories):
    return categories.get(str(node.get('modelId') or ''))


def _opening(node: dict, categories: ModelCategories) -> RawOpening | None:
    entry = _class(node, categories)
    kind = OPENING_CLASSES.get(entry.category) if entry is not None else None
    bb = _bbox(node)
    if node.get('type') != 'Object' or kind is None or bb is None:
        return None
    lo, hi = bb
    return RawOpening(kind, _footprint(lo, hi), float(lo[1]), float(hi[1]),
                      str(node.get('id') or ''))


def _room(path, house, li, node, nodes, openings, categories, models, known_types) -> RawRoom:
    types = [str(t) for t in node.get('roomTypes') or [] if isinstance(t, str)]
    rtype = next((t for t in types if t in known_types), types[0] if types else '')
    raw = RawRoom(str(path), house, str(node.get('id') or f'{li}_?'), rtype, None,
                  openings=openings)
    bb = _bbox(node)
    floor_base = 0.0
    if bb is not None:
        floor_base = float(bb[0][1])
        raw.wall_height = float(bb[1][1] - bb[0][1])
    raw.floor = _floor_mesh(models, house, str(node.get('modelId') or ''), raw)
    if raw.floor is None and bb is not None:
        raw.floor = _footprint(*bb)
        raw.notes.append('the floor is the room\'s bounding box (no room mesh was given)')
    elif raw.floor is None:
        raw.floor_problem = 'it has neither a floor mesh nor a bbox'
    for i in node.get('nodeIndices') or []:
        if not isinstance(i, int) or not 0 <= i < len(nodes) or not isinstance(nodes[i], dict):
            raw.objects.append(RawObject(f'node {i}', problem=f'its node index {i} is not a '
                                         f'node of the level', reason='missing model'))
            continue
        obj = _object(nodes[i], categories, models, floor_base)
        if obj is not None:
            raw.objects.append(obj)
    return raw


def _floor_mesh(models: ModelBoxes | None, house: str, model_id: str,
                raw: RawRoom) -> Polygon | None:
    if models is None or not model_id or '/' in model_id:
        return None
    path = models.root / 'room' / house / f'{model_id}f.obj'
    if not path.is_file():
        return None
    import trimesh  # heavy: only an import given SUNCG's room meshes reads them
    try:
        mesh = trimesh.load(path, force='mesh', process=False)
        v = (C @ np.asarray(mesh.vertices, dtype=float).T).T
        tris = [Polygon(v[f, :2]) for f in np.asarray(mesh.faces)]
    except Exception:        # a broken mesh: the bbox stands in, with a note
        raw.notes.append(f'the floor mesh {path.name} could not be read')
        return None
    tris = [t for t in tris if t.is_valid and t.area > 1e-8]
    if not tris:
        return None
    merged = shapely.union_all(tris).buffer(1e-4, join_style='mitre').buffer(
        -1e-4, join_style='mitre')
    parts = sorted(getattr(merged, 'geoms', [merged]), key=lambda g: -g.area)
    return Polygon(parts[0].exterior) if parts and isinstance(parts[0], Polygon) else None


def _object(node: dict, categories: ModelCategories, models: ModelBoxes | None,
            floor_base: float) -> RawObject | None:
    mid = str(node.get('modelId') or '')
    obj = RawObject(str(node.get('id') or '?'), model_id=mid)
    entry = _class(node, categories)
    if node.get('type') != 'Object':
        obj.problem, obj.reason = f'it is a {node.get("type")} node, not an object', \
            'not furniture'
        return obj
    if entry is not None and entry.category in OPENING_CLASSES:
        return None                       # an opening of the level
    if node.get('valid') == 0:
        obj.problem, obj.reason = f'model {mid} is marked invalid in the file', 'invalid model'
    elif entry is None:
        obj.problem, obj.reason = f'model {mid} is missing from the category mapping', \
            'missing model'
    elif entry.structure:
        obj.problem, obj.reason = f'model {mid} is architecture ({entry.category})', \
            'architecture'
    elif not normalise_category(entry.category) or entry.category in ('unknown', 'empty'):
        obj.problem, obj.reason = f'model {mid} has the category {entry.category or "(none)"}', \
            'unknown category'
    else:
        obj.category = normalise_category(entry.category)
        try:
            _place(obj, node, models, floor_base)
        except (frames.BrokenTransform, TypeError, ValueError) as e:
            obj.problem, obj.reason = f'its transform is broken: {e}', 'broken transform'
    return obj


def _place(obj: RawObject, node: dict, models: ModelBoxes | None, floor_base: float) -> None:
    t = frames.column_major(node.get('transform'))
    if not np.all(np.isfinite(t)):
        raise frames.BrokenTransform('the transform has numbers that are not finite')
    p = frames.placement(t[:3, :3], C)
    bb = _bbox(node)
    if bb is None:
        obj.problem, obj.reason = 'it has no usable bbox', 'no size'
        return
    lo, hi = bb
    centre = C @ ((lo + hi) / 2)
    obj.position = (float(centre[0]), float(centre[1]), float(lo[1] - floor_base))
    obj.yaw, obj.scale = p.yaw, p.scale
    height = float(hi[1] - lo[1])
    bounds = models.get(obj.model_id) if models is not None else None
    if bounds is not None:
        ext = bounds[1] - bounds[0]
        obj.size = (float(ext[frames.LATERAL] * p.scale[0]),
                    float(ext[frames.FRONT] * p.scale[1]), float(ext[frames.UP] * p.scale[2]))
        return
    a, b = C @ lo, C @ hi
    width, depth, guessed = unrotate(abs(b[0] - a[0]), abs(b[1] - a[1]), p.yaw)
    obj.size = (width, depth, height)
    if guessed:
        obj.note = (f'object {obj.source_id}: turned {math.degrees(p.yaw):.0f} degrees and '
                    f'no model file, so its footprint is taken as square')


def unrotate(ex: float, ey: float, yaw: float) -> tuple[float, float, bool]:
    """(width, depth, guessed) of the rectangle whose box, turned by ``yaw``, is ex x ey:
    ex = |cos| depth + |sin| width, ey = |sin| depth + |cos| width. Near 45 degrees the
    two equations are one and a square is assumed (``guessed``)."""
    c, s = abs(math.cos(yaw)), abs(math.sin(yaw))
    det = c * c - s * s
    if abs(det) >= 0.2:
        depth = (c * ex - s * ey) / det
        width = (c * ey - s * ex) / det
        if depth > 0 and width > 0:
            return width, depth, False
    side = (ex + ey) / 2 / (c + s)
    return side, side, True
