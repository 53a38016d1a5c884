"""ProcTHOR import (datasets/procthor.py) on JSON lines written by hand: Unity degrees about
y, nested children, holes on walls, asset boxes, and broken lines, against hand
calculation.

Unity's (x, z) is REP-103's (x, y). The bedroom is x 0..5, y 0..4.

* the wall from (0, 0) to (5, 0) has its polygon written from (5, 0): a door's hole at
  x 1.0..1.9 along it is centred 1.45 m from (5, 0), at (3.55, 0);
* a window on the wall from (0, 0) to (0, 4) (polygon from (0, 0)), hole x 1..2, y 0.9..2;
* a bed (box x 1.6, y 1.0, z 2.1) at (1.05, 0.5, 2.0) turned 90 degrees: Unity turns
  clockwise seen from above, so its +z front goes to +x, yaw 0; 1.6 wide, 2.1 deep, its
  bottom at 0.5 - 1.0 / 2 = 0 (positions are box centres);
* a dresser turned 180 degrees (yaw -90) with a desk lamp child, its bottom at the
  dresser's top (0.9 m): the lamp's support is the dresser.
"""
import gzip
import json
import math

import pytest

from scene_synth_ros import schema
from scene_synth_ros.datasets import ImportConfig, import_dataset, load_room_types

ASSETS = {
    'Bed_1': {'objectType': 'Bed', 'boundingBox': {'x': 1.6, 'y': 1.0, 'z': 2.1}},
    'Dresser_1': {'objectType': 'Dresser', 'boundingBox': {'x': 1.2, 'y': 0.9, 'z': 0.5}},
    'Desk_Lamp_1': {'objectType': 'DeskLamp', 'boundingBox': {'x': 0.3, 'y': 0.5, 'z': 0.3}},
}


def p(x, z, y=0.0):
    return {'x': x, 'y': y, 'z': z}


def wall(room, a, b, height=2.8):
    wid = f'wall|{room}|{min(a[0], b[0]):.2f}|{min(a[1], b[1]):.2f}|' \
          f'{max(a[0], b[0]):.2f}|{max(a[1], b[1]):.2f}'
    return {'id': wid, 'roomId': room,
            'polygon': [p(*a), p(*b), p(*a, height), p(*b, height)]}


def obj(oid, asset, x, y, z, ry=0.0, rx=0.0, children=()):
    d = {'id': oid, 'assetId': asset, 'position': p(x, z, y),
         'rotation': {'x': rx, 'y': ry, 'z': 0}, 'kinematic': True}
    if children:
        d['children'] = list(children)
    return d


def house(room_type='Bedroom'):
    walls = [wall('room|1', (5, 0), (0, 0)), wall('room|1', (0, 0), (0, 4)),
             wall('room|1', (0, 4), (5, 4)), wall('room|1', (5, 4), (5, 0))]
    return {
        'rooms': [{'id': 'room|1', 'roomType': room_type,
                   'floorPolygon': [p(0, 0), p(5, 0), p(5, 4), p(0, 4)]}],
        'walls': walls,
        'doors': [{'id': 'door|1', 'room0': 'room|1', 'room1': 'room|1',
                   'wall0': walls[0]['id'], 'wall1': walls[0]['id'] + '|exterior',
                   'holePolygon': [p(1.0, 0, 0), p(1.9, 0, 2.1)], 'assetId': 'Doorway_1'}],
        'windows': [{'id': 'window|1', 'room0': 'room|1', 'room1': 'room|1',
                     'wall0': walls[1]['id'], 'wall1': walls[1]['id'] + '|exterior',
                     'holePolygon': [p(1.0, 0, 0.9), p(2.0, 0, 2.0)]}],
        'objects': [
            obj('bed', 'Bed_1', 1.05, 0.5, 2.0, ry=90),
            obj('dresser', 'Dresser_1', 3.0, 0.45, 3.75, ry=180, children=[
                obj('lamp', 'Desk_Lamp_1', 3.0, 1.15, 3.75)]),
            obj('ghost', 'Ghost_9', 2.5, 0.5, 2.0, children=[
                obj('orphan', 'Desk_Lamp_1', 2.5, 1.0, 2.0)]),
            obj('tipped', 'Bed_1', 3.0, 0.5, 1.5, ry=0, rx=90),
        ],
    }


@pytest.fixture
def data(tmp_path):
    lines = [json.dumps(house()), '{"rooms": [{"id": "room|1", "roomType": "Bed',
             json.dumps(house('Garage')), '', json.dumps([1, 2])]
    text = '\n'.join(lines) + '\n'
    (tmp_path / 'houses.jsonl').write_text(text)
    with gzip.open(tmp_path / 'houses2.jsonl.gz', 'wt') as f:
        f.write(text)
    (tmp_path / 'procthor_asset_boxes.json').write_text(json.dumps(ASSETS))
    return tmp_path


def run(inputs, **kw):
    config = ImportConfig(room_types=load_room_types('procthor'), **kw)
    return import_dataset('procthor', inputs, config=config)


def test_house_matches_hand_calculation(data):
    result = run([data / 'houses.jsonl'])
    (name, scene), = result.scenes.items()
    assert name == 'procthor_1_room_1'
    room = scene['room']
    assert room['wall_height'] == pytest.approx(2.8)
    (door,) = room['doors']
    assert door['position'] == pytest.approx([3.55, 0.0])
    assert (door['width'], door['height']) == pytest.approx((0.9, 2.1))
    (window,) = room['windows']
    assert window['position'] == pytest.approx([0.0, 1.5])
    assert (window['width'], window['sill'], window['height']) == pytest.approx((1.0, 0.9, 1.1))
    objs = {o['category']: o for o in scene['objects']}
    assert set(objs) == {'bed', 'dresser', 'desk lamp'}
    bed, dresser, lamp = objs['bed'], objs['dresser'], objs['desk lamp']
    assert bed['model_id'] == 'Bed_1'
    assert bed['position'] == pytest.approx([1.05, 2.0, 0.0])
    assert bed['yaw'] == pytest.approx(0.0, abs=1e-9)
    assert bed['size'] == pytest.approx([1.6, 2.1, 1.0])
    assert dresser['position'] == pytest.approx([3.0, 3.75, 0.0])
    assert dresser['yaw'] == pytest.approx(-math.pi / 2)
    assert dresser['size'] == pytest.approx([1.2, 0.5, 0.9])
    assert lamp['position'] == pytest.approx([3.0, 3.75, 0.9])
    assert lamp['yaw'] == pytest.approx(math.pi / 2)
    assert lamp['support'] == dresser['id']
    assert [o['category'] for o in scene['objects']][-1] == 'desk lamp'   # second tier last
    schema.check_against_schema(scene, 'scene')


def test_broken_lines_and_objects_are_report_lines(data):
    report = run([data / 'houses.jsonl']).report
    houses = [x for x in report.lines if x.what == 'house']
    assert len(houses) == 2
    assert 'line 2' in houses[0].text and 'not valid JSON' in houses[0].text
    assert 'line 5' in houses[1].text and 'not a ProcTHOR house' in houses[1].text
    dropped = report.dropped('object')
    assert dropped == {'missing model': 1, 'support dropped': 1, 'broken transform': 1}
    assert report.dropped('room') == {'unmapped room type': 1}
    assert any('orphan' in x.text and 'ghost' in x.text for x in report.lines
               if x.reason == 'support dropped')


def test_gzip_reads_the_same_and_folders_are_searched(data):
    plain = run([data / 'houses.jsonl'])
    both = run([data])
    assert len(both.scenes) == 2 and both.report.files == [
        str(data / 'houses.jsonl'), str(data / 'houses2.jsonl.gz')]
    scenes = list(both.scenes.values())
    assert scenes[0]['objects'] == scenes[1]['objects'] == \
        next(iter(plain.scenes.values()))['objects']
    assert sorted(both.scenes) == ['procthor_1_room_1', 'procthor_1_room_1_2']


def test_a_truncated_gzip_file_is_a_report_line(data):
    blob = (data / 'houses2.jsonl.gz').read_bytes()
    (data / 'cut.jsonl.gz').write_bytes(blob[: len(blob) // 2])
    report = run([data / 'cut.jsonl.gz']).report
    assert report.dropped('file') == {'unreadable file': 1}
