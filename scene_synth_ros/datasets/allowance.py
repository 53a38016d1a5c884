"""A data set's ``allowance.Allowance``, derived from its own rooms.

A habit of the data set becomes an allowance when it is a habit, not an accident: seen in at
least ``min_rooms`` rooms and in at least ``min_share`` of the cases that could show it (of
the rooms holding both categories, for a tuck; of the objects on that parent category, for
resting inside it; of all second-tier objects, for hovering above the support). The allowed
amount covers the ``quantile`` share of what the data does, so one extreme room does not set
it:

* a tuck's depth is that quantile of the overlap depths of the pair (``geometry.overlap_depth``;
  the smaller footprint is the tucked one);
* resting inside a parent allows bases down to the (1 - quantile) quantile of their heights
  above the parent's base, as fractions of its height;
* hovering allows the quantile of the gaps above the support surface;
* a door's clear zone is as deep as the (1 - quantile) quantile of the clear depths in front
  of the data set's doors (the distance from the opening to the nearest object on the floor
  in the strict zone, the strict depth where none is), when objects enter the strict zones.

Collisions are counted only between first-tier objects whose heights overlap, as
``geometry.collisions`` counts them.
"""
from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from typing import Iterable

import numpy as np
from shapely.geometry import LineString

from ..allowance import Allowance
from ..geometry import (
    door_zone,
    door_zone_depth,
    enters_zone,
    overlap_depth,
    overlapping,
    raised,
)
from ..scene import Scene

ON_TOP = 0.01    # metres: a base this close to its parent's top is on it (``geometry.rests_on``)


@dataclass(frozen=True)
class AllowanceConfig:
    min_rooms: int = 3
    min_share: float = 0.10
    quantile: float = 0.95


class Deriver:
    """Collects a data set's rooms one at a time; ``result`` is their allowance."""

    def __init__(self, config: AllowanceConfig = AllowanceConfig()):
        self.config = config
        self.depths: dict[tuple[str, str], list[float]] = defaultdict(list)
        self.tuck_rooms: dict[tuple[str, str], int] = defaultdict(int)
        self.pair_rooms: dict[frozenset, int] = defaultdict(int)
        self.inside: dict[str, list[float]] = defaultdict(list)
        self.inside_rooms: dict[str, int] = defaultdict(int)
        self.children: dict[str, int] = defaultdict(int)
        self.gaps: list[float] = []
        self.gap_rooms = 0
        self.second_tier = 0
        self.door_depths: list[float] = []
        self.doors_entered = 0
        self.door_rooms = 0

    def add(self, scene: Scene) -> None:
        self._add_tucks(scene)
        self._add_support(scene)
        self._add_doors(scene)

    def _add_doors(self, scene: Scene) -> None:
        room, entered = scene.room, False
        floor = [o for o in scene.first_tier if not raised(o)]
        for door in room.doors:
            zone = door_zone(room, door)
            wall = room.wall_of(door)
            strict = door_zone_depth(door)
            ends = [np.asarray(door.position) + s * wall.direction * door.width / 2
                    for s in (-1, 1)]
            opening = LineString(ends)
            inside = [o for o in floor if enters_zone(o, zone)]
            self.door_depths.append(min((opening.distance(o.footprint()) for o in inside),
                                        default=strict))
            self.doors_entered += bool(inside)
            entered |= bool(inside)
        self.door_rooms += entered

    def _add_tucks(self, scene: Scene) -> None:
        objs = scene.first_tier
        cats = sorted({o.category for o in objs})
        for i, a in enumerate(cats):
            for b in cats[i:]:
                if a != b or sum(o.category == a for o in objs) > 1:
                    self.pair_rooms[frozenset((a, b))] += 1
        seen = set()
        for a, b in overlapping(objs):
            tucked, host = sorted((a, b), key=lambda o: o.width * o.depth)
            key = (tucked.category, host.category)
            self.depths[key].append(overlap_depth(a, b))
            seen.add(key)
        for key in seen:
            self.tuck_rooms[key] += 1

    def _add_support(self, scene: Scene) -> None:
        by_id = {o.id: o for o in scene.objects}
        inside_here, hovering = set(), False
        for o in scene.second_tier:
            parent = by_id.get(o.support)
            if parent is None:
                continue
            self.second_tier += 1
            self.children[parent.category] += 1
            gap = o.position[2] - parent.top
            if gap > ON_TOP:
                self.gaps.append(gap)
                hovering = True
            elif gap < -ON_TOP and o.position[2] >= parent.position[2] - ON_TOP:
                self.inside[parent.category].append(
                    max(0.0, (o.position[2] - parent.position[2]) / parent.size[2]))
                inside_here.add(parent.category)
        for cat in inside_here:
            self.inside_rooms[cat] += 1
        self.gap_rooms += hovering

    def result(self) -> Allowance:
        c = self.config
        tucks = []
        for (tucked, host), depths in sorted(self.depths.items()):
            rooms = self.tuck_rooms[(tucked, host)]
            if rooms >= c.min_rooms and rooms >= c.min_share * self.pair_rooms[
                    frozenset((tucked, host))]:
                tucks.append((tucked, host, float(np.quantile(depths, c.quantile))))
        inside = []
        for parent, fractions in sorted(self.inside.items()):
            if (self.inside_rooms[parent] >= c.min_rooms
                    and len(fractions) >= c.min_share * self.children[parent]):
                inside.append((parent, float(np.quantile(fractions, 1 - c.quantile))))
        settle = 0.0
        if self.gap_rooms >= c.min_rooms and len(self.gaps) >= c.min_share * self.second_tier:
            settle = float(np.quantile(self.gaps, c.quantile))
        door_depth = None
        if (self.door_rooms >= c.min_rooms
                and self.doors_entered >= c.min_share * len(self.door_depths)):
            door_depth = float(np.quantile(self.door_depths, 1 - c.quantile))
        return Allowance(tuple(tucks), tuple(inside), settle, door_depth)


def derive(scenes: Iterable[Scene], config: AllowanceConfig = AllowanceConfig()) -> Allowance:
    """The allowance of a data set's rooms (``Deriver`` over all of them)."""
    d = Deriver(config)
    for s in scenes:
        d.add(s)
    return d.result()
