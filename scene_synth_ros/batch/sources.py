"""What rooms a batch makes: room ``i`` (``i`` = 0 .. n-1) is furnished with the synthesis seed
``seed + i``, in the ``i``-th room of its source (the manifest's ``layout`` in brackets):

- shells (``generate -n``): the shell of the first attempt at corpus room (type, ``seed``,
  ``i``), ``corpus.generate.first_shell`` (most often the corpus room's own shell, drawn
  without furnishing the corpus room); several room types (``all``) are cycled, room ``i``
  being of the ``i % k``-th (``bedroom shell: corpus seed 0, room 42``);
- one layout or partial room (``generate --layout F -n``, ``complete F -n``): that room every
  time (``F``);
- a directory (``--layouts DIR``, ``complete DIR``): its ``*.json``, ``*.yaml`` and ``*.yml``
  files in name order (the file's name);
- a JSON-lines file (``*.jsonl``): its non-blank lines (``rooms.jsonl:17``, the line);
- house plans (``generate -n --houses``): procedural house plan ``i`` of plan seed ``seed``
  (``corpus.house_plan``), a whole house (``house plan: plan seed 0, house 42``).

A document may be a house layout or house scene as well as a room's (``schema.is_house``):
the house is furnished whole (``house_synth.furnish_house``), one house to a row, its files
named as a room's.

So room 0 of ``generate -n N --seed S`` is the room of ``generate --seed S``, and any room is
made again alone from its scene file and seed (``generate --layout
DIR/scenes/room_000042.json --seed 42``): to the last digit with ``--lockstep 1`` when torch
has one thread there too (the one-room command uses every core, which changes the last digits
of the networks' sums), and in lockstep nearly always the same room (see ``worker``).
``generate`` furnishes from empty (objects in the input are dropped); ``complete`` keeps them
and adds the rest.
"""
from __future__ import annotations

from dataclasses import dataclass
import os
from pathlib import Path
from typing import Iterator

from ..categories import PAPER, Vocabulary
from ..errors import SceneSynthError
from ..limits import MAX_PAYLOAD_BYTES
from ..schema import parse_document

LAYOUT_SUFFIXES = ('.json', '.yaml', '.yml')


class BatchError(SceneSynthError):
    """A batch that cannot start (bad options, an unusable directory), in one sentence."""


def room_name(index: int) -> str:
    return f'room_{index:06d}'


@dataclass(frozen=True)
class RoomJob:
    """Everything a worker needs to furnish room ``index``: a shell to draw, or a document."""

    index: int
    seed: int
    layout: str                     # where the room comes from, as the manifest names it
    room_type: str | None = None    # a shell of this type (corpus seed ``shell_seed``)...
    shell_seed: int = 0
    house_plan: bool = False        # ...or house plan ``index`` of plan seed ``shell_seed``...
    data: bytes | None = None       # ...or a layout or scene, JSON or YAML
    problem: str | None = None      # why the document could not be read

    @property
    def name(self) -> str:
        return room_name(self.index)


def _read_document(path: Path) -> tuple[bytes | None, str | None]:
    # One byte past the limit is enough for the schema's reader to refuse it in one sentence.
    try:
        with open(path, 'rb') as f:
            return f.read(MAX_PAYLOAD_BYTES + 1), None
    except OSError as e:
        return None, f'{path.name} cannot be read: {e.strerror or e}'


def _jsonl_lines(path: Path) -> Iterator[tuple[int, bytes]]:
    """(line number, text) of every non-blank line; a line past the payload limit is cut
    there (the reader then refuses it) and the rest of it skipped."""
    with open(path, 'rb') as f:
        number = 0
        while True:
            line = f.readline(MAX_PAYLOAD_BYTES + 1)
            if not line:
                return
            number += 1
            if len(line) > MAX_PAYLOAD_BYTES and not line.endswith(b'\n'):
                rest = line
                while rest and not rest.endswith(b'\n'):
                    rest = f.readline(MAX_PAYLOAD_BYTES)
            if line.strip():
                yield number, line


@dataclass(frozen=True)
class Source:
    """Where a batch's rooms come from (see the module docstring)."""

    kind: str                       # 'shells', 'plans', 'file', 'directory' or 'jsonl'
    room_types: tuple[str, ...] = ()
    path: str = ''

    @classmethod
    def shells(cls, room_types, vocabulary: Vocabulary = PAPER) -> Source:
        types = tuple(vocabulary.resolve(t) for t in room_types)
        if not types:
            raise BatchError('shells need at least one room type')
        own = [t for t in types if vocabulary.defines(t)]
        if own:
            raise BatchError(f'{own[0]} is a room type of the data set the weights were '
                             f'trained on, and the corpus makes only the package\'s own: '
                             f'give --layouts')
        return cls('shells', types)

    @classmethod
    def plans(cls) -> Source:
        """Procedural house plans, a whole house a row."""
        return cls('plans')

    @classmethod
    def at(cls, path: str | os.PathLike) -> Source:
        """A directory of layouts, a JSON-lines file or one layout or scene file."""
        p = Path(path)
        if p.is_dir():
            return cls('directory', path=str(p.resolve()))
        if not p.is_file():
            raise BatchError(f'{path}: no such file or directory')
        return cls('jsonl' if p.suffix.lower() == '.jsonl' else 'file', path=str(p.resolve()))

    @property
    def finite(self) -> bool:
        """Whether the source has a number of rooms of its own (else -n is needed)."""
        return self.kind in ('directory', 'jsonl')

    def identity(self) -> dict:
        # Shells name how they are drawn: a directory whose rooms are the corpus rooms' own
        # shells (before first_shell) must not be resumed with others.
        if self.kind == 'plans':
            return {'kind': self.kind}
        return ({'kind': self.kind, 'room_types': list(self.room_types),
                 'shells': 'first attempt'}
                if self.kind == 'shells' else {'kind': self.kind, 'path': self.path})

    def jobs(self, seed: int, n: int | None) -> list[RoomJob]:
        """Rooms 0 .. n-1 (every room of a finite source when ``n`` is None); documents of a
        directory are read later, by ``load``, for the rooms still to do."""
        path = Path(self.path)
        if self.kind == 'shells':
            k = len(self.room_types)
            return [RoomJob(i, seed + i, f'{self.room_types[i % k]} shell: corpus seed {seed}, '
                            f'room {i}', room_type=self.room_types[i % k], shell_seed=seed)
                    for i in range(n)]
        if self.kind == 'plans':
            return [RoomJob(i, seed + i, f'house plan: plan seed {seed}, house {i}',
                            shell_seed=seed, house_plan=True) for i in range(n)]
        if self.kind == 'file':
            return [RoomJob(i, seed + i, str(path)) for i in range(n)]
        if self.kind == 'directory':
            try:
                names = sorted(p.name for p in path.iterdir()
                               if p.suffix.lower() in LAYOUT_SUFFIXES and p.is_file())
            except OSError as e:
                raise BatchError(f'{path}: cannot be listed: {e.strerror or e}') from None
            if not names:
                raise BatchError(f'{path} holds no room layouts (*.json, *.yaml, *.yml)')
            return [RoomJob(i, seed + i, name) for i, name in enumerate(names[:n])]
        jobs = []
        try:
            for i, (number, line) in enumerate(_jsonl_lines(path)):
                if n is not None and i >= n:
                    break
                jobs.append(RoomJob(i, seed + i, f'{path.name}:{number}', data=line))
        except OSError as e:
            raise BatchError(f'{path}: cannot be read: {e.strerror or e}') from None
        if not jobs:
            raise BatchError(f'{path} holds no room layouts (one JSON layout a line)')
        return jobs

    def load(self, job: RoomJob) -> RoomJob:
        """``job`` with its document read, or with why it could not be."""
        if self.kind not in ('file', 'directory'):
            return job
        path = Path(self.path) if self.kind == 'file' else Path(self.path) / job.layout
        data, problem = _read_document(path)
        return RoomJob(job.index, job.seed, job.layout, data=data, problem=problem)


def scene_from_document(data: bytes, models=None, vocabulary: Vocabulary = PAPER):
    """A scene or room layout (JSON or YAML) as a validated Scene, as ``schema.load_scene``
    reads a file, or a house layout or house scene as a HouseScene; model ids are those of
    ``models`` (a ``catalog.Catalog``, default the procedural one)."""
    return parse_document(data, models, vocabulary)
