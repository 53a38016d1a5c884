"""The model catalog (sizes, ids, nearest) and its meshes (bounds, parts, orientation,
export, placement in a scene)."""
from __future__ import annotations

from itertools import pairwise
import math
import time

import numpy as np
import pytest
import trimesh

from scene_synth_ros import catalog, meshes
from scene_synth_ros.categories import (
    CATEGORIES,
    PLAUSIBLE_PARENTS,
    ROLES,
    TABLE_COUNTS,
    paper_spec,
    roles_of,
)
from scene_synth_ros.errors import UnknownCategory
from scene_synth_ros.scene import PlacedObject, Room, Scene, box_corners

TOL = 1e-3   # metres
ALL_CATEGORIES = list(CATEGORIES)
# categories whose every variant (all three styles) is checked in full
FULL_CATEGORIES = ('double bed', 'office chair', 'wardrobe', 'toilet', 'television', 'sofa',
                   'plant', 'cup', 'counter', 'kitchen sink', 'fridge', 'dining table')
# the categories of a home beyond the paper's table (kitchens, dining rooms, hallways)
PAPER_CATEGORIES = {c for counts in TABLE_COUNTS.values() for c in counts}
HOME_CATEGORIES = [c for c in CATEGORIES if c not in PAPER_CATEGORIES]


def _one_each():
    """One variant per category, cycling through the styles."""
    return [catalog.variants(c)[i % catalog.VARIANTS_PER_CATEGORY] for i, c in
            enumerate(ALL_CATEGORIES)]


def _checked_variants():
    seen = {v.model_id: v for v in _one_each()}
    for c in FULL_CATEGORIES:
        for v in catalog.variants(c):
            seen[v.model_id] = v
    return list(seen.values())


def _box_bounds(v):
    return np.array([[-v.depth / 2, -v.width / 2, 0.0], [v.depth / 2, v.width / 2, v.height]])


def _count_bodies(mesh: trimesh.Trimesh) -> int:
    """Connected components of the mesh as stored (shared vertex indices), like trimesh's
    ``body_count`` (which needs scipy)."""
    faces = np.asarray(mesh.faces)
    labels = np.arange(len(mesh.vertices))
    while True:
        face_min = labels[faces].min(axis=1)
        new = labels.copy()
        for k in range(3):
            np.minimum.at(new, faces[:, k], face_min)
        new = new[new]                       # pointer jumping speeds up convergence
        if np.array_equal(new, labels):
            break
        labels = new
    return len(np.unique(labels[np.unique(faces)]))


def _world_bounds(sm: trimesh.Scene, object_id: str) -> np.ndarray:
    """Bounds of everything below the node ``object_id`` of a scene, in world coordinates."""
    pts = []
    for node in sm.graph.nodes_geometry:
        if not node.startswith(object_id + '/'):
            continue
        matrix, geom = sm.graph[node]
        pts.append(trimesh.transform_points(sm.geometry[geom].vertices, matrix))
    pts = np.vstack(pts)
    return np.array([pts.min(axis=0), pts.max(axis=0)])


# ---------------------------------------------------------------------------------------
# categories


def test_every_category_info_is_consistent():
    for name, info in CATEGORIES.items():
        assert info.name == name and info.tier in ('first', 'second'), name
        for lo, hi in (info.width, info.depth, info.height):
            assert 0 < lo <= hi < 4.0, (name, lo, hi)
        assert info.roles == roles_of(name) and info.roles <= set(ROLES), name
        parents = [p for p, _ in info.parents]
        if info.tier == 'second':
            # a second-tier object stands on first-tier parents, where a designer expects it
            assert info.supported_by, name
            assert all(CATEGORIES[p].tier == 'first' for p in info.supported_by), name
            assert set(parents) <= set(info.supported_by), name
            assert all(w > 0 for _, w in info.parents), name
            assert parents == list(PLAUSIBLE_PARENTS.get(name, {})), name
        else:
            assert not info.supported_by and not parents, name
    for role, names in ROLES.items():
        assert names and len(set(names)) == len(names), role
        assert set(names) <= set(CATEGORIES), (role, set(names) - set(CATEGORIES))


def test_the_home_categories_come_after_the_papers_and_leave_them_alone():
    assert len(HOME_CATEGORIES) == 16
    names = list(CATEGORIES)
    # appended: the paper's categories keep their places (plot colours, previews)
    assert names[:len(PAPER_CATEGORIES)] == [c for c in names if c in PAPER_CATEGORIES]
    for role, members in ROLES.items():
        # the corpus draws among a role's members in order: the paper's come first
        paper = [c in PAPER_CATEGORIES for c in members]
        assert paper == sorted(paper, reverse=True), role
    for c in HOME_CATEGORIES:
        info = CATEGORIES[c]
        assert info.description and info.roles, c
        assert all(c not in paper_spec(rt) for rt in TABLE_COUNTS)
        # nothing of the paper's stands on them: the paper's category infos are unchanged
        assert not any(c in CATEGORIES[p].supported_by for p in PAPER_CATEGORIES), c
    # the rules to come find a kitchen's pieces by role
    assert set(ROLES['work triangle']) == {'kitchen sink', 'stove', 'fridge'}
    assert {'fridge', 'dishwasher', 'stove', 'sideboard', 'counter'} <= set(ROLES['door front'])
    assert {'dining chair', 'bar stool'} <= set(ROLES['table seat']) & set(ROLES['dining seat'])
    assert set(ROLES['dining surface']) == {'dining table', 'kitchen island'}


def test_kitchen_units_share_one_worktop_height():
    counter = CATEGORIES['counter']
    for c in ('stove', 'dishwasher'):
        lo, hi = CATEGORIES[c].height
        assert counter.height[0] - 0.05 <= lo <= hi <= counter.height[1] + 0.05, c
    # a sink unit's box rises to its tap; its worktop is a counter's
    for v in catalog.variants('kitchen sink'):
        top = _parts(v, 'worktop')[0].bounds[1, 2]
        assert counter.height[0] - TOL <= top <= counter.height[1] + TOL, v.model_id
        tap = max(p.bounds[1, 2] for p in meshes.build_parts(v) if p.name.startswith('tap'))
        assert tap == pytest.approx(v.height, abs=TOL) and tap - top > 0.15


# ---------------------------------------------------------------------------------------
# catalog


@pytest.mark.parametrize('category', ALL_CATEGORIES)
def test_variants_lie_in_and_span_the_ranges(category):
    info = CATEGORIES[category]
    vs = catalog.variants(category)
    inside = [v for v in vs if all(lo - 1e-9 <= s <= hi + 1e-9 for s, (lo, hi) in
                                   zip(v.size, (info.width, info.depth, info.height), strict=True))]
    assert len(inside) >= 5
    for axis, (lo, hi) in enumerate((info.width, info.depth, info.height)):
        values = [v.size[axis] for v in vs]
        quarter = 0.25 * (hi - lo)
        assert min(values) <= lo + quarter + 1e-9, (category, axis, values)
        assert max(values) >= hi - quarter - 1e-9, (category, axis, values)
    assert all(v.category == category for v in vs)
    assert {v.style for v in vs} == {0, 1, 2}


def test_model_ids_unique_and_get_round_trips():
    everything = catalog.all_variants()
    ids = [v.model_id for v in everything]
    assert len(ids) == len(set(ids)) == len(CATEGORIES) * catalog.VARIANTS_PER_CATEGORY
    for v in everything:
        assert catalog.get(v.model_id) == v
    with pytest.raises(KeyError):
        catalog.get('no_such_model_99')


@pytest.mark.parametrize('category', ['double bed', 'cup', 'sofa', 'desk', 'toilet'])
def test_nearest_returns_exact_variant_and_is_monotonic(category):
    vs = catalog.variants(category)
    for v in vs:
        assert catalog.nearest(category, v.width, v.depth) == v
        assert catalog.ranked(category, v.width, v.depth)[0] == v
    info = CATEGORIES[category]
    depth = sum(info.depth) / 2
    widths = np.linspace(info.width[0] * 0.7, info.width[1] * 1.3, 60)
    chosen = [catalog.nearest(category, w, depth).width for w in widths]
    assert all(a <= b + 1e-12 for a, b in pairwise(chosen))
    assert chosen[0] < chosen[-1]
    width = sum(info.width) / 2
    depths = np.linspace(info.depth[0] * 0.7, info.depth[1] * 1.3, 60)
    chosen = [catalog.nearest(category, width, d).depth for d in depths]
    assert all(a <= b + 1e-12 for a, b in pairwise(chosen))
    # a request far larger than the catalog gets the largest footprint
    big = catalog.nearest(category, info.width[1] * 3, info.depth[1] * 3)
    assert big.width * big.depth == max(v.width * v.depth for v in vs)


# ---------------------------------------------------------------------------------------
# meshes


@pytest.mark.parametrize('variant', _checked_variants(), ids=lambda v: v.model_id)
def test_mesh_bounds_parts_and_colours(variant):
    mesh = meshes.build_mesh(variant)
    assert len(mesh.faces) > 0
    np.testing.assert_allclose(mesh.bounds, _box_bounds(variant), atol=TOL)
    assert _count_bodies(mesh) >= 3
    assert len(mesh.faces) <= 3000
    parts = meshes.build_parts(variant)
    assert len(parts) >= 3
    assert len({tuple(np.round(p.bounds, 4).ravel()) for p in parts}) >= 3   # not stacked copies
    assert all(p.material in meshes.MATERIALS for p in parts)
    # vertex colours follow the parts' materials
    colours = np.asarray(mesh.visual.vertex_colors)
    start = 0
    for p in parts:
        assert (colours[start:start + len(p.vertices)] == meshes.MATERIALS[p.material].rgba).all()
        start += len(p.vertices)


def test_every_category_has_its_own_builder():
    # a furniture module the registry forgets to import would leave its categories as plain boxes
    assert set(meshes.BUILDERS) == set(CATEGORIES)
    assert meshes.builder_for('sofa') is meshes.builder_for('armchair')


def test_every_catalog_mesh_fits_its_box_quickly():
    start = time.perf_counter()
    for v in catalog.all_variants():
        parts = meshes.build_parts.__wrapped__(v)
        verts = np.vstack([p.vertices for p in parts])
        bounds = np.array([verts.min(axis=0), verts.max(axis=0)])
        np.testing.assert_allclose(bounds, _box_bounds(v), atol=TOL, err_msg=v.model_id)
        assert sum(len(p.faces) for p in parts) <= 3000, v.model_id
        assert len(parts) >= 3, v.model_id
    assert time.perf_counter() - start < 30.0


def test_styles_differ_in_shape():
    for c in ALL_CATEGORIES:
        names = {tuple(sorted({p.name for p in meshes.build_parts(v)}))
                 for v in catalog.variants(c)[:3]}
        counts = {len(meshes.build_parts(v)) for v in catalog.variants(c)[:3]}
        assert len(names) > 1 or len(counts) > 1, c


def _parts(variant, name):
    ps = [p for p in meshes.build_parts(variant) if p.name == name]
    assert ps, f'{variant.model_id} has no part {name!r}'
    return ps


def _top_vertices_x(variant, band=0.01):
    v = meshes.build_mesh(variant).vertices
    return v[v[:, 2] >= variant.height - band, 0]


@pytest.mark.parametrize('category', ['double bed', 'single bed', 'daybed', 'sofa', 'sofa chair',
                                      'armchair', 'office chair', 'straight chair', 'chair',
                                      'toilet', 'sink', 'bidet', 'kitchen sink', 'dining chair'])
def test_back_is_at_minus_x(category):
    """Headboards, backrests, toilet tanks and taps are the highest points, at the back."""
    for v in catalog.variants(category):
        xs = _top_vertices_x(v)
        assert len(xs) and (xs < 0).all(), (v.model_id, xs.max())


def test_bed_pillows_near_the_head_and_blanket_towards_the_foot():
    for c in ('double bed', 'single bed'):
        for v in catalog.variants(c):
            assert all(p.centre[0] < -v.depth / 4 for p in _parts(v, 'pillow'))
            assert all(p.centre[0] > 0 for p in _parts(v, 'blanket'))
            assert all(p.centre[0] < -v.depth / 2 + 0.15 for p in _parts(v, 'headboard'))


def test_fronts_face_plus_x():
    for v in catalog.variants('wardrobe') + catalog.variants('dresser'):
        for h in _parts(v, 'handle'):
            assert h.bounds[0, 0] > 0 and h.bounds[1, 0] == pytest.approx(v.depth / 2, abs=TOL)
    for v in catalog.variants('television'):
        screen = _parts(v, 'screen')[0]
        panel = _parts(v, 'panel')[0]
        assert screen.bounds[0, 0] > 0 and screen.centre[0] > panel.centre[0]
        assert screen.bounds[1, 2] - screen.bounds[0, 2] > 0.6 * v.height
    for v in catalog.variants('washer'):
        assert _parts(v, 'door_glass')[0].centre[0] > v.depth / 2 - 0.03
    for v in catalog.variants('loudspeaker'):
        assert all(p.centre[0] > v.depth / 2 - 0.03 for p in _parts(v, 'woofer_cone'))
    for v in catalog.variants('piano'):
        assert _parts(v, 'keys_white')[0].centre[0] > 0 > _parts(v, 'case')[0].centre[0]
    for v in catalog.variants('pedestal fan'):
        assert _parts(v, 'grille')[0].centre[0] > _parts(v, 'motor')[0].centre[0]
    for v in catalog.variants('laptop'):
        assert _parts(v, 'lid')[0].centre[0] < _parts(v, 'base')[0].centre[0]
        assert _parts(v, 'lid')[0].bounds[1, 2] == pytest.approx(v.height, abs=TOL)
    for v in catalog.variants('fireplace'):
        assert _parts(v, 'mantel')[0].bounds[1, 2] == pytest.approx(v.height, abs=TOL)
        assert _parts(v, 'firebox')[0].bounds[0, 0] == pytest.approx(-v.depth / 2, abs=TOL)
    for v in catalog.variants('toilet'):
        tank = _parts(v, 'tank')[0]
        bowl = _parts(v, 'bowl')[0]
        assert tank.centre[0] < 0 < bowl.centre[0]


def test_special_shapes():
    for v in catalog.variants('bunker bed'):
        assert len(_parts(v, 'mattress')) == 2 and len(_parts(v, 'post')) == 4
        assert len(_parts(v, 'ladder_rung')) >= 3
    for v in catalog.variants('baby bed'):
        assert len(_parts(v, 'bar')) >= 12
    for v in catalog.variants('office chair'):
        assert len(_parts(v, 'star_arm')) == 5 and len(_parts(v, 'caster')) == 5
    for v in catalog.variants('dresser'):
        assert len(_parts(v, 'drawer')) >= 3
    for v in catalog.variants('bathtub'):
        # the inside is a recess: something lies well below the rim inside the footprint
        inner = [p for p in meshes.build_parts(v) if p.name in ('inside', 'tub_inside')]
        assert inner and inner[0].bounds[1, 2] < 0.5 * v.height
    for v in catalog.variants('shower'):
        glass = _parts(v, 'glass')
        assert glass and all(min(p.bounds[1, :2] - p.bounds[0, :2]) < 0.03 for p in glass)
    for v in catalog.variants('sofa'):
        assert len(_parts(v, 'arm')) == 2 and len(_parts(v, 'seat_cushion')) >= 2


def _front_reaches(v, name):
    """Whether a part called ``name`` reaches the front of ``v``'s box."""
    return any(p.bounds[1, 0] == pytest.approx(v.depth / 2, abs=TOL) for p in _parts(v, name))


def test_kitchen_shapes():
    for v in catalog.variants('counter'):
        # one module per 60 cm or so, each with a door or drawers, under a worktop
        fronts = _parts(v, 'door') + [p for p in meshes.build_parts(v) if p.name == 'drawer']
        assert len(fronts) >= round(v.width / 0.6)
        assert all(p.centre[0] > v.depth / 2 - 0.06 for p in fronts)
        assert _parts(v, 'worktop')[0].bounds[1, 2] == pytest.approx(v.height, abs=TOL)
    for v in catalog.variants('stove'):
        rings = [p for p in meshes.build_parts(v) if p.name in ('hob_ring', 'burner')]
        assert len(rings) >= 4 and all(p.bounds[1, 2] > v.height - 0.01 for p in rings)
        door = _parts(v, 'oven_door')[0]
        assert door.centre[0] > v.depth / 2 - 0.06 and _front_reaches(v, 'handle')
    for v in catalog.variants('fridge') + catalog.variants('dishwasher'):
        assert _parts(v, 'door') and _front_reaches(v, 'handle'), v.model_id
    for v in catalog.variants('microwave'):
        assert _parts(v, 'window')[0].centre[0] > v.depth / 2 - 0.02
    for v in catalog.variants('kitchen island'):
        # doors towards the cook at the back, knee space for stools under the front overhang
        assert all(p.centre[0] < -v.depth / 2 + 0.05 for p in _parts(v, 'door'))
        assert _parts(v, 'carcass')[0].bounds[1, 0] < v.depth / 2 - 0.2
    for v in catalog.variants('bar stool'):
        assert _parts(v, 'seat')[0].bounds[1, 2] >= 0.6 - TOL
        assert [p for p in meshes.build_parts(v) if p.name.startswith('footrest')]


def test_dining_and_hallway_shapes():
    for v in catalog.variants('dining table'):
        top = _parts(v, 'top')[0]
        assert top.bounds[0, 2] > v.height - 0.05
        if v.style == 1:
            # round (oval): the top is the ellipse in the box, its corners empty
            x, y = top.vertices[:, 0] / (v.depth / 2), top.vertices[:, 1] / (v.width / 2)
            assert (x ** 2 + y ** 2 <= 1 + 1e-6).all()
        else:
            legs = [p for p in meshes.build_parts(v) if p.name in ('leg', 'trestle_foot')]
            assert len(legs) >= 2
    for v in catalog.variants('coat rack'):
        hooks = _parts(v, 'hook')
        assert len(hooks) >= 3 and all(p.bounds[0, 0] < -v.depth / 2 + 0.05 for p in hooks)
        assert all(1.2 < p.centre[2] < v.height for p in hooks)
    for v in catalog.variants('shoe bench'):
        assert len(_parts(v, 'shoe')) >= 2
        assert all(p.bounds[1, 2] < v.height - 0.2 for p in _parts(v, 'shoe'))
    for v in catalog.variants('sideboard'):
        assert len(_parts(v, 'handle')) >= 3 and _front_reaches(v, 'handle')


@pytest.mark.parametrize('fmt', ['glb', 'obj'])
def test_export_round_trip(tmp_path, fmt):
    for v in (catalog.variants('double bed')[1], catalog.variants('coffee table')[1],
              catalog.variants('fishbowl')[0]):
        path = meshes.export_model(v, tmp_path / f'{v.model_id}.{fmt}')
        assert path.exists() and path.stat().st_size > 1000
        loaded = trimesh.load(path)
        np.testing.assert_allclose(loaded.bounds, _box_bounds(v), atol=TOL)
        if fmt == 'obj':
            assert path.with_suffix('.mtl').exists()
        else:
            assert len(loaded.geometry) >= 2          # one primitive per material
    with pytest.raises(ValueError):
        meshes.export_model(catalog.variants('cup')[0], tmp_path / 'cup.stl')


def test_export_catalog_and_mesh_path(tmp_path):
    paths = meshes.export_catalog(tmp_path, fmt='glb', categories=['cup'])
    expected = [meshes.mesh_path(v.model_id, tmp_path, 'glb') for v in catalog.variants('cup')]
    assert paths == expected
    assert all(p.exists() and p.name.endswith('.glb') for p in paths)
    assert meshes.mesh_path('cup_03', tmp_path, 'obj') == tmp_path / 'cup_03.obj'
    with pytest.raises(UnknownCategory, match="unknown category 'spaceship'"):
        meshes.export_catalog(tmp_path, categories=['spaceship'])


# ---------------------------------------------------------------------------------------
# scenes


def _scene(objects):
    room = Room('bedroom', ((0, 0), (5, 0), (5, 4), (0, 4)))
    return Scene(room, list(objects))


def _expected_bounds(obj):
    c = box_corners(obj.position[0], obj.position[1], obj.yaw, obj.width, obj.depth)
    return np.array([[c[:, 0].min(), c[:, 1].min(), obj.position[2]],
                     [c[:, 0].max(), c[:, 1].max(), obj.position[2] + obj.height]])


@pytest.mark.parametrize('yaw', [0.0, math.pi / 2, -math.pi / 2, math.pi])
def test_scene_mesh_places_objects(yaw):
    w = catalog.variants('wardrobe')[2]
    d = catalog.variants('dresser')[4]
    objs = [PlacedObject('wardrobe_0', 'wardrobe', w.model_id, (2.0, 1.0, 0.0), yaw, w.size),
            PlacedObject('dresser_0', 'dresser', d.model_id, (4.0, 3.0, 0.0), 0.0, d.size)]
    sm = meshes.scene_mesh(_scene(objs))
    for obj in objs:
        np.testing.assert_allclose(sm.graph[obj.id][0],
                                   meshes.object_transform(obj.position, obj.yaw), atol=1e-12)
        np.testing.assert_allclose(_world_bounds(sm, obj.id), _expected_bounds(obj), atol=TOL)
    np.testing.assert_allclose(
        sm.bounds, np.array([np.minimum(*[_expected_bounds(o)[0] for o in objs]),
                             np.maximum(*[_expected_bounds(o)[1] for o in objs])]), atol=TOL)


def test_scene_mesh_front_follows_yaw():
    """A wardrobe turned to face +y has its handles on its +y side."""
    w = catalog.variants('wardrobe')[0]
    obj = PlacedObject('w', 'wardrobe', w.model_id, (1.0, 1.0, 0.0), math.pi / 2, w.size)
    sm = meshes.scene_mesh(_scene([obj]))
    handle = np.vstack([p.vertices for p in meshes.build_parts(w) if p.name == 'handle'])
    world = trimesh.transform_points(handle, sm.graph['w'][0])
    assert (world[:, 1] > 1.0).all()
    assert world[:, 1].max() == pytest.approx(1.0 + w.depth / 2, abs=TOL)


def test_scene_mesh_resizes_and_shares_geometry(tmp_path):
    cup = catalog.variants('cup')[0]
    other = (0.09, 0.085, 0.11)
    objs = [PlacedObject('cup_0', 'cup', cup.model_id, (1.0, 1.0, 0.7), math.pi / 2, cup.size,
                         't'),
            PlacedObject('cup_1', 'cup', cup.model_id, (1.5, 1.0, 0.7), 0.3, cup.size, 't'),
            PlacedObject('cup_2', 'cup', cup.model_id, (2.0, 1.0, 0.7), 0.0, other, 't'),
            PlacedObject('x_0', 'cup', 'not_in_catalog', (3.0, 1.0, 0.0), math.pi, other)]
    sm = meshes.scene_mesh(_scene(objs))
    for obj in objs:
        if obj.yaw == 0.3:
            # a round cup turned by an odd angle stays inside its turned footprint
            inv = np.linalg.inv(meshes.object_transform(obj.position, obj.yaw))
            for node in sm.graph.nodes_geometry:
                if node.startswith(obj.id + '/'):
                    matrix, geom = sm.graph[node]
                    local = trimesh.transform_points(sm.geometry[geom].vertices, inv @ matrix)
                    assert (np.abs(local[:, 0]) <= obj.depth / 2 + TOL).all()
                    assert (np.abs(local[:, 1]) <= obj.width / 2 + TOL).all()
            continue
        np.testing.assert_allclose(_world_bounds(sm, obj.id), _expected_bounds(obj), atol=TOL)
    # the two same-size cups share geometry; the re-sized ones get their own
    n_mat = len(meshes.model_scene(cup).geometry)
    assert len(sm.geometry) == 2 * n_mat + len(meshes.model_scene(
        meshes.variant_for(objs[3])).geometry)
    path = tmp_path / 'scene.glb'
    sm.export(path)
    np.testing.assert_allclose(trimesh.load(path).bounds, sm.bounds, atol=TOL)


# ---------------------------------------------------------------------------------------
# previews


def test_render_image_and_preview(tmp_path):
    v = catalog.variants('double bed')[0]
    img = meshes.render_image(v, px=96)
    assert img.shape == (96, 96, 3)
    drawn = (img < 0.98).any(axis=2)
    assert 0.1 < drawn.mean() < 0.9
    path = meshes.render_preview(v, tmp_path / 'bed.png', size_px=120)
    assert path.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n'
