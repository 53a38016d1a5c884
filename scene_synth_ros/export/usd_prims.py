"""USD prims the exports share (prim names, UsdPreviewSurface materials, triangle meshes),
and a catalog model as a USD layer of its own.

``pxr`` (usd-core) is imported where a prim is written: it is a heavy optional dependency that
only USD exports need.
"""
from __future__ import annotations

import os
from pathlib import Path
import tempfile

import numpy as np

from ..catalog import ModelVariant
from ..meshes import MATERIALS, material_meshes


def identifier(text: str, taken: set[str]) -> str:
    """A prim name for ``text``, unique among ``taken``."""
    from pxr import Tf  # usd-core: USD exports only
    name = Tf.MakeValidIdentifier(text)
    out, k = name, 1
    while out in taken:
        out, k = f'{name}_{k}', k + 1
    taken.add(out)
    return out


def surface(stage, path: str, rgba, metallic: float, roughness: float):
    from pxr import Gf, Sdf, UsdShade  # usd-core: USD exports only
    material = UsdShade.Material.Define(stage, path)
    shader = UsdShade.Shader.Define(stage, f'{path}/Surface')
    shader.CreateIdAttr('UsdPreviewSurface')
    shader.CreateInput('diffuseColor', Sdf.ValueTypeNames.Color3f).Set(Gf.Vec3f(*rgba[:3]))
    shader.CreateInput('opacity', Sdf.ValueTypeNames.Float).Set(float(rgba[3]))
    shader.CreateInput('metallic', Sdf.ValueTypeNames.Float).Set(float(metallic))
    shader.CreateInput('roughness', Sdf.ValueTypeNames.Float).Set(float(roughness))
    material.CreateSurfaceOutput().ConnectToSource(shader.ConnectableAPI(), 'surface')
    return material


def mesh(stage, path: str, vertices, faces):
    from pxr import UsdGeom, Vt  # usd-core: USD exports only
    prim = UsdGeom.Mesh.Define(stage, path)
    vertices = np.asarray(vertices, dtype=float)
    prim.CreatePointsAttr(Vt.Vec3fArray.FromNumpy(vertices.astype(np.float32)))
    prim.CreateFaceVertexCountsAttr(Vt.IntArray([3] * len(faces)))
    prim.CreateFaceVertexIndicesAttr(Vt.IntArray([int(i) for i in np.asarray(faces).ravel()]))
    prim.CreateSubdivisionSchemeAttr('none')
    prim.CreateExtentAttr([tuple(vertices.min(axis=0)), tuple(vertices.max(axis=0))])
    return prim


def model_layer_bytes(variant: ModelVariant) -> bytes:
    """The catalog model as a USD crate file: ``/Model`` (the default prim) with one mesh
    per material, bound to ``/Model/Looks/<material>``."""
    from pxr import Usd, UsdGeom, UsdShade  # usd-core: USD exports only
    stage = Usd.Stage.CreateInMemory()
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    root = UsdGeom.Xform.Define(stage, '/Model')
    stage.SetDefaultPrim(root.GetPrim())
    taken: set[str] = {'Looks'}
    for material, part in material_meshes(variant).items():
        name = identifier(material, taken)
        m = MATERIALS[material]
        look = surface(stage, f'/Model/Looks/{name}', np.asarray(m.rgba) / 255.0, m.metallic,
                        m.roughness)
        prim = mesh(stage, f'/Model/{name}', part.vertices, part.faces)
        UsdShade.MaterialBindingAPI.Apply(prim.GetPrim()).Bind(look)
    fd, tmp = tempfile.mkstemp(suffix='.usdc')
    os.close(fd)
    try:
        stage.GetRootLayer().Export(tmp)
        return Path(tmp).read_bytes()
    finally:
        os.unlink(tmp)
