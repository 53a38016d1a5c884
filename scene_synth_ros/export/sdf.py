"""A furnished room or house as a Gazebo world (SDF 1.9), or as one model to spawn into a
world.

The world holds a sun, the floor (seen as the outline, an SDF polyline 5 cm thick with its
top at z = 0; colliding as ``architecture.floor_box``), the walls as static box models with
the openings left open, and every object as a model whose link has the catalog mesh as
visual (OBJ + MTL in the mesh folder, relative URI), the collision boxes of ``physics`` (one
``<collision>`` per piece, friction ``mu``), and the mass, centre of mass and inertia tensor
of ``physics``. Objects are dynamic bodies unless ``fixed`` (then ``<static>``). Every model
carries its semantic label (``labels.semantic_label``: the object's category, ``floor`` or
``wall``) through Gazebo's Label system, which its segmentation cameras read; the labels'
names are in ``<stem>_labels.json`` beside the file. A house is one world: every room's floor,
each wall once (``architecture.house_wall_boxes``), every room's objects (``ROOM/ID``).

``root='model'`` writes the same content as one top-level ``<model>`` with the floor, walls
and objects as nested models, which is what ``ros_gz_sim create`` and
``gz_spawn_model.launch.py`` spawn into a running world.
"""
from __future__ import annotations

import json
from pathlib import Path
from xml.etree import ElementTree as ET

from ..catalog import Catalog
from ..files import safe_name, write_atomic
from ..house import HouseScene
from ..scene import Scene
from .architecture import FLOOR_RGBA, FLOOR_THICKNESS, WALL_RGBA, architecture_of, floor_box
from .labels import FLOOR, WALL, label_table, semantic_label
from .meshfiles import MeshFolder
from .physics import DEFAULT_PHYSICS, Body, PhysicsConfig, world_bodies

SDF_VERSION = '1.9'
ROOTS = ('world', 'model')


def _pose(x, y, z, yaw=0.0) -> str:
    return f'{x:.6g} {y:.6g} {z:.6g} 0 0 {yaw:.6g}'


def _sub(parent, tag: str, text: str | None = None, **attrib):
    e = ET.SubElement(parent, tag, attrib)
    if text is not None:
        e.text = text
    return e


def _numbers(values) -> str:
    return ' '.join(f'{float(v):.6g}' for v in values)


def _sun(world) -> None:
    sun = _sub(world, 'light', type='directional', name='sun')
    _sub(sun, 'cast_shadows', 'true')
    _sub(sun, 'pose', '0 0 10 0 0 0')
    _sub(sun, 'direction', '-0.5 0.1 -0.9')
    _sub(sun, 'diffuse', '0.8 0.8 0.8 1')


def _label(model, category: str) -> None:
    """The category's label on every visual of ``model``, which Gazebo's segmentation
    cameras read (its Label system)."""
    plugin = _sub(model, 'plugin', filename='gz-sim-label-system',
                  name='gz::sim::systems::Label')
    _sub(plugin, 'label', str(semantic_label(category)))


def _architecture(parent, scene: Scene | HouseScene) -> None:
    # Floor: seen as the outline extruded downwards (SDF polyline geometry handles L
    # shapes), colliding as the outline's enclosing box, which every physics engine of
    # Gazebo supports with multi-point box contacts.
    built = architecture_of(scene)
    for name, room in built.floors:
        model = _sub(parent, 'model', name=name)
        _sub(model, 'static', 'true')
        _sub(model, 'pose', _pose(0, 0, -FLOOR_THICKNESS))
        link = _sub(model, 'link', name='link')
        box = floor_box(room)
        collision = _sub(link, 'collision', name='collision')
        _sub(collision, 'pose', _pose(box.centre[0], box.centre[1], FLOOR_THICKNESS / 2,
                                      box.yaw))
        _sub(_sub(_sub(collision, 'geometry'), 'box'), 'size', _numbers(box.size))
        visual = _sub(link, 'visual', name='visual')
        poly = _sub(_sub(visual, 'geometry'), 'polyline')
        for x, y in room.floor:
            _sub(poly, 'point', f'{x:.6g} {y:.6g}')
        _sub(poly, 'height', f'{FLOOR_THICKNESS:.6g}')
        colour = _sub(visual, 'material')
        _sub(colour, 'diffuse', _numbers(FLOOR_RGBA))
        _sub(colour, 'ambient', _numbers(FLOOR_RGBA))
        _label(model, FLOOR)
    for box in built.walls:
        model = _sub(parent, 'model', name=box.name)
        _sub(model, 'static', 'true')
        _sub(model, 'pose', _pose(*box.centre, box.yaw))
        link = _sub(model, 'link', name='link')
        for kind in ('collision', 'visual'):
            element = _sub(link, kind, name=kind)
            _sub(_sub(_sub(element, 'geometry'), 'box'), 'size', _numbers(box.size))
            if kind == 'visual':
                colour = _sub(element, 'material')
                _sub(colour, 'diffuse', _numbers(WALL_RGBA))
                _sub(colour, 'ambient', _numbers(WALL_RGBA))
        _label(model, WALL)


def _inertial(link, body: Body) -> None:
    inertial = _sub(link, 'inertial')
    _sub(inertial, 'pose', _pose(*body.com))
    _sub(inertial, 'mass', f'{body.mass:.6g}')
    tensor = _sub(inertial, 'inertia')
    i = body.inertia
    for tag, value in (('ixx', i[0, 0]), ('ixy', i[0, 1]), ('ixz', i[0, 2]), ('iyy', i[1, 1]),
                       ('iyz', i[1, 2]), ('izz', i[2, 2])):
        _sub(tensor, tag, f'{value:.6g}')


def _object(parent, body: Body, uri: str, fixed: bool, friction: float) -> None:
    model = _sub(parent, 'model', name=safe_name(body.id))
    _sub(model, 'static', 'true' if fixed else 'false')
    _sub(model, 'pose', _pose(*body.position, body.yaw))
    link = _sub(model, 'link', name='link')
    _inertial(link, body)
    visual = _sub(link, 'visual', name='visual')
    _sub(_sub(_sub(visual, 'geometry'), 'mesh'), 'uri', uri)
    for k, piece in enumerate(body.pieces):
        collision = _sub(link, 'collision', name=f'collision_{k}')
        _sub(collision, 'pose', _pose(*piece.centre))
        _sub(_sub(_sub(collision, 'geometry'), 'box'), 'size', _numbers(piece.size))
        ode = _sub(_sub(_sub(collision, 'surface'), 'friction'), 'ode')
        _sub(ode, 'mu', f'{friction:.6g}')
        _sub(ode, 'mu2', f'{friction:.6g}')
    _label(model, body.category)


def _uri(meshes: MeshFolder, path: Path, world_dir: Path) -> str:
    # Relative below the world's folder (Gazebo resolves it against the file), else absolute.
    if path.resolve().is_relative_to(world_dir.resolve()):
        return meshes.relative(path)
    return path.resolve().as_uri()


def export_sdf(scene: Scene | HouseScene, path: str | Path, mesh_dir: str | Path | None = None,
               fixed: bool = False, root: str = 'world',
               physics: PhysicsConfig = DEFAULT_PHYSICS, catalog: Catalog | None = None
               ) -> Path:
    """Write ``scene``, a room or a whole house, as SDF to ``path``; OBJ meshes go to
    ``mesh_dir`` (default ``<stem>_meshes/`` beside the file). ``fixed`` makes the furniture
    static; ``root`` is ``'world'`` (a world file for ``gz sim``) or ``'model'`` (one model
    to spawn)."""
    if root not in ROOTS:
        raise ValueError(f'root must be one of {", ".join(ROOTS)}, got {root!r}')
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    meshes = MeshFolder(mesh_dir or path.parent / f'{path.stem}_meshes', path.parent)
    sdf = ET.Element('sdf', version=SDF_VERSION)
    if root == 'world':
        parent = _sub(sdf, 'world', name='scene_synth_room')
        _sub(parent, 'gravity', '0 0 -9.81')
        _sun(parent)
    else:
        parent = _sub(sdf, 'model', name=safe_name(path.stem))
    _architecture(parent, scene)
    bodies = world_bodies(scene, physics, catalog)
    for body in bodies:
        uri = _uri(meshes, meshes.obj(body.variant), path.parent)
        _object(parent, body, uri, fixed or body.fixed, physics.friction)
    ET.indent(sdf)
    path.write_text('<?xml version="1.0"?>\n' + ET.tostring(sdf, encoding='unicode') + '\n')
    labels = label_table(sorted({b.category for b in bodies}))
    write_atomic(path.with_name(f'{path.stem}_labels.json'),
                 json.dumps(labels, indent=1) + '\n')
    return path
