"""How a set of rooms compares with the paper's table: category distribution, objects per
room, doors and windows per room, and physical validity."""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from typing import Iterable

from ..categories import kl_divergence, paper_spec
from ..geometry import check_scene
from ..scene import Scene


@dataclass
class CorpusStats:
    room_type: str
    rooms: int = 0
    counts: Counter = field(default_factory=Counter)
    doors: int = 0
    windows: int = 0
    l_shaped: int = 0
    invalid: int = 0

    def add(self, scene: Scene, check: bool = True) -> None:
        self.rooms += 1
        self.counts.update(o.category for o in scene.objects)
        self.doors += len(scene.room.doors)
        self.windows += len(scene.room.windows)
        self.l_shaped += len(scene.room.floor) > 4
        if check and not check_scene(scene).ok:
            self.invalid += 1

    def distribution(self) -> dict[str, float]:
        total = sum(self.counts.values())
        return {k: v / total for k, v in self.counts.items()} if total else {}

    @property
    def kl_to_table(self) -> float:
        """KL(corpus || table), the direction of the paper's table 1."""
        return kl_divergence(self.distribution(), paper_spec(self.room_type).distribution())

    @property
    def kl_from_table(self) -> float:
        """KL(table || corpus): large when the corpus misses a category of the table."""
        return kl_divergence(paper_spec(self.room_type).distribution(), self.distribution())

    @property
    def objects_per_room(self) -> float:
        return sum(self.counts.values()) / max(self.rooms, 1)

    def frequency(self, category: str) -> float:
        return self.counts.get(category, 0) / max(self.rooms, 1)

    def summary_row(self) -> dict[str, float]:
        spec = paper_spec(self.room_type)
        return {
            'room_type': self.room_type, 'rooms': self.rooms,
            'kl_corpus_table': self.kl_to_table, 'kl_table_corpus': self.kl_from_table,
            'objects_per_room': self.objects_per_room,
            'table_objects_per_room': spec.mean_objects_per_room,
            'doors_per_room': self.doors / max(self.rooms, 1),
            'table_doors_per_room': spec.doors_per_room,
            'windows_per_room': self.windows / max(self.rooms, 1),
            'table_windows_per_room': spec.windows_per_room,
            'l_shaped_fraction': self.l_shaped / max(self.rooms, 1),
            'invalid_rooms': self.invalid,
        }

    def category_table(self) -> list[tuple[str, float, float]]:
        """(category, per room here, per room in the table), in the table's order."""
        return [(c.name, self.frequency(c.name), c.frequency)
                for c in paper_spec(self.room_type).categories]


def collect(room_type: str, scenes: Iterable[Scene], check: bool = True) -> CorpusStats:
    stats = CorpusStats(room_type)
    for s in scenes:
        stats.add(s, check)
    return stats
