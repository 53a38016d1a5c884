"""A furnished room or house as URDF files for PyBullet (the engine the paper checked
collisions with).

A URDF describes one articulated body, so a room (or a house: every room's floor, each wall
once) is several files:

- ``<stem>.urdf``: the architecture as one link, loaded with ``useFixedBase``: the floor
  (visual: the outline's slab as an OBJ; collision: ``architecture.floor_box``) and the wall
  pieces as boxes;
- ``<stem>_objects/<object>.urdf``: one file per object, in the object's own frame: the
  catalog mesh (OBJ + MTL) as visual, the collision boxes of ``physics``, and its mass and
  inertia, the tensor written in its principal axes (the inertial origin's ``rpy``) because
  PyBullet keeps only the diagonal of a URDF inertia;
- ``<stem>.poses.json``: where each object goes: its URDF (relative to the room's), position,
  orientation (x, y, z, w, as PyBullet takes it) and whether it is fixed.

``rest.load_pybullet`` loads all three. Friction is PyBullet's ``<contact>`` extension
(lateral friction ``PhysicsConfig.friction``, no rolling or spinning friction); PyBullet
ignores ``<contact>`` everywhere else, and other URDF readers ignore it.
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np

from ..catalog import Catalog
from ..files import safe_name
from ..house import HouseScene
from ..scene import Scene
from .architecture import (
    FLOOR_RGBA,
    WALL_RGBA,
    Architecture,
    architecture_of,
    floor_box,
    floor_slab,
)
from .meshfiles import MeshFolder, obj_of
from .physics import DEFAULT_PHYSICS, Body, PhysicsConfig, world_bodies


def poses_path(path: str | Path) -> Path:
    """The poses file of the room URDF ``path``."""
    path = Path(path)
    return path.with_name(f'{path.stem}.poses.json')


def objects_dir(path: str | Path) -> Path:
    """Where the object URDFs of the room URDF ``path`` go."""
    path = Path(path)
    return path.with_name(f'{path.stem}_objects')


def rpy(matrix: np.ndarray) -> tuple[float, float, float]:
    """URDF's roll, pitch, yaw of a rotation matrix (R = Rz(yaw) Ry(pitch) Rx(roll))."""
    pitch = math.asin(-max(-1.0, min(1.0, float(matrix[2, 0]))))
    if abs(math.cos(pitch)) > 1e-9:
        roll = math.atan2(matrix[2, 1], matrix[2, 2])
        yaw = math.atan2(matrix[1, 0], matrix[0, 0])
    else:                                   # gimbal lock: put it all in roll
        roll, yaw = math.atan2(-matrix[1, 2], matrix[1, 1]), 0.0
    return roll, pitch, yaw


def _numbers(values) -> str:
    return ' '.join(f'{float(v):.6g}' for v in values)


def _sub(parent, tag: str, **attrib):
    return ET.SubElement(parent, tag, {k: str(v) for k, v in attrib.items()})


def _contact(link, friction: float) -> None:
    contact = _sub(link, 'contact')
    _sub(contact, 'lateral_friction', value=f'{friction:g}')
    _sub(contact, 'rolling_friction', value='0')
    _sub(contact, 'spinning_friction', value='0')


def _box(parent, kind: str, centre, yaw: float, size, name: str, rgba=None) -> None:
    element = _sub(parent, kind, name=name)
    _sub(element, 'origin', xyz=_numbers(centre), rpy=f'0 0 {yaw:.6g}')
    _sub(_sub(element, 'geometry'), 'box', size=_numbers(size))
    if rgba is not None:
        _sub(_sub(element, 'material', name=name), 'color', rgba=_numbers(rgba))


def _write(root, path: Path) -> None:
    ET.indent(root)
    path.write_text('<?xml version="1.0"?>\n' + ET.tostring(root, encoding='unicode') + '\n')


def _room_urdf(built: Architecture, path: Path, meshes: MeshFolder, friction: float) -> None:
    robot = ET.Element('robot', name='room')
    link = _sub(robot, 'link', name='room')
    _contact(link, friction)
    inertial = _sub(link, 'inertial')          # static: PyBullet takes mass 0 as immovable
    _sub(inertial, 'mass', value='0')
    _sub(inertial, 'inertia', ixx='0', ixy='0', ixz='0', iyy='0', iyz='0', izz='0')
    for name, room in built.floors:
        floor_file = meshes.text(f'{safe_name(path.stem)}_{name}.obj',
                                 obj_of(floor_slab(room), 'floor slab'))
        visual = _sub(link, 'visual', name=name)
        _sub(_sub(visual, 'geometry'), 'mesh', filename=meshes.relative(floor_file))
        _sub(_sub(visual, 'material', name='floor'), 'color', rgba=_numbers(FLOOR_RGBA))
        floor = floor_box(room)
        _box(link, 'collision', floor.centre, floor.yaw, floor.size, name)
    for box in built.walls:
        _box(link, 'visual', box.centre, box.yaw, box.size, box.name, WALL_RGBA)
        _box(link, 'collision', box.centre, box.yaw, box.size, box.name)
    _write(robot, path)


def _object_urdf(body: Body, path: Path, meshes: MeshFolder, friction: float) -> None:
    robot = ET.Element('robot', name=safe_name(body.id))
    link = _sub(robot, 'link', name='base')
    _contact(link, friction)
    moments, axes = body.principal_inertia()
    inertial = _sub(link, 'inertial')
    _sub(inertial, 'origin', xyz=_numbers(body.com), rpy=_numbers(rpy(axes)))
    _sub(inertial, 'mass', value=f'{body.mass:.6g}')
    _sub(inertial, 'inertia', ixx=f'{moments[0]:.6g}', ixy='0', ixz='0', iyy=f'{moments[1]:.6g}',
         iyz='0', izz=f'{moments[2]:.6g}')
    visual = _sub(link, 'visual', name='visual')
    _sub(_sub(visual, 'geometry'), 'mesh', filename=meshes.relative(meshes.obj(body.variant)))
    for k, piece in enumerate(body.pieces):
        _box(link, 'collision', piece.centre, 0.0, piece.size, f'collision_{k}')
    _write(robot, path)


def export_urdf(scene: Scene | HouseScene, path: str | Path, mesh_dir: str | Path | None = None,
                fixed: bool = False, physics: PhysicsConfig = DEFAULT_PHYSICS,
                catalog: Catalog | None = None) -> Path:
    """Write ``scene``, a room or a whole house, as URDF: its architecture at ``path``, one
    URDF per object in ``<stem>_objects/``, and ``<stem>.poses.json``; OBJ meshes go to
    ``mesh_dir`` (default ``<stem>_meshes/`` beside ``path``). Returns ``path``."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    folder = Path(mesh_dir) if mesh_dir else path.parent / f'{path.stem}_meshes'
    _room_urdf(architecture_of(scene), path, MeshFolder(folder, path.parent),
               physics.friction)
    objects = objects_dir(path)
    objects.mkdir(exist_ok=True)
    meshes = MeshFolder(folder, objects)
    entries = []
    for body in world_bodies(scene, physics, catalog):
        file = objects / f'{safe_name(body.id)}.urdf'
        _object_urdf(body, file, meshes, physics.friction)
        entries.append({'id': body.id, 'category': body.category,
                        'urdf': Path(objects.name, file.name).as_posix(),
                        'position': list(body.position),
                        'orientation_xyzw': [0.0, 0.0, math.sin(body.yaw / 2),
                                             math.cos(body.yaw / 2)],
                        'fixed': fixed or body.fixed, 'support': body.support})
    poses_path(path).write_text(json.dumps({'room': path.name, 'objects': entries}, indent=1)
                                + '\n')
    return path
