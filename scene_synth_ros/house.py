"""A house: rooms that share walls, joined by doors, with one or more entrances.

Each room is a ``scene.Room`` of its own (its floor, wall height and windows, and the doors on
its walls); a door between two rooms is in both rooms' ``doors``, an entrance (a door to the
outside) in its one room's. ``schema.parse_house_layout`` makes a House from a house layout
(``msg_schemas/house_layout.schema.json``) after checking that the rooms do not overlap,
that each door lies on a wall its rooms share (an entrance on an outside wall) and that every
room can be reached from an entrance; ``House.to_dict`` writes the layout back. A
``HouseScene`` is a furnished house (``msg_schemas/house_scene.schema.json``): each room's
``Scene``, its objects in that room's frame, which is the house's.
"""
from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import shapely

from .scene import Opening, PlacedObject, Room, Scene, Wall
from .thresholds import MAX_WALL_THICKNESS, OPENING_TOLERANCE


def back_to_back(wall: Wall, other: Wall, slack: float = 0.0) -> float | None:
    """How far behind ``wall`` the wall ``other`` stands, facing it (within 1 degree) at
    most ``MAX_WALL_THICKNESS`` (plus ``slack``) away, as two rooms' walls do on either
    side of one wall; None where it does not."""
    if float(np.dot(other.direction, wall.direction)) > -0.9998:
        return None
    depth = float(np.dot(np.subtract(other.start, wall.start), -wall.normal))
    return depth if -OPENING_TOLERANCE <= depth <= MAX_WALL_THICKNESS + slack else None


def across(room: Room, opening: Opening, wall: Wall) -> Opening | None:
    """``opening``, which lies on ``wall`` of another room, as it opens into ``room``: on a
    wall of ``room`` back to back with ``wall`` at most ``MAX_WALL_THICKNESS`` behind it,
    moved onto it (None: ``room`` has no such wall under the whole opening)."""
    for other in room.walls:
        depth = back_to_back(wall, other)
        if depth is None:
            continue
        x, y = np.asarray(opening.position) - wall.normal * depth
        moved = Opening(opening.kind, (float(x), float(y)), opening.width, opening.height,
                        opening.sill)
        if room.wall_of(moved, OPENING_TOLERANCE) is not None:
            return moved
    return None


# Square metres two rooms' floors may share before they overlap (a rounding of shared walls),
# and that a floor must have behind a door or window for the opening to lead into it.
HOUSE_OVERLAP = 1e-3


class Floors:
    """The floors of a house's rooms and an R-tree of them: which rooms an opening lies on
    the wall of, and which it leads into through that wall."""

    def __init__(self, rooms):
        self.rooms = list(rooms)
        self.polygons = [room.polygon for room in self.rooms]
        self.tree = shapely.STRtree(self.polygons)

    def on_walls(self, opening: Opening) -> dict[int, Wall]:
        """The rooms (indices) with ``opening`` on one of their walls, and that wall."""
        near = self.tree.query(shapely.Point(opening.position).buffer(OPENING_TOLERANCE))
        return {int(i): w for i in sorted(near)
                if (w := self.rooms[i].wall_of(opening, OPENING_TOLERANCE)) is not None}

    def behind(self, opening: Opening, wall: Wall, home: int) -> list[int]:
        """The rooms other than ``home`` whose floor the opening leads into: those that
        meet the opening's width taken ``MAX_WALL_THICKNESS`` out through ``wall``."""
        off = wall.offset_of(opening.position)
        a = wall.point_at(off - opening.width / 2 + OPENING_TOLERANCE)
        b = wall.point_at(off + opening.width / 2 - OPENING_TOLERANCE)
        out = -wall.normal * MAX_WALL_THICKNESS
        box = shapely.Polygon([a, b, b + out, a + out])
        return [int(i) for i in sorted(self.tree.query(box)) if i != home
                and self.polygons[i].intersection(box).area > HOUSE_OVERLAP]


@dataclass(frozen=True)
class HouseDoor:
    """A door of a house: the ids of the two rooms it joins, or of the one room it leads
    out of (an entrance); ``opening`` as the layout gives it, and ``openings`` the door as
    each of its rooms has it, on that room's wall (a wall has a thickness: two rooms' walls
    back to back may stand apart, ``thresholds.MAX_WALL_THICKNESS``)."""

    rooms: tuple[str, ...]
    opening: Opening
    openings: dict[str, Opening] = field(default_factory=dict, compare=False)

    def __post_init__(self):
        if not self.openings:
            object.__setattr__(self, 'openings', {r: self.opening for r in self.rooms})

    @property
    def entrance(self) -> bool:
        return len(self.rooms) == 1

    def to_dict(self) -> dict[str, Any]:
        o = self.opening
        return {'rooms': list(self.rooms), 'position': [o.position[0], o.position[1]],
                'width': o.width, 'height': o.height}


@dataclass
class House:
    """Rooms by id, in the layout's order, and the doors that join them."""

    rooms: dict[str, Room]
    doors: tuple[HouseDoor, ...] = ()
    meta: dict[str, Any] = field(default_factory=dict)

    @property
    def entrances(self) -> tuple[HouseDoor, ...]:
        return tuple(d for d in self.doors if d.entrance)

    def neighbours(self, room_id: str) -> list[str]:
        """The rooms a door of ``room_id`` leads into, in the doors' order."""
        return [r for d in self.doors if room_id in d.rooms and not d.entrance
                for r in d.rooms if r != room_id]

    def reachable(self) -> list[str]:
        """The rooms reached from the entrances through the doors, in the order reached."""
        seen = list(dict.fromkeys(d.rooms[0] for d in self.entrances))
        queue = deque(seen)
        while queue:
            for other in self.neighbours(queue.popleft()):
                if other not in seen:
                    seen.append(other)
                    queue.append(other)
        return seen

    @property
    def area(self) -> float:
        return sum(room.area for room in self.rooms.values())

    def to_dict(self) -> dict[str, Any]:
        """The house layout (``msg_schemas/house_layout.schema.json``); every room carries
        its own wall height."""
        rooms = []
        for rid, room in self.rooms.items():
            d = room.to_dict()
            rooms.append({'id': rid, 'room_type': d['room_type'], 'floor': d['floor'],
                          'wall_height': d['wall_height'], 'windows': d['windows']})
        out: dict[str, Any] = {'rooms': rooms, 'doors': [d.to_dict() for d in self.doors]}
        if 'request_id' in self.meta:
            out['request_id'] = self.meta['request_id']
        return out


@dataclass
class HouseScene:
    """A furnished house: each room's scene by room id (its room as ``house`` has it) and
    free-form metadata."""

    house: House
    scenes: dict[str, Scene]
    meta: dict[str, Any] = field(default_factory=dict)

    def copy(self) -> 'HouseScene':
        """A copy whose rooms' object lists and meta may be changed on their own."""
        return HouseScene(self.house, {rid: s.copy() for rid, s in self.scenes.items()},
                          dict(self.meta))

    def objects(self) -> list[tuple[str, PlacedObject]]:
        """(room id, object) of every object, room by room in the layout's order."""
        return [(rid, o) for rid in self.house.rooms for o in self.scenes[rid].objects]

    def to_dict(self) -> dict[str, Any]:
        """The house scene (``msg_schemas/house_scene.schema.json``): the house layout with
        each room's objects in that room."""
        d = self.house.to_dict()
        for room in d['rooms']:
            room['objects'] = [o.to_dict() for o in self.scenes[room['id']].objects]
        if self.meta:
            d['meta'] = dict(self.meta)
        return d


def count_objects(scene: Scene | HouseScene) -> int:
    """The objects of a room, or of every room of a house."""
    return len(scene.objects()) if isinstance(scene, HouseScene) else len(scene)
