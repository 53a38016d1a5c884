"""Batches of whole houses: `scene-synth generate -n N --houses` (procedural house plans) and
`--layouts DIR` holding house layouts, on worker processes and on Ray: one manifest row and
one scene file a house, the same houses whatever runs them."""
import json
from pathlib import Path
import shutil

from conftest import EXAMPLES
import pytest
from test_batch import rows, scenes, stable
from test_house import HOUSE

from scene_synth_ros.schema import parse_house_scene


def test_house_plans_on_one_and_two_workers_are_the_same_houses(cli, tmp_path):
    one, two = tmp_path / 'one', tmp_path / 'two'
    proc = cli('generate', '-n', 3, '--houses', '--seed', 4, '--workers', 2, '--png',
               '--export', 'mjcf', '--out', two, '-q')
    assert '3 houses asked for; 3 furnished and 0 failed' in proc.stdout
    assert 'on 2 worker processes' in proc.stdout
    cli('generate', '-n', 3, '--houses', '--seed', 4, '--workers', 1, '--out', one, '-q')
    assert scenes(one) == scenes(two)
    for row in rows(two):
        assert row['room_type'] == 'house' and row['rooms'] >= 3
        assert row['valid'] and row['robot_kept'], row
        assert row['layout'] == f'house plan: plan seed 4, house {row["index"]}'
        house = parse_house_scene((two / 'scenes' / f'{row["room"]}.json').read_text())
        assert len(house.scenes) == row['rooms'] and len(house.objects()) == row['objects']
        assert (two / 'png' / f'{row["room"]}.png').stat().st_size > 1000
        world = (two / 'mjcf' / f'{row["room"]}.xml').read_text()
        assert world.count('<freejoint') == row['objects']
    r = cli('generate', '--houses', '--seed', 4, ok=False)
    assert r.returncode == 2 and '--houses is for batches' in r.stderr
    r = cli('generate', '-n', 2, '--houses', '--layouts', EXAMPLES, '--out', tmp_path / 'x',
            ok=False)
    assert r.returncode == 2 and 'without --layout and --layouts' in r.stderr


def test_a_directory_of_house_and_room_layouts(cli, tmp_path):
    layouts = tmp_path / 'layouts'
    layouts.mkdir()
    (layouts / 'a_house.json').write_text(json.dumps(HOUSE))
    shutil.copy(EXAMPLES / 'apartment_layout.json', layouts / 'b_apartment.json')
    shutil.copy(EXAMPLES / 'bedroom_layout.json', layouts / 'c_bedroom.json')
    out = tmp_path / 'out'
    proc = cli('generate', '--layouts', layouts, '--seed', 1, '--workers', 2, '--lockstep', 1,
               '--out', out, '-q')
    assert '3 furnished and 0 failed' in proc.stdout
    got = rows(out)
    assert [r['room_type'] for r in got] == ['house', 'house', 'bedroom']
    assert [r.get('rooms') for r in got] == [3, 6, None]
    assert all(r['valid'] and r['robot_kept'] for r in got)
    apartment = parse_house_scene((out / 'scenes' / 'room_000001.json').read_text())
    assert list(apartment.scenes) == ['hall', 'living', 'dining', 'bedroom', 'bathroom',
                                      'kitchen']


def test_ray_gives_the_houses_of_the_process_pool(cli, tmp_path):
    ray = pytest.importorskip('ray')
    assert not ray.is_initialized()
    pool, on_ray = tmp_path / 'pool', tmp_path / 'ray'
    cli('generate', '-n', 2, '--houses', '--seed', 9, '--workers', 2, '--out', pool, '-q')
    proc = cli('generate', '-n', 2, '--houses', '--seed', 9, '--workers', 2, '--ray',
               '--out', on_ray, '-q')
    assert 'on 2 Ray workers' in proc.stdout and not ray.is_initialized()
    assert scenes(on_ray) == scenes(pool)
    assert [stable(r) for r in rows(on_ray)] == [stable(r) for r in rows(pool)]
    assert Path(on_ray / 'summary.json').is_file()
