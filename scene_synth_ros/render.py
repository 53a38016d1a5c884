"""Multi-channel top-down images of a scene: the input of every neural module of the paper.

An image is a float32 array shaped ``(C, N, N)`` whose channels are, in this order:

====  ==============  ========================================================================
 0    ``ROOM``        floor of the room (1 inside the floor polygon)
 1    ``WALL``        walls: outside the floor and within the wall reach of its outline
 2    ``OBJECT``      any object's footprint
 3    ``HEIGHT``      top height of the highest object at the pixel, metres / ``HEIGHT_SCALE``
 4    ``SIN``         sin of the yaw of that highest object, relative to the frame's yaw
 5    ``COS``         cos of the same (sin and cos are 0 where there is no object)
 6    ``DOOR``        door openings
 7    ``WINDOW``      window openings
 8..  categories      one channel per category of the room type, in ``room_spec(rt).names``
                      order (``FIRST_CATEGORY + index``), 1 inside that category's footprints
====  ==============  ========================================================================

Geometry of an image (``Frame``): a square of side ``extent`` metres centred at ``centre``
and rotated by ``yaw``, sampled by ``N x N`` pixels of ``m = extent / N`` metres. Pixel
(row ``i``, column ``j``) has its centre at the frame-local point
``u = (j + 0.5 - N/2) m``, ``v = (i + 0.5 - N/2) m`` and at the world point
``centre + R(yaw) (u, v)``. The row index grows with local +y: show images with
``origin='lower'`` to see them the way the world is drawn.

The room's frame (``Frame.for_room``, the global view the category and location modules
see and the only definition of it): the room is seen in its own axes, those of its longest
wall with the wall's direction reduced to [-45, 45) degrees (``room_axis_yaw``; 0 for an
axis-aligned room), centred on its bounding box in those axes. Its pixels are always the room
type's size (``size_cap`` metres over the networks' ``resolution`` pixels): a room that fits
the type's square is seen over that square, as the paper's rooms are; a larger one over a
larger square of as many more pixels as it needs, rounded up to a multiple the networks
divide evenly (the location module is fully convolutional and the category module pools
globally, so both take any size). Rooms up to ``MAX_ROOM_SIDE`` metres along their longer
side fit (``RoomDoesNotFit`` otherwise); layout validation asks the same question through
``room_frame_box``. Local views (``Frame.local``) have the same scale, centred at a point,
and always the networks' own size.

Pixel rule: a pixel belongs to a shape iff its centre lies inside the shape or on its boundary
(closed shapes; a tolerance of ``EPS_PX`` pixel absorbs floating-point rounding, so a centre
exactly on an edge counts as inside whatever rotation or whole-pixel shift produced it).
Everything is rasterised directly in the frame (polygons and boxes are transformed, then
tested at the pixel centres); nothing is resampled, so rotated local crops are as crisp as the
global view.

Objects are drawn in order of increasing top height (ties: scene order), so the highest object
at a pixel owns ``HEIGHT``, ``SIN`` and ``COS`` there: a second-tier object wins over its
parent.

Walls: a pixel is wall iff its centre is outside the floor polygon and within the wall reach
``max(WALL_BAND, m)`` of the floor outline (at least one pixel, so that coarse images
still have a closed wall ring).

Doors and windows are drawn as the rectangle of the opening: along its wall, the opening's
width centred at its position; across the wall, from ``max(OPENING_DEPTH, wall reach)``
outside to the same distance inside the floor outline (so the opening covers the wall pixels
it interrupts plus a strip of floor).
"""
from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass
from functools import lru_cache
import math
from typing import Iterable

import numpy as np

from .categories import PAPER, Vocabulary
from .errors import SceneSynthError, number, with_article
from .scene import Room, Scene
from .thresholds import MAX_ROOM_SIDE

# Channel indices.
ROOM = 0
WALL = 1
OBJECT = 2
HEIGHT = 3
SIN = 4
COS = 5
DOOR = 6
WINDOW = 7
FIRST_CATEGORY = 8
FIXED_CHANNEL_NAMES = ('room', 'wall', 'object', 'height', 'sin', 'cos', 'door', 'window')

HEIGHT_SCALE = 3.0        # metres: the HEIGHT channel holds top height / HEIGHT_SCALE
WALL_BAND = 0.15          # metres of wall drawn outside the floor outline (at least 1 pixel)
OPENING_DEPTH = 0.15      # metres a door/window rectangle reaches on each side of its wall
EPS_PX = 1e-6             # pixels: boundary tolerance of the pixel-centre rule
FIT_TOLERANCE = 1e-6      # metres a room may exceed its square by (rounding of its vertices)
DEFAULT_RESOLUTION = 64


# A room type's categories, and so its images' channels, are those of a vocabulary: the
# paper's unless a data set's is given (``categories.Vocabulary``).
def num_channels(room_type: str, vocabulary: Vocabulary = PAPER) -> int:
    """Number of channels of an image of ``room_type``."""
    return FIRST_CATEGORY + len(vocabulary.spec(room_type).names)


def channel_names(room_type: str, vocabulary: Vocabulary = PAPER) -> tuple[str, ...]:
    """Names of the channels of an image of ``room_type``, in order."""
    return FIXED_CHANNEL_NAMES + vocabulary.spec(room_type).names


def _category_channels(room_type: str, vocabulary: Vocabulary = PAPER) -> dict[str, int]:
    return _channels_of(vocabulary.spec(room_type).names)


@lru_cache(maxsize=64)
def _channels_of(names: tuple[str, ...]) -> dict[str, int]:
    # Keyed by the category list, not the room type's name: a data set's vocabulary may
    # have a type of the same name with other categories (categories.Vocabulary).
    return {name: FIRST_CATEGORY + k for k, name in enumerate(names)}


def category_channel(room_type: str, category: str, vocabulary: Vocabulary = PAPER) -> int:
    """Channel index of ``category`` in images of ``room_type``."""
    try:
        return _category_channels(room_type, vocabulary)[category]
    except KeyError:
        raise ValueError(f'category {category!r} is not one of the {room_type} categories') \
            from None


# --------------------------------------------------------------------------------------------
# Frames and coordinate conversions
# --------------------------------------------------------------------------------------------

def room_axis_yaw(room: Room) -> float:
    """Direction of the room's longest wall reduced to [-45, 45) degrees: the yaw of the
    room's frame (0 for an axis-aligned room; the first of equally long walls decides)."""
    wall = max(room.walls, key=lambda w: w.length)
    d = wall.direction
    q = math.pi / 2
    return (math.atan2(d[1], d[0]) + q / 2) % q - q / 2


@dataclass(frozen=True)
class RoomFrameBox:
    """A room's bounding box in its own axes, its type's square and the largest room."""

    room_type: str
    yaw: float
    centre: tuple[float, float]    # world coordinates of the box centre
    span: tuple[float, float]      # metres along the frame's u and v axes
    cap: float                     # side of the room type's square, metres

    @property
    def bound(self) -> float:
        """The longest side a room of this type may have, metres: ``MAX_ROOM_SIDE``, or the
        type's square where a data set's type has a larger one."""
        return max(self.cap, MAX_ROOM_SIDE)

    @property
    def fits(self) -> bool:
        return max(self.span) <= self.bound + FIT_TOLERANCE

    @property
    def in_square(self) -> bool:
        """Whether the room fits its type's square (and is seen at the networks' size)."""
        return max(self.span) <= self.cap + FIT_TOLERANCE


def room_frame_box(room: Room, vocabulary: Vocabulary = PAPER) -> RoomFrameBox:
    """The room measured in its frame's axes (see the module docstring)."""
    rt = vocabulary.resolve(room.room_type)
    yaw = room_axis_yaw(room)
    cap = vocabulary.spec(rt).size_cap
    axes = Frame((0.0, 0.0), yaw, cap, 1)     # the room's axes through the origin
    uv = axes.to_local(np.asarray(room.floor, dtype=float))
    lo, hi = uv.min(axis=0), uv.max(axis=0)
    centre = axes.to_world((lo + hi) / 2.0)
    return RoomFrameBox(rt, yaw, (float(centre[0]), float(centre[1])),
                        (float(hi[0] - lo[0]), float(hi[1] - lo[1])), cap)


class RoomDoesNotFit(SceneSynthError, ValueError):
    """A room longer, in its own axes, than the longest a room may be (``RoomFrameBox``)."""

    def __init__(self, box: RoomFrameBox, subject: str | None = None):
        self.box = box
        rt = box.room_type
        long_, short = (number(v) for v in sorted(box.span, reverse=True))
        super().__init__(f'{subject or "the " + rt} is {long_} m x {short} m along its walls, '
                         f'longer than the {number(box.bound)} m {with_article(rt)} may be '
                         f'along its longer side')


@dataclass(frozen=True)
class Frame:
    """The square of the world an image covers (see the module docstring for the geometry)."""

    centre: tuple[float, float]
    yaw: float
    extent: float          # side of the square, metres
    resolution: int        # N: the image is N x N pixels

    def __post_init__(self):
        object.__setattr__(self, 'centre', (float(self.centre[0]), float(self.centre[1])))
        object.__setattr__(self, 'yaw', float(self.yaw))
        object.__setattr__(self, 'extent', float(self.extent))
        object.__setattr__(self, 'resolution', int(self.resolution))
        if self.extent <= 0 or self.resolution <= 0:
            raise ValueError('a frame needs a positive extent and resolution')

    @property
    def metres_per_pixel(self) -> float:
        return self.extent / self.resolution

    @classmethod
    def for_room(cls, room: Room, resolution: int = DEFAULT_RESOLUTION,
                 vocabulary: Vocabulary = PAPER, multiple: int = 1) -> 'Frame':
        """The room's frame (see the module docstring): its type's square at ``resolution``
        pixels, or for a room larger than that square, as many more pixels of the same size
        as it needs, a multiple of ``multiple``; ``RoomDoesNotFit`` if the room is longer
        than a room may be."""
        box = room_frame_box(room, vocabulary)
        if not box.fits:
            raise RoomDoesNotFit(box)
        if box.in_square:
            return cls(box.centre, box.yaw, box.cap, resolution)
        n = grown_resolution(max(box.span), box.cap / resolution, multiple)
        return cls(box.centre, box.yaw, n * box.cap / resolution, n)

    @classmethod
    def local(cls, room_type: str, point: Iterable[float], yaw: float,
              resolution: int = DEFAULT_RESOLUTION, vocabulary: Vocabulary = PAPER
              ) -> 'Frame':
        """A view of the same scale as the global one, centred at ``point`` (x, y; a z is
        ignored) and rotated by ``yaw``: in it, world direction ``yaw`` is the image's +u
        (column) axis."""
        p = tuple(point)
        return cls((p[0], p[1]), yaw, vocabulary.spec(room_type).size_cap, resolution)

    # World <-> frame-local metres.
    def to_local(self, xy) -> np.ndarray:
        """World points (..., 2) to frame-local metres (u, v)."""
        d = np.asarray(xy, dtype=float)[..., :2] - np.asarray(self.centre)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return np.stack([c * d[..., 0] + s * d[..., 1], -s * d[..., 0] + c * d[..., 1]], -1)

    def to_world(self, uv) -> np.ndarray:
        """Frame-local metres (..., 2) to world points."""
        uv = np.asarray(uv, dtype=float)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        return np.stack([self.centre[0] + c * uv[..., 0] - s * uv[..., 1],
                         self.centre[1] + s * uv[..., 0] + c * uv[..., 1]], -1)

    def world_to_pixel(self, xy, continuous: bool = False) -> np.ndarray:
        return world_to_pixel(self, xy, continuous)

    def pixel_to_world(self, ij) -> np.ndarray:
        return pixel_to_world(self, ij)


def grown_resolution(side: float, metres_per_pixel: float, multiple: int = 1) -> int:
    """Pixels of a square of at least ``side`` metres at ``metres_per_pixel``, rounded up to
    a multiple of ``multiple``."""
    multiple = max(1, int(multiple))
    pixels = math.ceil((side - FIT_TOLERANCE) / metres_per_pixel - EPS_PX)
    return max(multiple, -(-pixels // multiple) * multiple)


def pixel_to_world(frame: Frame, ij) -> np.ndarray:
    """World (x, y) of pixel coordinates ``ij`` = (..., 2) as (row, col). Integer coordinates
    give pixel centres; fractional ones interpolate (pixel (i, j) covers [i-0.5, i+0.5) x
    [j-0.5, j+0.5) in these units)."""
    ij = np.asarray(ij, dtype=float)
    m, half = frame.metres_per_pixel, frame.resolution / 2.0
    uv = np.stack([(ij[..., 1] + 0.5 - half) * m, (ij[..., 0] + 0.5 - half) * m], -1)
    return frame.to_world(uv)


def world_to_pixel(frame: Frame, xy, continuous: bool = False) -> np.ndarray:
    """Pixel (row, col) of world points ``xy`` (..., 2).

    By default the integer index of the pixel containing each point (a point on a pixel border
    goes to the higher index; indices outside [0, N) mean outside the image). With
    ``continuous=True`` the fractional coordinates, the exact inverse of ``pixel_to_world``."""
    uv = frame.to_local(xy)
    m, half = frame.metres_per_pixel, frame.resolution / 2.0
    rc = np.stack([uv[..., 1] / m + half - 0.5, uv[..., 0] / m + half - 0.5], -1)
    if continuous:
        return rc
    return np.floor(rc + 0.5).astype(np.int64)


# --------------------------------------------------------------------------------------------
# Rasterisation (all in pixel-centre coordinates: pixel (i, j) is the point x = j, y = i)
# --------------------------------------------------------------------------------------------

def quarter_turns(angle: float, tol: float = 1e-9) -> int | None:
    """How many quarter turns (0-3, anticlockwise) ``angle`` is, or None when it is not
    within ``tol`` of a multiple of 90 degrees."""
    q = round(angle / (math.pi / 2))
    if abs(angle - q * (math.pi / 2)) > tol:
        return None
    return q % 4


def turn_image(image: np.ndarray, q: int) -> None:
    """Turns ``image`` (C, N, N), drawn in a frame, in place into the image of the same scene
    in that frame turned by ``q`` quarter turns about its centre (``Frame.yaw`` + q x 90
    degrees), without drawing it again.

    Pixel centres sit symmetrically about the frame's centre, so a quarter turn of the frame
    maps the grid onto itself: pixel (i, j) of the turned frame is pixel (j, N - 1 - i) of
    this one (``np.rot90``), and every mask is the one drawn in the turned frame. Only the
    yaws relative to the frame change: SIN and COS become those of ``theta - q x 90``
    degrees (to float32 rounding of the direct computation)."""
    q %= 4
    if not q:
        return
    # Turned whole pixels at a time: for an image laid out channels-last (the synthesizer's
    # on the CPU) 85 us, 5x less than drawing a crop; laid out channels-first it is a
    # strided copy as slow as drawing.
    pixels = np.moveaxis(image, 0, -1)
    turned = np.rot90(pixels, q, axes=(0, 1)).copy()
    sin, cos = turned[..., SIN].copy(), turned[..., COS].copy()
    turned[..., SIN], turned[..., COS] = {1: (-cos, sin), 2: (-sin, -cos), 3: (cos, -sin)}[q]
    pixels[...] = turned


def _to_px(frame: Frame, x: float, y: float) -> tuple[float, float]:
    """World point to pixel-centre coordinates (col, row) as floats.

    The scalar twin of ``world_to_pixel(..., continuous=True)``: the per-object loop of
    ``render`` calls it for every object, where numpy's per-call overhead would dominate."""
    c, s = math.cos(frame.yaw), math.sin(frame.yaw)
    dx, dy = x - frame.centre[0], y - frame.centre[1]
    m, half = frame.metres_per_pixel, frame.resolution / 2.0 - 0.5
    return (c * dx + s * dy) / m + half, (-s * dx + c * dy) / m + half


def _box_window(n: int, cx: float, cy: float, theta: float, hx: float, hy: float):
    """Pixels of a rotated box (pixel units): centre (cx, cy), axis ``theta``, half extents
    ``hx`` along the axis, ``hy`` across. Returns (r0, r1, c0, c1, mask) with ``mask`` the
    boolean pixels of rows r0:r1, columns c0:c1, or None if no pixel centre is inside."""
    c, s = math.cos(theta), math.sin(theta)
    ex = abs(c) * hx + abs(s) * hy
    ey = abs(s) * hx + abs(c) * hy
    r0 = max(0, math.ceil(cy - ey - EPS_PX))
    r1 = min(n, math.floor(cy + ey + EPS_PX) + 1)
    c0 = max(0, math.ceil(cx - ex - EPS_PX))
    c1 = min(n, math.floor(cx + ex + EPS_PX) + 1)
    if r0 >= r1 or c0 >= c1:
        return None
    dy = (np.arange(r0, r1, dtype=float) - cy)[:, None]
    dx = (np.arange(c0, c1, dtype=float) - cx)[None, :]
    a = dx * c + dy * s
    b = dy * c - dx * s
    mask = (np.abs(a) <= hx + EPS_PX) & (np.abs(b) <= hy + EPS_PX)
    if not mask.any():
        return None
    return r0, r1, c0, c1, mask


def _polygon_parity(n: int, px: np.ndarray, py: np.ndarray) -> np.ndarray:
    """Even-odd inside test of all pixel centres against a closed polygon (pixel units), by
    scanlines: each edge toggles, on every row it crosses, the pixels left of the crossing."""
    rows_all, ks_all = [], []
    k = len(px)
    for e in range(k):
        x0, y0, x1, y1 = px[e], py[e], px[(e + 1) % k], py[(e + 1) % k]
        if y0 == y1:
            continue
        lo, hi = (y0, y1) if y0 < y1 else (y1, y0)
        r_lo, r_hi = max(0, math.ceil(lo)), min(n, math.ceil(hi))   # rows with lo <= r < hi
        if r_lo >= r_hi:
            continue
        rows = np.arange(r_lo, r_hi)
        xc = x0 + (rows - y0) * ((x1 - x0) / (y1 - y0))
        rows_all.append(rows)
        ks_all.append(np.clip(np.ceil(xc), 0, n).astype(np.int64))   # toggles j < xc
    if not rows_all:
        return np.zeros((n, n), dtype=bool)
    rows = np.concatenate(rows_all)
    ks = np.concatenate(ks_all)
    d = np.bincount(rows * (n + 1) + ks, minlength=n * (n + 1)).reshape(n, n + 1)
    counts = np.cumsum(d[:, ::-1], axis=1)[:, ::-1]     # counts[:, j] = crossings with k >= j
    return (counts[:, 1:] & 1).astype(bool)             # pixel j: crossings with k > j


def _boundary_distance2(n: int, px: np.ndarray, py: np.ndarray, reach: float) -> np.ndarray:
    """Squared distance (pixels^2) from every pixel centre to the polygon's outline, exact
    within ``reach`` pixels of it and +inf (or larger than reach^2) beyond."""
    d2 = np.full((n, n), np.inf)
    k = len(px)
    for e in range(k):
        x0, y0, x1, y1 = px[e], py[e], px[(e + 1) % k], py[(e + 1) % k]
        r0 = max(0, math.ceil(min(y0, y1) - reach))
        r1 = min(n, math.floor(max(y0, y1) + reach) + 1)
        c0 = max(0, math.ceil(min(x0, x1) - reach))
        c1 = min(n, math.floor(max(x0, x1) + reach) + 1)
        if r0 >= r1 or c0 >= c1:
            continue
        ex, ey = x1 - x0, y1 - y0
        ll = ex * ex + ey * ey
        qy = (np.arange(r0, r1, dtype=float) - y0)[:, None]
        qx = (np.arange(c0, c1, dtype=float) - x0)[None, :]
        t = np.clip((qx * ex + qy * ey) / ll, 0.0, 1.0) if ll > 0 else 0.0
        dd = (qx - t * ex) ** 2 + (qy - t * ey) ** 2
        np.minimum(d2[r0:r1, c0:c1], dd, out=d2[r0:r1, c0:c1])
    return d2


# --------------------------------------------------------------------------------------------
# Room geometry and the static (architecture) layers
# --------------------------------------------------------------------------------------------

def _room_key(room: Room):
    return (room.room_type, room.floor, room.doors, room.windows)


def _opening_boxes(room: Room) -> list[tuple[int, float, float, float, float]]:
    """(channel, cx, cy, wall angle, half width) of every door and window, in world units."""
    out = []
    for channel, openings in ((DOOR, room.doors), (WINDOW, room.windows)):
        for op in openings:
            wall = room.wall_of(op)
            if wall is None:     # not within tolerance of a wall: use the nearest one
                wall = min(room.walls, key=lambda w: w.distance_to(op.position))
            dx, dy = wall.direction
            out.append((channel, op.position[0], op.position[1], math.atan2(dy, dx),
                        op.width / 2.0))
    return out


def wall_reach(frame: Frame) -> float:
    """Metres outside the floor outline that are drawn as wall in ``frame``."""
    return max(WALL_BAND, frame.metres_per_pixel)


def static_layers(room: Room, frame: Frame, openings=None) -> np.ndarray:
    """The architecture of ``room`` in ``frame``: float32 (4, N, N) = room, wall, door,
    window masks (uncached; ``TopDownRenderer`` caches them)."""
    n = frame.resolution
    m = frame.metres_per_pixel
    pts = np.array([_to_px(frame, x, y) for x, y in room.floor])
    px, py = pts[:, 0], pts[:, 1]
    reach_m = wall_reach(frame)
    reach = reach_m / m + EPS_PX
    d2 = _boundary_distance2(n, px, py, reach)
    floor = _polygon_parity(n, px, py) | (d2 <= EPS_PX * EPS_PX)
    wall = ~floor & (d2 <= reach * reach)
    out = np.zeros((4, n, n), dtype=np.float32)
    out[0] = floor
    out[1] = wall
    if openings is None:
        openings = _opening_boxes(room)
    for channel, x, y, angle, half_w in openings:
        cx, cy = _to_px(frame, x, y)
        win = _box_window(n, cx, cy, angle - frame.yaw, half_w / m,
                          max(OPENING_DEPTH, reach_m) / m)
        if win is not None:
            r0, r1, c0, c1, mask = win
            out[2 if channel == DOOR else 3, r0:r1, c0:c1][mask] = 1.0
    return out


class _LRU:
    def __init__(self, maxsize: int):
        self.maxsize = maxsize
        self.data: OrderedDict = OrderedDict()

    def get(self, key):
        value = self.data.get(key)
        if value is not None:
            self.data.move_to_end(key)
        return value

    def put(self, key, value):
        self.data[key] = value
        self.data.move_to_end(key)
        while len(self.data) > self.maxsize:
            self.data.popitem(last=False)

    def clear(self):
        self.data.clear()


# --------------------------------------------------------------------------------------------
# The renderer
# --------------------------------------------------------------------------------------------

class TopDownRenderer:
    """Renders scenes to ``(C, N, N)`` float32 images (see the module docstring).

    The architecture layers are cached per (room, frame) in a small LRU keyed on the room's
    content (type, floor, doors, windows) and the frame, so furnishing a room object by
    object re-rasterises only the objects. A scene's categories are those its room type has
    in ``vocabulary`` (default: the paper's table)."""

    def __init__(self, resolution: int = DEFAULT_RESOLUTION, cache_size: int = 32,
                 vocabulary: Vocabulary = PAPER):
        self.resolution = int(resolution)
        self.vocabulary = vocabulary
        self._static = _LRU(cache_size)
        self._rooms = _LRU(max(8, cache_size))

    def clear_cache(self) -> None:
        self._static.clear()
        self._rooms.clear()

    def num_channels(self, room_type: str) -> int:
        return num_channels(room_type, self.vocabulary)

    def static_layers(self, room: Room, frame: Frame, keep: bool = True) -> np.ndarray:
        """Cached (4, N, N) room, wall, door, window masks. Do not modify the result.
        ``keep=False``: a frame seen once (a crop's), not kept, so that it does not push the
        frames that are seen again (each room's own) out of the cache."""
        rkey = _room_key(room)
        key = (rkey, frame)
        layers = self._static.get(key)
        if layers is None:
            openings = self._rooms.get(rkey)
            if openings is None:
                openings = _opening_boxes(room)
                self._rooms.put(rkey, openings)
            layers = static_layers(room, frame, openings)
            if keep:
                self._static.put(key, layers)
        return layers

    def render(self, scene: Scene, frame: Frame | None = None,
               out: np.ndarray | None = None, keep: bool = True) -> np.ndarray:
        """The image of ``scene`` in ``frame`` (default: the room's frame, the global view
        the category and location modules see), drawn into ``out`` when given (a float32
        array of the image's shape, overwritten: the synthesizer reuses one per room for
        its crops instead of allocating and stacking fresh ones). ``keep``: whether the
        frame's architecture layers are cached (``static_layers``)."""
        room = scene.room
        if frame is None:
            frame = Frame.for_room(room, self.resolution, self.vocabulary)
        channels = _category_channels(room.room_type, self.vocabulary)
        objs = sorted(scene.objects, key=lambda o: o.top)
        chans = []
        for o in objs:
            ch = channels.get(o.category)
            if ch is None:
                raise ValueError(f'object {o.id!r} has category {o.category!r}, which is not '
                                 f'one of the {room.room_type} categories')
            chans.append(ch)

        n = frame.resolution
        shape = (FIRST_CATEGORY + len(channels), n, n)
        if out is None:
            out = np.zeros(shape, dtype=np.float32)
        elif out.shape != shape or out.dtype != np.float32:
            raise ValueError(f'render needs a float32 array of shape {shape} to draw into, '
                             f'got {out.dtype} {out.shape}')
        else:
            out.fill(0.0)
        static = self.static_layers(room, frame, keep)
        out[ROOM:WALL + 1] = static[0:2]
        out[DOOR:WINDOW + 1] = static[2:4]

        m = frame.metres_per_pixel
        fyaw = frame.yaw
        for o, ch in zip(objs, chans, strict=True):
            cx, cy = _to_px(frame, o.position[0], o.position[1])
            theta = o.yaw - fyaw
            win = _box_window(n, cx, cy, theta, o.size[1] / (2.0 * m), o.size[0] / (2.0 * m))
            if win is None:
                continue
            r0, r1, c0, c1, mask = win
            out[OBJECT, r0:r1, c0:c1][mask] = 1.0
            out[ch, r0:r1, c0:c1][mask] = 1.0
            out[HEIGHT, r0:r1, c0:c1][mask] = o.top / HEIGHT_SCALE
            out[SIN, r0:r1, c0:c1][mask] = math.sin(theta)
            out[COS, r0:r1, c0:c1][mask] = math.cos(theta)
        return out

    def render_local(self, scene: Scene, point, yaw: float) -> np.ndarray:
        """The image of ``scene`` in ``Frame.local(room_type, point, yaw)``: what the
        orientation and dimension modules see for an object placed at ``point``."""
        return self.render(scene, Frame.local(scene.room.room_type, point, yaw,
                                              self.resolution, self.vocabulary))
