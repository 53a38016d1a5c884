"""Exports of a furnished room for simulators, one module per format.

- ``sdf``: a Gazebo world (SDF 1.9), or one model to spawn into a world: floor, walls and
  objects with meshes, collision boxes, mass and inertia;
- ``gltf``: floor, walls and objects as one binary glTF, y up; no physics;
- ``mjcf``: a MuJoCo model: static floor and walls, a free body per object with its meshes,
  collision boxes, mass and inertia;
- ``urdf``: URDF for PyBullet: the room as one fixed URDF, one URDF per object, their poses;
- ``usd``: an OpenUSD stage, Z up in metres: meshes with materials, UsdPhysics colliders and
  rigid bodies.

Shared by all: ``architecture`` (the floor slab and the wall pieces with their openings),
``physics`` (each object's collision pieces, mass and inertia: one model for every format)
and ``meshfiles`` (the catalog meshes written once into a folder, named relatively). Every
writer takes a ``catalog`` (``catalog.Catalog``): objects whose model is one of the user's
show the user's mesh, stretched to the object's size; the others the procedural meshes.
``rest`` loads MJCF and URDF exports in MuJoCo and PyBullet and checks that the furniture
stands still.

``FORMATS`` names them for the command line and the node (``export_formats``), and
``write`` writes one; ``parse_formats`` reads a comma list of names. A format's module is
imported when it first writes (the node starts without trimesh, pxr and their kin).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ..catalog import Catalog
from ..errors import SceneSynthError, quoted
from ..lazy import lazy_names
from ..scene import Scene
from .architecture import (
    FLOOR_THICKNESS,
    WALL_THICKNESS,
    WallBox,
    floor_box,
    floor_slab,
    room_meshes,
    wall_boxes,
)

# The names imported from their modules when first asked for (PEP 562).
_LAZY = {'export_gltf': 'gltf', 'export_mjcf': 'mjcf', 'export_sdf': 'sdf',
         'export_urdf': 'urdf', 'export_usd': 'usd', 'Body': 'physics',
         'PhysicsConfig': 'physics', 'Piece': 'physics', 'scene_bodies': 'physics'}


__getattr__ = lazy_names(__name__, _LAZY)


class UnknownFormat(SceneSynthError, ValueError):
    """An export format that is not one of ``FORMATS``, said in one sentence."""


@dataclass(frozen=True)
class Format:
    """One export format: its name, the suffix the node's files get, and the name of its
    writer (``writer`` gives the function)."""

    name: str
    suffix: str
    writer_name: str
    meshes: bool = True          # whether it writes mesh files (a mesh folder applies)

    @property
    def writer(self) -> Callable:
        return __getattr__(self.writer_name)


FORMATS: dict[str, Format] = {f.name: f for f in (
    Format('sdf', '.sdf', 'export_sdf'),
    Format('gltf', '.glb', 'export_gltf', meshes=False),
    Format('mjcf', '.xml', 'export_mjcf'),
    Format('urdf', '.urdf', 'export_urdf'),
    Format('usd', '.usd', 'export_usd'),
)}


def parse_formats(text: str) -> tuple[str, ...]:
    """The formats of a comma list (``'sdf,gltf'``), in the order given, without repeats;
    an unknown name is one sentence naming it and the known ones."""
    out: list[str] = []
    for part in str(text).split(','):
        name = part.strip().lower()
        if not name:
            continue
        if name not in FORMATS:
            raise UnknownFormat(f'export format {quoted(name)} is not one of '
                                f'{", ".join(FORMATS)}')
        if name not in out:
            out.append(name)
    return tuple(out)


def write(scene: Scene, fmt: str, path: str | Path, mesh_dir: str | Path | None = None,
          fixed: bool = False, catalog: Catalog | None = None) -> Path:
    """Write ``scene`` in format ``fmt`` to ``path``; mesh files go to ``mesh_dir`` (default
    ``<stem>_meshes/`` beside ``path``); ``fixed`` makes the furniture static; objects of the
    user's ``catalog`` (``catalog.Catalog``) show the user's meshes."""
    f = FORMATS[fmt]
    if not f.meshes:
        return f.writer(scene, path, catalog=catalog)
    return f.writer(scene, path, mesh_dir, fixed=fixed, catalog=catalog)

__all__ = [
    'FLOOR_THICKNESS', 'FORMATS', 'WALL_THICKNESS', 'Body', 'Format', 'PhysicsConfig', 'Piece',
    'UnknownFormat', 'WallBox', 'export_gltf', 'export_mjcf', 'export_sdf', 'export_urdf',
    'export_usd', 'floor_box', 'floor_slab', 'parse_formats', 'room_meshes', 'scene_bodies',
    'wall_boxes', 'write',
]
