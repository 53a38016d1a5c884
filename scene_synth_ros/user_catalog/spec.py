"""What the catalog is told about one model before it is measured (``ModelSpec``), and the
checks of the values a manifest (or a data set's table) gives for it.

Defaults, per model: the id is the file's stem (characters other than letters, digits,
``_``, ``-`` and ``.`` become ``_``); the axes follow the file format's own convention:
glTF (``.glb``, ``.gltf``) is y up with its front towards +z (the glTF specification),
every other format z up with its front towards +x (REP-103 and this package); ``units`` are
metres and ``scale`` is 1. The size in metres is the file's coordinates times
``units`` times ``scale``.
"""
from __future__ import annotations

from dataclasses import dataclass
import math
from pathlib import Path
import re
from typing import Any

import numpy as np

from ..categories import PAPER, Vocabulary
from ..errors import quoted
from .axes import parse_axis

GLTF_SUFFIXES = ('.glb', '.gltf')
MESH_SUFFIXES = ('.glb', '.gltf', '.obj', '.stl', '.ply', '.off')
UNITS = {'m': 1.0, 'cm': 0.01, 'mm': 0.001, 'in': 0.0254, 'ft': 0.3048}
MAX_ID = 128                   # characters, as the scene schema allows a model_id
SPEC_KEYS = ('file', 'category', 'id', 'up', 'front', 'scale', 'units')


@dataclass(frozen=True)
class ModelSpec:
    """One model to measure: its file, category, id and how its axes and units map onto
    the package's."""

    file: Path                 # absolute
    name: str                  # the file as the report names it (relative to the folder)
    category: str
    model_id: str
    up: str                    # '+y', ...
    front: str
    scale: float               # metres per unit of the file


def default_axes(path: Path) -> tuple[str, str]:
    """(up, front) of a file format's own convention (see the module docstring)."""
    return ('+y', '+z') if path.suffix.lower() in GLTF_SUFFIXES else ('+z', '+x')


def default_id(path: Path) -> str:
    return re.sub(r'[^A-Za-z0-9_.-]', '_', path.stem)[:MAX_ID] or 'model'


def category_of(text: object, vocabulary: Vocabulary = PAPER) -> str | None:
    """A category of ``vocabulary`` from its name, or a folder's (``double_bed``), else
    None: the paper's, and those of the data set whose weights are in use
    (``--weights-dir`` on the command line)."""
    if not isinstance(text, str):
        return None
    name = text.strip().lower().replace('_', ' ')
    try:
        vocabulary.info(name)
    except KeyError:
        return None
    return name


def make_spec(entry: dict[str, Any], folder: Path, defaults: dict[str, Any],
              vocabulary: Vocabulary = PAPER) -> ModelSpec | str:
    """The spec of one manifest entry (its ``file`` relative to ``folder``), with
    ``defaults`` under it; or what is wrong with it, as a report clause."""
    unknown = sorted(set(entry) - set(SPEC_KEYS), key=str)
    if unknown:
        return (f'unknown key {quoted(unknown[0])} (a model has {", ".join(SPEC_KEYS)})')
    file = entry.get('file')
    if not isinstance(file, str) or not file.strip():
        return 'no "file" (the mesh file, relative to the folder)'
    path = Path(file) if Path(file).is_absolute() else folder / file
    category = category_of(entry.get('category'), vocabulary)
    if category is None:
        return (f'category {quoted(entry.get("category"))} is not a category of ours '
                f'(`scene-synth catalog list` shows them)')
    merged = {**defaults, **entry}
    up_default, front_default = default_axes(path)
    axes = {}
    for key, default in (('up', up_default), ('front', front_default)):
        v = parse_axis(merged.get(key, default))
        if v is None:
            return f'{key} {quoted(merged.get(key))} is not an axis (+x, -x, +y, -y, +z or -z)'
        axes[key] = v
    if abs(float(np.dot(axes['up'], axes['front']))) > 0.5:
        return 'its front and up are the same axis'
    units = merged.get('units', 'm')
    if units not in UNITS:
        return f'units {quoted(units)} are not one of {", ".join(UNITS)}'
    scale = merged.get('scale', 1.0)
    if isinstance(scale, bool) or not isinstance(scale, (int, float)) or \
            not math.isfinite(scale) or scale <= 0:
        return f'scale {quoted(scale)} is not a positive number'
    model_id = entry.get('id', default_id(path))
    if not isinstance(model_id, str) or not model_id or len(model_id) > MAX_ID or \
            '@' in model_id or not model_id.isprintable():
        return (f'id {quoted(model_id)} must be a printable text of 1 to {MAX_ID} '
                f'characters without "@"')
    return ModelSpec(path, file, category, model_id, _axis_name(axes['up']),
                     _axis_name(axes['front']), UNITS[units] * float(scale))


def _axis_name(v: np.ndarray) -> str:
    k = int(np.argmax(np.abs(v)))
    return f'{"+" if v[k] > 0 else "-"}{"xyz"[k]}'
