"""What the ROS node does, without ROS: a current room, a worker that furnishes it, and the
requests that change it.

The node (``node.py``) only turns messages into calls of ``SceneServer`` and the results
into messages. Everything here is plain Python so it can be driven and tested from a prompt.

One worker thread runs every synthesis, so subscriptions and services are never blocked by
the networks. It serves the cheapest kind of request first (``RANK``), in arrival order
within a kind, and runs short calls between two insertions of a ``generate`` (see
``_between``). A room layout supersedes whatever came before it: the synthesis in progress
is cancelled between two insertions and older queued requests are answered at once, so only
complete rooms for the latest layout are ever handed out. Bad input is rejected with one
sentence; the current room stays as it was.
"""
from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
import itertools
import json
import os
from pathlib import Path
import textwrap
import threading
import time
from typing import Any, Callable

import yaml

from .catalog import PROCEDURAL, Catalog
from .categories import PAPER, ROOM_TYPE_ALIASES, ROOM_TYPES, Vocabulary
from .errors import (
    CatalogError,
    ConfigError,
    SceneSynthError,
    UnknownRoomType,
    quoted,
    quoted_list,
    sentence,
    with_article,
)
from .export import FORMATS as EXPORT_FORMATS
from .export import UnknownFormat, parse_formats, write
from .files import write_atomic
from .house import HouseScene, count_objects
from .house_synth import check_house_fits, furnish_house
from .markers import MARKER_STYLES
from .networks.config import device_name
from .networks.runtime import set_threads
from .occupancy import OccupancyGrid, occupancy_grid
from .rules import robot
from .rules.robot import Robot, RobotReport
from .scene import PlacedObject, Scene
from .schema import dump_house_scene, dump_scene, parse_layout
from .synth import MODULES, SynthConfig, SynthesisCancelled, Synthesizer, check_room_fits
from .synth_config import MapConfig, check_value, setting, settings_of, shared
from .user_catalog import load_catalog

OK, WARN, ERROR = 0, 1, 2               # the levels of diagnostic_msgs/DiagnosticStatus
CATALOG_FILE = 'catalog.json'           # what `scene-synth catalog build FOLDER` writes
SERVICE_TIMEOUT = 120.0                 # seconds a service waits for the worker


@dataclass
class ServerConfig:
    """The node's parameters (same names) with their defaults, each with its ``Setting``
    (``synth_config``): the synthesis settings the node exposes are those of
    ``SynthConfig`` (``shared``), the rest are the node's own."""

    room_type: str = setting(
        'bedroom', 'room type of layouts arriving on ~/room_polygon, one of those of the '
        'weights: the shipped weights have ' + ', '.join(ROOM_TYPES) + ' (also accepted: '
        'aliases such as ' + ', '.join(f"'{a}'" for a in list(ROOM_TYPE_ALIASES)[:4]) + '); '
        'weights trained on an imported data set, its room types')
    seed: int = setting(
        0, 'seed of the next room, object or suggestion; reads as the one the next request '
        'will use (each request takes the next integer); set it to replay a room',
        bounds=(0, 2**31 - 1))
    location_temperature: float = shared('location_temperature')
    max_objects: int = shared('max_objects')
    device: str = shared('device', 'auto')
    runtime: str = shared('runtime')
    weights_dir: str = setting(
        '', "directory of <room type>.pt bundles; '' = the shipped weights")
    catalog_dir: str = setting(
        '', 'folder holding a catalog.json written by `scene-synth catalog build` (or that '
        "file): your models for the categories it covers; '' = the procedural catalog")
    frame_id: str = setting('map', 'frame of the published markers, poses and of incoming '
                            'polygons')
    marker_style: str = setting('cube', 'objects as boxes (cube) or catalog meshes (mesh)',
                                choices=MARKER_STYLES)
    auto_generate: bool = setting(True, 'furnish a room as soon as its layout arrives')
    autostart: bool = setting(
        True, 'configure and activate the node as it starts; false: it waits, unconfigured, '
        'for a lifecycle manager (ros2 lifecycle set, nav2 lifecycle_manager)',
        read_only=True)
    wall_height: float = setting(2.6, 'wall height of rooms arriving on ~/room_polygon (m)',
                                 bounds=(1.8, 6.0))
    export_dir: str = setting(
        '', "write every room served here as JSON and in each of export_formats; '' = off")
    export_formats: str = setting(
        'sdf,gltf', 'formats written to export_dir, a comma list of: '
        + ', '.join(EXPORT_FORMATS))
    # One thread, as the node shares its cores with its clients.
    torch_threads: int = setting(1, 'CPU threads the networks may use (torch or onnxruntime)',
                                 bounds=(1, 64),
                                 read_only=True)
    max_pending: int = setting(
        8, 'service calls that may wait ahead of a call (reset and next_object are served '
        'before generate and suggest); one more is answered "busy" at once', bounds=(1, 12))
    next_category: str = setting(
        '', "category of the objects ~/next_object inserts (e.g. office_chair); '' = the "
        'category module chooses')
    suggestions: int = setting(5, 'how many proposals ~/suggest answers with', bounds=(1, 20))
    robot_radius: float = shared('robot_radius')
    robot_reach: float = shared('robot_reach')
    robot_clearance: float = shared('robot_clearance')
    map_resolution: float = shared('map_resolution')
    map_scan_height: float = shared('map_scan_height')


# name -> (description, numeric range or allowed strings, read only), from ServerConfig's
# settings. The node builds its parameter descriptors from this table, and ``check``
# enforces the same limits.
_SETTINGS = settings_of(ServerConfig)
PARAMETERS: dict[str, tuple[str, Any, bool]] = {
    name: (s.description, s.limits, s.read_only) for name, (s, _) in _SETTINGS.items()}

# The head of config/scene_synth_node.yaml (``parameters_file``).
_FILE_HEAD = """\
# Parameters of scene_synth_node with their defaults, in the format of
#   ros2 run scene_synth_ros scene_synth_node --ros-args --params-file <this file>
# Copy it, change what you need. Each parameter's meaning and range is above it; the same
# as `ros2 param describe` and `ros2 run scene_synth_ros scene_synth_node --help` say.
# The key /** applies it to the node under any name and namespace (-r __ns:=/sim).
# Written from the parameters' table by scene_synth_ros.server.parameters_file().
/**:
  ros__parameters:"""


def parameters_file() -> str:
    """The text of ``config/scene_synth_node.yaml``: every parameter with its default, under
    its description and range (a test holds the shipped file to it). To write it again:
    ``python -c "from scene_synth_ros.server import parameters_file as f; print(f(), end='')"
    > config/scene_synth_node.yaml``."""
    lines = [_FILE_HEAD]
    for name, (s, default) in _SETTINGS.items():
        about = s.description + (f'; {s.limits_text()}' if s.limits is not None else '')
        if s.read_only:
            about += '; read-only'
        lines += [f'    # {line}' for line in textwrap.wrap(about, 88)]
        lines.append('    ' + yaml.safe_dump({name: default}, width=1000).strip())
    return '\n'.join(lines) + '\n'


REQUESTS = ('generate', 'next_object', 'reset', 'suggest')
# The worker's order, by what a request costs: a layout first (it supersedes everything
# queued), then the calls of one insertion at most (reset: none), then the whole-room ones.
# Calls from different clients have no order of their own, so serving a 30 ms call before a
# 300 ms one that came earlier breaks no promise, and keeps short calls short under load.
RANK = {'layout': 0, 'reset': 1, 'next_object': 1, 'suggest': 2, 'generate': 2}
SHORT = 1
# A whole-room call that has waited this long (the bound for a generate) ranks with
# the short ones, in arrival order: short calls overtake it for a while, never for ever. A
# shorter time put short calls behind whole rooms as soon as the queue was long (node_load).
PROMOTE_AFTER = 5.0


# Checked once the weights are loaded: their data set may define room types and categories
# (a user catalog may hold models of those categories).
BY_WEIGHTS = ('room_type', 'next_category', 'catalog_dir')


def _check_weights_hold(config: ServerConfig, synth: Synthesizer) -> None:
    """ConfigError unless the weights in use have a bundle for ``config.room_type``."""
    if config.room_type not in synth.room_types:
        raise ConfigError(f'room_type {config.room_type!r} has no weights in '
                          f'{config.weights_dir or "the package"}; they have '
                          f'{", ".join(synth.room_types) or "none"}')


def load_catalog_dir(value: str, vocabulary: Vocabulary = PAPER) -> Catalog:
    """The catalog the parameter ``catalog_dir`` names: the procedural one for '', else the
    ``catalog.json`` in that folder (or the file itself), of the categories of
    ``vocabulary``; ConfigError saying what is wrong."""
    if not value:
        return PROCEDURAL
    path = Path(value).expanduser()
    if path.is_dir():
        path = path / CATALOG_FILE
        if not path.is_file():
            raise ConfigError(f'catalog_dir {quoted(value)} holds no {CATALOG_FILE} '
                              f'(`scene-synth catalog build FOLDER` writes one)')
    elif not path.exists():
        raise ConfigError(f'catalog_dir {quoted(value)} does not exist')
    try:
        return load_catalog(path, vocabulary)
    except CatalogError as e:
        raise ConfigError(f'catalog_dir {quoted(value)} cannot be used: {e}') from None


def check(name: str, value: Any, vocabulary: Vocabulary = PAPER) -> Any:
    """``value`` for parameter ``name``, normalised, or ConfigError saying why not; a room
    type or category is one of ``vocabulary`` (the weights' in use, ``BY_WEIGHTS``)."""
    if name not in _SETTINGS:
        raise ConfigError(f'{name} is not a parameter of scene_synth_node')
    value = check_value(name, value, _SETTINGS[name][0])
    return _check_text(name, value, vocabulary) if isinstance(value, str) else value


def _check_text(name: str, value: str, vocabulary: Vocabulary = PAPER) -> str:
    """What a string parameter must be beyond its choices."""
    if name == 'room_type':
        try:
            return vocabulary.resolve(value)
        except UnknownRoomType:
            raise ConfigError(f'room_type {quoted(value)} is not one of '
                              f'{", ".join(vocabulary.room_types)}') from None
    if name == 'device':
        try:
            device_name(value)
        except ValueError as e:
            raise ConfigError(str(e)) from None
    if name == 'next_category' and value:
        value = ' '.join(value.replace('_', ' ').lower().split())     # office_chair too
        try:
            vocabulary.info(value)
        except KeyError:
            raise ConfigError(f'next_category {quoted(value)} is not a category '
                              f'(`scene-synth catalog list` shows them)') from None
    if name == 'frame_id' and (not value or any(c.isspace() for c in value)):
        raise ConfigError(f'frame_id must be a non-empty name without spaces, got {value!r}')
    if name == 'export_formats':
        try:
            return ','.join(parse_formats(value))
        except UnknownFormat as e:
            raise ConfigError(str(e)) from None
    if name in ('catalog_dir', 'export_dir') and value:
        _check_folder(name, value, vocabulary)
    return value


def _check_folder(name: str, value: str, vocabulary: Vocabulary = PAPER) -> None:
    """catalog_dir: its catalog reads; export_dir: it exists (made now) and is writable."""
    if name == 'catalog_dir':
        load_catalog_dir(value, vocabulary)
        return
    p = Path(value).expanduser()
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise ConfigError(f'{name} {value!r} cannot be created: {e.strerror}') from None
    if not os.access(p, os.W_OK):
        raise ConfigError(f'{name} {value!r} is not writable')


@dataclass
class Served:
    """A room or a house handed to the publisher: the scene and how it came about."""

    scene: Scene | HouseScene
    source: str           # 'room_layout', 'room_polygon', 'generate', 'next_object', 'reset'
    seed: int | None
    added: list[PlacedObject] = field(default_factory=list)
    seconds: float = 0.0
    stopped: str = ''
    timings: dict[str, float] = field(default_factory=dict)
    json: str = ''                       # the scene as published on ~/scene
    robot: RobotReport | None = None     # the robot promise, when synthesis measured it
    rooms_robot: dict[str, RobotReport] = field(default_factory=dict)   # a house's, by room
    map: OccupancyGrid | None = None     # the room for a navigation stack, as ~/map has it
    catalog: Catalog = PROCEDURAL        # whose model ids the scene holds (catalog_dir)
    vocabulary: Vocabulary = PAPER       # whose room types and categories (the weights')


@dataclass
class Status:
    """What /diagnostics reports."""

    level: int = OK
    message: str = 'waiting for a room layout'
    last_error: str = ''
    rooms_served: int = 0
    inputs_rejected: int = 0
    requests_superseded: int = 0
    requests_busy: int = 0               # calls answered "busy" (max_pending were ahead)
    busy: bool = False
    objects: int = 0
    room_type: str = ''
    seed: int | None = None
    last_seconds: float = 0.0
    timings: dict[str, float] = field(default_factory=dict)

    def values(self) -> dict[str, str]:
        """Key/value pairs for a DiagnosticStatus."""
        out = {'rooms served': str(self.rooms_served),
               'inputs rejected': str(self.inputs_rejected),
               'requests superseded': str(self.requests_superseded),
               'requests answered busy': str(self.requests_busy),
               'busy': str(self.busy).lower(),
               'room type': self.room_type, 'objects': str(self.objects),
               'seed': '' if self.seed is None else str(self.seed),
               'last room seconds': f'{self.last_seconds:.3f}',
               'last error': self.last_error}
        for k in MODULES:
            out[f'{k} ms'] = f'{1000 * self.timings.get(k, 0.0):.1f}'
        return out


@dataclass
class _Job:
    kind: str                             # 'layout' or one of REQUESTS
    epoch: int
    seq: int = 0                          # arrival order
    queued: float = 0.0                   # time.monotonic() of its arrival
    scene: Scene | HouseScene | None = None
    room: str = ''                        # the room of the house a request acts on
    source: str = ''                      # where a layout came from: the topic's name
    done: threading.Event = field(default_factory=threading.Event)
    ok: bool = False
    message: str = ''
    abandoned: bool = False               # its caller stopped waiting: do not run it
    # What a typed request states itself (None: the node's parameters decide).
    seed: int | None = None
    category: str | None = None
    k: int | None = None
    robot: Robot | None = None
    furnish: bool = False                 # a layout furnished whatever auto_generate says
    on_object: Callable[[PlacedObject, int, float], None] | None = None
    cancelled: Callable[[], bool] | None = None
    # The typed answer: the room served, or the objects proposed or inserted.
    served: Served | None = None
    objects: list[PlacedObject] = field(default_factory=list)
    used_seed: int | None = None


@dataclass
class Answer:
    """What a request or a furnishing ended with: ``message`` is the JSON text the Trigger
    services answer on success and one sentence on failure; the rest is typed."""

    ok: bool
    message: str
    seed: int | None = None
    objects: list[PlacedObject] = field(default_factory=list)
    served: Served | None = None


class SceneServer:
    """The current room and the worker that furnishes it.

    ``publish(served)`` is called from the worker thread with every complete room;
    ``on_status(status)`` whenever the status changes; ``on_seed(seed)`` whenever the seed
    the next request will use changes (not when ``reconfigure`` sets it). Construction
    reads and checks every room type's weights, readies the calls of ``room_type`` (the
    others' at their first room) and raises ``BundleError`` (naming the file) or
    ``ConfigError``.
    """

    def __init__(self, config: ServerConfig, publish: Callable[[Served], None],
                 on_status: Callable[[Status], None] | None = None,
                 log: Callable[[str, str], None] | None = None,
                 on_seed: Callable[[int], None] | None = None):
        # The weights come first: those trained on an imported data set define the room types
        # and categories that room_type and next_category are checked against.
        for f in fields(ServerConfig):
            if f.name not in BY_WEIGHTS:
                setattr(config, f.name, check(f.name, getattr(config, f.name)))
        set_threads(config.torch_threads)
        self._synth = self._load(config.weights_dir, config.device, config.runtime)
        for name in BY_WEIGHTS:
            setattr(config, name, check(name, getattr(config, name), self._synth.vocabulary))
        _check_weights_hold(config, self._synth)
        # The calls of the room type served by default are readied now, the others' at their
        # first room (0.1 s each with their graphs in the cache): a shorter start.
        self._synth.prepare(config.room_type)
        robot_of(config)
        self.config = config
        # read once by check: cached
        self._catalog = load_catalog_dir(config.catalog_dir, self._synth.vocabulary)
        self._publish = publish
        self._on_status = on_status or (lambda s: None)
        self._logger = log or (lambda level, text: None)
        self._on_seed = on_seed or (lambda seed: None)
        self._lock = threading.Lock()
        self._epoch = 0                    # bumped by every accepted layout
        self._next_seed = config.seed
        self._scene: Scene | HouseScene | None = None
        self.status = Status()
        self._jobs: list[_Job] = []        # queued for the worker (a handful: no heap needed)
        self._wake = threading.Condition(self._lock)
        self._arrivals = itertools.count()
        self._calls: list[_Job] = []       # service calls queued or running, not yet answered
        self._closing = False
        self._worker = threading.Thread(target=self._run, name='scene_synth_worker',
                                        daemon=True)
        self._worker.start()

    # ---- set-up and parameters ------------------------------------------------------------
    @staticmethod
    def _load(weights_dir: str, device: str, runtime: str) -> Synthesizer:
        synth = Synthesizer(Path(weights_dir).expanduser() if weights_dir else None,
                            SynthConfig(device=device, runtime=runtime))
        synth.load_all(ready=())        # a bad weights file is said now, not at a room
        return synth

    def reconfigure(self, changes: dict[str, Any]) -> None:
        """Apply parameter changes, all or none; ConfigError names the first bad one."""
        checked = {name: check(name, value) for name, value in changes.items()
                   if name not in BY_WEIGHTS}
        for name in checked:
            if PARAMETERS[name][2] and checked[name] != getattr(self.config, name):
                raise ConfigError(f'{name} is read-only: set it when the node starts')
        new = replace(self.config, **checked)
        synth = None
        loaded = ('weights_dir', 'device', 'runtime')
        changed = [n for n in loaded if getattr(new, n) != getattr(self.config, n)]
        what = ', '.join(f'{n} {quoted(getattr(new, n))}' for n in changed)
        if changed:
            try:
                synth = self._load(new.weights_dir, new.device, new.runtime)
            except SceneSynthError as e:
                raise ConfigError(f'{what} cannot be used: {e}') from None
        late = {name: check(name, value, (synth or self._synth).vocabulary)
                for name, value in changes.items() if name in BY_WEIGHTS}
        new = replace(new, **late)
        _check_weights_hold(new, synth or self._synth)
        if synth is not None:
            try:
                synth.prepare(new.room_type)
            except SceneSynthError as e:
                raise ConfigError(f'{what} cannot be used: {e}') from None
        robot_of(new)
        # Read again when it changed, or when other weights may define its categories.
        models = load_catalog_dir(new.catalog_dir, (synth or self._synth).vocabulary) \
            if 'catalog_dir' in late or synth is not None else None
        with self._lock:
            self.config = new
            if synth is not None:
                self._synth = synth
            if models is not None:
                self._catalog = models
            if 'seed' in checked:
                self._next_seed = new.seed

    # ---- requests (any thread) ------------------------------------------------------------
    def submit_layout(self, payload: Any, source: str = 'room_layout') -> bool:
        """Queue a room layout (JSON text or dict); False, with the reason on the status,
        when it is rejected."""
        return isinstance(self._accept_layout(payload, source), _Job)

    def furnish(self, payload: Any, seed: int | None = None, for_robot: Robot | None = None,
                on_object: Callable[[PlacedObject, int, float], None] | None = None,
                cancelled: Callable[[], bool] | None = None,
                source: str = 'furnish') -> Answer:
        """Furnish the room layout ``payload`` (JSON or YAML text, or a dict) and wait for
        it, whatever ``auto_generate`` says: it becomes the current room, as a layout on the
        topic does, and supersedes what came before. ``seed`` None takes the node's next
        seed; ``for_robot`` None the node's robot. ``on_object(obj, objects, seconds)`` is told
        of each object placed; ``cancelled()`` is asked between insertions."""
        seed, wrong = _seed_arg(seed)
        if wrong:
            return Answer(False, wrong)
        job = self._accept_layout(payload, source, seed=seed, robot=for_robot, furnish=True,
                                  on_object=on_object, cancelled=cancelled)
        if not isinstance(job, _Job):
            return Answer(False, job)
        # Not one of the calls that max_pending counts: a layout is served before them all.
        # close() answers it, queued or running, so the wait ends.
        job.done.wait()
        return Answer(job.ok, job.message, job.used_seed, job.objects, job.served)

    def _accept_layout(self, payload: Any, source: str, **what) -> _Job | str:
        """The queued job of a room or house layout, or why it was rejected (also on the
        status)."""
        with self._lock:
            models, vocabulary = self._catalog, self._synth.vocabulary
        try:
            scene = parse_layout(payload, models, vocabulary)
            if isinstance(scene, Scene):
                check_room_fits(scene.room, vocabulary)
            else:
                check_house_fits(scene.house, vocabulary)
        except SceneSynthError as e:
            self._reject(f'{source}: {e}')
            return sentence(e)
        with self._lock:
            if self._closing:
                return 'the node is shutting down'
            self._epoch += 1
            job = self._queue('layout', scene=scene, source=source, **what)
            # What was queued before it is for an older room: answered now, not after this
            # layout is furnished (it is served first).
            stale = [j for j in self._jobs if self._stale(j)]
            self._jobs = [j for j in self._jobs if not self._stale(j)]
        for old in stale:
            self._supersede(old)
            old.done.set()
        return job

    def submit_polygon(self, points, frame_id: str = '') -> bool:
        """Queue a bare floor outline ((x, y[, z]) points) as a room of the configured type
        and wall height, without doors or windows."""
        cfg = self.config
        if frame_id and frame_id != cfg.frame_id:
            self._reject(f'room_polygon: the polygon is in frame {frame_id!r} but the node '
                         f'works in {cfg.frame_id!r} (parameter frame_id)')
            return False
        layout = {'room_type': cfg.room_type, 'wall_height': cfg.wall_height,
                  'floor': [[float(p[0]), float(p[1])] for p in points],
                  'doors': [], 'windows': []}
        return self.submit_layout(layout, 'room_polygon')

    def request(self, kind: str, timeout: float = SERVICE_TIMEOUT) -> tuple[bool, str]:
        """Run one of ``REQUESTS`` on the current room with the node's parameters; returns
        (success, JSON text or reason). ``suggest`` answers proposals and changes nothing."""
        answer = self.call(kind, timeout)
        return answer.ok, answer.message

    def call(self, kind: str, timeout: float = SERVICE_TIMEOUT, *, seed: int | None = None,
             category: str | None = None, k: int | None = None, room: str = '') -> Answer:
        """``request`` with its arguments stated, each None for the node's parameter:
        ``seed`` (-1 too), ``category`` of ``next_object`` ('' lets the category module
        choose), ``k`` proposals of ``suggest`` (0 too). ``room`` names the room of a house
        the request acts on: required by ``next_object`` and ``suggest`` while the node
        serves a house ('' makes ``generate`` and ``reset`` act on every room), and '' while
        it serves a single room."""
        if kind not in REQUESTS:
            raise ValueError(f'unknown request {kind!r}')
        seed, wrong = _seed_arg(seed)
        if wrong:
            return Answer(False, wrong)
        if category:
            try:
                category = check('next_category', category, self._synth.vocabulary)
            except ConfigError as e:
                return Answer(False, str(e).replace('next_category', 'category', 1))
        k = k or None
        if k is not None and not 1 <= k <= PARAMETERS['suggestions'][1][1]:
            return Answer(False, f'k {k} is out of range: 1 to '
                                 f'{PARAMETERS["suggestions"][1][1]}, or 0 for the parameter '
                                 f'suggestions')
        with self._lock:
            if self._closing:
                return Answer(False, 'the node is shutting down')
            # The load policy: a bounded wait, never a queue that grows with the callers.
            # Each waiting call holds one of the executor's threads; when ``max_pending``
            # calls would be served before this one, the caller learns at once that it should
            # call again. Only those count: a reset is not turned away because generates
            # wait, since it overtakes them.
            ahead = sum(1 for j in self._calls if RANK[j.kind] <= RANK[kind])
            busy = ahead >= self.config.max_pending
            if not busy:
                # under the lock: close() either drains it or was first
                job = self._queue(kind, seed=seed, category=category, k=k, room=room)
                self._calls.append(job)
        if busy:
            self._set_status(increment='requests_busy')
            return Answer(False, f'busy: {ahead} requests are already waiting for the '
                                 f'synthesis worker ahead of this one (max_pending); call '
                                 f'again shortly')
        try:
            if not job.done.wait(timeout):
                job.abandoned = True
                return Answer(False, f'{kind} did not finish within {timeout:.0f} s')
            return Answer(job.ok, job.message, job.used_seed, job.objects, job.served)
        finally:
            with self._lock:
                self._calls.remove(job)

    def _queue(self, kind: str, **what) -> _Job:
        """A new job for the worker; the caller holds the lock."""
        job = _Job(kind, self._epoch, next(self._arrivals), time.monotonic(), **what)
        self._jobs.append(job)
        self._wake.notify()
        return job

    @property
    def next_seed(self) -> int:
        """The seed the next request that draws will use."""
        with self._lock:
            return self._next_seed

    @property
    def scene(self) -> Scene | HouseScene | None:
        with self._lock:
            return None if self._scene is None else self._scene.copy()

    def close(self, timeout: float = 5.0) -> None:
        """Stop the worker after cancelling what it is doing; every call still waiting is
        answered at once that the node is shutting down."""
        with self._lock:
            self._closing = True
            self._epoch += 1               # cancels the synthesis under way
            waiting, self._jobs = self._jobs, []
            self._wake.notify_all()
        for job in waiting:
            job.ok, job.message = False, 'the node is shutting down'
            job.done.set()
        self._worker.join(timeout)

    # ---- the worker -----------------------------------------------------------------------
    def _run(self) -> None:
        while True:
            with self._lock:
                while not self._jobs and not self._closing:
                    self._wake.wait()
                if self._closing:
                    return
                job = self._take(short_only=False)
            self._serve(job)

    def _take(self, short_only: bool, before: int | None = None) -> _Job | None:
        """The queued job to serve next, removed from the queue (the caller holds the lock).
        With ``short_only``, only a short call that is next anyway and arrived before
        ``before``; else None."""
        if not self._jobs:
            return None
        now = time.monotonic()

        def order(j: _Job) -> tuple[int, int]:
            rank = RANK[j.kind]
            if rank > SHORT and now - j.queued >= PROMOTE_AFTER:
                rank = SHORT
            return rank, j.seq
        job = min(self._jobs, key=order)
        if short_only and (RANK[job.kind] != SHORT or (before is not None and job.seq > before)):
            return None
        self._jobs.remove(job)
        return job

    def _serve(self, job: _Job) -> None:
        try:
            self._execute(job)
        except Exception as e:   # a bug must not kill the worker: report it and go on
            text = sentence(e) or type(e).__name__
            job.ok, job.message = False, f'internal error in {job.kind}: {text}'
            self._set_status(level=ERROR, message=job.message, last_error=job.message)
            self._log('error', job.message)
        finally:
            self._set_status(busy=False)
            job.done.set()

    def _between(self, running: _Job) -> bool:
        """Asked by a running ``generate`` before each insertion: true when a newer layout
        superseded it. Else it first serves the short calls queued now (those that arrive
        meanwhile wait for the next insertion, so the generate still moves on).

        A generate starts from the empty room and only replaces the room at its end, so a
        reset or an object inserted meanwhile is the same as one served just before it: the
        short call need not wait for the whole room."""
        with self._lock:
            before = next(self._arrivals)
        while not self._stale(running):
            with self._lock:
                job = self._take(short_only=True, before=before)
            if job is None:
                return False
            self._serve(job)
            self._set_status(busy=True)
        return True

    def _stale(self, job: _Job) -> bool:
        return job.epoch != self._epoch

    def _execute(self, job: _Job) -> None:
        if job.abandoned:
            return
        if self._stale(job):
            self._supersede(job)
            return
        with self._lock:
            cfg, synth, current, models = self.config, self._synth, self._scene, self._catalog
        if job.kind == 'layout':
            base = job.scene
        elif current is None:
            job.message = ('no room yet: publish a layout on ~/room_layout or ~/room_polygon '
                           'first')
            return
        else:
            base = current
        if isinstance(base, HouseScene):
            self._execute_house(job, base, cfg, synth, models)
            return
        if job.room:
            job.message = (f'room {quoted(job.room)}: the node serves a single room, which '
                           f'has no room ids; leave room empty')
            return
        base = in_catalog(base, models, synth.vocabulary)
        if job.kind == 'reset':
            scene = Scene(base.room, [], _answered(base.meta))
            self._commit(job, Served(scene, 'reset', base.meta.get('seed'), catalog=models,
                                     vocabulary=synth.vocabulary))
            job.ok, job.message = True, '{"objects": 0}'
            return
        if job.kind == 'layout' and not cfg.auto_generate and not job.furnish:
            scene = base.copy()
            scene.meta = {'generator': 'scene_synth_ros', 'seed': None, **base.meta}
            self._commit(job, Served(scene, job.source, None, catalog=models,
                                     vocabulary=synth.vocabulary))
            job.ok = True
            return
        settings = self._settings(job, cfg, synth, models)
        seed = self._job_seed(job)
        try:
            if job.kind == 'next_object':
                category = cfg.next_category if job.category is None else job.category
                self._next_object(job, synth, base, seed, category, settings)
                return
            if job.kind == 'suggest':
                found = synth.suggest(base, job.k or cfg.suggestions, seed, config=settings)
                job.ok, job.objects = True, found
                job.message = _json({'seed': seed, 'objects': [o.to_dict() for o in found]})
                return
            if job.kind == 'generate':
                result = synth.complete(Scene(base.room, []), seed,
                                        cancel=lambda: self._between(job), config=settings)
            else:
                result = synth.complete(base, seed, cancel=lambda: self._stop_layout(job),
                                        config=settings, on_object=self._progress(job, base))
        except SynthesisCancelled:
            self._cancelled(job)
            return
        except SceneSynthError as e:
            self._refused(job, e)
            return
        served = Served(result.scene, job.source or job.kind, seed, result.added,
                        result.seconds, result.stopped, result.timings, robot=result.robot,
                        catalog=models, vocabulary=synth.vocabulary)
        if self._commit(job, served):
            job.ok, job.objects = True, result.added
            job.message = _json({'seed': seed, 'objects': len(result.scene),
                                 'added': [o.id for o in result.added],
                                 'stopped': result.stopped,
                                 'seconds': round(result.seconds, 4)})

    @staticmethod
    def _settings(job: _Job, cfg: ServerConfig, synth: Synthesizer,
                  models: Catalog) -> SynthConfig:
        """This job's settings, passed with each call: the synthesizer is shared."""
        return replace(synth.config, location_temperature=cfg.location_temperature,
                       max_objects=cfg.max_objects, robot=job.robot or robot_of(cfg),
                       catalog=models)

    def _job_seed(self, job: _Job) -> int:
        """The seed ``job`` draws with; a seed the request states leaves the node's own
        sequence where it is. The worker is busy from here on."""
        seed = job.used_seed = self._take_seed() if job.seed is None else job.seed
        self._set_status(busy=True)
        return seed

    def _refused(self, job: _Job, error: SceneSynthError) -> None:
        """``job``'s synthesis refused its input: said on the status and in the answer."""
        self._reject(f'{job.source or job.kind}: {error}')
        job.message = str(error)

    def _cancelled(self, job: _Job) -> None:
        if job.cancelled is not None and job.cancelled():
            job.message = 'cancelled'
        else:
            self._supersede(job)

    def _execute_house(self, job: _Job, base: HouseScene, cfg: ServerConfig,
                       synth: Synthesizer, models: Catalog) -> None:
        """``job`` on a house: a house layout, or a request on the house served now, on
        one room of it (``job.room``) or, for ``generate`` and ``reset``, on every room."""
        house = base.house
        if job.kind != 'layout':    # the layout's request id named the house that answered it
            house = replace(house, meta=_answered(house.meta))
        base = HouseScene(house, {rid: in_catalog(s, models, synth.vocabulary)
                                  for rid, s in base.scenes.items()}, _answered(base.meta))
        rid, rooms = job.room, list(base.house.rooms)
        if rid and rid not in base.scenes:
            job.message = (f'room {quoted(rid)} is not a room of the house served now; its '
                           f'rooms are {quoted_list(rooms)}')
            return
        if not rid and job.kind in ('next_object', 'suggest'):
            job.message = (f'{job.kind} acts on one room of the house served now: name it in '
                           f'room (one of {quoted_list(rooms)})')
            return
        served_as = dict(source=job.source or job.kind, catalog=models,
                         vocabulary=synth.vocabulary)
        if job.kind == 'reset':
            scenes = {r: Scene(s.room, [], {}) if r == rid or not rid else s
                      for r, s in base.scenes.items()}
            self._commit(job, Served(HouseScene(base.house, scenes, _answered(base.meta)),
                                     seed=base.meta.get('seed'), **served_as))
            job.ok, job.message = True, _json({'objects': sum(map(len, scenes.values()))})
            return
        if job.kind == 'layout' and not cfg.auto_generate and not job.furnish:
            given = HouseScene(base.house, base.scenes,
                               {'generator': 'scene_synth_ros', 'seed': None, **base.meta})
            self._commit(job, Served(given, seed=None, **served_as))
            job.ok = True
            return
        settings = self._settings(job, cfg, synth, models)
        seed = self._job_seed(job)

        def with_room(scene: Scene) -> HouseScene:
            # The house as it is now, not as it was when this job started: a generate of one
            # room serves short calls on the others meanwhile (``_between``), and keeps them.
            # (Within the job's epoch the house served is this one; else it is not committed.)
            with self._lock:
                now = self._scene
            scenes = dict((now if isinstance(now, HouseScene) else base).scenes)
            scenes[rid] = Scene(scene.room, scene.objects, {})
            return HouseScene(base.house, scenes,
                              {**_answered(base.meta), 'generator': 'scene_synth_ros',
                               'seed': seed})
        try:
            if job.kind == 'next_object':
                category = cfg.next_category if job.category is None else job.category
                self._next_object(job, synth, base.scenes[rid], seed, category, settings,
                                  with_room)
                return
            if job.kind == 'suggest':
                found = synth.suggest(base.scenes[rid], job.k or cfg.suggestions, seed,
                                      config=settings)
                job.ok, job.objects = True, found
                job.message = _json({'seed': seed, 'room': rid,
                                     'objects': [o.to_dict() for o in found]})
                return
            if rid:                     # generate, one room of the house from empty
                result = synth.complete(Scene(base.scenes[rid].room, []), seed,
                                        cancel=lambda: self._between(job), config=settings)
                served = Served(with_room(result.scene), seed=seed, added=result.added,
                                seconds=result.seconds, stopped=result.stopped,
                                timings=result.timings,
                                rooms_robot={rid: result.robot} if result.robot else {},
                                **served_as)
                added = {rid: result.added}
            else:                       # a house layout, or generate: every room
                start = base if job.kind == 'layout' else base.house
                stop = ((lambda: self._between(job)) if job.kind == 'generate'
                        else (lambda: self._stop_layout(job)))
                out = furnish_house(synth, start, seed, cancel=stop, config=settings)
                added = {r: s.added for r, s in out.rooms.items()}
                served = Served(out.scene, seed=seed, added=[o for a in added.values()
                                                             for o in a],
                                seconds=out.seconds, stopped='stop',
                                rooms_robot={r: s.robot for r, s in out.rooms.items()
                                             if s.robot is not None}, **served_as)
        except SynthesisCancelled:
            self._cancelled(job)
            return
        except SceneSynthError as e:
            self._refused(job, e)
            return
        if self._commit(job, served):
            job.ok, job.objects = True, served.added
            job.message = _json({'seed': seed, 'objects': len(served.scene.objects()),
                                 'added': {r: [o.id for o in a] for r, a in added.items()},
                                 'seconds': round(served.seconds, 4)})

    def _next_object(self, job: _Job, synth: Synthesizer, base: Scene, seed: int,
                     category: str, settings: SynthConfig,
                     into: Callable[[Scene], Scene | HouseScene] | None = None) -> None:
        """One more object for the room ``base``, committed as ``into`` makes the room
        with it (default: the room itself)."""
        t0 = time.perf_counter()
        try:
            obj = synth.next_object(base, seed, category or None, config=settings)
        except SceneSynthError as e:
            job.message = str(e)
            return
        if obj is None:
            what = f'no {category}' if category else 'nothing more'
            job.message = (f'{what} fits: the room has {len(base)} objects'
                           + (' (max_objects)' if len(base) >= settings.max_objects
                              else ''))
            return
        scene = base.copy()
        scene.objects.append(obj)
        scene.meta = {**_answered(scene.meta), 'generator': 'scene_synth_ros', 'seed': seed}
        if self._commit(job, Served(into(scene) if into else scene, 'next_object', seed, [obj],
                                   time.perf_counter() - t0, catalog=settings.catalog,
                                   vocabulary=synth.vocabulary)):
            job.ok, job.message, job.objects = True, _json(obj.to_dict()), [obj]

    def _stop_layout(self, job: _Job) -> bool:
        """Whether a layout's synthesis should stop now: a newer layout came, or its
        caller cancelled it."""
        return self._stale(job) or (job.cancelled is not None and bool(job.cancelled()))

    @staticmethod
    def _progress(job: _Job, base: Scene) -> Callable[[PlacedObject], None] | None:
        """What synthesis tells of each object placed for ``job``, counted with the
        layout's own objects."""
        if job.on_object is None:
            return None
        t0, count = time.perf_counter(), itertools.count(len(base) + 1)

        def told(obj: PlacedObject) -> None:
            try:
                job.on_object(obj, next(count), time.perf_counter() - t0)
            except Exception:   # a caller gone (a goal whose client left) stops nothing
                pass
        return told

    def _take_seed(self) -> int:
        with self._lock:
            seed = self._next_seed
            self._next_seed = (self._next_seed + 1) % 2**31
            following = self._next_seed
        self._on_seed(following)
        return seed

    def _commit(self, job: _Job, served: Served) -> bool:
        """Make ``served`` the current room or house and publish it, unless a newer layout
        came."""
        # Synthesis measured the promise for the robot it furnished for; other rooms (reset,
        # one more object, a layout published as given) are measured here.
        if isinstance(served.scene, HouseScene):
            promise, where = self._house_promise(served)
        else:
            promise = served.robot or robot.report(served.scene, robot_of(self.config))
            served.scene.meta['robot'] = promise.to_dict()
            where = with_article(served.scene.room.room_type)
        # Never publish what the schema would refuse; the model ids are the catalog's.
        dump = dump_house_scene if isinstance(served.scene, HouseScene) else dump_scene
        served.json = dump(served.scene, served.catalog, served.vocabulary)
        with self._lock:
            stale = self._stale(job)
            if not stale:
                self._scene, job.served = served.scene, served
        if stale:
            self._supersede(job)
            return False
        # the map of the robot the room was furnished for (a goal's own, else the node's)
        served.map = occupancy_grid(served.scene, promise.robot, map_of(self.config))
        objects = count_objects(served.scene)
        message = f'{served.source}: {objects} objects in {where}'
        if not promise.kept:       # a user's objects broke it; synthesis never does
            message += f', but {promise.sentence()}'
            self._log('warn', message)
        self._set_status(level=OK if promise.kept else WARN, message=message,
                         increment='rooms_served', objects=objects,
                         room_type=kind_of(served.scene), seed=served.seed,
                         last_seconds=served.seconds, timings=dict(served.timings))
        self._publish(served)
        if self.config.export_dir:
            self._export(served, Path(self.config.export_dir).expanduser())
        return True

    def _house_promise(self, served: Served) -> tuple[RobotReport, str]:
        """The robot promise of every room of the house ``served`` (synthesis's where it
        measured it), put in the house's meta; the first room that breaks it, else the first
        room's, and the words for the house."""
        house = served.scene
        measured = served.rooms_robot
        who = next(iter(measured.values())).robot if measured else robot_of(self.config)
        reports = {rid: measured.get(rid) or robot.report(s, who)
                   for rid, s in house.scenes.items()}
        house.meta['robot'] = {'promise_kept': all(r.kept for r in reports.values()),
                               'rooms': {rid: r.to_dict() for rid, r in reports.items()}}
        broken = [(rid, r) for rid, r in reports.items() if not r.kept]
        promise = broken[0][1] if broken else next(iter(reports.values()))
        where = f'a house of {len(reports)} rooms'
        if broken:
            where += f' (room {quoted(broken[0][0])})'
        return promise, where

    def _export(self, served: Served, directory: Path) -> None:
        """Write the room as JSON and in every one of ``export_formats`` (mesh files shared
        in ``meshes/``); a failure is reported, not fatal. A house is one world in each
        format, ``house_NNNNN``."""
        kind = 'house' if isinstance(served.scene, HouseScene) else 'room'
        stem = f'{kind}_{self.status.rooms_served:05d}'
        try:
            directory.mkdir(parents=True, exist_ok=True)
            write_atomic(directory / f'{stem}.json', served.json + '\n')
            for fmt in parse_formats(self.config.export_formats):
                write(served.scene, fmt, directory / f'{stem}{EXPORT_FORMATS[fmt].suffix}',
                      directory / 'meshes', catalog=served.catalog)
        except (OSError, CatalogError) as e:    # CatalogError: a user's mesh gone since
            text = f'export to {directory} failed: {getattr(e, "strerror", None) or e}'
            self._log('warn', text)
            self._set_status(level=WARN, message=text, last_error=text)

    # ---- status ---------------------------------------------------------------------------
    def _log(self, level: str, text: str) -> None:
        try:
            self._logger(level, sentence(text))
        except Exception:      # a failing logger (its context going away) must not stop the worker
            pass

    def _reject(self, reason: str) -> None:
        self._log('warn', reason)
        self._set_status(level=WARN, message=f'input rejected: {reason}',
                         last_error=reason, increment='inputs_rejected')

    def _supersede(self, job: _Job) -> None:
        if self._closing:
            job.message = 'the node is shutting down'
            return
        job.message = 'superseded by a newer room layout'
        self._set_status(increment='requests_superseded')

    def _set_status(self, increment: str | None = None, **changes) -> None:
        for key in ('message', 'last_error'):      # bounded on /diagnostics, whatever the input
            if key in changes:
                changes[key] = sentence(changes[key])
        with self._lock:
            if increment:
                changes[increment] = getattr(self.status, increment) + 1
            self.status = replace(self.status, **changes)
            status = self.status
        self._on_status(status)


def kind_of(scene: Scene | HouseScene) -> str:
    """What /diagnostics calls the room served: its room type, or 'house'."""
    return 'house' if isinstance(scene, HouseScene) else scene.room.room_type


def map_of(config: ServerConfig) -> MapConfig:
    """The occupancy map's settings of the node's parameters."""
    return MapConfig(config.map_resolution, config.map_scan_height)


def robot_of(config: ServerConfig) -> Robot:
    """The robot of the node's parameters; ConfigError when they do not make one."""
    try:
        return Robot(config.robot_radius, config.robot_reach, config.robot_clearance)
    except ValueError as e:
        raise ConfigError(str(e)) from None


def in_catalog(scene: Scene, models: Catalog, vocabulary: Vocabulary = PAPER) -> Scene:
    """``scene`` with each model id that ``models`` lacks replaced by the nearest model of
    its category: a room parsed or furnished before catalog_dir changed keeps its objects and
    shows the new catalog's models, and its JSON still validates. The room's categories are
    those of ``vocabulary``."""
    def known(o: PlacedObject) -> bool:
        try:
            return models.get(o.model_id, vocabulary).category == o.category
        except KeyError:
            return False
    if all(known(o) for o in scene.objects):
        return scene
    out = scene.copy()
    out.objects = [o if known(o) else replace(o, model_id=models.nearest(
        o.category, o.width, o.depth, scene.room.room_type, vocabulary).model_id)
        for o in out.objects]
    return out


def _seed_arg(seed: int | None) -> tuple[int | None, str]:
    """A request's seed (None or negative: the node's next one), or why it is refused."""
    if seed is None or seed < 0:
        return None, ''
    if seed >= 2**31:
        return None, f'seed {seed} is out of range: 0 to {2**31 - 1}, or -1 for the next seed'
    return seed, ''


def _answered(meta: dict) -> dict:
    """A room's meta once a later request changes the room: the layout's request id
    identified the room that answered it, not the ones after."""
    return {k: v for k, v in meta.items() if k != 'request_id'}


def _json(d: dict) -> str:
    return json.dumps(d, separators=(', ', ': '), allow_nan=False)
