"""The RViz marker descriptions of a furnished room (pure Python, no ROS needed)."""
from __future__ import annotations

from collections import Counter
from dataclasses import replace
import math
from pathlib import Path
import subprocess
import sys

import numpy as np
import pytest
from shapely.geometry import Point
import trimesh

from scene_synth_ros import catalog, plot
from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.export import WALL_THICKNESS, wall_boxes
from scene_synth_ros.markers import (
    MARKER_STYLES,
    MarkerSpec,
    category_color,
    scene_markers,
)
from scene_synth_ros.meshes import MATERIALS, shipped_name, write_shipped_meshes
from scene_synth_ros.paths import examples_dir, meshes_dir
from scene_synth_ros.scene import PlacedObject, Scene
from scene_synth_ros.schema import load_scene
from scene_synth_ros.user_catalog import load_catalog

ROOM_NS = ('floor', 'walls', 'doors', 'windows')
ROOT = Path(__file__).resolve().parent.parent
SHIPPED = ROOT / 'meshes'                    # installed to share/scene_synth_ros/meshes
PACKAGE_MESHES = 'package://scene_synth_ros/meshes/'


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


def shipped_path(uri: str) -> Path:
    """The repository file a package://scene_synth_ros/meshes/ URI names."""
    assert uri.startswith(PACKAGE_MESHES), uri
    name = uri[len(PACKAGE_MESHES):]
    assert name and '/' not in name, uri
    return SHIPPED / name


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


def object_markers(markers: list[MarkerSpec]) -> list[MarkerSpec]:
    return [m for m in markers if m.ns not in ROOM_NS + ('labels',)]


def scaled_mesh(m: MarkerSpec) -> trimesh.Trimesh:
    """The shipped mesh of a mesh marker, loaded with trimesh and stretched by its scale (in
    the marker's own frame, before its pose, as RViz does)."""
    mesh = trimesh.load(shipped_path(m.mesh_resource), force='mesh', process=False)
    return mesh.apply_scale(m.scale)


def posed_footprint(m: MarkerSpec, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """Footprint corners of the local box lo..hi put where the marker's pose puts it."""
    c, s = math.cos(m.yaw), math.sin(m.yaw)
    local = [(lo[0], lo[1]), (hi[0], lo[1]), (hi[0], hi[1]), (lo[0], hi[1])]
    return np.array([(m.position[0] + c * x - s * y, m.position[1] + s * x + c * y)
                     for x, y in local])


def assert_mesh_covers_the_object(m: MarkerSpec, obj: PlacedObject) -> None:
    """The scaled shipped mesh, posed by the marker, covers the object's box within 1 cm."""
    lo, hi = scaled_mesh(m).bounds
    assert lo == pytest.approx((-obj.depth / 2, -obj.width / 2, 0.0), abs=0.01)
    assert hi == pytest.approx((obj.depth / 2, obj.width / 2, obj.height), abs=0.01)
    assert posed_footprint(m, lo, hi) == pytest.approx(obj.corners(), abs=0.01)
    assert m.position[2] + lo[2] == pytest.approx(obj.position[2], abs=0.01)
    assert m.position[2] + hi[2] == pytest.approx(obj.top, abs=0.01)


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


def test_every_number_is_a_finite_plain_float():
    markers = (scene_markers(rich_bedroom()) + scene_markers(lshaped())
               + scene_markers(rich_bedroom(), 'mesh'))
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


def test_unknown_style_raises():
    with pytest.raises(ValueError, match='cube.*mesh'):
        scene_markers(bedroom(), style='sphere')
    assert MARKER_STYLES == ('cube', 'mesh')


# ---- meshes ---------------------------------------------------------------------------------

def test_every_catalog_model_has_a_shipped_mesh_equal_to_what_the_generator_writes(tmp_path):
    # A catalog, builder or palette change without `scripts/build_meshes.py` fails here.
    generated = {p.name: p.read_bytes() for p in write_shipped_meshes(tmp_path)}
    shipped = {p.name: p.read_bytes() for p in SHIPPED.iterdir()}
    assert sorted(shipped) == sorted(generated), 'run scripts/build_meshes.py and commit meshes/'
    stale = sorted(n for n in generated if shipped[n] != generated[n])
    assert not stale, f'{stale[:5]} differ from the generator: run scripts/build_meshes.py'
    models = catalog.all_variants()
    names = {shipped_name(v.model_id) for v in models}
    assert names | {n[:-len('.obj')] + '.mtl' for n in names} == set(shipped)
    assert len(shipped) == 2 * len(models)
    assert meshes_dir() == SHIPPED            # what paths finds in a checkout


def test_each_shipped_mesh_names_its_own_material_library():
    for path in SHIPPED.glob('*.obj'):
        lines = path.read_text().splitlines()
        assert lines[1] == f'mtllib {path.stem}.mtl', path.name
        used = [ln.split()[1] for ln in lines if ln.startswith('usemtl ')]
        mtl = path.with_suffix('.mtl').read_text().splitlines()
        assert [ln.split()[1] for ln in mtl if ln.startswith('newmtl ')] == used, path.name
    # The library resolves beside the OBJ: trimesh reads the colours through it, as RViz's
    # loader (assimp) does through the same package:// folder.
    scene = trimesh.load(SHIPPED / 'stand_00.obj', process=False)
    assert scene.geometry
    for name, geom in scene.geometry.items():
        assert tuple(geom.visual.material.diffuse) == MATERIALS[name].rgba


@pytest.mark.parametrize('room_type', ROOM_TYPES)
def test_mesh_markers_of_a_furnished_room_are_shipped_package_meshes(room_type):
    # the first of the corpus rooms 3, 4, ... that holds something (a hallway may not)
    scene = next(s for i in range(3, 20) if (s := generate_room(room_type, 0, i)).objects)
    markers = scene_markers(scene, 'mesh')
    assert not [m for m in markers if 'file:' in m.mesh_resource]
    meshes = [m for m in markers if m.kind == 'mesh']
    assert len(meshes) == len(object_markers(markers)) == len(scene.objects) > 0
    for m, obj in zip(meshes, scene.objects, strict=True):
        assert m.ns == obj.category and m.color == category_color(obj.category)
        assert m.mesh_resource == PACKAGE_MESHES + f'{obj.model_id}.obj'
        assert shipped_path(m.mesh_resource).is_file()
        # A catalog object at its catalog size is the mesh as it is, posed at its base.
        assert m.scale == (1.0, 1.0, 1.0)
        assert m.position == pytest.approx(obj.position)
        assert m.yaw == pytest.approx(obj.yaw)
    assert_mesh_covers_the_object(meshes[0], scene.objects[0])


def test_mesh_markers_keep_pose_colour_and_ids_of_the_objects():
    scene = rich_bedroom()
    cubes = object_markers(scene_markers(scene, 'cube'))
    meshes = object_markers(scene_markers(scene, 'mesh'))
    assert [(m.ns, m.id, m.color, m.yaw) for m in meshes] == \
        [(m.ns, m.id, m.color, m.yaw) for m in cubes]
    for m, obj in zip(meshes, scene.objects, strict=True):
        assert m.kind == 'mesh'
        assert m.position == pytest.approx(obj.position)        # the base, not the centre
        assert_mesh_covers_the_object(m, obj)


def test_a_resized_object_is_its_shipped_model_stretched_by_the_marker_scale():
    v = catalog.variants('stand')[2]
    w, d, h = v.size
    obj = PlacedObject('stand_7', 'stand', v.model_id, (2.0, 1.5, 0.0), 0.9,
                       (2 * w, 0.8 * d, 1.25 * h))
    [m] = object_markers(scene_markers(Scene(bedroom().room, [obj]), 'mesh'))
    assert m.mesh_resource == PACKAGE_MESHES + f'{v.model_id}.obj'     # no file of its own
    # Marker scale is in the mesh's axes: x depth, y width, z height.
    assert m.scale == pytest.approx((0.8, 2.0, 1.25))
    assert_mesh_covers_the_object(m, obj)
    # The partial bedroom's second stand has a size of its own as well.
    stand_1 = object_markers(scene_markers(rich_bedroom(), 'mesh'))[-2]
    assert stand_1.ns == 'stand' and stand_1.id == 1 and stand_1.scale != (1.0, 1.0, 1.0)


@pytest.mark.parametrize('model_id', ['custom.1', 'double_bed_00', ''])
def test_an_unknown_model_id_shows_the_nearest_variant_scaled(model_id):
    # Unknown to the catalog, or a model of another category: the stand nearest in footprint.
    size = (0.47, 0.36, 0.58)
    obj = PlacedObject('stand_0', 'stand', model_id, (1.0, 1.0, 0.0), -0.4, size)
    [m] = object_markers(scene_markers(Scene(bedroom().room, [obj]), 'mesh'))
    nearest = catalog.nearest('stand', size[0], size[1])
    assert m.mesh_resource == PACKAGE_MESHES + f'{nearest.model_id}.obj'
    assert m.scale == pytest.approx((size[1] / nearest.depth, size[0] / nearest.width,
                                     size[2] / nearest.height))
    assert_mesh_covers_the_object(m, obj)


def test_a_category_without_catalog_models_stays_a_box_in_mesh_style():
    obj = PlacedObject('robot_0', 'robot', 'robot_00', (1.0, 1.0, 0.0), 0.3, (0.5, 0.6, 1.2))
    [m] = object_markers(scene_markers(Scene(bedroom().room, [obj]), 'mesh'))
    assert m.kind == 'cube' and m.mesh_resource == ''
    assert m.scale == pytest.approx((0.6, 0.5, 1.2))
    assert m.position == pytest.approx((1.0, 1.0, 0.6))


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


# ---- the user's own furniture -----------------------------------------------------------------
def _user_bed(catalog_file: Path, size=(1.6, 2.0, 1.0)) -> tuple[Scene, catalog.Catalog]:
    """The partial bedroom's room with the user's bed at ``size`` (not its own)."""
    models = load_catalog(catalog_file)
    obj = PlacedObject('double_bed_0', 'double bed', 'oak_bed', (2.1, 2.0, 0.0), 0.6, size)
    return Scene(bedroom().room, [obj]), models


def test_a_user_model_is_its_stl_posed_scaled_and_coloured(tmp_path):
    from test_user_catalog import make_real_set
    _, path = make_real_set(tmp_path)
    scene, models = _user_bed(path)
    bed = models.get('oak_bed')
    [m] = object_markers(scene_markers(scene, 'mesh', models))
    obj = scene.objects[0]
    assert m.kind == 'mesh' and m.mesh_resource == 'file://' + bed.marker
    assert Path(bed.marker).is_absolute() and Path(bed.marker).is_file()
    assert not m.mesh_materials                   # STL has none: the category's colour
    assert m.color == category_color('double bed') and m.ns == 'double bed'
    # The scale in the mesh's axes (x depth, y width, z height), as for shipped meshes.
    assert m.scale == pytest.approx((2.0 / 2.1, 1.6 / 1.7, 1.0 / 1.1))
    assert m.position == pytest.approx(obj.position) and m.yaw == pytest.approx(obj.yaw)
    mesh = trimesh.load(bed.marker, force='mesh', process=False).apply_scale(m.scale)
    lo, hi = mesh.bounds
    assert lo == pytest.approx((-obj.depth / 2, -obj.width / 2, 0.0), abs=1e-4)
    assert hi == pytest.approx((obj.depth / 2, obj.width / 2, obj.height), abs=1e-4)
    assert posed_footprint(m, lo, hi) == pytest.approx(obj.corners(), abs=1e-4)
    # Cube style and procedural models are as before; without the catalog the bed is the
    # nearest procedural model.
    [cube] = object_markers(scene_markers(scene, 'cube', models))
    assert cube.kind == 'cube' and cube.mesh_resource == ''
    [plain] = object_markers(scene_markers(scene, 'mesh'))
    assert plain.mesh_resource == PACKAGE_MESHES + shipped_name(
        catalog.nearest('double bed', 1.6, 2.0).model_id) and plain.mesh_materials
    room = bedroom()
    assert scene_markers(room, 'mesh', models) == scene_markers(room, 'mesh')


def test_a_user_model_without_its_stl_falls_back_to_a_procedural_mesh(tmp_path):
    from test_user_catalog import make_real_set
    _, path = make_real_set(tmp_path)
    scene, models = _user_bed(path)
    nearest = catalog.nearest('double bed', 1.6, 2.0)
    older = catalog.Catalog([replace(m, marker='') for m in models.user.values()])
    Path(models.get('oak_bed').marker).unlink()      # removed since the build
    for cat in (models, older):                      # or a catalog built before markers
        [m] = object_markers(scene_markers(scene, 'mesh', cat))
        assert m.mesh_resource == PACKAGE_MESHES + shipped_name(nearest.model_id)
        assert m.mesh_materials
        assert_mesh_covers_the_object(m, scene.objects[0])
