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

from ..scene import Room

WALL_THICKNESS = 0.10     # metres, outside the floor outline
FLOOR_THICKNESS = 0.05    # metres, below z = 0


@dataclass(frozen=True)
class WallBox:
    """One solid piece of wall: centre, yaw (along the wall), size (length, thickness,
    height)."""

    name: str
    centre: tuple[float, float, float]
    yaw: float
    size: tuple[float, float, float]


def wall_boxes(room: Room, thickness: float = WALL_THICKNESS) -> list[WallBox]:
    """The solid pieces of every wall, with the door and window openings left out."""
    out = []
    for wall in room.walls:
        cuts = []   # (start offset, end offset, bottom, top) of each opening on this wall
        for op in room.openings:
            if room.wall_of(op) == wall:
                mid = wall.offset_of(op.position)
                top = min(op.sill + op.height, room.wall_height)
                cuts.append((max(mid - op.width / 2, 0.0), min(mid + op.width / 2, wall.length),
                             op.sill, top))
        # Split the wall along its length at every opening edge; each span is solid from
        # the floor to the ceiling except where an opening covers it.
        edges = sorted({0.0, wall.length} | {c[0] for c in cuts} | {c[1] for c in cuts})
        k = 0
        for a, b in itertools.pairwise(edges):
            if b - a < 1e-6:
                continue
            mid = (a + b) / 2
            holes = sorted((c[2], c[3]) for c in cuts if c[0] <= mid <= c[1])
            z = 0.0
            for lo, hi in holes + [(room.wall_height, room.wall_height)]:
                if lo - z > 1e-6:
                    centre = (wall.point_at(mid) - wall.normal * thickness / 2)
                    out.append(WallBox(f'wall_{wall.index}_{k}',
                                       (float(centre[0]), float(centre[1]), (z + lo) / 2),
                                       math.atan2(wall.direction[1], wall.direction[0]),
                                       (b - a, thickness, lo - z)))
                    k += 1
                z = max(z, hi)
    return out


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


def room_meshes(room: Room) -> dict[str, trimesh.Trimesh]:
    """The floor (a slab under z = 0 in the floor's outline) and the wall pieces."""
    out = {'floor': floor_slab(room)}
    for box in wall_boxes(room):
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
