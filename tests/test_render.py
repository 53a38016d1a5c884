"""Tests of the multi-channel top-down renderer (scene_synth_ros.render)."""
from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from scene_synth_ros import catalog
from scene_synth_ros.categories import ROOM_SIZE_CAP, room_spec
from scene_synth_ros.render import (
    COS,
    DOOR,
    FIRST_CATEGORY,
    HEIGHT,
    HEIGHT_SCALE,
    OBJECT,
    ROOM,
    SIN,
    WALL,
    WINDOW,
    Frame,
    RoomDoesNotFit,
    TopDownRenderer,
    category_channel,
    channel_names,
    num_channels,
    pixel_to_world,
    quarter_turns,
    turn_image,
    wall_reach,
    world_to_pixel,
)
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene

SQUARE = Room('bedroom', ((-3.0, -3.0), (3.0, -3.0), (3.0, 3.0), (-3.0, 3.0)))
# 6.4 m / 64 px: 0.1 m a pixel, pixel centres at (k - 31.5) * 0.1 m.
FRAME_64 = Frame((0.0, 0.0), 0.0, 6.4, 64)


def obj(category, x, y, yaw, width, depth, height=0.5, z=0.0, oid=None, support=None):
    return PlacedObject(oid or f'{category}_{x}_{y}', category,
                        catalog.variants(category)[0].model_id, (x, y, z), yaw,
                        (width, depth, height), support)


def l_room(**kw) -> Room:
    """An L-shaped 5 x 4 m bedroom without its 2 x 1.5 m top-right corner (17 m^2)."""
    return Room('bedroom', ((0.0, 0.0), (5.0, 0.0), (5.0, 2.5), (3.0, 2.5), (3.0, 4.0),
                            (0.0, 4.0)), **kw)


def furnished_l_scene() -> Scene:
    room = l_room(doors=(Opening('door', (4.0, 0.0), 0.9, 2.1),),
                  windows=(Opening('window', (0.0, 2.0), 1.2, 1.3, 0.9),
                           Opening('window', (5.0, 1.2), 1.0, 1.3, 0.9)))
    bed = obj('double bed', 1.55, 2.93, -math.pi / 2, 1.6, 2.05, 1.0, oid='bed')
    objs = [
        bed,
        obj('stand', 0.33, 3.71, -math.pi / 2, 0.5, 0.42, 0.55, oid='stand'),
        obj('table lamp', 0.33, 3.71, 0.2, 0.3, 0.3, 0.5, z=0.55, oid='lamp',
            support='stand'),
        obj('wardrobe', 4.67, 1.3, math.pi, 1.6, 0.6, 2.1, oid='wardrobe'),
        obj('desk', 2.1, 0.33, math.pi / 2, 1.2, 0.62, 0.75, oid='desk'),
        obj('office chair', 2.07, 0.95, -1.3, 0.6, 0.6, 1.0, oid='chair'),
        obj('book', 1.52, 2.61, 0.7, 0.22, 0.27, 0.05, z=1.0, oid='book', support='bed'),
    ]
    return Scene(room, objs)


def transform_scene(scene: Scene, point, yaw) -> Scene:
    """The scene moved rigidly by the inverse of (translate to ``point``, rotate by ``yaw``)."""
    return scene.moved(0.0, (-point[0], -point[1])).moved(-yaw)


def iou(a, b) -> float:
    a, b = a > 0.5, b > 0.5
    return (a & b).sum() / max(1, (a | b).sum())


# ---------------------------------------------------------------------------------------------

def test_channel_layout():
    names = room_spec('bedroom').names
    assert num_channels('bedroom') == 8 + len(names) == 46
    assert (ROOM, WALL, OBJECT, HEIGHT, SIN, COS, DOOR, WINDOW, FIRST_CATEGORY) == tuple(range(9))
    assert channel_names('bedroom')[FIRST_CATEGORY:] == names
    assert category_channel('bedroom', names[0]) == FIRST_CATEGORY
    assert category_channel('bedroom', 'double bed') == FIRST_CATEGORY + names.index('double bed')
    img = TopDownRenderer(32).render(Scene(SQUARE, []))
    assert img.shape == (46, 32, 32) and img.dtype == np.float32


def test_axis_aligned_box_exact_pixels():
    # Depth 1.0 m along x, width 0.5 m along y, centred at (1.03, -0.52):
    # x in [0.53, 1.53] -> columns with 0.53 <= (j - 31.5) * 0.1 <= 1.53 -> j = 37..46;
    # y in [-0.77, -0.27] -> rows with -0.77 <= (i - 31.5) * 0.1 <= -0.27 -> i = 24..28.
    scene = Scene(SQUARE, [obj('desk', 1.03, -0.52, 0.0, 0.5, 1.0, 0.75)])
    img = TopDownRenderer().render(scene, FRAME_64)
    expected = np.zeros((64, 64), bool)
    expected[24:29, 37:47] = True
    assert np.array_equal(img[OBJECT] > 0, expected)
    assert np.array_equal(img[category_channel('bedroom', 'desk')] > 0, expected)
    others = [c for c in range(FIRST_CATEGORY, img.shape[0])
              if c != category_channel('bedroom', 'desk')]
    assert not img[others].any()


def test_pixel_centre_rule_on_boundary_counts_as_inside():
    # Box edges exactly through pixel centres: x in [-0.05, 0.25] covers centres of columns
    # 31..34 (-0.05, 0.05, 0.15, 0.25), y in [0.05, 0.15] covers rows 32..33.
    scene = Scene(SQUARE, [obj('desk', 0.10, 0.10, 0.0, 0.10, 0.30)])
    img = TopDownRenderer().render(scene, FRAME_64)
    rows, cols = np.nonzero(img[OBJECT])
    assert set(rows) == {32, 33} and set(cols) == {31, 32, 33, 34}
    assert len(rows) == 8


def test_rotated_box_is_transposed_footprint():
    r = TopDownRenderer()
    a = r.render(Scene(SQUARE, [obj('desk', 0.73, -1.21, 0.0, 0.55, 1.37)]), FRAME_64)
    b = r.render(Scene(SQUARE, [obj('desk', -1.21, 0.73, math.pi / 2, 0.55, 1.37)]), FRAME_64)
    assert a[OBJECT].sum() > 50
    assert np.array_equal(a[OBJECT], b[OBJECT].T)
    m = b[OBJECT] > 0
    assert np.allclose(b[SIN][m], 1.0) and np.allclose(b[COS][m], 0.0, atol=1e-7)
    assert np.allclose(a[SIN][a[OBJECT] > 0], 0.0) and np.allclose(a[COS][a[OBJECT] > 0], 1.0)


def test_rotated_box_matches_brute_force_geometry():
    rng = np.random.default_rng(3)
    r = TopDownRenderer()
    frame = Frame((0.2, -0.1), 0.37, 6.4, 64)
    centres = pixel_to_world(frame, np.stack(np.meshgrid(np.arange(64), np.arange(64),
                                                         indexing='ij'), -1))
    for _ in range(20):
        o = obj('desk', *rng.uniform(-2, 2, 2), rng.uniform(-math.pi, math.pi),
                *rng.uniform(0.2, 1.8, 2))
        img = r.render(Scene(SQUARE, [o]), frame)
        expected = shapely.intersects_xy(o.footprint(), centres[..., 0], centres[..., 1])
        assert np.array_equal(img[OBJECT] > 0, expected)


def test_height_sin_cos_and_second_tier_wins():
    bed = obj('double bed', 0.0, 0.0, 0.0, 1.6, 2.0, 1.0, oid='bed')
    lamp = obj('table lamp', 0.3, 0.2, 0.6, 0.4, 0.4, 0.5, z=1.0, oid='lamp', support='bed')
    # Parent after child in the scene: drawing order must follow the top height.
    img = TopDownRenderer().render(Scene(SQUARE, [lamp, bed]), FRAME_64)
    bed_px = img[category_channel('bedroom', 'double bed')] > 0
    lamp_px = img[category_channel('bedroom', 'table lamp')] > 0
    assert lamp_px.sum() > 4 and (lamp_px & ~bed_px).sum() == 0
    assert np.array_equal(img[OBJECT] > 0, bed_px | lamp_px)
    only_bed = bed_px & ~lamp_px
    assert np.allclose(img[HEIGHT][only_bed], 1.0 / HEIGHT_SCALE)
    assert np.allclose(img[SIN][only_bed], 0.0) and np.allclose(img[COS][only_bed], 1.0)
    assert np.allclose(img[HEIGHT][lamp_px], 1.5 / HEIGHT_SCALE)
    assert np.allclose(img[SIN][lamp_px], math.sin(0.6))
    assert np.allclose(img[COS][lamp_px], math.cos(0.6))
    empty = ~(bed_px | lamp_px)
    assert not img[HEIGHT][empty].any() and not img[SIN][empty].any()
    assert not img[COS][empty].any()


def test_render_draws_into_a_reused_buffer_as_into_a_fresh_one():
    bed = obj('double bed', 0.0, 0.0, 0.0, 1.6, 2.0, 1.0, oid='bed')
    r = TopDownRenderer()
    fresh = r.render(Scene(SQUARE, [bed]), FRAME_64)
    buf = np.full_like(fresh, 7.0)                 # whatever the last crop left there
    assert r.render(Scene(SQUARE, [bed]), FRAME_64, out=buf) is buf
    assert np.array_equal(buf, fresh)
    r.render(Scene(SQUARE, []), FRAME_64, out=buf)  # the bed does not linger
    assert not buf[OBJECT].any() and buf[0].any()
    with pytest.raises(ValueError, match='float32 array of shape'):
        r.render(Scene(SQUARE, [bed]), FRAME_64, out=np.zeros(fresh.shape))
    with pytest.raises(ValueError, match='float32 array of shape'):
        r.render(Scene(SQUARE, [bed]), FRAME_64, out=buf[1:])


@pytest.mark.parametrize('k', [0, 1, 2, 3])
def test_local_frame_equals_inverse_transformed_scene_right_angles(k):
    scene = furnished_l_scene()
    point, yaw = (1.83, 1.27), k * math.pi / 2
    r = TopDownRenderer()
    local = r.render_local(scene, point, yaw)
    moved = transform_scene(scene, point, yaw)
    ref = r.render(moved, Frame((0.0, 0.0), 0.0, ROOM_SIZE_CAP['bedroom'], 64))
    assert local[OBJECT].sum() > 100 and local[DOOR].sum() > 0 and local[WALL].sum() > 50
    np.testing.assert_allclose(local, ref, atol=1e-6)
    assert np.array_equal(local[[ROOM, WALL, OBJECT, DOOR, WINDOW]] > 0,
                          ref[[ROOM, WALL, OBJECT, DOOR, WINDOW]] > 0)


@pytest.mark.parametrize('yaw', [0.4, -2.2, 3.0])
def test_local_frame_equals_inverse_transformed_scene_general_yaw(yaw):
    scene = furnished_l_scene()
    point = (2.4, 1.6)
    r = TopDownRenderer()
    local = r.render_local(scene, point, yaw)
    ref = r.render(transform_scene(scene, point, yaw),
                   Frame((0.0, 0.0), 0.0, ROOM_SIZE_CAP['bedroom'], 64))
    for ch in (ROOM, WALL, OBJECT, DOOR, WINDOW, category_channel('bedroom', 'double bed')):
        assert iou(local[ch], ref[ch]) > 0.95, ch


def test_local_frame_orientation():
    # An object 1 m ahead of the point along the frame's yaw lands right of the image centre
    # (column axis = the yaw direction); 1 m to its left lands above (row axis).
    yaw = 0.9
    ahead = obj('stool', 2.0 + math.cos(yaw), 2.0 + math.sin(yaw), 0.0, 0.3, 0.3)
    left = obj('ottoman', 2.0 - math.sin(yaw), 2.0 + math.cos(yaw), 0.0, 0.3, 0.3)
    img = TopDownRenderer(64).render_local(Scene(l_room(), [ahead, left]), (2.0, 2.0), yaw)
    m = ROOM_SIZE_CAP['bedroom'] / 64
    rows, cols = np.nonzero(img[category_channel('bedroom', 'stool')])
    assert abs(rows.mean() + 0.5 - 32) < 0.5 and abs((cols.mean() + 0.5 - 32) * m - 1.0) < 0.05
    rows, cols = np.nonzero(img[category_channel('bedroom', 'ottoman')])
    assert abs(cols.mean() + 0.5 - 32) < 0.5 and abs((rows.mean() + 0.5 - 32) * m - 1.0) < 0.05


@pytest.mark.parametrize('layout', ['channels-first', 'channels-last'])
@pytest.mark.parametrize('yaw', [0.0, 0.37, -2.9])
def test_a_crop_turned_by_quarter_turns_is_the_crop_drawn_in_the_turned_frame(yaw, layout):
    # The dimensions module's crops are the orientation module's turned (``Synthesizer.
    # _local_images``): every mask must be the one drawn, and SIN/COS the yaws relative to
    # the turned frame.
    scene = furnished_l_scene()
    r = TopDownRenderer()
    masks = [c for c in range(num_channels('bedroom')) if c not in (SIN, COS)]
    for point in ((1.83, 1.27), (0.4, 3.6), (4.1, 0.9)):
        drawn = r.render_local(scene, point, yaw)
        assert drawn[OBJECT].sum() > 20 and drawn[WALL].sum() > 20
        for q in (1, 2, 3):
            want = r.render_local(scene, point, math.remainder(yaw + q * math.pi / 2,
                                                               2 * math.pi))
            got = drawn.copy()
            if layout == 'channels-last':
                got = np.moveaxis(np.ascontiguousarray(np.moveaxis(got, 0, -1)), -1, 0)
            turn_image(got, q)
            assert np.array_equal(got[masks], want[masks]), (point, q)
            np.testing.assert_allclose(got[[SIN, COS]], want[[SIN, COS]], atol=1e-6)
            assert not np.array_equal(got[OBJECT], drawn[OBJECT])
        same = drawn.copy()
        turn_image(same, 4)
        assert np.array_equal(same, drawn)


def test_quarter_turns_are_told_from_other_angles():
    assert [quarter_turns(k * math.pi / 2) for k in range(-4, 5)] == [0, 1, 2, 3] * 2 + [0]
    assert quarter_turns(math.pi / 2 + 1e-12) == 1
    assert quarter_turns(math.pi / 2 + 1e-6) is None and quarter_turns(0.3) is None


@pytest.mark.parametrize('yaw', [0.0, 0.3])
def test_whole_pixel_translation_shifts_image(yaw):
    scene = furnished_l_scene()
    r = TopDownRenderer()
    f1 = Frame((2.5, 2.0), yaw, 6.0, 64)
    kx, ky = 5, 3
    shift = f1.to_world(np.array([kx, ky]) * f1.metres_per_pixel) - np.array(f1.centre)
    f2 = Frame(tuple(np.array(f1.centre) + shift), yaw, 6.0, 64)
    a, b = r.render(scene, f1), r.render(scene, f2)
    assert a[OBJECT].sum() > 100
    np.testing.assert_allclose(b[:, :64 - ky, :64 - kx], a[:, ky:, kx:], atol=1e-6)
    assert np.array_equal(b[:, :64 - ky, :64 - kx] > 0, a[:, ky:, kx:] > 0)


@pytest.mark.parametrize('res, tol', [(64, 0.03), (256, 0.01)])
def test_l_shaped_room_mask_area(res, tol):
    room = l_room()
    img = TopDownRenderer(res).render(Scene(room, []))
    m = ROOM_SIZE_CAP['bedroom'] / res
    assert abs(img[ROOM].sum() - room.area / m ** 2) < tol * room.area / m ** 2
    # The missing corner is not floor; the wall is outside the floor and rings it.
    frame = Frame.for_room(room, res)
    i, j = world_to_pixel(frame, (4.2, 3.4))
    assert img[ROOM, i, j] == 0
    assert not (img[ROOM] * img[WALL]).any()
    for wall in room.walls:
        mid = wall.point_at(wall.length / 2) - wall.normal * 0.5 * wall_reach(frame)
        i, j = world_to_pixel(frame, mid)
        assert img[WALL, i, j] == 1 and img[ROOM, i, j] == 0
        inside = wall.point_at(wall.length / 2) + wall.normal * 0.3
        i, j = world_to_pixel(frame, inside)
        assert img[ROOM, i, j] == 1 and img[WALL, i, j] == 0
    # Every wall pixel is within the wall reach of the outline.
    centres = pixel_to_world(frame, np.argwhere(img[WALL] > 0))
    d = shapely.distance(room.polygon.exterior, shapely.points(centres))
    assert d.max() <= wall_reach(frame) + 1e-9


def test_doors_and_windows_land_on_the_wall():
    scene = furnished_l_scene()
    room = scene.room
    r = TopDownRenderer()
    frame = Frame.for_room(room, 64)
    img = r.render(scene, frame)
    for ch, openings in ((DOOR, room.doors), (WINDOW, room.windows)):
        px = img[ch] > 0
        assert (px & (img[WALL] > 0)).sum() > 0
        centres = pixel_to_world(frame, np.argwhere(px))
        lines = [shapely.LineString([room.wall_of(o).point_at(room.wall_of(o).offset_of(
            o.position) - o.width / 2), room.wall_of(o).point_at(room.wall_of(o).offset_of(
                o.position) + o.width / 2)]) for o in openings]
        d = np.min([shapely.distance(line, shapely.points(centres)) for line in lines], 0)
        assert d.max() <= max(0.15, wall_reach(frame)) + 1e-9
        for o in openings:
            wall = room.wall_of(o)
            # Wall pixels along the opening are covered.
            for t in (-0.3, 0.0, 0.3):
                p = np.asarray(o.position) + wall.direction * t * o.width \
                    - wall.normal * 0.5 * wall_reach(frame)
                i, j = world_to_pixel(frame, p)
                assert img[ch, i, j] == 1 and img[WALL, i, j] == 1
            area = o.width * 2 * max(0.15, wall_reach(frame)) / frame.metres_per_pixel ** 2
            assert 0.5 * area < px.sum()
    assert img[DOOR].sum() < img[WINDOW].sum()


def test_room_larger_than_its_square_is_seen_at_the_same_pixel_size():
    big = Room('bedroom', ((0, 0), (7.5, 0), (7.5, 3.8), (0, 3.8)))
    m = ROOM_SIZE_CAP['bedroom'] / 64
    frame = Frame.for_room(big, 64)
    assert frame.resolution == 80 and frame.metres_per_pixel == pytest.approx(m)
    grown = Frame.for_room(big, 64, multiple=32)
    assert grown.resolution == 96 and grown.metres_per_pixel == pytest.approx(m)
    assert grown.centre == pytest.approx((3.75, 1.9))
    img = TopDownRenderer(96).render(Scene(big, []), grown)
    # The whole floor is drawn, at the type's pixel size, with its wall ring closed.
    assert img[ROOM].sum() == pytest.approx(7.5 * 3.8 / m ** 2, rel=0.03)
    rows, cols = np.nonzero(img[WALL])
    assert rows.min() > 0 and cols.min() > 0 and rows.max() < 95 and cols.max() < 95
    # A room that fits its square is the middle of its image in a grown frame: the pixels
    # sit at the same places of the world, so the larger image holds the smaller one.
    fits = furnished_l_scene()
    small = Frame.for_room(fits.room, 64)
    wide = Frame(small.centre, small.yaw, 96 * small.metres_per_pixel, 96)
    a = TopDownRenderer(64).render(fits, small)
    b = TopDownRenderer(96).render(fits, wide)
    assert a[2:].any()
    assert np.array_equal(b[:, 16:80, 16:80], a)
    assert not b[:, :16].any() and not b[:, 80:].any()


def test_room_longer_than_a_room_may_be_raises():
    huge = Room('bedroom', ((0, 0), (16.5, 0), (16.5, 3), (0, 3)))
    with pytest.raises(RoomDoesNotFit, match='16.5 m x 3 m along its walls, longer than the '
                                             '16 m a bedroom may be along its longer side'):
        TopDownRenderer().render(Scene(huge, []))
    exact = Room('bedroom', ((0, 0), (6.0, 0), (6.0, 6.0), (0, 6.0)))
    assert Frame.for_room(exact, 64).centre == (3.0, 3.0)
    assert Frame.for_room(exact, 64).resolution == 64
    longest = Room('bathroom', ((0, 0), (16.0, 0), (16.0, 2.0), (0, 2.0)))
    assert Frame.for_room(longest, 64, multiple=32).resolution == 224
    # A local view is not limited by the room's size.
    assert TopDownRenderer().render_local(Scene(huge, []), (1.0, 1.0), 0.0).shape[1:] == (64, 64)


def test_unknown_category_raises():
    with pytest.raises(ValueError, match='toilet'):
        TopDownRenderer().render(Scene(SQUARE, [obj('toilet', 0, 0, 0, 0.4, 0.7)]), FRAME_64)


def test_pixel_world_round_trip():
    frame = Frame((1.3, -0.4), 0.77, 6.0, 64)
    ij = np.array([[0, 0], [10, 50], [63, 63], [31, 7]])
    xy = pixel_to_world(frame, ij)
    assert np.array_equal(world_to_pixel(frame, xy), ij)
    assert np.allclose(world_to_pixel(frame, xy, continuous=True), ij)
    # Nudging within a pixel keeps the pixel.
    m = frame.metres_per_pixel
    assert np.array_equal(world_to_pixel(frame, xy + 0.4 * m * np.array([0.7, -0.7])), ij)
    # Frame at yaw 0: pixel (0, 0) is the bottom-left corner (min x, min y).
    f0 = Frame((0.0, 0.0), 0.0, 6.4, 64)
    assert np.allclose(pixel_to_world(f0, (0, 0)), (-3.15, -3.15))
    assert np.allclose(pixel_to_world(f0, (0, 63)), (3.15, -3.15))
    assert np.array_equal(f0.world_to_pixel((0.001, 0.001)), (32, 32))


def test_room_cache_is_reused_and_safe():
    scene = furnished_l_scene()
    r = TopDownRenderer(64)
    a = r.render(scene)
    frame = Frame.for_room(scene.room, 64)
    layers = r.static_layers(scene.room, frame)
    # An equal room built anew hits the same cache entry.
    same = Room.from_dict(scene.room.to_dict())
    assert r.static_layers(same, frame) is layers
    a[:] = 0.0                                  # the caller owns the image it gets
    b = r.render(scene)
    assert b[ROOM].sum() > 1000
    r.clear_cache()
    c = r.render(scene)
    assert np.array_equal(b, c)
    # A different room is not confused with the cached one.
    other = Scene(Room('bedroom', ((0, 0), (3, 0), (3, 3), (0, 3))), [])
    assert r.render(other)[ROOM].sum() < b[ROOM].sum()


def test_object_outside_frame_is_skipped():
    far = obj('desk', 30.0, 30.0, 0.3, 1.0, 0.6)
    img = TopDownRenderer().render(Scene(SQUARE, [far]), FRAME_64)
    assert not img[OBJECT].any()


# ---- the room's frame: one definition, rooms of any orientation ------------------------------
RECT = ((0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (0.0, 3.0))
ELL = ((0.0, 0.0), (5.0, 0.0), (5.0, 2.0), (2.5, 2.0), (2.5, 4.0), (0.0, 4.0))


def furnished(floor) -> Scene:
    room = Room('bedroom', floor, 2.6, doors=(Opening('door', (1.0, 0.0), 0.9, 2.0),),
                windows=(Opening('window', (0.0, 1.5), 1.0, 1.2, 0.9),))
    return Scene(room, [obj('double bed', 2.2, 1.1, 0.0, 1.6, 2.0, 0.5),
                        obj('stand', 3.5, 0.3, 0.4, 0.45, 0.4, 0.55),
                        obj('desk', 1.0, 2.6, -1.2, 1.2, 0.6, 0.75)])


@pytest.mark.parametrize('floor', [RECT, ELL], ids=['rectangle', 'L'])
@pytest.mark.parametrize('degrees', [0, 17, 30, 45, 90])
def test_room_frame_turns_with_the_room(floor, degrees):
    """A room turned by any angle is seen in its own axes: its frame yaw is the angle reduced
    to [-45, 45) degrees, and its image is the unturned room's image, turned by the whole
    quarter turns the reduction took away."""
    base = furnished(floor)
    angle = math.radians(degrees)
    turned = base.moved(angle, (0.7, -1.3))
    r = TopDownRenderer(64)
    f0, f1 = Frame.for_room(base.room, 64), Frame.for_room(turned.room, 64)
    assert f0.yaw == 0.0 and -math.pi / 4 - 1e-9 <= f1.yaw < math.pi / 4
    quarters = round((angle - f1.yaw) / (math.pi / 2))
    assert math.isclose(angle - f1.yaw, quarters * math.pi / 2, abs_tol=1e-9)
    # The frame's centre is the centre of the room's own box, wherever the room is.
    assert np.allclose(f1.to_local(np.array(turned.room.floor)).min(0),
                       -f1.to_local(np.array(turned.room.floor)).max(0), atol=1e-9)
    want = np.rot90(r.render(base, f0), quarters, axes=(2, 1))
    got = r.render(turned, f1)
    fixed = [c for c in range(got.shape[0]) if c not in (SIN, COS)]
    assert np.array_equal(got[fixed], want[fixed])
    # The yaw channels hold yaws relative to the frame: a quarter turn maps (sin, cos) to
    # (cos, -sin).
    sin, cos = want[SIN], want[COS]
    for _ in range(quarters % 4):
        sin, cos = cos, -sin
    assert np.allclose(got[SIN], sin, atol=1e-6) and np.allclose(got[COS], cos, atol=1e-6)


@pytest.mark.parametrize('degrees', [0, 17, 30, 45, 90])
def test_room_fits_iff_it_fits_in_its_own_axes(degrees):
    angle = math.radians(degrees)
    fits = Scene(Room('bedroom', ((0, 0), (5.5, 0), (5.5, 5.0), (0, 5.0)))).moved(angle)
    assert Frame.for_room(fits.room, 64).extent == ROOM_SIZE_CAP['bedroom']
    grown = Scene(Room('bedroom', ((0, 0), (6.2, 0), (6.2, 2.0), (0, 2.0)))).moved(angle)
    assert Frame.for_room(grown.room, 64, multiple=32).resolution == 96
    too_long = Scene(Room('bedroom', ((0, 0), (16.2, 0), (16.2, 2.0), (0, 2.0)))).moved(angle)
    with pytest.raises(RoomDoesNotFit, match='16.2 m x 2 m along its walls'):
        Frame.for_room(too_long.room, 64)
