"""ProcTHOR houses: JSON lines (plain or gzip), one house per line, AI2-THOR (Unity)
coordinates: metres, y up, left-handed (``frames.UNITY_TO_ZUP``).

What is read, in the file's own words:

* ``rooms[]``: ``id``, ``roomType``, ``floorPolygon`` (``{x, y, z}`` points on the floor);
* ``walls[]``: ``id`` (``wall|<room>|x0|z0|x1|z1``), ``roomId``, ``polygon``; the tallest
  wall of a room is its wall height;
* ``doors[]`` and ``windows[]``: ``room0``/``wall0`` and ``room1``/``wall1`` (the two
  sides), ``holePolygon`` (two corners ``{x, y}``: x along the wall, measured from the
  first point of ``wall0``'s polygon, y the height above the floor). An opening belongs to
  both rooms it joins;
* ``objects[]``: ``id``, ``assetId`` (our ``model_id``), ``position`` (the centre of the
  asset's box), ``rotation`` (Euler degrees, Unity's z-x-y order; normally only y), nested
  ``children[]`` standing on them (the second tier; their ``support`` is the parent). An
  object belongs to the room whose floor holds its centre.

Sizes: AI2-THOR assets face their +z, so ``size`` = (box x, box z, box y) from the asset
table (``procthor_asset_boxes.json``: ``objectType``, our category, and ``boundingBox``).
A house has no id in the file: it is named by its line number.
"""
from __future__ import annotations

import gzip
import math
from pathlib import Path
from typing import Any, Iterator

import numpy as np
from shapely.geometry import LineString, Point, Polygon

from . import frames
from .models import AssetBoxes
from .records import RawObject, RawOpening, RawRoom, normalise_category

U = frames.UNITY_TO_ZUP


def lines(path: Path) -> Iterator[tuple[int, str]]:
    """(line number, text) of the non-empty lines of a JSON-lines file, gzip or plain."""
    opener = gzip.open if path.suffix == '.gz' else open
    with opener(path, 'rt', encoding='utf-8') as f:
        for n, line in enumerate(f, 1):
            if line.strip():
                yield n, line


def read_house(path: Path, line_no: int, house: Any, assets: AssetBoxes) -> list[RawRoom]:
    """The rooms of one parsed house."""
    if not isinstance(house, dict) or not isinstance(house.get('rooms'), list):
        raise ValueError('it has no "rooms" list, so it is not a ProcTHOR house')
    hid = str(line_no)
    walls = {str(w.get('id')): w for w in _dicts(house.get('walls'))}
    rooms: dict[str, RawRoom] = {}
    for r in _dicts(house['rooms']):
        rid = str(r.get('id'))
        raw = RawRoom(str(path), hid, rid, str(r.get('roomType') or ''), None,
                      parent_links=True)
        raw.floor, raw.floor_problem = _floor(r.get('floorPolygon'))
        heights = [_wall_height(w) for w in walls.values() if str(w.get('roomId')) == rid]
        heights = [h for h in heights if h is not None]
        raw.wall_height = max(heights) if heights else None
        rooms[rid] = raw
    for kind, key in (('door', 'doors'), ('window', 'windows')):
        for op in _dicts(house.get(key)):
            opening = _opening(kind, op, walls.get(str(op.get('wall0'))))
            sides = {str(op.get('room0')), str(op.get('room1'))}
            for room in (rooms.get(s) for s in sorted(sides)):
                if room is not None and opening is not None:
                    room.openings.append(opening)
    for i, obj in enumerate(_dicts(house.get('objects'))):
        placed = list(_objects(obj, None, assets, f'objects[{i}]'))
        target = _room_of(placed[0], rooms) if placed else None
        if target is not None:
            target.objects += placed
    return list(rooms.values())


def _dicts(value: Any) -> list[dict]:
    return [v for v in value if isinstance(v, dict)] if isinstance(value, list) else []


def _xz(p: Any) -> tuple[float, float]:
    q = U @ np.array([float(p['x']), float(p.get('y', 0.0)), float(p['z'])])
    return float(q[0]), float(q[1])


def _floor(points: Any) -> tuple[Polygon | None, str]:
    try:
        pts = [_xz(p) for p in points]
    except (TypeError, KeyError, ValueError):
        return None, 'its floorPolygon is missing or not a list of {x, z} points'
    if len(pts) < 3 or not all(math.isfinite(v) for p in pts for v in p):
        return None, f'its floorPolygon has {len(pts)} usable points'
    return Polygon(pts), ''


def _wall_height(wall: dict) -> float | None:
    try:
        return max(float(p['y']) for p in wall['polygon'])
    except (TypeError, KeyError, ValueError):
        return None


def _wall_ends(wall_id: str, wall: dict | None) -> tuple[np.ndarray, np.ndarray] | None:
    """The wall's start and end in REP-103: the first point of the wall's ``polygon`` and
    the other end of its bottom edge (a hole's x is measured from that start; with the
    id's (x0, z0) instead, 111 of the 1116 paintings of the 500 real houses would overlap a
    window or door, with the polygon's none). Without a polygon, the id's points."""
    try:
        x0, z0, x1, z1 = (float(v) for v in wall_id.split('|')[-4:])
    except ValueError:
        return None
    a, b = np.array(_xz({'x': x0, 'z': z0})), np.array(_xz({'x': x1, 'z': z1}))
    try:
        corners = [np.array(_xz(p)) for p in wall['polygon']]
    except (TypeError, KeyError, ValueError):
        corners = []
    if corners:
        # the id rounds to 1 cm; the polygon does not, and its first point is the start
        start = corners[0]
        near_a = float(np.linalg.norm(start - a)) <= float(np.linalg.norm(start - b))
        end = b if near_a else a
        a, b = start, min(corners, key=lambda c: float(np.linalg.norm(c - end)))
    return (a, b) if np.linalg.norm(b - a) > 1e-6 else None


def _opening(kind: str, op: dict, wall: dict | None) -> RawOpening | None:
    ends = _wall_ends(str(op.get('wall0') or ''), wall)
    hole = op.get('holePolygon')
    if ends is None or not isinstance(hole, list) or len(hole) < 2:
        return None
    try:
        xs = [float(p['x']) for p in hole]
        ys = [float(p['y']) for p in hole]
    except (TypeError, KeyError, ValueError):
        return None
    a, b = ends
    d = (b - a) / np.linalg.norm(b - a)
    segment = LineString([tuple(a + d * min(xs)), tuple(a + d * max(xs))])
    return RawOpening(kind, segment, min(ys), max(ys), str(op.get('id') or ''), own=True)


def _objects(obj: dict, parent: str | None, assets: AssetBoxes,
             path: str) -> Iterator[RawObject]:
    """The object and, after it, everything standing on it."""
    oid = str(obj.get('id') or path)
    yield _object(oid, obj, parent, assets)
    for i, child in enumerate(_dicts(obj.get('children'))):
        yield from _objects(child, oid, assets, f'{path}.children[{i}]')


def _object(oid: str, obj: dict, parent: str | None, assets: AssetBoxes) -> RawObject:
    asset = str(obj.get('assetId') or '')
    out = RawObject(oid, model_id=asset, parent=parent)
    box = assets.get(asset)
    if box is None:
        out.problem, out.reason = (f'asset {asset or "(none)"} is missing from the asset '
                                   f'table'), 'missing model'
        return out
    out.category = normalise_category(box.object_type)
    if not out.category:
        out.problem, out.reason = f'asset {asset} has no object type', 'unknown category'
        return out
    try:
        rot = obj.get('rotation') or {}
        m = frames.unity_euler_matrix(rot.get('x', 0), rot.get('y', 0), rot.get('z', 0))
        p = frames.placement(m, U)
        pos = obj['position']
        centre = U @ np.array([float(pos['x']), float(pos['y']), float(pos['z'])])
    except frames.BrokenTransform as e:
        out.problem, out.reason = f'its transform is broken: {e}', 'broken transform'
        return out
    except (TypeError, KeyError, ValueError) as e:
        out.problem, out.reason = f'its position or rotation is unreadable ({e})', \
            'broken transform'
        return out
    if not np.all(np.isfinite(centre)):
        out.problem, out.reason = 'its position is not finite', 'broken transform'
        return out
    bx, by, bz = box.size
    out.yaw = p.yaw
    out.size = (bx, bz, by)
    out.position = (float(centre[0]), float(centre[1]), float(centre[2] - by / 2))
    return out


def _room_of(obj: RawObject, rooms: dict[str, RawRoom]) -> RawRoom | None:
    """The room whose floor holds the object (the nearest floor if none does)."""
    floors = [(r, r.floor) for r in rooms.values() if r.floor is not None]
    if not floors:
        return next(iter(rooms.values()), None)
    point = Point(obj.position[:2])
    return min(floors, key=lambda rf: rf[1].distance(point))[0]
