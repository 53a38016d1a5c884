"""Malformed files of each format: every one is report lines, never an exception."""
import json

import pytest
from test_datasets_procthor import ASSETS
from test_datasets_procthor import house as procthor_house

from scene_synth_ros.datasets import import_dataset

BOW_TIE = [{'x': 0, 'y': 0, 'z': 0}, {'x': 4, 'y': 0, 'z': 4}, {'x': 4, 'y': 0, 'z': 0},
           {'x': 0, 'y': 0, 'z': 4}]


def procthor_lines():
    bow = procthor_house()
    bow['rooms'][0]['floorPolygon'] = BOW_TIE
    no_floor = procthor_house()
    no_floor['rooms'][0]['floorPolygon'] = [{'x': 0, 'z': 0}]
    junk = procthor_house()
    junk['objects'] += [{'id': 1, 'assetId': 'Bed_1', 'position': 'here'}, 'not an object',
                       {'assetId': 'Bed_1', 'position': {'x': 1, 'y': 0.5, 'z': 1},
                        'rotation': {'y': 'ninety'}}]
    junk['doors'][0]['holePolygon'] = 'a hole'
    junk['windows'][0]['wall0'] = 'wall|nowhere'
    deep = '[' * 100000 + ']' * 100000
    return [bow, no_floor, junk, {'rooms': 'none'}, 7, deep]


def test_malformed_procthor_houses(tmp_path):
    lines = [x if isinstance(x, str) else json.dumps(x) for x in procthor_lines()]
    (tmp_path / 'bad.jsonl').write_text('\n'.join(lines) + '\n\x00\xff garbage\n')
    (tmp_path / 'procthor_asset_boxes.json').write_text(json.dumps(ASSETS))
    result = import_dataset('procthor', [tmp_path])
    report = result.report
    assert report.dropped('room')['no floor'] == 2
    assert report.dropped('object')['broken transform'] == 3     # 2 here, 1 in house()
    assert len([x for x in report.lines if x.what == 'house']) == 4
    (scene,) = result.scenes.values()           # the junk house keeps its good objects
    assert scene['room']['doors'] == [] and scene['room']['windows'] == []


@pytest.mark.parametrize('text', [
    '{"scene": {"room": [{"type": "Bedroom", "children": [{"ref": 5}, 3, '
    '{"ref": "m", "rot": [1, 2]}]}]}, "mesh": [{"uid": "m", "type": "Floor", '
    '"xyz": [0, 0, 0, 1, 0, 0, 1, 0, 1], "faces": ["a", "b", "c"]}]}',
    '{"scene": {"rot": [0, 0, 0, 0], "room": []}}',
    '{"scene": "flat"}',
    '[1, 2, 3]',
    '{"furniture": 5, "mesh": {"a": 1}, "scene": {"room": [{"children": {"a": 1}}]}}',
    '{"scene": {"room": [{"type": "Bedroom"',
])
def test_malformed_3dfront_files(tmp_path, text):
    (tmp_path / 'house.json').write_text(text)
    (tmp_path / 'map.csv').write_text('model_id,category\n')
    result = import_dataset('3dfront', [tmp_path / 'house.json'], table=tmp_path / 'map.csv')
    assert not result.scenes and result.report.lines


@pytest.mark.parametrize('levels', [
    'none', [5, {'nodes': 'x'}],
    [{'nodes': [{'type': 'Room', 'roomTypes': 'Bedroom', 'nodeIndices': 'abc',
                 'bbox': {'min': [0, 0, 0], 'max': [1, 'a', 1]}}]}],
    [{'nodes': [{'type': 'Room', 'roomTypes': ['Bedroom'], 'nodeIndices': [1, -1, 99],
                 'bbox': {'min': [0, 0, 0], 'max': [4, 2.8, 4]}},
                {'type': 'Object', 'modelId': 'm', 'transform': 'id', 'bbox': {}}]}],
])
def test_malformed_suncg_files(tmp_path, levels):
    (tmp_path / 'house.json').write_text(json.dumps({'id': 'h', 'levels': levels}))
    (tmp_path / 'ModelCategoryMapping.csv').write_text(
        'model_id,fine_grained_class,empty_struct_obj\nm,chair,2\n')
    result = import_dataset('suncg', [tmp_path])
    assert result.report.lines
