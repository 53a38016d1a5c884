"""The occupancy map (``scene_synth_ros.occupancy``, ``scene-synth map``): occupied where a
wall or an object stands at the scan height, free where the robot drives from the doors,
unknown elsewhere; written as nav2's map_server reads it, and a planner on it finds the
paths the robot promise says exist."""
from collections import deque
import json
import math
import subprocess
import sys

import numpy as np
import pytest
import yaml

from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.errors import ConfigError
from scene_synth_ros.geometry import door_entry_point
from scene_synth_ros.occupancy import FREE, OCCUPIED, UNKNOWN, occupancy_grid, write_map
from scene_synth_ros.rules.robot import Robot, reach_zone, state
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene
from scene_synth_ros.schema import save_scene
from scene_synth_ros.synth_config import MapConfig

ROOM = Room('bedroom', ((0, 0), (4, 0), (4, 3), (0, 3)), 2.6,
            doors=(Opening('door', (1.0, 0.0), 0.9, 2.0),),
            windows=(Opening('window', (4.0, 1.5), 1.2, 1.2, sill=0.9),))


def _scene() -> Scene:
    bed = PlacedObject('bed_0', 'double bed', 'double_bed_00', (2.5, 2.0, 0.0), 0.0,
                       (1.6, 2.0, 0.5))
    # shelving hung on the wall above the height the laser scans
    hung = PlacedObject('shelving_0', 'shelving', 'shelving_00', (0.15, 1.5, 1.2), 0.0,
                        (0.8, 0.3, 0.6))
    return Scene(ROOM, [bed, hung])


def _cell(grid, x, y):
    return grid.data[grid.cell_of(x, y)]


def test_walls_and_objects_at_the_scan_height_are_occupied_the_driven_floor_free():
    grid = occupancy_grid(_scene(), Robot(radius=0.2), MapConfig(map_resolution=0.05))
    assert grid.data.dtype == np.int8 and set(np.unique(grid.data)) == {FREE, OCCUPIED,
                                                                         UNKNOWN}
    assert _cell(grid, 2.5, 2.0) == OCCUPIED                 # the bed
    assert _cell(grid, 2.0, -0.05) == OCCUPIED               # the wall beside the door
    assert _cell(grid, 1.0, -0.05) == FREE                   # the door's opening
    assert _cell(grid, 4.05, 1.5) == OCCUPIED                # below the window's sill
    assert _cell(grid, 1.0, 1.0) == FREE                     # open floor
    assert _cell(grid, 0.15, 1.5) != OCCUPIED                # under the cabinet, unseen
    assert _cell(grid, -0.15, 1.5) == UNKNOWN                # outside the walls
    # A laser scanning above the bed sees the cabinet and not the bed; below the sill, the
    # window's wall; at the sill's height, through the window.
    high = occupancy_grid(_scene(), Robot(radius=0.2), MapConfig(map_scan_height=1.3))
    assert _cell(high, 2.5, 2.0) != OCCUPIED and _cell(high, 0.15, 1.5) == OCCUPIED
    assert _cell(high, 4.05, 1.5) != OCCUPIED
    # Floor the robot cannot drive to (behind a wall-to-wall row of cabinets) is unknown.
    cut = occupancy_grid(Scene(ROOM, [PlacedObject(
        'wardrobe_0', 'wardrobe', 'wardrobe_00', (2.0, 2.2, 0.0), math.pi / 2,
        (4.0, 0.4, 2.0))]))
    assert _cell(cut, 2.0, 2.2) == OCCUPIED
    assert _cell(cut, 2.0, 2.8) == UNKNOWN and _cell(cut, 2.0, 1.0) == FREE


def test_the_settings_are_checked_in_one_sentence():
    with pytest.raises(ConfigError, match='map_resolution must be between 0.01 and 1'):
        MapConfig(map_resolution=0.0)
    with pytest.raises(ConfigError, match='map_scan_height must be'):
        MapConfig(map_scan_height=float('nan'))


def _read_as_map_server(path):
    """The map as nav2's map_server loads a trinary map: the YAML's keys, the PGM's pixels
    turned into occupancy by ``(255 - v) / 255`` (negate 0), the image's top row the map's
    last."""
    meta = yaml.safe_load(path.read_text())
    assert set(meta) == {'image', 'mode', 'resolution', 'origin', 'negate', 'occupied_thresh',
                         'free_thresh'}
    assert meta['mode'] == 'trinary' and meta['negate'] == 0 and len(meta['origin']) == 3
    header, rest = [], (path.parent / meta['image']).read_bytes()
    while len(header) < 4:                  # P5, width, height, maxval; comments skipped
        line, rest = rest.split(b'\n', 1)
        if not line.startswith(b'#'):
            header += line.split()
    assert header[0] == b'P5' and int(header[3]) == 255
    w, h = int(header[1]), int(header[2])
    pixels = np.frombuffer(rest, np.uint8).reshape(h, w)
    p = (255 - pixels.astype(float)) / 255.0
    occ = np.full((h, w), -1, dtype=np.int8)
    occ[p > meta['occupied_thresh']] = 100
    occ[p < meta['free_thresh']] = 0
    return meta, occ[::-1]


def test_map_server_reads_back_the_grid(tmp_path):
    grid = occupancy_grid(_scene())
    path = write_map(grid, tmp_path / 'room.yaml')
    meta, occ = _read_as_map_server(path)
    assert meta['resolution'] == pytest.approx(grid.resolution)
    assert meta['origin'][:2] == pytest.approx(list(grid.origin), abs=1e-6)
    assert np.array_equal(occ, grid.data)


def _reachable(grid, start) -> np.ndarray:
    """The free cells a planner on the grid reaches from ``start`` (4-connected)."""
    seen = np.zeros(grid.data.shape, bool)
    queue = deque([start])
    seen[start] = True
    while queue:
        r, c = queue.popleft()
        for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            n = (r + dr, c + dc)
            if 0 <= n[0] < grid.height and 0 <= n[1] < grid.width and not seen[n] \
                    and grid.data[n] == FREE:
                seen[n] = True
                queue.append(n)
    return seen


@pytest.mark.parametrize('room_type', ['bedroom', 'living', 'office', 'kitchen'])
def test_a_planner_on_the_map_reaches_what_the_robot_promise_says(room_type):
    import shapely
    robot = Robot()
    for i in range(4):
        scene = generate_room(room_type, HELDOUT_SEED, i)
        grid = occupancy_grid(scene, robot)
        now = state(scene, robot)
        doors = [grid.cell_of(*door_entry_point(scene.room, d, robot.width).coords[0])
                 for d in scene.room.doors]
        if not doors:
            continue
        reached = _reachable(grid, doors[0])
        if now.doors_connected:
            assert all(reached[d] for d in doors), (room_type, i)
        x, y = grid.centres()
        for k in now.reached:
            zone = reach_zone(scene.first_tier[k], robot)
            assert (reached & shapely.contains_xy(zone, x, y)).any(), \
                (room_type, i, scene.first_tier[k].id)


def test_the_command_writes_the_map(tmp_path):
    scene = _scene()
    save_scene(scene, tmp_path / 'room.json')
    out = subprocess.run([sys.executable, '-m', 'scene_synth_ros.cli', 'map',
                          str(tmp_path / 'room.json'), '--out', str(tmp_path / 'm' / 'map.yaml'),
                          '--resolution', '0.1'], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert 'wrote' in out.stdout and (tmp_path / 'm' / 'map.pgm').is_file()
    meta, occ = _read_as_map_server(tmp_path / 'm' / 'map.yaml')
    assert meta['resolution'] == 0.1
    assert np.array_equal(occ, occupancy_grid(scene, config=MapConfig(0.1)).data)
    bad = subprocess.run([sys.executable, '-m', 'scene_synth_ros.cli', 'map',
                          str(tmp_path / 'room.json'), '--out', str(tmp_path / 'x.yaml'),
                          '--scan-height', '9'], capture_output=True, text=True)
    assert bad.returncode == 2
    assert '--scan-height must be between 0.0 and 3.0, got 9.0' in bad.stderr
    assert len(bad.stderr.strip().splitlines()) == 1
    assert json.loads((tmp_path / 'room.json').read_text())['objects']
