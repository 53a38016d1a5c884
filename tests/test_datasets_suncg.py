"""SUNCG import (datasets/suncg.py) on a house written by hand: column-major transforms,
world boxes, openings and broken inputs against hand calculation.

The file is y up: a REP-103 point (x, y) is (x, ·, -y) in it. The bedroom's box spans
x 0..5 and z 0..4, so its floor is x 0..5, y -4..0 in REP-103.

* a double bed turned 90 degrees about y (its +z front to +x: yaw 0), world box x 0..2.2,
  z 1.2..2.8: depth 2.2 along x, width 1.6, centre (1.1, -2.0);
* a chair mirrored along its front (scale z -1): front -z in the file, +y in REP-103
  (yaw 90 degrees); world box x 3.25..3.75, z 0.7..1.3: width 0.5, depth 0.6;
* a table lamp on the bed (its bottom at the bed's top, 1.0 m): the second tier from the
  geometry, as SUNCG has no parent links;
* a door through the wall x = 5 over z 1.0..1.9 and a window through z = 0 over x 1..2.5.
"""
import csv
import json
import math

import pytest

from scene_synth_ros import schema
from scene_synth_ros.datasets import ImportConfig, import_dataset, load_room_types

IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]


def column_major(rot3, t):
    """16 numbers, column after column, of [[rot3, t], [0, 1]]."""
    m = [[*rot3[i], t[i]] for i in range(3)] + [[0, 0, 0, 1]]
    return [m[r][c] for c in range(4) for r in range(4)]


def obj(i, model, lo, hi, transform=IDENTITY):
    return {'id': f'0_{i}', 'type': 'Object', 'valid': 1, 'modelId': model,
            'transform': transform, 'bbox': {'min': lo, 'max': hi}}


def house():
    r90 = column_major([[0, 0, 1], [0, 1, 0], [-1, 0, 0]], [1.1, 0, 2.0])
    mirror = column_major([[1, 0, 0], [0, 1, 0], [0, 0, -1]], [3.5, 0, 1.0])
    r45 = column_major([[math.cos(math.pi / 4), 0, math.sin(math.pi / 4)], [0, 1, 0],
                        [-math.sin(math.pi / 4), 0, math.cos(math.pi / 4)]], [4.0, 0, 3.0])
    nodes = [
        {'id': '0_0', 'type': 'Room', 'valid': 1, 'modelId': 'fr_0rm_0',
         'roomTypes': ['Bedroom'], 'nodeIndices': list(range(3, 15)),
         'bbox': {'min': [0, 0, 0], 'max': [5, 2.8, 4]}},
        {'id': '0_1', 'type': 'Room', 'modelId': 'fr_0rm_1', 'roomTypes': ['Garage', 'Office'],
         'nodeIndices': []},
        {'id': '0_2', 'type': 'Room', 'modelId': 'fr_0rm_2', 'roomTypes': ['Garage'],
         'nodeIndices': [], 'bbox': {'min': [10, 0, 0], 'max': [14, 2.8, 4]}},
        obj(3, 'm_bed', [0, 0, 1.2], [2.2, 1.0, 2.8], r90),
        obj(4, 'm_chair', [3.25, 0, 0.7], [3.75, 0.9, 1.3], mirror),
        obj(5, 'm_lamp', [0.9, 1.0, 1.8], [1.3, 1.5, 2.2]),
        obj(6, 'm_door', [4.9, 0, 1.0], [5.1, 2.1, 1.9]),
        obj(7, 'm_window', [1.0, 0.8, -0.1], [2.5, 2.0, 0.1]),
        obj(8, 'm_wall', [2, 0, 2], [2.1, 2.8, 3]),
        obj(9, 'm_unknown', [2, 0, 2], [2.5, 1, 2.5]),
        obj(10, 'm_missing', [2, 0, 2], [2.5, 1, 2.5]),
        obj(11, 'm_chair', [2, 0, 2], [2.5, 1, 2.5], [float('nan')] * 16),
        obj(12, 'm_chair', [2, 0, 2], [2.5, 1, 2.5], [0] * 15 + [1]),
        obj(13, 'm_table', [3.5, 0, 2.5], [4.5, 0.4, 3.5], r45),
        99,
    ]
    return {'id': 'h1', 'up': [0, 1, 0], 'front': [0, 0, 1], 'scaleToMeters': 1,
            'levels': [{'id': '0', 'nodes': nodes}]}


@pytest.fixture
def data(tmp_path):
    (tmp_path / 'house.json').write_text(json.dumps(house()))
    with open(tmp_path / 'ModelCategoryMapping.csv', 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['index', 'model_id', 'fine_grained_class', 'coarse_grained_class',
                    'empty_struct_obj'])
        for i, (m, c, s) in enumerate([('m_bed', 'double_bed', 2), ('m_chair', 'chair', 2),
                                       ('m_lamp', 'table_lamp', 2), ('m_door', 'door', 2),
                                       ('m_window', 'window', 2), ('m_wall', 'partition', 1),
                                       ('m_unknown', 'unknown', 2),
                                       ('m_table', 'coffee_table', 2)]):
            w.writerow([i, m, c, c, s])
    return tmp_path


def run(data):
    config = ImportConfig(room_types=load_room_types('suncg'))
    return import_dataset('suncg', [data], config=config)     # the mapping found beside it


def test_objects_and_openings_match_hand_calculation(data):
    result = run(data)
    (name, scene), = result.scenes.items()
    assert name == 'suncg_h1_0_0'
    room = scene['room']
    assert room['room_type'] == 'bedroom' and room['wall_height'] == pytest.approx(2.8)
    assert sorted(map(tuple, room['floor'])) == [(0, -4), (0, 0), (5, -4), (5, 0)]
    (door,) = room['doors']
    assert door['position'] == pytest.approx([5.0, -1.45]) and door['width'] == pytest.approx(0.9)
    assert door['height'] == pytest.approx(2.1)
    (window,) = room['windows']
    assert window['position'] == pytest.approx([1.75, 0.0])
    assert (window['width'], window['sill'], window['height']) == pytest.approx((1.5, 0.8, 1.2))
    objs = {o['category']: o for o in scene['objects']}
    bed, chair, lamp = objs['double bed'], objs['chair'], objs['table lamp']
    assert bed['position'] == pytest.approx([1.1, -2.0, 0.0])
    assert bed['yaw'] == pytest.approx(0.0, abs=1e-9)
    assert bed['size'] == pytest.approx([1.6, 2.2, 1.0])
    assert chair['position'] == pytest.approx([3.5, -1.0, 0.0])
    assert chair['yaw'] == pytest.approx(math.pi / 2)
    assert chair['size'] == pytest.approx([0.5, 0.6, 0.9])
    assert lamp['position'] == pytest.approx([1.1, -2.0, 1.0])
    assert lamp['support'] == bed['id']
    table = objs['coffee table']                 # 45 degrees: a square footprint, noted
    assert table['size'][:2] == pytest.approx([1 / math.sqrt(2)] * 2, abs=1e-4)
    schema.check_against_schema(scene, 'scene')


def test_broken_inputs_are_report_lines(data):
    report = run(data).report
    got = {(x.what, x.reason) for x in report.lines}
    assert {('object', 'architecture'), ('object', 'unknown category'),
            ('object', 'missing model'), ('object', 'broken transform'),
            ('room', 'no floor'), ('room', 'unmapped room type'),
            ('note', 'mapped with a guess')} <= got
    assert report.dropped('object')['broken transform'] == 2     # NaN and singular
    # the room with several types takes the first one the mapping knows (Office)
    assert report.room_types['Office -> office'] == 1
    assert any('0_1:' in x.text for x in report.lines if x.reason == 'no floor')
    assert any('0_13' in x.text and 'square' in x.text for x in report.lines
               if x.what == 'note')


def test_a_suncg_folder_gives_the_floor_mesh_and_model_boxes(data, tmp_path):
    from shapely.geometry import Polygon
    import trimesh
    models = tmp_path / 'suncg'
    (models / 'room' / 'h1').mkdir(parents=True)
    (models / 'object' / 'm_bed').mkdir(parents=True)
    # an L-shaped floor: REP-103 (0,-4) (5,-4) (5,-2) (2.5,-2) (2.5,0) (0,0), i.e. z = -y
    rep = [(0, -4), (5, -4), (5, -2), (2.5, -2), (2.5, 0), (0, 0)]
    tris = [[0, 1, 2], [0, 2, 3], [0, 3, 5], [3, 4, 5]]
    trimesh.Trimesh([(x, 0.0, -y) for x, y in rep], tris, process=False).export(
        models / 'room' / 'h1' / 'fr_0rm_0f.obj')
    trimesh.creation.box(extents=(1.5, 0.9, 2.0)).export(models / 'object' / 'm_bed' / 'm_bed.obj')
    config = ImportConfig(room_types=load_room_types('suncg'))
    result = import_dataset('suncg', [data], config=config, models=models)
    scene = result.scenes['suncg_h1_0_0']
    assert Polygon(scene['room']['floor']).symmetric_difference(Polygon(rep)).area < 1e-6
    objs = {o['category']: o for o in scene['objects']}
    assert objs['double bed']['size'] == pytest.approx([1.5, 2.0, 0.9])
    assert 'chair' not in objs               # its centre (3.5, -1) is in the L's notch
    assert any('0_4' in x.text for x in result.report.lines if x.reason == 'outside floor')
    assert not any('bounding box' in x.text for x in result.report.lines)
