"""The mesh files an export refers to, written once into one folder and named relatively.

Every format shows an object as its catalog model (``meshes.variant_for``). The files go into
a mesh folder (``meshes/`` of the node's ``export_dir``, or ``<stem>_meshes/`` beside a file
written from the command line) and are referred to by paths relative to the file that names
them, so the output folder can be moved as a whole:

- ``<model>.obj`` + ``<model>.mtl``: one OBJ with a group per material (Gazebo, PyBullet);
- ``<model>/<material>.obj``: one OBJ per material, for MuJoCo, which gives a mesh only one
  material and does not read groups;
- ``<model>.usdc``: the model as a USD layer with one mesh and one UsdPreviewSurface per
  material (USD).

A file already holding the bytes it would get is left alone, so rooms exported into one
folder share their models and a reader never sees a file change under it for nothing.
"""
from __future__ import annotations

import os
from pathlib import Path

from ..catalog import ModelVariant
from ..files import safe_name, write_atomic
from ..meshes import material_meshes, mtl_text, obj_text
from .usd_prims import model_layer_bytes


def obj_of(mesh, comment: str) -> str:
    """One mesh (a trimesh) as OBJ text without groups or materials."""
    lines = [f'# {comment}, metres, z up']
    lines += [f'v {x:.6f} {y:.6f} {z:.6f}' for x, y, z in mesh.vertices]
    lines += [f'f {i + 1} {j + 1} {k + 1}' for i, j, k in mesh.faces]
    return '\n'.join(lines) + '\n'


class MeshFolder:
    """Writes model files into ``folder`` and names them relative to ``referrer``, the
    directory of the file that refers to them."""

    def __init__(self, folder: str | Path, referrer: str | Path):
        self.folder = Path(folder)
        self.referrer = Path(referrer)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.written: set[Path] = set()

    def relative(self, path: Path) -> str:
        """``path`` as the referring file names it (POSIX separators)."""
        return Path(os.path.relpath(path.resolve(), self.referrer.resolve())).as_posix()

    def _write(self, path: Path, data: str | bytes) -> None:
        if path in self.written:
            return
        raw = data.encode('utf-8') if isinstance(data, str) else data
        if not (path.is_file() and path.read_bytes() == raw):
            path.parent.mkdir(parents=True, exist_ok=True)
            write_atomic(path, raw)
        self.written.add(path)

    def obj(self, variant: ModelVariant) -> Path:
        """The model as one OBJ with its MTL beside it; returns the OBJ's path."""
        path = self.folder / f'{safe_name(variant.model_id)}.obj'
        if path not in self.written:
            text, used = obj_text(variant, path.with_suffix('.mtl').name)
            self._write(path.with_suffix('.mtl'), mtl_text(used))   # the one referred to first
            self._write(path, text)
        return path

    def obj_per_material(self, variant: ModelVariant) -> dict[str, Path]:
        """One OBJ per material of the model, by material name."""
        out = {}
        for material, mesh in material_meshes(variant).items():
            path = self.folder / safe_name(variant.model_id) / f'{safe_name(material)}.obj'
            if path not in self.written:
                self._write(path, obj_of(mesh, f'{variant.model_id}, material {material}'))
            out[material] = path
        return out

    def usd(self, variant: ModelVariant) -> Path:
        """The model as a USD layer (binary crate file)."""
        path = self.folder / f'{safe_name(variant.model_id)}.usdc'
        if path not in self.written:
            self._write(path, model_layer_bytes(variant))
        return path

    def text(self, name: str, data: str) -> Path:
        """A file of the room's own (a floor slab) under ``name``."""
        path = self.folder / name
        self._write(path, data)
        return path
