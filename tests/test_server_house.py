"""A house served by the node's core (server.SceneServer): a house layout on the same input
as a room's, every room furnished at once, requests that name the room they act on."""
from __future__ import annotations

from contextlib import contextmanager
import copy
import json
import time

import pytest
from test_house import HOUSE
from test_server import LAYOUT, Recorder, _user_server

from scene_synth_ros.geometry import check_scene
from scene_synth_ros.house import HouseScene
from scene_synth_ros.markers import house_markers
from scene_synth_ros.schema import parse_house_scene
from scene_synth_ros.server import OK


@contextmanager
def serving(**config):
    """(server, its Recorder), closed after."""
    rec = Recorder()
    srv = _user_server(rec, **config)
    srv.rec = rec
    try:
        yield srv, rec
    finally:
        srv.close()


@pytest.fixture(scope='module')
def served():
    with serving() as (srv, rec):
        assert srv.submit_layout(json.dumps(HOUSE))
        yield srv, rec.wait(1)


def test_a_house_layout_is_furnished_whole_and_published_as_one_house_scene(served):
    srv, first = served
    house = parse_house_scene(first.json)
    assert list(house.scenes) == ['hall', 'bed', 'kitchen'] and first.seed == 0
    for rid, scene in house.scenes.items():
        assert scene.objects, rid
        assert check_scene(scene).ok, (rid, check_scene(scene).summary())
    robot = house.meta['robot']
    assert robot['promise_kept'] and set(robot['rooms']) == set(house.scenes)
    assert {o.id for o in first.added} and len(first.added) == len(house.objects())
    # the map is the whole house's: it spans every room
    xs = [p[0] for s in house.scenes.values() for p in s.room.floor]
    assert first.map.width * first.map.resolution >= max(xs) - min(xs)
    status = srv.status
    assert status.level == OK and status.room_type == 'house'
    assert status.objects == len(house.objects())
    assert 'a house of 3 rooms' in status.message
    markers = house_markers(house)
    assert {m.ns.split('/')[0] for m in markers} == {'hall', 'bed', 'kitchen', 'walls'}
    assert len({(m.ns, m.id) for m in markers}) == len(markers)
    walls = [m for m in markers if m.ns == 'walls']
    from scene_synth_ros.export.architecture import house_wall_boxes
    assert [m.scale for m in walls] == [b.size for b in house_wall_boxes(house.house)]


def test_requests_on_a_house_name_their_room_and_change_only_that_room(served):
    srv, first = served
    before = parse_house_scene(first.json)
    answer = srv.call('next_object', room='hall')
    n = len(srv.rec.served)
    if answer.ok:       # something more fits in the hall: it went there, nowhere else
        now = parse_house_scene(srv.rec.wait(n).json)
        assert len(now.scenes['hall']) == len(before.scenes['hall']) + 1
        assert now.scenes['bed'].to_dict() == before.scenes['bed'].to_dict()
    else:
        assert 'fits' in answer.message
    assert srv.call('reset', room='kitchen').ok
    now = srv.scene
    assert isinstance(now, HouseScene) and not now.scenes['kitchen'].objects
    assert now.scenes['bed'].objects
    found = srv.call('suggest', room='kitchen', k=3)
    assert found.ok and found.objects
    again = srv.call('generate', room='kitchen', seed=5)
    assert again.ok and srv.scene.scenes['kitchen'].objects
    assert srv.scene.scenes['bed'].to_dict() == now.scenes['bed'].to_dict()
    for kind in ('next_object', 'suggest'):
        a = srv.call(kind)
        assert not a.ok and "name it in room (one of 'hall', 'bed', 'kitchen')" in a.message
    a = srv.call('reset', room='attic')
    assert not a.ok and "room 'attic' is not a room of the house" in a.message
    assert srv.call('reset').ok and not srv.scene.objects()
    assert srv.call('generate').ok and len(srv.scene.objects()) > 0


def test_a_house_gives_way_to_a_room_and_a_room_refuses_room_ids():
    with serving(auto_generate=False) as (srv, rec):
        house = copy.deepcopy(HOUSE)
        assert srv.submit_layout(house)
        given = rec.wait(1)
        assert isinstance(given.scene, HouseScene) and not given.scene.objects()
        assert srv.furnish(json.dumps(house), seed=2).ok
        assert srv.scene.objects()
        assert srv.submit_layout(LAYOUT)
        rec.wait(3)
        a = srv.call('reset', room='bed')
        assert not a.ok and 'serves a single room' in a.message
        bad = copy.deepcopy(HOUSE)
        bad['doors'][0]['rooms'] = ['hall', 'nowhere']
        assert not srv.submit_layout(bad)
        assert 'nowhere' in srv.status.last_error and len(srv.status.last_error) < 400


def test_a_house_served_is_exported_as_one_world_in_each_format(tmp_path):
    with serving(export_dir=str(tmp_path), export_formats='sdf,mjcf') as (srv, rec):
        assert srv.submit_layout(json.dumps(HOUSE))
        served = rec.wait(1)
        deadline = time.monotonic() + 30       # written just after it is published
        while not (tmp_path / 'house_00001.xml').exists():
            assert time.monotonic() < deadline
            time.sleep(0.1)
        assert sorted(p.name for p in tmp_path.glob('house_00001*')) == [
            'house_00001.json', 'house_00001.sdf', 'house_00001.xml',
            'house_00001_labels.json']
        assert parse_house_scene((tmp_path / 'house_00001.json').read_text()).to_dict() == \
            parse_house_scene(served.json).to_dict()


def test_a_room_generated_keeps_what_was_done_meanwhile_to_the_others(served):
    import threading
    srv, _ = served
    assert srv.call('reset', room='bed').ok
    done = {}
    worker = threading.Thread(
        target=lambda: done.update(answer=srv.call('generate', room='kitchen', seed=11)))
    worker.start()
    inserted = srv.call('next_object', room='bed', seed=2)
    worker.join(120)
    assert done['answer'].ok and inserted.ok
    now = srv.scene
    # served before the generate or during it: the bed's new object is there after it
    assert [o.id for o in now.scenes['bed'].objects] == [inserted.objects[0].id]
    assert now.scenes['kitchen'].objects


def test_a_house_layout_is_refused_whole_for_one_room_that_cannot_hold_furniture():
    with serving(auto_generate=False) as (srv, rec):
        bad = copy.deepcopy(HOUSE)
        bad['rooms'].append({'id': 'slit', 'room_type': 'dining',
                             'floor': [[6, 0], [6.3, 0], [6.3, 8], [6, 8]]})
        bad['doors'].append({'rooms': ['hall', 'slit'], 'position': [6, 0.7], 'width': 0.6,
                             'height': 2.0})
        assert not srv.submit_layout(bad)
        text = srv.status.last_error
        assert "room 'slit'" in text and '\n' not in text and len(text) < 400, text
        assert rec.served == []


def test_a_house_layouts_request_id_marks_only_the_scene_that_answers_it(served):
    srv, _ = served
    layout = copy.deepcopy(HOUSE)
    layout['request_id'] = 'house-42'
    n = len(srv.rec.served)
    assert srv.submit_layout(layout)
    answer = json.loads(srv.rec.wait(n + 1).json)
    assert answer['request_id'] == 'house-42' and answer['meta']['request_id'] == 'house-42'
    assert srv.call('reset', room='hall').ok
    later = json.loads(srv.rec.wait(n + 2).json)
    assert 'request_id' not in later and 'request_id' not in later.get('meta', {})
    assert srv.call('generate').ok
    again = json.loads(srv.rec.served[-1].json)
    assert 'request_id' not in again and 'request_id' not in again.get('meta', {})
