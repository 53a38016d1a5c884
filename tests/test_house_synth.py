"""Whole houses furnished in one request (house_synth.furnish_house), the house scene
(msg_schemas/house_scene.schema.json) and `scene-synth generate --layout HOUSE`."""
import copy
import json
import shutil

import pytest
import shapely
from test_house import HOUSE, one_sentence

from scene_synth_ros.geometry import check_scene
from scene_synth_ros.house_synth import HouseSynthesisError, furnish_house, room_seed
from scene_synth_ros.paths import weights_dir
from scene_synth_ros.schema import (
    SceneValidationError,
    dump_house_scene,
    parse_house_layout,
    parse_house_scene,
)
from scene_synth_ros.synth import Synthesizer


@pytest.fixture(scope='module')
def furnished(synth):
    house = parse_house_layout(HOUSE)
    return house, furnish_house(synth, house, seed=3)


@pytest.fixture(scope='module')
def synth():
    return Synthesizer()


def test_every_room_is_furnished_validly_by_its_type_with_both_sides_of_each_door_clear(
        furnished):
    house, result = furnished
    assert list(result.rooms) == ['hall', 'bed', 'kitchen']
    for rid, r in result.rooms.items():
        scene = result.scene.scenes[rid]
        assert scene.room is house.rooms[rid] and scene.objects == r.scene.objects
        assert scene.objects, rid
        # check_scene keeps every door of the room clear; the door between two rooms is
        # in both rooms, so it is kept clear on both sides.
        assert check_scene(scene, r.allowance).ok, (rid, check_scene(scene).summary())
        assert r.robot.kept, (rid, r.robot.sentence())
    assert result.robot_kept and 'reaches every object' in result.robot_sentence()
    hall_door = next(d for d in house.doors if set(d.rooms) == {'hall', 'bed'})
    assert hall_door.openings['hall'] in house.rooms['hall'].doors
    assert hall_door.openings['bed'] in house.rooms['bed'].doors
    cats = {rid: {o.category for o in s.objects} for rid, s in result.scene.scenes.items()}
    assert cats['bed'] & {'double bed', 'single bed'}, cats
    assert not cats['hall'] & {'double bed', 'single bed'}, cats


def test_the_same_seed_gives_the_same_house_and_rooms_get_seeds_of_their_own(synth, furnished):
    house, result = furnished
    again = furnish_house(synth, house, seed=3)
    assert again.scene.to_dict() == result.scene.to_dict()
    other = furnish_house(synth, house, seed=4)
    assert other.scene.to_dict() != result.scene.to_dict()
    seeds = {room_seed(s, k) for s in range(20) for k in range(64)}
    assert len(seeds) == 20 * 64
    assert [r.scene.meta['seed'] for r in result.rooms.values()] == \
        [room_seed(3, k) for k in range(len(house.rooms))]
    with pytest.raises(ValueError, match='width must be at least 1'):
        furnish_house(synth, house, seed=3, width=0)


def test_the_house_scene_round_trips_and_names_a_misplaced_object(furnished):
    _, result = furnished
    text = dump_house_scene(result.scene)
    d = json.loads(text)
    assert d['meta']['seed'] == 3 and [r['id'] for r in d['rooms']] == ['hall', 'bed', 'kitchen']
    assert all('objects' in r for r in d['rooms'])
    back = parse_house_scene(text)
    assert back.to_dict() == result.scene.to_dict()
    assert [rid for rid, _ in back.objects()] == [rid for rid, _ in result.scene.objects()]
    wrong = copy.deepcopy(d)
    obj = wrong['rooms'][1]['objects'][0]
    obj['position'] = [20.0, 20.0, obj['position'][2]]
    with pytest.raises(SceneValidationError) as err:
        parse_house_scene(wrong)
    assert one_sentence(err.value, err.value.path).startswith('rooms[1].objects[0]')
    wrong = copy.deepcopy(d)
    wrong['rooms'][0]['objects'][0]['colour'] = 'red'
    with pytest.raises(SceneValidationError) as err:
        parse_house_scene(wrong)
    assert 'colour' in one_sentence(err.value, err.value.path)


def test_a_room_without_weights_is_named(tmp_path):
    shutil.copy(weights_dir() / 'bedroom.pt', tmp_path / 'bedroom.pt')
    synth = Synthesizer(tmp_path)
    with pytest.raises(HouseSynthesisError) as err:
        furnish_house(synth, parse_house_layout(HOUSE), seed=0)
    msg = str(err.value)
    assert msg.startswith("room 'hall': ") and '\n' not in msg and len(msg) <= 400, msg


def test_the_command_furnishes_a_house_layout_and_draws_it(cli, tmp_path):
    layout = tmp_path / 'house.json'
    layout.write_text(json.dumps(HOUSE))
    out, png = tmp_path / 'house_scene.json', tmp_path / 'house.png'
    r = cli('generate', '--layout', str(layout), '--seed', '3', '--out', str(out),
            '--png', str(png))
    assert r.returncode == 0, r.stderr
    assert 'bed (bedroom, 14.4 m2):' in r.stdout and 'robot: ' in r.stdout
    scene = parse_house_scene(out.read_text())
    assert sorted(scene.scenes) == ['bed', 'hall', 'kitchen'] and scene.objects()
    assert png.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
    # complete keeps a house scene's objects and furnishes the rest of every room
    partial = json.loads(out.read_text())
    kept = partial['rooms'][1]['objects'][:2]
    partial['rooms'][1]['objects'] = kept
    partial['rooms'][0]['objects'] = []
    (tmp_path / 'partial.json').write_text(json.dumps(partial))
    r = cli('complete', str(tmp_path / 'partial.json'), '--seed', '4', '--out',
            str(tmp_path / 'done.json'))
    done = parse_house_scene((tmp_path / 'done.json').read_text())
    rid = partial['rooms'][1]['id']
    bed = done.scenes[rid]
    given = parse_house_scene(partial).scenes[rid].objects
    assert [o.to_dict() for o in bed.objects[:2]] == [o.to_dict() for o in given]
    assert len(bed.objects) > 2 and done.scenes['hall'].objects
    # validate and render read a house too, every room of it
    r = cli('validate', str(tmp_path / 'done.json'))
    assert 'schema OK, a house of 3 rooms' in r.stdout and 'physically valid' in r.stdout
    cli('render', str(tmp_path / 'done.json'), '--png', str(tmp_path / 'r.png'))
    assert (tmp_path / 'r.png').read_bytes()[:4] == b'\x89PNG'
    r = cli('render', str(tmp_path / 'done.json'), '--channels', str(tmp_path / 'r.npy'),
            ok=False)
    assert r.returncode == 2 and 'is a house' in r.stderr
    # A house where one room is expected says so in one line.
    r = cli('suggest', str(layout), ok=False)
    assert r.returncode == 2 and 'house layout' in r.stderr and r.stderr.count('\n') == 1, \
        r.stderr


def test_procedural_house_plans_are_furnished_validly_room_by_room(synth):
    from scene_synth_ros.corpus.house_plan import house_plan
    for i in range(3):
        house = house_plan(0, i)
        result = furnish_house(synth, house, seed=i)
        assert list(result.rooms) == list(house.rooms)
        for rid, r in result.rooms.items():
            check = check_scene(r.scene, r.allowance)
            assert check.ok, (i, rid, check.summary())
            assert r.robot.kept, (i, rid, r.robot.sentence())
        assert sum(len(s.objects) for s in result.scene.scenes.values()) >= 2 * len(house.rooms)


def test_the_map_of_a_house_joins_its_rooms_through_their_doors(furnished, cli, tmp_path):
    from test_occupancy import _reachable

    from scene_synth_ros.occupancy import FREE, OCCUPIED, occupancy_grid
    from scene_synth_ros.synth_config import MapConfig
    house, result = furnished
    grid = occupancy_grid(result.scene)
    h = MapConfig().map_scan_height
    for rid, o in result.scene.objects():
        if o.position[2] <= h <= o.top:
            assert grid.data[grid.cell_of(*o.position[:2])] == OCCUPIED, (rid, o.id)
    # A planner starting just inside the entrance reaches every room, through every door.
    entrance = house.entrances[0]
    hall = house.rooms[entrance.rooms[0]]
    start = hall.wall_of(entrance.opening).normal * 0.3 + entrance.opening.position
    reached = _reachable(grid, grid.cell_of(*start))
    x, y = grid.centres()
    for rid, room in house.rooms.items():
        inside = shapely.contains_xy(room.polygon, x, y) & (grid.data == FREE)
        assert (reached & inside).any(), rid
    for door in house.doors:
        assert reached[grid.cell_of(*door.opening.position)], door.rooms
    scene_file = tmp_path / 'house_scene.json'
    scene_file.write_text(dump_house_scene(result.scene))
    r = cli('map', str(scene_file), '--out', str(tmp_path / 'map.yaml'))
    assert (tmp_path / 'map.pgm').is_file() and f'{grid.width} x {grid.height} cells' in r.stdout


def test_the_map_passes_doors_through_walls_a_wall_thickness_apart():
    from test_occupancy import _reachable

    from scene_synth_ros.house import HouseScene
    from scene_synth_ros.occupancy import occupancy_grid
    from scene_synth_ros.scene import Scene
    d = copy.deepcopy(HOUSE)
    d['rooms'][1]['floor'] = [[0, 1.8], [4, 1.8], [4, 5], [0, 5]]   # 0.4 m behind the hall's
    house = parse_house_layout(d)
    grid = occupancy_grid(HouseScene(house, {rid: Scene(r, []) for rid, r in
                                             house.rooms.items()}))
    entrance = house.entrances[0]
    start = house.rooms['hall'].wall_of(entrance.opening).normal * 0.3 + \
        entrance.opening.position
    reached = _reachable(grid, grid.cell_of(*start))
    assert reached[grid.cell_of(2.0, 3.5)]          # the middle of the bedroom


def test_the_readme_apartment_commands_as_written(tmp_path):
    """README's "A whole home": the six-room apartment furnished, exported as one world and
    mapped by the commands as a user types them, and by the library's call it names."""
    from pathlib import Path
    import subprocess
    import sys

    from scene_synth_ros.export.rest import mujoco_rest
    from scene_synth_ros.schema import load_layout
    root = Path(__file__).resolve().parent.parent
    block = (root / 'README.md').read_text().split('## A whole home\n', 1)[1]
    commands = [c for c in block.split('```bash', 1)[1].split('```', 1)[0].splitlines()
                if c.startswith('.venv/bin/scene-synth ')]
    assert [c.split()[1] for c in commands] == ['generate', 'export', 'map']
    (tmp_path / 'examples').symlink_to(root / 'examples')
    (tmp_path / '.venv').mkdir()
    (tmp_path / '.venv' / 'bin').symlink_to(Path(sys.executable).parent)
    for line in commands:
        done = subprocess.run(['bash', '-c', line], cwd=tmp_path, capture_output=True,
                              text=True, timeout=300)
        assert done.returncode == 0, f'$ {line}\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}'
    scene = parse_house_scene((tmp_path / 'apartment.json').read_text())
    assert len(scene.scenes) == 6
    assert all(s.objects for s in scene.scenes.values())
    report = mujoco_rest(tmp_path / 'apartment' / 'world.xml')
    assert report.bodies == len(scene.objects()) and report.passed(), report.failures()
    assert (tmp_path / 'apartment_map.pgm').is_file()
    again = furnish_house(Synthesizer(), load_layout(root / 'examples' /
                                                     'apartment_layout.json').house, seed=0)
    assert again.scene.to_dict()['rooms'] == scene.to_dict()['rooms']
