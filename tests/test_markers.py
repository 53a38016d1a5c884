"""The RViz marker descriptions of a furnished room (pure Python, no ROS needed)."""
from __future__ import annotations

from collections import Counter
import math
from pathlib import Path
import subprocess
import sys
import threading
from urllib.parse import unquote, urlparse

import numpy as np
import pytest
from shapely.geometry import Point

from scene_synth_ros import catalog, plot
from scene_synth_ros.export import WALL_THICKNESS, wall_boxes
from scene_synth_ros.markers import (
    MARKER_STYLES,
    MarkerSpec,
    MeshCache,
    category_color,
    scene_markers,
)
from scene_synth_ros.paths import examples_dir
from scene_synth_ros.scene import PlacedObject, Scene
from scene_synth_ros.schema import load_scene

ROOM_NS = ('floor', 'walls', 'doors', 'windows')


def bedroom() -> Scene:
    return load_scene(examples_dir() / 'partial_bedroom.json')


def lshaped() -> Scene:
    return load_scene(examples_dir() / 'lshaped_living_layout.json')


def rich_bedroom() -> Scene:
    """The partial bedroom plus a second stand at an oblique yaw with a non-catalog size (a
    resized variant) and a lamp standing on the first stand (a second-tier object)."""
    scene = bedroom()
    stand = scene.get('stand_0')
    lamp_id = catalog.variants('table lamp')[0].model_id
    scene.objects += [
        PlacedObject('stand_1', 'stand', stand.model_id, (3.3, 0.9, 0.0), 0.3,
                     (0.45, 0.38, 0.52)),
        PlacedObject('table_lamp_0', 'table lamp', lamp_id,
                     (stand.position[0], stand.position[1], stand.top), 0.7,
                     (0.25, 0.22, 0.45), support='stand_0'),
    ]
    return scene


def by_ns(markers: list[MarkerSpec]) -> dict[str, list[MarkerSpec]]:
    out: dict[str, list[MarkerSpec]] = {}
    for m in markers:
        out.setdefault(m.ns, []).append(m)
    return out


def uri_path(uri: str) -> Path:
    parsed = urlparse(uri)
    assert parsed.scheme == 'file', uri
    return Path(unquote(parsed.path))


def triangles(marker: MarkerSpec) -> np.ndarray:
    pts = np.asarray(marker.points, dtype=float)
    assert len(pts) % 3 == 0 and len(pts) > 0
    return pts.reshape(-1, 3, 3)


def signed_areas(tris: np.ndarray) -> np.ndarray:
    a, b, c = tris[:, 0, :2], tris[:, 1, :2], tris[:, 2, :2]
    return ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1])
            - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])) / 2.0


def cube_corners(m: MarkerSpec) -> np.ndarray:
    """Footprint corners of a cube marker worked out from its pose and scale alone."""
    c, s = math.cos(m.yaw), math.sin(m.yaw)
    hx, hy = m.scale[0] / 2, m.scale[1] / 2
    local = [(-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy)]
    return np.array([(m.position[0] + c * x - s * y, m.position[1] + s * x + c * y)
                     for x, y in local])


def obj_bounds(path: Path) -> np.ndarray:
    verts = np.array([[float(v) for v in line.split()[1:4]]
                      for line in path.read_text().splitlines() if line.startswith('v ')])
    return np.array([verts.min(axis=0), verts.max(axis=0)])


# ---- structure ------------------------------------------------------------------------------

def test_counts_order_and_unique_ids_of_the_partial_bedroom():
    scene = bedroom()
    assert len(scene.objects) == 2
    markers = scene_markers(scene)
    counts = Counter(m.ns for m in markers)
    assert counts == {'floor': 1, 'walls': len(wall_boxes(scene.room)), 'doors': 1,
                      'windows': 1, 'double bed': 1, 'stand': 1, 'labels': 2}
    # floor, walls, doors, windows, objects in scene order, labels
    assert [m.ns for m in markers] == (['floor'] + ['walls'] * counts['walls'] + ['doors']
                                       + ['windows'] + ['double bed', 'stand']
                                       + ['labels'] * 2)
    keys = [(m.ns, m.id) for m in markers]
    assert len(set(keys)) == len(keys)


def test_object_ids_count_per_category_and_labels_per_object():
    scene = rich_bedroom()
    markers = scene_markers(scene)
    groups = by_ns(markers)
    assert [m.id for m in groups['stand']] == [0, 1]
    assert [m.id for m in groups['double bed']] == [0]
    assert [m.id for m in groups['table lamp']] == [0]
    keys = [(m.ns, m.id) for m in markers]
    assert len(set(keys)) == len(keys)
    labels = groups['labels']
    assert [m.id for m in labels] == list(range(len(scene.objects)))
    for m, obj in zip(labels, scene.objects, strict=True):
        assert m.kind == 'text'
        assert m.text == obj.id
        assert m.position == pytest.approx((obj.position[0], obj.position[1], obj.top + 0.15))
        assert m.scale == pytest.approx((0.0, 0.0, 0.15))
        assert m.color == (1.0, 1.0, 1.0, 1.0)


def test_every_number_is_a_finite_plain_float(tmp_path):
    markers = (scene_markers(rich_bedroom()) + scene_markers(lshaped())
               + scene_markers(rich_bedroom(), 'mesh', MeshCache(tmp_path)))
    for m in markers:
        assert m.kind in ('cube', 'mesh', 'text', 'triangle_list')
        assert type(m.id) is int
        values = [*m.position, m.yaw, *m.scale, *m.color] + [v for p in m.points for v in p]
        for v in values:
            assert type(v) is float and math.isfinite(v), (m.ns, m.id, v)
        assert all(0.0 <= c <= 1.0 for c in m.color)


def test_non_finite_values_are_refused():
    with pytest.raises(ValueError):
        MarkerSpec('x', 0, 'cube', (0.0, float('nan'), 0.0), 0.0, (1, 1, 1), (1, 1, 1, 1))
    with pytest.raises(ValueError):
        MarkerSpec('x', 0, 'sphere', (0, 0, 0), 0.0, (1, 1, 1), (1, 1, 1, 1))


# ---- floor and walls ------------------------------------------------------------------------

@pytest.mark.parametrize('make', [bedroom, lshaped])
def test_floor_triangles_cover_the_floor_exactly(make):
    room = make().room
    floor = by_ns(scene_markers(make()))['floor']
    assert len(floor) == 1 and floor[0].id == 0 and floor[0].kind == 'triangle_list'
    assert floor[0].scale == (1.0, 1.0, 1.0)
    tris = triangles(floor[0])
    assert np.all(tris[:, :, 2] == 0.0)
    areas = signed_areas(tris)
    assert np.all(areas > 0)                      # counter-clockwise seen from above
    assert areas.sum() == pytest.approx(room.area, rel=1e-9)
    # No triangle may lie outside the floor (the convex hull of an L would).
    for t in tris:
        assert room.polygon.buffer(1e-9).contains(Point(t[:, :2].mean(axis=0)))


def test_lshaped_room_has_its_area_and_openings():
    scene = lshaped()
    assert scene.room.area == pytest.approx(34.5)
    groups = by_ns(scene_markers(scene))
    assert len(groups['doors']) == 2 and len(groups['windows']) == 2
    assert 'labels' not in groups


@pytest.mark.parametrize('make', [bedroom, lshaped])
def test_wall_cubes_are_the_export_wall_boxes(make):
    room = make().room
    boxes = wall_boxes(room)
    walls = by_ns(scene_markers(make()))['walls']
    assert len(walls) == len(boxes)
    assert [m.id for m in walls] == list(range(len(boxes)))
    for m, b in zip(walls, boxes, strict=True):
        assert m.kind == 'cube'
        assert m.position == pytest.approx(b.centre)
        assert m.yaw == pytest.approx(b.yaw)
        assert m.scale == pytest.approx(b.size)


@pytest.mark.parametrize('make', [bedroom, lshaped])
def test_door_and_window_cubes_fill_their_openings_on_their_walls(make):
    room = make().room
    groups = by_ns(scene_markers(make()))
    for ns, openings in (('doors', room.doors), ('windows', room.windows)):
        assert len(groups[ns]) == len(openings)
        for m, op in zip(groups[ns], openings, strict=True):
            wall = room.wall_of(op)
            assert m.kind == 'cube'
            # centred in the wall's thickness, which stands outside the floor outline
            assert wall.distance_to(m.position[:2]) == pytest.approx(WALL_THICKNESS / 2)
            assert not room.polygon.contains(Point(m.position[:2]))
            assert wall.offset_of(m.position[:2]) == pytest.approx(wall.offset_of(op.position))
            assert (math.cos(m.yaw), math.sin(m.yaw)) == pytest.approx(tuple(wall.direction))
            assert m.scale == pytest.approx((op.width, 0.04, op.height))
            bottom = m.position[2] - m.scale[2] / 2
            assert bottom == pytest.approx(op.sill)
            assert m.position[2] + m.scale[2] / 2 == pytest.approx(op.sill + op.height)
            if ns == 'doors':
                assert bottom == pytest.approx(0.0)
    assert groups['doors'][0].color[3] == pytest.approx(0.6)
    assert groups['windows'][0].color[3] == pytest.approx(0.4)


# ---- objects --------------------------------------------------------------------------------

def test_object_cubes_match_the_objects():
    scene = rich_bedroom()
    markers = [m for m in scene_markers(scene, 'cube') if m.ns not in ROOM_NS + ('labels',)]
    assert len(markers) == len(scene.objects)
    for m, obj in zip(markers, scene.objects, strict=True):
        assert m.ns == obj.category and m.kind == 'cube'
        assert m.yaw == pytest.approx(obj.yaw)
        assert m.scale == pytest.approx((obj.depth, obj.width, obj.height))
        assert cube_corners(m) == pytest.approx(obj.corners(), abs=1e-9)
        assert m.position[2] - m.scale[2] / 2 == pytest.approx(obj.position[2])
        assert m.position[2] + m.scale[2] / 2 == pytest.approx(obj.top)
        assert m.color == category_color(obj.category)
    lamp = markers[-1]
    assert lamp.ns == 'table lamp' and lamp.position[2] > lamp.scale[2] / 2   # on the stand


def test_category_colours_are_stable_distinct_and_shared_with_the_pictures():
    assert category_color('double bed') == category_color('double bed')
    assert category_color('double bed') != category_color('stand')
    assert category_color('stand') == tuple(plot.category_color('stand'))
    assert len(category_color('stand')) == 4
    assert all(type(c) is float for c in category_color('stand'))


def test_unknown_style_and_mesh_without_cache_raise():
    with pytest.raises(ValueError, match='cube.*mesh'):
        scene_markers(bedroom(), style='sphere')
    with pytest.raises(ValueError, match='MeshCache'):
        scene_markers(bedroom(), style='mesh')
    assert MARKER_STYLES == ('cube', 'mesh')


# ---- meshes ---------------------------------------------------------------------------------

def test_mesh_style_writes_obj_files_and_points_at_them(tmp_path):
    scene = rich_bedroom()
    cache = MeshCache(tmp_path / 'meshes')
    markers = [m for m in scene_markers(scene, 'mesh', cache)
               if m.ns not in ROOM_NS + ('labels',)]
    assert len(markers) == len(scene.objects)
    for m, obj in zip(markers, scene.objects, strict=True):
        assert m.kind == 'mesh' and m.ns == obj.category
        assert m.position == pytest.approx(obj.position)         # the base, not the centre
        assert m.yaw == pytest.approx(obj.yaw)
        assert m.scale == (1.0, 1.0, 1.0)
        assert m.color == category_color(obj.category)
        path = uri_path(m.mesh_resource)
        assert path.is_file() and path.suffix == '.obj'
        assert path.parent == (tmp_path / 'meshes').resolve()
        assert path.with_suffix('.mtl').is_file()
        assert set(path.stem) <= set('abcdefghijklmnopqrstuvwxyz'
                                     'ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-')
        # The mesh shows the object at its size with its origin at the bottom centre, which
        # is why the marker's pose is the object's base.
        lo, hi = obj_bounds(path)
        assert lo == pytest.approx((-obj.depth / 2, -obj.width / 2, 0.0), abs=1e-5)
        assert hi == pytest.approx((obj.depth / 2, obj.width / 2, obj.height), abs=1e-5)
    # stand_1 is resized (its model id has '@', 'x' and '.'), so it has its own file.
    stands = [uri_path(m.mesh_resource) for m in markers if m.ns == 'stand']
    assert stands[0] != stands[1]
    assert len(list((tmp_path / 'meshes').glob('*.obj'))) == len(scene.objects)
    assert not [p for p in (tmp_path / 'meshes').iterdir() if p.name.startswith('.tmp')]


def test_mesh_files_are_reused(tmp_path):
    scene = rich_bedroom()
    cache = MeshCache(tmp_path)
    first = scene_markers(scene, 'mesh', cache)
    paths = [uri_path(m.mesh_resource) for m in first if m.kind == 'mesh']
    stats = {p: (p.stat().st_ino, p.stat().st_mtime_ns) for p in paths}
    again = scene_markers(scene, 'mesh', cache)                      # in-memory cache
    fresh = scene_markers(scene, 'mesh', MeshCache(tmp_path))       # files on disk
    assert again == first and fresh == first
    for p in paths:
        assert (p.stat().st_ino, p.stat().st_mtime_ns) == stats[p]


def test_model_ids_that_sanitise_alike_get_different_files(tmp_path):
    # Unknown model ids are kept in the variant's id; '.' and '_' must not collide.
    size = (0.4, 0.4, 0.5)
    a = PlacedObject('stand_0', 'stand', 'custom.1', (1.0, 1.0, 0.0), 0.0, size)
    b = PlacedObject('stand_1', 'stand', 'custom_1', (2.0, 1.0, 0.0), 0.0, size)
    cache = MeshCache(tmp_path)
    assert uri_path(cache.uri(a)) != uri_path(cache.uri(b))
    assert len(list(tmp_path.glob('*.obj'))) == 2


def test_mesh_cache_is_thread_safe(tmp_path):
    obj = rich_bedroom().get('stand_1')
    cache = MeshCache(tmp_path)
    uris, errors = [], []

    def work():
        try:
            uris.append(cache.uri(obj))
        except Exception as e:        # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(6)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert len(uris) == 6 and len(set(uris)) == 1
    assert sorted(p.suffix for p in tmp_path.iterdir()) == ['.mtl', '.obj']


def test_markers_module_needs_no_ros():
    # In a fresh interpreter where any ROS import fails, the module (and what it imports)
    # must still load and work.
    code = ("import sys\n"
            "for name in ('rclpy', 'visualization_msgs', 'geometry_msgs', 'std_msgs'):\n"
            "    sys.modules[name] = None\n"
            "from scene_synth_ros.markers import scene_markers\n"
            "from scene_synth_ros.paths import examples_dir\n"
            "from scene_synth_ros.schema import load_scene\n"
            "scene = load_scene(examples_dir() / 'partial_bedroom.json')\n"
            "print(len(scene_markers(scene)))\n")
    done = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert int(done.stdout) == len(scene_markers(bedroom()))
