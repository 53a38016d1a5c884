"""Clients of ``scene_synth_node`` on rclpy, for where the ros2 command-line tools are not
installed: what ``scene-synth ros ...`` runs, and what the node tests and benchmarks use.

Like ``node.py`` this is an adapter: it imports rclpy; the library does not.
"""
from __future__ import annotations

import json
import math
import os
import random
import signal
import subprocess
import sys
import time
from typing import Any
import uuid

from diagnostic_msgs.msg import DiagnosticArray
from geometry_msgs.msg import Point32, PolygonStamped, PoseArray
from nav_msgs.msg import OccupancyGrid
from rcl_interfaces.msg import Parameter as ParameterMsg
import rclpy
from rclpy.action import ActionClient
from rclpy.context import Context
from rclpy.event_handler import PublisherEventCallbacks
from rclpy.executors import SingleThreadedExecutor
from rclpy.parameter import Parameter
from rclpy.parameter_client import AsyncParameterClient
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from rclpy.signals import SignalHandlerOptions
from scene_synth_msgs.action import Furnish
from scene_synth_msgs.srv import ClearObjects, InsertObject, SuggestObjects
from std_msgs.msg import String
from std_srvs.srv import Trigger
from visualization_msgs.msg import MarkerArray

from .errors import SceneSynthError
from .ros_messages import object_dict, quaternion_yaw
from .schema import SceneValidationError, parse_layout, read_payload

DEFAULT_NODE = '/scene_synth_node'

# The QoS of the node's topics, defined here for both ends (node.py imports them, and this
# module, unlike node.py, loads without the library behind the node).
# The room outputs: a late `ros2 topic echo` or RViz still gets the last room.
LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)
# Room layouts in and diagnostics out: none may be lost.
RELIABLE = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
# Layouts out: volatile, so that they match only the node's volatile subscription to
# ~/room_layout and arrive in the order sent. A transient-local publisher matches its
# latched subscription too, and a layout sent right after another could be served before it
# (node.py). The middleware warns once that the latched subscription is incompatible.
LAYOUTS = RELIABLE
TOPICS = {'scene': String, 'markers': MarkerArray, 'poses': PoseArray, 'map': OccupancyGrid}
# The node's std_srvs/Trigger services (``server.REQUESTS``; this module does not import the
# library behind the node).
SERVICES = ('generate', 'next_object', 'reset', 'suggest')
# The typed services (node.TYPED_SERVICES).
TYPED = {'insert_object': InsertObject, 'suggest_objects': SuggestObjects,
         'clear_objects': ClearObjects}


class ClientError(SceneSynthError):
    """The node did not answer as asked: one sentence."""


class SceneSynthClient:
    """Talks to one ``scene_synth_node``; keeps the latest message of every output topic."""

    def __init__(self, node: str = DEFAULT_NODE, domain_id: int | None = None):
        self.target = node if node.startswith('/') else '/' + node
        self.context = Context()
        # No rclpy signal handlers: Ctrl-C stays a KeyboardInterrupt for the caller (the
        # command line exits with 130), and a test runner keeps its own handlers.
        rclpy.init(context=self.context, domain_id=domain_id,
                   signal_handler_options=SignalHandlerOptions.NO)
        self.node = rclpy.create_node(f'scene_synth_client_{os.getpid()}_{id(self) % 10000}',
                                      context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        # topic -> [(sequence number, arrival time, message)], the last 50 of each
        self.received: dict[str, list[tuple[int, float, Any]]] = {
            k: [] for k in (*TOPICS, 'diagnostics')}
        self._counts = dict.fromkeys(self.received, 0)
        for topic, kind in TOPICS.items():
            self.node.create_subscription(kind, f'{self.target}/{topic}',
                                          self._keeper(topic), LATCHED)
        self.node.create_subscription(DiagnosticArray, '/diagnostics',
                                      self._keeper('diagnostics'), RELIABLE)
        # The node's latched subscription cannot match it, by design: no warning of that.
        self._layout_pub = self.node.create_publisher(
            String, f'{self.target}/room_layout', LAYOUTS,
            event_callbacks=PublisherEventCallbacks(incompatible_qos=lambda event: None))
        self._polygon_pub = self.node.create_publisher(
            PolygonStamped, f'{self.target}/room_polygon', RELIABLE)
        self._services = {k: self.node.create_client(Trigger, f'{self.target}/{k}')
                          for k in SERVICES}
        self._typed = {k: self.node.create_client(t, f'{self.target}/{k}')
                       for k, t in TYPED.items()}
        self._furnish = ActionClient(self.node, Furnish, f'{self.target}/furnish')
        self._params = AsyncParameterClient(self.node, self.target)

    def _keeper(self, topic: str):
        def keep(msg):
            self._counts[topic] += 1
            self.received[topic].append((self._counts[topic], time.monotonic(), msg))
            del self.received[topic][:-50]        # a long echo must not grow without bound
        return keep

    def close(self) -> None:
        self.executor.shutdown(timeout_sec=1.0)
        # The action client holds the node: left to the garbage collector, the node would be
        # finalised there, in whatever process runs it (a forked worker hangs joining the
        # middleware's threads, which it does not have).
        self._furnish.destroy()
        self.node.destroy_node()
        rclpy.try_shutdown(context=self.context)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ---- waiting --------------------------------------------------------------------------
    def spin_until(self, predicate, timeout: float, what: str):
        """Spin until ``predicate()`` returns something truthy; ClientError after timeout."""
        deadline = time.monotonic() + timeout
        while True:
            value = predicate()
            if value:
                return value
            if time.monotonic() > deadline:
                raise ClientError(f'no {what} from {self.target} within {timeout:.0f} s')
            self.executor.spin_once(timeout_sec=0.05)

    def ready(self) -> bool:
        """Whether the node's services and subscriptions are discovered (no spinning)."""
        return (all(c.service_is_ready() for c in self._services.values())
                and all(c.service_is_ready() for c in self._typed.values())
                and self._furnish.server_is_ready()
                and self._layout_pub.get_subscription_count() > 0
                and self._polygon_pub.get_subscription_count() > 0)

    def count(self, topic: str) -> int:
        """How many messages arrived on ``topic`` so far."""
        return self._counts[topic]

    def counts(self) -> dict[str, int]:
        """Messages received so far per topic, to wait for newer ones with ``wait_room``."""
        return dict(self._counts)

    def wait_room(self, after: dict[str, int], timeout: float = 60.0):
        """(scene dict, MarkerArray, PoseArray) of a room published after ``after``
        (from ``counts``): waits for all its topics (its map too, ``latest('map')``)."""
        self.spin_until(lambda: all(self._counts[t] > after[t] for t in TOPICS), timeout,
                        'room (scene, markers, poses and map)')
        return (json.loads(self.received['scene'][-1][2].data),
                self.received['markers'][-1][2], self.received['poses'][-1][2])

    def latest(self, topic: str, timeout: float = 5.0):
        """The latest message on ``topic`` (scene, markers, poses, map, diagnostics)."""
        return self.spin_until(lambda: self.received[topic] and self.received[topic][-1][2],
                               timeout, topic)

    def diagnostics(self, timeout: float = 5.0) -> dict[str, str]:
        """The node's latest diagnostic status as a dict (level, message and its values)."""
        def mine():
            for _, _, msg in reversed(self.received['diagnostics']):
                for st in msg.status:
                    if st.name.startswith(self.target + ':'):
                        d = {kv.key: kv.value for kv in st.values}
                        d.update(level=str(ord(st.level)), message=st.message)
                        return d
            return None
        return self.spin_until(mine, timeout, 'diagnostics')

    def wait_scene(self, after: int, timeout: float = 60.0,
                   request_id: str | None = None) -> dict[str, Any]:
        """The first scene received after ``after`` scenes (and, if given, the one that
        answers the layout of ``request_id``)."""
        def arrived():
            for seq, _, msg in self.received['scene']:
                if seq <= after:
                    continue
                d = json.loads(msg.data)
                if request_id is None or d.get('meta', {}).get('request_id') == request_id:
                    return d
            return None
        return self.spin_until(arrived, timeout, 'scene')

    # ---- requests -------------------------------------------------------------------------
    def publish_layout(self, layout: str | dict, wait: bool = True, timeout: float = 60.0,
                       check: bool = True) -> dict[str, Any] | None:
        """Publish a room or house layout (JSON or YAML text, or a dict); with ``wait``,
        return the scene the node answers with.

        With ``check`` the layout is validated here first, so bad input fails at once with
        the same sentence the node would log. With ``wait``, a valid layout without a
        ``request_id`` is sent as JSON with a new one, and the answer is the scene that
        carries it; without, the text is sent as given."""
        text = layout if isinstance(layout, str) else json.dumps(layout)
        request_id = None
        if check or wait:
            try:
                parse_layout(text)
                d = read_payload(text)
                request_id = d.get('request_id')
                if request_id is None and wait:
                    request_id = d['request_id'] = uuid.uuid4().hex
                    text = json.dumps(d)
            except SceneValidationError as e:
                if check:
                    raise ClientError(f'the layout is invalid: {e}') from None
        self.spin_until(lambda: self._layout_pub.get_subscription_count() > 0, timeout,
                        'subscription to room_layout')
        before = self.count('scene')
        self._layout_pub.publish(String(data=text))
        if not wait:
            return None
        return self.wait_scene(before, timeout, request_id)

    def publish_polygon(self, points, frame_id: str = 'map') -> None:
        msg = PolygonStamped()
        msg.header.frame_id = frame_id
        msg.polygon.points = [Point32(x=float(p[0]), y=float(p[1]), z=0.0) for p in points]
        self.spin_until(lambda: self._polygon_pub.get_subscription_count() > 0, 10.0,
                        'subscription to room_polygon')
        self._polygon_pub.publish(msg)

    def call_async(self, service: str):
        """Send a call of one of ``SERVICES`` without waiting: the rclpy future, which
        completes while this client spins."""
        return self._services[service].call_async(Trigger.Request())

    def call(self, service: str, timeout: float = 120.0,
             retry_busy: bool = True) -> tuple[bool, str]:
        """Call one of ``SERVICES``: (success, message). A "busy" answer (the node already
        has ``max_pending`` calls waiting ahead of this one) is retried after a growing,
        jittered pause until ``timeout``, unless ``retry_busy`` is off."""
        client = self._services[service]
        deadline = time.monotonic() + timeout
        self.spin_until(client.service_is_ready, min(timeout, 30.0), f'{service} service')
        pause = 0.05
        while True:
            future = self.call_async(service)
            self.spin_until(future.done, max(deadline - time.monotonic(), 0.0),
                            f'{service} response')
            response = future.result()
            busy = not response.success and response.message.startswith('busy:')
            if not (busy and retry_busy) or time.monotonic() + pause > deadline:
                return response.success, response.message
            until = time.monotonic() + pause * (0.5 + random.random())
            self.spin_until(lambda u=until: time.monotonic() > u, pause * 2, 'pause')
            pause = min(pause * 2, 0.5)

    def furnish(self, layout: str | dict, seed: int | None = None,
                feedback=None, timeout: float = 120.0) -> dict[str, Any]:
        """Furnish a room or house layout (JSON or YAML text, or a dict) through the ~/furnish
        action, with ``seed`` or the node's next one; ``feedback(msg)`` is called with each
        Furnish.Feedback (an object placed). The furnished room as a scene dict."""
        text = layout if isinstance(layout, str) else json.dumps(layout)
        self.spin_until(self._furnish.server_is_ready, min(timeout, 30.0), 'furnish action')
        goal = Furnish.Goal(layout_text=text, seed=-1 if seed is None else seed)
        sent = self._furnish.send_goal_async(
            goal, feedback_callback=None if feedback is None else
            (lambda m: feedback(m.feedback)))
        self.spin_until(sent.done, timeout, 'furnish goal response')
        result = sent.result().get_result_async()
        self.spin_until(result.done, timeout, 'furnish result')
        answer = result.result().result
        if not answer.success:
            raise ClientError(f'furnish refused: {answer.message}')
        return json.loads(answer.scene_json)

    def _typed_call(self, service: str, request, timeout: float):
        client = self._typed[service]
        self.spin_until(client.service_is_ready, min(timeout, 30.0), f'{service} service')
        future = client.call_async(request)
        self.spin_until(future.done, timeout, f'{service} response')
        response = future.result()
        if not response.success:
            raise ClientError(f'{service} refused: {response.message}')
        return response

    def next_object(self, category: str | None = None, seed: int | None = None,
                    timeout: float = 120.0, room: str = '') -> dict[str, Any]:
        """Insert one object, of ``category`` or of the category module's choice, with
        ``seed`` or the node's next one, into the room served (of a house: room ``room``);
        the new object as a dict."""
        response = self._typed_call('insert_object', InsertObject.Request(
            category=category or '', seed=-1 if seed is None else seed, room=room), timeout)
        return object_dict(response.object)

    def suggest(self, k: int | None = None, seed: int | None = None,
                timeout: float = 120.0, room: str = '') -> list[dict[str, Any]]:
        """``k`` (or the node's ``suggestions``) proposals for the next object (of a house:
        in room ``room``), as dicts; the room does not change."""
        response = self._typed_call('suggest_objects', SuggestObjects.Request(
            k=k or 0, seed=-1 if seed is None else seed, room=room), timeout)
        return [object_dict(o) for o in response.objects]

    def reset(self, timeout: float = 120.0, room: str = '') -> dict[str, Any]:
        """Remove every object from the current room (of a house: from room ``room``, or
        from every room)."""
        self._typed_call('clear_objects', ClearObjects.Request(room=room), timeout)
        return {'objects': 0}

    # Generate has no typed service (the action furnishes a layout): it is shaped by the
    # node's parameters, set just before the call.
    def generate(self, seed: int | None = None, timeout: float = 120.0) -> dict[str, Any]:
        """Furnish the current room again from empty, with ``seed`` or the node's next one;
        the answer's JSON (seed, objects, added, ...)."""
        return self._call_with({'seed': seed} if seed is not None else {}, 'generate',
                               timeout)

    def _call_with(self, params: dict[str, Any], service: str, timeout: float) -> Any:
        refused = self.set_parameters(params, timeout) if params else []
        if refused:
            raise ClientError(f'the node refused {refused[0]}')
        ok, message = self.call(service, timeout)
        if not ok:
            raise ClientError(f'{service} refused: {message}')
        return json.loads(message)

    def get_parameters(self, names: list[str], timeout: float = 10.0) -> dict[str, Any]:
        self.spin_until(lambda: self._params.services_are_ready(), timeout, 'parameter services')
        future = self._params.get_parameters(names)
        self.spin_until(future.done, timeout, 'parameters')
        values = future.result().values
        return {n: Parameter.from_parameter_msg(_named(n, v)).value
                for n, v in zip(names, values, strict=False)}

    def set_parameters(self, values: dict[str, Any], timeout: float = 30.0) -> list[str]:
        """Set parameters; returns the reasons of those the node refused (empty if none)."""
        self.spin_until(lambda: self._params.services_are_ready(), timeout, 'parameter services')
        future = self._params.set_parameters([Parameter(k, value=v) for k, v in values.items()])
        self.spin_until(future.done, timeout, 'parameter result')
        return [f'{name}: {r.reason}' for name, r in zip(values, future.result().results,
                                                             strict=False)
                if not r.successful]


def _named(name, value):
    return ParameterMsg(name=name, value=value)


# ---- text renderings for the command line -----------------------------------------------
def format_markers(msg: MarkerArray) -> str:
    names = {0: 'ARROW', 1: 'CUBE', 9: 'TEXT', 10: 'MESH', 11: 'TRIANGLE_LIST'}
    lines = []
    for m in msg.markers:
        if m.action == m.DELETEALL:
            lines.append('DELETEALL')
            continue
        yaw = quaternion_yaw(m.pose.orientation)
        lines.append(f'{m.ns:18s} {m.id:3d} {names.get(m.type, m.type):13s} '
                     f'x {m.pose.position.x:6.2f} y {m.pose.position.y:6.2f} '
                     f'z {m.pose.position.z:5.2f} yaw {math.degrees(yaw):7.1f}° scale '
                     f'{m.scale.x:.2f} {m.scale.y:.2f} {m.scale.z:.2f}'
                     + (f'  "{m.text}"' if m.text else '')
                     + (f'  {m.mesh_resource}' if m.mesh_resource else ''))
    return '\n'.join(lines)


def format_poses(msg: PoseArray) -> str:
    lines = [f'frame {msg.header.frame_id}, {len(msg.poses)} poses']
    for k, p in enumerate(msg.poses):
        yaw = quaternion_yaw(p.orientation)
        lines.append(f'{k:3d}  x {p.position.x:6.2f}  y {p.position.y:6.2f}  '
                     f'z {p.position.z:5.2f}  yaw {math.degrees(yaw):7.1f}°')
    return '\n'.join(lines)


def format_map(msg: OccupancyGrid) -> str:
    info = msg.info
    data = bytes(msg.data)
    occupied, free = data.count(100), data.count(0)
    return (f'frame {msg.header.frame_id}, {info.width} x {info.height} cells of '
            f'{info.resolution:g} m, origin x {info.origin.position.x:.3f} y '
            f'{info.origin.position.y:.3f}: {occupied} occupied, {free} free, '
            f'{len(data) - occupied - free} unknown')


# ---- the node as a child process ---------------------------------------------------------
def node_command(params: dict[str, Any] | None = None, params_file: str | None = None,
                 namespace: str = '') -> list[str]:
    cmd = [sys.executable, '-m', 'scene_synth_ros.node', '--ros-args']
    if namespace:
        cmd += ['-r', f'__ns:={namespace}']
    if params_file:
        cmd += ['--params-file', str(params_file)]
    for k, v in (params or {}).items():
        value = json.dumps(v) if isinstance(v, bool) else str(v)
        cmd += ['-p', f'{k}:={value}']
    return cmd


def node_env(domain_id: int) -> dict[str, str]:
    env = dict(os.environ)
    env['ROS_DOMAIN_ID'] = str(domain_id)
    env.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    env['PYTHONUNBUFFERED'] = '1'
    return env


def start_node(domain_id: int, params: dict[str, Any] | None = None, log=None,
               params_file: str | None = None, namespace: str = '') -> subprocess.Popen:
    """Start ``scene_synth_node`` in a child process on ``domain_id``."""
    return subprocess.Popen(node_command(params, params_file, namespace),
                            env=node_env(domain_id),
                            stdout=log or subprocess.DEVNULL,
                            stderr=subprocess.STDOUT if log else subprocess.DEVNULL)


def stop_node(proc: subprocess.Popen, sig: int = signal.SIGINT, timeout: float = 20.0) -> int:
    """Signal the node and wait for it; returns its exit code (killed after ``timeout``)."""
    if proc.poll() is None:
        proc.send_signal(sig)
        try:
            proc.wait(timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    return proc.returncode
