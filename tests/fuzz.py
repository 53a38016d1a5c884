"""Hypothesis strategies for what reaches the package from outside: room layouts that are
mostly well formed (real outlines, openings on walls, objects of the room's categories) with
the corruptions a fuzzer finds (near-repeated and near-closing vertices, far offsets, slivers,
huge or non-finite numbers, deep nesting, strange keys and strings), and arbitrary JSON.

Shared by ``tests/test_fuzz.py`` (a fixed number of derandomised examples in ``make test``)
and ``benchmarks/fuzz_inputs.py`` (more of them, with timings)."""
from __future__ import annotations

import math

from hypothesis import strategies as st

from scene_synth_ros.categories import CATEGORIES, ROOM_TYPES, room_spec

# Leaves of arbitrary JSON, including what breaks naive readers.
SCALARS = st.one_of(
    st.none(), st.booleans(),
    st.integers(-10**6, 10**6), st.integers(),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([1e308, -1e308, 5e-324]),
    st.sampled_from([400, -4301]).map(lambda n: (-1 if n < 0 else 1) * 10 ** abs(n)),
    st.text(max_size=40),
    st.sampled_from(['\ud800', '\x00', 'a\nb', '\u202e', 'x' * 5000]))
JSON = st.recursive(SCALARS, lambda kids: st.one_of(
    st.lists(kids, max_size=6),
    st.dictionaries(st.text(max_size=12), kids, max_size=6)), max_leaves=30)


def _deep(depth: int, leaf):
    for _ in range(depth):
        leaf = [leaf]
    return leaf


@st.composite
def outlines(draw, wild: bool = True) -> list[list[float]]:
    """A floor outline: a rectangle, an L or a jittered polygon, sometimes scaled, moved far,
    closed explicitly or nearly, or with a vertex nearly repeated."""
    kind = draw(st.sampled_from(['rect', 'rect', 'L', 'poly']))
    w = draw(st.floats(0.3, 9.0) if wild else st.floats(1.6, 4.8))
    h = draw(st.floats(0.3, 9.0) if wild else st.floats(1.6, 4.8))
    if kind == 'rect':
        pts = [[0, 0], [w, 0], [w, h], [0, h]]
    elif kind == 'L':
        a = draw(st.floats(0.05, 0.95))
        b = draw(st.floats(0.05, 0.95))
        pts = [[0, 0], [w, 0], [w, h * b], [w * a, h * b], [w * a, h], [0, h]]
    else:
        n = draw(st.integers(3, 14))
        r = draw(st.floats(1.0, 4.0))
        jit = draw(st.lists(st.floats(0.5, 1.0), min_size=n, max_size=n))
        pts = [[r * j * math.cos(2 * math.pi * k / n), r * j * math.sin(2 * math.pi * k / n)]
               for k, j in enumerate(jit)]
    if draw(st.booleans()):
        pts.reverse()
    off = draw(st.sampled_from([0.0, 0.0, 3.7, -1e3, 1e4, 9.9e4, 1e5 + 1, 1e9] if wild
                               else [0.0, 3.7, -1e3, 1e4]))
    pts = [[x + off, y + off] for x, y in pts]
    extra = draw(st.sampled_from(['none', 'close', 'near_close', 'near_repeat', 'collinear',
                                  'spike'] + (['many'] if wild else [])))
    if extra == 'close':
        pts.append(list(pts[0]))
    elif extra == 'near_close':
        e = draw(st.sampled_from([1e-4, 5e-4, 9.99e-4, 1e-3, 2e-3]))
        pts.append([pts[0][0] + e, pts[0][1]])
    elif extra == 'near_repeat':
        k = draw(st.integers(0, len(pts) - 1))
        e = draw(st.sampled_from([0.0, 1e-4, 9e-4, 1.1e-3]))
        pts.insert(k + 1, [pts[k][0] + e, pts[k][1] - e])
    elif extra == 'collinear':
        k = draw(st.integers(0, len(pts) - 1))
        a, b = pts[k], pts[(k + 1) % len(pts)]
        t = draw(st.floats(0.001, 0.999))
        pts.insert(k + 1, [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])])
    elif extra == 'spike':
        k = draw(st.integers(0, len(pts) - 1))
        a = pts[k]
        pts.insert(k + 1, [a[0] + 2e-3, a[1] + 1.0])
        pts.insert(k + 2, [a[0] + 1e-3, a[1]])
    elif extra == 'many':
        n = draw(st.sampled_from([200, 256, 257, 3000]))
        pts = [[off + 2 + 2 * math.cos(2 * math.pi * k / n),
                off + 2 + 2 * math.sin(2 * math.pi * k / n)] for k in range(n)]
    return pts


@st.composite
def openings(draw, floor: list[list[float]], kind: str, wild: bool = True) -> list[dict]:
    """Doors or windows, mostly centred on a wall, some off it or too wide."""
    out = []
    walls = st.integers(0, max(len(floor) - 1, 0))
    for k in draw(st.lists(walls, max_size=3, unique=not wild)):
        a, b = floor[k], floor[(k + 1) % len(floor)]
        odd = wild and draw(st.booleans())      # anywhere on the wall, or of an odd size
        t = draw(st.floats(0.0, 1.0) if odd else st.floats(0.4, 0.6))
        pos = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
        if odd and draw(st.booleans()):
            pos = [pos[0] + draw(st.floats(-0.5, 0.5)), pos[1]]
        door = kind == 'door'
        if odd:
            width, height, sill = (draw(st.floats(0.1, 3.0)) for _ in range(3))
        else:
            width = draw(st.floats(0.6, 0.9) if door else st.floats(0.5, 0.9))
            height = draw(st.floats(1.9, 2.3) if door else st.floats(0.5, 1.4))
            sill = draw(st.floats(0.3, 1.0))
        item = {'position': pos, 'width': width, 'height': height}
        if not door:
            item['sill'] = sill
        out.append(item)
    return out


def _sizes(category: str, wild: bool):
    """[width, depth, height] of a category: mostly within its ranges, sometimes not."""
    info = CATEGORIES[category]
    plausible = st.tuples(*(st.floats(lo, hi) for lo, hi in (info.width, info.depth,
                                                                info.height))).map(list)
    return (plausible | st.lists(st.floats(0.01, 5.0), min_size=3, max_size=3)) if wild \
        else plausible


@st.composite
def objects(draw, room_type: str, floor: list[list[float]], wild: bool = True) -> list[dict]:
    """A partial room's objects: categories of the room type, sizes near plausible,
    positions inside the outline's box, sometimes a support, sometimes junk fields."""
    names = list(room_spec(room_type).names) if room_type in ROOM_TYPES else ['double bed']
    xs = [p[0] for p in floor] or [0.0]
    ys = [p[1] for p in floor] or [0.0]
    out = []
    for i in range(draw(st.integers(0, 4))):
        item_category = draw(st.sampled_from(names))
        item = {'category': item_category,
                'position': [draw(st.floats(min(xs), max(xs))), draw(st.floats(min(ys), max(ys))),
                             draw(st.sampled_from([0.0, 0.0, 0.7, -0.5]))],
                'yaw': draw(st.floats(-7.0, 7.0)),
                'size': draw(_sizes(item_category, wild))}
        if draw(st.booleans()):
            item['id'] = draw(st.sampled_from([f'o{i}', 'o0', 'x' * 200, '\ud800'] if wild
                                              else [f'o{i}', f'\u00e9\u263a{i}']))
        if wild and draw(st.booleans()):
            item['support'] = draw(st.sampled_from(['o0', 'o1', None, 'missing']))
        out.append(item)
    return out


@st.composite
def layouts(draw, wild: bool = True) -> dict:
    """A room layout dict, nearly well formed and sometimes corrupted at one field; with
    ``wild`` off, well formed but for the outline's edge cases (near-closing and
    near-repeated vertices, collinear vertices, slivers, far offsets), which are what an
    accepted room has to survive downstream."""
    room_type = draw(st.sampled_from(list(ROOM_TYPES) + (['living room', 'garage', '']
                                                         if wild else [])))
    floor = draw(outlines(wild))
    d = {'room_type': room_type, 'floor': floor}
    if draw(st.booleans()):
        d['wall_height'] = draw(st.sampled_from([2.6, 1.8, 6.0, 1.7, 2.4]))
    d['doors'] = draw(openings(floor, 'door', wild))
    d['windows'] = draw(openings(floor, 'window', wild))
    if draw(st.booleans()):
        d['objects'] = draw(objects(room_type, floor, wild))
    if not wild:
        return d
    corruption = draw(st.integers(0, 3))
    if corruption == 0:
        key = draw(st.sampled_from(['room_type', 'floor', 'wall_height', 'doors', 'windows',
                                    'objects', 'extra', '\ud800', 'x' * 5000]))
        d[key] = draw(JSON)
    elif corruption == 1:
        d['floor'] = _deep(draw(st.sampled_from([3, 31, 32, 33, 200, 975])), 0)
    return d
