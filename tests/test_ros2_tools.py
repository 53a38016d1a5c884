"""The node driven with the real ros2 tools, as a user types the commands: `ros2 launch`,
`ros2 run`, `ros2 action send_goal --feedback`, `ros2 service call`, `ros2 topic pub/echo`,
`ros2 param`, `ros2 interface`. The README's and docs/node.md's commands are run as written.

The tools (ros2cli, launch, launch_ros) are not on the package index: `make test` installs
them from ../shared/ros2-tools where that is beside the checkout. Without them these tests
are skipped, as the real-data tests are without ../shared/data.
"""
import os
from pathlib import Path
import re
import signal
import subprocess
import sys
import time

from conftest import ros_domains
import pytest

from scene_synth_ros.schema import parse_scene

ROOT = Path(__file__).resolve().parent.parent
BIN = Path(sys.prefix) / 'bin'
MSGS = ROOT / 'scene_synth_msgs'
pytestmark = [
    pytest.mark.slow,       # node processes
    pytest.mark.skipif(not (BIN / 'ros2').exists(),
                       reason='the ros2 tools are not installed (make test installs them '
                              'from ../shared/ros2-tools)')]
ECHO_SCENE = ('ros2 topic echo --once --field data --full-length --qos-reliability reliable '
              '--qos-durability transient_local /scene_synth_node/scene std_msgs/msg/String')
# Domains apart from tests/test_node.py's (1-99) and the benchmarks' (100-149).
_DOMAINS = ros_domains(160, 230)


_USED: list[dict] = []      # the environments of the domains used, for the daemons' end


def _env(domain: int) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(('ROS_', 'RMW_', 'FASTRTPS_', 'FASTDDS_'))}
    env.update(AMENT_PREFIX_PATH=sys.prefix, ROS_DOMAIN_ID=str(domain),
               ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST', PATH=f'{BIN}:{env["PATH"]}',
               PYTHONUNBUFFERED='1')
    _USED.append(env)
    return env


@pytest.fixture(scope='module', autouse=True)
def _stop_daemons():
    """The ros2 commands start a discovery daemon per domain, as they do for a user; the
    tests stop theirs rather than leave them running."""
    yield
    for env in _USED:
        subprocess.run(['ros2', 'daemon', 'stop'], env=env, capture_output=True, timeout=30)


def _sh(line: str, env: dict, timeout: float = 120) -> str:
    """Run one command line as a user's shell would, from the repository root; its output."""
    done = subprocess.run(['bash', '-c', line], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=timeout)
    assert done.returncode == 0, f'$ {line[:200]}\n{done.stdout[-2000:]}\n{done.stderr[-2000:]}'
    return done.stdout


def _documented(doc: str, heading: str) -> list[str]:
    """The ros2 command lines of the first bash block under ``heading`` of ``doc``."""
    block = (ROOT / doc).read_text().split(heading + '\n', 1)[1].split('```bash', 1)[1]
    return [line for line in block.split('```', 1)[0].splitlines() if line.startswith('ros2 ')]


class Started:
    """A command that keeps running (ros2 launch, ros2 run), its output in a file."""

    def __init__(self, line: str, env: dict, log: Path, ready: str, timeout: float = 90):
        self.log_path = log
        self._log = open(log, 'w')
        self.proc = subprocess.Popen(['bash', '-c', 'exec ' + line], cwd=ROOT, env=env,
                                     stdout=self._log, stderr=subprocess.STDOUT,
                                     start_new_session=True)
        deadline = time.monotonic() + timeout
        while ready not in self.log():
            assert self.proc.poll() is None and time.monotonic() < deadline, self.log()
            time.sleep(0.2)

    def log(self) -> str:
        if not self._log.closed:
            self._log.flush()
        return self.log_path.read_text()

    def stop(self) -> int:
        """Ctrl-C, as in a terminal (to the whole process group); the exit code."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGINT)
        try:
            return self.proc.wait(60)
        finally:
            if self.proc.poll() is None:
                os.killpg(self.proc.pid, signal.SIGKILL)
            self._log.close()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return Path(f'/proc/{pid}/status').read_text().find('State:\tZ') < 0


@pytest.fixture(scope='module')
def launched(tmp_path_factory):
    """The README's launch line, RViz asked for but not installed."""
    env = _env(next(_DOMAINS))
    (line, *_) = _documented('README.md', '## ROS 2 in one minute')
    assert line.startswith('ros2 launch scene_synth_ros ') and 'rviz:=true' in line
    run = Started(line, env, tmp_path_factory.mktemp('launch') / 'launch.log',
                  'waiting for ~/room_layout')
    run.env = env
    yield run
    node_pid = int(re.search(r'scene_synth_node-1\]: process started with pid \[(\d+)\]',
                             run.log()).group(1))
    assert run.stop() == 0, run.log()
    assert not _alive(node_pid), 'ros2 launch left scene_synth_node running'
    assert 'Traceback' not in run.log(), run.log()


def test_interface_show_explains_every_type():
    env = _env(next(_DOMAINS))
    files = sorted(f'scene_synth_msgs/{p.parent.name}/{p.stem}'
                   for p in MSGS.glob('*/*') if p.suffix in ('.msg', '.srv', '.action'))
    assert len(files) == 12
    listed = sorted(_sh('ros2 interface package scene_synth_msgs', env).split())
    assert listed == files
    for name in files:
        shown = _sh(f'ros2 interface show {name}', env)
        # Each type explains itself: its comments come with it.
        source = next(MSGS.glob(name.split('/', 1)[1] + '.*')).read_text()
        assert shown.startswith('#') and source.splitlines()[0] in shown, name
    furnish = _sh('ros2 interface show scene_synth_msgs/action/Furnish', env)
    assert furnish.count('\n---\n') == 2
    for field in ('RoomLayout layout', 'string layout_text', 'int64 seed -1', 'Robot robot',
                  'Scene scene', 'string scene_json', 'PlacedObject object'):
        assert field in furnish, field


def test_the_readme_quick_start_with_the_real_tools(launched):
    _, *commands = _documented('README.md', '## ROS 2 in one minute')
    assert [c.split()[1] for c in commands] == ['action', 'topic', 'service']
    goal, echo, call = (_sh(c, launched.env) for c in commands)
    assert 'Goal finished with status: SUCCEEDED' in goal, goal
    scene = parse_scene(echo.rsplit('---', 1)[0])
    assert scene.room.room_type == 'bedroom' and len(scene.objects) >= 3
    # One feedback per object placed, counting up. The last ones may not be printed: the
    # result comes on a channel of its own and can overtake them, and the tool ends with it.
    counts = [int(n) for n in re.findall(r'^objects: (\d+)$', goal, re.M)]
    assert counts == list(range(1, len(counts) + 1)) and 1 <= len(counts), goal
    assert 'success=True' in call and "category='plant'" in call, call
    # The launch said in one line that RViz is missing, and the node served on.
    assert launched.log().count('RViz (the package rviz2) is not installed') == 1


def test_the_node_guide_commands_with_the_real_tools(launched):
    """Every command of docs/node.md's "From the ros2 command line" block, in order."""
    outputs = []
    for line in _documented('docs/node.md', '## From the ros2 command line'):
        outputs.append(_sh(line, launched.env))
        print('$', line[:160], '\n', outputs[-1][-400:])
    goals = [o for o in outputs if 'Goal accepted' in o]
    assert goals and all('status: SUCCEEDED' in g for g in goals)
    responses = [o for o in outputs if 'response:' in o]
    assert responses and all('success=True' in r for r in responses), responses
    assert any("category='office chair'" in r for r in responses)
    maps = [o for o in outputs if 'resolution: 0.05' in o]
    assert len(maps) == 1 and re.search(r'width: [1-9]\d*', maps[0]), outputs
    assert outputs[-1].strip() == 'Integer value is: 43'


def _house_through_the_node(pub: str, echo_map: str, env: dict, room: str, timeout: float):
    """Run ``pub`` (a house layout published with `ros2 topic pub`), wait for the node's
    scene to be the house (``room`` one of its room ids), check ``echo_map`` (`ros2 topic
    echo` of the map's info) against that house's map; the house."""
    from scene_synth_ros.occupancy import occupancy_grid
    from scene_synth_ros.schema import parse_house_scene
    assert pub.startswith('ros2 topic pub') and echo_map.startswith('ros2 topic echo')
    _sh(pub, env)
    deadline = time.monotonic() + timeout
    while f'"{room}"' not in (text := _sh(ECHO_SCENE, env).rsplit('---', 1)[0]):
        assert time.monotonic() < deadline, text[-400:]
        time.sleep(0.5)
    house = parse_house_scene(text)
    want = occupancy_grid(house)
    info = _sh(echo_map, env)
    assert f'width: {want.width}' in info and f'height: {want.height}' in info, info
    return house


def test_the_node_guide_house_commands_with_the_real_tools(launched):
    """docs/node.md's house: its layout published with `ros2 topic pub`, its map echoed."""
    pub, echo_map = _documented('docs/node.md', '## Houses')
    house = _house_through_the_node(pub, echo_map, launched.env, 'bed', 60)
    assert list(house.scenes) == ['hall', 'bed'] and house.objects()


def test_the_readme_apartment_through_the_node_with_the_real_tools(launched):
    """README's "A whole home": the apartment's layout file published with `ros2 topic pub`,
    the whole home's map echoed."""
    section = (ROOT / 'README.md').read_text().split('## A whole home\n', 1)[1]
    pub, echo_map = [c for c in section.split('\n## ', 1)[0].splitlines()
                     if c.startswith('ros2 ')]
    assert 'apartment_layout.json' in pub and '/map' in echo_map
    house = _house_through_the_node(pub, echo_map, launched.env, 'bathroom', 90)
    assert len(house.scenes) == 6 and all(s.objects for s in house.scenes.values())


def test_a_layout_latched_before_the_node_starts_is_furnished(tmp_path):
    """A simulator publishes its layout transient local at start-up, before the node is
    up: the node furnishes it once started."""
    env = _env(next(_DOMAINS))
    layout = (ROOT / 'examples' / 'kitchen_layout.json').read_text().replace('\n', ' ')
    publisher = Started(f'ros2 topic pub -w 0 -t 1 --keep-alive 120 --qos-durability '
                        f"transient_local /scene_synth_node/room_layout std_msgs/msg/String "
                        f"\"data: '{layout}'\"", env, tmp_path / 'pub.log', 'publishing #1')
    # with one QoS overridden, as a user may at start-up (qos_overriding_options)
    node = Started('ros2 run scene_synth_ros scene_synth_node --ros-args -p '
                   'qos_overrides./scene_synth_node/markers.publisher.durability:=volatile',
                   env, tmp_path / 'node.log', 'waiting for ~/room_layout')
    try:
        deadline = time.monotonic() + 60
        while 'kitchen with' not in node.log():
            assert time.monotonic() < deadline, node.log()
            time.sleep(0.2)
        scene = parse_scene(_sh(ECHO_SCENE, env).rsplit('---', 1)[0])
        assert scene.room.room_type == 'kitchen' and scene.objects
        # Once, though the latched layout matched both of the node's subscriptions.
        assert node.log().count('room_layout: kitchen with') == 1, node.log()
        assert _published_durability('/scene_synth_node/markers', env) == 'VOLATILE'
        assert _published_durability('/scene_synth_node/scene', env) == 'TRANSIENT_LOCAL'
    finally:
        assert node.stop() == 0, node.log()
        publisher.stop()


def _published_durability(topic: str, env: dict) -> str:
    """The durability the node publishes ``topic`` with, as `ros2 topic info -v` says."""
    # Discovery without the daemon takes longer on a loaded machine (two test workers): a
    # spin too short says "Unknown topic", so look again, longer.
    for spin in (3, 6, 12):
        done = subprocess.run(['ros2', 'topic', 'info', '--no-daemon', '--spin-time', str(spin),
                               '-v', topic], cwd=ROOT, env=env, capture_output=True,
                              text=True, timeout=120)
        publishers = [b for b in done.stdout.split('Node name:')
                      if 'Endpoint type: PUBLISHER' in b]
        if done.returncode == 0 and publishers:
            break
    assert len(publishers) == 1, f'{done.stdout[-2000:]}\n{done.stderr[-2000:]}'
    return re.search(r'Durability: (\w+)', publishers[0]).group(1)


def test_parameters_keep_their_types_and_diagnostics_name_the_node(launched):
    env = launched.env
    assert 'successful' in _sh('ros2 param set /scene_synth_node location_temperature 1', env)
    described = _sh('ros2 param describe /scene_synth_node location_temperature', env)
    assert 'Type: double' in described, described
    assert _sh('ros2 param get /scene_synth_node location_temperature', env).strip() == \
        'Double value is: 1.0'
    diagnostics = _sh('ros2 topic echo --once /diagnostics diagnostic_msgs/msg/DiagnosticArray',
                      env)
    assert 'name: "/scene_synth_node: scene synthesis"' in diagnostics or \
        "name: '/scene_synth_node: scene synthesis'" in diagnostics, diagnostics


def test_a_lifecycle_manager_or_ros2_lifecycle_drives_the_node(tmp_path):
    """Started for a lifecycle manager (none is installed here: the launch says so), the
    node waits unconfigured; `ros2 lifecycle set` configures, activates, deactivates, cleans
    it up and shuts it down as nav2's manager would, and the launch then ends."""
    env = _env(next(_DOMAINS))
    launch = Started('ros2 launch scene_synth_ros scene_synth.launch.xml lifecycle_manager:=true '
                     'namespace:=sim', env, tmp_path / 'launch.log', 'process started with pid')
    node = '/sim/scene_synth_node'
    try:
        deadline = time.monotonic() + 60
        while 'unconfigured' not in (subprocess.run(
                ['ros2', 'lifecycle', 'get', node], env=env, capture_output=True,
                text=True).stdout):
            assert time.monotonic() < deadline, launch.log()
            time.sleep(0.5)
        assert 'nav2_lifecycle_manager is not installed' in launch.log()
        # `set` looks the node up in the graph the ros2 daemon has discovered, which can lag
        # behind the service `get` called directly
        while (done := subprocess.run(['ros2', 'lifecycle', 'set', node, 'configure'],
                                      env=env, capture_output=True, text=True)
               ).stderr.strip() == 'Node not found':
            assert time.monotonic() < deadline, launch.log()
            time.sleep(0.5)
        assert 'Transitioning successful' in done.stdout, (done.stdout, done.stderr)
        assert _sh(f'ros2 lifecycle get {node}', env).startswith('inactive')
        refused = _sh(f'ros2 service call {node}/clear_objects '
                      'scene_synth_msgs/srv/ClearObjects', env)
        assert 'success=False' in refused and 'is inactive' in refused, refused
        goal = (f'ros2 action send_goal {node}/furnish scene_synth_msgs/action/Furnish '
                "\"{layout_text: '$(tr -d '\\n' < examples/kitchen_layout.json)'}\"")
        assert 'Goal was rejected' in _sh(goal, env)
        _sh(f'ros2 lifecycle set {node} activate', env)
        assert 'status: SUCCEEDED' in _sh(goal, env)
        _sh(f'ros2 lifecycle set {node} deactivate', env)
        assert 'Goal was rejected' in _sh(goal, env)
        _sh(f'ros2 lifecycle set {node} cleanup', env)
        assert _sh(f'ros2 lifecycle get {node}', env).startswith('unconfigured')
        services = _sh('ros2 service list', env)
        assert f'{node}/change_state' in services and f'{node}/insert_object' not in services
        _sh(f'ros2 lifecycle set {node} shutdown', env)
        assert launch.proc.wait(30) == 0, launch.log()
        assert 'Traceback' not in launch.log(), launch.log()
    finally:
        launch.stop()
