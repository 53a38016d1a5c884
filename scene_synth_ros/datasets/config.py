"""What an import keeps: the room-type mapping and the filters (``ImportConfig``).

The filters are the ones the field's preprocessing of 3D-FRONT applies (ATISS, the
paper's SUNCG filtering), each one an option:

* ``scale_range``: an object whose scale along any axis is outside it is dropped (scales
  of 0.01 or 100 are data-entry mistakes, not furniture);
* ``object_count``: a room with fewer or more kept objects is dropped;
* ``room_size``: per room type, the longest side the room may have in its own axes (the
  axes of ``render.room_axis_yaw``, the question the networks' frame asks); by default
  ``thresholds.MAX_ROOM_SIDE``, the longest room the package furnishes, for the package's
  room types and no limit for others;
* objects whose footprint centre lies more than ``floor_tolerance`` outside the floor are
  dropped.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping

from ..categories import ROOM_TYPES
from ..errors import DatasetError, quoted
from ..limits import MAX_OBJECTS, LimitExceeded, YamlError, loads_yaml
from ..thresholds import MAX_ROOM_SIDE

FORMATS = ('3dfront', 'suncg', 'procthor')
ROOM_TYPES_FILE = Path(__file__).with_name('room_types.yaml')


@dataclass(frozen=True)
class ImportConfig:
    """Filters of an import (see the module docstring)."""

    scale_range: tuple[float, float] = (0.2, 5.0)
    object_count: tuple[int, int] = (1, MAX_OBJECTS)
    # None: MAX_ROOM_SIDE for the package's room types, no limit for the others.
    room_size: Mapping[str, float] | None = None
    floor_tolerance: float = 0.01        # m an object's centre may lie outside the floor
    support_tolerance: float = 0.1       # m between a parent's top and a child's bottom
    on_floor: float = 0.1                # m: an object whose bottom is lower stands on the floor
    opening_reach: float = 0.4           # m from a wall line at which an opening is its own
    room_types: Mapping[str, str] = field(default_factory=dict)   # data set's -> ours

    def __post_init__(self):
        lo, hi = self.scale_range
        if not 0 < lo <= hi:
            raise DatasetError(f'the scale range must be 0 < min <= max, got {lo} to {hi}')
        lo, hi = self.object_count
        if not 0 <= lo <= hi:
            raise DatasetError(f'the object count range must be 0 <= min <= max, got {lo} '
                               f'to {hi}')
        if hi > MAX_OBJECTS:
            raise DatasetError(f'a scene holds at most {MAX_OBJECTS} objects, so the object '
                               f'count range cannot go up to {hi}')
        for name, side in (self.room_size or {}).items():
            if not side > 0:
                raise DatasetError(f'the room size of {quoted(name)} must be positive, '
                                   f'got {side}')

    def size_limit(self, room_type: str) -> float | None:
        """The longest side a room of this type may have, or None."""
        if self.room_size is not None:
            return self.room_size.get(room_type)
        return _DEFAULT_ROOM_SIZE.get(room_type)


_DEFAULT_ROOM_SIZE = dict.fromkeys(ROOM_TYPES, MAX_ROOM_SIDE)


def parse_room_size(items: list[str]) -> dict[str, float]:
    """``TYPE=METRES`` items of ``--room-size`` as a mapping (the defaults where not given)."""
    out: dict[str, float] = dict(_DEFAULT_ROOM_SIZE)
    for item in items:
        name, sep, value = item.partition('=')
        try:
            out[name.strip()] = float(value)
        except ValueError:
            sep = ''
        if not sep or not name.strip():
            raise DatasetError(f'--room-size takes TYPE=METRES, got {quoted(item)}')
    return out


def load_room_types(fmt: str, path: str | Path | None = None) -> dict[str, str]:
    """The room-type mapping of format ``fmt`` from ``path`` (the shipped file by default):
    a YAML mapping of format -> {data set's room type: our room type}."""
    if fmt not in FORMATS:
        raise DatasetError(f'unknown format {quoted(fmt)}; expected one of {", ".join(FORMATS)}')
    table = _read_room_types(str(path or ROOM_TYPES_FILE))
    mapping = table.get(fmt)
    if mapping is None:
        raise DatasetError(f'{path or ROOM_TYPES_FILE} has no room types for {fmt} (a '
                           f'top-level key {quoted(fmt)} is needed)')
    return dict(mapping)


def _read_room_types(path: str) -> dict[str, dict[str, str]]:
    try:
        text = Path(path).read_text(encoding='utf-8')
    except OSError as e:
        raise DatasetError(f'cannot read the room-type file {path}: {e.strerror}') from None
    try:
        table = loads_yaml(text)
    except (YamlError, LimitExceeded) as e:
        raise DatasetError(f'the room-type file {path} is not valid YAML: {e}') from None
    if not isinstance(table, dict):
        raise DatasetError(f'the room-type file {path} must be a mapping of format -> '
                           f'{{room type: room type}}')
    for fmt, mapping in table.items():
        if not isinstance(mapping, dict) or not all(
                isinstance(k, str) and isinstance(v, str) and v.strip()
                for k, v in mapping.items()):
            raise DatasetError(f'the room-type file {path}: {quoted(fmt)} must map room '
                               f'type names to room type names')
    return {fmt: {k: v.strip() for k, v in m.items()} for fmt, m in table.items()}
