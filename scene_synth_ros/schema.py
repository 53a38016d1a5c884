"""Validated reading and writing of room layouts and scenes as JSON.

Everything that comes from outside (a ROS message, a file, a service request) goes through
here: the JSON Schema documents in ``msg_schemas/`` first, then the checks a schema cannot
express (geometry, room-type rules, support relations). Any problem raises
``SceneValidationError`` whose ``path`` names the offending field (``"room.floor[2]"``,
``"objects[3].size"``; ``""`` for the document itself) and whose message is one sentence.

Two JSON documents are read:

* a *room layout* (``parse_room_layout``): ``room_type``, ``floor``, optional
  ``wall_height``/``doors``/``windows`` and optional ``objects`` (a partial room) whose ``id``
  and ``model_id`` may be omitted and are then filled in;
* a *scene* (``parse_scene``): ``{"room": ..., "objects": [...], "meta": {...}}``, as written
  by ``dump_scene``; every object has an ``id`` and a ``model_id``.

Paths inside a layout are relative to the layout (``"floor[2]"``); inside a scene the room's
fields are under ``"room."``. Room types are stored under their canonical name
(``"living room"`` becomes ``"living"``), floors counter-clockwise.

The schemas are resolved locally through a ``referencing`` registry; nothing is fetched.
"""
from __future__ import annotations

from collections import Counter
from collections.abc import Mapping
from functools import lru_cache
import json
import math
import os
from pathlib import Path
import re
from typing import Any, Iterable

from jsonschema import Draft202012Validator
from jsonschema.exceptions import best_match
import numpy as np
from referencing import Registry
from referencing.jsonschema import DRAFT202012
import shapely

from . import catalog
from .categories import CATEGORIES, PAPER, RoomTypeSpec, Vocabulary
from .errors import SceneSynthError, UnknownRoomType, number, quoted, with_article
from .files import write_atomic
from .house import HOUSE_OVERLAP, Floors, House, HouseDoor, HouseScene, across
from .limits import LimitExceeded, YamlError, check_tree, join, loads, loads_yaml
from .paths import schema_dir
from .render import RoomDoesNotFit, room_frame_box
from .scene import DEFAULT_WALL_HEIGHT, Opening, PlacedObject, Room, Scene, ccw, fresh_id
from .thresholds import (
    CENTRE_OFF_FLOOR,
    MIN_FLOOR_AREA,
    MIN_VERTEX_SPACING,
    OPENING_TOLERANCE,
    SIZE_SLACK,
)

__all__ = [
    'SceneValidationError', 'parse_room_layout', 'parse_scene', 'load_scene', 'dump_scene',
    'save_scene', 'validate_scene_dict', 'validate_layout_dict', 'SCHEMA_IDS',
    'plain_json', 'check_against_schema', 'check_floor', 'format_json', 'read_payload',
    'parse_house_layout',
]

_BASE = 'https://scene-synth-ros.invalid/msg_schemas/'
SCHEMA_IDS = {
    'room_layout': _BASE + 'room_layout.schema.json',
    'placed_object': _BASE + 'placed_object.schema.json',
    'scene': _BASE + 'scene.schema.json',
    'house_scene': _BASE + 'house_scene.schema.json',
    'house_layout': _BASE + 'house_layout.schema.json',
}


class SceneValidationError(SceneSynthError, ValueError):
    """Invalid layout or scene. ``path`` names the field (``""``: the whole document)."""

    def __init__(self, message: str, path: str = ''):
        super().__init__(message)
        self.path = path

    def __reduce__(self):
        return (type(self), (str(self), self.path))


# ----------------------------------------------------------------------------- formatting

_join = join


def _path_of(prefix: str, parts: Iterable[str | int]) -> str:
    path = prefix
    for p in parts:
        path = _join(path, p)
    return path


def _name(path: str) -> str:
    """How a path reads in a message: the path, or 'the payload' for the document."""
    return path or 'the payload'


def _json_type(value: Any) -> str:
    if value is None:
        return 'null'
    if isinstance(value, bool):
        return 'boolean'
    if isinstance(value, (int, float)):
        return 'number'
    if isinstance(value, str):
        return 'string'
    if isinstance(value, list):
        return 'array'
    if isinstance(value, dict):
        return 'object'
    return type(value).__name__


_ARTICLE = {'array': 'an array', 'object': 'an object', 'integer': 'an integer',
            'number': 'a number', 'string': 'a string', 'boolean': 'a boolean', 'null': 'null'}

_UNITS = {'floor': ' m', 'position': ' m', 'size': ' m', 'width': ' m', 'height': ' m',
          'sill': ' m', 'wall_height': ' m', 'yaw': ' rad'}


def _unit(path: str) -> str:
    """The unit of the numeric field at ``path`` ('' when it has none)."""
    for part in reversed(path.replace('[', '.').split('.')):
        if part and not part[0].isdigit():
            return _UNITS.get(part, '')
    return ''


# ----------------------------------------------------------------------------- plumbing

def _plain(value: Any) -> Any:
    """A JSON-like copy: mappings -> dict, tuples -> lists, numpy scalars/arrays -> Python."""
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value


def plain_json(value: Any) -> Any:
    """``value`` as plain JSON values, once it is known to be within ``limits``."""
    try:
        check_tree(value)
    except LimitExceeded as e:
        raise SceneValidationError(str(e), e.path) from None
    return _plain(value)


def _load(text_or_dict: Any, yaml_ok: bool = False) -> Any:
    """The payload as plain JSON values, within ``limits`` (the type of the top level is
    checked by the schema). With ``yaml_ok``, text that is not JSON is read as YAML."""
    if isinstance(text_or_dict, (bytes, bytearray, str)):
        try:
            text_or_dict = loads(text_or_dict)
        except LimitExceeded as e:
            raise SceneValidationError(str(e), e.path) from None
        except UnicodeDecodeError as e:
            raise SceneValidationError(
                f'the payload is not valid UTF-8 text: byte {e.start} cannot be decoded',
                '') from None
        except json.JSONDecodeError as e:
            if not yaml_ok:
                raise SceneValidationError(f'the payload is not valid JSON: {_where(e)}',
                                           '') from None
            text_or_dict = _load_yaml(e.doc, e)
        except RecursionError:
            raise SceneValidationError('the payload is not valid JSON: it is nested too deeply',
                                       '') from None
        return plain_json(text_or_dict)
    if isinstance(text_or_dict, Mapping):
        return plain_json(text_or_dict)
    raise SceneValidationError(
        f'the payload must be JSON text or a dict, got {type(text_or_dict).__name__}', '')


def _where(e: json.JSONDecodeError) -> str:
    return f'{e.msg} at line {e.lineno} column {e.colno}'


# What a person who typed a Python dict (or pasted one: ``ros2 topic pub`` turns an unquoted
# mapping into one) needs to hear.
PYTHON_DICT_HINT = ("it reads as a Python dict: send JSON in single quotes, "
                    "data: '{\"room_type\": \"bedroom\", ...}'")


def looks_like_python_dict(text: Any) -> bool:
    """Whether ``text`` starts like a Python dict's repr (single-quoted keys), which is what
    a mapping given to ``ros2 topic pub`` for a string field arrives as."""
    return isinstance(text, str) and re.match(r"\s*\{\s*'[^']{0,200}'\s*:", text) is not None


def _load_yaml(text: str, json_error: json.JSONDecodeError) -> Any:
    try:
        return loads_yaml(text)
    except LimitExceeded as e:
        raise SceneValidationError(str(e), e.path) from None
    except YamlError as e:
        hint = f'; {PYTHON_DICT_HINT}' if looks_like_python_dict(text) else ''
        raise SceneValidationError(f'the payload is neither JSON ({_where(json_error)}) nor '
                                   f'YAML ({e}){hint}', '') from None


@lru_cache(maxsize=None)
def _schemas() -> dict[str, dict[str, Any]]:
    out = {}
    for key in SCHEMA_IDS:
        with open(schema_dir() / f'{key}.schema.json', encoding='utf-8') as f:
            out[key] = json.load(f)
    return out


@lru_cache(maxsize=None)
def _validator(key: str):
    schemas = _schemas()
    # No ``retrieve`` callable: a reference outside these three documents is an error,
    # never a download.
    registry = Registry().with_resources(
        (s['$id'], DRAFT202012.create_resource(s)) for s in schemas.values())
    return Draft202012Validator(schemas[key], registry=registry)


def _schema_error_message(error, prefix: str) -> tuple[str, str]:
    """(path, one-sentence message) for a jsonschema ValidationError."""
    path = _path_of(prefix, error.absolute_path)
    name = _name(path)
    kw = error.validator
    inst = error.instance
    val = error.validator_value
    if kw == 'required':
        missing = [k for k in val if isinstance(inst, dict) and k not in inst]
        key = missing[0] if missing else str(val)
        path = _join(path, key)
        return path, f'{path} is required but missing'
    if kw in ('additionalProperties', 'unevaluatedProperties'):
        known = set(error.schema.get('properties', {}))
        extra = [k for k in inst if k not in known] if isinstance(inst, dict) else []
        key = extra[0] if extra else '?'
        epath = _join(path, key)
        allowed = ', '.join(error.schema.get('properties', {})) or 'none'
        return epath, (f'{epath} is not a known field of {name} (allowed fields: {allowed})')
    if kw == 'type':
        types = [val] if isinstance(val, str) else list(val)
        expected = ' or '.join(_ARTICLE.get(t, t) for t in types)
        return path, f'{name} must be {expected}, got {_json_type(inst)}'
    if kw in ('minItems', 'maxItems'):
        lo = error.schema.get('minItems')
        hi = error.schema.get('maxItems')
        if lo is not None and lo == hi:
            need = f'exactly {lo}'
        elif kw == 'minItems':
            need = f'at least {val}'
        else:
            need = f'at most {val}'
        noun = 'vertices' if path.endswith('floor') else 'entries'
        return path, f'{name} must have {need} {noun}, got {len(inst)}'
    if kw == 'minLength':
        return path, f'{name} must not be empty'
    if kw == 'maxLength':
        return path, f'{name} must be at most {val} characters long, got {len(inst)}'
    bounds = {'minimum': 'at least', 'maximum': 'at most',
              'exclusiveMinimum': 'greater than', 'exclusiveMaximum': 'less than'}
    if kw in bounds:
        unit = _unit(path)
        return path, f'{name} must be {bounds[kw]} {number(val)}{unit}, got {number(inst)}{unit}'
    text = ' '.join(str(error.message).split())
    return path, f'{name} is invalid: {text}'


def check_against_schema(d: Any, key: str, prefix: str = '') -> None:
    error = best_match(_validator(key).iter_errors(d))
    if error is not None:
        path, message = _schema_error_message(error, prefix)
        raise SceneValidationError(message, path)


# ----------------------------------------------------------------------------- room checks

def _room_type(value: str, path: str, vocabulary: Vocabulary) -> str:
    try:
        return vocabulary.resolve(value)
    except UnknownRoomType:
        raise SceneValidationError(
            f'{path} {quoted(value)} is not a known room type (expected one of '
            f'{", ".join(vocabulary.room_types)}, or an alias such as \'living room\')',
            path) from None


def check_floor(points: list[list[float]], prefix: str) -> list[tuple[float, float]]:
    """The floor's vertices as the room keeps them (an explicit closing vertex dropped),
    after the checks that they make a simple polygon of a room's area."""
    path = _join(prefix, 'floor')
    pts = [(float(x), float(y)) for x, y in points]
    if len(pts) > 1 and math.dist(pts[0], pts[-1]) < MIN_VERTEX_SPACING:
        pts = pts[:-1]          # an explicitly closed ring: the closing vertex is allowed
    distinct = {(round(x / MIN_VERTEX_SPACING), round(y / MIN_VERTEX_SPACING)) for x, y in pts}
    if len(distinct) < 3:
        raise SceneValidationError(
            f'{path} must have at least 3 distinct vertices, got {len(distinct)}', path)
    for i in range(1, len(pts)):
        if math.dist(pts[i], pts[i - 1]) < MIN_VERTEX_SPACING:
            vpath = _join(path, i)
            raise SceneValidationError(
                f'{vpath} repeats the previous vertex ({number(pts[i][0])}, {number(pts[i][1])})',
                vpath)
    if math.dist(pts[-1], pts[0]) < MIN_VERTEX_SPACING:     # the ring closes past two
        vpath = _join(path, len(pts) - 1)
        raise SceneValidationError(
            f'{vpath} repeats the first vertex ({number(pts[0][0])}, {number(pts[0][1])}) '
            f'after the ring was already closed', vpath)
    arr = np.asarray(pts)
    centred = arr - arr.mean(axis=0)
    extent = float(np.abs(centred).max())
    if np.linalg.svd(centred, compute_uv=False)[-1] <= 1e-9 * max(extent, 1.0):
        raise SceneValidationError(
            f'{path} has zero area: all its vertices lie on one line', path)
    poly = shapely.Polygon(pts)
    if not poly.is_valid:
        reason = shapely.is_valid_reason(poly)
        where = ''
        if '[' in reason:
            coords = reason[reason.index('[') + 1:reason.rindex(']')].split()
            try:
                where = f' near ({number(float(coords[0]))}, {number(float(coords[1]))})'
            except (ValueError, IndexError):
                where = ''
        raise SceneValidationError(
            f'{path} is self-intersecting{where}: its edges must not cross or touch, so list '
            f'the vertices in order around the room', path)
    if poly.area < MIN_FLOOR_AREA:
        raise SceneValidationError(
            f'{path} encloses {number(poly.area)} m², less than the {number(MIN_FLOOR_AREA)} m² '
            f'minimum of a room', path)
    return pts


def _check_fits(room: Room, prefix: str, vocabulary: Vocabulary) -> None:
    """The room must be at most as long as a room may be, in its own axes: the question the
    networks' frame asks (``render.room_frame_box``), so every room accepted here can be
    furnished."""
    box = room_frame_box(room, vocabulary)
    if not box.fits:
        path = _join(prefix, 'floor')
        raise SceneValidationError(str(RoomDoesNotFit(box, path)), path)


def _check_openings(room: Room, prefix: str,
                    named: list[tuple[str, Opening]] | None = None, owner: str = '') -> None:
    """Each opening of ``room`` within the wall height, on one wall, not overlapping another;
    ``named``: (path, opening) of each, where the paths are not the room's own (a house's
    doors), and ``owner`` the room's name in the sentences then."""
    placed = []       # (path, wall index, start offset, end offset) of checked openings
    if named is None:
        named = ([(_join(_join(prefix, 'doors'), i), o) for i, o in enumerate(room.doors)]
                 + [(_join(_join(prefix, 'windows'), i), o)
                    for i, o in enumerate(room.windows)])
    for path, op in named:
        top = op.sill + op.height
        if top > room.wall_height + 1e-9:
            what = (f'sill {number(op.sill)} m + height {number(op.height)} m'
                    if op.kind == 'window' else f'height {number(op.height)} m')
            of = f' of {owner}' if owner else ''
            raise SceneValidationError(
                f'{path} reaches {number(top)} m ({what}), above the {number(room.wall_height)} m '
                f'wall height{of}', path)
        wall = room.wall_of(op, tol=OPENING_TOLERANCE)
        if wall is None:
            near = sorted(room.walls, key=lambda w: w.distance_to(op.position))
            dist = near[0].distance_to(op.position)
            if dist > OPENING_TOLERANCE:
                raise SceneValidationError(
                    f'{path} is not on any wall: its centre is {number(dist)} m from the '
                    f'nearest wall', path)
            on_line = [w for w in near if w.distance_to(op.position) <= OPENING_TOLERANCE]
            longest = max(on_line, key=lambda w: w.length)
            wname = (f'the wall from {_join(_join(prefix, "floor"), longest.index)} to '
                     f'{_join(_join(prefix, "floor"), (longest.index + 1) % len(room.walls))}')
            if op.width > longest.length + OPENING_TOLERANCE:
                raise SceneValidationError(
                    f'{path} is wider ({number(op.width)} m) than {wname} '
                    f'({number(longest.length)} m long)', path)
            raise SceneValidationError(
                f'{path} runs past the end of {wname}: its {number(op.width)} m width must lie '
                f'on one wall', path)
        off = wall.offset_of(op.position)
        lo, hi = off - op.width / 2.0, off + op.width / 2.0
        for other_path, other_wall, olo, ohi in placed:
            overlap = min(hi, ohi) - max(lo, olo)
            if other_wall == wall.index and overlap > OPENING_TOLERANCE:
                raise SceneValidationError(
                    f'{path} overlaps {other_path} on the same wall by {number(overlap)} m',
                    path)
        placed.append((path, wall.index, lo, hi))


def _build_room(d: dict[str, Any], prefix: str, vocabulary: Vocabulary) -> Room:
    """The Room of an (already schema-valid) room dict, after the geometric checks."""
    room_type = _room_type(d['room_type'], _join(prefix, 'room_type'), vocabulary)
    room = Room.from_dict({**d, 'room_type': room_type,
                           'floor': ccw(check_floor(d['floor'], prefix))})
    _check_fits(room, prefix, vocabulary)
    _check_openings(room, prefix)
    return room


# ----------------------------------------------------------------------------- object checks

def _range(lo: float, hi: float) -> str:
    return f'{number(lo * (1 - SIZE_SLACK))} to {number(hi * (1 + SIZE_SLACK))} m'


def _build_objects(items: list[dict[str, Any]], room: Room, prefix: str,
                   models: catalog.Catalog | None, vocabulary: Vocabulary) -> list[PlacedObject]:
    """PlacedObjects of (already schema-valid) object dicts, checked against the room;
    missing ids and model ids (from ``models``, default the procedural catalog) are filled
    in."""
    models = catalog.PROCEDURAL if models is None else models
    spec = vocabulary.spec(room.room_type)
    seen: dict[str, int] = {}
    for i, d in enumerate(items):
        _check_object(d, _join(prefix, i), room, spec, models, vocabulary)
        if d.get('id') is not None:
            ipath = _join(_join(prefix, i), 'id')
            if d['id'] in seen:
                first = _join(prefix, seen[d['id']])
                raise SceneValidationError(
                    f'{ipath} {quoted(d["id"])} is already the id of {first}', ipath)
            seen[d['id']] = i
    for i in range(len(items)):
        _check_support(items, i, seen, _join(_join(prefix, i), 'support'), room, spec)

    objects: list[PlacedObject] = []
    for d in _fill_ids(items):
        size = tuple(float(v) for v in d['size'])
        model_id = d.get('model_id')
        if model_id is None:
            model_id = models.nearest(d['category'], size[0], size[1], spec.room_type,
                                      vocabulary).model_id
        objects.append(PlacedObject.from_dict({**d, 'model_id': model_id}))
    return objects


def _check_object(d: dict[str, Any], path: str, room: Room, spec: RoomTypeSpec,
                  models: catalog.Catalog = catalog.PROCEDURAL,
                  vocabulary: Vocabulary = PAPER) -> None:
    """One object dict's category, size, position and model id against the room."""
    category = d['category']
    cpath = _join(path, 'category')
    if category not in spec and category not in CATEGORIES:
        raise SceneValidationError(
            f'{cpath} {quoted(category)} is not a known category', cpath)
    if category not in spec:
        raise SceneValidationError(
            f'{cpath} {quoted(category)} is not a category of {with_article(room.room_type)} '
            f'({with_article(room.room_type)} may hold: {", ".join(spec.names)})', cpath)
    info = spec.info(category)
    w, dep, h = (float(v) for v in d['size'])
    if not info.size_is_plausible(w, dep, h, SIZE_SLACK):
        spath = _join(path, 'size')
        bad = [f'{label} {number(v)} m is outside {_range(*rng)}'
               for label, v, rng in (('width', w, info.width), ('depth', dep, info.depth),
                                     ('height', h, info.height))
               if not rng[0] * (1 - SIZE_SLACK) <= v <= rng[1] * (1 + SIZE_SLACK)]
        raise SceneValidationError(
            f'{spath} is not plausible for {with_article(category)}: {"; ".join(bad)}', spath)
    x, y, z = (float(v) for v in d['position'])
    if z < -CENTRE_OFF_FLOOR:
        zpath = _join(_join(path, 'position'), 2)
        raise SceneValidationError(
            f'{zpath} is {number(z)} m, below the floor (z is the bottom of the object)',
            zpath)
    outside = room.polygon.distance(shapely.Point(x, y))
    if outside > CENTRE_OFF_FLOOR:
        ppath = _join(path, 'position')
        raise SceneValidationError(
            f'{ppath} is outside the floor: the centre ({number(x)}, {number(y)}) is '
            f'{number(outside)} m outside the room', ppath)
    if d.get('model_id') is not None:
        mpath = _join(path, 'model_id')
        try:
            model = models.get(d['model_id'], vocabulary)
        except KeyError:
            raise SceneValidationError(
                f'{mpath} {quoted(d["model_id"])} is not a catalog model id', mpath) from None
        if model.category != category:
            raise SceneValidationError(
                f'{mpath} {quoted(d["model_id"])} is {with_article(model.category)} model, not '
                f'{with_article(category)}', mpath)


def _check_support(items: list[dict[str, Any]], i: int, seen: dict[str, int], spath: str,
                   room: Room, spec: RoomTypeSpec) -> None:
    """Object ``i`` has a support iff it is second tier, and the support (``seen``: id ->
    index) is another object that can hold it."""
    category = items[i]['category']
    support = items[i].get('support')
    if spec.info(category).tier == 'first':
        if support is not None:
            raise SceneValidationError(
                f'{spath} must be absent because {with_article(category)} stands on the '
                f'floor (first tier), got {quoted(support)}', spath)
        return
    parents = spec.supports(category)
    if support is None:
        raise SceneValidationError(
            f'{spath} is required because {with_article(category)} stands on another '
            f'object (one of {", ".join(parents)})', spath)
    if support not in seen:
        raise SceneValidationError(
            f'{spath} {quoted(support)} is not the id of any object in the scene', spath)
    if seen[support] == i:
        raise SceneValidationError(f'{spath} names the object itself', spath)
    parent_category = items[seen[support]]['category']
    if parent_category not in parents:
        raise SceneValidationError(
            f'{spath} {quoted(support)} is {with_article(parent_category)}, which cannot hold '
            f'{with_article(category)} in {with_article(room.room_type)} '
            f'(allowed: {", ".join(parents)})', spath)


def _fill_ids(items: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Copies of the object dicts with ``id`` filled in where missing (``Scene.new_id``'s
    order: given ids are reserved first, then missing ones are assigned in list order)."""
    given = [d for d in items if d.get('id') is not None]
    taken = {str(d['id']) for d in given}
    counts = Counter(d['category'] for d in given)
    out = []
    for d in items:
        d = dict(d)
        if d.get('id') is None:
            d['id'] = fresh_id(d['category'], taken, counts[d['category']])
            taken.add(d['id'])
            counts[d['category']] += 1
        out.append(d)
    return out


# ----------------------------------------------------------------------------- public API

def validate_layout_dict(d: Any, vocabulary: Vocabulary = PAPER) -> None:
    """Raise SceneValidationError unless ``d`` is a valid room layout (objects optional)."""
    _layout_to_scene(plain_json(d), vocabulary=vocabulary)


def validate_scene_dict(d: Any, vocabulary: Vocabulary = PAPER) -> None:
    """Raise SceneValidationError unless ``d`` is a valid scene dict."""
    _scene_from_dict(plain_json(d), vocabulary=vocabulary)


def _layout_to_scene(d: Any, models: catalog.Catalog | None = None,
                     vocabulary: Vocabulary = PAPER) -> Scene:
    check_against_schema(d, 'room_layout')
    room = _build_room(d, '', vocabulary)
    items = d.get('objects', [])
    objects = _build_objects(items, room, 'objects', models, vocabulary)
    return Scene(room, objects, {'request_id': d['request_id']} if 'request_id' in d else {})


# ----------------------------------------------------------------------------- houses

class _HouseRooms:
    """The checked rooms of a house layout, the names its sentences give them, and where
    they are (``house.Floors``)."""

    def __init__(self, d: dict[str, Any], vocabulary: Vocabulary):
        self.ids: dict[str, int] = {}
        for i, rd in enumerate(d['rooms']):
            if rd['id'] in self.ids:
                path = f'rooms[{i}].id'
                raise SceneValidationError(
                    f'{path} {quoted(rd["id"])} is the id of rooms[{self.ids[rd["id"]]}] too: '
                    'room ids must be unique', path)
            self.ids[rd['id']] = i
        height = d.get('wall_height', DEFAULT_WALL_HEIGHT)
        self.rooms = [_build_room({**rd, 'wall_height': rd.get('wall_height', height),
                                   'doors': []}, f'rooms[{i}]', vocabulary)
                      for i, rd in enumerate(d['rooms'])]
        self.names = [f'rooms[{i}] ({quoted(rd["id"])})' for i, rd in enumerate(d['rooms'])]
        self.floors = Floors(self.rooms)
        polygons = self.floors.polygons
        for i, j in zip(*self.floors.tree.query(polygons, predicate='intersects'), strict=True):
            if i < j:
                shared = polygons[i].intersection(polygons[j]).area
                if shared > HOUSE_OVERLAP:
                    path = f'rooms[{j}].floor'
                    raise SceneValidationError(
                        f'{path} overlaps {self.names[i]} by {number(shared)} m²: the rooms of '
                        'a house must not overlap, only share walls', path)


def _house_door(dd: dict[str, Any], path: str, house: _HouseRooms) -> HouseDoor:
    """A (schema-valid) door of a house layout, after the checks that the rooms it names
    exist and share the wall it lies on (back to back within a wall's thickness, no third
    room between them), and that an entrance leads into no room; each room's opening is
    on that room's wall."""
    members, names = [], house.names
    for k, rid in enumerate(dd['rooms']):
        if rid not in house.ids:
            rpath = f'{path}.rooms[{k}]'
            raise SceneValidationError(
                f'{rpath} {quoted(rid)} is not the id of a room of the house', rpath)
        members.append(house.ids[rid])
    if len(members) == 2 and members[0] == members[1]:
        raise SceneValidationError(f'{path}.rooms names {quoted(dd["rooms"][0])} twice: a '
                                   'door joins two rooms, or leads out of one', path)
    opening = Opening('door', (float(dd['position'][0]), float(dd['position'][1])),
                      float(dd['width']), float(dd['height']))
    walls = house.floors.on_walls(opening)
    home = next((i for i in members if i in walls), None)
    if home is None:
        elsewhere = f': it is on a wall of {names[next(iter(walls))]}' if walls else ''
        raise SceneValidationError(f'{path} is not on a wall of {names[members[0]]}{elsewhere}',
                                   path)
    behind = house.floors.behind(opening, walls[home], home)
    if len(members) == 1:
        if behind:
            raise SceneValidationError(
                f'{path} leads outside from {names[home]} but lies on the wall it shares '
                f'with {names[behind[0]]}: name both rooms for a door between them', path)
        return HouseDoor(tuple(dd['rooms']), opening, {dd['rooms'][0]: opening})
    other = next(i for i in members if i != home)
    moved = opening if other in walls else across(house.rooms[other], opening, walls[home])
    if other not in behind or moved is None:
        raise SceneValidationError(
            f'{path} is on a wall of {names[home]} that {names[other]} does not share along '
            'its whole width: the door must lie on the wall between them', path)
    if len(behind) > 1:
        third = next(i for i in behind if i != other)
        raise SceneValidationError(
            f'{path} between {names[home]} and {names[other]} also opens into '
            f'{names[third]}: a door joins two rooms', path)
    return HouseDoor(tuple(dd['rooms']), opening,
                     {dd['rooms'][0]: opening if members[0] == home else moved,
                      dd['rooms'][1]: opening if members[1] == home else moved})


def _house_from_dict(d: Any, vocabulary: Vocabulary = PAPER) -> House:
    check_against_schema(d, 'house_layout')
    house = _HouseRooms(d, vocabulary)
    names = house.names
    for i, room in enumerate(house.rooms):
        for k, window in enumerate(room.windows):
            behind = house.floors.behind(window, room.wall_of(window, OPENING_TOLERANCE), i)
            if behind:
                path = f'rooms[{i}].windows[{k}]'
                raise SceneValidationError(
                    f'{path} is on the wall {names[i]} shares with {names[behind[0]]}: '
                    'windows go on outside walls', path)
    doors, named = [], [[] for _ in house.rooms]
    for j, dd in enumerate(d['doors']):
        door = _house_door(dd, f'doors[{j}]', house)
        for rid, opening in door.openings.items():
            named[house.ids[rid]].append((f'doors[{j}]', opening))
        doors.append(door)
    out = {}
    for i, (room, rd) in enumerate(zip(house.rooms, d['rooms'], strict=True)):
        room = Room(room.room_type, room.floor, room.wall_height,
                    tuple(o for _, o in named[i]), room.windows)
        _check_openings(room, f'rooms[{i}]', named[i] + [
            (f'rooms[{i}].windows[{k}]', w) for k, w in enumerate(room.windows)], names[i])
        out[rd['id']] = room
    result = House(out, tuple(doors),
                   {'request_id': d['request_id']} if 'request_id' in d else {})
    if not result.entrances:
        raise SceneValidationError('doors has no entrance: a house needs a door that names '
                                   'one room and leads outside', 'doors')
    reached = set(result.reachable())
    for i, rid in enumerate(out):
        if rid not in reached:
            raise SceneValidationError(f'{names[i]} cannot be reached from an entrance through '
                                       'the doors', f'rooms[{i}]')
    return result


def parse_house_layout(text_or_dict: Any, vocabulary: Vocabulary = PAPER) -> House:
    """A house layout (JSON or YAML text, bytes or dict) as a validated House
    (``msg_schemas/house_layout.schema.json``; see ``house``)."""
    d = _load(text_or_dict, yaml_ok=True)
    try:
        return _house_from_dict(d, vocabulary)
    except SceneValidationError as e:
        if looks_like_python_dict(text_or_dict):
            raise SceneValidationError(f'{e}; {PYTHON_DICT_HINT}', e.path) from None
        raise


def _house_scene_from_dict(d: Any, models: catalog.Catalog | None = None,
                           vocabulary: Vocabulary = PAPER) -> HouseScene:
    check_against_schema(d, 'house_scene')
    layout = {k: v for k, v in d.items() if k != 'meta'}
    layout['rooms'] = [{k: v for k, v in r.items() if k != 'objects'} for r in d['rooms']]
    house = _house_from_dict(layout, vocabulary)
    scenes = {}
    for i, rd in enumerate(d['rooms']):
        room = house.rooms[rd['id']]
        scenes[rd['id']] = Scene(room, _build_objects(rd.get('objects', []), room,
                                                      f'rooms[{i}].objects', models, vocabulary))
    return HouseScene(house, scenes, dict(d.get('meta', {})))


def parse_house_scene(text_or_dict: Any, models: catalog.Catalog | None = None,
                      vocabulary: Vocabulary = PAPER) -> HouseScene:
    """A house scene (JSON text, bytes or dict; ``msg_schemas/house_scene.schema.json``) as
    a validated HouseScene: the house checked as ``parse_house_layout`` checks it, each
    room's objects as ``parse_scene`` checks a room's."""
    return _house_scene_from_dict(_load(text_or_dict), models, vocabulary)


def dump_house_scene(scene: HouseScene, models: catalog.Catalog | None = None,
                     vocabulary: Vocabulary = PAPER) -> str:
    """The house scene as JSON text, validated first, as ``dump_scene`` does a room's."""
    d = plain_json(scene.to_dict())
    _house_scene_from_dict(d, models, vocabulary)
    return _formatted(d)


def _scene_from_dict(d: Any, models: catalog.Catalog | None = None,
                     vocabulary: Vocabulary = PAPER) -> Scene:
    check_against_schema(d, 'scene')
    room = _build_room(d['room'], 'room', vocabulary)
    objects = _build_objects(d.get('objects', []), room, 'objects', models, vocabulary)
    return Scene(room, objects, dict(d.get('meta', {})))


def parse_room_layout(text_or_dict: Any, catalog: catalog.Catalog | None = None,
                      vocabulary: Vocabulary = PAPER) -> Scene:
    """A room layout (JSON or YAML text, bytes or dict), possibly with objects, as a
    validated Scene.

    Missing object ids are assigned with ``Scene.new_id`` and missing model ids with
    ``catalog.nearest``; the room type becomes its canonical name. The scene's meta holds
    the layout's ``request_id``, if it has one, and nothing else. Model ids are those of
    ``catalog`` (a user catalog, ``catalog.Catalog``; default: the procedural one), here and
    in every reader and writer below. The room types and categories known are those of
    ``vocabulary`` (default: the paper's; a synthesizer's are ``Synthesizer.vocabulary``),
    here and below too.
    """
    d = _load(text_or_dict, yaml_ok=True)
    try:
        return _layout_to_scene(d, catalog, vocabulary)
    except SceneValidationError as e:
        if looks_like_python_dict(text_or_dict):
            raise SceneValidationError(f'{e}; {PYTHON_DICT_HINT}', e.path) from None
        raise


def is_house(d: Any) -> bool:
    """Whether a layout's or scene's dict is a house's: its rooms, and neither a room nor a
    room type of its own."""
    return isinstance(d, dict) and 'rooms' in d and 'room' not in d and 'room_type' not in d


def parse_layout(text_or_dict: Any, catalog: catalog.Catalog | None = None,
                 vocabulary: Vocabulary = PAPER) -> Scene | HouseScene:
    """A room layout as ``parse_room_layout`` reads it, or a house layout (``is_house``),
    its rooms possibly holding objects, as a HouseScene."""
    d = _load(text_or_dict, yaml_ok=True)
    try:
        if is_house(d):
            return _house_scene_from_dict(d, catalog, vocabulary)
        return _layout_to_scene(d, catalog, vocabulary)
    except SceneValidationError as e:
        if looks_like_python_dict(text_or_dict):
            raise SceneValidationError(f'{e}; {PYTHON_DICT_HINT}', e.path) from None
        raise


def read_payload(text_or_dict: Any) -> Any:
    """JSON or YAML text (or a dict) as plain JSON values within ``limits``, before any
    schema check (SceneValidationError otherwise)."""
    return _load(text_or_dict, yaml_ok=True)


def parse_scene(text_or_dict: Any, catalog: catalog.Catalog | None = None,
                vocabulary: Vocabulary = PAPER) -> Scene:
    """A scene (JSON text, bytes or dict, as written by ``dump_scene``) as a validated Scene."""
    return _scene_from_dict(_load(text_or_dict), catalog, vocabulary)


def load_scene(path: str | os.PathLike, catalog: catalog.Catalog | None = None,
               vocabulary: Vocabulary = PAPER) -> Scene:
    """Read a scene file; a file whose top level has no ``"room"`` is read as a room layout.

    I/O errors (a missing file, ...) propagate as OSError.
    """
    layout = load_layout(path, catalog, vocabulary)
    if isinstance(layout, HouseScene):
        raise SceneValidationError('rooms: this is a house layout, and a room or scene is '
                                   'expected here', 'rooms')
    return layout


def load_layout(path: str | os.PathLike, catalog: catalog.Catalog | None = None,
                vocabulary: Vocabulary = PAPER) -> Scene | HouseScene:
    """Read a layout or scene file: a house (a top level with ``"rooms"``: a house layout,
    or a house scene with its objects) as a HouseScene, else as ``load_scene`` reads it."""
    return parse_document(Path(path).read_text(encoding='utf-8'), catalog, vocabulary)


def parse_document(text_or_dict: Any, catalog: catalog.Catalog | None = None,
                   vocabulary: Vocabulary = PAPER) -> Scene | HouseScene:
    """A layout or scene (JSON or YAML text, bytes or dict), whichever it is: a house layout
    or house scene (``is_house``) as a HouseScene, a room layout as ``parse_room_layout``
    reads it, a scene as ``parse_scene`` does."""
    d = _load(text_or_dict, yaml_ok=True)
    if is_house(d):
        return _house_scene_from_dict(d, catalog, vocabulary)
    if isinstance(d, dict) and 'room' not in d:
        return _layout_to_scene(d, catalog, vocabulary)
    return _scene_from_dict(d, catalog, vocabulary)


def dump_scene(scene: Scene, catalog: catalog.Catalog | None = None,
               vocabulary: Vocabulary = PAPER) -> str:
    """The scene as JSON text, validated first (an invalid scene raises
    SceneValidationError, so nothing invalid is ever written)."""
    d = plain_json(scene.to_dict())
    _scene_from_dict(d, catalog, vocabulary)
    return _formatted(d)


def _formatted(d: dict) -> str:
    """A validated scene's (or house scene's) dict as ``format_json`` text."""
    try:
        return format_json(d)
    except (TypeError, ValueError) as e:
        raise SceneValidationError(
            f'meta cannot be written as JSON: {" ".join(str(e).split())}', 'meta') from None


def format_json(value: Any, indent: int = 0) -> str:
    """JSON with an indented structure but numeric arrays (points, sizes) on one line."""
    flat = json.dumps(value, allow_nan=False, ensure_ascii=False, separators=(', ', ': '))
    if not isinstance(value, (dict, list)) or (
            len(flat) + indent <= 96 and not _has_dict(value)) or not value:
        return flat
    pad, inner = ' ' * indent, ' ' * (indent + 2)
    if isinstance(value, list):
        body = ',\n'.join(inner + format_json(v, indent + 2) for v in value)
        return f'[\n{body}\n{pad}]'
    body = ',\n'.join(f'{inner}{json.dumps(str(k), ensure_ascii=False)}: '
                      f'{format_json(v, indent + 2)}' for k, v in value.items())
    return f'{{\n{body}\n{pad}}}'


def _has_dict(value: Any) -> bool:
    if isinstance(value, dict):
        return True
    return isinstance(value, list) and any(_has_dict(v) for v in value)


def save_scene(scene: Scene, path: str | os.PathLike,
               catalog: catalog.Catalog | None = None, vocabulary: Vocabulary = PAPER) -> None:
    """Validate ``scene`` and write it as JSON to ``path`` (via a temporary file, so a failed
    write never leaves a half-written scene behind)."""
    write_atomic(path, dump_scene(scene, catalog, vocabulary) + '\n')


# What the importers of other data sets (``datasets``) reuse for scenes whose categories are
# the data set's own: the same limits, JSON schemas, floor checks and file layout.
