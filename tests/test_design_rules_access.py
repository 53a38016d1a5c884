"""The access rules on hand-built rooms: each rule kept where a designer would say yes and
broken where they would not, with exact (kept, cases) counts."""
import math

import pytest

from scene_synth_ros.rules import access
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene

YAW = {'N': math.pi / 2, 'S': -math.pi / 2, 'E': 0.0, 'W': math.pi}


def box(category: str, x0: float, y0: float, x1: float, y1: float, facing: str,
        name: str | None = None) -> PlacedObject:
    """A first-tier object filling the axis-aligned rectangle, its front facing a compass
    direction (north is +y)."""
    across, deep = (x1 - x0, y1 - y0) if facing in 'NS' else (y1 - y0, x1 - x0)
    stem = category.replace(' ', '_')
    return PlacedObject(name or f'{stem}_0', category, f'{stem}_00',
                        ((x0 + x1) / 2, (y0 + y1) / 2, 0.0), YAW[facing], (across, deep, 1.0))


def room(width: float = 4.0, depth: float = 4.0, door: bool = True,
         room_type: str = 'bedroom') -> Room:
    doors = (Opening('door', (width / 2, 0.0), 0.8, 2.0),) if door else ()
    return Room(room_type, ((0, 0), (width, 0), (width, depth), (0, depth)), doors=doors)


def scene(*objects: PlacedObject, **kwargs) -> Scene:
    return Scene(room(**kwargs), list(objects))


def wardrobe(name: str = 'wardrobe_0') -> PlacedObject:
    """Back on the north wall of a 4 m room, front 3.4 m north, 0.4 to 1.6 m east."""
    return box('wardrobe', 0.4, 3.4, 1.6, 4.0, 'S', name)


# ---- storage_clearance ---------------------------------------------------------------
def test_storage_with_its_front_clear_keeps_the_rule():
    dresser = box('dresser', 1.6, 3.5, 2.6, 4.0, 'S')      # touches the wardrobe's side
    assert access.storage_clearance(scene(wardrobe(), dresser)) == (2, 2)


def test_a_coffee_table_before_wardrobe_doors_breaks_it():
    table = box('coffee table', 0.5, 2.7, 1.5, 3.3, 'N')    # 10 cm from the doors
    assert access.storage_clearance(scene(wardrobe(), table)) == (0, 1)


@pytest.mark.parametrize('table_top, kept', [(2.85, 1), (2.915, 1), (2.95, 0)])
def test_storage_clearance_is_half_a_metre_with_a_small_tolerance(table_top, kept):
    # 0.55 m clear; 1.5 cm into the strip (within the 2 cm tolerance); 5 cm into it
    table = box('coffee table', 0.5, 2.3, 1.5, table_top, 'N')
    assert access.storage_clearance(scene(wardrobe(), table)) == (kept, 1)


def test_storage_blocked_at_one_end_only_breaks_it():
    # a nightstand against the side wall covers 0.3 m of the wardrobe's 1.2 m front
    stand = box('stand', 0.0, 2.9, 0.7, 3.35, 'E')
    assert access.storage_clearance(scene(wardrobe(), stand)) == (0, 1)


def test_storage_facing_a_wall_closer_than_half_a_metre_breaks_it():
    facing_wall = box('shelving', 0.4, 1.5, 0.75, 2.7, 'W')    # 0.4 m from the west wall
    assert access.storage_clearance(scene(facing_wall)) == (0, 1)


def test_a_stool_blocks_a_wardrobe_but_not_a_dressing_table():
    table = box('dressing table', 2.6, 3.55, 3.6, 4.0, 'S')
    stool = box('stool', 2.9, 3.1, 3.3, 3.5, 'N')
    assert access.storage_clearance(scene(table, stool)) == (1, 1)
    moved = box('stool', 0.8, 3.0, 1.2, 3.35, 'N')
    assert access.storage_clearance(scene(wardrobe(), moved)) == (0, 1)


def test_only_storage_is_a_case_of_storage_clearance():
    desk = box('desk', 0.4, 3.4, 1.6, 4.0, 'S')
    chair = box('office chair', 0.7, 2.9, 1.3, 3.35, 'N')
    assert access.storage_clearance(scene(desk, chair)) == (0, 0)
    assert access.storage_clearance(scene()) == (0, 0)


# ---- fixture_clearance ---------------------------------------------------------------
def bathroom(*objects: PlacedObject) -> Scene:
    return scene(*objects, width=3.0, depth=3.0, room_type='bathroom')


@pytest.mark.parametrize('sink_top, kept', [(1.7, 2), (1.75, 1)])
def test_a_toilet_needs_six_tenths_and_a_sink_half_a_metre(sink_top, kept):
    toilet = box('toilet', 1.3, 2.3, 1.7, 3.0, 'S')            # front at y = 2.3
    sink = box('sink', 1.0, sink_top - 0.5, 2.0, sink_top, 'N')
    # 0.6 m between them: both clear; 0.55 m: the sink's 0.5 m is, the toilet's 0.6 m not
    assert access.fixture_clearance(bathroom(toilet, sink)) == (kept, 2)


@pytest.mark.parametrize('cabinet_y0, kept', [(2.75, 1), (2.5, 0)])
def test_a_shower_entry_needs_six_tenths_of_its_front_clear(cabinet_y0, kept):
    shower = box('shower', 2.1, 2.1, 3.0, 3.0, 'W')              # corner, front at x = 2.1
    cabinet = box('cabinet', 1.6, cabinet_y0, 2.0, 3.0, 'S')     # leaves 0.65 m or 0.4 m
    assert access.fixture_clearance(bathroom(shower, cabinet)) == (kept, 1)


@pytest.mark.parametrize('x0, x1, kept', [(2.3, 2.9, 1), (1.45, 2.85, 0)])
def test_a_bath_is_entered_along_part_of_its_long_side(x0, x1, kept):
    bath = box('bathtub', 1.2, 0.0, 2.9, 0.75, 'N')              # front along y = 0.75
    table = box('coffee table', x0, 0.9, x1, 1.4, 'S')
    # 1.1 m of the side clear, or only 0.25 m at one end and 0.05 m at the other
    assert access.fixture_clearance(bathroom(bath, table)) == (kept, 1)


# ---- bed_access ----------------------------------------------------------------------
def stands() -> list[PlacedObject]:
    return [box('stand', 0.7, 3.55, 1.15, 4.0, 'S', 'stand_0'),
            box('stand', 2.85, 3.55, 3.3, 4.0, 'S', 'stand_1')]


def double_bed() -> PlacedObject:
    return box('double bed', 1.2, 1.9, 2.8, 4.0, 'S')           # head on the north wall


def test_a_double_bed_with_both_sides_free_keeps_bed_access():
    assert access.bed_access(scene(double_bed(), *stands())) == (1, 1)


def test_a_double_bed_in_a_corner_breaks_it():
    in_corner = box('double bed', 0.0, 1.9, 1.6, 4.0, 'S')
    assert access.bed_access(scene(in_corner)) == (0, 1)


def test_a_dressing_table_15_cm_from_a_double_bed_breaks_it():
    table = box('dressing table', 2.95, 2.0, 3.45, 3.2, 'W')
    # with the nightstand, only 0.35 m of that side is left, and 0.1 m
    assert access.bed_access(scene(double_bed(), table, *stands())) == (0, 1)


def test_a_single_bed_needs_its_foot_or_one_side():
    alcove = box('single bed', 0.0, 1.9, 1.0, 4.0, 'S')           # sides: a wall, 0.3 m
    assert access.bed_access(scene(alcove, width=1.3)) == (1, 1)
    bench = box('bench chair', 0.05, 1.5, 0.95, 1.85, 'N')        # at the foot
    assert access.bed_access(scene(alcove, bench, width=1.3)) == (0, 1)
    assert access.bed_access(scene(alcove, bench, width=1.5)) == (1, 1)


# ---- front_not_to_wall ---------------------------------------------------------------
@pytest.mark.parametrize('front_x, kept', [(0.2, 0), (0.35, 1)])
def test_a_seat_facing_a_wall_closer_than_30_cm_breaks_the_rule(front_x, kept):
    armchair = box('armchair', front_x, 1.0, front_x + 0.8, 1.8, 'W')
    assert access.front_not_to_wall(scene(armchair)) == (kept, 1)


def test_fronts_facing_the_room_or_furniture_keep_it_and_lamps_are_no_case():
    desk = box('desk', 0.0, 2.5, 0.6, 3.7, 'E')
    chair = box('office chair', 0.7, 2.8, 1.3, 3.4, 'W')         # faces the desk, 0.7 m
    lamp = box('floor lamp', 3.5, 0.1, 3.9, 0.5, 'S')            # faces a wall at 0.1 m
    assert access.front_not_to_wall(scene(wardrobe(), desk, chair, lamp)) == (3, 3)


# ---- front_reachable, room_fully_reachable -----------------------------------------------
def both(s: Scene) -> tuple:
    return access.front_reachable(s), access.room_fully_reachable(s)


def test_furniture_open_to_the_room_is_reachable():
    table = box('coffee table', 2.4, 1.8, 3.2, 2.4, 'N')
    assert both(scene(wardrobe(), table)) == ((2, 2), (1, 1))


def test_a_wardrobe_sealed_behind_a_bed_is_not_reachable():
    bed = box('double bed', 0.0, 1.5, 2.1, 3.1, 'E')             # 0.3 m below the wardrobe
    s = scene(wardrobe(), bed)
    assert both(s) == ((1, 2), (0, 1))
    assert [o.id for o in access.unreachable(s)] == ['wardrobe_0']
    # the same room asked again after the bed moved: nothing is remembered that is stale
    s.objects[1] = box('double bed', 0.0, 1.0, 2.1, 2.6, 'E')
    assert both(s) == ((2, 2), (1, 1))


def test_a_front_corner_reached_from_the_side_is_not_reached():
    # the robot fits beside the 0.3 m gap, 0.25 m from the wardrobe's corner, not before it
    shifted = box('wardrobe', 0.6, 3.4, 1.8, 4.0, 'S')
    bed = box('double bed', 0.6, 1.5, 2.7, 3.1, 'E')
    assert both(scene(shifted, bed)) == ((1, 2), (0, 1))
    # the bed 0.3 m further east: the robot stands before the first 0.1 m of the front
    bed = box('double bed', 0.9, 1.5, 3.0, 3.1, 'E')
    assert both(scene(shifted, bed)) == ((2, 2), (1, 1))


def test_what_is_beyond_a_row_of_furniture_is_not_reachable():
    shelving = box('shelving', 0.0, 1.5, 4.0, 1.9, 'S')          # across the whole room
    table = box('coffee table', 1.5, 2.5, 2.5, 3.0, 'N')
    assert both(scene(shelving, table)) == ((1, 2), (0, 1))


def test_rooms_without_doors_are_no_case():
    assert both(scene(wardrobe(), door=False)) == ((0, 0), (0, 0))
    assert both(scene()) == ((0, 0), (1, 1))


# ---- the family --------------------------------------------------------------------------
def test_every_rule_has_a_unique_name_and_a_one_line_question():
    names = [r.name for r in access.RULES]
    assert len(set(names)) == len(names) == 6
    for r in access.RULES:
        assert r.family == 'access'
        assert r.question.strip() and '\n' not in r.question
        assert r.question.endswith('?')
        assert r.measure(scene()) in ((0, 0), (1, 1))
