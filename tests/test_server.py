"""SceneServer: the node's behaviour without ROS, with the shipped weights."""
from __future__ import annotations

from dataclasses import fields
import json
import threading
import time

import pytest
import yaml

from scene_synth_ros import server as server_module
from scene_synth_ros.networks.bundle import BundleError
from scene_synth_ros.paths import config_dir, examples_dir, weights_dir
from scene_synth_ros.schema import parse_room_layout, parse_scene
from scene_synth_ros.server import (
    ERROR,
    OK,
    PARAMETERS,
    WARN,
    ConfigError,
    SceneServer,
    ServerConfig,
    check,
    parameters_file,
)
from scene_synth_ros.synth import SynthConfig
from scene_synth_ros.synth_config import ROBOT_SETTINGS, settings_of
from scene_synth_ros.user_catalog import load_catalog

LAYOUT = (examples_dir() / 'bedroom_layout.json').read_text()
PARTIAL = (examples_dir() / 'partial_bedroom.json').read_text()


class Recorder:
    """Collects what the server hands out, and lets a test wait for it."""

    def __init__(self):
        self.served = []
        self.statuses = []
        self.logs = []
        self.seeds = []             # what on_seed announced
        self.cond = threading.Condition()

    def publish(self, served):
        with self.cond:
            self.served.append(served)
            self.cond.notify_all()

    def status(self, status):
        self.statuses.append(status)

    def log(self, level, text):
        self.logs.append((level, text))

    def seed(self, seed):
        self.seeds.append(seed)

    def wait(self, n, timeout=60.0):
        with self.cond:
            assert self.cond.wait_for(lambda: len(self.served) >= n, timeout), \
                f'only {len(self.served)} rooms served, waited for {n}'
        return self.served[n - 1]


@pytest.fixture
def server():
    rec = Recorder()
    srv = SceneServer(ServerConfig(torch_threads=1), rec.publish, rec.status, rec.log,
                      rec.seed)
    srv.rec = rec
    yield srv
    srv.close()


def test_layout_is_furnished_and_published_as_valid_json(server):
    assert server.submit_layout(LAYOUT)
    served = server.rec.wait(1)
    assert served.source == 'room_layout' and served.seed == 0
    scene = parse_scene(served.json)
    assert scene.room.room_type == 'bedroom' and len(scene) == len(served.added) > 0
    assert scene.meta['seed'] == 0
    assert server.scene.to_dict() == scene.to_dict()
    assert server.status.level == OK and server.status.rooms_served == 1
    assert server.status.timings['location'] > 0


def test_requests_before_any_room_are_refused_with_a_reason(server):
    for kind in ('next_object', 'generate', 'reset'):
        ok, message = server.request(kind)
        assert not ok and 'no room yet' in message
    assert server.rec.served == []


def test_services_change_the_current_room(server):
    server.submit_layout(PARTIAL)
    first = server.rec.wait(1)
    kept = [o.id for o in parse_room_layout(PARTIAL).objects]
    assert [o.id for o in first.scene.objects][:2] == kept      # a partial room is completed

    ok, message = server.request('reset')
    assert ok and len(server.rec.wait(2).scene) == 0

    ok, message = server.request('next_object')
    assert ok
    obj = json.loads(message)
    third = server.rec.wait(3)
    assert [o.id for o in third.scene.objects] == [obj['id']] and third.source == 'next_object'

    ok, message = server.request('generate')
    assert ok
    summary = json.loads(message)
    fourth = server.rec.wait(4)
    assert summary['objects'] == len(fourth.scene) and summary['seed'] == fourth.seed
    assert fourth.seed == third.seed + 1 == first.seed + 2     # every furnishing a new seed


def test_bad_layouts_are_rejected_in_one_sentence_and_the_room_stays(server):
    server.submit_layout(LAYOUT)
    server.rec.wait(1)
    before = server.scene.to_dict()
    bad = {
        'not json': '{"room_type": "bedroom", ',
        'schema': json.dumps({'room_type': 'bedroom'}),
        'self-intersecting': json.dumps({'room_type': 'bedroom', 'floor': [[0, 0], [4, 4],
                                                                           [4, 0], [0, 4]]}),
        'NaN': LAYOUT.replace('4.2, 0.0', 'NaN, 0.0', 1),
        'too small': json.dumps({'room_type': 'bedroom', 'floor': [[0, 0], [0.5, 0],
                                                                   [0.5, 0.5], [0, 0.5]]}),
        'unknown room type': LAYOUT.replace('"bedroom"', '"garage"'),
        # 2 m² pass the schema, but two doors' clear zones cover the whole floor
        'no room for anything': json.dumps({
            'room_type': 'bathroom', 'floor': [[0, 0], [2.05, 0], [2.05, 1.0], [0, 1.0]],
            'doors': [{'position': [0.5, 0], 'width': 0.9, 'height': 2.0},
                      {'position': [1.55, 0], 'width': 0.9, 'height': 2.0}]}),
    }
    for n, (what, text) in enumerate(bad.items(), start=1):
        assert not server.submit_layout(text), what
        sentence = server.status.last_error
        assert server.status.level == WARN and server.status.inputs_rejected == n
        assert sentence.startswith('room_layout: ') and '\n' not in sentence, what
    assert 'not even the smallest, a trash can' in sentence
    assert not server.submit_polygon([(0, 0, 0), (1, 0, 0)])
    assert 'room_polygon' in server.status.last_error
    assert not server.submit_polygon([(0, 0, 0), (4, 0, 0), (4, 3, 0)], frame_id='odom')
    assert "'odom'" in server.status.last_error
    assert len(server.rec.served) == 1 and server.scene.to_dict() == before
    ok, _ = server.request('next_object')                    # and it keeps serving
    assert ok


def test_a_new_layout_supersedes_queued_and_running_ones(server):
    layouts = []
    for k in range(5):
        d = json.loads(LAYOUT)
        d['floor'] = [[x + k, y] for x, y in d['floor']]
        d['doors'][0]['position'][0] += k
        d['windows'][0]['position'][0] += k
        layouts.append(d)
    for d in layouts:
        assert server.submit_layout(d)
    last = parse_scene(json.dumps({'room': layouts[-1]})).room
    served = server.rec.wait(1)
    server.request('reset')           # queued after the layouts: once done, all were handled
    rooms = [s.scene.room for s in server.rec.served if s.source == 'room_layout']
    assert rooms[-1] == last
    assert len(rooms) < 5 and server.status.requests_superseded >= 5 - len(rooms)
    assert served.scene.room in [parse_scene(json.dumps({'room': d})).room for d in layouts]


def test_parameters_are_checked_and_applied(server):
    with pytest.raises(ConfigError, match='location_temperature must be between'):
        server.reconfigure({'location_temperature': -1.0})
    with pytest.raises(ConfigError, match='room_type'):
        server.reconfigure({'room_type': 'garage'})
    with pytest.raises(ConfigError, match='read-only'):
        server.reconfigure({'torch_threads': 2})
    with pytest.raises(ConfigError, match='marker_style must be one of cube, mesh'):
        server.reconfigure({'marker_style': 'sphere'})
    with pytest.raises(ConfigError, match='weights_dir'):
        server.reconfigure({'weights_dir': '/nonexistent/weights'})
    with pytest.raises(ConfigError, match='runtime must be one of auto, torch, onnxruntime'):
        server.reconfigure({'runtime': 'tpu'})
    assert server.config.location_temperature == 0.8          # all or none
    # Another runtime loads the networks again, as another device does.
    assert server._synth.runtime == 'onnxruntime'
    server.reconfigure({'runtime': 'torch'})
    assert server._synth.runtime == 'torch' and server.config.runtime == 'torch'
    server.reconfigure({'room_type': 'office', 'wall_height': 3.0, 'max_objects': 1,
                        'seed': 40, 'auto_generate': True})
    assert server.submit_polygon([(0, 0, 0), (4, 0, 0), (4, 3, 0), (0, 3, 0)], 'map')
    served = server.rec.wait(1)
    assert served.scene.room.room_type == 'office' and served.scene.room.wall_height == 3.0
    assert served.seed == 40 and len(served.scene) <= 1
    # The job's settings went with its calls: the shared synthesizer keeps its own.
    assert server._synth.config.max_objects == SynthConfig().max_objects


def test_rooms_are_furnished_for_the_robot_of_the_parameters(server):
    with pytest.raises(ConfigError, match='robot_radius must be between 0.05 and 0.5'):
        server.reconfigure({'robot_radius': 0.9})
    with pytest.raises(ConfigError, match='must be less than its reach'):
        server.reconfigure({'robot_clearance': 0.3, 'robot_reach': 0.2})
    server.reconfigure({'robot_radius': 0.3, 'robot_clearance': 0.05})
    server.submit_layout(LAYOUT)
    meta = parse_scene(server.rec.wait(1).json).meta['robot']
    assert (meta['radius'], meta['reach'], meta['clearance']) == (0.3, 0.15, 0.05)
    assert meta['promise_kept'] and meta['unreachable'] == []
    assert server.request('next_object')[0]
    assert parse_scene(server.rec.wait(2).json).meta['robot']['promise_kept']
    # A room given as it is (auto_generate off) whose objects break the promise is
    # published, with one sentence saying so.
    server.reconfigure({'auto_generate': False})
    sealed = json.loads(PARTIAL)
    sealed['objects'] = [
        {'id': 'wardrobe_0', 'category': 'wardrobe', 'model_id': 'wardrobe_04',
         'position': [1.0, 3.3, 0], 'yaw': -1.5708, 'size': [1.6, 0.6, 2.0]},
        {'id': 'bed_0', 'category': 'double bed', 'model_id': 'double_bed_06',
         'position': [1.0, 2.05, 0], 'yaw': -1.5708, 'size': [2.0, 1.6, 0.5]}]
    server.submit_layout(json.dumps(sealed))
    served = server.rec.wait(3)
    assert served.scene.meta['robot']['unreachable'] == ['wardrobe_0']
    assert server.status.level == WARN
    assert 'but a robot of radius 0.3 m keeping 0.05 m clear cannot reach wardrobe_0' in \
        server.status.message


def test_auto_generate_off_publishes_the_room_as_given(server):
    server.reconfigure({'auto_generate': False})
    server.submit_layout(PARTIAL)
    served = server.rec.wait(1)
    assert len(served.scene) == 2 and served.added == []


def test_export_dir_gets_json_sdf_and_gltf(server, tmp_path):
    server.reconfigure({'export_dir': str(tmp_path)})
    server.submit_layout(LAYOUT)
    served = server.rec.wait(1)
    server.request('reset')            # the export of room 1 is done before reset runs
    assert parse_scene((tmp_path / 'room_00001.json').read_text()).to_dict() == \
        served.scene.to_dict()
    assert (tmp_path / 'room_00001.sdf').stat().st_size > 0
    assert (tmp_path / 'room_00001.glb').read_bytes()[:4] == b'glTF'


def test_the_shipped_parameter_file_is_the_parameters_table_with_its_defaults():
    text = (config_dir() / 'scene_synth_node.yaml').read_text()
    assert text == parameters_file(), 'write it again: see server.parameters_file'
    values = yaml.safe_load(text)['/**']['ros__parameters']
    defaults = ServerConfig()
    assert values == {f.name: getattr(defaults, f.name) for f in fields(ServerConfig)}
    # The node's synthesis settings are SynthConfig's: description, range and default (the
    # device excepted: the node takes a GPU where there is one).
    synth = SynthConfig()
    for name, (s, default) in settings_of(SynthConfig).items():
        if s.node:
            assert PARAMETERS[name][:2] == (s.description, s.limits)
            assert values[name] == (default if name != 'device' else 'auto')
    for name, (s, default) in ROBOT_SETTINGS.items():
        assert PARAMETERS[name][:2] == (s.description, s.limits)
        assert values[name] == default == getattr(synth.robot, name.removeprefix('robot_'))


def test_check_rejects_what_the_descriptors_would():
    assert check('seed', 3.0) == 3 and check('room_type', 'living room') == 'living'
    for name, value in (('seed', -1), ('seed', 1.5), ('max_objects', 0), ('seed', True),
                        ('auto_generate', 1), ('frame_id', ''), ('frame_id', 'a b'),
                        ('device', 'tpu'), ('nonsense', 1), ('wall_height', float('nan'))):
        with pytest.raises(ConfigError):
            check(name, value)


def test_missing_and_corrupt_weights_fail_at_construction_naming_the_file(tmp_path):
    import shutil
    with pytest.raises(BundleError, match='no weights bundles'):
        SceneServer(ServerConfig(weights_dir=str(tmp_path)), lambda s: None)
    # A directory may hold only some room types (a data set's, or one retrained type): the
    # node serves those, and a room_type without weights is refused up front.
    shutil.copy(weights_dir() / 'bedroom.pt', tmp_path / 'bedroom.pt')
    srv = SceneServer(ServerConfig(weights_dir=str(tmp_path), auto_generate=False),
                      lambda s: None)
    try:
        with pytest.raises(ConfigError, match="room_type 'living' has no weights in .*; "
                           'they have bedroom'):
            srv.reconfigure({'room_type': 'living'})
    finally:
        srv.close()
    with pytest.raises(ConfigError, match="room_type 'office' has no weights"):
        SceneServer(ServerConfig(weights_dir=str(tmp_path), room_type='office'),
                    lambda s: None)
    for rt in ('living', 'office', 'bathroom'):
        shutil.copy(weights_dir() / f'{rt}.pt', tmp_path / f'{rt}.pt')
    data = (tmp_path / 'office.pt').read_bytes()
    (tmp_path / 'office.pt').write_bytes(data[:len(data) // 2])
    with pytest.raises(BundleError, match='office.pt'):
        SceneServer(ServerConfig(weights_dir=str(tmp_path)), lambda s: None)


def test_an_exception_in_the_publisher_is_reported_and_the_worker_survives():
    calls, rec = [], Recorder()

    def publish(served):
        calls.append(served)
        if len(calls) == 1:
            raise RuntimeError('publisher broke')

    srv = SceneServer(ServerConfig(torch_threads=1, auto_generate=False), publish, rec.status)
    try:
        srv.submit_layout(LAYOUT)
        ok, _ = srv.request('reset')
        errors = [s for s in rec.statuses if s.level == ERROR]
        assert errors and errors[0].last_error == 'internal error in layout: publisher broke'
        assert ok and srv.status.level == OK          # the next room went out fine
        assert len(calls) == 2
    finally:
        srv.close()


def _hold_worker(srv):
    """Make the worker wait inside the publisher until the returned event is set."""
    entered, release = threading.Event(), threading.Event()
    publish = srv._publish

    def slow(served):
        entered.set()
        release.wait(30)
        publish(served)
    srv._publish = slow
    return entered, release


def _two_calls_waiting(srv):
    """A room served, then two ``next_object`` calls waiting behind a worker held in its
    publisher: (their answers as they come, the calling threads, the event releasing it)."""
    assert srv.submit_layout(LAYOUT)
    srv.rec.wait(1)
    entered, release = _hold_worker(srv)
    answers = []
    callers = [threading.Thread(target=lambda: answers.append(srv.request('next_object')))
               for _ in range(2)]
    for t in callers:
        t.start()
    assert entered.wait(30)
    return answers, callers, release


def test_calls_past_max_pending_are_answered_busy_at_once(server):
    server.reconfigure({'max_pending': 2})
    answers, callers, release = _two_calls_waiting(server)
    ok, message = server.request('generate')            # two are waiting: this one is not
    assert not ok and message.startswith('busy: 2 requests are already waiting')
    assert server.status.requests_busy == 1
    release.set()
    for t in callers:
        t.join(30)
    assert len(answers) == 2 and all(ok or 'nothing more fits' in m for ok, m in answers)
    ok, _ = server.request('reset')                      # and then it takes calls again
    assert ok


def test_close_answers_every_waiting_call_at_once(server):
    answers, callers, release = _two_calls_waiting(server)
    closer = threading.Thread(target=server.close, kwargs={'timeout': 0.5})
    closer.start()
    closer.join(5)
    release.set()
    for t in callers:
        t.join(5)
    assert not any(t.is_alive() for t in callers)
    assert any(m == 'the node is shutting down' for _, m in answers), answers
    assert server.request('reset') == (False, 'the node is shutting down')


class Calls:
    """Service calls made from threads. The order the worker served them in is the order of
    ``Recorder.served``: a calling thread may wake up later than the next call's."""

    def __init__(self, srv):
        self.srv = srv
        self.answers = []           # (label, success, message)
        self.threads = []

    def start(self, label, kind):
        def call():
            ok, message = self.srv.request(kind)
            self.answers.append((label, ok, message))
        t = threading.Thread(target=call)
        self.threads.append(t)
        t.start()

    def queued(self, n):
        """Wait until ``n`` jobs are queued for the worker."""
        deadline = time.monotonic() + 30
        while len(self.srv._jobs) < n:
            assert time.monotonic() < deadline, f'{len(self.srv._jobs)} queued, not {n}'
            time.sleep(0.005)

    def join(self):
        """Wait for every call; their answers by label."""
        for t in self.threads:
            t.join(60)
        assert not any(t.is_alive() for t in self.threads)
        return {label: (ok, message) for label, ok, message in self.answers}


def _held_after_one_room(srv):
    """A room served, then the worker held in the publisher of a ``next_object``:
    (the calls, the event releasing the worker)."""
    assert srv.submit_layout(LAYOUT)
    srv.rec.wait(1)
    entered, release = _hold_worker(srv)
    calls = Calls(srv)
    calls.start('held', 'next_object')
    assert entered.wait(30)
    return calls, release


def test_short_calls_overtake_queued_generates_in_arrival_order(server):
    calls, release = _held_after_one_room(server)
    for label, kind in (('generate 1', 'generate'), ('generate 2', 'generate'),
                        ('reset', 'reset'), ('next_object', 'next_object')):
        calls.start(label, kind)
        calls.queued(len(calls.threads) - 1)
    release.set()
    answers = calls.join()
    assert all(ok for ok, _ in answers.values()), answers
    assert [s.source for s in server.rec.served[1:]] == [
        'next_object', 'reset', 'next_object', 'generate', 'generate']
    first, second = (json.loads(answers[f'generate {k}'][1])['seed'] for k in (1, 2))
    assert first < second


def test_a_generate_that_waited_long_is_no_longer_overtaken(server, monkeypatch):
    monkeypatch.setattr(server_module, 'PROMOTE_AFTER', 0.0)     # every one waited long
    calls, release = _held_after_one_room(server)
    for label, kind in (('generate 1', 'generate'), ('generate 2', 'generate'),
                        ('reset', 'reset')):
        calls.start(label, kind)
        calls.queued(len(calls.threads) - 1)
    release.set()
    assert all(ok for ok, _ in calls.join().values())
    # The reset came after both generates: it waits for the first (not even served between
    # its insertions, since the second is ahead of it) and then overtakes only the running
    # one, between two of its insertions.
    assert [s.source for s in server.rec.served[1:]] == [
        'next_object', 'generate', 'reset', 'generate']


def test_short_calls_are_served_between_insertions_of_a_running_generate(server):
    server.submit_layout(LAYOUT)
    server.rec.wait(1)
    server.reconfigure({'seed': 40})
    # Hold the generate before its second insertion while calls arrive.
    complete, entered, release = server._synth.complete, threading.Event(), threading.Event()

    def held_complete(scene, seed, cancel=None, config=None):
        asked = []

        def held_cancel():
            asked.append(1)
            if len(asked) == 2:
                entered.set()
                release.wait(30)
            return cancel()
        return complete(scene, seed, held_cancel, config)
    server._synth.complete = held_complete
    calls = Calls(server)
    calls.start('generate', 'generate')
    assert entered.wait(30)
    calls.start('reset', 'reset')
    calls.start('next_object', 'next_object')
    calls.queued(2)
    release.set()
    assert all(ok for ok, _ in calls.join().values())
    assert [s.source for s in server.rec.served[1:]] == ['reset', 'next_object', 'generate']
    generated = server.rec.served[-1]
    assert generated.seed == 40 and server.scene.to_dict() == generated.scene.to_dict()
    # The calls served meanwhile took seeds of their own and left the room it furnishes alone:
    # the same seed again, with nothing in between, gives the same room.
    server._synth.complete = complete
    server.reconfigure({'seed': 40})
    assert server.request('generate')[0]
    assert server.rec.wait(5).scene.objects == generated.scene.objects


def test_busy_counts_only_the_calls_served_before_it(server):
    server.reconfigure({'max_pending': 2})
    calls, release = _held_after_one_room(server)
    calls.start('generate', 'generate')
    calls.queued(1)
    ok, message = server.request('generate')        # two calls ahead: busy
    assert not ok and message.startswith('busy: 2 requests are already waiting')
    calls.start('reset', 'reset')                    # one ahead (held): it waits
    calls.queued(2)
    ok, message = server.request('next_object')      # two ahead: busy
    assert not ok and message.startswith('busy: 2 requests')
    assert server.status.requests_busy == 2
    release.set()
    assert set(calls.join()) == {'held', 'generate', 'reset'}
    assert [s.source for s in server.rec.served[1:]] == ['next_object', 'reset', 'generate']


def test_a_layout_answers_the_calls_queued_before_it_at_once(server):
    calls, release = _held_after_one_room(server)
    calls.start('generate', 'generate')
    calls.queued(1)
    assert server.submit_layout(LAYOUT)
    calls.threads[1].join(30)           # answered while the worker is still held
    assert calls.answers == [('generate', False, 'superseded by a newer room layout')]
    release.set()
    calls.join()
    assert server.rec.wait(3).source == 'room_layout'


def test_a_failing_logger_does_not_stop_the_worker():
    def log(level, text):
        raise RuntimeError('the logging context is gone')

    rec = Recorder()
    srv = SceneServer(ServerConfig(torch_threads=1, auto_generate=False), rec.publish,
                      rec.status, log)
    try:
        assert not srv.submit_layout('{"room_type": "garage"')        # logged: raises
        assert srv.submit_layout(LAYOUT)
        assert srv.request('reset')[0]
        assert srv.status.inputs_rejected == 1
    finally:
        srv.close()


def test_requests_with_arguments_come_from_parameters(server):
    seeds = server.rec.seeds
    layout = json.loads(LAYOUT)
    layout['request_id'] = 'mine-1'
    assert server.submit_layout(json.dumps(layout))
    first = server.rec.wait(1)
    assert first.scene.meta['request_id'] == 'mine-1'        # the answer to that layout
    assert seeds == [1] and server.next_seed == 1

    # next_category: every ~/next_object inserts that category, until it is cleared.
    server.reconfigure({'next_category': 'Floor_Lamp'})        # as typed: floor lamp
    for k in (2, 3):
        ok, message = server.request('next_object')
        assert ok, message
        assert json.loads(message)['category'] == 'floor lamp'
        later = server.rec.wait(k)
        assert 'request_id' not in later.scene.meta               # a later room: not its answer
    server.reconfigure({'next_category': 'toilet'})             # a category, not a bedroom's
    ok, message = server.request('next_object')
    assert not ok and "'toilet' is not a category of bedroom rooms" in message
    with pytest.raises(ConfigError, match='not a category'):
        server.reconfigure({'next_category': 'spaceship'})

    # suggest: k proposals, the room unchanged, a seed taken.
    server.reconfigure({'next_category': '', 'suggestions': 3})
    before = server.scene
    ok, message = server.request('suggest')
    answer = json.loads(message)
    assert ok and len(answer['objects']) == 3
    assert server.scene.to_dict() == before.to_dict()
    assert len(server.rec.served) == 3                         # nothing published
    # The seed of a request is the one the parameter showed before it.
    server.reconfigure({'seed': 40})
    ok, message = server.request('generate')
    assert ok and json.loads(message)['seed'] == 40 and seeds[-1] == 41


def test_status_and_sources_name_the_topic_and_read_as_english(server):
    office = json.dumps({'room_type': 'office', 'floor': [[0, 0], [4, 0], [4, 3.5], [0, 3.5]]})
    assert server.submit_layout(office, 'room_polygon')
    served = server.rec.wait(1)
    assert served.source == 'room_polygon'
    assert server.status.message.endswith('objects in an office')


# ---- catalog_dir: the user's own furniture ---------------------------------------------------
@pytest.fixture
def furniture(tmp_path):
    """(folder, catalog file) of the user catalog tests' bed, stand, wardrobe and desk."""
    from test_user_catalog import make_real_set
    return make_real_set(tmp_path / 'furniture')


def _user_server(rec, **config):
    return SceneServer(ServerConfig(torch_threads=1, **config), rec.publish, rec.status,
                       rec.log, rec.seed)


def test_catalog_dir_furnishes_publishes_and_exports_the_users_models(furniture, tmp_path):
    import trimesh

    from scene_synth_ros.schema import SceneValidationError
    root, path = furniture
    rec = Recorder()
    srv = _user_server(rec, catalog_dir=str(root), export_dir=str(tmp_path / 'export'),
                       export_formats='gltf')
    try:
        models = load_catalog(path)
        covered = set(models.user_categories)
        assert srv.submit_layout(LAYOUT)
        served = rec.wait(1)
        assert served.catalog is models
        own = [o for o in served.scene.objects if o.category in covered]
        assert own and all(o.model_id in models.user for o in own)
        assert all(o.model_id not in models.user for o in served.scene.objects
                   if o.category not in covered)
        # The published JSON reads with the catalog (and only with it).
        assert parse_scene(served.json, models).to_dict() == served.scene.to_dict()
        with pytest.raises(SceneValidationError, match='is not a catalog model id'):
            parse_scene(served.json)
        srv.reconfigure({'next_category': 'stand'})
        assert srv.request('reset')[0]                  # after room 1's export
        ok, message = srv.request('next_object')
        assert ok and json.loads(message)['model_id'] == 'night_left', message
        glb = trimesh.load(tmp_path / 'export' / 'room_00001.glb')
        for o in own:                                   # the user's meshes, not sketches
            assert any(g.startswith(o.model_id) for g in glb.geometry), o.model_id
        # A partial room that names the user's models is read with the catalog.
        srv.reconfigure({'auto_generate': False})
        partial = json.loads(PARTIAL)
        partial['objects'][0]['model_id'] = 'oak_bed'
        assert srv.submit_layout(json.dumps(partial))
        assert rec.wait(4).scene.objects[0].model_id == 'oak_bed'
    finally:
        srv.close()


def test_a_bad_catalog_dir_is_refused_in_one_sentence_and_the_old_one_kept(furniture,
                                                                            tmp_path):
    from scene_synth_ros import catalog
    from scene_synth_ros.errors import MAX_SENTENCE
    root, path = furniture
    empty = tmp_path / 'empty'
    empty.mkdir()
    broken = tmp_path / 'broken'
    broken.mkdir()
    (broken / 'catalog.json').write_text('{"format": "something else"}')
    bad = {str(tmp_path / 'nowhere'): 'does not exist',
           str(empty): 'holds no catalog.json',
           str(broken): 'cannot be used: .* is not a catalog written by'}
    for value, says in bad.items():
        with pytest.raises(ConfigError, match=f'catalog_dir .*{says}') as e:
            SceneServer(ServerConfig(catalog_dir=value), lambda s: None)
        assert '\n' not in str(e.value) and len(str(e.value)) <= MAX_SENTENCE
    rec = Recorder()
    srv = _user_server(rec, catalog_dir=str(path), next_category='stand',   # the file too
                       auto_generate=False)
    try:
        srv.submit_layout(PARTIAL)                      # a bed and a stand, as given
        rec.wait(1)
        for value, says in bad.items():
            with pytest.raises(ConfigError, match=says):
                srv.reconfigure({'catalog_dir': value, 'max_objects': 5})
        assert srv.config.catalog_dir == str(path) and srv.config.max_objects == 30
        ok, message = srv.request('next_object')        # still the user's stands
        assert ok and json.loads(message)['model_id'] == 'night_left'
        # Back to the procedural catalog: the room keeps its objects, their user models
        # replaced by the nearest procedural ones, so its JSON reads without a catalog.
        assert rec.wait(2).scene.objects[-1].model_id == 'night_left'
        srv.reconfigure({'catalog_dir': '', 'next_category': 'wardrobe'})
        ok, message = srv.request('next_object')
        assert ok and json.loads(message)['model_id'].startswith('wardrobe_'), message
        scene = parse_scene(rec.wait(3).json)
        assert [o.id for o in scene.objects][:-1] == [o.id for o in rec.served[1].scene.objects]
        assert scene.objects[2].model_id == catalog.nearest('stand', *scene.objects[2].size[:2]
                                                            ).model_id
    finally:
        srv.close()
