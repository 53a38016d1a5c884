"""A user model's mesh as the exporters draw it: the file's triangle meshes put in the
package's object frame (``user_catalog.measure.placement``) and stretched onto the model's
box, like a procedural model (``meshes.builder.Builder.finish``): ``x in [-depth/2, depth/2]``,
``y in [-width/2, width/2]``, ``z in [0, height]``.

Each mesh of the file is one part. The exporters write the package's named materials
(``meshes.MATERIALS``), so a part is painted with the material nearest its main colour;
textures are not carried over.
"""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
import trimesh

from ..catalog import UserModel
from ..errors import CatalogError, quoted
from .builder import Part
from .materials import MATERIALS

DEFAULT_MATERIAL = 'paint_grey'


def load_triangles(path: Path) -> list[tuple[str, object]]:
    """(name, trimesh.Trimesh) of every triangle mesh in the file, with the file's node
    transforms applied (glTF scenes, OBJ objects); point clouds and lines are left out.
    Raises whatever trimesh raises on a file it cannot read."""
    loaded = trimesh.load(str(path), force='scene', process=False)
    out = []
    for node in loaded.graph.nodes_geometry:
        transform, name = loaded.graph[node]
        g = loaded.geometry.get(name)
        if isinstance(g, trimesh.Trimesh) and len(g.faces) and len(g.vertices):
            g = g.copy()
            g.apply_transform(transform)
            out.append((str(node), g))
    return out


def nearest_material(rgba) -> str:
    """The opaque palette material whose colour is nearest ``rgba`` (0-255)."""
    rgb = np.asarray(rgba, float)[:3]
    opaque = [m for m in MATERIALS.values() if not m.transparent]
    return min(opaque, key=lambda m: float(np.sum((np.asarray(m.rgba[:3]) - rgb) ** 2))).name


def _main_colour(mesh):
    """The mesh's main colour (RGBA 0-255), or None when it has none of its own."""
    visual = mesh.visual
    try:
        if getattr(visual, 'kind', None) == 'texture' or hasattr(visual, 'material'):
            colour = getattr(visual.material, 'main_color', None)
        elif getattr(visual, 'kind', None) is None:
            return None                                  # no colours in the file
        else:
            colour = visual.main_color
    except Exception:      # a visual trimesh cannot summarise is painted the default
        return None
    return None if colour is None else np.asarray(colour, float)


@lru_cache(maxsize=64)
def _file_meshes(source: str, stamp) -> tuple[tuple[str, str, np.ndarray, np.ndarray], ...]:
    """(name, material, vertices, faces) of the file's meshes, in the file's coordinates."""
    out = []
    for name, m in load_triangles(Path(source)):
        colour = _main_colour(m)
        material = DEFAULT_MATERIAL if colour is None else nearest_material(colour)
        out.append((name, material, np.asarray(m.vertices, float),
                    np.asarray(m.faces, np.int64)))
    return tuple(out)


def user_parts(model: UserModel) -> tuple[Part, ...]:
    """The parts of ``model``'s mesh fitted to its box (read-only arrays). A mesh file that
    is gone or unreadable since the catalog was built is a ``CatalogError``."""
    try:
        st = Path(model.source).stat()
        meshes = _file_meshes(model.source, (st.st_mtime_ns, st.st_size))
    except Exception as e:         # gone, or changed into something trimesh cannot read
        raise CatalogError(f'the mesh of the user model {quoted(model.model_id)}, '
                           f'{quoted(model.source, 80)}, cannot be read any more '
                           f'({getattr(e, "strerror", None) or e}); build the catalog '
                           f'again') from None
    if not meshes:
        raise CatalogError(f'the mesh of the user model {quoted(model.model_id)} holds no '
                           f'triangles any more; build the catalog again')
    t = model.matrix
    placed = [v @ t[:3, :3].T + t[:3, 3] for _, _, v, _ in meshes]
    allv = np.vstack(placed)
    lo, hi = allv.min(axis=0), allv.max(axis=0)
    w, d, h = model.size
    t_lo, t_hi = np.array([-d / 2, -w / 2, 0.0]), np.array([d / 2, w / 2, h])
    scale = (t_hi - t_lo) / np.maximum(hi - lo, 1e-12)
    parts = []
    for (name, material, _, faces), v in zip(meshes, placed, strict=True):
        v = np.clip((v - lo) * scale + t_lo, t_lo, t_hi)
        v.setflags(write=False)
        f = faces.copy()
        f.setflags(write=False)
        parts.append(Part(name, material, v, f))
    return tuple(parts)
