"""A furnished room as the 2-D occupancy grid a navigation stack loads (nav2's map_server).

A cell is **occupied** where a wall piece or an object stands at the height a robot's laser
scans (``synth_config.MapConfig.map_scan_height``: a table top above it is not seen, its
legs are not modelled, so a table counts where its box spans that height); **free** where
the robot's body passes from the doors (``rules.robot.driven_floor``, and the doors'
openings through the walls; in a room without doors, wherever it fits) and nothing stands;
**unknown** everywhere else (inside furniture it cannot reach, outside the walls). A cell is
judged at its centre.

``write_map`` writes the map as map_server reads it: a YAML file (``image``, ``mode:
trinary``, ``resolution``, ``origin``, ``negate: 0``, ``occupied_thresh``, ``free_thresh``)
and a binary PGM beside it whose first row is the map's top (largest y), occupied cells
black (0), free ones white (254), unknown ones grey (205): map_server turns a pixel ``v``
into the probability ``(255 - v) / 255``, occupied above ``occupied_thresh`` and free below
``free_thresh``.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
from shapely.geometry import Polygon

from .export.architecture import WALL_THICKNESS, wall_boxes
from .files import write_atomic
from .geometry import free_space
from .house import HouseScene
from .rules.robot import Robot, driven_floor
from .scene import Scene, box_corners
from .synth_config import MapConfig
from .thresholds import OPENING_TOLERANCE

# The values of ``OccupancyGrid.data``, as nav_msgs/OccupancyGrid has them.
OCCUPIED, FREE, UNKNOWN = 100, 0, -1
# The PGM grey of each, and the thresholds map_server reads them with: those nav2's
# map_saver writes for a trinary map (as ROS 1's did). Its parameters' default free
# threshold, 0.25, would read the unknown grey, (255 - 205) / 255 = 0.196, as free.
PIXELS = {OCCUPIED: 0, FREE: 254, UNKNOWN: 205}
OCCUPIED_THRESH, FREE_THRESH = 0.65, 0.196
# Metres of unknown cells around the walls' outsides.
MARGIN = 0.2


@dataclass(frozen=True)
class OccupancyGrid:
    """Cells in rows of increasing y from ``origin`` (the world x, y of cell (0, 0)'s
    lower-left corner), each ``resolution`` metres square: ``data[row, col]`` is
    ``OCCUPIED``, ``FREE`` or ``UNKNOWN`` (int8)."""

    data: np.ndarray
    resolution: float
    origin: tuple[float, float]

    @property
    def height(self) -> int:
        return self.data.shape[0]

    @property
    def width(self) -> int:
        return self.data.shape[1]

    def cell_of(self, x: float, y: float) -> tuple[int, int]:
        """The (row, col) of the cell holding the world point (x, y)."""
        return (int((y - self.origin[1]) // self.resolution),
                int((x - self.origin[0]) // self.resolution))

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        """The world x and y of every cell's centre, shaped as ``data``."""
        cols = self.origin[0] + (np.arange(self.width) + 0.5) * self.resolution
        rows = self.origin[1] + (np.arange(self.height) + 0.5) * self.resolution
        return np.meshgrid(cols, rows)


def occupancy_grid(scene: Scene | HouseScene, robot: Robot | None = None,
                   config: MapConfig | None = None) -> OccupancyGrid:
    """The occupancy grid of ``scene``, a room or a whole house (``house.HouseScene``: each
    room's walls, objects and driven floor, the doors between rooms open), for ``robot``
    (default: ``Robot()``) with ``config`` (default: ``MapConfig()``); see the module
    docstring."""
    robot = robot or Robot()
    config = config or MapConfig()
    rooms = list(scene.scenes.values()) if isinstance(scene, HouseScene) else [scene]
    parts = [_room_cells(s, robot, config.map_scan_height) for s in rooms]
    solid = shapely.union_all([p[0] for p in parts])
    through = _through_walls(scene.house) if isinstance(scene, HouseScene) else []
    free = shapely.union_all([p[1] for p in parts] + through)
    bounds = shapely.union_all([*(s.room.polygon for s in rooms), solid]).bounds
    lo = np.asarray(bounds[:2]) - MARGIN
    hi = np.asarray(bounds[2:]) + MARGIN
    r = config.map_resolution
    shape = tuple(int(np.ceil(v)) for v in (hi - lo)[::-1] / r)
    grid = OccupancyGrid(np.full(shape, UNKNOWN, dtype=np.int8), r, (float(lo[0]), float(lo[1])))
    x, y = grid.centres()
    grid.data[shapely.contains_xy(free, x, y)] = FREE
    grid.data[shapely.contains_xy(solid, x, y)] = OCCUPIED
    return grid


def _through_walls(house) -> list[Polygon]:
    """The passage of each door between two rooms from one room's wall to the other's: walls
    back to back may stand a wall's thickness apart (``thresholds.MAX_WALL_THICKNESS``),
    more than each room's own door gap spans."""
    out = []
    for door in house.doors:
        if door.entrance:
            continue
        ends = []
        for rid in door.rooms:
            o = door.openings[rid]
            wall = house.rooms[rid].wall_of(o, OPENING_TOLERANCE)
            half = wall.direction * o.width / 2
            ends += [np.asarray(o.position) - half, np.asarray(o.position) + half]
        out.append(shapely.MultiPoint(ends).convex_hull)
    return out


def _room_cells(scene: Scene, robot: Robot, h: float):
    """(what a laser at height ``h`` hits, the floor the robot drives over) of one room."""
    room = scene.room
    seen = [Polygon(box_corners(b.centre[0], b.centre[1], b.yaw, b.size[1], b.size[0]))
            for b in wall_boxes(room)
            if b.centre[2] - b.size[2] / 2 <= h <= b.centre[2] + b.size[2] / 2]
    seen += [o.footprint() for o in scene.objects if o.position[2] <= h <= o.top]
    solid = shapely.union_all(seen)
    if room.doors:
        free = driven_floor(scene, robot)
    else:
        free = free_space(scene, robot.width).buffer(robot.radius)
    free = free.intersection(room.polygon)
    # The robot passes the doors' openings through the walls' thickness too.
    gaps = []
    for door in room.doors:
        wall = room.wall_of(door)
        centre = np.asarray(door.position) - wall.normal * WALL_THICKNESS / 2
        gaps.append(Polygon(box_corners(centre[0], centre[1], wall.inward_yaw, door.width,
                                        WALL_THICKNESS)))
    return solid, shapely.union_all([free, *gaps])


def write_map(grid: OccupancyGrid, path: str | Path) -> Path:
    """Write ``grid`` as map_server reads it: ``path`` (YAML) and the PGM beside it (same
    stem); the YAML's path."""
    path = Path(path)
    image = path.with_suffix('.pgm')
    pixels = np.full(grid.data.shape, PIXELS[UNKNOWN], dtype=np.uint8)
    for value, grey in PIXELS.items():
        pixels[grid.data == value] = grey
    header = f'P5\n# scene_synth_ros occupancy map\n{grid.width} {grid.height}\n255\n'
    write_atomic(image, header.encode('ascii') + pixels[::-1].tobytes())
    text = (f'image: {image.name}\n'
            'mode: trinary\n'
            f'resolution: {grid.resolution:g}\n'
            f'origin: [{grid.origin[0]:.6f}, {grid.origin[1]:.6f}, 0.0]\n'
            'negate: 0\n'
            f'occupied_thresh: {OCCUPIED_THRESH}\n'
            f'free_thresh: {FREE_THRESH}\n')
    write_atomic(path, text)
    return path
