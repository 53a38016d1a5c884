"""The walls family of design rules, on hand-built rooms that keep and break each rule."""
import math

import numpy as np

from scene_synth_ros.rules import walls
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene

UP, DOWN, RIGHT, LEFT = math.pi / 2, -math.pi / 2, 0.0, math.pi   # where a front faces

WARDROBE = (1.0, 0.6, 2.0)       # (width, depth, height)
DESK = (1.4, 0.7, 0.75)
OFFICE_CHAIR = (0.6, 0.6, 1.0)
DOUBLE_BED = (1.6, 2.0, 1.0)
DAYBED = (2.0, 0.95, 0.9)


def room(width=5.0, depth=4.0, windows=(), floor=None):
    floor = floor or ((0, 0), (width, 0), (width, depth), (0, depth))
    return Room('bedroom', floor, 2.6, (), tuple(windows))


def window(x, y, width=1.2, sill=0.9):
    return Opening('window', (x, y), width, 1.2, sill)


def scene(r, *objects):
    placed = []
    for k, (category, x, y, yaw, size) in enumerate(objects):
        stem = category.replace(' ', '_')
        placed.append(PlacedObject(f'{stem}_{k}', category, f'{stem}_00', (x, y, 0.0), yaw,
                                   size))
    return Scene(r, placed)


def on_floor_wall(category, x, size, gap):
    """A piece backed onto the wall y = 0 with ``gap`` metres behind it, facing the room."""
    return (category, x, size[1] / 2 + gap, UP, size)


# ---- wall_contact and wall_near_miss ----------------------------------------------------
def test_wall_contact_counts_wall_furniture_with_its_back_within_10_cm():
    s = scene(room(),
              on_floor_wall('wardrobe', 1.0, WARDROBE, 0.02),
              on_floor_wall('dresser', 2.5, (1.0, 0.5, 0.9), 0.08),
              on_floor_wall('shelving', 4.0, (1.0, 0.35, 1.8), 0.25),
              ('armchair', 2.5, 2.5, DOWN, (0.8, 0.8, 0.9)))      # not wall furniture
    s.objects.append(PlacedObject('lamp', 'table lamp', 'table_lamp_00', (2.5, 0.33, 0.9),
                                  UP, (0.3, 0.3, 0.5), support='dresser_1'))
    assert walls.measure_wall_contact(s) == (2, 3)


def test_wall_contact_wants_the_back_on_the_wall_not_a_side_or_a_corner():
    in_corner = ('wardrobe', 0.5, 0.31, UP, WARDROBE)      # back on y = 0, side on x = 0
    side_on = ('wardrobe', 0.6, 3.5, RIGHT, WARDROBE)      # side on y = 4, back 0.3 off x = 0
    s = scene(room(), in_corner, side_on)
    assert walls.measure_wall_contact(s) == (1, 2)


def test_wall_contact_does_not_take_one_touching_corner_for_a_back():
    tilted = PlacedObject('wardrobe_0', 'wardrobe', 'wardrobe_00', (2.5, 1.0, 0.0),
                          UP + math.radians(20), WARDROBE)
    lift = 0.005 - tilted.corners()[:, 1].min()
    tilted.position = (2.5, 1.0 + lift, 0.0)          # one back corner 5 mm off the wall
    assert walls.measure_wall_contact(Scene(room(), [tilted])) == (0, 1)


def test_wall_contact_takes_a_daybed_and_a_bath_by_their_long_backs():
    s = scene(room(),
              on_floor_wall('daybed', 1.2, DAYBED, 0.01),
              on_floor_wall('bathtub', 3.6, (1.7, 0.8, 0.6), 0.01),
              ('double bed', 2.5, 3.0, LEFT, DOUBLE_BED))       # headboard 1.5 m off x = 5
    assert walls.measure_wall_contact(s) == (2, 3)


def test_wall_contact_takes_a_wall_drawn_in_two_collinear_pieces_as_one():
    r = room(floor=((0, 0), (2, 0), (4, 0), (4, 3), (0, 3)))
    s = scene(r, on_floor_wall('wardrobe', 2.0, (1.6, 0.6, 2.0), 0.01))
    assert walls.measure_wall_contact(s) == (1, 1)


def test_wall_near_miss_flags_backs_10_to_40_cm_off_the_wall():
    s = scene(room(6.0),
              on_floor_wall('wardrobe', 0.8, WARDROBE, 0.05),
              on_floor_wall('wardrobe', 2.0, WARDROBE, 0.25),
              on_floor_wall('wardrobe', 3.2, WARDROBE, 0.38),
              on_floor_wall('wardrobe', 4.6, WARDROBE, 0.60))
    assert walls.measure_wall_near_miss(s) == (2, 4)
    assert walls.measure_wall_contact(s) == (1, 4)


def test_wall_rules_have_no_case_in_a_room_without_wall_furniture():
    s = scene(room(), ('armchair', 2.5, 2.0, UP, (0.8, 0.8, 0.9)))
    assert walls.measure_wall_contact(s) == (0, 0)
    assert walls.measure_wall_near_miss(s) == (0, 0)


# ---- no_floating_large_pieces ------------------------------------------------------------
def desk_mid_room(*others):
    return scene(room(6.0, 5.0), ('desk', 3.0, 2.5, RIGHT, DESK), *others)


def test_a_desk_alone_mid_room_floats():
    assert walls.measure_floating(desk_mid_room()) == (0, 1)


def test_a_desk_with_a_seat_turned_to_it_is_a_group():
    at_desk = ('office chair', 3.35 + 0.1 + 0.3, 2.5, LEFT, OFFICE_CHAIR)
    assert walls.measure_floating(desk_mid_room(at_desk)) == (1, 1)


def test_a_seat_turned_away_or_too_far_does_not_excuse_a_desk():
    turned_away = ('office chair', 3.35 + 0.1 + 0.3, 2.5, RIGHT, OFFICE_CHAIR)
    too_far = ('office chair', 3.35 + 0.8 + 0.3, 2.5, LEFT, OFFICE_CHAIR)
    assert walls.measure_floating(desk_mid_room(turned_away)) == (0, 1)
    assert walls.measure_floating(desk_mid_room(too_far)) == (0, 1)


def test_a_large_piece_within_40_cm_of_a_wall_does_not_float():
    near = scene(room(6.0, 5.0), ('desk', 0.35 + 0.3, 2.5, RIGHT, DESK))   # 0.3 m off x = 0
    off = scene(room(6.0, 5.0), ('desk', 0.35 + 0.5, 2.5, RIGHT, DESK))    # 0.5 m off
    assert walls.measure_floating(near) == (1, 1)
    assert walls.measure_floating(off) == (0, 1)


def test_a_bed_with_its_nightstand_is_a_group_and_a_tv_stand_has_no_partner():
    s = scene(room(7.0, 6.0),
              ('double bed', 2.5, 3.0, UP, DOUBLE_BED),
              ('stand', 2.5 + 0.8 + 0.05 + 0.25, 2.0 + 0.2, UP, (0.5, 0.4, 0.55)),
              ('tv stand', 5.0, 3.0, LEFT, (1.5, 0.45, 0.5)),
              ('office chair', 4.4, 3.0, RIGHT, OFFICE_CHAIR))
    # The bed keeps the rule by its nightstand; the TV stand floats; the nightstand is small.
    assert walls.measure_floating(s) == (1, 2)


# ---- windows_clear -----------------------------------------------------------------------
def with_window(*objects, windows=None):
    """A 4 x 3 m room with a 1.2 m window, sill 0.9 m, centred on the wall y = 3."""
    return scene(room(4.0, 3.0, windows or [window(2.0, 3.0)]), *objects)


def wardrobe_down_at(x, gap):
    """A wardrobe backed onto the wall y = 3 with ``gap`` metres behind it."""
    return ('wardrobe', x, 3.0 - WARDROBE[1] / 2 - gap, DOWN, WARDROBE)


def test_a_wardrobe_in_front_of_a_window_covers_it():
    assert walls.measure_windows_clear(with_window(wardrobe_down_at(2.0, 0.02))) \
        == (0, 1)


def test_a_window_is_clear_of_low_furniture_and_of_tall_furniture_beside_or_back_from_it():
    desk = ('desk', 2.0, 3.0 - 0.35 - 0.01, DOWN, DESK)                  # top 0.75 < sill
    beside = wardrobe_down_at(2.0 + 0.6 + 0.5 + 0.05, 0.02)       # past its edge
    assert walls.measure_windows_clear(with_window(desk, beside)) == (1, 1)
    back_from_it = wardrobe_down_at(2.0, 0.25)                    # 25 cm from glass
    assert walls.measure_windows_clear(with_window(back_from_it)) == (1, 1)


def test_a_window_may_lose_a_quarter_of_its_width_counted_once():
    def lamp_at(x, y, depth=0.25):
        return ('floor lamp', x, y, DOWN, (0.25, depth, 1.6))          # 0.25 of 1.2 m wide
    one = with_window(lamp_at(1.6, 2.85))
    two_side_by_side = with_window(lamp_at(1.6, 2.85), lamp_at(2.4, 2.85))
    # Both enter the 20 cm strip (y > 2.8) over the same stretch of the wall.
    one_behind_another = with_window(lamp_at(1.6, 2.93, depth=0.12), lamp_at(1.6, 2.74))
    assert walls.measure_windows_clear(one) == (1, 1)
    assert walls.measure_windows_clear(two_side_by_side) == (0, 1)
    assert walls.measure_windows_clear(one_behind_another) == (1, 1)


def test_hidden_stretches_of_a_window_are_counted_once():
    assert walls.union_length([(0.0, 1.0), (0.2, 0.5), (0.8, 1.5), (2.0, 3.0)]) == 2.5
    assert walls.union_length([]) == 0.0


def test_windows_clear_counts_every_window_on_a_wall():
    wins = [window(2.0, 3.0), window(4.0, 1.5, 1.0), window(2.0, 1.5)]    # last: off walls
    s = with_window(wardrobe_down_at(2.0, 0.02), windows=wins)
    assert walls.measure_windows_clear(s) == (1, 2)


# ---- beds_not_across_windows --------------------------------------------------------------
def bedroom_with_window(*objects, sill=0.8):
    """A 4 x 4 m room with a 1.2 m window centred on the wall y = 4."""
    return scene(room(4.0, 4.0, [window(2.0, 4.0, sill=sill)]), *objects)


def test_a_headboard_under_a_window_is_across_it_unless_the_bed_stays_below_the_sill():
    headboard = ('double bed', 2.0, 4.0 - 1.0 - 0.01, DOWN, DOUBLE_BED)
    assert walls.measure_beds_not_across_windows(bedroom_with_window(headboard)) == (0, 1)
    assert walls.measure_beds_not_across_windows(
        bedroom_with_window(headboard, sill=1.05)) == (1, 1)


def test_a_long_side_along_a_window_is_across_it_and_the_foot_is_not():
    long_side = ('double bed', 1.0 + 0.01, 4.0 - 0.8 - 0.01, RIGHT, DOUBLE_BED)
    foot = ('double bed', 2.0, 4.0 - 1.0 - 0.01, UP, DOUBLE_BED)
    assert walls.measure_beds_not_across_windows(bedroom_with_window(long_side)) == (0, 1)
    assert walls.measure_beds_not_across_windows(bedroom_with_window(foot)) == (1, 1)


def test_a_daybed_counts_its_long_back_but_not_its_short_ends():
    back = ('daybed', 2.0, 4.0 - 0.475 - 0.01, DOWN, DAYBED)
    end_on = ('daybed', 0.475 + 1.6, 4.0 - 1.0 - 0.01, LEFT, DAYBED)   # short end to y = 4
    room_of_two = bedroom_with_window(back, ('single bed', 3.4, 1.0, UP, (0.9, 2.0, 0.6)))
    assert walls.measure_beds_not_across_windows(room_of_two) == (1, 2)
    assert walls.measure_beds_not_across_windows(bedroom_with_window(end_on)) == (1, 1)


def test_beds_in_a_windowless_room_keep_the_rule():
    s = scene(room(), ('double bed', 2.0, 1.01, UP, DOUBLE_BED))
    assert walls.measure_beds_not_across_windows(s) == (1, 1)
    assert walls.measure_beds_not_across_windows(scene(room())) == (0, 0)


def test_corner_array_is_every_footprint_s_corners_at_once():
    objs = [PlacedObject(f'o{k}', 'desk', 'desk_00', (1.0 + k, 2.0 - k, 0.0), yaw, DESK)
            for k, yaw in enumerate((0.0, 0.4, -2.0, math.pi))]
    assert np.allclose(walls.corner_array(objs), [o.corners() for o in objs])


# ---- the family -------------------------------------------------------------------------
def test_every_walls_rule_is_named_once_and_asks_one_question():
    names = [r.name for r in walls.RULES]
    assert names == ['wall_contact', 'wall_near_miss', 'no_floating_large_pieces',
                     'windows_clear', 'beds_not_across_windows']
    assert len(set(names)) == len(names)
    for r in walls.RULES:
        assert r.family == 'walls'
        assert r.question.strip() and '\n' not in r.question and r.question.endswith('.')


def test_the_large_pieces_are_the_wall_categories_a_room_is_planned_around():
    assert {'piano', 'fireplace', 'tv stand', 'desk', 'double bed', 'bathtub', 'shower',
            'wardrobe', 'sofa', 'shelving'} <= walls.LARGE_PIECES
    assert not {'stand', 'toilet', 'bidet', 'shoes cabinet'} & walls.LARGE_PIECES
    assert walls.LARGE_PIECES <= walls.WALL_FURNITURE
