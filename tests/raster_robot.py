"""An independent check of the robot promise, on a raster: no shapely, no code of ``robot``.

The floor is sampled on a grid of ``CELL`` metres (matplotlib's point-in-polygon test). A
cell is free for the robot's centre when no blocked cell (outside the floor, or inside a
first-tier footprint) lies within the robot's radius plus clearance: the blocked mask grown
by a disc. The robot reaches what a flood fill over free cells, started at each door's entry
point, reaches. An object is reached when a reached cell lies in its reach zone, measured in
the object's own frame: straight before the front within radius plus reach for what is
operated at the front, within that distance of the footprint for the rest.

The raster errs by up to a cell either way, so ``check`` runs the robot a ``slack`` smaller
(and the reach that much shorter) than the promise's: a room that keeps the promise passes,
and one where the robot misses by more than the slack fails.
"""
from __future__ import annotations

from dataclasses import dataclass

from matplotlib.path import Path as PolyPath
import numpy as np

CELL = 0.02


@dataclass
class RasterVerdict:
    doors_connected: bool
    unreachable: list[str]


def _disc(radius_cells: float) -> list[tuple[int, int]]:
    r = int(np.floor(radius_cells))
    return [(i, j) for i in range(-r, r + 1) for j in range(-r, r + 1)
            if i * i + j * j <= radius_cells ** 2]


def _grow(mask: np.ndarray, offsets) -> np.ndarray:
    out = mask.copy()
    n, m = mask.shape
    for di, dj in offsets:
        out[max(di, 0):n + min(di, 0), max(dj, 0):m + min(dj, 0)] |= \
            mask[max(-di, 0):n + min(-di, 0), max(-dj, 0):m + min(-dj, 0)]
    return out


def _flood(free: np.ndarray, seeds: np.ndarray) -> np.ndarray:
    """Cells of ``free`` 4-connected to a ``seeds`` cell."""
    seen = seeds & free
    while True:
        grown = seen.copy()
        grown[1:] |= seen[:-1]
        grown[:-1] |= seen[1:]
        grown[:, 1:] |= seen[:, :-1]
        grown[:, :-1] |= seen[:, 1:]
        grown &= free
        if (grown == seen).all():
            return seen
        seen = grown


def _local(obj, xy: np.ndarray) -> np.ndarray:
    """Cell centres in the object's frame: x along its width, y out of its front."""
    c, s = np.cos(obj.yaw), np.sin(obj.yaw)
    d = xy - np.asarray(obj.position[:2])
    # The object's depth runs along its yaw: its front is at +depth/2 along (cos, sin).
    return np.stack([-s * d[..., 0] + c * d[..., 1], c * d[..., 0] + s * d[..., 1]], -1)


def check(scene, radius: float, reach: float, clearance: float = 0.0,
          operated_front=(), slack: float = 2 * CELL) -> RasterVerdict:
    room = scene.room
    x0, y0, x1, y1 = room.bounds
    xs = np.arange(x0 + CELL / 2, x1, CELL)
    ys = np.arange(y0 + CELL / 2, y1, CELL)
    gx, gy = np.meshgrid(xs, ys, indexing='ij')
    xy = np.stack([gx, gy], -1)
    flat = xy.reshape(-1, 2)
    blocked = ~PolyPath(np.asarray(room.floor)).contains_points(flat).reshape(gx.shape)
    for o in scene.first_tier:
        blocked |= PolyPath(o.corners()).contains_points(flat).reshape(gx.shape)
    body = radius + clearance - slack
    free = ~_grow(blocked, _disc(body / CELL))
    # Cells beyond the raster's edge are outside the room: block a border of the body's width.
    edge = int(np.ceil(body / CELL))
    free[:edge], free[-edge:], free[:, :edge], free[:, -edge:] = False, False, False, False

    entries = []
    for door in room.doors:
        wall = room.wall_of(door)
        p = np.asarray(door.position) + wall.normal * (radius + clearance + 0.1)
        entries.append((int((p[0] - xs[0]) / CELL + 0.5), int((p[1] - ys[0]) / CELL + 0.5)))
    comps = []
    for i, j in entries:
        seed = np.zeros_like(free)
        if 0 <= i < free.shape[0] and 0 <= j < free.shape[1]:
            seed[i, j] = True
        comps.append(_flood(free, seed))
    connected = all(c.any() for c in comps) and all((c == comps[0]).all() for c in comps)
    reached = np.zeros_like(free)
    for c in comps:
        reached |= c

    r = radius + reach - slack
    missed = []
    for o in scene.first_tier:
        u = _local(o, xy[reached])
        if not len(u):
            missed.append(o.id)
            continue
        hw, hd = o.width / 2, o.depth / 2
        if o.category in operated_front:
            ok = (np.abs(u[:, 0]) <= hw) & (u[:, 1] >= hd) & (u[:, 1] <= hd + r)
        else:
            dx = np.maximum(np.abs(u[:, 0]) - hw, 0)
            dy = np.maximum(np.abs(u[:, 1]) - hd, 0)
            ok = np.hypot(dx, dy) <= r
        if not ok.any():
            missed.append(o.id)
    return RasterVerdict(connected, missed)
