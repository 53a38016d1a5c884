"""The models a folder offers, as ``ModelSpec``s and report lines, from one of three
layouts (``find_specs`` picks the first that applies):

1. a manifest (``--manifest FILE``, else ``manifest.yaml``, ``manifest.yml`` or
   ``manifest.json`` in the folder): ``models`` is a list of entries with ``file`` and
   ``category`` and optionally ``id``, ``up``, ``front``, ``units``, ``scale``; an optional
   ``defaults`` mapping gives ``up``, ``front``, ``units`` or ``scale`` to every entry that
   does not say (see ``spec``);
2. 3D-FUTURE (``model_info.json`` in the folder): its list of ``{model_id, category, ...}``
   with each model's mesh at ``<model_id>/raw_model.obj`` (y up, front +z, metres); its
   categories become ours through ``future_categories.yaml`` (an editable table; pass
   another with ``category_map``);
3. one sub-folder per category (``double_bed/``, ``office chair/``) holding mesh files.

A bad entry is one report line and is skipped; a folder or manifest that cannot be read at
all is a ``CatalogError``.
"""
from __future__ import annotations

from collections import Counter
from pathlib import Path
from typing import Any

import yaml

from ..categories import PAPER, Vocabulary
from ..datasets.models import ModelCategories
from ..errors import CatalogError, DatasetError, quoted
from .spec import MESH_SUFFIXES, ModelSpec, category_of, make_spec

MANIFEST_NAMES = ('manifest.yaml', 'manifest.yml', 'manifest.json')
FUTURE_INFO = 'model_info.json'
FUTURE_MESH = 'raw_model.obj'
FUTURE_AXES = {'up': '+y', 'front': '+z', 'units': 'm'}
FUTURE_MAP = Path(__file__).with_name('future_categories.yaml')


def find_specs(folder: str | Path, manifest: str | Path | None = None,
               category_map: str | Path | None = None, vocabulary: Vocabulary = PAPER
               ) -> tuple[list[ModelSpec], list[str]]:
    """The models of ``folder`` and the report lines of those skipped; their categories are
    those of ``vocabulary``."""
    folder = Path(folder)
    if not folder.is_dir():
        raise CatalogError(f'the model folder {quoted(str(folder), 80)} does not exist')
    if manifest is None:
        manifest = next((folder / n for n in MANIFEST_NAMES if (folder / n).is_file()), None)
    if manifest is not None:
        return read_manifest(Path(manifest), folder, vocabulary)
    if (folder / FUTURE_INFO).is_file():
        return read_future(folder, category_map, vocabulary)
    return read_category_folders(folder, vocabulary)


def _yaml(path: Path, what: str) -> Any:
    try:
        return yaml.safe_load(path.read_text(encoding='utf-8'))
    except FileNotFoundError:
        raise CatalogError(f'the {what} {quoted(str(path), 80)} does not exist') from None
    except (OSError, UnicodeDecodeError) as e:
        raise CatalogError(f'cannot read the {what} {quoted(str(path), 80)}: '
                           f'{getattr(e, "strerror", None) or e}') from None
    except yaml.YAMLError as e:
        mark = getattr(e, 'problem_mark', None)
        where = f' at line {mark.line + 1}' if mark is not None else ''
        raise CatalogError(f'the {what} {quoted(str(path), 80)} is not valid YAML or '
                           f'JSON{where}') from None


def read_manifest(path: Path, folder: Path, vocabulary: Vocabulary = PAPER
                  ) -> tuple[list[ModelSpec], list[str]]:
    data = _yaml(path, 'manifest')
    if isinstance(data, list):
        data = {'models': data}
    if not isinstance(data, dict) or not isinstance(data.get('models'), list):
        raise CatalogError(f'the manifest {quoted(str(path), 80)} needs a "models" list of '
                           f'entries with file and category (docs/catalog.md, "Your own '
                           'furniture")')
    defaults = data.get('defaults') or {}
    if not isinstance(defaults, dict):
        raise CatalogError(f'the manifest\'s defaults must be a mapping (of up, front, units '
                           f'or scale), not {quoted(defaults)}')
    bad = sorted(set(defaults) - {'up', 'front', 'units', 'scale'}, key=str)
    if bad:
        raise CatalogError(f'the manifest\'s defaults may give up, front, units and scale, '
                           f'not {quoted(bad[0])}')
    specs, lines = [], []
    for i, entry in enumerate(data['models']):
        where = f'models[{i}]'
        if not isinstance(entry, dict):
            lines.append(f'{where}: not a mapping with file and category')
            continue
        spec = make_spec(entry, folder, defaults, vocabulary)
        if isinstance(spec, str):
            name = entry.get('file') if isinstance(entry.get('file'), str) else ''
            lines.append(f'{where} {quoted(name, 60)}: {spec}' if name else f'{where}: {spec}')
        else:
            specs.append(spec)
    return specs, lines


def future_mapping(path: str | Path | None = None, vocabulary: Vocabulary = PAPER
                   ) -> dict[str, str | None]:
    """3D-FUTURE category (lower case) -> our category, or None for one we drop."""
    path = Path(path) if path is not None else FUTURE_MAP
    data = _yaml(path, 'category map')
    if not isinstance(data, dict):
        raise CatalogError(f'the category map {quoted(str(path), 80)} must map 3D-FUTURE '
                           f'categories to ours (or to null)')
    out: dict[str, str | None] = {}
    for theirs, ours in data.items():
        mapped = category_of(ours, vocabulary)
        if ours is not None and mapped is None:
            raise CatalogError(f'the category map {quoted(str(path), 80)} maps '
                               f'{quoted(str(theirs))} to {quoted(ours)}, which is not a '
                               f'category of ours')
        out[str(theirs).strip().lower()] = mapped
    return out


def read_future(folder: Path, category_map: str | Path | None = None,
                vocabulary: Vocabulary = PAPER) -> tuple[list[ModelSpec], list[str]]:
    """The 3D-FUTURE models present in ``folder`` (its ``model_info.json`` may list many
    more: those are counted in one line, not one line each)."""
    try:
        table = ModelCategories(folder / FUTURE_INFO).table
    except DatasetError as e:
        raise CatalogError(str(e)) from None
    mapping = future_mapping(category_map, vocabulary)
    specs, lines = [], []
    absent, nameless, unmapped, unknown = 0, 0, Counter(), Counter()
    for model_id, entry in table.items():
        if not (folder / model_id / FUTURE_MESH).is_file():
            absent += 1
            continue
        theirs = entry.category.lower()
        if not theirs:
            nameless += 1
            continue
        if theirs not in mapping:
            unknown[entry.category] += 1
            continue
        if mapping[theirs] is None:
            unmapped[entry.category] += 1
            continue
        spec = make_spec({'file': f'{model_id}/{FUTURE_MESH}', 'category': mapping[theirs],
                          'id': model_id}, folder, FUTURE_AXES, vocabulary)
        if isinstance(spec, str):
            lines.append(f'{model_id}: {spec}')
        else:
            specs.append(spec)
    for name, n in sorted(unknown.items()):
        lines.append(f'3D-FUTURE category {quoted(name)} ({n} models) is not in the category '
                     f'map; add it there to keep them')
    for name, n in sorted(unmapped.items()):
        lines.append(f'3D-FUTURE category {quoted(name)} ({n} models) maps to none of ours')
    if nameless:
        lines.append(f'{nameless} models of {FUTURE_INFO} have no category')
    if absent:
        lines.append(f'{absent} models of {FUTURE_INFO} have no {FUTURE_MESH} in this folder')
    listed = set(table)
    for d in sorted(p for p in folder.iterdir() if p.is_dir() and p.name not in listed):
        lines.append(f'{quoted(d.name, 60)}: a model folder that {FUTURE_INFO} does not list')
    return specs, lines


def read_category_folders(folder: Path, vocabulary: Vocabulary = PAPER
                          ) -> tuple[list[ModelSpec], list[str]]:
    """Every mesh file in a sub-folder named after a category, with the format's axes."""
    specs, lines = [], []
    for d in sorted(p for p in folder.iterdir() if p.is_dir()):
        category = category_of(d.name, vocabulary)
        files = sorted(p for p in d.rglob('*') if p.suffix.lower() in MESH_SUFFIXES)
        if category is None:
            if files:
                lines.append(f'{quoted(d.name, 60)}/: not a category of ours, so its '
                             f'{len(files)} mesh files are skipped')
            continue
        for f in files:
            spec = make_spec({'file': f.relative_to(folder).as_posix(), 'category': category},
                             folder, {}, vocabulary)
            (lines.append(f'{f.relative_to(folder)}: {spec}') if isinstance(spec, str)
             else specs.append(spec))
    if not specs and not lines:
        raise CatalogError(f'{quoted(str(folder), 80)} has no manifest ({", ".join(MANIFEST_NAMES)}'
                           f'), no {FUTURE_INFO} and no category folders of mesh files')
    return specs, lines
