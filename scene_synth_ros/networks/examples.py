"""Training examples made from furnished rooms by removing objects (paper, section 4).

Ordering rules: every first-tier object comes before every second-tier one (so supporting
parents come before what they support); within a tier, the category module sees objects in
decreasing importance of their category and the other modules in random order. A partial
scene is a prefix of that order. The location target marks the centroid of every removed
object whose supporting parent is present. Every example may be turned by a multiple of 90
degrees about the room's centre (the paper's augmentation).
"""
from __future__ import annotations

from dataclasses import replace
import math

import numpy as np
import torch

from ..categories import PAPER, Vocabulary
from ..render import Frame, TopDownRenderer
from ..scene import Opening, PlacedObject, Room, Scene, wrap_angle
from . import NETWORKS
from .orientation import is_snapped


# ---- augmentation -------------------------------------------------------------------------
def _turn(xy, centre, k: int):
    x, y = xy[0] - centre[0], xy[1] - centre[1]
    for _ in range(k % 4):
        x, y = -y, x
    return (x + centre[0], y + centre[1])


def rotate_scene(scene: Scene, k: int) -> Scene:
    """The scene turned by ``k`` x 90 degrees counter-clockwise about its bounding-box
    centre (coordinates are only swapped and negated about the centre, so the images of the
    turned scene are the turned images, pixel for pixel)."""
    k %= 4
    if k == 0:
        return scene
    xs = [p[0] for p in scene.room.floor]
    ys = [p[1] for p in scene.room.floor]
    centre = ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)
    room = scene.room

    def turn_opening(o: Opening) -> Opening:
        return replace(o, position=_turn(o.position, centre, k))

    room = Room(room.room_type, [_turn(p, centre, k) for p in room.floor], room.wall_height,
                tuple(turn_opening(o) for o in room.doors),
                tuple(turn_opening(o) for o in room.windows))
    objs = []
    for o in scene.objects:
        x, y = _turn(o.position, centre, k)
        yaw = wrap_angle(o.yaw + k * math.pi / 2)
        objs.append(replace(o, position=(x, y, o.position[2]), yaw=yaw))
    return Scene(room, objs, dict(scene.meta))


# ---- ordering -----------------------------------------------------------------------------
def insertion_order(scene: Scene, rng: np.random.Generator, by_importance: bool,
                    vocabulary: Vocabulary = PAPER) -> list[PlacedObject]:
    """The objects in the order the pipeline would insert them (see the module docstring);
    ties in importance are broken at random. The room type's importance order is that of
    ``vocabulary``."""
    spec = vocabulary.spec(scene.room.room_type)
    rank = {name: k for k, name in enumerate(spec.importance_order())}
    out = []
    for tier in (scene.first_tier, scene.second_tier):
        objs = list(tier)
        noise = rng.random(len(objs))
        if by_importance:
            keys = [(rank[o.category], r) for o, r in zip(objs, noise, strict=True)]
        else:
            keys = [(r,) for r in noise]
        out += [o for _, o in sorted(zip(keys, objs, strict=True), key=lambda t: t[0])]
    return out


def placeable(removed: list[PlacedObject], kept: list[PlacedObject]) -> list[PlacedObject]:
    """The removed objects that could be inserted next: first tier, or whose parent is kept."""
    ids = {o.id for o in kept}
    return [o for o in removed if o.support is None or o.support in ids]


# ---- examples -----------------------------------------------------------------------------
class _Pool:
    """Training rooms (indices into a source's list) to draw from, uniformly or in
    proportion to their states."""

    def __init__(self, index: np.ndarray, states: np.ndarray):
        self.index = index
        self._cdf = np.cumsum(states[index]) / states[index].sum()

    def draw(self, rng: np.random.Generator, per_state: bool) -> int:
        if per_state:
            k = min(int(np.searchsorted(self._cdf, rng.random(), side='right')),
                    len(self.index) - 1)
        else:
            k = int(rng.integers(len(self.index)))
        return int(self.index[k])


class SizeBuckets:
    """Training rooms grouped by the side of their image, smallest first, each group of
    whole image sizes and at least ``least`` rooms (the last takes what is left over).

    A batch is padded to its largest image, so the cost of a step follows its largest room:
    a batch drawn from one group costs about what its own rooms cost. Drawing the group of
    a first room drawn from all rooms, then every room of the batch within that group,
    leaves each room's chance to be in a batch as it was (``pool``)."""

    def __init__(self, sides: list[int], states: np.ndarray, least: int):
        if least < 1:
            raise ValueError(f'size buckets of at least {least} rooms: give 1 or more '
                             f'(train.size_buckets; 0 turns them off)')
        sides = np.asarray(sides)
        order = np.argsort(sides, kind='stable')
        groups: list[list[int]] = [[]]
        for n in np.unique(sides):
            if len(groups[-1]) >= least:
                groups.append([])
            groups[-1] += [int(k) for k in order if sides[k] == n]
        if len(groups) > 1 and len(groups[-1]) < least:
            last = groups.pop()
            groups[-1] += last
        self.groups = [_Pool(np.array(g), states) for g in groups]
        self._group_of = np.empty(len(sides), dtype=int)
        for g, pool in enumerate(self.groups):
            self._group_of[pool.index] = g
        self._all = _Pool(np.arange(len(sides)), states)

    def pool(self, rng: np.random.Generator, per_state: bool) -> _Pool:
        return self.groups[self._group_of[self._all.draw(rng, per_state)]]


class ExampleSource:
    """Makes batches of training examples for each module from a list of furnished rooms of
    one type. A batch is a pure function of its seed, so a resumed run sees the same data.
    The room type's categories are those of ``vocabulary`` (a data set's, or the paper's)."""

    def __init__(self, room_type: str, scenes: list[Scene], resolution: int,
                 location_resolution: int, augment: bool = True, target_radius: int = 0,
                 vocabulary: Vocabulary = PAPER, multiple: int = 1, size_buckets: int = 0):
        self.vocabulary = vocabulary
        self.room_type = vocabulary.resolve(room_type)
        self.spec = vocabulary.spec(self.room_type)
        self.index = {n: k for k, n in enumerate(self.spec.names)}
        # An empty room teaches only STOP, and has no object to orient or size.
        self.scenes = [s for s in scenes if s.objects]
        if not self.scenes:
            raise ValueError(f'no furnished {self.room_type} among the {len(scenes)} rooms given')
        self.resolution = resolution
        self.location_resolution = location_resolution
        # A room larger than its type's square is seen as synthesis sees it: a larger image
        # whose side is a multiple of this (the location module's ``multiple``).
        self.multiple = multiple
        self.augment = augment
        self.target_radius = target_radius
        self.renderer = TopDownRenderer(resolution, cache_size=64, vocabulary=vocabulary)
        self._renderers = {resolution: self.renderer}   # the rooms' frames', by their size
        # A room of N objects is N + 1 states of the sequential model (0 ... N objects
        # placed); drawing rooms in proportion to that draws states as synthesis meets them.
        self._states = np.array([len(s.objects) + 1 for s in self.scenes], dtype=float)
        self._all = _Pool(np.arange(len(self.scenes)), self._states)
        self._buckets = SizeBuckets(
            [self._frame(s.room).resolution for s in self.scenes], self._states,
            size_buckets) if size_buckets else None

    @property
    def extent(self) -> float:
        """Metres of room an image at the networks' resolution covers (the room type's size
        cap; a larger room's image covers more, at the same pixels)."""
        return self.spec.size_cap

    @property
    def num_categories(self) -> int:
        return len(self.spec.names)

    def _scene(self, rng, per_state: bool = False, pool: _Pool | None = None) -> Scene:
        """A training room of ``pool`` (default: all), uniformly, or with ``per_state`` in
        proportion to its number of states (objects + 1)."""
        scene = self.scenes[(pool or self._all).draw(rng, per_state)]
        return rotate_scene(scene, int(rng.integers(4))) if self.augment else scene

    def counts(self, objects) -> np.ndarray:
        c = np.zeros(self.num_categories, dtype=np.float32)
        for o in objects:
            c[self.index[o.category]] += 1
        return c

    # One example of each kind. Each returns a tuple of numpy arrays / numbers.
    def category_example(self, rng, pool: _Pool | None = None):
        # Uniform over (room, prefix) pairs, the states synthesis visits: drawing the room
        # uniformly and then the prefix would weigh a prefix of an N-object room 1 / (N + 1),
        # overweighting complete small rooms and so teaching STOP too early
        # (docs/design/investigations.md).
        scene = self._scene(rng, per_state=True, pool=pool)
        order = insertion_order(scene, rng, by_importance=True,
                                vocabulary=self.vocabulary)
        k = int(rng.integers(len(order) + 1))
        part = Scene(scene.room, order[:k])
        frame = self._frame(scene.room)
        image = self._renderer(frame).render(part, frame)
        target = self.index[order[k].category] if k < len(order) else self.num_categories
        return image, self.counts(order[:k]), target

    def location_example(self, rng, pool: _Pool | None = None):
        scene = self._scene(rng, pool=pool)
        order = insertion_order(scene, rng, by_importance=False,
                                vocabulary=self.vocabulary)
        k = int(rng.integers(len(order) + 1))
        kept, removed = order[:k], order[k:]
        frame = self._frame(scene.room)
        image = self._renderer(frame).render(Scene(scene.room, kept), frame)
        target, offset = self.location_target(frame, placeable(removed, kept))
        return image, target, offset

    def _frame(self, room) -> Frame:
        return Frame.for_room(room, self.resolution, self.vocabulary, self.multiple)

    def _renderer(self, frame: Frame) -> TopDownRenderer:
        n = frame.resolution
        if n not in self._renderers:
            self._renderers[n] = TopDownRenderer(n, cache_size=64, vocabulary=self.vocabulary)
        return self._renderers[n]

    def location_target(self, frame: Frame, objects) -> tuple[np.ndarray, np.ndarray]:
        """Per-pixel labels on the location grid: 0, or 1 + the category of an object whose
        centroid is within ``target_radius`` pixels (0: the centroid's pixel alone, as in the
        paper; larger radii give a sparse target more positive pixels to learn from); and
        (2 x L x L) the offset from each labelled pixel's centre to that centroid, in pixels
        (row, col; 0 elsewhere)."""
        n = frame.resolution * self.location_resolution // self.resolution
        r = self.target_radius
        out = np.zeros((n, n), dtype=np.int64)
        offset = np.zeros((2, n, n), dtype=np.float32)
        grid = Frame(frame.centre, frame.yaw, frame.extent, n)
        rows, cols = np.mgrid[0:n, 0:n]
        for o in objects:
            i, j = grid.world_to_pixel(o.position[:2])
            if 0 <= i < n and 0 <= j < n:
                block = np.s_[max(i - r, 0):i + r + 1, max(j - r, 0):j + r + 1]
                out[block] = 1 + self.index[o.category]
                ci, cj = grid.world_to_pixel(o.position[:2], continuous=True)
                offset[0][block] = ci - rows[block]
                offset[1][block] = cj - cols[block]
        return out, offset

    def _target_object(self, rng):
        """A partial scene and one object that could be inserted into it next."""
        scene = self._scene(rng)
        order = insertion_order(scene, rng, by_importance=False,
                                vocabulary=self.vocabulary)
        k = int(rng.integers(len(order)))
        kept, removed = order[:k], order[k:]
        cands = placeable(removed, kept)
        return Scene(scene.room, kept), cands[int(rng.integers(len(cands)))]

    def orientation_example(self, rng):
        part, obj = self._target_object(rng)
        frame = self._frame(part.room)
        image = self.renderer.render(part, Frame.local(self.room_type, obj.position, frame.yaw,
                                                       self.resolution, self.vocabulary))
        theta = wrap_angle(obj.yaw - frame.yaw)
        return image, self.index[obj.category], theta

    def dimensions_example(self, rng):
        part, obj = self._target_object(rng)
        image = self.renderer.render(part, Frame.local(self.room_type, obj.position, obj.yaw,
                                                       self.resolution, self.vocabulary))
        return image, self.index[obj.category], (math.log(obj.depth), math.log(obj.width))

    # Batches as tensors.
    def batch(self, module: str, seed, size: int, by_size: bool = True
              ) -> dict[str, torch.Tensor]:
        """``size`` examples for ``module``, a pure function of ``seed``. With size buckets
        and ``by_size``, a category or location batch holds rooms of one bucket: the first
        room's, drawn as any room is, so every room keeps its chance to be drawn."""
        rng = np.random.default_rng(seed)
        pool = None
        if by_size and self._buckets is not None and module in ('category', 'location'):
            pool = self._buckets.pool(rng, per_state=module == 'category')
        if module == 'category':
            ex = [self.category_example(rng, pool) for _ in range(size)]
            return {'image': padded_batch(e[0] for e in ex), 'counts': _stack(e[1] for e in ex),
                    'target': torch.tensor([e[2] for e in ex])}
        if module == 'location':
            ex = [self.location_example(rng, pool) for _ in range(size)]
            return {'image': padded_batch(e[0] for e in ex),
                    'target': padded_batch(e[1] for e in ex),
                    'offset': padded_batch(e[2] for e in ex)}
        if module in ('orientation', 'snap'):
            ex = [self.orientation_example(rng) for _ in range(size)]
            theta = torch.tensor([e[2] for e in ex], dtype=torch.float32)
            return {'image': _stack(e[0] for e in ex),
                    'category': torch.tensor([e[1] for e in ex]),
                    'theta': theta, 'snapped': is_snapped(theta).float()}
        if module == 'dimensions':
            ex = [self.dimensions_example(rng) for _ in range(size)]
            return {'image': _stack(e[0] for e in ex),
                    'category': torch.tensor([e[1] for e in ex]),
                    'target': torch.tensor([e[2] for e in ex], dtype=torch.float32)}
        raise ValueError(f'unknown module {module!r}; expected one of {", ".join(NETWORKS)}')


def _stack(arrays) -> torch.Tensor:
    return torch.from_numpy(np.stack(list(arrays)))


def padded_batch(arrays) -> torch.Tensor:
    """Images (or location targets) of rooms of several sizes as one batch, each in the
    middle of the largest: the pixels around a smaller room are those of a larger frame
    about the same centre, all zero (nothing there; "empty" in a target), since frames grow
    by an even number of pixels."""
    arrays = list(arrays)
    n = max(a.shape[-1] for a in arrays)
    if all(a.shape[-1] == n for a in arrays):
        return _stack(arrays)
    out = np.zeros((len(arrays),) + arrays[0].shape[:-2] + (n, n), dtype=arrays[0].dtype)
    for k, a in enumerate(arrays):
        p = (n - a.shape[-1]) // 2
        out[k, ..., p:p + a.shape[-2], p:p + a.shape[-1]] = a
    return torch.from_numpy(out)
