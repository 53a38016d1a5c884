"""One ``RawRoom`` (any format) -> one Scene JSON dict, or report lines saying why not.

In order: the room type is mapped (unmapped: dropped); the floor is checked with the
package's own floor checks (``schema.check_floor``: simple, at least 2 m², no repeated
vertices) and must be at most the room-size filter's length along its own axes
(``render.room_axis_yaw``);
openings are put on the wall whose line is nearest to their footprint, measured along it,
merged where the source splits one opening into several meshes, and checked against the
layout schema's limits (a door 0.3 to 5 m wide and at least 1.5 m high); objects are
filtered (problems found by the reader, scale, outside the floor, below it), given their
support (the data's parent link, else the first-tier object whose top they stand on and
whose footprint holds their centre and half their footprint), counted against the
object-count range, and named ``<category>_<n>``. The result is validated against
``msg_schemas/scene.schema.json``; the category checks of ``schema.py`` are not applied,
because they know only the paper's categories and an imported data set brings its own.
"""
from __future__ import annotations

import math
import re
from typing import Any

import numpy as np
import shapely
from shapely.errors import GEOSException
from shapely.geometry import Point, Polygon

from .. import schema
from ..limits import MAX_OPENINGS
from ..render import room_axis_yaw
from ..scene import DEFAULT_WALL_HEIGHT, Room
from ..thresholds import OPENING_TOLERANCE, WALL_HEIGHT_RANGE
from .config import ImportConfig
from .records import RawObject, RawOpening, RawRoom, footprint
from .report import ImportReport

MIN_OPENING, MAX_OPENING = 0.3, 5.0      # m, exclusive (room_layout.schema.json)
MIN_DOOR_HEIGHT = 1.5                     # m (room_layout.schema.json)
MIN_WINDOW_HEIGHT = 0.2                   # m, exclusive
MAX_NAME = 100                            # characters of an object id before its number


def where(raw: RawRoom) -> str:
    return f'{raw.source.rsplit("/", 1)[-1]} house {raw.house_id} room {raw.room_id}'


def assemble(raw: RawRoom, fmt: str, config: ImportConfig,
             report: ImportReport) -> dict[str, Any] | None:
    """The scene dict of ``raw``, or None after the report says why it was dropped."""
    at = where(raw)
    report.rooms_seen += 1
    room_type = config.room_types.get(raw.room_type)
    if room_type is None:
        report.add('room', 'unmapped room type', at,
                   f'its room type {raw.room_type or "(none)"} is not in the room-type mapping')
        return None
    report.room_types[f'{raw.room_type} -> {room_type}'] += 1
    room = _room(raw, room_type, config, report, at)
    if room is None:
        return None
    for note in raw.notes:
        report.add('note', 'mapped with a guess', at, note)
    objects = _objects(raw, room, config, report, at)
    lo, hi = config.object_count
    if not lo <= len(objects) <= hi:
        reason = 'too few objects' if len(objects) < lo else 'too many objects'
        report.add('room', reason, at, f'it keeps {len(objects)} objects, outside the '
                   f'{lo} to {hi} of the object-count filter')
        return None
    doors, windows = _openings(raw, room, config.opening_reach, report, at)
    scene = {
        'room': {'room_type': room_type, 'floor': [list(p) for p in room.floor],
                 'wall_height': room.wall_height, 'doors': doors, 'windows': windows},
        'objects': objects,
        'meta': {'source': {'format': fmt, 'file': raw.source.rsplit('/', 1)[-1],
                            'house_id': raw.house_id, 'room_id': raw.room_id,
                            'room_type': raw.room_type},
                 'generator': 'scene-synth import'}}
    try:
        scene = schema.plain_json(scene)          # plain JSON values, within the package's limits
        schema.check_against_schema(scene, 'scene')
    except schema.SceneValidationError as e:
        report.add('room', 'invalid scene', at, f'the scene fails the JSON schema: {e}')
        return None
    report.rooms_kept[room_type] += 1
    report.objects_kept[room_type] += len(objects)
    report.openings_kept['door'] += len(doors)
    report.openings_kept['window'] += len(windows)
    for o in objects:
        report.categories[o['category']] += 1
    return scene


# ----------------------------------------------------------------------------- the room

def _room(raw: RawRoom, room_type: str, config: ImportConfig, report: ImportReport,
          at: str) -> Room | None:
    if raw.floor is None:
        report.add('room', 'no floor', at, raw.floor_problem or 'it has no floor')
        return None
    try:
        points = schema.check_floor(_floor_points(raw.floor), 'floor')
    except schema.SceneValidationError as e:
        report.add('room', 'no floor', at, f'its floor is not usable: {e}')
        return None
    except (ValueError, GEOSException):
        report.add('room', 'no floor', at, 'its floor outline is not a polygon')
        return None
    height = raw.wall_height if raw.wall_height is not None else DEFAULT_WALL_HEIGHT
    lo, hi = WALL_HEIGHT_RANGE
    if not math.isfinite(height):
        height = DEFAULT_WALL_HEIGHT
    elif not lo <= height <= hi:
        kept = min(max(height, lo), hi)
        report.add('note', 'mapped with a guess', at, f'its wall height {height:.2f} m is '
                   f'outside {lo} to {hi} m; {kept} m is used')
        height = kept
    room = Room(room_type, tuple(points), round(float(height), 4))
    side = config.size_limit(room_type)
    if side is not None:
        span = room_span(room)
        if max(span) > side + 1e-6:
            report.add('room', 'room too large', at,
                       f'it is {max(span):.2f} m x {min(span):.2f} m along its walls, '
                       f'longer than the {side:g} m of the room-size filter for {room_type}')
            return None
    return room


def _floor_points(poly: Polygon) -> list[list[float]]:
    """The outline's vertices, rounded to 0.1 mm, collinear ones removed, at most 256."""
    poly = shapely.set_precision(poly, 1e-4)
    for tol in (1e-3, 5e-3, 0.01, 0.02, 0.05):
        simple = poly.simplify(tol)
        if isinstance(simple, Polygon) and len(simple.exterior.coords) - 1 <= 256:
            poly = simple
            break
    if not isinstance(poly, Polygon) or poly.is_empty:
        return []
    return [[round(x, 4), round(y, 4)] for x, y in poly.exterior.coords[:-1]]


def room_span(room: Room) -> tuple[float, float]:
    """The room's extent along its own axes (those of ``render.room_axis_yaw``)."""
    yaw = room_axis_yaw(room)
    c, s = math.cos(yaw), math.sin(yaw)
    pts = np.asarray(room.floor)
    u = pts @ np.array([c, s])
    v = pts @ np.array([-s, c])
    return float(u.max() - u.min()), float(v.max() - v.min())


# ----------------------------------------------------------------------------- openings

def _openings(raw: RawRoom, room: Room, reach: float, report: ImportReport, at: str):
    """(doors, windows) as layout dicts, each on one wall of ``room``."""
    placed: dict[tuple[int, str], list[list[float]]] = {}   # (wall, kind) -> [lo, hi, bot, top]
    for op in raw.openings:
        hit = _on_wall(op, room, reach)
        if hit is None:
            if op.own:
                report.add('opening', 'opening off the walls', at,
                           f'{op.kind} {op.source_id} lies on none of the room\'s walls')
            continue
        wall, lo, hi = hit
        placed.setdefault((wall, op.kind), []).append([lo, hi, op.bottom, op.top])
    doors: list[tuple[int, float, float, dict]] = []
    windows: list[tuple[int, float, float, dict]] = []
    for (wall_index, kind), spans in sorted(placed.items()):
        for lo, hi, bottom, top in _merge(spans):
            d = _opening_dict(kind, room, wall_index, lo, hi, bottom, top, report, at)
            if d is not None:
                (doors if kind == 'door' else windows).append((wall_index, lo, hi, d))
    kept: list[tuple[int, float, float, dict]] = []
    for wall_index, lo, hi, d in doors + windows:       # doors win over windows
        clash = next((k for k in kept if k[0] == wall_index
                      and min(hi, k[2]) - max(lo, k[1]) > OPENING_TOLERANCE), None)
        if clash is not None:
            kind = 'door' if 'sill' not in d else 'window'
            report.add('opening', 'overlapping openings', at,
                       f'a {kind} at ({d["position"][0]:.2f}, {d["position"][1]:.2f}) '
                       f'overlaps another opening on the same wall')
            continue
        kept.append((wall_index, lo, hi, d))
    doors = [k[3] for k in kept if 'sill' not in k[3]]
    windows = [k[3] for k in kept if 'sill' in k[3]]
    for kind, items in (('door', doors), ('window', windows)):
        if len(items) > MAX_OPENINGS:
            report.add('opening', f'too many {kind}s', at, f'it has {len(items)} {kind}s; the '
                       f'first {MAX_OPENINGS} are kept, as a layout holds no more')
    return doors[:MAX_OPENINGS], windows[:MAX_OPENINGS]


def _on_wall(op: RawOpening, room: Room, reach: float):
    """(wall index, lo, hi offsets along it) of the wall the opening cuts, or None."""
    if op.footprint.is_empty:
        return None
    centre = op.footprint.centroid
    wall = min(room.walls, key=lambda w: w.distance_to((centre.x, centre.y)))
    if wall.distance_to((centre.x, centre.y)) > reach:
        return None
    coords = np.asarray(op.footprint.exterior.coords if isinstance(op.footprint, Polygon)
                        else op.footprint.coords)
    offsets = [wall.offset_of(p) for p in coords[:, :2]]
    lo, hi = min(offsets), max(offsets)
    clo, chi = max(lo, 0.0), min(hi, wall.length)
    if chi - clo < 0.5 * (hi - lo) or chi <= clo:
        return None          # mostly past the wall's ends: another room's opening
    return wall.index, clo, chi


def _merge(spans: list[list[float]]) -> list[list[float]]:
    """Overlapping spans of one wall and kind merged (a door and its frame, two panes)."""
    out: list[list[float]] = []
    for lo, hi, bottom, top in sorted(spans):
        if out and lo < out[-1][1] - 1e-6:
            last = out[-1]
            last[1], last[2], last[3] = max(last[1], hi), min(last[2], bottom), max(last[3], top)
        else:
            out.append([lo, hi, bottom, top])
    return out


def _opening_dict(kind, room, wall_index, lo, hi, bottom, top, report, at) -> dict | None:
    wall = room.walls[wall_index]
    width = hi - lo
    x, y = (float(v) for v in wall.point_at((lo + hi) / 2))
    here = f'the {kind} at ({x:.2f}, {y:.2f})'
    if not MIN_OPENING < width < MAX_OPENING:
        report.add('opening', f'{kind} width', at, f'{here} is {width:.2f} m wide, outside '
                   f'the {MIN_OPENING} to {MAX_OPENING} m of the layout schema')
        return None
    top = min(top, room.wall_height)
    pos = [round(x, 4), round(y, 4)]
    if kind == 'door':
        if top < MIN_DOOR_HEIGHT:
            report.add('opening', 'door height', at, f'{here} is {top:.2f} m high, lower '
                       f'than the {MIN_DOOR_HEIGHT} m of a door')
            return None
        return {'position': pos, 'width': round(width, 4), 'height': round(top, 4)}
    sill = max(bottom, 0.0)
    if not MIN_WINDOW_HEIGHT < top - sill < MAX_OPENING:
        report.add('opening', 'window height', at, f'{here} is {top - sill:.2f} m high, '
                   f'outside the {MIN_WINDOW_HEIGHT} to {MAX_OPENING} m of a window')
        return None
    return {'position': pos, 'width': round(width, 4), 'height': round(top - sill, 4),
            'sill': round(sill, 4)}


# ----------------------------------------------------------------------------- objects

def _objects(raw: RawRoom, room: Room, config: ImportConfig, report: ImportReport,
             at: str) -> list[dict[str, Any]]:
    kept: list[RawObject] = []
    seen: set[str] = set()
    for obj in raw.objects:
        if obj.source_id in seen:       # ids must name one object each for the support links
            obj.source_id = f'{obj.source_id}#{len(seen)}'
        seen.add(obj.source_id)
        why = _problem(obj, room, config)
        if why:
            report.add('object', why[0], at, f'object {obj.source_id}: {why[1]}')
            continue
        if obj.note:
            report.add('note', 'mapped with a guess', at, obj.note)
        if -config.on_floor <= obj.position[2] < 0:
            obj.position = (obj.position[0], obj.position[1], 0.0)
        kept.append(obj)
    support = _supports(raw, kept, config, room.wall_height, report, at)
    kept = [o for o in kept if support.get(o.source_id, '') is not None]
    names = _ids(kept)
    first = [o for o in kept if not support.get(o.source_id)]
    second = [o for o in kept if support.get(o.source_id)]
    return [_object_dict(o, names, support) for o in first + second]


def _problem(obj: RawObject, room: Room, config: ImportConfig) -> tuple[str, str] | None:
    """(reason, sentence) of why ``obj`` is dropped, or None."""
    if obj.problem:
        return obj.reason or 'unreadable', obj.problem
    lo, hi = config.scale_range
    if any(not lo <= s <= hi for s in obj.scale):
        scale = ', '.join(f'{s:.3g}' for s in obj.scale)
        return 'scale out of range', f'its scale ({scale}) is outside {lo:g} to {hi:g}'
    if not all(math.isfinite(v) and v > 0 for v in obj.size):
        return 'no size', 'its size is not positive'
    if not obj.category or len(obj.category) > 128:
        return 'unknown category', 'its category is empty or too long'
    x, y, z = obj.position
    outside = room.polygon.distance(Point(x, y))
    if outside > config.floor_tolerance:
        return 'outside floor', (f'its centre ({x:.2f}, {y:.2f}) is {outside:.2f} m outside '
                                 f'the floor')
    if z < -config.on_floor:
        return 'below floor', f'its bottom is {-z:.2f} m below the floor'
    return None


def _supports(raw: RawRoom, kept: list[RawObject], config: ImportConfig, ceiling: float,
              report: ImportReport, at: str) -> dict[str, str | None]:
    """source id -> the source id it stands on ('' none; None: dropped, its parent was).
    Without the data's links: the floor-standing object whose top is within the support
    tolerance of the object's bottom, whose footprint holds its centre and at least half
    its footprint (closest top wins); an object reaching the ceiling hangs from it."""
    ids = {o.source_id for o in kept}
    out: dict[str, str | None] = {}
    if raw.parent_links:
        for o in kept:
            if o.parent and o.parent not in ids:
                report.add('object', 'support dropped', at, f'object {o.source_id} stands on '
                           f'{o.parent}, which was not kept')
                out[o.source_id] = None
            else:
                out[o.source_id] = o.parent or ''
        return out
    floor = [o for o in kept if o.position[2] <= config.on_floor]
    feet = {o.source_id: footprint(o) for o in floor}
    for o in kept:
        out[o.source_id] = ''
        if o.position[2] <= config.on_floor or o.position[2] + o.size[2] >= ceiling - 0.05:
            continue          # on the floor, or hanging from the ceiling
        mine = footprint(o)
        best, gap = '', config.support_tolerance
        for p in floor:
            g = abs(o.position[2] - (p.position[2] + p.size[2]))
            if g <= gap and feet[p.source_id].covers(Point(o.position[:2])) \
                    and feet[p.source_id].intersection(mine).area >= 0.5 * mine.area:
                best, gap = p.source_id, g
        out[o.source_id] = best
    return out


def _ids(kept: list[RawObject]) -> dict[str, str]:
    """source id -> '<category>_<n>' (n counting from 0 per category, in source order)."""
    counts: dict[str, int] = {}
    out = {}
    for o in kept:
        stem = re.sub(r'[^a-z0-9]+', '_', o.category).strip('_')[:MAX_NAME] or 'object'
        n = counts.get(stem, 0)
        counts[stem] = n + 1
        out[o.source_id] = f'{stem}_{n}'
    return out


def _object_dict(o: RawObject, names: dict[str, str], support: dict) -> dict[str, Any]:
    d = {'id': names[o.source_id], 'category': o.category,
         'model_id': (o.model_id or 'unknown')[:128],
         'position': [round(float(v), 4) for v in o.position],
         'yaw': round(float(o.yaw), 6),
         'size': [round(max(float(v), 1e-4), 4) for v in o.size]}
    parent = support.get(o.source_id)
    if parent:
        d['support'] = names[parent]
    return d
