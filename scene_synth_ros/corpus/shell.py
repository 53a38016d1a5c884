"""Empty room shells: floor outline, doors and windows, with sizes typical of each room type
and door/window counts per room matching the paper's table."""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np

from ..categories import ROOM_SIZE_CAP, paper_spec
from ..home_tables import ROOM_SIZES, SIZE_QUANTILES
from ..scene import Opening, Room
from ..thresholds import MAX_ROOM_SIDE

# A room type whose real rooms (``home_tables.ROOM_SIZES``) number at least this many is drawn
# at their sizes (``shell_area``: its floor area from theirs, up to ``thresholds.MAX_ROOM_SIDE``);
# the others keep the sizes of ``SHELLS`` within their type's square (too few real rooms).
MIN_REAL_ROOMS = 100


def real_sizes(room_type: str):
    """The real rooms' sizes a corpus of ``room_type`` draws from, or None."""
    sizes = ROOM_SIZES.get(room_type)
    return sizes if sizes is not None and sizes.rooms >= MIN_REAL_ROOMS else None


def shell_area(room_type: str, rng: np.random.Generator) -> float:
    """A floor area (m²) drawn as the type's real rooms have them (their quantiles,
    interpolated), or uniformly within ``SHELLS``' range."""
    sizes = real_sizes(room_type)
    if sizes is None:
        return float(rng.uniform(*SHELLS[room_type].area))
    return float(np.interp(rng.random(), SIZE_QUANTILES, sizes.area))


def shell_cap(room_type: str) -> float:
    """The longest side a corpus shell of ``room_type`` may have (m)."""
    return MAX_ROOM_SIDE if real_sizes(room_type) is not None else ROOM_SIZE_CAP[room_type]


@dataclass(frozen=True)
class ShellConfig:
    """Typical dimensions of one room type, in metres and square metres."""

    area: tuple[float, float]
    aspect: tuple[float, float]          # long side / short side
    door_width: tuple[float, float]
    window_width: tuple[float, float]
    window_height: tuple[float, float]
    sill: tuple[float, float]
    wall_height: tuple[float, float] = (2.5, 2.9)
    l_shape_probability: float = 0.2
    min_side: float = 1.9
    doors: tuple[int, int] = (1, 2)      # fewest and most doors, around the table's mean


SHELLS = {
    'bedroom': ShellConfig((9.0, 20.0), (1.0, 1.6), (0.8, 0.9), (0.8, 1.8), (1.1, 1.5),
                           (0.8, 1.0)),
    'living': ShellConfig((15.0, 38.0), (1.0, 1.8), (0.8, 1.2), (1.0, 2.4), (1.2, 1.6),
                          (0.5, 0.9)),
    'office': ShellConfig((9.0, 30.0), (1.0, 1.7), (0.8, 0.95), (0.9, 2.0), (1.1, 1.5),
                          (0.8, 1.0)),
    'bathroom': ShellConfig((3.6, 11.0), (1.0, 1.8), (0.7, 0.85), (0.5, 1.0), (0.6, 1.0),
                            (1.1, 1.4), min_side=1.6),
    # A galley kitchen is at least 2.4 m wide (two 0.6 m runs and a 1.2 m aisle); a one-wall
    # kitchen 1.9 m. Windows sit above the worktop (sill 1.0-1.1 m).
    'kitchen': ShellConfig((7.0, 26.0), (1.0, 2.0), (0.8, 0.9), (0.6, 1.6), (0.9, 1.3),
                           (1.0, 1.1)),
    'dining': ShellConfig((9.0, 22.0), (1.0, 1.6), (0.8, 1.2), (0.9, 2.0), (1.2, 1.6),
                          (0.6, 0.9)),
    # Long and narrow, joining the rooms of a home: its doors are on its long walls.
    'hallway': ShellConfig((3.0, 13.0), (2.0, 5.0), (0.8, 0.9), (0.6, 1.0), (0.8, 1.2),
                           (0.9, 1.1), l_shape_probability=0.15, min_side=1.1, doors=(2, 5)),
}

OPENING_GAP = 0.3       # clear wall between two openings
CORNER_GAP = 0.1        # clear wall between an opening and a corner


def count_from_mean(mean: float, low: int, high: int, rng: np.random.Generator) -> int:
    """An integer in [low, high] with the given mean and little spread: the two integers
    around the mean, mixed to hit it exactly."""
    mean = min(max(mean, low), high)
    base = math.floor(mean)
    return int(min(high, base + (rng.random() < mean - base)))


def window_count(mean: float, rng: np.random.Generator) -> int:
    """0-3 windows with the table's mean: binomial spread, so rooms without windows and rooms
    with three both occur."""
    return int(rng.binomial(3, min(mean / 3.0, 1.0)))


def rectangle_sides(area: float, aspect: float, cap: float, min_side: float
                    ) -> tuple[float, float]:
    """(long, short) sides of a rectangle of ``area`` m² and long/short ``aspect``, neither
    longer than ``cap`` nor the short one under ``min_side``."""
    long_side = min(math.sqrt(area * aspect), cap)
    return long_side, min(max(area / long_side, min_side), cap)


def floor_outline(room_type: str, area: float, rng: np.random.Generator,
                  cfg: ShellConfig, cap: float | None = None) -> list[tuple[float, float]]:
    """A rectangle, or with ``l_shape_probability`` an L: the rectangle less one corner;
    no side longer than ``cap`` (default: the type's square)."""
    cap = (ROOM_SIZE_CAP[room_type] if cap is None else cap) - 0.05
    aspect = rng.uniform(*cfg.aspect)
    l_shape = rng.random() < cfg.l_shape_probability
    cut = (rng.uniform(0.3, 0.45), rng.uniform(0.3, 0.45)) if l_shape else (0.0, 0.0)
    long_side, short_side = rectangle_sides(area / (1.0 - cut[0] * cut[1]), aspect, cap,
                                            cfg.min_side)
    w, d = (long_side, short_side) if rng.random() < 0.5 else (short_side, long_side)
    w, d = round(w, 2), round(d, 2)
    if not l_shape:
        return [(0.0, 0.0), (w, 0.0), (w, d), (0.0, d)]
    cw, cd = round(w * cut[0], 2), round(d * cut[1], 2)
    pts = [(0.0, 0.0), (w, 0.0), (w, d - cd), (w - cw, d - cd), (w - cw, d), (0.0, d)]
    # Rotate the vertex list so the missing corner is any of the four.
    quarter = int(rng.integers(4))
    cx, cy = w / 2, d / 2
    out = []
    for x, y in pts:
        for _ in range(quarter):
            x, y = cx - (y - cy), cy + (x - cx)     # 90 degrees about the centre
        out.append((x, y))
    minx, miny = min(p[0] for p in out), min(p[1] for p in out)
    return [(round(x - minx, 3), round(y - miny, 3)) for x, y in out]


def _place_openings(room: Room, kind: str, count: int, width: tuple[float, float],
                    height: tuple[float, float], sill: tuple[float, float],
                    taken: list[tuple[int, float, float]], rng: np.random.Generator,
                    walls: list[int] | None = None) -> list[Opening]:
    out = []
    for _ in range(count):
        for _attempt in range(20):
            w = round(rng.uniform(*width), 2)
            pool = [wl for wl in room.walls if wl.length >= w + 2 * CORNER_GAP + 0.01
                    and (walls is None or wl.index in walls)]
            if not pool:
                break
            lengths = np.array([wl.length for wl in pool])
            wall = pool[rng.choice(len(pool), p=lengths / lengths.sum())]
            lo, hi = CORNER_GAP + w / 2, wall.length - CORNER_GAP - w / 2
            if kind == 'door' and rng.random() < 0.5:
                off = lo if rng.random() < 0.5 else hi     # doors are often by a corner
            else:
                off = rng.uniform(lo, hi)
            a, b = off - w / 2, off + w / 2
            if any(i == wall.index and a < tb + OPENING_GAP and b > ta - OPENING_GAP
                   for i, ta, tb in taken):
                continue
            taken.append((wall.index, a, b))
            x, y = wall.point_at(off)
            s = 0.0 if kind == 'door' else round(rng.uniform(*sill), 2)
            out.append(Opening(kind, (round(float(x), 4), round(float(y), 4)), w,
                               round(rng.uniform(*height), 2), s))
            break
    return out


def sample_shell(room_type: str, rng: np.random.Generator, min_area: float = 0.0,
                 real_sizes: bool = False) -> Room:
    """An empty room of ``room_type`` with at least ``min_area`` square metres of floor
    (as far as the room-size cap allows): within its type's square (``SHELLS``' areas, the
    paper's rooms), or with ``real_sizes`` as large as real rooms of its type are
    (``shell_area``, up to ``shell_cap``) where enough of them were counted."""
    cfg = SHELLS[room_type]
    spec = paper_spec(room_type)
    if real_sizes:
        cap = shell_cap(room_type)
        drawn = shell_area(room_type, rng)
    else:
        cap = ROOM_SIZE_CAP[room_type]
        drawn = rng.uniform(*cfg.area)
    area = min(max(drawn, min_area), 0.8 * cap * cap)
    floor = floor_outline(room_type, area, rng, cfg, cap)
    shell = Room(room_type, floor, round(rng.uniform(*cfg.wall_height), 2))
    taken: list[tuple[int, float, float]] = []
    doors = _place_openings(shell, 'door', count_from_mean(spec.doors_per_room, *cfg.doors, rng),
                            cfg.door_width, (2.0, 2.1), (0.0, 0.0), taken, rng)
    # Windows go on the outside walls: one wall, or two for rooms with many windows.
    n_windows = window_count(spec.windows_per_room, rng)
    outside = [int(i) for i in rng.permutation(len(shell.walls))[:1 + (n_windows > 1)]]
    windows = _place_openings(shell, 'window', n_windows, cfg.window_width, cfg.window_height,
                              cfg.sill, taken, rng, walls=outside)
    if len(windows) < n_windows:      # the outside walls were too short: use any wall
        windows += _place_openings(shell, 'window', n_windows - len(windows),
                                   cfg.window_width, cfg.window_height, cfg.sill, taken, rng)
    return Room(room_type, floor, shell.wall_height, tuple(doors), tuple(windows))
