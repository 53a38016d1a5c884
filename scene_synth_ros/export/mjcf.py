"""A furnished room or house as a MuJoCo model (MJCF).

The world body holds the floor and the walls, static: the floor collides as the outline's
enclosing box (``architecture.floor_box``, whose box-box contacts hold several points where
a triangulated slab would give one) and shows as the outline itself (an inline mesh); each
wall piece is one box geom with the openings left open. Every object is a body at its pose
with a free joint (or none when ``fixed``: MuJoCo then welds it to the world), the explicit
mass, centre of mass and full inertia tensor of ``physics``, one visual mesh geom per material
(group 2, no contacts, the OBJ files of ``meshfiles``) and one box geom per collision piece
(group 3). Second-tier objects are bodies of their own resting on their parents.

Contact parameters, and why (``MjcfOptions``):
- timestep 2 ms with the ``implicitfast`` integrator, MuJoCo's recommendation for stiff
  contacts without velocity actuators;
- elliptic friction cones: the pyramidal default lets a resting box creep sideways under
  asymmetric contact forces;
- ``solref`` (0.02 s, 1): the default time constant, ten timesteps (MuJoCo asks for at least
  two), critically damped; with the default ``solimp`` (impedance 0.9-0.95 over 1 mm) a body
  resting under gravity sinks by about g (1 - d) / (d k), k = 1 / (d_max^2 tau^2): 0.2 to
  0.4 mm, the same for every mass (MuJoCo's contacts act on accelerations), which the
  benchmark measures (``benchmarks/sim_rest.py``: at most 0.33 mm over 200 rooms);
- friction 0.6 (``PhysicsConfig.friction``), torsional 0.005, rolling 0.0001: MuJoCo's
  defaults for the last two, wood and fabric on a floor for the first.
Nothing here is tuned to hide motion: the rest test (``rest.mujoco_rest``) fails a body
exported 5 cm in the air.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np

from ..catalog import Catalog
from ..files import safe_name
from ..house import HouseScene
from ..meshes import MATERIALS
from ..scene import Scene
from .architecture import (
    FLOOR_RGBA,
    WALL_RGBA,
    Architecture,
    architecture_of,
    floor_box,
    floor_slab,
)
from .meshfiles import MeshFolder
from .physics import DEFAULT_PHYSICS, GRAVITY, Body, PhysicsConfig, quat_wxyz, world_bodies

VISUAL_GROUP, COLLISION_GROUP = 2, 3


@dataclass(frozen=True)
class MjcfOptions:
    """The simulation options written into the model (see the module docstring)."""

    timestep: float = 0.002
    integrator: str = 'implicitfast'
    cone: str = 'elliptic'
    solref: tuple[float, float] = (0.02, 1.0)
    solimp: tuple[float, float, float] = (0.9, 0.95, 0.001)
    torsional_friction: float = 0.005
    rolling_friction: float = 0.0001


def _numbers(values) -> str:
    return ' '.join(f'{float(v):.6g}' for v in values)


def _sub(parent, tag: str, **attrib):
    return ET.SubElement(parent, tag, {k: str(v) for k, v in attrib.items()})


def _header(root, options: MjcfOptions, friction: float) -> None:
    _sub(root, 'compiler', angle='radian', inertiafromgeom='false', autolimits='true')
    _sub(root, 'option', timestep=f'{options.timestep:g}', integrator=options.integrator,
         cone=options.cone, gravity=f'0 0 {-GRAVITY:g}')
    default = _sub(root, 'default')
    _sub(_sub(default, 'default', **{'class': 'visual'}), 'geom', type='mesh', contype=0,
         conaffinity=0, group=VISUAL_GROUP)
    _sub(_sub(default, 'default', **{'class': 'collision'}), 'geom', type='box',
         group=COLLISION_GROUP, condim=3,
         friction=_numbers((friction, options.torsional_friction, options.rolling_friction)),
         solref=_numbers(options.solref), solimp=_numbers(options.solimp))


def _assets(root, built: Architecture, bodies: list[Body], meshes: MeshFolder) -> dict:
    """Materials and meshes; returns, per model id, its (mesh name, material name) pairs."""
    asset = _sub(root, 'asset')
    _sub(asset, 'material', name='floor', rgba=_numbers(FLOOR_RGBA))
    _sub(asset, 'material', name='wall', rgba=_numbers(WALL_RGBA))
    for name, room in built.floors:
        slab = floor_slab(room)
        _sub(asset, 'mesh', name=name, vertex=_numbers(np.asarray(slab.vertices).ravel()),
             face=' '.join(str(int(i)) for i in np.asarray(slab.faces).ravel()))
    used_materials: set[str] = set()
    visuals: dict[str, list[tuple[str, str]]] = {}
    for body in bodies:
        model = body.variant.model_id
        if model in visuals:
            continue
        visuals[model] = []
        for material, file in meshes.obj_per_material(body.variant).items():
            name = f'{safe_name(model)}__{safe_name(material)}'
            _sub(asset, 'mesh', name=name, file=meshes.relative(file))
            visuals[model].append((name, f'm_{safe_name(material)}'))
            used_materials.add(material)
    for material in sorted(used_materials):
        m = MATERIALS[material]
        _sub(asset, 'material', name=f'm_{safe_name(material)}',
             rgba=_numbers(np.asarray(m.rgba) / 255.0),
             specular=f'{0.5 * m.metallic + 0.1:.3g}', shininess=f'{1.0 - m.roughness:.3g}',
             reflectance='0')
    return visuals


def _architecture(world, built: Architecture) -> None:
    _sub(world, 'light', name='sun', directional='true', pos='0 0 10', dir='0.5 -0.1 -0.9',
         diffuse='0.8 0.8 0.8')
    for name, room in built.floors:
        floor = floor_box(room)
        _sub(world, 'geom', name=name, **{'class': 'collision'}, pos=_numbers(floor.centre),
             quat=_numbers(quat_wxyz(floor.yaw)), size=_numbers(np.asarray(floor.size) / 2),
             rgba='0 0 0 0')
        _sub(world, 'geom', name=f'{name}_visual', **{'class': 'visual'}, mesh=name,
             material='floor')
    for box in built.walls:
        _sub(world, 'geom', name=box.name, **{'class': 'collision'}, group=0,
             pos=_numbers(box.centre), quat=_numbers(quat_wxyz(box.yaw)),
             size=_numbers(np.asarray(box.size) / 2), material='wall')


def _body(world, body: Body, visuals, fixed: bool) -> None:
    b = _sub(world, 'body', name=safe_name(body.id), pos=_numbers(body.position),
             quat=_numbers(quat_wxyz(body.yaw)))
    if not fixed:
        _sub(b, 'freejoint', name=safe_name(body.id))
    i = body.inertia
    _sub(b, 'inertial', pos=_numbers(body.com), mass=f'{body.mass:.6g}',
         fullinertia=_numbers((i[0, 0], i[1, 1], i[2, 2], i[0, 1], i[0, 2], i[1, 2])))
    for mesh, material in visuals[body.variant.model_id]:
        _sub(b, 'geom', **{'class': 'visual'}, mesh=mesh, material=material)
    for k, piece in enumerate(body.pieces):
        _sub(b, 'geom', name=f'{safe_name(body.id)}__collision_{k}', **{'class': 'collision'},
             pos=_numbers(piece.centre), size=_numbers(np.asarray(piece.size) / 2),
             rgba='0.5 0.5 0.9 0.4')


def export_mjcf(scene: Scene | HouseScene, path: str | Path, mesh_dir: str | Path | None = None,
                fixed: bool = False, physics: PhysicsConfig = DEFAULT_PHYSICS,
                options: MjcfOptions = MjcfOptions(), catalog: Catalog | None = None) -> Path:
    """Write ``scene``, a room or a whole house, as an MJCF model to ``path``;
    per-material OBJ meshes go to ``mesh_dir`` (default ``<stem>_meshes/`` beside the file),
    named relative to it. ``fixed`` welds the furniture to the world instead of giving it
    free joints."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    meshes = MeshFolder(mesh_dir or path.parent / f'{path.stem}_meshes', path.parent)
    bodies = world_bodies(scene, physics, catalog)
    built = architecture_of(scene)
    root = ET.Element('mujoco', model='scene_synth_room')
    _header(root, options, physics.friction)
    visuals = _assets(root, built, bodies, meshes)
    world = _sub(root, 'worldbody')
    _architecture(world, built)
    for body in bodies:
        _body(world, body, visuals, fixed or body.fixed)
    ET.indent(root)
    path.write_text(ET.tostring(root, encoding='unicode') + '\n')
    return path
