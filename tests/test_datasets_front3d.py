"""3D-FRONT import (datasets/front3d.py) on a house written by hand: positions, yaws,
footprints, floor, doors and windows against hand calculation, and every broken input as a
report line.

The house, in REP-103 (x, y); the file is y up, so a REP point (x, y) is (x, 0, -y) there:

* an L-shaped floor (0,0) (4,0) (4,2) (2,2) (2,4) (0,4), as four triangles;
* a door mesh through the wall x = 4 over y 0.5..1.3, 2 m high; a window mesh through the
  wall y = 0 over x 1..2.2 with its sill at 0.9 m and its top at 2.1 m; the ceiling at 2.7 m;
* a king-size bed (older layout: size = x, z, y = 2.0, 2.2, 1.0) turned 90 degrees about y,
  centre (1.1, 1.0): its front faces +x (yaw 0) and its back touches the wall x = 0;
* a nightstand (newer layout: bbox = x, y, z = 0.5, 0.6, 0.4) turned 180 degrees about y
  and mirrored across its front (scale x -1.5), at (0.5, 3.0): yaw 90 degrees, 0.75 wide;
* a table lamp on the nightstand (bottom 0.6 m, the nightstand's top), mirrored along its
  front (scale z -1): identity rotation, so its front turns from -y to +y (yaw 90 degrees);
* a door model among the furniture (category Door) at (1, 4) on the wall y = 4.
"""
import csv
import json
import math

import numpy as np
import pytest

from scene_synth_ros import schema
from scene_synth_ros.datasets import ImportConfig, import_dataset, load_room_types

Q90 = [0, math.sin(math.pi / 4), 0, math.cos(math.pi / 4)]


def yup(x, y, z=0.0):
    """REP-103 (x, y, z) as the file's y-up (x, y, z)."""
    return [x, z, -y]


def quad(x0, y0, x1, y1):
    """Two triangles of a floor rectangle, as flat xyz and faces from ``start``."""
    return [yup(x0, y0), yup(x1, y0), yup(x1, y1), yup(x0, y1)], [0, 1, 2, 0, 2, 3]


def mesh(uid, kind, boxes):
    xyz, faces = [], []
    for verts, f in boxes:
        faces += [i + len(xyz) for i in f]
        xyz += verts
    return {'uid': uid, 'jid': '', 'type': kind, 'xyz': [c for v in xyz for c in v],
            'faces': faces}


def slab(x0, y0, x1, y1, bottom, top):
    """The eight corners of an opening's box (faces are not needed for openings)."""
    return [yup(x, y, z) for x in (x0, x1) for y in (y0, y1) for z in (bottom, top)], []


def child(ref, iid, pos, rot=(0, 0, 0, 1), scale=(1, 1, 1)):
    return {'ref': ref, 'instanceid': iid, 'pos': list(pos), 'rot': list(rot),
            'scale': list(scale)}


def house():
    floor = mesh('floor/0', 'Floor', [quad(0, 0, 4, 2), quad(0, 2, 2, 4)])
    ceiling = mesh('ceiling/0', 'Ceiling', [([yup(0, 0, 2.7), yup(4, 0, 2.7), yup(4, 4, 2.7)],
                                             [0, 1, 2])])
    door = mesh('door/0', 'Door', [slab(3.9, 0.5, 4.1, 1.3, 0.0, 2.0)])
    threshold = mesh('door/1', 'Door', [slab(3.9, 0.5, 4.1, 1.3, 0.0, 0.0)])
    window = mesh('window/0', 'Window', [slab(1.0, -0.1, 2.2, 0.1, 0.9, 2.1)])
    furniture = [
        {'uid': 'bed/model', 'jid': 'jid-bed', 'size': [2.0, 2.2, 1.0], 'bbox': [2.0, 2.2, 1.0],
         'title': '', 'valid': True},
        {'uid': 'ns/model', 'jid': 'jid-ns', 'category': 'Nightstand', 'bbox': [0.5, 0.6, 0.4],
         'valid': True},
        {'uid': 'lamp/model', 'jid': 'jid-lamp', 'size': [0.4, 0.4, 0.5], 'valid': True},
        {'uid': 'empty/model', 'jid': 'jid-empty', 'size': [1, 1, 1]},
        {'uid': 'missing/model', 'jid': 'jid-missing', 'size': [1, 1, 1]},
        {'uid': 'bad/model', 'jid': 'jid-bed', 'size': [1, 1, 1], 'valid': False},
        {'uid': 'nosize/model', 'jid': 'jid-lamp'},
        {'uid': 'door/model', 'jid': 'jid-door'},
        {'uid': 'door2/model', 'jid': 'jid-door2', 'size': [0.9, 0.1, 2.05]},
    ]
    bed_room = {'type': 'MasterBedroom', 'instanceid': 'MasterBedroom-1', 'pos': [0, 0, 0],
                'rot': [0, 0, 0, 1], 'scale': [1, 1, 1], 'children': [
                    child('floor/0', 'mesh/1', (0, 0, 0)),
                    child('ceiling/0', 'mesh/2', (0, 0, 0)),
                    child('bed/model', 'furniture/1', yup(1.1, 1.0), Q90),
                    child('ns/model', 'furniture/2', yup(0.5, 3.0), (0, 1, 0, 0),
                          (-1.5, 1, 1)),
                    child('lamp/model', 'furniture/3', yup(0.5, 3.0, 0.6), scale=(1, 1, -1)),
                    child('bed/model', 'furniture/4', yup(3.0, 3.0), Q90),   # in the notch
                    child('bed/model', 'furniture/5', [float('nan'), 0, 0]),
                    child('empty/model', 'furniture/6', yup(1, 1)),
                    child('missing/model', 'furniture/7', yup(1, 1)),
                    child('ghost/model', 'furniture/8', yup(1, 1)),
                    child('bad/model', 'furniture/9', yup(1, 1)),
                    child('nosize/model', 'furniture/10', yup(1, 1)),
                    child('bed/model', 'furniture/11', yup(1, 1), scale=(0.01, 1, 1)),
                    child('door/model', 'furniture/12', yup(4, 0.9)),
                    child('door2/model', 'furniture/13', yup(1.0, 4.0)),
                ]}
    bath = {'type': 'Bathroom', 'instanceid': 'Bathroom-2',
            'children': [child('lamp/model', 'furniture/20', yup(10, 10))]}
    garage = {'type': 'Garage', 'instanceid': 'Garage-3', 'children': []}
    return {'uid': 'house-1', 'jobid': 'job', 'furniture': furniture,
            'mesh': [floor, ceiling, door, threshold, window],
            'extension': {'door': [{'ref': ['door/model'], 'roomId': 'MasterBedroom-1'}]},
            'lights': [], 'groups': [],
            'scene': {'ref': '-1', 'pos': [0, 0, 0], 'rot': [0, 0, 0, 1], 'scale': [1, 1, 1],
                      'room': [bed_room, bath, garage]}}


@pytest.fixture
def data(tmp_path):
    (tmp_path / 'house.json').write_text(json.dumps(house()))     # NaN written as NaN
    with open(tmp_path / 'map.csv', 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['index', 'model_id', 'category', 'super-category'])
        w.writerow([0, 'jid-bed', 'King-size Bed', 'Bed'])
        w.writerow([1, 'jid-lamp', 'Table Lamp', 'Lighting'])
        w.writerow([2, 'jid-empty', '', ''])
        w.writerow([3, 'jid-door2', 'Door', 'Door'])
    return tmp_path


def by_category(scene):
    return {o['category']: o for o in scene['objects']}


def run(data, **kw):
    config = ImportConfig(room_types=load_room_types('3dfront'))
    return import_dataset('3dfront', [data / 'house.json'], table=data / 'map.csv',
                          config=config, **kw)


def test_room_floor_openings_and_objects_match_hand_calculation(data):
    result = run(data)
    (name, scene), = result.scenes.items()
    assert name == '3dfront_house-1_MasterBedroom-1'
    room = scene['room']
    assert room['room_type'] == 'bedroom' and room['wall_height'] == pytest.approx(2.7)
    # the L: six vertices, counter-clockwise, 12 m^2
    from shapely.geometry import Polygon
    floor = Polygon(room['floor'])
    assert len(room['floor']) == 6 and floor.area == pytest.approx(12.0)
    assert floor.exterior.is_ccw
    assert floor.symmetric_difference(
        Polygon([(0, 0), (4, 0), (4, 2), (2, 2), (2, 4), (0, 4)])).area < 1e-6
    door, door2 = sorted(room['doors'], key=lambda d: -d['position'][0])
    assert door['position'] == pytest.approx([4.0, 0.9]) and door['width'] == pytest.approx(0.8)
    assert door['height'] == pytest.approx(2.0)
    # a door model among the furniture (size x 0.9, z 0.1, y 2.05) on the wall y = 4
    assert door2['position'] == pytest.approx([1.0, 4.0])
    assert (door2['width'], door2['height']) == pytest.approx((0.9, 2.05))
    (window,) = room['windows']
    assert window['position'] == pytest.approx([1.6, 0.0])
    assert (window['width'], window['sill'], window['height']) == pytest.approx((1.2, 0.9, 1.2))

    objs = by_category(scene)
    assert set(objs) == {'king-size bed', 'nightstand', 'table lamp'}
    bed = objs['king-size bed']
    assert bed['model_id'] == 'jid-bed' and bed['id'] == 'king_size_bed_0'
    assert bed['position'] == pytest.approx([1.1, 1.0, 0.0])
    assert bed['yaw'] == pytest.approx(0.0, abs=1e-6)
    assert bed['size'] == pytest.approx([2.0, 2.2, 1.0])
    ns = objs['nightstand']
    assert ns['position'] == pytest.approx([0.5, 3.0, 0.0])
    assert ns['yaw'] == pytest.approx(math.pi / 2)
    assert ns['size'] == pytest.approx([0.75, 0.4, 0.6])     # bbox (x, y, z), x scaled 1.5
    lamp = objs['table lamp']
    assert lamp['position'] == pytest.approx([0.5, 3.0, 0.6])
    assert lamp['yaw'] == pytest.approx(math.pi / 2)          # mirrored along its front
    assert lamp['size'] == pytest.approx([0.4, 0.4, 0.5])
    assert lamp['support'] == ns['id'] and 'support' not in ns
    assert scene['meta']['source'] == {'format': '3dfront', 'file': 'house.json',
                                       'house_id': 'house-1', 'room_id': 'MasterBedroom-1',
                                       'room_type': 'MasterBedroom'}
    schema.check_against_schema(scene, 'scene')


def test_every_broken_input_is_a_report_line(data):
    report = run(data).report
    lines = {(x.what, x.reason, x.text.split(': ', 1)[1].split(':')[0]) for x in report.lines}
    expected_objects = {
        ('object', 'outside floor', 'object furniture/4'),
        ('object', 'broken transform', 'object furniture/5'),
        ('object', 'unknown category', 'object furniture/6'),
        ('object', 'missing model', 'object furniture/7'),
        ('object', 'missing model', 'object furniture/8'),
        ('object', 'invalid model', 'object furniture/9'),
        ('object', 'no size', 'object furniture/10'),
        ('object', 'scale out of range', 'object furniture/11'),
    }
    assert expected_objects <= lines
    rooms = {(x.reason, x.text.split(' room ')[1].split(':')[0]) for x in report.lines
             if x.what == 'room'}
    assert rooms == {('no floor', 'Bathroom-2'), ('unmapped room type', 'Garage-3')}
    t = report.totals()
    assert (t['rooms_seen'], t['rooms_kept'], t['rooms_dropped']) == (3, 1, 2)
    assert (t['objects_kept'], t['objects_dropped']) == (3, 8)
    assert all(len(x.text) <= 300 and '\n' not in x.text for x in report.lines)


def test_a_model_folder_gives_the_box_and_the_footprint_centre(data, tmp_path):
    import trimesh
    models = tmp_path / 'models'
    (models / 'jid-bed').mkdir(parents=True)
    # an off-centre box: extents x 1.8, y 0.9, z 2.1, centred at (0.3, 0.45, -0.2)
    box = trimesh.creation.box(extents=(1.8, 0.9, 2.1))
    box.apply_translation((0.3, 0.45, -0.2))
    box.export(models / 'jid-bed' / 'raw_model.obj')
    (scene,) = run(data, models=models).scenes.values()
    bed = by_category(scene)['king-size bed']
    assert bed['size'] == pytest.approx([1.8, 2.1, 0.9])
    # the box centre turned 90 degrees about y: (0.3, 0, -0.2) -> (-0.2, 0, -0.3), so the
    # footprint centre is (1.1 - 0.2, 0, -1.0 - 0.3) in the file: (0.9, 1.3) in REP-103
    assert bed['position'] == pytest.approx([0.9, 1.3, 0.0])
    assert bed['yaw'] == pytest.approx(0.0, abs=1e-6)


def test_model_info_json_is_a_category_mapping_too(data):
    info = [{'model_id': 'jid-bed', 'category': 'King-size Bed', 'super-category': 'Bed'},
            {'model_id': 'jid-lamp', 'category': 'Table Lamp', 'super-category': 'Lighting'}]
    (data / 'model_info.json').write_text(json.dumps(info))
    config = ImportConfig(room_types=load_room_types('3dfront'))
    result = import_dataset('3dfront', [data / 'house.json'], config=config,
                            table=data / 'model_info.json')
    (scene,) = result.scenes.values()
    assert set(by_category(scene)) == {'king-size bed', 'nightstand', 'table lamp'}


def test_filters_drop_large_rooms_and_count_ranges(data):
    small = ImportConfig(room_types=load_room_types('3dfront'), room_size={'bedroom': 3.5})
    result = import_dataset('3dfront', [data], table=data / 'map.csv', config=small)
    assert not result.scenes
    assert result.report.dropped('room')['room too large'] == 1
    few = ImportConfig(room_types=load_room_types('3dfront'), object_count=(4, 10))
    result = import_dataset('3dfront', [data], table=data / 'map.csv', config=few)
    assert result.report.dropped('room')['too few objects'] == 1
    assert np.isclose(sum(result.report.rooms_kept.values()), 0)
