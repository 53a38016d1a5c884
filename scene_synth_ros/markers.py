"""RViz markers of a furnished room as plain dataclasses, without any ROS import.

The ROS node copies each ``MarkerSpec`` field into a ``visualization_msgs/Marker``; keeping
the geometry here lets it be tested without a ROS installation. Units and frames follow
REP-103 and ``scene.py``: metres, z up, yaw about +z, an object's front along its local +x.
Colours come from ``colors`` so that RViz and the top-down PNGs agree.

With ``style='mesh'`` an object is its catalog model's mesh as shipped in the package
(``package://scene_synth_ros/meshes/<model id>.obj``, see ``meshes.shipped``), which RViz
resolves on any machine where the package is installed; the marker's scale stretches it onto
the object's box when the object's size is not the model's. An object whose model is one of
the user's (a ``catalog.Catalog`` passed in) shows the user's mesh instead, from the STL
that ``scene-synth catalog build`` wrote (``meshes.user_marker``), painted in the category's
colour since STL has no materials.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
import math

import shapely

from . import colors
from .catalog import Catalog
from .categories import PAPER, Vocabulary
from .export import WALL_THICKNESS, wall_boxes
from .export.architecture import house_wall_boxes
from .house import HouseScene
from .meshes import file_uri, mesh_scale, package_uri, shipped_variant, user_marker
from .scene import Opening, PlacedObject, Room, Scene

MARKER_STYLES = ('cube', 'mesh')
MARKER_KINDS = ('cube', 'mesh', 'text', 'triangle_list')

Vec3 = tuple[float, float, float]
RGBA = tuple[float, float, float, float]

OPENING_THICKNESS = 0.04   # m: thin enough to read as a panel inside the wall's gap
LABEL_HEIGHT = 0.15        # m: text height, and the gap between an object's top and its label


def _floats(values, n: int, what: str) -> tuple[float, ...]:
    # numpy scalars leak out of shapely/numpy maths; ROS message fields want plain floats.
    out = tuple(float(v) for v in values)
    if len(out) != n or not all(math.isfinite(v) for v in out):
        raise ValueError(f'marker {what} must be {n} finite numbers, got {out}')
    return out


@dataclass(frozen=True)
class MarkerSpec:
    """One RViz marker, field for field what ``visualization_msgs/Marker`` needs."""

    ns: str
    id: int
    kind: str
    position: Vec3
    yaw: float
    scale: Vec3
    color: RGBA
    text: str = ''
    mesh_resource: str = ''
    points: tuple[Vec3, ...] = ()
    mesh_materials: bool = True   # the mesh's own materials; False: ``color`` paints it

    def __post_init__(self):
        if self.kind not in MARKER_KINDS:
            raise ValueError(f'marker kind must be one of {", ".join(MARKER_KINDS)}, '
                             f'got {self.kind!r}')
        set_ = object.__setattr__
        set_(self, 'id', int(self.id))
        set_(self, 'position', _floats(self.position, 3, 'position'))
        set_(self, 'yaw', _floats([self.yaw], 1, 'yaw')[0])
        set_(self, 'scale', _floats(self.scale, 3, 'scale'))
        set_(self, 'color', _floats(self.color, 4, 'color'))
        set_(self, 'points', tuple(_floats(p, 3, 'point') for p in self.points))


def category_color(category: str, vocabulary: Vocabulary = PAPER) -> RGBA:
    """The RGBA colour of a category, the same as in the top-down pictures."""
    return _floats(colors.category_color(category, vocabulary), 4, 'color')


# The room's parts: their colour and opacity. Read when the first room is drawn (matplotlib
# names the colours), not when the node starts.
_PARTS = {'floor': (colors.FLOOR_COLOR, None), 'walls': (colors.WALL_COLOR, None),
          'doors': (colors.DOOR_COLOR, 0.6), 'windows': (colors.WINDOW_GLASS_COLOR, 0.4)}


@lru_cache(maxsize=None)
def part_color(part: str) -> RGBA:
    """The RGBA of a room's ``part`` (``floor``, ``walls``, ``doors`` or ``windows``)."""
    return _floats(colors.rgba(*_PARTS[part]), 4, 'color')


def warm_up() -> None:
    """Read the colours now (importing matplotlib takes 0.3 s), so that the first room's
    markers do not wait for them: the node does this beside its serving, once it serves."""
    for part in _PARTS:
        part_color(part)
    colors.category_colors()
LABEL_RGBA = (1.0, 1.0, 1.0, 1.0)


def _floor_marker(room: Room) -> MarkerSpec:
    points = []
    for tri in shapely.constrained_delaunay_triangles(room.polygon).geoms:
        (ax, ay), (bx, by), (cx, cy) = list(tri.exterior.coords)[:3]
        corners = [(ax, ay, 0.0), (bx, by, 0.0), (cx, cy, 0.0)]
        if (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) < 0:
            corners.reverse()   # counter-clockwise from above, so the face is lit from above
        points += corners
    return MarkerSpec('floor', 0, 'triangle_list', (0.0, 0.0, 0.0), 0.0, (1.0, 1.0, 1.0),
                      part_color('floor'), points=tuple(points))


def _opening_marker(room: Room, op: Opening, ns: str, k: int, color: RGBA) -> MarkerSpec:
    wall = room.wall_of(op)
    if wall is None:
        raise ValueError(f'the {op.kind} at {op.position} is not on any wall of the room')
    # In the middle of the wall's thickness: export.wall_boxes stands walls outside the floor.
    x, y = wall.point_at(wall.offset_of(op.position)) - wall.normal * WALL_THICKNESS / 2
    yaw = math.atan2(wall.direction[1], wall.direction[0])
    return MarkerSpec(ns, k, 'cube', (x, y, op.sill + op.height / 2), yaw,
                      (op.width, OPENING_THICKNESS, op.height), color)


def _object_marker(obj: PlacedObject, k: int, style: str,
                   models: Catalog | None = None, vocabulary: Vocabulary = PAPER
                   ) -> MarkerSpec:
    x, y, z = obj.position
    color = category_color(obj.category, vocabulary)
    user = user_marker(obj, models) if style == 'mesh' else None
    if user is not None:
        # The STL is in the object frame at the model's size, like the shipped meshes.
        return MarkerSpec(obj.category, k, 'mesh', (x, y, z), obj.yaw, mesh_scale(obj, user),
                          color, mesh_resource=file_uri(user.marker),
                          mesh_materials=False)
    variant = shipped_variant(obj) if style == 'mesh' else None
    if variant is None:   # cube style, or a category without any mesh: a box
        return MarkerSpec(obj.category, k, 'cube', (x, y, z + obj.height / 2), obj.yaw,
                          (obj.depth, obj.width, obj.height), color)
    # Catalog meshes have their origin at the bottom centre, so the pose is the base; the
    # scale (in the mesh's axes: depth, width, height) stretches the model onto the object.
    return MarkerSpec(obj.category, k, 'mesh', (x, y, z), obj.yaw, mesh_scale(obj, variant),
                      color, mesh_resource=package_uri(variant.model_id))


def scene_markers(scene: Scene, style: str = 'cube', catalog: Catalog | None = None,
                  vocabulary: Vocabulary = PAPER) -> list[MarkerSpec]:
    """The markers of a room and its objects: floor, walls, doors, windows, one marker per
    object (a box, or with ``style='mesh'`` its catalog mesh shipped in the package, as a
    ``package://`` URI that RViz resolves on any machine with the package, or the user's mesh
    of ``catalog`` as a ``file://`` URI) and one label per object. Colours are those of the
    categories of ``vocabulary``."""
    if style not in MARKER_STYLES:
        raise ValueError(f'unknown marker style {style!r}; use one of '
                         f'{", ".join(MARKER_STYLES)}')
    room = scene.room
    out = [_floor_marker(room)]
    out += [MarkerSpec('walls', k, 'cube', b.centre, b.yaw, b.size, part_color('walls'))
            for k, b in enumerate(wall_boxes(room))]
    out += [_opening_marker(room, d, 'doors', k, part_color('doors'))
            for k, d in enumerate(room.doors)]
    out += [_opening_marker(room, w, 'windows', k, part_color('windows'))
            for k, w in enumerate(room.windows)]
    seen: dict[str, int] = {}
    for obj in scene.objects:
        k = seen[obj.category] = seen.get(obj.category, -1) + 1
        out.append(_object_marker(obj, k, style, catalog, vocabulary))
    out += [MarkerSpec('labels', i, 'text', (o.position[0], o.position[1], o.top + LABEL_HEIGHT),
                       0.0, (0.0, 0.0, LABEL_HEIGHT), LABEL_RGBA, text=f'{o.id}')
            for i, o in enumerate(scene.objects)]
    return out


def house_markers(house: HouseScene, style: str = 'cube', catalog: Catalog | None = None,
                  vocabulary: Vocabulary = PAPER) -> list[MarkerSpec]:
    """``scene_markers`` of every room of a furnished house, each room's in namespaces of
    its own (``ROOM_ID/floor``, ``ROOM_ID/labels``, ...), so that RViz shows or hides a
    room at once, and the house's walls in ``walls``, each once as the exports have them
    (``export.architecture.house_wall_boxes``)."""
    out = [replace(m, ns=f'{rid}/{m.ns}') for rid, scene in house.scenes.items()
           for m in scene_markers(scene, style, catalog, vocabulary) if m.ns != 'walls']
    return out + [MarkerSpec('walls', k, 'cube', b.centre, b.yaw, b.size, part_color('walls'))
                  for k, b in enumerate(house_wall_boxes(house.house))]
