"""scene_synth_node in a child process, talked to over Fast DDS on loopback with real rclpy.

Every node gets a ROS domain of its own, so tests (and test runs) do not hear each other.
"""
from __future__ import annotations

from dataclasses import fields
import json
import math
import os
from pathlib import Path
import shutil
import signal
import subprocess
import sys
import time
from xml.etree import ElementTree as ET

from action_msgs.msg import GoalStatus
from conftest import ros_domains
import pytest
from scene_synth_msgs.action import Furnish
from scene_synth_msgs.msg import Robot
import yaml

os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'   # before any rclpy.init

from scene_synth_ros.errors import MAX_SENTENCE  # noqa: E402
from scene_synth_ros.paths import config_dir, examples_dir, meshes_dir, weights_dir  # noqa: E402
from scene_synth_ros.ros_client import (  # noqa: E402
    ClientError,
    SceneSynthClient,
    node_command,
    node_env,
    quaternion_yaw,
    start_node,
    stop_node,
)
from scene_synth_ros.ros_messages import room_msg  # noqa: E402
from scene_synth_ros.schema import parse_room_layout, parse_scene  # noqa: E402

pytestmark = pytest.mark.slow     # every test here starts node processes
from scene_synth_ros.server import PARAMETERS, ServerConfig  # noqa: E402
from scene_synth_ros.user_catalog import load_catalog  # noqa: E402

LAYOUT = (examples_dir() / 'bedroom_layout.json').read_text()
L_LAYOUT = (examples_dir() / 'lshaped_living_layout.json').read_text()
# Domains 1..232 are valid for Fast DDS; a random start keeps two concurrent runs apart.
_DOMAINS = ros_domains(1, 100)
MARKER_CUBE, MARKER_MESH = 1, 10


def _domain() -> int:
    return next(_DOMAINS)


class RunningNode:
    def __init__(self, tmp: Path, params=None, params_file=None, namespace=''):
        self.domain = _domain()
        self.log_path = tmp / f'node_{self.domain}.log'
        self._log = open(self.log_path, 'w')
        self.proc = start_node(self.domain, params, self._log, params_file, namespace)
        self.client = SceneSynthClient(f'{namespace}/scene_synth_node', domain_id=self.domain)
        try:
            self.client.spin_until(lambda: self.proc.poll() is not None or self.client.ready(),
                                   90.0, 'services')
        except Exception:
            self.stop()
            raise
        assert self.proc.poll() is None, self.log()

    def log(self) -> str:
        if not self._log.closed:
            self._log.flush()
        return self.log_path.read_text()

    def stop(self, sig=signal.SIGINT) -> int:
        code = stop_node(self.proc, sig)
        self.client.close()
        self._log.close()
        return code


@pytest.fixture(scope='module')
def node(tmp_path_factory):
    n = RunningNode(tmp_path_factory.mktemp('node'),
                    {'torch_threads': 1})
    yield n
    code = n.stop()
    assert code == 0, n.log()
    assert 'Traceback' not in n.log()


def _furnish(node, layout=LAYOUT) -> dict:
    return node.client.publish_layout(layout, timeout=60.0)


def _objects_agree(scene_d, markers, poses, frame='map'):
    scene = parse_scene(scene_d)                         # valid against msg_schemas/
    assert markers.markers[0].action == markers.markers[0].DELETEALL
    objs = [m for m in markers.markers[1:]
            if m.ns not in ('floor', 'walls', 'doors', 'windows', 'labels')]
    assert [m.ns for m in objs] == [o.category for o in scene.objects]
    labels = [m for m in markers.markers if m.ns == 'labels']
    assert [m.text for m in labels] == [o.id for o in scene.objects]
    room_ns = {'floor', 'walls'} | ({'doors'} if scene.room.doors else set()) | (
        {'windows'} if scene.room.windows else set())
    assert {m.ns for m in markers.markers[1:]} >= room_ns
    assert len(poses.poses) == len(scene)
    assert poses.header.frame_id == frame
    assert all(m.header.frame_id == frame for m in markers.markers)
    for o, m, p in zip(scene.objects, objs, poses.poses, strict=True):
        assert (p.position.x, p.position.y, p.position.z) == pytest.approx(o.position)
        assert math.cos(quaternion_yaw(p.orientation) - o.yaw) == pytest.approx(1.0)
        assert m.pose.position.x == pytest.approx(o.position[0])
        assert m.pose.position.y == pytest.approx(o.position[1])
        if m.type == MARKER_CUBE:
            assert (m.scale.x, m.scale.y, m.scale.z) == pytest.approx(
                (o.depth, o.width, o.height))
            assert m.pose.position.z == pytest.approx(o.position[2] + o.height / 2)
    return scene


def test_a_layout_gives_markers_poses_and_scene_that_agree(node):
    before = node.client.counts()
    node.client.publish_layout(LAYOUT, wait=False)
    d, markers, poses = node.client.wait_room(before)
    scene = _objects_agree(d, markers, poses)
    assert scene.room == parse_room_layout(LAYOUT).room
    assert isinstance(scene.meta['seed'], int) and len(scene) > 0
    diag = node.client.spin_until(
        lambda: (d := node.client.diagnostics()) and int(d['rooms served']) >= 1 and d, 5.0,
        'diagnostics of the room')
    assert diag['level'] == '0' and float(diag['location ms']) > 0


def test_a_late_subscriber_receives_the_last_room(node):
    d = _furnish(node, L_LAYOUT)
    with SceneSynthClient(domain_id=node.domain) as late:
        scene = json.loads(late.latest('scene', timeout=10.0).data)
        markers = late.latest('markers', timeout=10.0)
        poses = late.latest('poses', timeout=10.0)
    assert scene == d
    _objects_agree(scene, markers, poses)


def test_every_room_comes_with_its_occupancy_map_and_the_map_parameters_shape_it(node):
    import numpy as np

    from scene_synth_ros.occupancy import FREE, OCCUPIED, occupancy_grid
    from scene_synth_ros.synth_config import MapConfig
    d = _furnish(node)
    with SceneSynthClient(domain_id=node.domain) as late:      # latched, as map_server's
        grid = late.latest('map', timeout=10.0)
    scene = parse_scene(d)
    want = occupancy_grid(scene, config=MapConfig())
    assert grid.header.frame_id == 'map'
    assert (grid.info.width, grid.info.height) == (want.width, want.height)
    assert grid.info.resolution == pytest.approx(0.05)
    assert (grid.info.origin.position.x, grid.info.origin.position.y) == \
        pytest.approx(want.origin)
    data = np.frombuffer(bytes(grid.data), dtype=np.int8).reshape(want.data.shape)
    assert (data == want.data).all()
    assert (data == OCCUPIED).any() and (data == FREE).any()
    try:
        assert node.client.set_parameters({'map_resolution': 0.1, 'map_scan_height': 1.5}) \
            == []
        before = node.client.count('map')
        d = _furnish(node)
        node.client.spin_until(lambda: node.client.count('map') > before, 10.0, 'map')
        grid = node.client.latest('map')
        coarse = occupancy_grid(parse_scene(d), config=MapConfig(0.1, 1.5))
        assert grid.info.resolution == pytest.approx(0.1)
        assert (grid.info.width, grid.info.height) == (coarse.width, coarse.height)
        assert bytes(grid.data) == coarse.data.tobytes()
    finally:
        node.client.set_parameters({'map_resolution': 0.05, 'map_scan_height': 0.3})


def test_services_reset_next_object_and_generate(node):
    first = _furnish(node)
    client = node.client
    n = client.count('scene')
    ok, message = client.call('reset')
    assert ok and json.loads(message) == {'objects': 0}
    assert client.wait_scene(n)['objects'] == []

    n = client.count('scene')
    t0 = time.perf_counter()
    ok, message = client.call('next_object')
    assert ok, message
    obj = json.loads(message)
    scene = client.wait_scene(n)
    assert [o['id'] for o in scene['objects']] == [obj['id']]
    assert scene['objects'][0] == obj
    assert time.perf_counter() - t0 < 30

    before = client.counts()
    ok, message = client.call('generate')
    assert ok, message
    summary = json.loads(message)
    scene, markers, poses = client.wait_room(before)
    assert len(scene['objects']) == summary['objects']
    assert summary['seed'] == scene['meta']['seed'] != first['meta']['seed']
    _objects_agree(scene, markers, poses)


def test_a_reset_sent_behind_two_generates_is_answered_before_them(node):
    _furnish(node)
    client = node.client
    sent = {'generate 1': client.call_async('generate'),
            'generate 2': client.call_async('generate'),
            'reset': client.call_async('reset')}
    answered = []

    def all_answered():
        answered.extend(k for k, f in sent.items() if f.done() and k not in answered)
        return len(answered) == len(sent)
    client.spin_until(all_answered, 60.0, 'answers')
    assert all(f.result().success for f in sent.values()), [f.result() for f in sent.values()]
    # The second generate waits for the first, the reset for one insertion at most.
    assert answered.index('reset') < answered.index('generate 2'), answered


BAD_LAYOUTS = {
    'does not parse': ('{"room_type": "bedroom", "floor": [[0, 0]', 'JSON'),
    'breaks the schema': (json.dumps({'room_type': 'bedroom', 'wall_height': 2.5}), 'floor'),
    'self-intersecting': (json.dumps({'room_type': 'bedroom', 'floor': [[0, 0], [4, 4], [4, 0],
                                                                        [0, 4]]}),
                          'self-intersecting'),
    'NaN': (LAYOUT.replace('"wall_height": 2.6', '"wall_height": NaN'), 'wall_height'),
    'too small': (json.dumps({'room_type': 'bathroom', 'floor': [[0, 0], [0.6, 0], [0.6, 0.6],
                                                                 [0, 0.6]]}), 'm²'),
    'unknown room type': (LAYOUT.replace('"bedroom"', '"garage"'), 'garage'),
    # Each of these killed the node once (issue 12).
    'has a key that is a lone surrogate': ('{"\\ud800": 1, ' + LAYOUT.lstrip()[1:],
                                          'not a known field'),
    'has an integer of 4,301 digits': (LAYOUT.replace('"wall_height": 2.6',
                                                      '"wall_height": 1' + '0' * 4301),
                                       'at most 1000 are read'),
    'is nested 975 deep': ('{"room_type": "bedroom", "floor": ' + '[' * 975 + ']' * 975 + '}',
                           'nested'),
    'has a huge coordinate': (json.dumps({'room_type': 'bedroom',
                                          'floor': [[1e308, 0], [4, 0], [4, 4], [0, 4]]}),
                              'at most 100000 m'),
    'is 2 MB long': (json.dumps({'room_type': 'x' * 2_000_000, 'floor': [[0, 0], [1, 0]]}),
                     'bytes'),
}


def test_bad_input_is_rejected_in_one_sentence_and_the_node_keeps_serving(node):
    before = _furnish(node)
    client = node.client
    rejected = int(client.diagnostics()['inputs rejected'])
    scenes = client.count('scene')
    bad = [(what, lambda t=text: client.publish_layout(t, wait=False, check=False), needle)
           for what, (text, needle) in BAD_LAYOUTS.items()]
    bad += [('degenerate polygon', lambda: client.publish_polygon([(0, 0), (3, 0)]),
             'at least 3'),
            ('polygon with NaN', lambda: client.publish_polygon([(0, 0), (3, 0), (3, math.nan)]),
             'finite'),
            ('polygon in another frame',
             lambda: client.publish_polygon([(0, 0), (3, 0), (3, 3)], 'odom'), 'odom')]
    for what, send, needle in bad:
        send()
        rejected += 1
        diag = client.spin_until(
            lambda n=rejected: (d := client.diagnostics()) and int(d['inputs rejected']) >= n and d,
            15.0, f'rejection of the layout that {what}')
        assert diag['level'] == '1', what
        assert needle in diag['last error'] and '\n' not in diag['last error'], \
            (what, diag['last error'])
        assert len(diag['last error']) <= MAX_SENTENCE, what
        assert diag['message'].startswith('input rejected: '), what
    time.sleep(0.3)
    assert client.count('scene') == scenes                    # nothing was published for them
    assert json.loads(client.latest('scene').data) == before  # the previous room stays
    assert node.proc.poll() is None
    ok, message = client.call('next_object')
    assert ok or 'nothing more fits' in message
    assert node.log().count('[WARN]') >= len(bad)


def test_a_nearly_closed_outline_is_furnished_and_the_node_keeps_answering(node):
    # Its last vertex 0.5 mm from the first once reached the markers as a sliver wall, which
    # GEOS could not triangulate; the node then stopped answering.
    layout = json.loads(LAYOUT)
    x, y = layout['floor'][0]
    layout['floor'].append([x + 0.0005, y])
    scene = _furnish(node, json.dumps(layout))
    assert len(scene['room']['floor']) == len(layout['floor']) - 1
    ok, message = node.client.call('next_object')
    assert ok or 'nothing more fits' in message
    assert node.client.diagnostics()['level'] == '0'


def test_parameters_change_at_run_time_and_bad_values_are_refused(node, tmp_path):
    client = node.client
    refused = client.set_parameters({'location_temperature': -1.0})
    assert refused and 'location_temperature' in refused[0]
    refused = client.set_parameters({'room_type': 'garage'})
    assert refused and 'garage' in refused[0]
    refused = client.set_parameters({'torch_threads': 2})
    assert refused
    refused = client.set_parameters({'weights_dir': str(tmp_path)})
    assert refused and 'no weights bundles' in refused[0]
    assert client.get_parameters(['location_temperature', 'room_type']) == {
        'location_temperature': 0.8, 'room_type': 'bedroom'}

    assert client.set_parameters({'marker_style': 'mesh', 'frame_id': 'odom',
                                  'room_type': 'office', 'wall_height': 3.1,
                                  'export_dir': str(tmp_path / 'export')}) == []
    try:
        before = client.counts()
        client.publish_polygon([(0, 0), (4, 0), (4, 3.5), (0, 3.5)], 'odom')
        d, markers, poses = client.wait_room(before)
        scene = _objects_agree(d, markers, poses, frame='odom')
        assert scene.room.room_type == 'office' and scene.room.wall_height == 3.1
        assert scene.room.doors == () and scene.room.windows == ()
        meshes = [m for m in markers.markers if m.type == MARKER_MESH]
        assert len(meshes) == len(scene) > 0
        prefix = 'package://scene_synth_ros/meshes/'      # resolves wherever it is installed
        assert all(m.mesh_resource.startswith(prefix)
                   and (meshes_dir() / m.mesh_resource[len(prefix):]).is_file() for m in meshes)
        client.call('reset')            # queued behind the export of the office
        sdf = sorted((tmp_path / 'export').glob('room_*.sdf'))[0]
        world = ET.parse(sdf).getroot().find('world')
        ids = {o.id for o in scene.objects}
        assert {m.get('name') for m in world.findall('model')} >= ids
    finally:
        assert client.set_parameters({'marker_style': 'cube', 'frame_id': 'map',
                                      'room_type': 'bedroom', 'wall_height': 2.6,
                                      'export_dir': ''}) == []


def test_catalog_dir_shows_the_users_furniture_as_its_own_meshes(node, tmp_path):
    from test_user_catalog import make_real_set

    from scene_synth_ros.markers import category_color
    root, path = make_real_set(tmp_path)
    client = node.client
    refused = client.set_parameters({'catalog_dir': str(tmp_path / 'nowhere')})
    assert refused and 'does not exist' in refused[0]
    assert client.set_parameters({'catalog_dir': str(root), 'marker_style': 'mesh'}) == []
    try:
        models = load_catalog(path)
        for _ in range(4):          # a bedroom without a bed, stand, wardrobe or desk: again
            before = client.counts()
            client.publish_layout(LAYOUT, wait=False)
            d, markers, _ = client.wait_room(before)
            scene = parse_scene(d, models)                  # the scene reads with the catalog
            objs = [m for m in markers.markers[1:]
                    if m.ns not in ('floor', 'walls', 'doors', 'windows', 'labels')]
            pairs = list(zip(scene.objects, objs, strict=True))
            if any(o.model_id in models.user for o in scene.objects):
                break
        for o, m in pairs:
            assert m.type == MARKER_MESH
            user = models.user_model(o.model_id)
            if user is None:
                assert m.mesh_resource.startswith('package://') and m.mesh_use_embedded_materials
                continue
            # The user's own mesh, painted in its category's colour (STL has no materials).
            assert m.mesh_resource == 'file://' + user.marker and Path(user.marker).is_file()
            assert not m.mesh_use_embedded_materials
            assert (m.color.r, m.color.g, m.color.b, m.color.a) == pytest.approx(
                category_color(o.category))
        assert any(models.user_model(o.model_id) for o, _ in pairs)
    finally:
        assert client.set_parameters({'catalog_dir': '', 'marker_style': 'cube'}) == []


def test_a_new_layout_supersedes_the_one_being_furnished(node):
    client = node.client
    superseded = int(client.diagnostics()['requests superseded'])
    layouts = []
    for k in range(4):
        d = json.loads(LAYOUT)
        d['floor'] = [[x + k, y] for x, y in d['floor']]
        for op in d['doors'] + d['windows']:
            op['position'][0] += k
        layouts.append(json.dumps(d))
    n = client.count('scene')
    layouts[-1] = json.dumps(dict(json.loads(layouts[-1]), request_id='the-last'))
    for text in layouts:
        client.publish_layout(text, wait=False)
    last = client.wait_scene(n, request_id='the-last')
    assert parse_scene(last).room == parse_room_layout(layouts[-1]).room
    assert len(last['objects']) > 0
    ok, _ = client.call('reset')
    published = client.count('scene') - n
    assert published < len(layouts) + 1
    diag = client.diagnostics()
    assert int(diag['requests superseded']) >= superseded + len(layouts) + 1 - published


def test_a_layout_is_taken_once_and_an_overtaken_older_one_not_at_all():
    from scene_synth_ros.node import LayoutOrder
    order = LayoutOrder(window=2.0)
    assert order.admit(100, 1, now=10.0)
    assert not order.admit(100, 1, now=10.1)         # its copy on the other subscription
    assert order.admit(300, 3, now=10.2)             # the newer one, first on the latched one
    assert not order.admit(200, 2, now=10.3)         # the older one, overtaken: dropped
    assert not order.admit(300, 3, now=10.4)
    # Beyond the window an earlier stamp is another publisher's clock, not an old layout.
    assert order.admit(250, 1, now=12.5)
    assert order.admit(None, None, now=12.6) and order.admit(None, 7, now=12.6)


def test_layouts_a_transient_local_publisher_sends_in_a_row_end_with_the_newest(node):
    # A simulator that latches its layouts reaches both of the node's subscriptions: each
    # layout is furnished once at most, and the room served last is the newest (the order
    # that the two subscriptions deliver in is the middleware's: LayoutOrder, above, is
    # what drops an older layout overtaken on the other one).
    from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
    from std_msgs.msg import String
    client = node.client
    latched = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                         durability=DurabilityPolicy.TRANSIENT_LOCAL)
    pub = client.node.create_publisher(String, f'{client.target}/room_layout', latched)
    try:
        client.spin_until(lambda: pub.get_subscription_count() >= 2, 10.0, 'both subscriptions')
        n = client.count('scene')
        for k in range(6):
            d = json.loads(LAYOUT)
            d['floor'] = [[x + k, y] for x, y in d['floor']]
            for op in d['doors'] + d['windows']:
                op['position'][0] += k
            d['request_id'] = f'latched-{k}'
            pub.publish(String(data=json.dumps(d)))
        client.wait_scene(n, request_id='latched-5')
        until = time.monotonic() + 2.0
        client.spin_until(lambda: time.monotonic() > until, 3.0, 'two seconds')
        assert json.loads(client.latest('scene').data)['meta']['request_id'] == 'latched-5'
        served = [json.loads(m.data)['meta'].get('request_id')
                  for seq, _, m in client.received['scene'] if seq > n]
        assert served.count('latched-5') == 1       # each layout once, the newest last
    finally:
        client.node.destroy_publisher(pub)
        client.call('reset')


def test_parameters_rclpy_owns_pass_through_and_a_dump_loads_back(node):
    client = node.client
    assert client.set_parameters({'use_sim_time': True}) == []
    assert client.get_parameters(['use_sim_time']) == {'use_sim_time': True}
    assert client.set_parameters({'use_sim_time': False}) == []
    # `ros2 param dump` then `ros2 param load`: every writable parameter set back at once.
    names = ['use_sim_time', *(n for n, (_, _, ro) in PARAMETERS.items() if not ro)]
    dump = client.get_parameters(names)
    assert client.set_parameters(dump) == []
    assert client.get_parameters(names) == dump
    # A whole number for a double is taken as the double it means, which the parameter
    # stays (`ros2 param set ... location_temperature 1`); a text is refused by its type.
    assert client.set_parameters({'location_temperature': 1}) == []
    value = client.get_parameters(['location_temperature'])['location_temperature']
    assert value == 1.0 and isinstance(value, float)
    refused = client.set_parameters({'location_temperature': 'warm'})
    assert refused and 'expected' in refused[0] and 'DOUBLE' in refused[0]
    assert client.set_parameters({'location_temperature': 0.8}) == []


def test_the_seed_parameter_shows_the_next_seed_and_requests_take_arguments(node):
    client = node.client
    seed = client.get_parameters(['seed'])['seed']
    first = _furnish(node)
    second = _furnish(node)        # the same outline again: each call gets its own room
    assert (first['meta']['seed'], second['meta']['seed']) == (seed, seed + 1)
    assert first['meta']['request_id'] != second['meta']['request_id']
    assert client.get_parameters(['seed'])['seed'] == seed + 2

    summary = client.generate(seed=1234)
    assert summary['seed'] == 1234 and client.get_parameters(['seed'])['seed'] == 1235
    client.reset()
    n = client.count('scene')
    chair = client.next_object(category='office_chair')
    assert chair['category'] == 'office chair'
    (served,) = client.wait_scene(n)['objects']
    assert served['id'] == chair['id'] and served['position'] == pytest.approx(chair['position'])
    assert client.next_object()['id'] != chair['id']          # the model chooses again
    # The typed requests carry their arguments: nothing was set on the node.
    assert client.get_parameters(['next_category'])['next_category'] == ''
    with pytest.raises(ClientError, match='toilet.* is not a category of bedroom'):
        client.next_object(category='toilet')
    n = client.count('scene')
    # Up to k distinct proposals (the node's default k is 5): k reaches the node.
    proposals = client.suggest(k=3)
    assert 0 < len(proposals) <= 3 and all(parse_room_layout(
        dict(json.loads(LAYOUT), objects=[p])) for p in proposals)
    assert len(client.suggest(k=1)) == 1
    until = time.monotonic() + 1.0
    client.spin_until(lambda: time.monotonic() > until, 2.0, 'a second')
    assert client.count('scene') == n                          # the room did not change


def test_a_layout_typed_as_yaml_or_pasted_as_a_python_dict(node):
    client = node.client
    # What `ros2 topic pub .../room_layout std_msgs/String "data: '{room_type: office, ...}'"`
    # delivers.
    typed = ("{room_type: office, floor: [[0, 0], [4, 0], [4, 3.5], [0, 3.5]], "
             "request_id: typed-1}")
    n = client.count('scene')
    client.publish_layout(typed, wait=False, check=False)
    assert parse_scene(client.wait_scene(n, request_id='typed-1')).room.room_type == 'office'
    # What an unquoted mapping arrives as: a Python repr; one that cannot be read says how
    # to quote it.
    pasted = str({'room_type': 'office', 'floor': [(0, 0), (4, 0), (4, 3.5)]})
    rejected = int(client.diagnostics()['inputs rejected'])
    client.publish_layout(pasted, wait=False, check=False)
    diag = client.spin_until(lambda: (d := client.diagnostics()) and int(
        d['inputs rejected']) > rejected and d, 20.0, 'rejection')
    assert 'single quotes' in diag['last error']


def test_the_furnish_action_tells_each_object_and_answers_the_room(node):
    client = node.client
    seed = client.get_parameters(['seed'])['seed']
    told = []
    room = client.furnish(LAYOUT, seed=11, feedback=told.append)
    assert room['meta']['seed'] == 11 and room['objects']
    # One feedback per object placed, counting up; the room keeps what it did not withdraw.
    assert [f.objects for f in told] == list(range(1, len(told) + 1))
    assert {o['id'] for o in room['objects']} <= {f.object.id for f in told}
    assert all(f.seconds > 0 for f in told)
    # The same seed gives the same room; a seed stated leaves the node's sequence alone.
    assert client.furnish(LAYOUT, seed=11)['objects'] == room['objects']
    assert client.get_parameters(['seed'])['seed'] == seed
    # A typed layout furnishes as its text does.
    goal = Furnish.Goal(layout=room_msg(json.loads(LAYOUT)), seed=11)
    status, result = _furnish_goal(client, goal)
    assert status == GoalStatus.STATUS_SUCCEEDED and result.success
    typed = json.loads(result.scene_json)['objects']
    # (geometry_msgs/Polygon holds float32 vertices: the same room to a micrometre)
    assert [o['id'] for o in typed] == [o['id'] for o in room['objects']]
    assert [c for o in typed for c in o['position']] == pytest.approx(
        [c for o in room['objects'] for c in o['position']], abs=1e-4)
    assert [o.id for o in result.scene.objects] == [o['id'] for o in room['objects']]
    assert result.scene.seed == 11 and result.scene.header.frame_id == 'map'
    # Bad input is refused in one sentence and the goal aborts; the node serves on.
    status, result = _furnish_goal(client, Furnish.Goal(layout_text='{room_type: bedroom}'))
    assert status == GoalStatus.STATUS_ABORTED and not result.success
    assert 'floor' in result.message and len(result.message) <= MAX_SENTENCE
    status, result = _furnish_goal(client, Furnish.Goal(
        layout_text=LAYOUT, robot=Robot(radius=5.0, reach=1.0, clearance=0.0)))
    assert status == GoalStatus.STATUS_ABORTED and 'radius' in result.message


def _furnish_goal(client, goal, on_feedback=None, timeout: float = 60.0):
    """(status, result) of one ~/furnish goal; ``on_feedback(handle, feedback)``."""
    handle = None

    def feedback(msg):
        if on_feedback is not None:
            on_feedback(handle, msg.feedback)
    sent = client._furnish.send_goal_async(goal, feedback_callback=feedback)
    client.spin_until(sent.done, timeout, 'goal response')
    handle = sent.result()
    assert handle.accepted
    done = handle.get_result_async()
    client.spin_until(done.done, timeout, 'result')
    return done.result().status, done.result().result


def test_a_furnish_goal_is_cancelled_or_superseded_between_insertions(node):
    client = node.client
    big = L_LAYOUT

    def cancel_at_first(handle, feedback):
        if feedback.objects == 1:
            handle.cancel_goal_async()
    status, result = _furnish_goal(client, Furnish.Goal(layout_text=big, seed=3),
                                   cancel_at_first)
    assert status == GoalStatus.STATUS_CANCELED and result.message == 'cancelled'

    def supersede_at_first(handle, feedback):
        if feedback.objects == 1:
            client.publish_layout(LAYOUT, wait=False)
    n = client.count('scene')
    status, result = _furnish_goal(client, Furnish.Goal(layout_text=big, seed=3),
                                   supersede_at_first)
    assert status == GoalStatus.STATUS_ABORTED
    assert result.message == 'superseded by a newer room layout'
    # The layout that superseded it (a bedroom, not the living room) is the room served.
    assert client.wait_scene(n)['room']['room_type'] == 'bedroom'


def test_typed_requests_carry_their_arguments(node):
    client = node.client
    client.furnish(LAYOUT, seed=5)
    client.reset()
    seed = client.get_parameters(['seed'])['seed']
    chair = client.next_object(category='office_chair', seed=4)
    assert chair['category'] == 'office chair'
    client.reset()
    assert client.next_object(category='office chair', seed=4) == chair
    # Nothing was set on the node, and a stated seed took none of its own.
    assert client.get_parameters(['seed', 'next_category']) == {'seed': seed,
                                                                 'next_category': ''}
    proposals = client.suggest(k=3, seed=9)
    assert len(proposals) == 3 and client.suggest(k=3, seed=9) == proposals
    with pytest.raises(ClientError, match='toilet.* is not a category of bedroom'):
        client.next_object(category='toilet')
    with pytest.raises(ClientError, match='k 99 is out of range'):
        client.suggest(k=99)


def test_a_house_on_room_layout_is_furnished_whole_with_its_map_and_rooms_named(node):
    import numpy as np
    from test_house import HOUSE

    from scene_synth_ros.occupancy import occupancy_grid
    from scene_synth_ros.schema import parse_house_scene
    client = node.client
    try:
        before = client.counts()
        client.publish_layout(HOUSE, wait=False)
        d, markers, poses = client.wait_room(before, timeout=120.0)
        house = parse_house_scene(d)
        assert list(house.scenes) == ['hall', 'bed', 'kitchen'] and all(
            s.objects for s in house.scenes.values())
        assert d['meta']['robot']['promise_kept']
        assert {m.ns.split('/')[0] for m in markers.markers[1:]} == {*house.scenes, 'walls'}
        assert len(poses.poses) == len(house.objects())
        grid, want = client.latest('map'), occupancy_grid(house)
        data = np.frombuffer(bytes(grid.data), dtype=np.int8).reshape(want.data.shape)
        assert (data == want.data).all()
        proposals = client.suggest(k=2, seed=1, room='kitchen')
        assert proposals and all(p['category'] for p in proposals)
        with pytest.raises(ClientError, match="name it in room .one of 'hall', 'bed'"):
            client.suggest(k=2)
        published = client.count('scene')
        client.reset(room='bed')
        client.spin_until(lambda: client.count('scene') > published, 10.0, 'scene')
        now = parse_house_scene(client.latest('scene').data)
        assert not now.scenes['bed'].objects and now.scenes['kitchen'].objects
        chair = client.next_object(room='bed', seed=3)
        assert chair['category']
        # the Furnish action takes a house too, and answers it as a house
        again = client.furnish(json.dumps(HOUSE), seed=4)
        assert [r['id'] for r in again['rooms']] == ['hall', 'bed', 'kitchen']
    finally:
        client.publish_layout(LAYOUT, timeout=60.0)


def test_a_closed_client_leaves_nothing_a_forked_process_would_finalise(node):
    # A client's rclpy objects left to the garbage collector are finalised in whatever
    # process collects them: a worker forked later (a batch, a pool) hung there, joining
    # threads of the middleware it does not have. Run in a process of its own: forking this
    # test worker, whose other threads (pytest-xdist's) may hold a lock at the fork, can
    # hang the child for reasons of its own.
    script = f"""
import gc, multiprocessing, sys
from scene_synth_ros.ros_client import SceneSynthClient
client = SceneSynthClient({node.client.target!r}, domain_id={node.domain})
client.spin_until(client.ready, 60.0, 'services')
client.furnish({LAYOUT!r}, seed=1)
client.close()
del client
child = multiprocessing.get_context('fork').Process(target=gc.collect)
child.start()
child.join(60)
if child.exitcode is None:
    child.kill()
print('child exit', child.exitcode)
sys.exit(0 if child.exitcode == 0 else 1)
"""
    done = subprocess.run([sys.executable, '-c', script], capture_output=True, text=True,
                          timeout=180)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    assert 'child exit 0' in done.stdout


def test_the_guides_python_client_example_works_on_a_node_that_served_rooms(node):
    block = (Path(__file__).resolve().parent.parent / 'docs' / 'node.md').read_text() \
        .split('## Clients', 1)[1].split('```python\n', 1)[1].split('```', 1)[0]
    for seed in (0, 7):        # rooms served before: the node's seed has moved on
        node.client.furnish(LAYOUT, seed=seed)
        names = {'SceneSynthClient': lambda *a, **k: _Borrowed(node.client)}
        exec(block.replace('from scene_synth_ros.ros_client import SceneSynthClient\n', ''),
             names)
        assert names['chair']['category'] == 'office chair'
        assert len(names['proposals']) == 3 and names['scene']['objects']


class _Borrowed:
    """The module's client, as the example's ``with`` block opens its own."""

    def __init__(self, client):
        self.client = client

    def __enter__(self):
        return self.client

    def __exit__(self, *exc):
        return False


def test_help_prints_the_usage_and_a_stray_argument_is_named():
    r = subprocess.run([sys.executable, '-m', 'scene_synth_ros.node', '--help'],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and r.stderr == ''
    for name in [*PARAMETERS, '~/room_layout', '~/room_polygon', '~/scene', '~/markers',
                 '~/poses', '~/map', '/diagnostics', '~/generate', '~/next_object', '~/suggest',
                 '~/reset', "'living room'"]:
        assert name in r.stdout
    r = subprocess.run([sys.executable, '-m', 'scene_synth_ros.node', '-p', 'seed:=3'],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "'-p'" in r.stderr and '--ros-args' in r.stderr


def test_command_line_clients(node, tmp_path):
    env = node_env(node.domain)
    cli = [sys.executable, '-m', 'scene_synth_ros.cli', 'ros', '--timeout', '30']

    def run(*args):
        return subprocess.run(cli + list(args), env=env, capture_output=True, text=True,
                              timeout=120)

    r = run('publish-layout', str(examples_dir() / 'bedroom_layout.json'), '--out',
            str(tmp_path / 'room.json'))
    assert r.returncode == 0, r.stderr
    assert 'bedroom, 15.1 m²' in r.stdout
    scene = parse_scene((tmp_path / 'room.json').read_text())
    r = run('echo', 'poses')
    assert r.returncode == 0 and f'{len(scene)} poses' in r.stdout, r.stderr
    r = run('next-object')
    assert r.returncode == 0 or 'nothing more fits' in r.stderr, r.stderr
    r = run('param', 'set', 'location_temperature', '-2')
    assert r.returncode == 2 and 'location_temperature' in r.stderr
    r = run('param', 'set', 'location_temperature', '1')
    assert r.returncode == 0, r.stderr
    r = run('param', 'get', 'location_temperature')
    assert r.returncode == 0 and 'location_temperature: 1.0' in r.stdout
    assert node.client.set_parameters({'location_temperature': 0.8}) == []
    bad = tmp_path / 'bad.json'
    bad.write_text('{"room_type": "bedroom"}')
    r = run('publish-layout', str(bad))
    assert r.returncode == 2 and 'floor' in r.stderr and r.stderr.count('\n') == 1


def test_requests_without_a_room_and_sigterm_in_a_namespace(tmp_path):
    # Started from a copy of the shipped parameter file, as `ros2 run ... --params-file`,
    # under a namespace: the file's /** key applies to the node wherever it runs.
    params = yaml.safe_load((config_dir() / 'scene_synth_node.yaml').read_text())
    values = params['/**']['ros__parameters']
    assert values == {f.name: getattr(ServerConfig, f.name) for f in fields(ServerConfig)}
    # location_temperature: a whole number for a double
    values.update(seed=17, marker_style='mesh', location_temperature=1)
    (tmp_path / 'params.yaml').write_text(yaml.safe_dump(params))
    n = RunningNode(tmp_path, params_file=tmp_path / 'params.yaml', namespace='/sim')
    try:
        assert n.client.get_parameters(['seed', 'marker_style', 'location_temperature']) == {
            'seed': 17, 'marker_style': 'mesh', 'location_temperature': 1}
        ok, message = n.client.call('next_object')
        assert not ok and 'no room yet' in message
        ok, message = n.client.call('generate')
        assert not ok and 'no room yet' in message
    finally:
        code = n.stop(signal.SIGTERM)
    assert code == 0, n.log()
    assert 'Traceback' not in n.log()


def test_stopping_the_node_is_silent_every_time(tmp_path):
    # One Ctrl-C in six once printed "The following exception was never retrieved": stop it
    # 12 times, idle, just after a layout, and with service calls in flight, by either
    # signal (each of the six twice); with the bedroom's weights alone, which start fastest.
    weights = tmp_path / 'weights'
    weights.mkdir()
    shutil.copy(weights_dir() / 'bedroom.pt', weights / 'bedroom.pt')
    for k in range(12):
        n = RunningNode(tmp_path, {'torch_threads': 1, 'weights_dir': str(weights)})
        if k % 3:
            n.client.publish_layout(LAYOUT, wait=k % 3 == 1)
        if k % 3 == 2:
            n.client.call_async('generate')
            n.client.call_async('next_object')
            n.client.executor.spin_once(timeout_sec=0.05)
        code = n.stop(signal.SIGINT if k % 2 else signal.SIGTERM)
        log = n.log()
        assert code == 0, log
        lines = [line for line in log.splitlines() if not line.startswith('[INFO]')]
        assert lines == [], f'run {k}: {lines}'


def _start_and_wait(tmp_path, params) -> subprocess.CompletedProcess:
    return subprocess.run(node_command(params), env=node_env(_domain()), capture_output=True,
                          text=True, timeout=120)


def test_missing_or_corrupt_weights_stop_the_node_naming_the_file(tmp_path):
    shutil.copy(weights_dir() / 'bedroom.pt', tmp_path / 'bedroom.pt')
    # a directory may hold some room types only: the node refuses a room_type it lacks
    r = _start_and_wait(tmp_path, {'weights_dir': str(tmp_path), 'room_type': 'office'})
    assert r.returncode == 1
    assert "room_type 'office' has no weights in" in r.stderr and 'Traceback' not in r.stderr
    for rt in ('living', 'office', 'bathroom'):
        shutil.copy(weights_dir() / f'{rt}.pt', tmp_path / f'{rt}.pt')
    (tmp_path / 'office.pt').write_bytes(b'not a bundle')
    r = _start_and_wait(tmp_path, {'weights_dir': str(tmp_path)})
    assert r.returncode == 1
    assert 'office.pt' in r.stderr and 'Traceback' not in r.stderr


def test_a_bad_start_up_parameter_stops_the_node_in_one_sentence(tmp_path):
    r = _start_and_wait(tmp_path, {'location_temperature': -3.0})
    assert r.returncode == 1 and 'location_temperature' in r.stderr
    assert 'Traceback' not in r.stderr


def test_fast_dds_frees_large_messages_unless_the_user_configured_it(monkeypatch, tmp_path):
    # rmw_fastrtps kept every payload at the largest size it had held: refused megabyte
    # layouts left their buffers in the node (issue 12's memory target).
    from scene_synth_ros import node as node_module
    monkeypatch.chdir(tmp_path)

    def environment(**values):
        for k in (*node_module._FASTDDS_SETTINGS, 'RMW_IMPLEMENTATION'):
            # set first, so that monkeypatch restores what was there, unset included:
            # steady_middleware's own settings must not outlive this test
            monkeypatch.setenv(k, '')
            monkeypatch.delenv(k)
        for k, v in values.items():
            monkeypatch.setenv(k, v)
    environment()
    profile = node_module.steady_middleware()
    try:
        assert os.environ['FASTRTPS_DEFAULT_PROFILES_FILE'] == str(profile)
        assert os.environ['RMW_FASTRTPS_USE_QOS_FROM_XML'] == '1'
        ns = '{http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles}'
        root = ET.parse(profile).getroot()
        assert [e.text for e in root.iter(f'{ns}historyMemoryPolicy')] == ['DYNAMIC'] * 2
        assert [e.text for e in root.iter(f'{ns}kind')] == ['SYNCHRONOUS']
    finally:
        profile.unlink()
    for mine in ({'RMW_FASTRTPS_USE_QOS_FROM_XML': '0'},
                 {'FASTRTPS_DEFAULT_PROFILES_FILE': str(tmp_path / 'mine.xml')},
                 {'RMW_IMPLEMENTATION': 'rmw_cyclonedds_cpp'}):
        environment(**mine)
        assert node_module.steady_middleware() is None
        assert dict(os.environ).items() >= mine.items()
    environment()
    (tmp_path / 'DEFAULT_FASTRTPS_PROFILES.xml').write_text('<dds/>')
    assert node_module.steady_middleware() is None
    assert 'FASTRTPS_DEFAULT_PROFILES_FILE' not in os.environ


def test_the_node_logs_every_severity_and_any_text_from_one_place():
    # rclpy refuses a second severity from one call site; the worker once died of it.
    import rclpy
    from rclpy.context import Context

    from scene_synth_ros.node import SceneSynthNode
    ctx = Context()
    rclpy.init(context=ctx, domain_id=_domain())
    try:
        node = SceneSynthNode(context=ctx, parameter_overrides=[])
        try:
            for level in ('warn', 'error', 'warn', 'info', 'error'):
                node._log(level, 'a key \ud800 in a sentence\nover two lines ' + 'x' * 10_000)
        finally:
            node.destroy_node()
    finally:
        rclpy.try_shutdown(context=ctx)
