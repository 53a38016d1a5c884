"""The physical model every export shares (``export.physics``): collision pieces, clearance,
mass and inertia."""
import numpy as np
import pytest

from scene_synth_ros import catalog
from scene_synth_ros.categories import CATEGORIES
from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.export.physics import (
    DENSITIES,
    OPEN_FRAME,
    Piece,
    body_of,
    mass_properties,
    model_pieces,
    scene_bodies,
)
from scene_synth_ros.meshes import build_parts
from scene_synth_ros.scene import PlacedObject, Room, Scene
from scene_synth_ros.thresholds import COLLISION_TOLERANCE


def _extent(pieces):
    lo = np.min([np.subtract(p.centre, np.divide(p.size, 2)) for p in pieces], axis=0)
    hi = np.max([np.add(p.centre, np.divide(p.size, 2)) for p in pieces], axis=0)
    return lo, hi


def test_every_catalog_category_has_a_density_group_of_its_own():
    members = [c for _, group in DENSITIES.values() for c in group]
    assert len(members) == len(set(members))
    assert set(CATEGORIES) <= set(members)


def test_pieces_span_the_model_box_from_floor_to_top():
    # Whatever is merged or dropped, a model stands on z = 0 and holds things at its height.
    for category in CATEGORIES:
        for v in catalog.variants(category):
            pieces = model_pieces(v)
            lo, hi = _extent(pieces)
            w, d, h = v.size
            assert lo[2] == pytest.approx(0, abs=1e-9) and hi[2] == pytest.approx(h), v.model_id
            assert np.all(lo[:2] >= [-d / 2 - 1e-9, -w / 2 - 1e-9])
            assert np.all(hi[:2] <= [d / 2 + 1e-9, w / 2 + 1e-9])
            assert 1 <= len(pieces) <= 8
            if category not in OPEN_FRAME:
                assert len(pieces) == 1


def test_a_table_collides_as_top_and_legs_with_its_knee_space_free():
    v = catalog.variants('desk')[0]             # four legs, aprons and a top
    pieces = model_pieces(v)
    w, d, h = v.size
    top = max(pieces, key=lambda p: p.centre[2] + p.size[2] / 2)
    assert top.size[0] == pytest.approx(d) and top.size[1] == pytest.approx(w)
    assert top.size[2] < 0.1                    # a slab, not the whole box
    floor = [p for p in pieces if p.centre[2] - p.size[2] / 2 < 1e-9]
    assert len(floor) == 4 and all(p.size[0] * p.size[1] < 0.01 for p in floor)
    # The middle of the knee space is empty.
    centre = np.array([0.0, 0.0, h / 3])
    assert not any(np.all(np.abs(centre - p.centre) <= np.divide(p.size, 2)) for p in pieces)


def _covered(pieces, point, slack=1e-9) -> bool:
    return any(np.all(np.abs(np.subtract(point, p.centre)) <= np.divide(p.size, 2) + slack)
               for p in pieces)


def test_a_kitchen_island_leaves_knee_space_and_a_sink_its_worktop_free_beside_the_tap():
    for v in catalog.variants('kitchen island'):
        pieces = model_pieces(v)
        w, d, h = v.size
        # under the front overhang, where a bar stool's knees go, nothing collides
        assert not _covered(pieces, (d / 2 - 0.05, 0.0, h / 2)), v.model_id
        assert _covered(pieces, (d / 2 - 0.05, 0.0, h - 0.01)), v.model_id   # the worktop
    for v in catalog.variants('kitchen sink'):
        pieces = model_pieces(v)
        w, d, h = v.size
        assert 2 <= len(pieces) <= 8
        # a cup can stand on the worktop at the front corner; the tap is a piece of its own
        assert not _covered(pieces, (d / 2 - 0.05, w / 2 - 0.05, 0.95)), v.model_id
        tap = [p for p in build_parts(v) if p.name == 'tap'][0]
        assert _covered(pieces, (*tap.centre[:2], h - 0.05)), v.model_id


def test_a_chair_keeps_its_seat_and_the_space_under_it():
    for v in catalog.variants('straight chair')[:3]:
        pieces = model_pieces(v)
        seat_height = 0.45
        under = np.array([0.0, 0.0, seat_height / 2])
        assert not any(np.all(np.abs(under - p.centre) <= np.divide(p.size, 2) - 1e-9)
                       for p in pieces), v.model_id
        # Something covers the seat's centre at seat height.
        seat = np.array([0.05, 0.0, seat_height + 0.01])
        assert any(np.all(np.abs(seat - p.centre) <= np.divide(p.size, 2) + 1e-9)
                   for p in pieces), v.model_id


def test_mass_is_box_volume_times_the_group_density():
    room = Room('bedroom', ((0, 0), (4, 0), (4, 4), (0, 4)))
    v = catalog.variants('wardrobe')[0]
    obj = PlacedObject('w', 'wardrobe', v.model_id, (2.0, 2.0, 0.0), 0.0, v.size)
    body = body_of(obj, room)
    assert body.mass == pytest.approx(60.0 * v.width * v.depth * v.height)
    assert 40 < body.mass < 200                 # a wardrobe weighs what a wardrobe weighs


def test_inertia_of_one_box_is_the_textbook_one():
    pieces = (Piece((0.0, 0.0, 0.5), (2.0, 1.0, 1.0)),)
    com, inertia = mass_properties(pieces, 12.0)
    assert np.allclose(com, (0, 0, 0.5))
    assert np.allclose(inertia, np.diag([1 + 1, 4 + 1, 4 + 1]))


def test_inertia_is_symmetric_positive_and_obeys_the_triangle_inequality():
    scene = generate_room('office', 0, 3)
    for body in scene_bodies(scene):
        i = body.inertia
        assert np.allclose(i, i.T)
        moments, axes = body.principal_inertia()
        assert np.all(moments > 0) and np.linalg.det(axes) == pytest.approx(1)
        assert moments[0] + moments[1] >= moments[2] * (1 - 1e-9)
        assert np.allclose(axes @ np.diag(moments) @ axes.T, i)


def test_pieces_keep_clear_of_walls_neighbours_and_the_parent_edge():
    room = Room('bedroom', ((0, 0), (3, 0), (3, 3), (0, 3)))
    stand = catalog.variants('stand')[0]
    desk = catalog.variants('desk')[0]
    w, d, h = stand.size
    # A stand 8 mm through the back wall, a desk 8 mm into the stand's side, a vase a
    # quarter over the stand's edge towards the (taller) desk.
    s = PlacedObject('stand', 'stand', stand.model_id, (d / 2 - 0.008, 1.0, 0.0), 0.0,
                     stand.size)
    k = PlacedObject('desk', 'desk', desk.model_id,
                     (desk.depth / 2, 1.0 + w / 2 + desk.width / 2 - 0.008, 0.0), 0.0,
                     desk.size)
    vase = catalog.variants('vase')[0]
    top = PlacedObject('vase', 'vase', vase.model_id,
                       (s.position[0], 1.0 + w / 2 - vase.width / 4, h), 0.0, vase.size,
                       support='stand')
    bodies = {b.id: b for b in scene_bodies(Scene(room, [s, k, top]))}
    lo, hi = _extent(bodies['stand'].pieces)
    assert s.position[0] + lo[0] >= 0.0 - 1e-9                       # out of the wall
    assert s.position[1] + hi[1] <= 1.0 + w / 2 - COLLISION_TOLERANCE / 2 + 1e-9
    k_lo, _ = _extent(bodies['desk'].pieces)
    assert k.position[1] + k_lo[1] > s.position[1] + hi[1]            # a gap between them
    v_lo, v_hi = _extent(bodies['vase'].pieces)
    assert top.position[1] + v_hi[1] <= 1.0 + w / 2 - COLLISION_TOLERANCE / 2 + 1e-9
    assert v_lo[2] == 0.0 and top.position[2] == pytest.approx(h)     # on the stand's top


def test_turned_footprints_through_a_wall_are_cut_back_inside_the_floor():
    from shapely.geometry import Point, Polygon

    from scene_synth_ros.scene import box_corners
    room = Room('living', ((0, 0), (4, 0), (4, 2), (2, 2), (2, 4), (0, 4)))      # L-shaped
    rng = np.random.default_rng(0)
    v = catalog.variants('dresser')[0]
    floor = room.polygon.buffer(1e-6)
    checked = 0
    for _ in range(20000):
        if checked == 20:
            break
        yaw = rng.uniform(-np.pi, np.pi)
        pos = rng.uniform(0, 4, size=2)
        obj = PlacedObject('d', 'dresser', v.model_id, (*pos, 0.0), yaw, v.size)
        fp = obj.footprint()
        if not room.polygon.buffer(0.01).covers(fp) or room.polygon.covers(fp):
            continue                                  # only footprints up to 1 cm through
        (piece,) = body_of(obj, room).pieces
        corners = box_corners(0, 0, 0, piece.size[1], piece.size[0]) + piece.centre[:2]
        world = corners @ np.array([[np.cos(yaw), np.sin(yaw)], [-np.sin(yaw), np.cos(yaw)]])
        world = world + pos
        assert floor.covers(Polygon(world)), (pos, yaw)
        assert piece.size[0] > v.depth - 0.05 and piece.size[1] > v.width - 0.05
        assert all(floor.covers(Point(c)) for c in world)
        checked += 1
    assert checked == 20
