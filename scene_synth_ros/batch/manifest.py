"""A batch's directory, what it says about the rooms in it, and how a later run resumes it.

The directory::

    batch.json        what the rooms are: command, seed, source, synthesis options, lockstep
                      R, weights.
                      A later run into the directory must ask for the same rooms; -n, the
                      workers, the thumbnails and the exports may change.
    manifest.jsonl    one JSON row per room (see ``worker``), appended as its worker sends
                      it back, when the room ends (also in lockstep), so a killed run loses
                      only the rooms under way; sorted by index when a run ends
    summary.json      the counts of the manifest and the last run's speed and memory
    scenes/room_000042.json
    png/room_000042.png              (--png: a 240-pixel thumbnail)
    <format>/room_000042.<ext>       (--export: the suffixes of ``export.FORMATS``)
    <format>/meshes/                 the catalog models of that format's files, written once
                                     and named relatively, so each format's folder moves whole

Resumption: a room is skipped when the manifest has an ``ok`` row for it and every file this
run asks for (scene, thumbnail, exports) exists; a room's row is appended only after its
files are in place. A room that failed is tried again.
"""
from __future__ import annotations

from dataclasses import asdict
import json
import os
from pathlib import Path

from ..errors import quoted, sentence
from ..files import write_atomic
from .config import BatchConfig
from .sources import BatchError


class Manifest:
    """``manifest.jsonl``: rows appended as rooms finish, the last row of an index counting."""

    def __init__(self, path: Path):
        self.path = path
        self.rows: dict[int, dict] = {}
        if path.is_file():
            with open(path, 'rb') as f:
                for line in f:
                    try:
                        row = json.loads(line)
                        self.rows[int(row['index'])] = row
                    except (ValueError, KeyError, TypeError):
                        continue      # the torn last line of a killed run
        self._file = None

    def append(self, row: dict) -> None:
        if self._file is None:
            self._file = open(self.path, 'ab')
            # A killed run may have left half a line; the next row starts on a line of its own.
            if self._file.tell() and not self._ends_with_newline():
                self._file.write(b'\n')
        self._file.write(json.dumps(row, ensure_ascii=False).encode('utf-8') + b'\n')
        self._file.flush()
        self.rows[row['index']] = row

    def _ends_with_newline(self) -> bool:
        with open(self.path, 'rb') as f:
            f.seek(-1, os.SEEK_END)
            return f.read(1) == b'\n'

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None

    def compact(self) -> None:
        """The file as one row per room, by index."""
        self.close()
        text = ''.join(json.dumps(self.rows[i], ensure_ascii=False) + '\n'
                       for i in sorted(self.rows))
        write_atomic(self.path, text)


def batch_identity(cfg: BatchConfig, weights: Path) -> dict:
    """What determines the rooms (batch.json): not how many, by whom, nor what else is
    written."""
    return json.loads(json.dumps({
        'command': cfg.mode, 'seed': cfg.seed, 'source': cfg.source.identity(),
        'synthesis': asdict(cfg.synthesis), 'lockstep': cfg.lockstep,
        'weights': str(weights)}))


def _difference(old, new, where: str = '') -> str | None:
    if isinstance(old, dict) and isinstance(new, dict):
        for k in sorted(set(old) | set(new), key=str):
            d = _difference(old.get(k), new.get(k), f'{where}.{k}' if where else str(k))
            if d:
                return d
        return None
    return None if old == new else f'{where} {quoted(old, 60)} there, {quoted(new, 60)} now'


def check_directory(out: Path, identity: dict) -> None:
    """Create ``out`` and its batch.json, or check that the batch there is this one."""
    try:
        out.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise BatchError(f'{out} is a file, not a directory for the batch') from None
    except OSError as e:
        raise BatchError(f'{out} cannot be created: {e.strerror or e}') from None
    if not out.is_dir():
        raise BatchError(f'{out} is a file, not a directory for the batch')
    path = out / 'batch.json'
    if path.is_file():
        try:
            old = json.loads(path.read_text(encoding='utf-8'))
        except (OSError, ValueError) as e:
            raise BatchError(f'{path} is not a batch description ({sentence(e, 120)}): '
                             f'furnish into another directory') from None
        diff = _difference(old, identity)
        if diff:
            raise BatchError(f'{out} holds a batch of other rooms ({diff}): ask for the same '
                             f'rooms to resume it, or furnish into another directory')
        return
    try:
        write_atomic(path, json.dumps(identity, indent=2) + '\n')
    except OSError as e:
        raise BatchError(f'{out} is not writable: {e.strerror or e}') from None


def done(row: dict | None, out: Path, files: list[str]) -> bool:
    """Whether a room's ``row`` and the ``files`` this run asks for say it is there."""
    return bool(row) and row.get('status') == 'ok' and all((out / f).is_file() for f in files)
