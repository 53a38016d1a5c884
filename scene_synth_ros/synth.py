"""Scene synthesis with the four trained modules (the paper's Model section).

Objects are inserted one at a time, each in the paper's steps. Next Object Category: the
category module draws the next category, or STOP. Object Location: the location module gives
a distribution over the room for it, masked to the floor (or, for a second-tier category, to
the surfaces observed to support it; for a piece of a group kept at insertion, to where a
partner could have it: ``rules.insertion.partner_zone``) and tempered, and locations are drawn from
it, the first ones moved to the centre of the blob they fell in
(``SynthConfig.location_mode``, ``centre_draws``) and, in bundles with offsets, by the
offset predicted there; when they all fail for a piece of a group, a few more are drawn
uniformly over its partner zone (``zone_samples``). Object Orientation: at each location the
orientation module draws a facing, snapped to the room's axes when its classifier says so.
Object Dimensions: the dimensions module draws a footprint (around its decoded mean, by the
spread it learned, where it learned one). Object Insertion: the catalog model nearest that
footprint is placed; among near ties, for a module that answers its mean, models that
co-occur in the training rooms with those already there come first. A placement is rejected
if it collides with first-tier furniture, leaves the floor, enters a door's clear zone,
breaks the robot promise (``robot``: the configured robot must still drive between the doors
and reach every object it reached, and the new one), breaks a design rule kept at insertion
(``SynthConfig.insertion_rules``: a case that kept it, or the new piece itself), or (second
tier) stands less than 70 % on its parent or overlaps its neighbours there; then the next
model is tried, then the next location, and if nothing fits the category is drawn again
without the failed ones. A STOP drawn while a group still owes a partner
(``SynthConfig.owed_partners``: a coffee table without seating, a double bed without a
nightstand, a kitchen without its sink, stove or fridge) is answered with one more draw
among the partners' categories; a coffee table the finished room still leaves without
seating is taken out again (``groups.withdrawable``).
An empty room in which the robot cannot drive between the doors is refused in one sentence.

Three modes: ``generate`` (an empty room), ``complete`` (a partial room: keeps what is
there) and ``suggest`` (k distinct proposals for the next object, nothing committed). Each is
reproducible from its seed. ``Synthesis.timings`` has the seconds a room spent in each of
``MODULES``: rendering images, each network (snap with orientation), and insertion. Every
network call goes through ``lockstep.ask``, so that rooms furnished together in lockstep
(``lockstep.run``) share their forward passes; there a room's seconds also count the other
rooms' work while it waited. The networks themselves, loaded and laid out for the device and
run by torch or onnxruntime, are ``networks.loaded``'s; the rules kept at insertion are
``rules.insertion``'s.
"""
from __future__ import annotations

from contextlib import contextmanager
from dataclasses import dataclass, field, replace
import math
from pathlib import Path
import time
from typing import TYPE_CHECKING, Callable, Collection, Iterator

import numpy as np
import shapely
from shapely.geometry import Polygon

from . import catalog
from .allowance import STRICT, Allowance
from .categories import PAPER, PASSAGE_ROOM_TYPES, RoomTypeSpec, Vocabulary
from .errors import SceneSynthError, UnknownCategory, quoted
from .geometry import (
    door_zone,
    enters_zone,
    overlaps_any,
    support_fraction,
)
from .lockstep import ask
from .networks.config import device_name, resolve_runtime
from .networks.draws import (
    LocationDraws,
    category_probabilities,
    decode_angle,
    location_distribution,
    log_normaliser,
    prior_noise,
    sigmoid,
    snap_angle,
)
from .networks.loaded import LoadedNetworks
from .networks.runtime import OnnxCalls
from .networks.served import BundleError, Served, bundle_specs, weights_vocabulary
from .paths import weights_dir as shipped_weights_dir
from .render import FIRST_CATEGORY, OBJECT, Frame, TopDownRenderer, quarter_turns, turn_image
from .rules import groups, home, robot
from .rules.insertion import (
    INSERTION_RULES,
    OWED_RULES,
    owed,
    partner_zone,
    rule_categories,
    verdicts,
    waived_when_owed,
)
from .rules.robot import RobotReport, RobotState
from .scene import PlacedObject, Room, Scene, box_corners, wrap_angle
from .synth_config import SynthConfig
from .thresholds import FLOOR_TOLERANCE, MIN_SUPPORT
from .user_catalog import load_catalog

if TYPE_CHECKING:
    from .networks.graphs import TorchCalls  # torch: an annotation only

# What ``Synthesis.timings`` counts seconds of (see the module docstring).
MODULES = ('render', 'category', 'location', 'orientation', 'dimensions', 'insertion')


class SynthesisError(SceneSynthError):
    """A room the synthesizer cannot work on, said in one sentence."""


class SynthesisCancelled(Exception):
    """``complete`` was told to stop by its ``cancel`` callback (a newer request superseded
    it); nothing of the half-furnished room is returned."""


WALL_GAP = (0.0, 0.02)    # metres left between a wall and furniture pushed against it


def against_walls(room: Room, obj: PlacedObject, reach: float,
                  rng: np.random.Generator) -> PlacedObject:
    """``obj`` moved straight onto every wall that one of its sides runs parallel to within
    ``reach``, on either side of it (two walls at a corner), leaving a gap drawn from
    ``WALL_GAP``.

    The location module sees the room at about 9 cm a pixel, so furniture meant to stand
    against a wall lands a few centimetres off it, where the training rooms never put
    anything (their wall gaps are 0-2 cm), or a few centimetres through it, where it is
    refused and the category is lost (``docs/design/investigations.md``: most failed insertions are
    large pieces a median 4-10 cm past a wall). This closes that gap either way and nothing
    else."""
    pos = np.array(obj.position[:2], dtype=float)
    done: set[int] = set()
    for _ in range(2):
        corners = box_corners(pos[0], pos[1], obj.yaw, obj.width, obj.depth)
        best = None
        for wall in room.walls:
            if wall.index in done:
                continue
            a = (math.atan2(wall.direction[1], wall.direction[0]) - obj.yaw) % (math.pi / 2)
            if min(a, math.pi / 2 - a) > 1e-3:
                continue                                   # not parallel to a side
            rel = corners - np.asarray(wall.start)
            gap = float((rel @ wall.normal).min())
            along = rel @ wall.direction
            overlap = min(along.max(), wall.length) - max(along.min(), 0.0)
            off = gap > WALL_GAP[1] or gap < WALL_GAP[0]
            if off and -reach < gap < reach and overlap > 0.5 * np.ptp(along):
                if best is None or gap < best[0]:          # through a wall first
                    best = (gap, wall)
        if best is None:
            break
        gap, wall = best
        pos -= wall.normal * (gap - rng.uniform(*WALL_GAP))
        done.add(wall.index)
    if not done:
        return obj
    return replace(obj, position=(float(pos[0]), float(pos[1]), obj.position[2]))


def check_room_fits(room: Room, vocabulary: Vocabulary = PAPER) -> None:
    """SynthesisError unless the smallest first-tier model of the room's type (in
    ``vocabulary``) fits on its floor outside the door zones (a narrow strip passes the
    schema's area check but can hold nothing); a passage (``PASSAGE_ROOM_TYPES``) may hold
    nothing."""
    if room.room_type in PASSAGE_ROOM_TYPES:
        return
    spec = vocabulary.spec(room.room_type)
    small = min((v for c in spec.categories if c.tier == 'first'
                 for v in catalog.variants(c.name, spec.room_type, vocabulary)),
                key=lambda v: v.width * v.depth)
    short, long_ = sorted((small.width, small.depth))
    free = room.polygon
    for d in room.doors:
        free = free.difference(door_zone(room, d))
    core = free.buffer(-short / 2, join_style='mitre')
    parts = getattr(core, 'geoms', [core])
    reach = max((max(np.ptp(np.asarray(p.minimum_rotated_rectangle.exterior.coords), axis=0))
                 if not p.is_empty and p.area > 0 else 0.0) for p in parts) if parts else 0.0
    if core.is_empty or reach < long_ - short - 1e-6:
        raise SynthesisError(
            f'the floor is too small or narrow for any {room.room_type} furniture: not even '
            f'the smallest, a {small.category} of {small.width:.2f} m x {small.depth:.2f} m, '
            f'fits outside the door zones')


@dataclass
class Synthesis:
    """The outcome of ``generate`` / ``complete``."""

    scene: Scene
    added: list[PlacedObject]
    stopped: str                        # 'stop', 'max_objects' or 'nothing_fits'
    seconds: float
    timings: dict[str, float] = field(default_factory=dict)   # seconds per module
    robot: RobotReport | None = None     # the robot promise measured on ``scene``
    # what the networks' data set lets a room do (``Bundle.allowance``): judge ``scene`` by it
    allowance: Allowance = STRICT


@dataclass
class _Context:
    """Per-room state shared by the insertions into one room."""

    config: SynthConfig           # the settings of the call furnishing it
    room: Room
    spec: RoomTypeSpec
    bundle: Served                # what synthesis reads of the room type's bundle
    calls: OnnxCalls | TorchCalls  # the bundle's networks as ``lockstep.ask`` runs them
    frame: Frame                  # the room's frame: what the category and location modules see
    grid: Frame                   # the location module's output grid
    floor_mask: np.ndarray        # (L, L) bool: pixel centres on the floor
    door_mask: np.ndarray         # (L, L) bool: pixel centres in a door's clear zone
    centres: np.ndarray           # (L * L, 2): the world (x, y) of each grid pixel's centre
    floor: Polygon                # the floor grown by the floor tolerance
    zones: list[Polygon]          # the doors' clear zones
    rng: np.random.Generator      # every draw of this room's synthesis
    timings: dict[str, float] = field(default_factory=lambda: dict.fromkeys(MODULES, 0.0))
    # the first-tier objects of a scene (``_first_tier_key``) -> the robot in it
    # (``robot.state``), also for those of the placements that passed the robot check
    robot: dict[tuple, RobotState] = field(default_factory=dict)
    # (rule, id of the scene, its object count) -> the rule's verdict per case
    rules: dict[tuple[str, int, int], dict[int, bool]] = field(default_factory=dict)
    crops: np.ndarray | None = None   # (B, C, N, N): reused for the local images
    # (id of the scene, its object count, the points) whose crops at the room's yaw
    # ``crops`` holds, or None
    crops_held: tuple | None = None
    waived: frozenset[str] = frozenset()   # insertion rules not kept in this context

    @contextmanager
    def timed(self, module: str) -> Iterator[None]:
        """Adds the seconds the block takes to ``timings[module]``."""
        t = time.perf_counter()
        try:
            yield
        finally:
            self.timings[module] += time.perf_counter() - t


class SynthesisObserver:
    """What a ``Synthesizer`` tells its ``observer`` while it furnishes rooms: subclass it and
    override the events wanted (each does nothing here). Observing changes no room; with
    rooms in lockstep the events of the group's rooms interleave."""

    def category_drawn(self, category: str | None) -> None:
        """The category module drew ``category`` (None: STOP), also when it draws again
        after a category that found no place, and for a draw owed to a partner."""

    def placement_checked(self, obj: PlacedObject, refused_by: str | None) -> None:
        """``fits`` judged a candidate placement: ``refused_by`` is None where it stands,
        else the first check that refused it: ``floor``, ``support`` or ``sibling`` (second
        tier), ``collision``, ``door``, the name of a design rule kept at insertion, or
        ``robot`` (the robot promise)."""

    def object_added(self, obj: PlacedObject) -> None:
        """``complete`` (or ``generate``) added ``obj`` to the room; the pieces the finished
        room withdraws again (coffee tables left without seating) are told here too."""


class Synthesizer:
    """Furnishes rooms with the shipped (or given) weights. Bundles load on first use.

    ``observer``, a ``SynthesisObserver`` (also settable as the attribute of that name), is
    told of every category drawn, placement checked and object added; None, the default,
    costs nothing."""

    def __init__(self, weights_dir: str | Path | None = None,
                 config: SynthConfig | None = None,
                 observer: SynthesisObserver | None = None):
        self.weights_dir = Path(weights_dir) if weights_dir else shipped_weights_dir()
        self.config = config or SynthConfig()
        self.observer = observer
        _check_rules(self.config)
        try:
            self.device = device_name(self.config.device)
            self.runtime = resolve_runtime(self.config.runtime, self.device)
        except ValueError as e:
            raise SynthesisError(str(e)) from None
        self._renderers: dict[int, TopDownRenderer] = {}
        # The room types of the weights' bundles; what they know of each (a data set's
        # category sets where they were trained on one) is this synthesizer's vocabulary,
        # which its callers parse layouts with.
        specs = bundle_specs(self.weights_dir)
        self.room_types = list(specs)
        self.vocabulary = weights_vocabulary(self.weights_dir, specs)
        self.networks = LoadedNetworks(self.weights_dir, self.device, self.runtime,
                                       self.vocabulary)
        self._ready: set[str] = set()       # the room types ``prepare`` readied

    # ---- set-up ---------------------------------------------------------------------------
    def bundle(self, room_type: str):
        """The torch networks of ``room_type``, ready for inference (``LoadedNetworks.bundle``;
        this imports torch); raises ``BundleError`` naming a bad file."""
        return self.networks.bundle(room_type)

    def calls(self, room_type: str):
        """The networks of ``room_type`` as synthesis runs them (``LoadedNetworks.calls``),
        readied (``prepare``) at the room type's first use."""
        rt = self.vocabulary.resolve(room_type)
        if rt not in self._ready:
            self.prepare(rt)
        return self.networks.calls(rt)

    def load_all(self, ready: Collection[str] | None = None) -> None:
        """Read the bundle of every room type of the weights directory (its record, from the
        cache where it is there: ``LoadedNetworks.served``), so that a bad file is said now,
        and ready the calls (``prepare``) of the room types in ``ready`` (all of them by
        default), so that no room of those pays for that either; ``BundleError`` names a bad
        file, or says there is none."""
        if not self.room_types:
            raise BundleError(f'{self.weights_dir}: no weights bundles (<room type>.pt) there')
        for rt in self.room_types:
            if ready is None or rt in ready:
                self.prepare(rt)
            else:
                self.networks.served(rt)

    def prepare(self, room_type: str) -> None:
        """Ready ``room_type``'s calls (``LoadedNetworks.prepare``: its record, its graphs in
        sessions, or its bundle with torch). Networks onnxruntime cannot run are torch's
        under runtime ``auto``; asked for by name, that is a SynthesisError."""
        named = self.config.runtime == 'onnxruntime'
        why = self.networks.prepare(room_type, fall_back=not named)
        if why is not None and named:
            raise SynthesisError(why)
        self._ready.add(self.vocabulary.resolve(room_type))

    def _renderer(self, resolution: int) -> TopDownRenderer:
        if resolution not in self._renderers:
            # Each room under way keeps its frame's architecture layers (64 KB at 64 px):
            # room enough for the widest lockstep (``batch.MAX_LOCKSTEP``).
            self._renderers[resolution] = TopDownRenderer(resolution, cache_size=64,
                                                          vocabulary=self.vocabulary)
        return self._renderers[resolution]

    def _settings(self, config: SynthConfig | None) -> SynthConfig:
        """The settings of one call: ``config``, checked, or the synthesizer's own. Its
        device and runtime are the synthesizer's: the networks are loaded on them."""
        if config is None:
            return self.config
        _check_rules(config)
        for name in ('device', 'runtime'):
            if getattr(config, name) != getattr(self.config, name):
                raise SynthesisError(
                    f'a call cannot change the {name} ({quoted(getattr(config, name))}): the '
                    f'networks are loaded for {quoted(getattr(self.config, name))}; make a '
                    f'Synthesizer with that {name}')
        return config

    def _context(self, room: Room, seed: int, objects=(),
                 config: SynthConfig | None = None) -> _Context:
        """The state of one room's synthesis with the call's ``config`` (None: the
        synthesizer's own)."""
        config = self._settings(config)
        rt = self.vocabulary.resolve(room.room_type)
        spec = self.vocabulary.spec(rt)
        for o in objects:
            if o.category not in spec:
                raise SynthesisError(f'object {o.id!r} is a {o.category}, which is not one of '
                                     f'the {rt} categories the networks know')
        bundle = self.networks.served(rt)
        m = bundle.config.model
        frame = Frame.for_room(room, m.resolution, self.vocabulary, bundle.location_multiple)
        # The location grid covers the frame at the grid's own pixel size.
        n = frame.resolution * m.location_resolution // m.resolution
        grid = Frame(frame.centre, frame.yaw, frame.extent, n)
        ii, jj = np.meshgrid(np.arange(n), np.arange(n), indexing='ij')
        centres = grid.pixel_to_world(np.stack([ii, jj], -1)).reshape(-1, 2)
        floor_mask = shapely.contains_xy(room.polygon, centres[:, 0], centres[:, 1])
        zones = [door_zone(room, d, bundle.allowance) for d in room.doors]
        door_mask = np.zeros(n * n, dtype=bool)
        for z in zones:
            door_mask |= shapely.contains_xy(z, centres[:, 0], centres[:, 1])
        return _Context(
            config=config, room=room, spec=spec, bundle=bundle, calls=self.calls(rt),
            frame=frame, grid=grid,
            floor_mask=floor_mask.reshape(n, n), door_mask=door_mask.reshape(n, n),
            centres=centres,
            floor=room.polygon.buffer(FLOOR_TOLERANCE, join_style='mitre'), zones=zones,
            rng=np.random.default_rng(seed))

    # ---- public modes ---------------------------------------------------------------------
    def generate(self, room: Room | Scene, seed: int = 0, cancel=None,
                 config: SynthConfig | None = None) -> Synthesis:
        """Furnish ``room`` from empty (objects of a Scene given here are dropped)."""
        if isinstance(room, Scene):
            room = room.room
        check_room_fits(room, self.vocabulary)
        return self.complete(Scene(room, []), seed, cancel, config)

    def complete(self, scene: Scene, seed: int = 0, cancel=None,
                 config: SynthConfig | None = None,
                 on_object: Callable[[PlacedObject], None] | None = None) -> Synthesis:
        """Add objects to ``scene`` (a copy; what is there stays) until the category module
        says STOP, ``max_objects`` is reached or nothing more fits.

        ``cancel``, a callable, is asked before every insertion; when it returns true the
        call raises ``SynthesisCancelled``. ``config``: the settings of this call alone
        (default: the synthesizer's own; the device and runtime must be those).
        ``on_object`` is called with each object as it is added (the finished room may
        withdraw some again: coffee tables whose seating never came)."""
        t0 = time.perf_counter()
        ctx = self._context(scene.room, seed, scene.objects, config)
        cfg = ctx.config
        out = scene.copy()
        if not scene.first_tier and not self._robot_state(ctx, out).doors_connected:
            r = cfg.robot
            raise SynthesisError(
                f'a robot of radius {r.radius:g} m'
                + (f' keeping {r.clearance:g} m clear' if r.clearance else '')
                + ' cannot drive between the doors of this room even when it is empty, so '
                'nothing can be placed under the robot promise: lower robot_radius or widen '
                'the room')
        added: list[PlacedObject] = []
        stopped = 'stop'
        owing = math.inf        # broken cases of the owed-partner rules at the last STOP
        while True:
            if cancel is not None and cancel():
                raise SynthesisCancelled('superseded by a newer request')
            if len(out.objects) >= cfg.max_objects:
                stopped = 'max_objects'
                break
            obj, why = self._insert_one(ctx, out)
            if obj is None and why == 'stop':
                # A group still owed a partner gets one more draw, as long as the last one
                # mended something (a partner that found no case's side ends it).
                broken, partners = owed(out, cfg.owed_partners)
                if 0 < broken < owing:
                    owing = broken
                    obj, _ = self._insert_one(ctx, out, allow_stop=False, only=partners)
                    waive = waived_when_owed(partners, cfg.insertion_rules)
                    if obj is None and waive:
                        # Then where the rules it need not keep would refuse it.
                        kept, ctx.waived = ctx.waived, ctx.waived | waive
                        try:
                            obj, _ = self._insert_one(ctx, out, allow_stop=False,
                                                      only=partners)
                        finally:
                            ctx.waived = kept
            if obj is None:
                stopped = why
                break
            out.objects.append(obj)
            added.append(obj)
            if self.observer is not None:
                self.observer.object_added(obj)
            if on_object is not None:
                on_object(obj)
        self._withdraw(out, added, cfg.owed_partners)
        kept = robot.report(out, cfg.robot, self._robot_state(ctx, out))
        out.meta.update({'generator': 'scene_synth_ros', 'seed': int(seed),
                         'weights': ctx.bundle.config.name, 'robot': kept.to_dict()})
        if ctx.bundle.allowance != STRICT:
            out.meta['allowance'] = ctx.bundle.allowance.to_dict()
        return Synthesis(out, added, stopped, time.perf_counter() - t0, dict(ctx.timings),
                         kept, ctx.bundle.allowance)

    @staticmethod
    def _withdraw(scene: Scene, added: list[PlacedObject], owed: Collection[str]) -> None:
        """Take out of ``scene`` (and ``added``) the pieces this synthesis added that the
        finished room leaves breaking an owed-partner rule of ``owed``, the draws owed to them
        having found no partner for them (``groups.withdrawable``: coffee tables without
        seating), with what stands on them. What the scene held before synthesis stays."""
        mine = {o.id for o in added}
        gone = {t for t in groups.withdrawable(scene, owed) if t in mine}
        gone |= {o.id for o in scene.objects if o.support in gone}
        scene.objects[:] = [o for o in scene.objects if o.id not in gone]
        added[:] = [o for o in added if o.id not in gone]

    def next_object(self, scene: Scene, seed: int = 0, category: str | None = None,
                    config: SynthConfig | None = None) -> PlacedObject | None:
        """One more object for ``scene`` (not added to it), or None when nothing fits;
        STOP is not drawn. With ``category``, an object of that category: the category
        module is not asked, the other modules are (``UnknownCategory`` if the room type
        has no such category). ``config`` as for ``complete``."""
        ctx = self._context(scene.room, seed, scene.objects, config)
        if category is not None and category not in ctx.spec:
            raise UnknownCategory(f'{quoted(category)} is not a category of '
                                  f'{scene.room.room_type} rooms')
        if len(scene.objects) >= ctx.config.max_objects:
            return None
        if category is not None:
            # A piece the user names goes by a partner when the room has one; in a room with
            # none, the group rule that would refuse it outright is waived for it.
            ctx.waived = frozenset(
                rule for rule in ctx.config.insertion_rules
                if (zone := partner_zone(scene, rule, category,
                                                self.vocabulary)) is not None
                and zone.is_empty)
        obj, _ = self._insert_one(ctx, scene, allow_stop=False,
                                  only=None if category is None else (category,))
        return obj

    def suggest(self, scene: Scene, k: int = 5, seed: int = 0, max_tries: int | None = None,
                config: SynthConfig | None = None) -> list[PlacedObject]:
        """Up to ``k`` distinct proposals for the next object (different category, or the
        same category at least half a metre away or facing another way); nothing is
        committed. STOP is not a proposal. ``config`` as for ``complete``."""
        ctx = self._context(scene.room, seed, scene.objects, config)
        found: list[PlacedObject] = []
        for _ in range(max_tries or 6 * k):
            if len(found) >= k:
                break
            obj, _ = self._insert_one(ctx, scene, allow_stop=False)
            if obj is not None and all(_distinct(obj, f) for f in found):
                found.append(obj)
        return found

    # ---- one insertion: the paper's pipeline ------------------------------------------------
    def _insert_one(self, ctx: _Context, scene: Scene, allow_stop: bool = True,
                    only: Collection[str] | None = None) -> tuple[PlacedObject | None, str]:
        """One step of the sequential model: the next category (or STOP) drawn from the
        category module, then an object of it; a category that no insertion fits is drawn
        again without it (paper: Object Insertion). ``only`` names the categories that may
        be drawn. Returns the object, or None and why."""
        with ctx.timed('render'):
            image, small = self._top_down(ctx, scene)
            counts = self._bag_of_categories(ctx, scene)
        with ctx.timed('category'):
            category_logits = ask(ctx.calls, 'category', image, counts)[0][0]
        allowed = self._allowed_categories(ctx, scene, allow_stop)
        if only is not None:
            keep = np.zeros_like(allowed)
            keep[[ctx.spec.index(c) for c in only if c in ctx.spec]] = True
            allowed &= keep
        location = None      # (logits, offsets), for the first category that is not STOP
        for _ in range(ctx.config.category_attempts):
            if not bool(allowed.any()):
                break
            c = self._next_category(ctx, category_logits, allowed)
            if self.observer is not None:
                self.observer.category_drawn(ctx.spec.names[c] if c < len(ctx.spec.names)
                                             else None)
            if c == len(ctx.spec.names):         # the index after the categories: STOP
                return None, 'stop'
            if location is None:
                with ctx.timed('location'):
                    logits, offsets = ask(ctx.calls, 'location', image)
                    location = (logits[0], None if offsets is None else offsets[0],
                                log_normaliser(logits[0]))
            obj = self._insert_category(ctx, scene, c, location, small)
            if obj is not None:
                return obj, 'placed'
            allowed[c] = False
        return None, 'nothing_fits'

    def _top_down(self, ctx: _Context, scene: Scene) -> tuple[np.ndarray, np.ndarray]:
        """The scene image the category and location modules see (a batch of one), and the
        scene on the location grid, for the location mask."""
        n, c = ctx.frame.resolution, FIRST_CATEGORY + len(ctx.spec.names)
        full = self.networks.image(n, c, calls=ctx.calls)
        image = self._renderer(n).render(scene, ctx.frame, out=full[:c])
        if ctx.grid.resolution == ctx.frame.resolution:
            small = image
        else:
            small = self._renderer(ctx.grid.resolution).render(scene, ctx.grid)
        return full[None], small

    def _bag_of_categories(self, ctx: _Context, scene: Scene) -> np.ndarray:
        """How many objects of each category the room holds (a batch of one)."""
        spec = ctx.spec
        counts = np.zeros((1, len(spec.names)), dtype=np.float32)
        for o in scene.objects:
            if o.category in spec:
                counts[0, spec.index(o.category)] += 1
        return counts

    def _allowed_categories(self, ctx: _Context, scene: Scene, allow_stop: bool
                            ) -> np.ndarray:
        """Which of the categories and STOP (last) may come next: a second-tier category
        only once the room holds something that can support it."""
        spec = ctx.spec
        present = {o.category for o in scene.objects}
        allowed = np.ones(len(spec.names) + 1, dtype=bool)
        for k, name in enumerate(spec.names):
            if spec.info(name).tier == 'second' and not set(spec.supports(name)) & present:
                allowed[k] = False
        allowed[-1] = allow_stop
        return allowed

    @staticmethod
    def _next_category(ctx: _Context, logits: np.ndarray, allowed: np.ndarray) -> int:
        """A draw from the category module's distribution over the ``allowed`` categories
        (paper: Next Object Category)."""
        p = category_probabilities(logits, allowed)
        return int(ctx.rng.choice(len(p), p=p / p.sum()))

    def _insert_category(self, ctx: _Context, scene: Scene, c: int,
                         location: tuple[np.ndarray, np.ndarray | None, np.ndarray],
                         small: np.ndarray
                         ) -> PlacedObject | None:
        """An object of category ``c``: locations drawn from the masked, tempered location
        distribution (paper: Object Location), at each an orientation (Object Orientation)
        and dimensions (Object Dimensions), then a catalog model that stands there (Object
        Insertion). Locations are drawn ``location_batch`` at a time, so that the orientation
        and dimensions modules see them as one batch."""
        cfg = ctx.config
        location_logits, offsets, log_norm = location
        with ctx.timed('location'):
            mask, zoned = self._mask(ctx, scene, ctx.spec.names[c], small)
            p = location_distribution(location_logits, c, mask, cfg.location_temperature,
                                      log_norm)
        if p is None:
            return None
        obj = self._try_locations(ctx, scene, c, LocationDraws(p), cfg.location_samples,
                                  offsets, cfg.location_mode)
        if obj is None and zoned and cfg.zone_samples > 0:
            obj = self._try_locations(ctx, scene, c, LocationDraws(mask / mask.sum()),
                                      cfg.zone_samples, None, False)
        return obj

    def _try_locations(self, ctx: _Context, scene: Scene, c: int, draws: LocationDraws,
                       samples: int, offsets: np.ndarray | None, centre: bool
                       ) -> PlacedObject | None:
        """The first of ``samples`` locations from ``draws`` where an object of category
        ``c`` stands (the first ``centre_draws`` moved to their blob's centre, with
        ``centre``), drawn ``location_batch`` at a time."""
        cfg = ctx.config
        category = ctx.spec.names[c]
        tried = 0
        while tried < samples:
            n = min(cfg.location_batch, samples - tried)
            tried += n
            with ctx.timed('location'):
                mode = centre and tried <= cfg.centre_draws
                points = ctx.grid.pixel_to_world(draws.sample(ctx.rng, n, offsets, mode))
            yaws = self._orientation(ctx, scene, c, points)
            dims = self._dimensions(ctx, scene, c, points, yaws)
            with ctx.timed('insertion'):
                for point, yaw, (depth, width) in zip(points, yaws, dims, strict=True):
                    obj = self._insert_model(ctx, scene, category, point, yaw, width, depth)
                    if obj is not None:
                        return obj
        return None

    def _mask(self, ctx: _Context, scene: Scene, category: str, small: np.ndarray
              ) -> tuple[np.ndarray, bool]:
        """Where the centre of a new ``category`` object may go on the location grid, and
        whether a partner zone narrowed it."""
        spec = ctx.spec
        if spec.info(category).tier == 'first':
            # A centre inside other furniture or a door's clear zone is always rejected.
            mask = ctx.floor_mask & ~ctx.door_mask & (small[OBJECT] < 0.5)
            # A piece of a group goes only where a partner could have it, for the group
            # rules insertion keeps (a departure from the paper, as the rules are): the
            # location module spreads such pieces over the room.
            zoned = False
            for rule in ctx.config.insertion_rules:
                if rule in ctx.waived:
                    continue
                zone = partner_zone(scene, rule, category, self.vocabulary)
                if zone is not None:
                    zoned = True
                    mask &= shapely.contains_xy(zone, ctx.centres[:, 0],
                                                ctx.centres[:, 1]).reshape(mask.shape)
            return mask, zoned
        mask = np.zeros_like(ctx.floor_mask)
        for parent in spec.supports(category):
            mask |= small[FIRST_CATEGORY + spec.index(parent)] > 0.5
        for name in spec.names:
            if spec.info(name).tier == 'second':
                mask &= small[FIRST_CATEGORY + spec.index(name)] < 0.5
        return mask & ctx.floor_mask, False

    def _local_images(self, ctx: _Context, scene: Scene, points: np.ndarray,
                      yaws: list[float]) -> np.ndarray:
        """The scene image translated to each point and turned to each yaw, as a batch."""
        # Crops are the networks' own size whatever the room's: a view around a point.
        n = ctx.bundle.config.model.resolution
        r = self._renderer(n)
        c = FIRST_CATEGORY + len(ctx.spec.names)
        # One buffer per room, drawn over for every batch of crops (a fresh 750 KB image per
        # crop cost page faults and a copy into the batch). The networks read it before the
        # next batch is drawn; on a GPU it is copied there anyway.
        if ctx.crops is None or ctx.crops.shape[0] < len(points):
            ctx.crops = self.networks.image(n, c, len(points), ctx.calls)
        batch = ctx.crops[:len(points)]
        # The orientation module's crops (at the room's yaw) are still in the buffer when
        # the dimensions module asks for crops of the same points: one at a yaw a quarter
        # turn from the room's (most: snapped yaws) is one of those turned, not drawn again
        # (where the images are channels-last, which makes turning cheap).
        these = (id(scene), len(scene.objects), points.tobytes())
        held = self.networks.channels_last and ctx.crops_held == these
        for k, (pt, yaw) in enumerate(zip(points, yaws, strict=True)):
            q = quarter_turns(yaw - ctx.frame.yaw) if held else None
            if q is not None:
                turn_image(batch[k], q)
                continue
            # A crop's frame is seen once: not cached, so that the rooms' own frames stay
            # (in lockstep, 16 rooms' crops pushed them out of the cache at every step).
            r.render(scene, Frame.local(ctx.room.room_type, pt, yaw, n, self.vocabulary),
                     out=batch[k, :c], keep=False)
        ctx.crops_held = these if all(yaw == ctx.frame.yaw for yaw in yaws) else None
        return batch

    def _orientation(self, ctx: _Context, scene: Scene, c: int, points: np.ndarray
                     ) -> list[float]:
        """The yaw of a ``c`` object at each point: the orientation CVAE sees the image
        translated to the point, in the room's axes, and the snap classifier says whether
        its angle goes to the nearest of the room's four axes."""
        with ctx.timed('render'):
            x = self._local_images(ctx, scene, points, [ctx.frame.yaw] * len(points))
        with ctx.timed('orientation'):
            cats = np.full(len(points), c, dtype=np.int64)
            z = prior_noise(ctx.rng, len(points), ctx.bundle.latents['orientation'])
            out, snap_logits = ask(ctx.calls, 'orientation', x, cats, z)
            theta = decode_angle(out, ctx.rng)
            snap = sigmoid(snap_logits) > ctx.config.snap_threshold
            return [wrap_angle(ctx.frame.yaw + (snap_angle(th) if s else th))
                    for th, s in zip(theta.tolist(), snap.tolist(), strict=True)]

    def _dimensions(self, ctx: _Context, scene: Scene, c: int, points: np.ndarray,
                    yaws: list[float]) -> list[tuple[float, float]]:
        """The footprint (depth, width) of a ``c`` object at each point and yaw, from the
        dimensions CVAE shown the image in the object's frame: its decoded mean, drawn from
        the likelihood around it where the bundle learned its spread
        (``ModelConfig.dimensions_noise``)."""
        with ctx.timed('render'):
            x = self._local_images(ctx, scene, points, yaws)
        with ctx.timed('dimensions'):
            b = ctx.bundle
            cats = np.full(len(points), c, dtype=np.int64)
            z = prior_noise(ctx.rng, len(points), b.latents['dimensions'])
            log_dims, = ask(ctx.calls, 'dimensions', x, cats, z)
            log_dims = log_dims.astype(np.float64)
            if b.log_sigma is not None:
                # Drawn from the likelihood the bundle learned, by the room's own generator:
                # the same seed draws the same footprints in lockstep and alone.
                noise = ctx.rng.standard_normal(log_dims.shape)
                log_dims = log_dims + np.exp(b.log_sigma[c].astype(np.float64)) * noise
            dims = np.exp(log_dims).tolist()
        return [(d[0], d[1]) for d in dims]

    # ---- insertion: catalog retrieval and rejection -----------------------------------------
    def candidate_models(self, ctx: _Context, scene: Scene, category: str, width: float,
                         depth: float) -> list[catalog.ModelVariant]:
        """Catalog models from the best footprint fit; among those within ``fit_slack`` of
        the best (none but ties where the footprint was drawn from a learned spread), the
        ones that co-occur most with the models in the room come first (the user's models,
        which no training room holds, keep their footprint order)."""
        models = load_catalog(ctx.config.catalog, self.vocabulary)
        ranked = models.ranked(category, width, depth, ctx.spec.room_type, self.vocabulary)
        best = catalog.footprint_distance(ranked[0], width, depth)
        drawn = ctx.bundle.log_sigma is not None
        slack = 0.0 if drawn else ctx.config.fit_slack
        close = [v for v in ranked
                 if catalog.footprint_distance(v, width, depth) <= best + slack]
        rest = ranked[len(close):]
        b = ctx.bundle
        index = b.model_index
        present = [index[o.model_id] for o in scene.objects if o.model_id in index]
        if present and len(close) > 1:
            co = b.cooccurrence
            rooms = b.model_rooms[present]

            def affinity(v) -> float:
                k = index.get(v.model_id)
                if k is None:
                    return 0.0
                return float((co[k, present] / rooms).mean())
            close = sorted(close, key=lambda v: -affinity(v))
        return close + rest

    def _insert_model(self, ctx: _Context, scene: Scene, category: str, point: np.ndarray,
                      yaw: float, width: float, depth: float) -> PlacedObject | None:
        """The first of the ``models_per_location`` catalog models nearest the predicted
        footprint that stands at ``point`` facing ``yaw`` (pushed onto a wall it nearly
        touches, if it stands there too), or None."""
        second = ctx.spec.info(category).tier == 'second'
        parent = self._parent(ctx, scene, category, point) if second else None
        if second and parent is None:
            return None
        z = parent.top if parent is not None else 0.0
        models = self.candidate_models(ctx, scene, category, width, depth)
        for v in models[:ctx.config.models_per_location]:
            obj = PlacedObject(scene.new_id(category), category, v.model_id,
                               (float(point[0]), float(point[1]), float(z)), float(yaw),
                               v.size, parent.id if parent is not None else None)
            if parent is None and ctx.config.wall_reach > 0:
                pushed = against_walls(ctx.room, obj, ctx.config.wall_reach, ctx.rng)
                # A kitchen unit then joins the run beside it (a no-op elsewhere).
                joined = home.into_run(scene, pushed)
                if joined is not pushed and self.fits(ctx, scene, joined, parent):
                    return joined
                if pushed is not obj and self.fits(ctx, scene, pushed, parent):
                    return pushed
            if self.fits(ctx, scene, obj, parent):
                return obj
        return None

    @staticmethod
    def _parent(ctx: _Context, scene: Scene, category: str, point: np.ndarray
                ) -> PlacedObject | None:
        """The highest first-tier object of a supporting category under ``point``."""
        supports = set(ctx.spec.supports(category))
        pt = shapely.Point(float(point[0]), float(point[1]))
        under = [o for o in scene.first_tier
                 if o.category in supports and o.footprint().covers(pt)]
        return max(under, key=lambda o: o.top) if under else None

    def fits(self, ctx: _Context, scene: Scene, obj: PlacedObject,
             parent: PlacedObject | None = None) -> bool:
        """The insertion's rejection rules (see the module docstring)."""
        refused_by = self._refusal(ctx, scene, obj, parent)
        if self.observer is not None:
            self.observer.placement_checked(obj, refused_by)
        return refused_by is None

    def _refusal(self, ctx: _Context, scene: Scene, obj: PlacedObject,
                 parent: PlacedObject | None) -> str | None:
        """The first of ``fits``'s checks that refuses ``obj``, or None."""
        if not ctx.floor.covers(obj.footprint()):
            return 'floor'
        if obj.support is not None:
            if parent is None or support_fraction(obj, parent) < MIN_SUPPORT:
                return 'support'
            return 'sibling' if overlaps_any(obj, scene.children_of(parent.id)) else None
        if overlaps_any(obj, scene.first_tier, allowance=ctx.bundle.allowance):
            return 'collision'
        if any(enters_zone(obj, z) for z in ctx.zones):
            return 'door'
        after = Scene(scene.room, scene.objects + [obj])
        # The design rules kept at insertion, then the robot promise: what held before this
        # object must hold after it, and the object must keep them itself.
        for name in ctx.config.insertion_rules:
            changed_by = rule_categories(name, ctx.spec.room_type, self.vocabulary)
            if name in ctx.waived or (changed_by is not None and obj.category not in changed_by):
                continue
            key = (name, id(scene), len(scene.objects))
            if key not in ctx.rules:
                ctx.rules[key] = verdicts(name, scene, self.vocabulary)
            before = ctx.rules[key]
            now = verdicts(name, after, self.vocabulary, new=obj)
            if not all(ok or before.get(case) is False for case, ok in now.items()):
                return name
        if ctx.room.doors:
            before = self._robot_state(ctx, scene)
            now = robot.state_after(before, after, ctx.config.robot)
            if not robot.kept(before, now, len(after.first_tier) - 1):
                return 'robot'
            # The next step starts from it if ``obj`` goes in.
            ctx.robot[_first_tier_key(after)] = now
        return None

    def _robot_state(self, ctx: _Context, scene: Scene) -> RobotState:
        key = _first_tier_key(scene)
        if key not in ctx.robot:
            ctx.robot[key] = robot.state(scene, ctx.config.robot)
        return ctx.robot[key]


def _check_rules(config: SynthConfig) -> None:
    """SynthesisError unless insertion can keep each of ``config``'s insertion rules and
    owe a partner for each of its owed-partner rules; its other values are checked again
    (``SynthConfig.validate``: it may have been changed since it was made)."""
    config.validate()
    unknown = set(config.insertion_rules) - set(INSERTION_RULES)
    if unknown:
        raise SynthesisError(f'insertion cannot keep the design rule {quoted(min(unknown))}; '
                             f'it keeps {", ".join(INSERTION_RULES)}')
    unknown = set(config.owed_partners) - set(OWED_RULES)
    if unknown:
        raise SynthesisError(f'no partner can be owed for the rule {quoted(min(unknown))}; '
                             f'the rules that owe one are {", ".join(OWED_RULES)}')


def _first_tier_key(scene: Scene) -> tuple:
    """What the robot's state in ``scene`` depends on: its first-tier objects and where
    they stand (second-tier objects stand on them and change nothing for the robot)."""
    return tuple((o.id, o.placement) for o in scene.first_tier)


def _distinct(a: PlacedObject, b: PlacedObject) -> bool:
    if a.category != b.category:
        return True
    far = math.dist(a.position[:2], b.position[:2]) >= 0.5
    turned = abs(wrap_angle(a.yaw - b.yaw)) > math.radians(30)
    return far or turned
