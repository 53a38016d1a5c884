"""A furnished room or house as one binary glTF: floor, walls and objects, y up as glTF
expects.

Every object is a node named after its id (in a house, ``ROOM/ID``), with one child per
material of its catalog mesh; each floor slab and each wall piece are nodes of their own (a
house's walls once each, ``architecture.house_wall_boxes``). glTF carries no physics: it is the
format for viewers and renderers (Blender, three.js, Omniverse's importer).
"""
from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import trimesh

from ..catalog import Catalog
from ..house import HouseScene
from ..meshes import scene_mesh
from ..scene import Scene
from .architecture import FLOOR_RGBA, WALL_RGBA, architecture_of, room_meshes
from .physics import body_id

Z_UP_TO_Y_UP = np.array([[1, 0, 0, 0], [0, 0, 1, 0], [0, -1, 0, 0], [0, 0, 0, 1]], float)


def export_gltf(scene: Scene | HouseScene, path: str | Path, catalog: Catalog | None = None
                ) -> Path:
    """One binary glTF of the room or house and its objects, y-up as glTF viewers expect;
    objects of the user's ``catalog`` show the user's meshes."""
    built = architecture_of(scene)
    if isinstance(scene, HouseScene):
        scene = Scene(next(iter(scene.scenes.values())).room,
                      [replace(o, id=body_id(rid, o.id), support=None)
                       for rid, o in scene.objects()])
    out = scene_mesh(scene, catalog)
    floors = {name for name, _ in built.floors}
    for name, mesh in room_meshes(built).items():
        colour = list(FLOOR_RGBA if name in floors else WALL_RGBA)
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
