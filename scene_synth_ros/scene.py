"""The scene model: a room (architecture) and the objects placed in it.

Conventions (REP-103): metres, radians, right-handed, z up, yaw about +z.

An object's own frame has its front facing +x. ``size`` is ``(width, depth, height)``:
``width`` across the front (along local y), ``depth`` from back to front (along local x),
``height`` along z. ``position`` is the centre of the footprint with ``z`` at the object's
bottom (0 on the floor; the top of the supporting parent for a second-tier object).

``to_dict``/``from_dict`` here trust their input; everything that comes from outside goes
through ``scene_synth_ros.schema`` first, which validates it and says what is wrong.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
import math
from typing import Any, Callable, Collection, Hashable, Iterable, Iterator

import numpy as np
import shapely
from shapely.geometry import LineString, Polygon

DEFAULT_WALL_HEIGHT = 2.6      # m, a room layout's wall height when it gives none


@dataclass(frozen=True)
class Wall:
    """One straight wall of a room: the floor edge from ``start`` to ``end``."""

    index: int
    start: tuple[float, float]
    end: tuple[float, float]

    # Cached (synthesis asks each wall for them tens of thousands of times a second) and
    # read-only, since every caller shares them.
    @cached_property
    def length(self) -> float:
        return math.dist(self.start, self.end)

    @cached_property
    def direction(self) -> np.ndarray:
        d = np.subtract(self.end, self.start)
        d = d / np.linalg.norm(d)
        d.flags.writeable = False
        return d

    @cached_property
    def normal(self) -> np.ndarray:
        """Unit normal pointing into the room (floor polygons are kept counter-clockwise)."""
        dx, dy = self.direction
        n = np.array([-dy, dx])
        n.flags.writeable = False
        return n

    @cached_property
    def inward_yaw(self) -> float:
        """Yaw of an object whose back is on this wall and whose front faces the room."""
        nx, ny = self.normal
        return math.atan2(ny, nx)

    def point_at(self, offset: float) -> np.ndarray:
        return np.asarray(self.start) + self.direction * offset

    def offset_of(self, point: Iterable[float]) -> float:
        return float(np.dot(np.subtract(tuple(point), self.start), self.direction))

    def distance_to(self, point: Iterable[float]) -> float:
        return LineString([self.start, self.end]).distance(shapely.Point(tuple(point)))


@dataclass(frozen=True)
class Opening:
    """A door or window: an opening in a wall, centred at ``position`` on the wall line."""

    kind: str                     # 'door' or 'window'
    position: tuple[float, float]
    width: float
    height: float
    sill: float = 0.0             # height of the bottom above the floor (0 for doors)

    def to_dict(self) -> dict[str, Any]:
        d = {'position': [self.position[0], self.position[1]], 'width': self.width,
             'height': self.height}
        if self.kind == 'window':
            d['sill'] = self.sill
        return d

    @classmethod
    def from_dict(cls, kind: str, d: dict[str, Any]) -> 'Opening':
        return cls(kind, (float(d['position'][0]), float(d['position'][1])),
                   float(d['width']), float(d['height']),
                   float(d.get('sill', 0.0)) if kind == 'window' else 0.0)


def ccw(points: Iterable[Iterable[float]]) -> tuple[tuple[float, float], ...]:
    """The vertices as a counter-clockwise tuple, without a repeated closing vertex."""
    pts = [(float(x), float(y)) for x, y in points]
    if len(pts) > 1 and pts[0] == pts[-1]:
        pts = pts[:-1]
    # Relative to the first vertex: far from the origin the raw products cancel each other
    # and the sum can lose its sign.
    ox, oy = pts[0] if pts else (0.0, 0.0)
    rel = [(x - ox, y - oy) for x, y in pts]
    area2 = sum(x0 * y1 - x1 * y0
                for (x0, y0), (x1, y1) in zip(rel, rel[1:] + rel[:1], strict=True))
    return tuple(pts if area2 >= 0 else pts[::-1])


@dataclass(frozen=True, eq=False)
class Room:
    """The architecture of one room: floor outline, wall height, doors and windows."""

    room_type: str
    floor: tuple[tuple[float, float], ...]
    wall_height: float = 2.6
    doors: tuple[Opening, ...] = ()
    windows: tuple[Opening, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, 'floor', ccw(self.floor))
        object.__setattr__(self, 'doors', tuple(self.doors))
        object.__setattr__(self, 'windows', tuple(self.windows))

    def __eq__(self, other):
        if not isinstance(other, Room):
            return NotImplemented
        return self.to_dict() == other.to_dict()

    __hash__ = None

    @cached_property
    def polygon(self) -> Polygon:
        return Polygon(self.floor)

    @cached_property
    def walls(self) -> tuple[Wall, ...]:
        pts = self.floor
        return tuple(Wall(i, pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts)))

    @property
    def openings(self) -> tuple[Opening, ...]:
        return self.doors + self.windows

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        return self.polygon.bounds

    @property
    def centre(self) -> tuple[float, float]:
        x0, y0, x1, y1 = self.bounds
        return ((x0 + x1) / 2.0, (y0 + y1) / 2.0)

    @property
    def area(self) -> float:
        return self.polygon.area

    def wall_of(self, opening: Opening, tol: float = 0.01) -> Wall | None:
        """The wall an opening lies on (within ``tol`` metres, whole width on the wall)."""
        return self.remembered(('wall of', opening, tol), lambda: self._find_wall(opening, tol))

    def remembered(self, what: Hashable, make: Callable[[], Any]) -> Any:
        """``make()``, something of the room (it never changes) remembered under ``what``:
        the design rules ask for the walls of the doors and windows, the floor grown by a
        tolerance and the like at every candidate placement. Shared: never modify it."""
        known = self._remembered
        if what not in known:
            known[what] = make()
        return known[what]

    @cached_property
    def _remembered(self) -> dict:
        return {}

    def __getstate__(self) -> dict[str, Any]:
        # Pickles (worker processes) carry the room, not what was remembered of it (prepared
        # geometries cannot be pickled).
        return {k: v for k, v in self.__dict__.items() if k != '_remembered'}

    def _find_wall(self, opening: Opening, tol: float) -> Wall | None:
        best = None
        for wall in self.walls:
            dist = wall.distance_to(opening.position)
            if dist > tol:
                continue
            off = wall.offset_of(opening.position)
            if off - opening.width / 2 < -tol or off + opening.width / 2 > wall.length + tol:
                continue
            if best is None or dist < best[0]:
                best = (dist, wall)
        return None if best is None else best[1]

    def to_dict(self) -> dict[str, Any]:
        return {
            'room_type': self.room_type,
            'floor': [[x, y] for x, y in self.floor],
            'wall_height': self.wall_height,
            'doors': [d.to_dict() for d in self.doors],
            'windows': [w.to_dict() for w in self.windows],
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> 'Room':
        return cls(d['room_type'], tuple((float(x), float(y)) for x, y in d['floor']),
                   float(d.get('wall_height', DEFAULT_WALL_HEIGHT)),
                   tuple(Opening.from_dict('door', o) for o in d.get('doors', [])),
                   tuple(Opening.from_dict('window', o) for o in d.get('windows', [])))


def fresh_id(category: str, taken: Collection[str], count: int) -> str:
    """A readable id for one more object of ``category``: ``<category>_<n>``, from ``n`` =
    ``count`` (the objects of the category there already) up to the first not ``taken``."""
    stem = category.replace(' ', '_')
    n = count
    while f'{stem}_{n}' in taken:
        n += 1
    return f'{stem}_{n}'


def wrap_angle(yaw: float) -> float:
    """``yaw`` as the equal angle in [-pi, pi]."""
    return math.remainder(yaw, 2 * math.pi)


def rotation(yaw: float) -> np.ndarray:
    """The 2x2 matrix turning (x, y) by ``yaw`` about +z (counter-clockwise from above)."""
    c, s = math.cos(yaw), math.sin(yaw)
    return np.array([[c, -s], [s, c]])


def box_corners(cx: float, cy: float, yaw: float, width: float, depth: float) -> np.ndarray:
    """Footprint corners (4x2, counter-clockwise) of a box of the package's size convention."""
    hx, hy = depth / 2.0, width / 2.0
    local = np.array([[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]])
    return local @ rotation(yaw).T + np.array([cx, cy])


class Sized:
    """Named access to a ``size`` of (width, depth, height), the package's convention."""

    size: tuple[float, float, float]

    @property
    def width(self) -> float:
        return self.size[0]

    @property
    def depth(self) -> float:
        return self.size[1]

    @property
    def height(self) -> float:
        return self.size[2]


@dataclass
class PlacedObject(Sized):
    """One object in a scene."""

    id: str
    category: str
    model_id: str
    position: tuple[float, float, float]
    yaw: float
    size: tuple[float, float, float]          # (width, depth, height)
    support: str | None = None                # id of the supporting parent (second tier)

    @property
    def top(self) -> float:
        return self.position[2] + self.size[2]

    @property
    def front(self) -> np.ndarray:
        return np.array([math.cos(self.yaw), math.sin(self.yaw)])

    def corners(self) -> np.ndarray:
        return box_corners(self.position[0], self.position[1], self.yaw, self.width,
                           self.depth)

    def footprint(self, inset: float = 0.0) -> Polygon:
        """The footprint, with every side moved inwards by ``inset`` metres (never
        inverted)."""
        return self.remembered(('footprint', inset), lambda: self._footprint(inset))

    def _footprint(self, inset: float) -> Polygon:
        # ``shapely.polygons`` makes the same polygon as ``Polygon`` without its checks of
        # the argument, a fifth of the cost: the corpus makes hundreds of footprints a room.
        if not inset:
            return shapely.polygons(self.corners())
        w, d = max(self.width - 2 * inset, 1e-4), max(self.depth - 2 * inset, 1e-4)
        return shapely.polygons(box_corners(self.position[0], self.position[1], self.yaw, w, d))

    @property
    def placement(self) -> tuple:
        """Its category, place and size: all that its shapes depend on."""
        return (self.category, *self.position, self.yaw, *self.size)

    def remembered(self, what: Hashable, make: Callable[[], Any]) -> Any:
        """``make()``, a shape of the object that depends only on its ``placement``,
        remembered under ``what`` while that stays the same: insertion asks for the shapes
        of the room's objects (footprints, clear strips, reach zones) at every candidate
        placement. The shapes are shared: never modify one."""
        place = self.placement
        known = self.__dict__.get('_remembered')
        if known is None or known[0] != place:
            known = self.__dict__['_remembered'] = (place, {})
        shapes = known[1]
        if what not in shapes:
            shapes[what] = make()
        return shapes[what]

    def __getstate__(self) -> dict[str, Any]:
        # Pickles (worker processes) carry the object, not the shapes remembered.
        return {k: v for k, v in self.__dict__.items() if k != '_remembered'}

    def to_dict(self) -> dict[str, Any]:
        d = {'id': self.id, 'category': self.category, 'model_id': self.model_id,
             'position': list(self.position), 'yaw': self.yaw, 'size': list(self.size)}
        if self.support is not None:
            d['support'] = self.support
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> 'PlacedObject':
        return cls(str(d['id']), d['category'], d['model_id'],
                   tuple(float(v) for v in d['position']), float(d['yaw']),
                   tuple(float(v) for v in d['size']), d.get('support'))


@dataclass
class Scene:
    """A room and the objects placed in it, in insertion order."""

    room: Room
    objects: list[PlacedObject] = field(default_factory=list)
    meta: dict[str, Any] = field(default_factory=dict)

    def __iter__(self) -> Iterator[PlacedObject]:
        return iter(self.objects)

    def __len__(self) -> int:
        return len(self.objects)

    def get(self, object_id: str) -> PlacedObject:
        for o in self.objects:
            if o.id == object_id:
                return o
        raise KeyError(f'no object with id {object_id!r} in the scene')

    @property
    def first_tier(self) -> list[PlacedObject]:
        return [o for o in self.objects if o.support is None]

    def first_tier_of(self, categories) -> list[PlacedObject]:
        """The first-tier objects of ``categories``."""
        return [o for o in self.objects if o.category in categories and o.support is None]

    @property
    def second_tier(self) -> list[PlacedObject]:
        return [o for o in self.objects if o.support is not None]

    def children_of(self, object_id: str) -> list[PlacedObject]:
        return [o for o in self.objects if o.support == object_id]

    def new_id(self, category: str) -> str:
        """A fresh object id, readable and unique within this scene."""
        return fresh_id(category, {o.id for o in self.objects},
                        sum(1 for o in self.objects if o.category == category))

    def category_counts(self) -> dict[str, int]:
        counts: dict[str, int] = {}
        for o in self.objects:
            counts[o.category] = counts.get(o.category, 0) + 1
        return counts

    def copy(self) -> 'Scene':
        return Scene(self.room, [replace(o) for o in self.objects], dict(self.meta))

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {'room': self.room.to_dict(),
                             'objects': [o.to_dict() for o in self.objects]}
        if self.meta:
            d['meta'] = dict(self.meta)
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> 'Scene':
        return cls(Room.from_dict(d['room']),
                   [PlacedObject.from_dict(o) for o in d.get('objects', [])],
                   dict(d.get('meta', {})))

    def moved(self, yaw: float, offset: Iterable[float] = (0.0, 0.0)) -> 'Scene':
        """The scene under a rigid motion: turned by ``yaw`` about the origin, then shifted by
        ``offset`` (x, y). Heights, sizes, supports and ``meta`` are kept."""
        turn, shift = rotation(yaw), np.array([float(v) for v in offset])

        def move(p) -> tuple[float, float]:
            x, y = turn @ np.asarray(p[:2], dtype=float) + shift
            return (float(x), float(y))

        room = self.room
        room = Room(room.room_type, tuple(move(p) for p in room.floor), room.wall_height,
                    tuple(replace(o, position=move(o.position)) for o in room.doors),
                    tuple(replace(o, position=move(o.position)) for o in room.windows))
        objects = [replace(o, position=(*move(o.position), o.position[2]),
                           yaw=wrap_angle(o.yaw + yaw))
                   for o in self.objects]
        return Scene(room, objects, dict(self.meta))
