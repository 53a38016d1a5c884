"""Procedural house plans: empty house layouts (``house.House``) for those who have no floor
plans, as ProcTHOR draws its houses before it furnishes them.

A plan starts from a programme, the rooms a home has (``PROGRAMMES``, with extra rooms drawn
by ``EXTRA_ROOMS``), each with a floor area drawn as real rooms of its type have them
(``shell.shell_area``: 3D-FRONT's and ProcTHOR's rooms where enough exist) and a rectangle's
proportions from its type's shells (``shell.SHELLS``). The rooms stand on both sides of a
hallway, each joined to it by a door on the wall they share, the way an apartment's rooms
open onto its corridor: the living room, kitchen and dining room side by side on one side,
neighbours among them joined by a door too (an open kitchen through a door), the bedrooms,
bathrooms and study on the other, sides balanced by length. The entrance is a door in the
hallway's end wall. Windows go on each room's outside walls, as many as its type's table
gives (``shell.window_count``). Every plan is checked as a house layout
(``schema.parse_house_layout``), so it can be furnished as it is; one whose rooms do not fit
along a 16 m hallway is drawn again (``PlanError`` after ``ATTEMPTS``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from shapely.geometry import LineString, Polygon

from ..categories import paper_spec
from ..errors import SceneSynthError
from ..house import House, HouseDoor
from ..scene import Opening, Room
from ..schema import SceneValidationError, parse_house_layout
from ..thresholds import MAX_ROOM_SIDE
from .shell import (
    CORNER_GAP,
    SHELLS,
    _place_openings,
    rectangle_sides,
    shell_area,
    window_count,
)

# ESTIMATE, not a measurement (the data here has no whole homes to count): the programmes of
# small homes, by share: one to three bedrooms, a bathroom for up to two bedrooms.
PROGRAMMES = (
    (0.35, ('living', 'kitchen', 'bedroom', 'bathroom')),
    (0.40, ('living', 'kitchen', 'bedroom', 'bedroom', 'bathroom')),
    (0.25, ('living', 'kitchen', 'bedroom', 'bedroom', 'bedroom', 'bathroom', 'bathroom')),
)
# ESTIMATE: rooms some homes add, each with its share of homes.
EXTRA_ROOMS = (('dining', 0.3), ('office', 0.25))
# Rooms that open onto each other where they are neighbours (living, kitchen, dining).
DAY_ROOMS = ('living', 'kitchen', 'dining')

HALL_WIDTH = (1.2, 1.6)        # m: two people pass; the hallway's shells' narrowest is 1.1
DOOR_WIDTH = (0.8, 0.9)
DOOR_HEIGHT = (2.0, 2.1)
WALL_HEIGHT = (2.5, 2.9)
DOOR_INSET = 0.15              # m of wall between a door and the end of the wall it shares
ATTEMPTS = 20


class PlanError(SceneSynthError):
    """No plan of the programme asked for could be drawn."""


@dataclass(frozen=True)
class PlanConfig:
    """What a house plan may be: its programme drawn from ``PROGRAMMES`` unless ``rooms``
    names the room types (the hallway is added)."""

    rooms: tuple[str, ...] | None = None


def _programme(rng: np.random.Generator, config: PlanConfig) -> list[str]:
    if config.rooms is not None:
        return list(config.rooms)
    shares = np.array([p for p, _ in PROGRAMMES])
    rooms = list(PROGRAMMES[rng.choice(len(PROGRAMMES), p=shares / shares.sum())][1])
    rooms += [rt for rt, share in EXTRA_ROOMS if rng.random() < share]
    return rooms


def _rectangle(room_type: str, rng: np.random.Generator) -> tuple[float, float]:
    """(width along the hallway, depth away from it) of a room of ``room_type``, m."""
    cfg = SHELLS[room_type]
    area = shell_area(room_type, rng)
    long_side, short_side = rectangle_sides(area, rng.uniform(*cfg.aspect),
                                            MAX_ROOM_SIDE - 0.5, cfg.min_side)
    w, d = (long_side, short_side) if rng.random() < 0.5 else (short_side, long_side)
    return round(w, 2), round(d, 2)


def _sides(types: list[str], widths: list[float]) -> tuple[list[int], list[int]]:
    """The rooms' indices on each side of the hallway, in order from the entrance: the day
    rooms together on one side, the rest filling the shorter side first."""
    day = [i for i, rt in enumerate(types) if rt in DAY_ROOMS]
    night = [i for i, rt in enumerate(types) if rt not in DAY_ROOMS]
    sides = (list(day), [])
    for i in sorted(night, key=lambda i: -widths[i]):
        length = [sum(widths[k] for k in side) for side in sides]
        sides[int(length[1] <= length[0])].append(i)
    return sides


def _door_on(rng: np.random.Generator, start: float, end: float) -> tuple[float, float]:
    """(centre, width) of a door on a shared stretch of wall from ``start`` to ``end``."""
    width = round(float(rng.uniform(*DOOR_WIDTH)), 2)
    lo, hi = start + DOOR_INSET + width / 2, end - DOOR_INSET - width / 2
    return round(float(rng.uniform(lo, hi)), 3), width


def _windows(room: Room, outside: list[int], rng: np.random.Generator) -> tuple[Opening, ...]:
    cfg = SHELLS[room.room_type]
    count = window_count(paper_spec(room.room_type).windows_per_room, rng)
    taken = []
    for door in room.doors:
        wall = room.wall_of(door)
        off = wall.offset_of(door.position)
        taken.append((wall.index, off - door.width / 2, off + door.width / 2))
    return tuple(_place_openings(room, 'window', count, cfg.window_width, cfg.window_height,
                                 cfg.sill, taken, rng, walls=outside))


def _attempt(rng: np.random.Generator, config: PlanConfig) -> House | None:
    types = _programme(rng, config)
    sizes = [_rectangle(rt, rng) for rt in types]
    widths = [w for w, _ in sizes]
    sides = _sides(types, widths)
    length = max(sum(widths[i] for i in side) for side in sides)
    hall_w = round(float(rng.uniform(*HALL_WIDTH)), 2)
    if length > MAX_ROOM_SIDE - 0.1:
        return None
    wall_height = round(float(rng.uniform(*WALL_HEIGHT)), 2)
    ids = []
    counts: dict[str, int] = {}
    for rt in types:
        counts[rt] = counts.get(rt, 0) + 1
        ids.append(f'{rt}_{counts[rt]}')
    floors, doors = {}, []
    for side, members in enumerate(sides):
        x = 0.0
        for k, i in enumerate(members):
            w, d = sizes[i]
            y0, y1 = (hall_w, hall_w + d) if side == 0 else (-d, 0.0)
            floors[ids[i]] = [(x, y0), (x + w, y0), (x + w, y1), (x, y1)]
            centre, width = _door_on(rng, x, x + w)
            y = hall_w if side == 0 else 0.0
            opening = Opening('door', (centre, y), width,
                              round(float(rng.uniform(*DOOR_HEIGHT)), 2))
            doors.append(HouseDoor(('hallway_1', ids[i]), opening))
            if k and types[i] in DAY_ROOMS and types[members[k - 1]] in DAY_ROOMS:
                prev = sizes[members[k - 1]][1]
                shared = min(d, prev)
                lo, hi = (hall_w, hall_w + shared) if side == 0 else (-shared, 0.0)
                at, width = _door_on(rng, lo, hi)
                doors.append(HouseDoor((ids[members[k - 1]], ids[i]),
                                       Opening('door', (x, at), width, opening.height)))
            x += w
    floors = {'hallway_1': [(0.0, 0.0), (length, 0.0), (length, hall_w), (0.0, hall_w)],
              **floors}
    entrance = Opening('door', (0.0, round(hall_w / 2, 3)),
                       round(min(float(rng.uniform(*DOOR_WIDTH)), hall_w - 2 * CORNER_GAP - 0.02),
                             2), 2.1)
    doors.insert(0, HouseDoor(('hallway_1',), entrance))
    rooms = {}
    for rid, floor in floors.items():
        rt = 'hallway' if rid == 'hallway_1' else types[ids.index(rid)]
        mine = tuple(dr.opening for dr in doors if rid in dr.rooms)
        room = Room(rt, tuple(floor), wall_height, mine)
        rooms[rid] = room if rt == 'hallway' else Room(
            rt, room.floor, wall_height, mine, _windows(room, _outside(room, rid, floors),
                                                        rng))
    house = House(rooms, tuple(doors), {'generator': 'house_plan'})
    try:
        parse_house_layout(house.to_dict())        # as a user's layout would be checked
    except SceneValidationError:
        return None
    return house


def _outside(room: Room, rid: str, floors: dict) -> list[int]:
    """The walls of ``room`` with no other room behind them anywhere along them."""
    others = [Polygon(f) for r, f in floors.items() if r != rid]
    out = []
    for wall in room.walls:
        line = LineString([wall.start, wall.end])
        if not any(p.buffer(1e-3).intersection(line).length > 1e-2 for p in others):
            out.append(wall.index)
    return out


def house_plan(seed: int = 0, index: int = 0, config: PlanConfig = PlanConfig()) -> House:
    """House plan ``index`` of plan seed ``seed``: the same pair gives the same plan."""
    ss = np.random.SeedSequence([seed, 0x4853, index])
    for attempt in ss.spawn(ATTEMPTS):
        house = _attempt(np.random.default_rng(attempt), config)
        if house is not None:
            return house
    raise PlanError(f'no house plan of seed {seed}, index {index} in {ATTEMPTS} attempts: '
                    f'its rooms do not fit along a hallway of at most {MAX_ROOM_SIDE:g} m')
