"""3D-FRONT houses (one scene JSON per house) with 3D-FUTURE models.

What is read, in the file's own words:

* ``scene.room[]``: ``type`` (the room type), ``instanceid`` (the room id), ``pos``,
  ``rot``, ``scale`` and ``children[]``, each a ``ref`` to a ``furniture[].uid`` or a
  ``mesh[].uid`` with its own ``pos``, ``rot`` (quaternion x, y, z, w), ``scale``. The
  house's ``scene`` transform, the room's and the child's are composed.
* ``mesh[]``: ``type``, ``xyz`` (vertices, flat) and ``faces`` (triangles). The room's
  ``Floor`` meshes, unioned, give the floor outline (their exterior; an L-shaped room stays
  L-shaped); ``Ceiling`` gives the wall height; ``Door``, ``Window`` and ``Hole`` meshes of
  the whole house are the openings (a hole from the floor up at least 1.5 m high is a door,
  any other a window), each put on the wall of the room it cuts (``assemble.py``).
* ``furniture[]``: ``jid`` (the 3D-FUTURE model id, our ``model_id``), ``valid``, and the
  model's box: older files carry ``size`` = (x, z, y) extents, i.e. (width, depth,
  height); newer ones (the ones with an inline ``category``, ``jobid``, ``lights``,
  ``groups``) carry only ``bbox`` = (x, y, z) extents. Both are scaled by the child's
  ``scale``. With a 3D-FUTURE model folder the box is measured on ``<jid>/raw_model.obj``
  instead, and the footprint centre is the box's; without it the model's origin is taken
  as its bottom centre.
* categories: the 3D-FUTURE category of ``jid`` from the mapping (CSV or
  ``model_info.json``); a model the mapping does not have falls back to the newer files'
  inline ``category``, else it is dropped with a report line.

Frames: y up, right-handed (``frames.RH_YUP_TO_ZUP``); a model faces its +z.
Doors and windows found among ``furniture`` (a category naming a door or window, or a
``ref`` of ``extension.door``) are openings, not furniture.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
import re
from typing import Any, Iterator

import numpy as np
import shapely
from shapely.geometry import MultiPoint, Polygon

from . import frames
from .models import ModelBoxes, ModelCategories
from .records import RawObject, RawOpening, RawRoom, footprint, normalise_category

C = frames.RH_YUP_TO_ZUP
HOLE_DOOR_HEIGHT = 1.5      # m: a hole from the floor at least this high is a door
FLAT = 0.2                  # m: an opening mesh lower than this is a threshold, not the opening
OPENING_WORD = re.compile(r'\b(door|window)s?\b')   # 'outdoor chair' is furniture


def read(path: Path, categories: ModelCategories, models: ModelBoxes | None,
         data: dict[str, Any] | None = None) -> Iterator[RawRoom]:
    """The rooms of one 3D-FRONT house file (``data``: its parsed JSON, if read already)."""
    data = data if data is not None else json.loads(path.read_text(encoding='utf-8'))
    if not isinstance(data, dict) or not isinstance(data.get('scene'), dict):
        raise ValueError('it has no "scene" object, so it is not a 3D-FRONT house')
    house = str(data.get('uid') or path.stem)
    furniture = {str(f.get('uid')): f for f in _dicts(data.get('furniture'))}
    meshes = {str(m.get('uid')): m for m in _dicts(data.get('mesh'))}
    door_refs = {str(r) for d in _dicts((data.get('extension') or {}).get('door'))
                 for r in d.get('ref') or []}
    scene_t = _matrix(data['scene'])
    openings = list(_openings(meshes, scene_t))
    for room in _dicts(data['scene'].get('room')):
        yield _room(path, house, room, scene_t, furniture, meshes, door_refs, openings,
                    categories, models)


def _dicts(value: Any) -> list[dict]:
    return [v for v in value if isinstance(v, dict)] if isinstance(value, list) else []


def _matrix(node: dict[str, Any]) -> np.ndarray:
    """The 4x4 transform of a node's ``pos``, ``rot`` (x, y, z, w) and ``scale``."""
    t = np.eye(4)
    rot = frames.quaternion_matrix(node.get('rot', (0, 0, 0, 1)))
    scale = np.asarray(node.get('scale', (1, 1, 1)), dtype=float)
    pos = np.asarray(node.get('pos', (0, 0, 0)), dtype=float)
    if scale.shape != (3,) or pos.shape != (3,):
        raise frames.BrokenTransform('pos and scale need three numbers each')
    t[:3, :3] = rot @ np.diag(scale)
    t[:3, 3] = pos
    if not np.all(np.isfinite(t)):
        raise frames.BrokenTransform('the transform has numbers that are not finite')
    return t


def _vertices(mesh: dict[str, Any], t: np.ndarray) -> np.ndarray:
    """The mesh's vertices, transformed by ``t`` and converted to REP-103 (n x 3)."""
    xyz = np.asarray(mesh.get('xyz') or [], dtype=float)
    if xyz.size == 0 or xyz.size % 3:
        return np.zeros((0, 3))
    v = xyz.reshape(-1, 3)
    v = (t[:3, :3] @ v.T).T + t[:3, 3]
    return (C @ v.T).T


def _triangles(mesh: dict[str, Any], v: np.ndarray) -> list[Polygon]:
    faces = np.asarray(mesh.get('faces') or range(len(v)), dtype=int)
    faces = faces[: len(faces) // 3 * 3].reshape(-1, 3)
    faces = faces[(faces >= 0).all(axis=1) & (faces < len(v)).all(axis=1)]
    out = []
    for f in faces:
        tri = Polygon(v[f, :2])
        if tri.is_valid and tri.area > 1e-8:
            out.append(tri)
    return out


def _openings(meshes: dict[str, dict], scene_t: np.ndarray) -> Iterator[RawOpening]:
    """The house's door, window and hole meshes as openings (each room takes the ones on
    its walls). The meshes are in house coordinates: only the scene transform applies."""
    for uid, mesh in meshes.items():
        kind = mesh.get('type')
        if kind not in ('Door', 'Window', 'Hole'):
            continue
        try:
            v = _vertices(mesh, scene_t)
        except (TypeError, ValueError):
            continue
        if len(v) < 3 or not np.all(np.isfinite(v)):
            continue
        bottom, top = float(v[:, 2].min()), float(v[:, 2].max())
        if top - bottom < FLAT:
            continue
        if kind == 'Hole':
            kind = 'Door' if bottom < 0.1 and top - bottom >= HOLE_DOOR_HEIGHT else 'Window'
        hull = MultiPoint([tuple(p) for p in v[:, :2]]).convex_hull
        yield RawOpening(kind.lower(), hull, bottom, top, uid)


def _room(path, house, room, scene_t, furniture, meshes, door_refs, openings, categories,
          models) -> RawRoom:
    rid = str(room.get('instanceid') or room.get('id') or '?')
    raw = RawRoom(str(path), house, rid, str(room.get('type') or ''), None,
                  openings=list(openings))
    try:
        room_t = scene_t @ _matrix(room)
    except (frames.BrokenTransform, TypeError, ValueError) as e:
        raw.floor_problem = f'the room transform is broken: {e}'
        return raw
    floor_tris: list[Polygon] = []
    ceilings: list[float] = []
    for i, child in enumerate(_dicts(room.get('children'))):
        ref = str(child.get('ref'))
        cid = str(child.get('instanceid') or f'child{i}')
        try:
            t = room_t @ _matrix(child)
        except (frames.BrokenTransform, TypeError, ValueError) as e:
            raw.objects.append(RawObject(cid, problem=f'its transform is broken: {e}',
                                         reason='broken transform'))
            continue
        if ref in meshes:
            try:
                _room_mesh(meshes[ref], t, floor_tris, ceilings)
            except (TypeError, ValueError):     # a broken mesh: the room goes on without it
                raw.notes.append(f'mesh {ref} could not be read')
            continue
        if ref not in furniture:
            raw.objects.append(RawObject(cid, model_id=ref, problem=f'its ref {ref} is in '
                                         f'neither furniture nor mesh', reason='missing model'))
            continue
        obj = _object(cid, furniture[ref], t, categories, models, ref in door_refs)
        if isinstance(obj, RawOpening):
            raw.openings.append(obj)
        elif obj is not None:
            raw.objects.append(obj)
    if floor_tris:
        raw.floor = _outline(floor_tris, raw)
    else:
        raw.floor_problem = 'it has no Floor mesh'
    if ceilings:
        raw.wall_height = min(ceilings)
    return raw


def _room_mesh(mesh: dict[str, Any], t: np.ndarray, floor_tris: list[Polygon],
               ceilings: list[float]) -> None:
    """A room's Floor mesh adds its triangles, a Ceiling mesh its height."""
    if mesh.get('type') == 'Floor':
        floor_tris += _triangles(mesh, _vertices(mesh, t))
    elif mesh.get('type') == 'Ceiling':
        v = _vertices(mesh, t)
        if len(v) and np.all(np.isfinite(v)):
            ceilings.append(float(v[:, 2].min()))


def _outline(triangles: list[Polygon], raw: RawRoom) -> Polygon | None:
    """The exterior of the union of the floor triangles (slivers between them closed)."""
    merged = shapely.union_all(triangles).buffer(1e-4, join_style='mitre').buffer(
        -1e-4, join_style='mitre')
    parts = sorted(getattr(merged, 'geoms', [merged]), key=lambda g: -g.area)
    parts = [p for p in parts if isinstance(p, Polygon) and not p.is_empty]
    if not parts:
        raw.floor_problem = 'its Floor meshes enclose no area'
        return None
    if len(parts) > 1:
        raw.notes.append(f'the floor is in {len(parts)} pieces; the largest '
                         f'({parts[0].area:.1f} m²) is kept')
    return Polygon(parts[0].exterior).simplify(1e-3)


def _object(cid: str, f: dict[str, Any], t: np.ndarray, categories: ModelCategories,
            models: ModelBoxes | None, is_door: bool) -> RawObject | RawOpening | None:
    """The furniture as an object; a door or window as an opening (None when it has no
    box: the house's door and window meshes carry it)."""
    jid = str(f.get('jid') or '')
    obj = RawObject(cid, model_id=jid)
    entry = categories.get(jid)
    inline = str(f.get('category') or '')
    name = entry.category if entry is not None else inline
    cat = normalise_category(name) if name and name != 'Others' else ''
    opening = OPENING_WORD.search(cat)
    if is_door or opening:
        kind = opening.group(1) if opening else 'door'
        return _opening_furniture(cid, f, t, models, kind)
    if f.get('valid') is False:
        obj.problem, obj.reason = f'model {jid} is marked invalid in the file', 'invalid model'
        return obj
    if entry is None and not inline:
        obj.problem = f'model {jid or "(no jid)"} is missing from the category mapping'
        obj.reason = 'missing model'
        return obj
    if not cat:
        obj.problem = (f'model {jid} has the category {name}' if name else
                       f'model {jid} has an empty category in the mapping')
        obj.reason = 'unknown category'
        return obj
    obj.category = cat
    try:
        _place(obj, f, t, models)
    except frames.BrokenTransform as e:
        obj.problem, obj.reason = f'its transform is broken: {e}', 'broken transform'
    return obj


def _opening_furniture(cid: str, f: dict[str, Any], t: np.ndarray, models: ModelBoxes | None,
                       kind: str) -> RawOpening | None:
    """A door or window model placed like furniture, as the footprint of its box."""
    probe = RawObject(cid, model_id=str(f.get('jid') or ''), category=kind)
    try:
        _place(probe, f, t, models)
    except frames.BrokenTransform:
        return None
    if probe.problem:
        return None
    bottom = probe.position[2]
    return RawOpening(kind, footprint(probe), bottom, bottom + probe.size[2], cid)


def _model_box(f: dict[str, Any]) -> np.ndarray | None:
    """(x, y, z) extents of the model from the JSON: ``size`` is (x, z, y), ``bbox``
    (x, y, z)."""
    for key, order in (('size', (0, 2, 1)), ('bbox', (0, 1, 2))):
        value = f.get(key)
        try:
            a = np.asarray(value, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            continue
        if a.shape == (3,) and np.all(np.isfinite(a)) and np.all(a > 0):
            out = np.empty(3)
            out[list(order)] = a          # a[i] is the extent along model axis order[i]
            return out
    return None


def _place(obj: RawObject, f: dict[str, Any], t: np.ndarray, models: ModelBoxes | None) -> None:
    m = t[:3, :3]
    p = frames.placement(m, C)
    bounds = models.get(obj.model_id) if models is not None else None
    if bounds is not None:
        lo, hi = bounds
        extents = hi - lo
        base = np.array([(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2])
    else:
        extents = _model_box(f)
        if extents is None:
            obj.problem = f'model {obj.model_id} has no size (no size or bbox field'
            obj.problem += ' and no model folder)' if models is None else \
                ', and its raw_model.obj is not in the model folder)'
            obj.reason = 'no size'
            return
        base = np.zeros(3)
    centre = C @ (m @ base + t[:3, 3])
    obj.position = (float(centre[0]), float(centre[1]), float(centre[2]))
    obj.yaw = p.yaw
    obj.scale = p.scale
    obj.size = tuple(float(e * s) for e, s in zip(
        (extents[frames.LATERAL], extents[frames.FRONT], extents[frames.UP]), p.scale,
        strict=True))
    if not all(math.isfinite(v) for v in obj.position + obj.size):
        obj.problem, obj.reason = 'its position or size is not finite', 'broken transform'
