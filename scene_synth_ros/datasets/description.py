"""The data-set description (``dataset.yaml``): what a data set's rooms hold, per room type,
derived from the imported scenes and meant to be read and edited by a person.

Per room type: ``rooms``; ``size_cap`` (the side in metres of the square its images cover:
the package's square for its own room types, else the room-size filter's, else the largest
room's span rounded up to 0.5 m); doors and
windows per room; and per category:

* ``count`` (objects), ``per_room`` (count / rooms: the paper's frequency), ``rooms_with``;
* ``tier``: ``first`` (stands on the floor), ``second`` (stands on another object: the
  data's parent link, or the geometry, see ``assemble.py``) or ``mounted`` (neither: wall
  and ceiling fixtures); the majority of the category's objects decides;
* ``supported_by``: for the second tier, parent category -> how many of its objects stand
  on one;
* ``against_wall``: whether most of its objects have their back within ``WALL_GAP`` of a
  wall (``back_gap``);
* ``roles``: what it is for, as the design rules ask it (``categories.ROLES``: bed, table
  seat, storage, ...); written for the categories the paper's table names, to be edited for
  the others;
* ``width``, ``depth``, ``height``: min, median and max in metres (our convention: width
  across the front, depth back to front);
* ``importance``: the package's importance (``categories.RoomCategorySpec``): the mean
  footprint of the size range, ((width min + max) / 2) x ((depth min + max) / 2), times
  ``per_room``; ``importance_order`` lists the categories by it, as
  ``RoomTypeSpec.importance_order`` does.

Beside the room types, ``allowance``: what the data set's rooms do that the strict validity
checks refuse (chairs tucked under tables, things inside shelves; ``allowance.Allowance``,
derived at import by ``datasets.allowance``); the evaluation holds the data set's rooms, real
and synthesized, to it.

This carries what ``categories.RoomTypeSpec`` / ``CategoryInfo`` hold (room count, size
cap, doors and windows per room, per category its count, frequency, tier, size ranges,
parents, against-wall flag, roles and importance). ``load`` reads a (possibly edited) file back
and checks it; each problem is one sentence (``DatasetError``).
"""
from __future__ import annotations

from collections import Counter, defaultdict
from dataclasses import dataclass, field
import math
from pathlib import Path
from typing import Any, Iterable

import numpy as np
from shapely.geometry import LineString, Point, Polygon
import yaml

from ..allowance import STRICT, Allowance
from ..categories import ROLES, ROOM_SIZE_CAP, roles_of
from ..errors import DatasetError, quoted
from ..files import write_atomic
from ..scene import Room
from .assemble import room_span
from .config import ImportConfig

FILE_NAME = 'dataset.yaml'
VERSION = 1
TIERS = ('first', 'second', 'mounted')
WALL_GAP = 0.25          # m: a back this close to a wall is against it
RAY = 50.0               # m: farther than any wall of a room


# ----------------------------------------------------------------------------- geometry

def side_gaps(obj: dict[str, Any], floor: Polygon) -> dict[str, float]:
    """Distance from the middle of each side of the object's footprint (back, front, left,
    right) straight out to the room's boundary (0 where that middle is outside already)."""
    x, y = obj['position'][0], obj['position'][1]
    w, d = obj['size'][0], obj['size'][1]
    yaw = obj['yaw']
    fx, fy = math.cos(yaw), math.sin(yaw)
    lx, ly = -fy, fx                       # the object's left (local +y)
    sides = {'back': (-fx, -fy, d / 2), 'front': (fx, fy, d / 2),
             'left': (lx, ly, w / 2), 'right': (-lx, -ly, w / 2)}
    out = {}
    boundary = floor.exterior
    for name, (ux, uy, half) in sides.items():
        mx, my = x + ux * half, y + uy * half
        if not floor.covers(Point(mx, my)):
            out[name] = 0.0
            continue
        hit = LineString([(mx, my), (mx + ux * RAY, my + uy * RAY)]).intersection(boundary)
        out[name] = float(Point(mx, my).distance(hit)) if not hit.is_empty else RAY
    return out


def back_gap(obj: dict[str, Any], floor: Polygon) -> float:
    return side_gaps(obj, floor)['back']


def back_to_nearest_wall(obj: dict[str, Any], floor: Polygon, slack: float = 0.05) -> bool:
    """Whether the wall nearest to the object is behind it: its back's gap is the smallest
    of the four (within ``slack``, for objects in a corner)."""
    gaps = side_gaps(obj, floor)
    return gaps['back'] <= min(gaps.values()) + slack


# ----------------------------------------------------------------------------- describe

def _tier(obj: dict[str, Any], on_floor: float) -> str:
    if obj.get('support'):
        return 'second'
    return 'first' if obj['position'][2] <= on_floor else 'mounted'


def _stats(values: list[float]) -> dict[str, float]:
    a = np.asarray(values, dtype=float)
    return {'min': round(float(a.min()), 3), 'median': round(float(np.median(a)), 3),
            'max': round(float(a.max()), 3)}


def importance(cat: dict[str, Any]) -> float:
    """The package's importance of a category entry (see the module docstring)."""
    w, d = cat['width'], cat['depth']
    return (w['min'] + w['max']) / 2 * (d['min'] + d['max']) / 2 * cat['per_room']


@dataclass
class _Seen:
    """One object as the description needs it: a few numbers, not the scene."""

    size: tuple[float, float, float]
    tier: str
    parent: str | None          # the category it stands on
    back_gap: float


@dataclass
class _TypeTally:
    rooms: int = 0
    doors: int = 0
    windows: int = 0
    largest: float = 0.0                     # the longest span of a room, metres
    objects: dict = field(default_factory=lambda: defaultdict(list))   # category -> [_Seen]
    rooms_with: Counter = field(default_factory=Counter)


class Describer:
    """Collects scenes one at a time (an import of thousands of rooms keeps only a few
    numbers per object) and gives the description's dict."""

    def __init__(self, fmt: str, config: ImportConfig | None = None):
        self.fmt = fmt
        self.config = config or ImportConfig()
        self.types: dict[str, _TypeTally] = defaultdict(_TypeTally)

    def add(self, scene: dict[str, Any]) -> None:
        room = scene['room']
        tally = self.types[room['room_type']]
        tally.rooms += 1
        tally.doors += len(room.get('doors', []))
        tally.windows += len(room.get('windows', []))
        floor = Polygon(room['floor'])
        span = room_span(Room(room['room_type'], tuple(map(tuple, room['floor']))))
        tally.largest = max(tally.largest, *span)
        ids = {o['id']: o['category'] for o in scene['objects']}
        for o in scene['objects']:
            tally.objects[o['category']].append(_Seen(
                tuple(o['size']), _tier(o, self.config.on_floor), ids.get(o.get('support')),
                back_gap(o, floor)))
        tally.rooms_with.update(set(ids.values()))

    def result(self) -> dict[str, Any]:
        """The description (a plain dict, as written to YAML)."""
        types = {rt: self._type(rt, t) for rt, t in sorted(self.types.items())}
        c = self.config
        return {'version': VERSION, 'format': self.fmt,
                'filters': {'scale_range': list(c.scale_range),
                            'object_count': list(c.object_count),
                            'room_size': {rt: c.size_limit(rt) for rt in types},
                            'floor_tolerance': c.floor_tolerance},
                'room_types': types}

    def _type(self, rt: str, t: _TypeTally) -> dict[str, Any]:
        cats = {name: _with_roles(name, _category(seen, t.rooms, t.rooms_with[name]))
                for name, seen in sorted(t.objects.items(), key=lambda kv: (-len(kv[1]), kv[0]))}
        # The square a type's images cover: the package's for its own room types (a larger
        # room is seen larger at the same pixels), else the room-size filter's, else the
        # largest room's.
        cap = ROOM_SIZE_CAP.get(rt, self.config.size_limit(rt))
        if cap is None:
            cap = math.ceil(t.largest * 2) / 2
        return {'rooms': t.rooms, 'size_cap': float(cap),
                'doors_per_room': round(t.doors / t.rooms, 3),
                'windows_per_room': round(t.windows / t.rooms, 3),
                'importance_order': sorted(cats, key=lambda c: -cats[c]['importance']),
                'categories': cats}


def describe(scenes: Iterable[dict[str, Any]], fmt: str,
             config: ImportConfig | None = None) -> dict[str, Any]:
    """The description of imported scene dicts (``Describer`` over all of them)."""
    d = Describer(fmt, config)
    for s in scenes:
        d.add(s)
    return d.result()


def _category(seen: list[_Seen], rooms: int, rooms_with: int) -> dict[str, Any]:
    tiers = Counter(x.tier for x in seen)
    tier = max(TIERS, key=lambda t: (tiers[t], -TIERS.index(t)))
    parents = Counter(x.parent for x in seen if x.parent)
    against = sum(x.back_gap <= WALL_GAP for x in seen)
    entry = {'count': len(seen), 'per_room': round(len(seen) / rooms, 4),
             'rooms_with': rooms_with, 'tier': tier,
             'supported_by': dict(parents.most_common()) if tier == 'second' else {},
             'against_wall': bool(against * 2 > len(seen)),
             'width': _stats([x.size[0] for x in seen]),
             'depth': _stats([x.size[1] for x in seen]),
             'height': _stats([x.size[2] for x in seen])}
    entry['importance'] = round(importance(entry), 5)
    return entry


def _with_roles(name: str, entry: dict[str, Any]) -> dict[str, Any]:
    """``entry`` with the roles the paper's table gives category ``name``, where it has any."""
    roles = roles_of(name)
    return {**entry, 'roles': sorted(roles)} if roles else entry


HEADER = """\
# Data-set description written by `scene-synth import` (scene_synth_ros.datasets.description).
# Per room type: rooms, size_cap (side of the square its rooms fit in, m), doors and windows
# per room, the categories by importance, and per category: count, per_room (frequency),
# rooms_with, tier (first: on the floor, second: on another object, mounted: neither),
# supported_by (second tier: parent category -> objects), against_wall, width / depth /
# height (min, median, max in metres; width across the front, depth back to front) and
# importance (mean footprint of the size range x per_room); then the allowance (what these
# rooms do that the strict validity checks refuse: tucks, inside, settle, door_depth). Edit
# freely (merge or drop categories, fix a tier); `scene_synth_ros.datasets.description.load`
# checks the result.
"""


def write(desc: dict[str, Any], path: Path) -> None:
    write_atomic(path, HEADER + yaml.safe_dump(desc, sort_keys=False, allow_unicode=True,
                                               width=100, default_flow_style=None))


# ----------------------------------------------------------------------------- load

@dataclass(frozen=True)
class CategoryDescription:
    name: str
    count: int
    per_room: float
    tier: str
    supported_by: tuple[str, ...]
    against_wall: bool
    width: tuple[float, float, float]       # min, median, max
    depth: tuple[float, float, float]
    height: tuple[float, float, float]
    importance: float
    roles: frozenset[str] = frozenset()


@dataclass(frozen=True)
class RoomTypeDescription:
    room_type: str
    rooms: int
    size_cap: float
    doors_per_room: float
    windows_per_room: float
    categories: tuple[CategoryDescription, ...]
    importance_order: tuple[str, ...]

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(c.name for c in self.categories)


@dataclass(frozen=True)
class DatasetDescription:
    format: str
    room_types: dict[str, RoomTypeDescription]
    allowance: Allowance = STRICT


def load(path: str | Path) -> DatasetDescription:
    """Read and check a description file; any problem is one sentence naming the field."""
    path = Path(path)
    try:
        data = yaml.safe_load(path.read_text(encoding='utf-8'))
    except OSError as e:
        raise DatasetError(f'cannot read {path}: {e.strerror}') from None
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        at = f' at line {mark.line + 1}' if mark else ''
        raise DatasetError(f'{path} is not valid YAML{at}') from None
    return check(data, str(path))


def check(data: Any, name: str = 'the description') -> DatasetDescription:
    """The description's dict as dataclasses, after checking every field."""
    _need(isinstance(data, dict), f'{name} must be a mapping with version and room_types')
    _need(data.get('version') == VERSION,
          f'{name}: version must be {VERSION}, got {quoted(data.get("version"))}')
    types = data.get('room_types')
    _need(isinstance(types, dict) and types,
          f'{name}: room_types must map at least one room type to its description')
    allowance = data.get('allowance')
    return DatasetDescription(str(data.get('format', '')),
                              {str(rt): _check_type(str(rt), d, name)
                               for rt, d in types.items()},
                              STRICT if allowance is None
                              else Allowance.from_dict(allowance, f'{name}: allowance'))


def _need(ok: bool, message: str) -> None:
    if not ok:
        raise DatasetError(message)


def _number(value: Any, where: str, minimum: float = 0.0, integer: bool = False) -> float:
    ok = isinstance(value, (int, float)) and not isinstance(value, bool) \
        and math.isfinite(value) and value >= minimum and (not integer or value == int(value))
    kind = 'an integer' if integer else 'a number'
    _need(ok, f'{where} must be {kind} of at least {minimum:g}, got {quoted(value)}')
    return value


def _check_type(rt: str, d: Any, name: str) -> RoomTypeDescription:
    at = f'{name}: room_types.{rt}'
    _need(isinstance(d, dict), f'{at} must be a mapping')
    rooms = int(_number(d.get('rooms'), f'{at}.rooms', 1, integer=True))
    cap = _number(d.get('size_cap'), f'{at}.size_cap', 0.1)
    cats = d.get('categories')
    _need(isinstance(cats, dict) and cats, f'{at}.categories must map at least one category')
    entries = tuple(_check_category(str(c), e, f'{at}.categories') for c, e in cats.items())
    names = {c.name for c in entries}
    for c in entries:
        for parent in c.supported_by:
            _need(parent in names, f'{at}.categories.{c.name}.supported_by names '
                  f'{quoted(parent)}, which is not a category of {rt}')
    order = d.get('importance_order')
    if order is None:
        order = [c.name for c in sorted(entries, key=lambda c: -c.importance)]
    _need(isinstance(order, list) and sorted(map(str, order)) == sorted(names),
          f'{at}.importance_order must list each of its categories once')
    return RoomTypeDescription(rt, rooms, float(cap),
                               float(_number(d.get('doors_per_room', 0), f'{at}.doors_per_room')),
                               float(_number(d.get('windows_per_room', 0),
                                             f'{at}.windows_per_room')),
                               entries, tuple(map(str, order)))


def _check_category(cat: str, e: Any, at: str) -> CategoryDescription:
    at = f'{at}.{cat}'
    _need(isinstance(e, dict), f'{at} must be a mapping')
    tier = e.get('tier')
    _need(tier in TIERS, f'{at}.tier must be one of {", ".join(TIERS)}, got {quoted(tier)}')
    parents = e.get('supported_by') or {}
    _need(isinstance(parents, (dict, list)), f'{at}.supported_by must map parent categories '
          f'to counts')
    _need(tier == 'second' or not parents, f'{at}.supported_by must be empty for the '
          f'{tier} tier (only second-tier objects stand on others)')
    ranges = []
    for key in ('width', 'depth', 'height'):
        r = e.get(key)
        _need(isinstance(r, dict), f'{at}.{key} must be a mapping of min, median and max')
        lo, mid, hi = (_number(r.get(k), f'{at}.{key}.{k}', 1e-6) for k in
                       ('min', 'median', 'max'))
        _need(lo <= mid <= hi, f'{at}.{key} must have min <= median <= max, got {lo:g}, '
              f'{mid:g}, {hi:g}')
        ranges.append((float(lo), float(mid), float(hi)))
    count = int(_number(e.get('count'), f'{at}.count', 1, integer=True))
    per_room = float(_number(e.get('per_room'), f'{at}.per_room'))
    imp = e.get('importance')
    if imp is None:
        imp = importance({'width': dict(zip(('min', 'median', 'max'), ranges[0], strict=True)),
                          'depth': dict(zip(('min', 'median', 'max'), ranges[1], strict=True)),
                          'per_room': per_room})
    roles = e['roles'] if 'roles' in e else sorted(roles_of(cat))
    _need(isinstance(roles, list) and all(isinstance(r, str) for r in roles),
          f'{at}.roles must be a list of role names')
    unknown = sorted(set(roles) - set(ROLES))
    _need(not unknown, f'{at}.roles names {quoted(unknown[0]) if unknown else ""}, which is not '
          f'a role; the roles are {", ".join(ROLES)}')
    return CategoryDescription(cat, count, per_room, tier, tuple(map(str, parents)),
                               bool(e.get('against_wall', False)), ranges[0], ranges[1],
                               ranges[2], float(_number(imp, f'{at}.importance')),
                               frozenset(roles))
