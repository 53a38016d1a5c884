"""Whole scenes as trimesh scenes: every placed object of a ``scene_synth_ros.scene.Scene``
shown as its catalog model, posed by its position and yaw.

``variant_for`` decides which model an object shows (its catalog variant, re-sized when the
object's size differs; with a user catalog, ``catalog.Catalog``, the user's model when the
object's model id is one), ``object_transform`` where it goes, and ``scene_mesh`` builds the
scene graph, sharing geometry between objects that show the same model at the same size.
"""
from __future__ import annotations

from dataclasses import replace
from typing import Sequence

import numpy as np
import trimesh

from ..catalog import Catalog, ModelVariant
from .builder import rot_z
from .export import material_meshes
from .shipped import shipped_variant


def object_transform(position: Sequence[float], yaw: float) -> np.ndarray:
    """World transform of a placed object: translate(position) . rotate_z(yaw)."""
    t = np.eye(4)
    t[:3, :3] = rot_z(float(yaw))
    t[:3, 3] = [float(v) for v in position]
    return t


def _resized_id(model_id: str, size: tuple[float, float, float]) -> str:
    return f'{model_id}@{size[0]:.3f}x{size[1]:.3f}x{size[2]:.3f}'


def variant_for(obj, catalog: Catalog | None = None) -> ModelVariant:
    """The model a placed object shows: its catalog variant, re-sized to ``obj.size`` when
    the object's size differs from the catalog's (style kept); for an unknown model id, the
    style of the category's nearest variant. A model of the user's ``catalog`` shows the
    user's mesh, stretched to ``obj.size``."""
    size = tuple(float(v) for v in obj.size)
    user = catalog.user_model(obj.model_id) if catalog is not None else None
    if user is not None and user.category == obj.category:
        if np.allclose(user.size, size, atol=1e-6):
            return user
        return replace(user, model_id=_resized_id(user.model_id, size), size=size)
    v = shipped_variant(obj)
    if v is not None and v.model_id == obj.model_id:
        if np.allclose(v.size, size, atol=1e-6):
            return v
        return ModelVariant(_resized_id(v.model_id, size), v.category, size, v.style)
    return ModelVariant(_resized_id(obj.model_id or obj.category, size), obj.category, size,
                        0 if v is None else v.style)


def scene_mesh(scene, catalog: Catalog | None = None) -> trimesh.Scene:
    """A trimesh scene with every object of a ``scene_synth_ros.scene.Scene``.

    Each object is a node named after its id whose transform is
    ``translate(position) . rotate_z(yaw)``; its children are one node per material
    (``<object id>/<material>``) with identity transforms. Geometry is shared between
    objects showing the same model at the same size. The room itself is not included.
    ``catalog``: the user's models the objects may show (``variant_for``)."""
    out = trimesh.Scene()
    base = out.graph.base_frame
    cache: dict[str, dict[str, trimesh.Trimesh]] = {}
    for obj in scene.objects:
        v = variant_for(obj, catalog)
        if v.model_id not in cache:
            cache[v.model_id] = material_meshes(v)
        out.graph.update(frame_to=obj.id, frame_from=base,
                         matrix=object_transform(obj.position, obj.yaw))
        for mat_name, mesh in cache[v.model_id].items():
            geom = f'{v.model_id}/{mat_name}'
            if geom not in out.geometry:
                out.add_geometry(mesh, geom_name=geom, node_name=f'{obj.id}/{mat_name}',
                                 parent_node_name=obj.id)
            else:
                out.graph.update(frame_to=f'{obj.id}/{mat_name}', frame_from=obj.id,
                                 matrix=np.eye(4), geometry=geom)
    return out
