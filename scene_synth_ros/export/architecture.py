"""The room's architecture as every export shows it: the floor slab and the wall pieces.

Walls are boxes standing outside the floor outline (their inner face on it), cut where doors
and windows are: a door leaves a gap up to its height, a window leaves one between its sill
and its top. The floor is the outline extruded from ``-FLOOR_THICKNESS`` to 0. Both are
static in every format. Everything is in the package's frame (REP-103: metres, z up).
"""
from __future__ import annotations

from dataclasses import dataclass
import itertools
import math
from typing import TYPE_CHECKING

import numpy as np
import shapely

if TYPE_CHECKING:
    import trimesh

from ..house import House, HouseScene, back_to_back
from ..scene import Room, Scene
from ..thresholds import OPENING_TOLERANCE

WALL_THICKNESS = 0.10     # metres, outside the floor outline
# The thinnest wall between two rooms (metres): two floors that meet on one line still get a
# wall between them, half of it on each side of the line.
PARTITION = 0.01
FLOOR_THICKNESS = 0.05    # metres, below z = 0


@dataclass(frozen=True)
class WallBox:
    """One solid piece of wall: centre, yaw (along the wall), size (length, thickness,
    height)."""

    name: str
    centre: tuple[float, float, float]
    yaw: float
    size: tuple[float, float, float]


def _wall_pieces(room: Room, wall, spans, prefix: str) -> list[WallBox]:
    """The solid pieces of ``wall`` of ``room`` over ``spans``, each (start offset, end
    offset, thickness, depth of its centre behind the wall's line, height), with the room's
    door and window openings on that wall left out; named ``PREFIX_K``."""
    cuts = []   # (start offset, end offset, bottom, top) of each opening on this wall
    for op in room.openings:
        if room.wall_of(op) == wall:
            mid = wall.offset_of(op.position)
            top = op.sill + op.height
            cuts.append((max(mid - op.width / 2, 0.0), min(mid + op.width / 2, wall.length),
                         op.sill, top))
    yaw = math.atan2(wall.direction[1], wall.direction[0])
    out = []
    for start, end, thickness, depth, height in spans:
        # Split the span at every opening edge; each piece is solid from the floor to the
        # ceiling except where an opening covers it.
        edges = sorted({start, end} | {c[i] for c in cuts for i in (0, 1)
                                       if start < c[i] < end})
        for a, b in itertools.pairwise(edges):
            if b - a < 1e-6:
                continue
            mid = (a + b) / 2
            holes = sorted((min(c[2], height), min(c[3], height)) for c in cuts
                           if c[0] <= mid <= c[1])
            z = 0.0
            for lo, hi in holes + [(height, height)]:
                if lo - z > 1e-6:
                    centre = wall.point_at(mid) - wall.normal * depth
                    out.append(WallBox(f'{prefix}_{len(out)}',
                                       (float(centre[0]), float(centre[1]), (z + lo) / 2),
                                       yaw, (b - a, thickness, lo - z)))
                z = max(z, hi)
    return out


def wall_boxes(room: Room, thickness: float = WALL_THICKNESS) -> list[WallBox]:
    """The solid pieces of every wall, with the door and window openings left out."""
    return [box for wall in room.walls
            for box in _wall_pieces(room, wall, [(0.0, wall.length, thickness, thickness / 2,
                                                  room.wall_height)], f'wall_{wall.index}')]


def _shared(wall, others: list[tuple[int, Room]]) -> list[tuple[float, float, int, float]]:
    """Where another room stands behind ``wall``, back to back with it
    (``house.back_to_back``): (start offset, end offset, that room's index, the gap)."""
    out = []
    for j, other in others:
        for w in other.walls:
            gap = back_to_back(wall, w, slack=OPENING_TOLERANCE)
            if gap is None:
                continue
            a, b = sorted((wall.offset_of(w.start), wall.offset_of(w.end)))
            a, b = max(a, 0.0), min(b, wall.length)
            if b - a > OPENING_TOLERANCE:
                out.append((a, b, j, max(gap, 0.0)))
    return sorted(out)


def house_wall_boxes(house: House, thickness: float = WALL_THICKNESS) -> list[WallBox]:
    """The walls of a whole house, each once: an outside wall as a room's
    (``wall_boxes``), ``thickness`` outside its floor; a wall two rooms share, written by
    the first of the two in the layout's order, fills the gap between their floors (at
    least ``PARTITION`` thick, about the middle of the gap) up to the higher of their two
    walls, with the door between them left open (it is in both rooms' doors). Named
    ``wall_R_W_K``: room R (layout order), its wall W, piece K."""
    rooms = list(house.rooms.values())
    out: list[WallBox] = []
    for i, room in enumerate(rooms):
        others = [(j, r) for j, r in enumerate(rooms) if j != i]
        for wall in room.walls:
            spans, at = [], 0.0
            outside = (thickness, thickness / 2, room.wall_height)
            for a, b, j, gap in _shared(wall, others):
                if a > at:
                    spans.append((at, a, *outside))
                if j > i and b > at:
                    spans.append((max(a, at), b, max(gap, PARTITION), gap / 2,
                                  max(room.wall_height, rooms[j].wall_height)))
                at = max(at, b)
            if wall.length > at:
                spans.append((at, wall.length, *outside))
            out += _wall_pieces(room, wall, spans, f'wall_{i}_{wall.index}')
    return out


@dataclass(frozen=True)
class Architecture:
    """What every export builds of a room or a whole house: each room's floor (named) and
    the wall pieces."""

    floors: tuple[tuple[str, Room], ...]
    walls: tuple[WallBox, ...]


def architecture_of(scene: Scene | HouseScene) -> Architecture:
    """The floor (``floor``) and walls of a room; of a house, every room's floor
    (``floor_R``, R its index in the layout) and the house's walls (``house_wall_boxes``)."""
    if isinstance(scene, HouseScene):
        rooms = list(scene.house.rooms.values())
        return Architecture(tuple((f'floor_{i}', r) for i, r in enumerate(rooms)),
                            tuple(house_wall_boxes(scene.house)))
    return Architecture((('floor', scene.room),), tuple(wall_boxes(scene.room)))


def _box_mesh(box: WallBox) -> trimesh.Trimesh:
    import trimesh  # meshes only: the node's markers read the walls' boxes without it
    m = trimesh.creation.box(extents=box.size)
    t = trimesh.transformations.rotation_matrix(box.yaw, (0, 0, 1))
    t[:3, 3] = box.centre
    m.apply_transform(t)
    return m


def floor_slab(room: Room, thickness: float = FLOOR_THICKNESS) -> trimesh.Trimesh:
    """The floor outline extruded from z = -thickness to 0. Triangulated with shapely's
    constrained Delaunay triangulation (trimesh's own needs an optional engine)."""
    import trimesh  # meshes only, as above
    pts = np.asarray(room.floor, dtype=float)          # counter-clockwise
    n = len(pts)
    tris = shapely.constrained_delaunay_triangles(room.polygon)
    index = {tuple(np.round(p, 9)): k for k, p in enumerate(pts)}
    top = []
    for tri in tris.geoms:
        ring = np.asarray(tri.exterior.coords)[:3]
        face = [index[tuple(np.round(p, 9))] for p in ring]
        a, b, c = pts[face]
        if (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) < 0:
            face = face[::-1]                           # counter-clockwise seen from above
        top.append(face)
    top = np.array(top)
    vertices = np.vstack([np.c_[pts, np.zeros(n)], np.c_[pts, np.full(n, -thickness)]])
    sides = [[k, (k + 1) % n + n, (k + 1) % n] for k in range(n)] + \
            [[k, k + n, (k + 1) % n + n] for k in range(n)]
    faces = np.vstack([top, top[:, ::-1] + n, sides])
    return trimesh.Trimesh(vertices, faces, process=True)


def room_meshes(room: Room | Architecture) -> dict[str, trimesh.Trimesh]:
    """The floor (a slab under z = 0 in the floor's outline) and the wall pieces of a room,
    or every floor and wall of an ``Architecture``, by name."""
    built = room if isinstance(room, Architecture) else architecture_of(Scene(room, []))
    out = {name: floor_slab(r) for name, r in built.floors}
    for box in built.walls:
        out[box.name] = _box_mesh(box)
    return out


def floor_box(room: Room, thickness: float = FLOOR_THICKNESS) -> WallBox:
    """The floor's collision slab for engines whose contacts want boxes: the outline's
    smallest enclosing rectangle, top at z = 0. For an L-shaped room it also covers the
    missing corner, which lies behind walls where nothing can reach it; a convex box gives
    MuJoCo and Bullet their multi-point box contacts, which a triangulated floor would not."""
    rect = room.polygon.minimum_rotated_rectangle
    pts = np.asarray(rect.exterior.coords)[:4]
    edge_a, edge_b = pts[1] - pts[0], pts[2] - pts[1]
    centre = pts.mean(axis=0)
    return WallBox('floor', (float(centre[0]), float(centre[1]), -thickness / 2),
                   math.atan2(edge_a[1], edge_a[0]),
                   (float(np.linalg.norm(edge_a)), float(np.linalg.norm(edge_b)), thickness))


# The colours of the architecture in every format that shows colour (RGBA, 0..1).
FLOOR_RGBA = (0.78, 0.78, 0.76, 1.0)
WALL_RGBA = (0.92, 0.91, 0.88, 1.0)
