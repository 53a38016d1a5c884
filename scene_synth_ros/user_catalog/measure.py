"""A model file read with trimesh and measured in the package's object frame.

``placement`` is the one definition of where a model goes: its file's coordinates times
``scale``, turned by ``axes.to_package_frame`` (front onto +x, up onto +z), then moved by
``offset`` so that its bounding box is centred on the origin in x and y and stands on z = 0.
``measure`` finds that offset and the box's size as ``scene.PlacedObject`` has it: (width
along y, depth along x, height along z), and checks the model; what is wrong with it is a
report clause instead of a model.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..catalog import UserModel
from ..categories import PAPER, Vocabulary
from ..errors import number
from .axes import parse_axis, to_package_frame
from .spec import ModelSpec

MAX_FILE_BYTES = 512 * 2 ** 20
MIN_EXTENT = 1e-4              # m: a box thinner than this along any axis has no volume
UNIT_HINTS = {'cm': 0.01, 'mm': 0.001, 'in': 0.0254}   # tried on an implausible size


def placement(up: str, front: str, scale: float, offset) -> np.ndarray:
    """The 4x4 transform from a model file's coordinates to the package's object frame."""
    m = np.eye(4)
    m[:3, :3] = scale * to_package_frame(parse_axis(up), parse_axis(front))
    m[:3, 3] = np.asarray(offset, float)
    return m


def _file_problem(path: Path) -> str | None:
    if not path.exists():
        return 'no such file'
    if not path.is_file():
        return 'not a file'
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        return f'{size / 2 ** 20:.0f} MB, over the {MAX_FILE_BYTES // 2 ** 20} MB a model may have'
    return None


def measure(spec: ModelSpec, vocabulary: Vocabulary = PAPER) -> UserModel | str:
    """The model of ``spec``, measured; or what is wrong with it, as a report clause."""
    problem = _file_problem(spec.file)
    if problem:
        return problem
    from ..meshes.user import load_triangles  # trimesh: building a catalog only
    try:
        meshes = load_triangles(spec.file)
    except Exception as e:          # any reader failure is this file's problem, not ours
        return f'trimesh cannot read it ({type(e).__name__}: {e})'
    if not meshes:
        return 'it holds no triangles (an empty mesh)'
    vertices = np.vstack([np.asarray(m.vertices, float) for _, m in meshes])
    if not np.all(np.isfinite(vertices)):
        return 'it has non-finite vertex coordinates (NaN or infinity)'
    turned = vertices @ placement(spec.up, spec.front, spec.scale, (0, 0, 0))[:3, :3].T
    lo, hi = turned.min(axis=0), turned.max(axis=0)
    # Rounded to the micrometre: the size read back from the catalog file is the same
    depth, width, height = (round(float(v), 6) for v in hi - lo)
    if min(depth, width, height) < MIN_EXTENT:
        return (f'its box is flat ({_size(width, depth, height)}): a model needs volume '
                f'(is its scale right?)')
    problem = _implausible(spec, width, depth, height, vocabulary)
    if problem:
        return problem
    offset = tuple(round(float(v), 6) + 0.0 for v in (-(lo[0] + hi[0]) / 2,
                                                       -(lo[1] + hi[1]) / 2, -lo[2]))
    m = placement(spec.up, spec.front, spec.scale, offset)
    return UserModel(spec.model_id, spec.category, (width, depth, height), 0,
                     str(spec.file.resolve()), tuple(float(v) for v in m.ravel()))


def _size(w: float, d: float, h: float) -> str:
    return f'{number(w)} x {number(d)} x {number(h)} m'


def _implausible(spec: ModelSpec, w: float, d: float, h: float,
                 vocabulary: Vocabulary = PAPER) -> str | None:
    """Why (width, depth, height) is implausible for the category, with a hint at the
    likely mistake (units, a front along the wrong axis), or None."""
    info = vocabulary.info(spec.category)
    if info.size_is_plausible(w, d, h):
        return None
    # The ranges as ``size_is_plausible`` widens them by default (by half).
    bad = [f'{label} {number(v)} m is not within {number(lo * 0.5)}-{number(hi * 1.5)} m'
           for label, v, (lo, hi) in (('width', w, info.width), ('depth', d, info.depth),
                                      ('height', h, info.height))
           if not lo * 0.5 <= v <= hi * 1.5]
    hint = next((f'; are its units {u}?' for u, k in UNIT_HINTS.items()
                 if info.size_is_plausible(w * k, d * k, h * k)), '')
    if not hint and info.size_is_plausible(d, w, h):
        hint = '; is its front axis right?'
    if not hint and (info.size_is_plausible(w, h, d) or info.size_is_plausible(h, d, w)):
        hint = '; is its up axis right?'
    return f'a {_size(w, d, h)} {spec.category} is implausible: {"; ".join(bad)}{hint}'
