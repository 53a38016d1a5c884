"""``import_dataset``: files of one format -> one Scene JSON per room, the report and the
data-set description, written into one folder.

The files: each INPUT is a file, or a folder searched for the format's files
(``FILE_PATTERNS``). The tables the formats need are found beside the inputs when not
given (``TABLE_NAMES``): 3D-FRONT's 3D-FUTURE category mapping (CSV) or ``model_info.json``,
SUNCG's ``ModelCategoryMapping.csv``, ProcTHOR's ``procthor_asset_boxes.json``. A file
that cannot be read at all, and a ProcTHOR line that is not a house, are report lines.
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
import json
from pathlib import Path
import re
from typing import Any, Iterator, Sequence

from ..categories import PAPER
from ..errors import DatasetError
from ..files import write_atomic
from ..scene import Room, Scene
from ..schema import SceneValidationError, format_json, parse_house_layout
from . import allowance, description, front3d, procthor, suncg
from .assemble import assemble
from .config import FORMATS, ImportConfig, load_room_types
from .houses import house_of
from .models import AssetBoxes, ModelBoxes, ModelCategories
from .records import RawRoom
from .report import ImportReport
from .training import room_type_specs

FILE_PATTERNS = {
    '3dfront': ('*.json',),
    'suncg': ('house.json', '*house*.json'),
    'procthor': ('*.jsonl', '*.jsonl.gz'),
}
TABLE_NAMES = {
    '3dfront': ('3dfuture_model_category_mapping.csv', 'model_info.json',
                'model_category_mapping.csv'),
    'suncg': ('ModelCategoryMapping.csv', '*odel*ategory*apping*.csv'),
    'procthor': ('procthor_asset_boxes.json',),
}
NOT_SCENES = {'model_info.json', 'procthor_asset_boxes.json'}


@dataclass
class ImportResult:
    """The scenes (file name -> Scene dict; empty when not kept), the report and the
    description's dict."""

    scenes: dict[str, dict[str, Any]] = field(default_factory=dict)
    report: ImportReport | None = None
    description: dict[str, Any] | None = None
    houses: dict[str, dict[str, Any]] = field(default_factory=dict)   # name -> house layout


def find_files(fmt: str, inputs: Sequence[str | Path]) -> list[Path]:
    """The format's files named by ``inputs`` (files as given, folders searched)."""
    out: list[Path] = []
    for item in inputs:
        p = Path(item)
        if p.is_file():
            out.append(p)
        elif p.is_dir():
            found = {f for pattern in FILE_PATTERNS[fmt] for f in p.rglob(pattern)
                     if f.is_file() and f.name not in NOT_SCENES}
            out += sorted(found)
        else:
            raise DatasetError(f'{p}: no such file or folder')
    if not out:
        raise DatasetError(f'no {fmt} files in {", ".join(str(i) for i in inputs)} (looked '
                           f'for {", ".join(FILE_PATTERNS[fmt])})')
    return out


def find_table(fmt: str, given: str | Path | None, files: list[Path]) -> Path:
    """The mapping or asset table: ``given``, else the first known name beside an input."""
    if given is not None:
        if not Path(given).is_file():
            raise DatasetError(f'{given}: no such file')
        return Path(given)
    for folder in dict.fromkeys(f.parent for f in files):
        for name in TABLE_NAMES[fmt]:
            hit = sorted(folder.glob(name))
            if hit:
                return hit[0]
    flag = '--asset-sizes' if fmt == 'procthor' else '--category-map'
    raise DatasetError(f'no {" or ".join(TABLE_NAMES[fmt][:2])} beside the inputs; name the '
                       f'table with {flag} FILE')


def import_dataset(fmt: str, inputs: Sequence[str | Path], out: str | Path | None = None,
                   config: ImportConfig | None = None, table: str | Path | None = None,
                   models: str | Path | None = None,
                   keep_scenes: bool | None = None, layouts: bool = False) -> ImportResult:
    """Import the ``fmt`` files of ``inputs`` (see the module docstring). With ``out``, the
    scenes are written there as they come, with ``report.txt``/``report.json`` and
    ``dataset.yaml`` at the end; ``result.scenes`` holds them when ``keep_scenes`` (by
    default only without ``out``: a large data set need not fit in memory). With
    ``layouts``, each house's kept rooms are also an empty house layout (``houses.py``),
    in ``result.houses`` and, with ``out``, written to ``out/houses/``."""
    if fmt not in FORMATS:
        raise DatasetError(f'unknown format {fmt!r}; expected one of {", ".join(FORMATS)}')
    config = config or ImportConfig()
    if not config.room_types:
        config = replace(config, room_types=load_room_types(fmt))
    keep = out is None if keep_scenes is None else keep_scenes
    files = find_files(fmt, inputs)
    report = ImportReport(fmt, [str(f) for f in files])
    result = ImportResult(report=report)
    describer = description.Describer(fmt, config)
    deriver = allowance.Deriver()
    names: set[str] = set()
    rooms: dict[str, dict[str, Room]] = {}       # house -> room -> its shell (``layouts``)
    if out is not None:
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
    for raw in _rooms(fmt, files, find_table(fmt, table, files), models, config, report):
        scene = assemble(raw, fmt, config, report)
        if scene is None:
            continue
        name = _unique(scene_name(fmt, raw), names)
        names.add(name)
        describer.add(scene)
        deriver.add(Scene.from_dict(scene))
        if out is not None:
            _write_scene(out, name, scene)
        if keep:
            result.scenes[name] = scene
        if layouts:
            rooms.setdefault(_safe(raw.house_id), {})[_safe(raw.room_id)] = \
                Room.from_dict(scene['room'])
    result.description = {**describer.result(), 'allowance': deriver.result().to_dict()}
    if layouts:
        _houses(fmt, rooms, result, out, report)
    if out is not None:
        report.write(out)
        description.write(result.description, out / description.FILE_NAME)
    return result


def _houses(fmt: str, rooms: dict[str, dict[str, Room]], result: ImportResult,
            out: Path | None, report: ImportReport) -> None:
    """Each house's kept rooms as a house layout, checked as a layout sent to the node
    would be; what cannot be one is a report line."""
    vocabulary = PAPER
    if not {r.room_type for kept in rooms.values() for r in kept.values()} <= set(
            PAPER.room_types):        # a data set's own room types: as its rooms know them
        try:
            vocabulary = PAPER.with_specs(
                room_type_specs(description.check(result.description)).values())
        except DatasetError as e:
            report.add('layout', 'no house layout', 'every house', str(e))
            return
    for house_id, kept in rooms.items():
        house, notes = house_of(kept, house_id)
        for note in notes:
            report.add('layout', 'left out of its house layout', f'house {house_id}', note)
        if house is None:
            continue
        layout = house.to_dict()
        try:
            parse_house_layout(layout, vocabulary)
        except SceneValidationError as e:
            report.add('layout', 'no house layout', f'house {house_id}', str(e))
            continue
        name = f'{fmt}_{house_id}'
        result.houses[name] = layout
        if out is not None:
            (out / 'houses').mkdir(exist_ok=True)
            write_atomic(out / 'houses' / f'{name}.json', format_json(layout) + '\n')


def _rooms(fmt: str, files: list[Path], table: Path, models, config: ImportConfig,
           report: ImportReport) -> Iterator[RawRoom]:
    if fmt == 'procthor':
        assets = AssetBoxes(table)
        for path in files:
            yield from _procthor_file(path, assets, report)
        return
    categories = ModelCategories(table)
    boxes = ModelBoxes(models, fmt) if models is not None else None
    for path in files:
        try:
            data = json.loads(path.read_text(encoding='utf-8'))
            if fmt == '3dfront':
                rooms = list(front3d.read(path, categories, boxes, data))
            else:
                rooms = list(suncg.read(path, categories, boxes, set(config.room_types), data))
        except (OSError, UnicodeDecodeError, ValueError, TypeError, KeyError,
                AttributeError, RecursionError) as e:
            report.add('file', 'unreadable file', path.name, _why(e))
            continue
        if not rooms:
            report.add('file', 'no rooms', path.name, 'it has no rooms')
        yield from rooms


def _procthor_file(path: Path, assets: AssetBoxes, report: ImportReport) -> Iterator[RawRoom]:
    try:
        for n, line in procthor.lines(path):
            try:
                house = json.loads(line)
                rooms = procthor.read_house(path, n, house, assets)
            except (ValueError, TypeError, KeyError, AttributeError, RecursionError) as e:
                report.add('house', 'unreadable house', f'{path.name} line {n}', _why(e))
                continue
            if not rooms:
                report.add('house', 'no rooms', f'{path.name} line {n}', 'it has no rooms')
            yield from rooms
    except (OSError, EOFError, UnicodeDecodeError) as e:     # a truncated gzip stream
        report.add('file', 'unreadable file', path.name, _why(e))


def _why(e: Exception) -> str:
    if isinstance(e, json.JSONDecodeError):
        return f'it is not valid JSON ({e.msg} at line {e.lineno} column {e.colno})'
    if isinstance(e, OSError) and e.strerror:
        return f'it cannot be read ({e.strerror})'
    return f'it cannot be read ({type(e).__name__}: {e})'


def _safe(text: str) -> str:
    return re.sub(r'[^A-Za-z0-9_.-]+', '_', text).strip('._-')[:60] or 'x'


def scene_name(fmt: str, raw: RawRoom) -> str:
    """``<format>_<house>_<room>`` with only letters, digits, '_', '.' and '-'."""
    return f'{fmt}_{_safe(raw.house_id)}_{_safe(raw.room_id)}'


def _unique(name: str, taken: set[str]) -> str:
    out, n = name, 1
    while out in taken:
        n += 1
        out = f'{name}_{n}'
    return out


def _write_scene(out: Path, name: str, scene: dict[str, Any]) -> None:
    write_atomic(out / f'{name}.json', format_json(scene) + '\n')
