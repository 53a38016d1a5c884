"""Catalog models as files: binary glTF (``.glb``) and Wavefront (``.obj`` plus ``.mtl``).

Both formats carry one primitive per material rather than per-vertex colours, because that
is what simulators and viewers (RViz's MESH_RESOURCE markers, Gazebo) read most reliably: a
glTF PBR material per primitive, or an MTL entry per ``usemtl`` group. Coordinates stay the
package's (REP-103: metres, z up); a glTF consumer that insists on glTF's y-up convention
must add its own root rotation. ``model_scene`` and ``material_meshes`` are the in-memory
forms the files are written from, also used to assemble whole scenes.
"""
from __future__ import annotations

from pathlib import Path
from typing import Iterable

import numpy as np
import trimesh

from .. import catalog
from ..catalog import ModelVariant
from ..categories import CATEGORIES
from ..errors import UnknownCategory
from .builder import Part
from .materials import MATERIALS, Material
from .registry import build_parts


def material_meshes(variant: ModelVariant) -> dict[str, trimesh.Trimesh]:
    """The model's faces grouped by material, each group a mesh with a glTF PBR material."""
    groups: dict[str, list[Part]] = {}
    for p in build_parts(variant):
        groups.setdefault(p.material, []).append(p)
    out = {}
    for mat_name, parts in groups.items():
        mat = MATERIALS[mat_name]
        verts, faces, offset = [], [], 0
        for p in parts:
            verts.append(p.vertices)
            faces.append(p.faces + offset)
            offset += len(p.vertices)
        m = trimesh.Trimesh(np.vstack(verts), np.vstack(faces), process=False)
        m.visual = trimesh.visual.TextureVisuals(material=_pbr(mat))
        out[mat_name] = m
    return out


def _pbr(mat: Material):
    return trimesh.visual.material.PBRMaterial(
        name=mat.name, baseColorFactor=list(mat.rgba), metallicFactor=mat.metallic,
        roughnessFactor=mat.roughness, alphaMode='BLEND' if mat.transparent else 'OPAQUE',
        doubleSided=mat.transparent)


def model_scene(variant: ModelVariant) -> trimesh.Scene:
    """A trimesh scene for one model: a root node named after the model id, with one child
    node (and one geometry) per material."""
    scene = trimesh.Scene()
    root = variant.model_id
    scene.graph.update(frame_to=root, frame_from=scene.graph.base_frame, matrix=np.eye(4))
    for mat_name, mesh in material_meshes(variant).items():
        scene.add_geometry(mesh, node_name=f'{root}/{mat_name}',
                           geom_name=f'{root}/{mat_name}', parent_node_name=root)
    return scene


# Written by hand rather than with trimesh.exchange.obj.export_obj (trimesh 5.2): its MTL has
# no opacity (``d``), so RViz would draw glass and water opaque, and gives every material
# the same Ka 0.4 / Ks 0.4 / Ns 1, which washes out the colours and makes metal look like
# fabric; its files are not smaller either (1 % larger over the catalog).
def _write_obj(variant: ModelVariant, path: Path) -> None:
    """Wavefront OBJ with an MTL file next to it (``<stem>.mtl``), one group per material."""
    mtl_path = path.with_suffix('.mtl')
    text, used = obj_text(variant, mtl_path.name)
    path.write_text(text)
    mtl_path.write_text(mtl_text(used))


def obj_text(variant: ModelVariant, mtllib: str) -> tuple[str, list[str]]:
    """``variant``'s mesh as Wavefront OBJ text naming the material library ``mtllib``, one
    group per material, and the names of the materials it uses, in order of first use."""
    lines = [f'# {variant.model_id} ({variant.category}), metres, z up, front +x',
             f'mtllib {mtllib}']
    groups: dict[str, list[Part]] = {}
    for p in build_parts(variant):
        groups.setdefault(p.material, []).append(p)
    offset = 1
    for mat_name, parts in groups.items():
        lines += [f'o {mat_name}', f'usemtl {mat_name}']
        for p in parts:
            lines += [f'v {x:.6f} {y:.6f} {z:.6f}' for x, y, z in p.vertices]
            lines += [f'f {i + offset} {j + offset} {k + offset}' for i, j, k in p.faces]
            offset += len(p.vertices)
    return '\n'.join(lines) + '\n', list(groups)


def mtl_text(material_names: Iterable[str]) -> str:
    """The MTL entries of the named materials (see ``MATERIALS``), in the order given."""
    mtl = []
    for mat_name in material_names:
        mat = MATERIALS[mat_name]
        r, g, bl, a = (c / 255.0 for c in mat.rgba)
        ks = f'{0.5 * mat.metallic + 0.04:.3f}'
        mtl += [f'newmtl {mat_name}', f'Kd {r:.4f} {g:.4f} {bl:.4f}', 'Ka 0 0 0',
                f'Ks {ks} {ks} {ks}', f'Ns {max(1.0, (1.0 - mat.roughness) * 200):.1f}',
                f'd {a:.3f}', 'illum 2', '']
    return '\n'.join(mtl)


def export_model(variant: ModelVariant, path: str | Path) -> Path:
    """Write ``variant``'s mesh to ``path``: binary glTF for ``.glb`` (PBR material per
    colour, flat normals), Wavefront for ``.obj`` (plus ``.mtl``)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    suffix = path.suffix.lower()
    if suffix == '.glb':
        data = trimesh.exchange.gltf.export_glb(model_scene(variant), include_normals=False)
        path.write_bytes(data)
    elif suffix == '.obj':
        _write_obj(variant, path)
    else:
        raise ValueError(f'unsupported mesh format {path.suffix!r}; use .glb or .obj')
    return path


def mesh_path(model_id: str, out_dir: str | Path, fmt: str = 'glb') -> Path:
    """Where ``export_catalog`` puts ``model_id``: ``<out_dir>/<model_id>.<fmt>``."""
    fmt = fmt.lower().lstrip('.')
    if fmt not in ('glb', 'obj'):
        raise ValueError(f'unsupported mesh format {fmt!r}; use glb or obj')
    return Path(out_dir) / f'{model_id}.{fmt}'


def export_catalog(out_dir: str | Path, fmt: str = 'glb',
                   categories: Iterable[str] | None = None) -> list[Path]:
    """Write one file per catalog variant (all categories unless ``categories`` is given)."""
    cats = list(CATEGORIES) if categories is None else list(categories)
    for c in cats:
        if c not in CATEGORIES:
            raise UnknownCategory(f'unknown category {c!r}; `scene-synth catalog list` shows '
                                  f'the catalog')
    out = []
    for c in cats:
        for v in catalog.variants(c):
            out.append(export_model(v, mesh_path(v.model_id, out_dir, fmt)))
    return out
