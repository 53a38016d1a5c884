"""Exports of a furnished room for simulators: a Gazebo SDF world and one glTF of the room.

Walls are boxes standing outside the floor outline (their inner face on it), cut where doors
and windows are: a door leaves a gap up to its height, a window leaves one between its sill
and its top. Objects are static models: the catalog mesh as visual, their bounding box as
collision. Everything is in the package's frame (REP-103: z up); the glTF gets a root
rotation to glTF's y-up convention.
"""
from __future__ import annotations

from dataclasses import dataclass
import itertools
import math
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np
import shapely
import trimesh

from .files import safe_name
from .meshes import export_model, scene_mesh, variant_for
from .scene import Room, Scene

WALL_THICKNESS = 0.10     # metres, outside the floor outline
FLOOR_THICKNESS = 0.05    # metres, below z = 0
SDF_VERSION = '1.9'


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
    m = trimesh.creation.box(extents=box.size)
    t = trimesh.transformations.rotation_matrix(box.yaw, (0, 0, 1))
    t[:3, 3] = box.centre
    m.apply_transform(t)
    return m


def floor_slab(room: Room, thickness: float = FLOOR_THICKNESS) -> trimesh.Trimesh:
    """The floor outline extruded from z = -thickness to 0. Triangulated with shapely's
    constrained Delaunay triangulation (trimesh's own needs an optional engine)."""
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


# ---- glTF ---------------------------------------------------------------------------------
Z_UP_TO_Y_UP = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], float)


def export_gltf(scene: Scene, path: str | Path) -> Path:
    """One binary glTF of the room and its objects, y-up as glTF viewers expect."""
    out = scene_mesh(scene)
    for name, mesh in room_meshes(scene.room).items():
        colour = [0.78, 0.78, 0.76, 1.0] if name == 'floor' else [0.92, 0.91, 0.88, 1.0]
        mesh.visual = trimesh.visual.TextureVisuals(
            material=trimesh.visual.material.PBRMaterial(name=name, baseColorFactor=colour,
                                                         metallicFactor=0.0,
                                                         roughnessFactor=0.9))
        out.add_geometry(mesh, geom_name=name, node_name=name)
    out.apply_transform(Z_UP_TO_Y_UP)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(trimesh.exchange.gltf.export_glb(out, include_normals=False))
    return path


# ---- SDF ----------------------------------------------------------------------------------
def _pose(x, y, z, yaw=0.0) -> str:
    return f'{x:.6g} {y:.6g} {z:.6g} 0 0 {yaw:.6g}'


def _sub(parent, tag: str, text: str | None = None, **attrib):
    e = ET.SubElement(parent, tag, attrib)
    if text is not None:
        e.text = text
    return e


def export_sdf(scene: Scene, path: str | Path, mesh_dir: str | Path | None = None) -> Path:
    """A Gazebo world (SDF 1.9): a sun, the floor, the walls with their openings, and every
    object as a static model whose visual is its catalog mesh (OBJ files written to
    ``mesh_dir``, default ``<world name>_meshes/`` beside the world, referenced by relative
    URI) and whose collision is its bounding box."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    mesh_dir = Path(mesh_dir) if mesh_dir else path.parent / f'{path.stem}_meshes'
    sdf = ET.Element('sdf', version=SDF_VERSION)
    world = _sub(sdf, 'world', name='scene_synth_room')
    sun = _sub(world, 'light', type='directional', name='sun')
    _sub(sun, 'cast_shadows', 'true')
    _sub(sun, 'pose', '0 0 10 0 0 0')
    _sub(sun, 'direction', '-0.5 0.1 -0.9')
    _sub(sun, 'diffuse', '0.8 0.8 0.8 1')

    # Floor: the outline extruded downwards (SDF polyline geometry handles L shapes).
    model = _sub(world, 'model', name='floor')
    _sub(model, 'static', 'true')
    _sub(model, 'pose', _pose(0, 0, -FLOOR_THICKNESS))
    link = _sub(model, 'link', name='link')
    for kind in ('collision', 'visual'):
        geom = _sub(_sub(link, kind, name=kind), 'geometry')
        poly = _sub(geom, 'polyline')
        for x, y in scene.room.floor:
            _sub(poly, 'point', f'{x:.6g} {y:.6g}')
        _sub(poly, 'height', f'{FLOOR_THICKNESS:.6g}')

    for box in wall_boxes(scene.room):
        model = _sub(world, 'model', name=box.name)
        _sub(model, 'static', 'true')
        _sub(model, 'pose', _pose(*box.centre, box.yaw))
        link = _sub(model, 'link', name='link')
        for kind in ('collision', 'visual'):
            geom = _sub(_sub(link, kind, name=kind), 'geometry')
            _sub(_sub(geom, 'box'), 'size', ' '.join(f'{v:.6g}' for v in box.size))

    written: set[str] = set()
    for obj in scene.objects:
        v = variant_for(obj)
        fname = safe_name(v.model_id) + '.obj'
        if fname not in written:
            export_model(v, mesh_dir / fname)
            written.add(fname)
        model = _sub(world, 'model', name=safe_name(obj.id))
        _sub(model, 'static', 'true')
        _sub(model, 'pose', _pose(*obj.position, obj.yaw))
        link = _sub(model, 'link', name='link')
        visual = _sub(link, 'visual', name='visual')
        mesh = _sub(_sub(visual, 'geometry'), 'mesh')
        _sub(mesh, 'uri', (mesh_dir / fname).resolve().relative_to(path.parent.resolve())
             .as_posix() if mesh_dir.resolve().is_relative_to(path.parent.resolve())
             else (mesh_dir / fname).resolve().as_uri())
        collision = _sub(link, 'collision', name='collision')
        _sub(collision, 'pose', _pose(0, 0, obj.height / 2))
        _sub(_sub(_sub(collision, 'geometry'), 'box'), 'size',
             f'{obj.depth:.6g} {obj.width:.6g} {obj.height:.6g}')
    ET.indent(sdf)
    path.write_text('<?xml version="1.0"?>\n' + ET.tostring(sdf, encoding='unicode') + '\n')
    return path
