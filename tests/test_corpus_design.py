"""How the corpus furnishes by the design rules: the floor a placed piece keeps clear
(``corpus.clearance``), the partners a plan is given, and the pieces a designer takes out
again (``furnish.tidy``), on hand-built rooms; and every corpus room keeping every rule."""
import math

import numpy as np
import pytest

from scene_synth_ros import rules as design_rules
from scene_synth_ros.catalog import ModelVariant
from scene_synth_ros.corpus.furnish import tidy, with_partners
from scene_synth_ros.corpus.generate import KEPT_RULES, TABLE_BOUND, generate_corpus
from scene_synth_ros.corpus.layout import Layout
from scene_synth_ros.rules import access, groups
from scene_synth_ros.scene import Opening, Room

SOUTH = -math.pi / 2     # facing -y: the back against the north wall
NORTH = math.pi / 2


def layout(width=5.0, depth=5.0, room_type='bedroom', door_x=None, windows=()) -> Layout:
    doors = (Opening('door', (door_x if door_x is not None else width / 2, 0.0), 0.8, 2.0),)
    room = Room(room_type, ((0, 0), (width, 0), (width, depth), (0, depth)), doors=doors,
                windows=tuple(windows))
    return Layout(room, np.random.default_rng(0))


def model(category: str, width: float, depth: float, height: float = 1.0) -> ModelVariant:
    return ModelVariant(f'{category.replace(" ", "_")}_test', category, (width, depth, height), 0)


def place(lay: Layout, category: str, x: float, y: float, yaw: float, width: float,
          depth: float, height: float = 1.0):
    return lay.try_place(model(category, width, depth, height), (x, y), yaw)


# ---- the floor a piece keeps clear ------------------------------------------------------
def test_nothing_is_placed_in_front_of_a_wardrobe():
    lay = layout()
    assert place(lay, 'wardrobe', 1.5, 4.7, SOUTH, 1.2, 0.6) is not None   # front at y = 4.4
    # 0.3 m before its doors: refused; 0.7 m before them: placed
    assert place(lay, 'coffee table', 1.5, 3.8, NORTH, 1.0, 0.6) is None
    assert place(lay, 'coffee table', 1.5, 3.4, NORTH, 1.0, 0.6) is not None


def test_storage_is_not_placed_where_its_front_would_be_blocked():
    lay = layout()
    assert place(lay, 'coffee table', 1.5, 3.8, NORTH, 1.0, 0.6) is not None
    assert place(lay, 'wardrobe', 1.5, 4.7, SOUTH, 1.2, 0.6) is None
    assert place(lay, 'wardrobe', 4.0, 4.7, SOUTH, 1.2, 0.6) is not None


def test_a_double_bed_needs_both_sides_free_and_keeps_its_head_for_a_nightstand():
    lay = layout()
    # in the corner its left side would be the wall: refused; centred on the wall: placed
    assert place(lay, 'double bed', 0.8, 3.95, SOUTH, 1.6, 2.1) is None
    bed = place(lay, 'double bed', 2.5, 3.95, SOUTH, 1.6, 2.1)
    assert bed is not None
    beside_head = (2.5 + 0.8 + 0.03 + 0.25, 4.75)
    assert place(lay, 'dresser', *beside_head, SOUTH, 0.5, 0.45) is None       # kept for...
    stand = place(lay, 'stand', *beside_head, SOUTH, 0.5, 0.45)
    assert stand is not None and groups.at_head_of(stand, bed)                  # ...a stand
    # along the side, past the head, nothing at all
    assert place(lay, 'stand', 3.6, 3.6, SOUTH, 0.45, 0.4) is None


def test_a_chair_may_take_the_place_kept_before_a_desk_and_a_cabinet_may_not():
    lay = layout()
    desk = place(lay, 'desk', 2.5, 4.65, SOUTH, 1.4, 0.7)
    assert desk is not None
    assert place(lay, 'shoes cabinet', 2.5, 3.95, NORTH, 0.8, 0.3) is None
    chair = place(lay, 'office chair', 2.5, 3.95, NORTH, 0.6, 0.6)
    assert chair is not None and groups.seated_at(chair, desk)


def test_tall_furniture_keeps_clear_of_windows():
    window = Opening('window', (2.5, 5.0), 1.2, 1.2, sill=0.9)
    lay = layout(windows=(window,))        # the glass spans x = 1.9 .. 3.1
    assert place(lay, 'dresser', 2.5, 4.75, SOUTH, 1.2, 0.5, height=0.8) is not None
    # a wardrobe taller than the sill 10 cm beside the glass: refused; 50 cm beside it: placed
    assert place(lay, 'wardrobe', 3.8, 4.7, SOUTH, 1.2, 0.6, height=2.0) is None
    assert place(lay, 'wardrobe', 4.2, 4.7, SOUTH, 1.2, 0.6, height=2.0) is not None


# ---- partners in the plan ---------------------------------------------------------------
def _plan(room_type, plan):
    from scene_synth_ros.categories import room_spec
    rate = {c.name: c.frequency for c in room_spec(room_type).categories}
    return with_partners(room_type, plan, rate, np.random.default_rng(0))


def test_a_double_bed_gets_a_nightstand_and_a_coffee_table_seating():
    assert _plan('bedroom', ['double bed', 'wardrobe']).count('stand') == 1
    assert _plan('bedroom', ['single bed', 'wardrobe']).count('stand') == 0
    plan = _plan('office', ['coffee table', 'desk', 'office chair'])
    assert any(c in groups.LOUNGE_SEATS for c in plan)


def test_a_bidet_without_a_toilet_and_speakers_without_a_tv_stand_are_dropped():
    assert _plan('bathroom', ['bidet', 'sink']) == ['sink']
    assert 'loudspeaker' not in _plan('living', ['sofa', 'coffee table', 'loudspeaker'])
    assert 'loudspeaker' in _plan('office', ['desk', 'loudspeaker'])
    assert _plan('bathroom', ['toilet', 'bidet']) == ['toilet', 'bidet']


# ---- what a designer takes out again ----------------------------------------------------
def test_tidy_takes_out_a_chair_at_no_table_and_what_the_robot_cannot_reach():
    lay = layout(door_x=4.0)
    # a chair in the middle of the room, at no table
    chair = place(lay, 'chair', 2.5, 2.5, 0.0, 0.5, 0.5)
    # a cabinet in the north-west corner walled in by two wardrobes: nothing reaches its front
    cabinet = place(lay, 'cabinet', 0.3, 4.7, SOUTH, 0.6, 0.6)
    lay.add(lay.make(model('wardrobe', 1.2, 0.6), (0.3, 3.4), 0.0))
    lay.add(lay.make(model('wardrobe', 1.2, 0.6), (1.3, 4.4), math.pi))
    assert chair is not None and cabinet is not None
    assert cabinet in access.unreachable(lay.scene)
    tidy(lay)
    left = {o.id for o in lay.first_tier()}
    assert chair.id not in left and cabinet.id not in left
    assert not access.unreachable(lay.scene)


def test_tidy_gives_a_double_bed_its_nightstand():
    lay = layout()
    bed = place(lay, 'double bed', 2.5, 3.95, SOUTH, 1.6, 2.1)
    tidy(lay)
    assert [groups.at_head_of(s, bed) for s in lay.first_tier('stand')] == [True]


# ---- the corpus -------------------------------------------------------------------------
@pytest.mark.parametrize('room_type', ['bedroom', 'living', 'office', 'bathroom'])
def test_corpus_rooms_keep_every_design_rule_the_table_leaves_them(room_type):
    for scene in generate_corpus(room_type, 30, seed=4, workers=1):
        assert design_rules.broken(scene, KEPT_RULES) == [], scene.meta
    assert {r.name for r in design_rules.rules()} - {r.name for r in KEPT_RULES} == set(
        TABLE_BOUND)
