"""The import report: what was kept, how room types were mapped, and one line for every
room, object, opening or file that was dropped, with why.

Each line is one bounded sentence (``errors.sentence``) that starts with where: the file,
the house and the room (``procthor_1room_train.jsonl.gz house 12 room|2: ...``), so a line
can be found in the data. ``totals()`` counts by reason; ``text()`` is what the command
line prints and writes as ``report.txt``, ``to_dict()`` what it writes as ``report.json``.
"""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
import json
from pathlib import Path

from ..errors import sentence
from ..files import write_atomic

MAX_LINE = 300          # characters of a report line


@dataclass
class Line:
    what: str           # 'file', 'room', 'object', 'opening' or 'note'
    reason: str         # short key ('no floor', 'missing model', ...)
    text: str           # one sentence: where, then why


@dataclass
class ImportReport:
    """Everything one import kept and dropped."""

    format: str
    files: list[str] = field(default_factory=list)
    rooms_seen: int = 0
    rooms_kept: Counter = field(default_factory=Counter)          # our room type -> rooms
    objects_kept: Counter = field(default_factory=Counter)        # our room type -> objects
    room_types: Counter = field(default_factory=Counter)          # 'Theirs -> ours' -> rooms
    categories: Counter = field(default_factory=Counter)          # category -> objects kept
    openings_kept: Counter = field(default_factory=Counter)       # 'door' / 'window' -> count
    lines: list[Line] = field(default_factory=list)

    def add(self, what: str, reason: str, where: str, why: str) -> None:
        self.lines.append(Line(what, reason, sentence(f'{where}: {why}', MAX_LINE)))

    def dropped(self, what: str) -> Counter:
        """Reason -> count of the dropped things of one kind ('room', 'object', ...)."""
        return Counter(line.reason for line in self.lines if line.what == what)

    def totals(self) -> dict[str, object]:
        rooms_dropped = self.dropped('room')
        objects_dropped = self.dropped('object')
        return {
            'files': len(self.files),
            'files_dropped': sum(self.dropped('file').values()),
            'houses_dropped': sum(self.dropped('house').values()),
            'rooms_seen': self.rooms_seen,
            'rooms_kept': sum(self.rooms_kept.values()),
            'rooms_dropped': sum(rooms_dropped.values()),
            'objects_kept': sum(self.objects_kept.values()),
            'objects_dropped': sum(objects_dropped.values()),
            'rooms_dropped_by_reason': dict(sorted(rooms_dropped.items())),
            'objects_dropped_by_reason': dict(sorted(objects_dropped.items())),
            'openings_kept': dict(sorted(self.openings_kept.items())),
            'openings_dropped_by_reason': dict(sorted(self.dropped('opening').items())),
            'notes': sum(self.dropped('note').values()),
        }

    def to_dict(self) -> dict[str, object]:
        return {'format': self.format, 'files': list(self.files), 'totals': self.totals(),
                'rooms_kept': dict(sorted(self.rooms_kept.items())),
                'objects_kept': dict(sorted(self.objects_kept.items())),
                'room_types': dict(sorted(self.room_types.items())),
                'categories': dict(self.categories.most_common()),
                'lines': [{'what': x.what, 'reason': x.reason, 'text': x.text}
                          for x in self.lines]}

    def summary(self) -> str:
        """The totals in a few lines (what the command prints)."""
        t = self.totals()
        out = [f'{self.format}: {t["files"]} file(s), {t["rooms_seen"]} room(s) read, '
               f'{t["rooms_kept"]} kept, {t["rooms_dropped"]} dropped; '
               f'{t["objects_kept"]} object(s) kept, {t["objects_dropped"]} dropped']
        for rt, n in sorted(self.rooms_kept.items()):
            out.append(f'  kept {rt}: {n} room(s), {self.objects_kept[rt]} object(s)')
        for key, label in (('rooms_dropped_by_reason', 'rooms dropped'),
                           ('objects_dropped_by_reason', 'objects dropped'),
                           ('openings_dropped_by_reason', 'openings dropped')):
            for reason, n in t[key].items():
                out.append(f'  {label}, {reason}: {n}')
        for key in ('files_dropped', 'houses_dropped'):
            if t[key]:
                out.append(f'  {key.replace("_", " ")} (unreadable): {t[key]}')
        return '\n'.join(out)

    def text(self) -> str:
        """The summary, the room-type mapping, then every line."""
        out = [self.summary(), '', 'room types (theirs -> ours: rooms):']
        out += [f'  {k}: {n}' for k, n in sorted(self.room_types.items())]
        out += ['', 'lines (what, reason, where: why):']
        out += [f'  {x.what} [{x.reason}] {x.text}' for x in self.lines]
        return '\n'.join(out) + '\n'

    def write(self, folder: Path) -> tuple[Path, Path]:
        """``report.txt`` and ``report.json`` in ``folder``."""
        txt, js = folder / 'report.txt', folder / 'report.json'
        write_atomic(txt, self.text())
        write_atomic(js, json.dumps(self.to_dict(), indent=1, ensure_ascii=False) + '\n')
        return txt, js
