"""The catalog meshes shipped with the package, for RViz on any machine.

Every catalog model is a Wavefront OBJ file in the repository's ``meshes/`` folder, installed
to ``share/scene_synth_ros/meshes/`` and referred to from markers as
``package://scene_synth_ros/meshes/<model id>.obj``, which RViz resolves through the ament
index of the machine it runs on. Each OBJ names its material library ``<model id>.mtl``
beside it, with just the materials it uses; RViz's mesh loader (assimp) opens that file
relative to the OBJ's URI, so through the same ``package://`` folder. The files are what
``export_model`` (``scene-synth catalog export --format obj``) writes, with ``\\n`` line ends.

An object that shows a catalog model at another size, or whose model id the catalog does not
have, uses a shipped mesh as well: its own variant, or the nearest variant of its category,
stretched by the marker's scale (``mesh_scale``). ``scripts/build_meshes.py`` writes the
folder; the files are a pure function of the catalog, byte for byte.

A model of the user's catalog (``catalog.UserModel``) is shown by the STL that
``scene-synth catalog build`` wrote beside the catalog file (``user_marker``), referred to
as a ``file://`` URI: RViz reads it on the machine the node runs on or one that shares its
files.
"""
from __future__ import annotations

import os
from pathlib import Path

from .. import catalog
from ..catalog import Catalog, ModelVariant, UserModel
from ..categories import CATEGORIES
from ..files import safe_name

PACKAGE = 'scene_synth_ros'
SUFFIXES = ('.obj', '.mtl')


def shipped_name(model_id: str) -> str:
    """The file name of a catalog model's shipped mesh."""
    return f'{safe_name(model_id)}.obj'


def package_uri(model_id: str) -> str:
    """The ``package://`` URI of a catalog model's shipped mesh."""
    return f'package://{PACKAGE}/meshes/{shipped_name(model_id)}'


def shipped_variant(obj) -> ModelVariant | None:
    """The catalog model whose shipped mesh shows a placed object: its own model, else the
    nearest model of its category by footprint; None for a category the catalog lacks.
    Models of a data set's room types have no shipped mesh: a category of the same name
    in the paper's table lends its own."""
    try:
        v = catalog.get(obj.model_id)
    except KeyError:
        v = None
    if v is not None and catalog.DATA_SET_MARK in v.model_id:
        v = None
    if v is not None and v.category == obj.category:
        return v
    if obj.category not in CATEGORIES:
        return None
    return catalog.nearest(obj.category, float(obj.width), float(obj.depth))


def user_marker(obj, models: Catalog | None) -> UserModel | None:
    """The user's model whose marker mesh (``UserModel.marker``) shows ``obj``; None when
    ``models`` has no such model of its category or the STL is missing (a catalog built
    before the markers were written, or the file removed since), so that the marker falls
    back to a procedural mesh instead of showing nothing."""
    m = models.user_model(obj.model_id) if models is not None else None
    if m is None or m.category != obj.category or not m.marker:
        return None
    return m if os.path.isfile(m.marker) else None


def file_uri(path: str) -> str:
    """The ``file://`` URI of an absolute path, as RViz's resource retriever reads it."""
    return 'file://' + os.path.abspath(path)


def mesh_scale(obj, variant: ModelVariant) -> tuple[float, float, float]:
    """The marker scale that stretches ``variant``'s mesh onto ``obj``'s box: per axis of the
    mesh (x: depth, y: width, z: height), the object's size over the variant's."""
    return (float(obj.depth) / variant.depth, float(obj.width) / variant.width,
            float(obj.height) / variant.height)


def shipped_files() -> dict[str, bytes]:
    """Every file of the shipped ``meshes/`` folder, by name: per catalog model its OBJ and,
    just before it, the MTL it names. Text with ``\\n`` line ends, the same bytes everywhere."""
    from .export import mtl_text, obj_text  # trimesh: only writing the files needs it
    out = {}
    for v in catalog.all_variants():
        obj_name = shipped_name(v.model_id)
        mtl_name = obj_name[:-len('.obj')] + '.mtl'
        text, used = obj_text(v, mtl_name)
        out[mtl_name] = mtl_text(used).encode('utf-8')
        out[obj_name] = text.encode('utf-8')
    return out


def write_shipped_meshes(out_dir: str | Path, prune: bool = False) -> list[Path]:
    """Write ``shipped_files`` into ``out_dir``; a file already holding the same bytes is left
    alone. With ``prune``, remove the ``.obj``/``.mtl`` files there that are not shipped any
    more (a model dropped from the catalog). Returns the paths written or kept, sorted."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    files = shipped_files()
    for name, data in files.items():
        path = out_dir / name
        if not (path.is_file() and path.read_bytes() == data):
            path.write_bytes(data)
    if prune:
        for path in out_dir.iterdir():
            if path.suffix in SUFFIXES and path.name not in files:
                path.unlink()
    return sorted(out_dir / name for name in files)
