"""A furnished room as one binary glTF: floor, walls and objects, y up as glTF expects.

Every object is a node named after its id, with one child per material of its catalog mesh;
the floor slab and each wall piece are nodes of their own. glTF carries no physics: it is the
format for viewers and renderers (Blender, three.js, Omniverse's importer).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

from ..catalog import Catalog
from ..meshes import scene_mesh
from ..scene import Scene
from .architecture import FLOOR_RGBA, WALL_RGBA, room_meshes

Z_UP_TO_Y_UP = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], float)


def export_gltf(scene: Scene, path: str | Path, catalog: Catalog | None = None) -> Path:
    """One binary glTF of the room and its objects, y-up as glTF viewers expect; objects
    of the user's ``catalog`` show the user's meshes."""
    out = scene_mesh(scene, catalog)
    for name, mesh in room_meshes(scene.room).items():
        colour = list(FLOOR_RGBA if name == 'floor' else WALL_RGBA)
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
