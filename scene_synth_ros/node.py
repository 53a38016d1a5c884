"""``scene_synth_node``: the ROS 2 face of ``server.SceneServer``.

    ros2 run scene_synth_ros scene_synth_node [--ros-args -p room_type:=office ...]
    python -m scene_synth_ros.node [--ros-args ...]        (without the ros2 tools)

Subscriptions ~/room_layout (std_msgs/String, JSON or YAML; a layout latched before the
node started is received too) and ~/room_polygon (geometry_msgs/PolygonStamped); publications
~/markers, ~/poses, ~/scene (reliable, transient local) and /diagnostics; the action
~/furnish (scene_synth_msgs/action/Furnish); typed services ~/insert_object,
~/suggest_objects, ~/clear_objects (scene_synth_msgs/srv/...); and the services of the JSON
interface ~/next_object, ~/generate, ~/reset, ~/suggest (std_srvs/Trigger, JSON in
``message``). This module only converts between messages and the server's calls.
"""
from __future__ import annotations

from collections import deque
import os
from pathlib import Path
import signal
import sys
import tempfile
import threading
import time

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from geometry_msgs.msg import Point, PolygonStamped, PoseArray
from nav_msgs.msg import OccupancyGrid
from rcl_interfaces.msg import (
    FloatingPointRange,
    IntegerRange,
    ParameterDescriptor,
    SetParametersResult,
)
import rclpy
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from rclpy.event_handler import SubscriptionEventCallbacks
from rclpy.exceptions import InvalidParameterTypeException, InvalidParameterValueException
from rclpy.executors import ExternalShutdownException, MultiThreadedExecutor
from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy, QoSPolicyKind, QoSProfile, ReliabilityPolicy
from rclpy.qos_overriding_options import QoSOverridingOptions
from rclpy.signals import SignalHandlerOptions
from rclpy.utilities import remove_ros_args
from scene_synth_msgs.action import Furnish
from scene_synth_msgs.srv import ClearObjects, InsertObject, SuggestObjects
from std_msgs.msg import ColorRGBA, String
from std_srvs.srv import Trigger
from visualization_msgs.msg import Marker, MarkerArray

from .allocator import steady_allocator
from .errors import SceneSynthError, sentence
from .house import HouseScene
from .markers import house_markers, scene_markers, warm_up
from .ros_client import LATCHED, RELIABLE
from .ros_messages import (
    layout_dict,
    object_msg,
    occupancy_message,
    pose,
    robot_radius_reach_clearance,
    scene_msg,
)
from .rules.robot import Robot
from .server import (
    ERROR,
    OK,
    PARAMETERS,
    REQUESTS,
    Answer,
    ConfigError,
    SceneServer,
    Served,
    ServerConfig,
    Status,
    check,
)

NODE_NAME = 'scene_synth_node'
EXIT_STARTUP_FAILED = 1
# Service calls waiting for the worker hold one thread each: at most max_pending (12) short
# calls and as many whole-room ones (server.RANK). Two more keep answering "busy", the
# diagnostics timer and the subscriptions.
EXECUTOR_THREADS = 2 * PARAMETERS['max_pending'][1][1] + 2
# Seconds a stop waits for the room under way, then again for the answers being sent: a
# node destroyed while one is still sending prints an error at exit, and on a loaded machine
# two seconds were not always enough. Both waits and the executor's 2 s stay under the 10 s
# after which ros2 launch kills a node it asked to stop. An idle node stops at once.
STOP_WAIT = 3.5

# Fast DDS's profile for the node's own endpoints. rmw_fastrtps keeps every history payload
# at the largest size it has held (PREALLOCATED_WITH_REALLOC), so the 1-7 MB layouts that the
# input limits refuse, which still arrive whole, left their buffers behind: +17 MB of such
# blocks over 1,000 mixed inputs (node_load.py), more the more large messages came, up to
# the readers' history depths. DYNAMIC frees a payload with its sample. Publication stays
# synchronous, as rmw_fastrtps publishes in Jazzy.
FASTDDS_PROFILES = """<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <data_reader profile_name="scene_synth_reader" is_default_profile="true">
      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>
    </data_reader>
    <data_writer profile_name="scene_synth_writer" is_default_profile="true">
      <qos><publishMode><kind>SYNCHRONOUS</kind></publishMode></qos>
      <historyMemoryPolicy>DYNAMIC</historyMemoryPolicy>
    </data_writer>
  </profiles>
</dds>
"""
# What a user configures Fast DDS with; any of them and the node leaves Fast DDS alone.
_FASTDDS_SETTINGS = ('FASTRTPS_DEFAULT_PROFILES_FILE', 'FASTDDS_DEFAULT_PROFILES_FILE',
                     'RMW_FASTRTPS_USE_QOS_FROM_XML')

# ~/room_layout as a simulator latches it at start-up: reliable and transient local, so a
# layout published before the node was up still arrives. A second subscription, volatile,
# hears the publishers that are (`ros2 topic pub` by default), which a transient-local one
# would not match; a layout from a transient-local publisher arrives on both, once here.
# Of two layouts such a publisher sends in quick succession, the latched subscription
# (depth 1) can hand over the newer before the volatile one hands over the older: an older
# layout is dropped by its source stamp (``LAYOUT_ORDER_WINDOW``).
LATCHED_INPUT = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                           durability=DurabilityPolicy.TRANSIENT_LOCAL)
# What a user may set for the room topics and ~/room_polygon at start-up, as parameters
# qos_overrides./scene_synth_node/scene.publisher.durability and the like (read-only).
OVERRIDABLE = QoSOverridingOptions([QoSPolicyKind.DEPTH, QoSPolicyKind.DURABILITY,
                                    QoSPolicyKind.HISTORY, QoSPolicyKind.RELIABILITY])
# Layouts remembered to drop the second copy by: a handful in flight at most.
SEEN_LAYOUTS = 64
# Seconds after taking a layout in which one stamped earlier by its publisher (its source
# timestamp) is an older layout overtaken on the other subscription, and dropped. Short, so
# that a publisher on a host whose clock lags is only refused right after another's layout.
LAYOUT_ORDER_WINDOW = 2.0
# The typed services, each with the request of ``server.REQUESTS`` it runs.
TYPED_SERVICES = {'insert_object': (InsertObject, 'next_object'),
                  'suggest_objects': (SuggestObjects, 'suggest'),
                  'clear_objects': (ClearObjects, 'reset')}

_KINDS = {'cube': Marker.CUBE, 'mesh': Marker.MESH_RESOURCE, 'text': Marker.TEXT_VIEW_FACING,
          'triangle_list': Marker.TRIANGLE_LIST}


class StartupError(SceneSynthError):
    """The node cannot serve (bad weights, bad parameter): one sentence, exit non-zero."""


def _descriptor(name: str) -> ParameterDescriptor:
    text, limits, read_only = PARAMETERS[name]
    d = ParameterDescriptor(description=text, read_only=read_only)
    if isinstance(limits, tuple) and limits and isinstance(limits[0], float):
        d.floating_point_range = [FloatingPointRange(from_value=limits[0], to_value=limits[1])]
    elif isinstance(limits, tuple) and limits and isinstance(limits[0], int):
        d.integer_range = [IntegerRange(from_value=limits[0], to_value=limits[1], step=1)]
    elif isinstance(limits, tuple):
        d.additional_constraints = 'one of: ' + ', '.join(limits)
    return d


class LayoutOrder:
    """Which layouts arriving on ``~/room_layout``'s two subscriptions are taken: a copy of
    one already taken (the same source stamp and sequence number) is not, nor one stamped
    by its publisher before the newest one taken, within ``window`` seconds of that (an
    older layout overtaken on the other subscription)."""

    def __init__(self, seen: int = SEEN_LAYOUTS, window: float = LAYOUT_ORDER_WINDOW):
        self._seen: deque = deque(maxlen=seen)
        self._newest: tuple[int, float] | None = None     # (source stamp, taken at)
        self.window = window

    def admit(self, stamp: int | None, sequence: int | None, now: float) -> bool:
        key = (stamp, sequence)
        if key in self._seen:
            return False
        self._seen.append(key)
        if stamp is None:
            return True
        if self._newest is not None and stamp < self._newest[0] \
                and now - self._newest[1] < self.window:
            return False
        self._newest = (stamp, now)
        return True


class SceneSynthNode(LifecycleNode):
    def __init__(self, **kwargs):
        super().__init__(NODE_NAME, **kwargs)
        defaults = ServerConfig()
        self._updating_seed = threading.local()     # the node's own update of ``seed``
        # A whole number given for a double at start-up (`-p location_temperature:=1`, a
        # parameters file) is the double it means, as `_as_floats` makes it at run time:
        # rclpy keeps the start-up overrides in this dictionary, read by declare_parameter.
        overrides = getattr(self, '_parameter_overrides', {})
        for p in _as_floats(list(overrides.values())):
            overrides[p.name] = p
        try:
            for name in PARAMETERS:
                self.declare_parameter(name, getattr(defaults, name), _descriptor(name))
        except (InvalidParameterTypeException, InvalidParameterValueException) as e:
            raise StartupError(str(e)) from None
        self.add_pre_set_parameters_callback(_as_floats)
        self.add_on_set_parameters_callback(self._on_parameters)
        self.server: SceneServer | None = None      # made by configure, gone at cleanup
        self._active = False
        self._configure_error = ''
        self._made: list = []                       # what configure creates
        self._held_layout: tuple | None = None      # the last layout while inactive
        self.finalized = threading.Event()          # shut down: the process may end
        # what the first room's markers would wait for, read beside the serving, once
        self._warming = threading.Thread(target=warm_up, name='scene_synth_warm_up')
        # Diagnostics in every state: a manager's operator sees an unconfigured node too.
        self.diag_pub = self.create_publisher(DiagnosticArray, '/diagnostics', RELIABLE)
        self.create_timer(1.0, self._publish_diagnostics,
                          callback_group=MutuallyExclusiveCallbackGroup())

    # ---- the lifecycle (nav2's: configure loads, activate serves) --------------------------
    def on_configure(self, state) -> TransitionCallbackReturn:
        config = ServerConfig(**{n: self.get_parameter(n).value for n in PARAMETERS})
        try:
            self.server = SceneServer(config, self._publish_room, self._publish_diagnostics,
                                      self._log, self._show_next_seed)
        except SceneSynthError as e:
            self._configure_error = sentence(e)
            self._log('error', f'cannot configure: {e}')
            return TransitionCallbackReturn.FAILURE
        self._configure_error = ''
        inputs = MutuallyExclusiveCallbackGroup()
        services = ReentrantCallbackGroup()     # a waiting service must not block another
        self.markers_pub = self.create_lifecycle_publisher(
            MarkerArray, '~/markers', _own(LATCHED), qos_overriding_options=OVERRIDABLE)
        self.poses_pub = self.create_lifecycle_publisher(
            PoseArray, '~/poses', _own(LATCHED), qos_overriding_options=OVERRIDABLE)
        self.scene_pub = self.create_lifecycle_publisher(
            String, '~/scene', _own(LATCHED), qos_overriding_options=OVERRIDABLE)
        # as map_server publishes its map: reliable, transient local, the last one
        self.map_pub = self.create_lifecycle_publisher(
            OccupancyGrid, '~/map', _own(LATCHED), qos_overriding_options=OVERRIDABLE)
        self._layouts = LayoutOrder()
        made = [self.create_subscription(String, '~/room_layout', self._on_layout, RELIABLE,
                                         callback_group=inputs),
                # a volatile publisher cannot match it, by design: no warning of that
                self.create_subscription(String, '~/room_layout', self._on_layout,
                                         LATCHED_INPUT, callback_group=inputs,
                                         event_callbacks=SubscriptionEventCallbacks(
                                             incompatible_qos=lambda event: None))]
        made.append(self.create_subscription(PolygonStamped, '~/room_polygon',
                                             self._on_polygon, _own(RELIABLE),
                                             callback_group=inputs,
                                             qos_overriding_options=OVERRIDABLE))
        made += [self.create_service(Trigger, f'~/{kind}', self._service(kind),
                                     callback_group=services) for kind in REQUESTS]
        made += [self.create_service(srv, f'~/{name}', self._typed_service(kind),
                                     callback_group=services)
                 for name, (srv, kind) in TYPED_SERVICES.items()]
        made.append(ActionServer(
            self, Furnish, '~/furnish', self._furnish, callback_group=services,
            goal_callback=self._goal_response,
            cancel_callback=lambda goal: CancelResponse.ACCEPT))
        self._made = made
        self.get_logger().info(
            f'configured: weights from {config.weights_dir or "the package"}, models from '
            f'{config.catalog_dir or "the procedural catalog"}, device {config.device}, '
            f'torch threads {config.torch_threads}')
        return super().on_configure(state)

    def on_activate(self, state) -> TransitionCallbackReturn:
        done = super().on_activate(state)       # the lifecycle publishers
        self._active = True
        if self._warming.ident is None:
            self._warming.start()
        held, self._held_layout = self._held_layout, None
        if held is not None:
            self.server.submit_layout(*held)
        self.get_logger().info(
            f'ready: {len(PARAMETERS)} parameters; waiting for ~/room_layout, ~/room_polygon '
            f'or a ~/furnish goal')
        return done

    def on_deactivate(self, state) -> TransitionCallbackReturn:
        self._active = False
        self.get_logger().info('deactivated: requests are refused until activated again')
        return super().on_deactivate(state)

    def on_cleanup(self, state) -> TransitionCallbackReturn:
        self._release()
        return super().on_cleanup(state)

    def on_shutdown(self, state) -> TransitionCallbackReturn:
        self._release()
        self.finalized.set()        # a finalized node serves nothing again: the process ends
        return super().on_shutdown(state)

    def on_error(self, state) -> TransitionCallbackReturn:
        self._release()
        return super().on_error(state)

    def _release(self) -> None:
        """Undo configure: the server (its weights, its worker) and every endpoint."""
        self._active = False
        if self.server is not None:
            self.server.close()
        for thing in self._made:
            if isinstance(thing, ActionServer):
                thing.destroy()
            elif hasattr(thing, 'srv_type'):
                self.destroy_service(thing)
            else:
                self.destroy_subscription(thing)
        for pub in ('markers_pub', 'poses_pub', 'scene_pub', 'map_pub'):
            if hasattr(self, pub):
                self.destroy_lifecycle_publisher(getattr(self, pub))
                delattr(self, pub)
        self._made, self.server = [], None

    def start(self) -> None:
        """Configure and activate, as a lifecycle manager would (``autostart``);
        StartupError with configure's sentence when it fails."""
        if self.trigger_configure() != TransitionCallbackReturn.SUCCESS:
            raise StartupError(self._configure_error or 'configure failed')
        self.trigger_activate()

    def _inactive(self) -> str:
        """Why a request is refused now, or '' when the node serves."""
        if self._active:
            return ''
        return f'{self.get_fully_qualified_name()} is inactive: activate it to serve ' \
               f'(ros2 lifecycle set {self.get_fully_qualified_name()} activate)'

    def _goal_response(self, goal) -> GoalResponse:
        return GoalResponse.ACCEPT if self._active else GoalResponse.REJECT

    # ---- inputs ---------------------------------------------------------------------------
    def _on_layout(self, msg: String, info) -> None:
        if not self._layouts.admit(info.get('source_timestamp'),
                                   info.get('publication_sequence_number'), time.monotonic()):
            return
        if not self._active:        # kept for activation: a simulator latched it at start-up
            self._held_layout = (msg.data, 'room_layout')
            return
        self.server.submit_layout(msg.data, 'room_layout')

    def _on_polygon(self, msg: PolygonStamped) -> None:
        if self._active:
            self.server.submit_polygon([(p.x, p.y, p.z) for p in msg.polygon.points],
                                       msg.header.frame_id)

    def _service(self, kind: str):
        def call(request, response):
            response.success, response.message = (
                (False, self._inactive()) if self._inactive() else self.server.request(kind))
            return response
        return call

    def _typed_service(self, kind: str):
        def call(request, response):
            if self._inactive():
                response.success, response.message = False, self._inactive()
                return response
            answer = self.server.call(
                kind, seed=getattr(request, 'seed', None),
                category=getattr(request, 'category', None) if kind == 'next_object' else None,
                k=getattr(request, 'k', None), room=request.room)
            response.success = answer.ok
            response.message = '' if answer.ok else answer.message
            if hasattr(response, 'seed'):
                response.seed = -1 if answer.seed is None else answer.seed
            if hasattr(response, 'objects'):
                response.objects = [object_msg(o.to_dict(), request.room)
                                    for o in answer.objects]
            elif hasattr(response, 'object') and answer.objects:
                response.object = object_msg(answer.objects[0].to_dict(), request.room)
            return response
        return call

    def _furnish(self, goal_handle) -> Furnish.Result:
        goal = goal_handle.request
        result = Furnish.Result()
        server = self.server        # a cleanup meanwhile releases it
        answer = (self._furnish_goal(server, goal, goal_handle) if server is not None
                  else Answer(False, self._inactive() or 'the node is not configured'))
        result.success = answer.ok
        if answer.ok and answer.served is not None:
            result.scene_json = answer.served.json
            result.scene = scene_msg(answer.served.json, server.config.frame_id,
                                     self.get_clock().now().to_msg())
        else:
            result.message = answer.message
        if answer.ok:
            goal_handle.succeed()
        elif goal_handle.is_cancel_requested:
            goal_handle.canceled()
        else:
            goal_handle.abort()
        return result

    @staticmethod
    def _furnish_goal(server: SceneServer, goal, goal_handle) -> Answer:
        try:
            stated = robot_radius_reach_clearance(goal.robot)
            robot = None if stated is None else Robot(*stated)
        except ValueError as e:
            return Answer(False, sentence(e))

        def told(obj, objects: int, seconds: float) -> None:
            goal_handle.publish_feedback(Furnish.Feedback(
                object=object_msg(obj.to_dict()), objects=objects, seconds=seconds))
        return server.furnish(goal.layout_text or layout_dict(goal.layout),
                              seed=goal.seed, for_robot=robot, on_object=told,
                              cancelled=lambda: goal_handle.is_cancel_requested)

    def _on_parameters(self, params: list[Parameter]) -> SetParametersResult:
        # Parameters the node does not own (use_sim_time, what rclpy declares) pass through
        # to rclpy; so does the node's own update of ``seed`` after a request took one.
        ours = {p.name: p.value for p in params if p.name in PARAMETERS
                and not (p.name == 'seed' and getattr(self._updating_seed, 'on', False))}
        if not ours:
            return SetParametersResult(successful=True)
        try:
            if self.server is None:     # unconfigured: configure reads and checks them all
                for name, value in ours.items():
                    check(name, value)
            else:
                self.server.reconfigure(ours)
        except ConfigError as e:
            self._log('warn', f'parameter change refused: {e}')
            return SetParametersResult(successful=False, reason=str(e))
        return SetParametersResult(successful=True)

    def _show_next_seed(self, seed: int) -> None:
        """Make the ``seed`` parameter read as the seed the next request will use."""
        self._updating_seed.on = True
        try:
            # What the server holds now: a user's change meanwhile wins over ``seed``.
            self.set_parameters([Parameter('seed', value=self.server.next_seed)])
        except Exception:       # the context is going away during shutdown
            pass
        finally:
            self._updating_seed.on = False

    # ---- outputs --------------------------------------------------------------------------
    def _publish_room(self, served: Served) -> None:
        cfg = self.server.config
        stamp = self.get_clock().now().to_msg()
        array = MarkerArray()
        clear = Marker(action=Marker.DELETEALL)
        clear.header.frame_id, clear.header.stamp = cfg.frame_id, stamp
        array.markers.append(clear)
        scene = served.scene
        markers = house_markers if isinstance(scene, HouseScene) else scene_markers
        for spec in markers(scene, cfg.marker_style, served.catalog, served.vocabulary):
            m = Marker(ns=spec.ns, id=spec.id, type=_KINDS[spec.kind], action=Marker.ADD)
            m.header.frame_id, m.header.stamp = cfg.frame_id, stamp
            m.pose = pose(spec.position, spec.yaw)
            m.scale.x, m.scale.y, m.scale.z = (float(v) for v in spec.scale)
            m.color = ColorRGBA(r=spec.color[0], g=spec.color[1], b=spec.color[2],
                                a=spec.color[3])
            m.text = spec.text
            m.mesh_resource = spec.mesh_resource
            # The shipped OBJs have their materials; a user's STL is painted by ``color``.
            m.mesh_use_embedded_materials = bool(spec.mesh_resource) and spec.mesh_materials
            m.points = [Point(x=p[0], y=p[1], z=p[2]) for p in spec.points]
            array.markers.append(m)
        poses = PoseArray()
        poses.header.frame_id, poses.header.stamp = cfg.frame_id, stamp
        objects = ([o for _, o in scene.objects()] if isinstance(scene, HouseScene)
                   else scene.objects)
        poses.poses = [pose(o.position, o.yaw) for o in objects]
        self.markers_pub.publish(array)
        self.poses_pub.publish(poses)
        self.scene_pub.publish(String(data=served.json))
        if served.map is not None:
            self.map_pub.publish(occupancy_message(served.map, cfg.frame_id, stamp))
        added = f', {len(served.added)} added in {served.seconds:.2f} s' if served.added else ''
        seed = '' if served.seed is None else f' (seed {served.seed})'
        what = (f'a house of {len(scene.scenes)} rooms' if isinstance(scene, HouseScene)
                else scene.room.room_type)
        self.get_logger().info(f'{served.source}: {what} with {len(objects)} objects'
                               f'{added}{seed}')

    def _publish_diagnostics(self, status: Status | None = None) -> None:
        if status is None and self.server is None:
            status = Status(level=ERROR if self._configure_error else OK,
                            message=self._configure_error or 'unconfigured: waiting for a '
                            'lifecycle manager to configure it')
        status = status or self.server.status
        array = DiagnosticArray()
        array.header.stamp = self.get_clock().now().to_msg()
        array.status = [DiagnosticStatus(
            level=bytes([status.level]),
            name=f'{self.get_fully_qualified_name()}: scene synthesis',
            message=status.message, hardware_id='scene_synth_ros',
            values=[KeyValue(key=k, value=v) for k, v in status.values().items()])]
        try:
            self.diag_pub.publish(array)
        except Exception:   # the context is going away during shutdown
            pass

    def _log(self, level: str, text: str) -> None:
        # One call per severity: rclpy keys a logger's settings by the calling line and
        # refuses a second severity from the same line.
        text = sentence(text)
        logger = self.get_logger()
        if level == 'error':
            logger.error(text)
        elif level == 'warn':
            logger.warning(text)
        else:
            logger.info(text)

    def destroy_node(self):
        self._release()
        super().destroy_node()


def _own(profile: QoSProfile) -> QoSProfile:
    """A copy of ``profile`` for one endpoint: rclpy writes a QoS override into the profile
    it is given, which would change every endpoint sharing it."""
    return QoSProfile(history=profile.history, depth=profile.depth,
                      reliability=profile.reliability, durability=profile.durability)


def _as_floats(params: list[Parameter]) -> list[Parameter]:
    """`ros2 param set location_temperature 1` sends an integer: set the double it means,
    so the parameter stays a double (describe, dump) and rclpy's type check passes."""
    floats = {name for name, (_, limits, _) in PARAMETERS.items()
              if isinstance(limits, tuple) and limits and isinstance(limits[0], float)}
    return [Parameter(p.name, value=float(p.value))
            if p.name in floats and p.type_ == Parameter.Type.INTEGER else p for p in params]


def usage() -> str:
    """What ``scene_synth_node --help`` prints: how to run it, its parameters, topics and
    services."""
    defaults = ServerConfig()
    lines = [f'usage: ros2 run scene_synth_ros {NODE_NAME} [--ros-args -p NAME:=VALUE ... '
             f'--params-file FILE -r __ns:=/NAMESPACE]',
             '',
             'Furnishes empty rooms (Ritchie et al., CVPR 2019). Names starting with ~/ are',
             f'under the node: /{NODE_NAME}/... by default. A lifecycle node: it configures',
             'and activates itself unless autostart is false (then: ros2 lifecycle set).',
             '', 'parameters (default; ros2 param describe tells more):']
    for name, (text, _, read_only) in PARAMETERS.items():
        value = getattr(defaults, name)
        shown = str(value).lower() if isinstance(value, bool) else repr(value) \
            if isinstance(value, str) else value
        lines.append(f'  {name} ({shown}{", read-only" if read_only else ""}): {text}')
    lines += ['', 'subscriptions:',
              '  ~/room_layout   std_msgs/String: a room layout as JSON or YAML '
              '(msg_schemas/room_layout.schema.json);',
              '                  reliable, also latched (transient local) before the start',
              '  ~/room_polygon  geometry_msgs/PolygonStamped: a floor outline of room_type',
              '', 'publications:',
              '  ~/scene         std_msgs/String: the furnished room as JSON',
              '  ~/markers       visualization_msgs/MarkerArray',
              '  ~/poses         geometry_msgs/PoseArray: one pose per object',
              '  ~/map           nav_msgs/OccupancyGrid: the room as map_server would serve '
              'it',
              '                  (map_resolution, map_scan_height; docs/navigation.md)',
              '                  (these four reliable and transient local, depth 1)',
              '  /diagnostics    diagnostic_msgs/DiagnosticArray, once a second',
              '', 'action (ros2 interface show scene_synth_msgs/action/Furnish):',
              '  ~/furnish       furnish a layout (typed or as text) with a seed and a robot;',
              '                  feedback per object placed, the scene as the result',
              '', 'typed services (scene_synth_msgs/srv/...; the request carries its arguments):',
              '  ~/insert_object    InsertObject: one more object (category, seed)',
              '  ~/suggest_objects  SuggestObjects: k proposals (k, seed), changing nothing',
              '  ~/clear_objects    ClearObjects: remove every object',
              '', 'services of the JSON interface (std_srvs/Trigger; the answer is JSON in '
              'message):',
              '  ~/generate      furnish the current room again from empty, with the next seed',
              '  ~/next_object   insert one object (of next_category, if set)',
              '  ~/suggest       propose `suggestions` objects, changing nothing',
              '  ~/reset         remove every object']
    return '\n'.join(lines)


def _command_line(args: list[str] | None) -> int | None:
    """Handle what is not a ROS argument: --help prints the usage (exit 0); anything else is
    a mistake said in one line (exit 2). None when there is nothing to handle."""
    rest = remove_ros_args(sys.argv if args is None else ['scene_synth_node', *args])[1:]
    if not rest:
        return None
    if rest[0] in ('-h', '--help'):
        print(usage())
        return 0
    print(f'{NODE_NAME}: unexpected argument {rest[0]!r}; parameters and remappings go after '
          f'--ros-args (e.g. {NODE_NAME} --ros-args -p room_type:=office); --help lists them',
          file=sys.stderr)
    return 2


def steady_middleware() -> Path | None:
    """Point Fast DDS at ``FASTDDS_PROFILES`` (through the environment, before rclpy starts)
    unless the user configured it or chose another middleware. Returns the profile's file,
    which may be removed once the node exists, or None when nothing was changed."""
    if (any(k in os.environ for k in _FASTDDS_SETTINGS)
            or Path('DEFAULT_FASTRTPS_PROFILES.xml').exists()       # Fast DDS reads that one
            or not os.environ.get('RMW_IMPLEMENTATION', 'rmw_fastrtps_cpp').startswith(
                'rmw_fastrtps')):
        return None
    try:
        fd, name = tempfile.mkstemp(prefix='scene_synth_fastdds_', suffix='.xml')
        with os.fdopen(fd, 'w') as f:
            f.write(FASTDDS_PROFILES)
    except OSError:         # no writable temporary directory: Fast DDS's defaults, as before
        return None
    os.environ['FASTRTPS_DEFAULT_PROFILES_FILE'] = name
    os.environ['RMW_FASTRTPS_USE_QOS_FROM_XML'] = '1'
    return Path(name)


def _settle(executor: MultiThreadedExecutor, timeout: float) -> None:
    """Let every callback the executor has handed to its threads run to its end, and take
    its outcome, before the executor and node go.

    A callback still running when the node is destroyed, or one handed over by the last
    spin that starts only after ``Executor.shutdown`` has destroyed its guard condition,
    fails with "cannot use Destroyable", which rclpy prints at exit as an exception never
    retrieved. ``Executor.shutdown`` is meant to wait for them, but in Jazzy's rclpy it sets
    its flag before testing it and returns at once, and its count of work in progress
    starts only once a callback runs; so wait on the handed-over callbacks themselves."""
    handlers = list(getattr(executor, '_futures', ()))
    deadline = time.monotonic() + timeout
    while any(not h.done() for h in handlers) and time.monotonic() < deadline:
        time.sleep(0.01)
    for h in handlers:
        if h.done():
            try:
                h.result()
            except Exception:   # noqa: BLE001 - a callback cut short by the shutdown itself
                pass


def main(args: list[str] | None = None) -> int:
    handled = _command_line(args)
    if handled is not None:
        return handled
    steady_allocator()      # before the threads and the first messages
    profile = steady_middleware()
    # SIGINT and SIGTERM only raise a flag that the spin loop checks: letting rclpy's own
    # handlers shut the context down under a multi-threaded executor races with its wait set.
    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.set())
    node = None
    code = 0
    try:
        rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
        try:
            node = SceneSynthNode()
        finally:
            if profile is not None:        # read by now: no file left behind
                profile.unlink(missing_ok=True)
        if node.get_parameter('autostart').value:
            node.start()
        executor = MultiThreadedExecutor(num_threads=EXECUTOR_THREADS)
        executor.add_node(node)
        while not stop.is_set() and not node.finalized.is_set() and rclpy.ok():
            executor.spin_once(timeout_sec=0.2)
        node.get_logger().info('shutting down')
        # Answer the calls waiting for the worker first: their callbacks hold the executor's
        # threads, which its shutdown waits for.
        if node.server is not None:
            node.server.close(timeout=STOP_WAIT)
        _settle(executor, STOP_WAIT)
        executor.shutdown(timeout_sec=2.0)
    except StartupError as e:
        print(f'{NODE_NAME}: cannot start: {e}', file=sys.stderr)
        code = EXIT_STARTUP_FAILED
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
    return code


if __name__ == '__main__':
    sys.exit(main())
