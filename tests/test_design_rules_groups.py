"""The ``groups`` design rules on hand-built rooms: each rule kept and broken, exactly counted."""
import math

import numpy as np
import pytest
import shapely
from shapely.geometry import LineString

from scene_synth_ros.geometry import footprint_gap
from scene_synth_ros.rules import groups
from scene_synth_ros.scene import PlacedObject, Room, Scene

SIZES = {       # (width, depth, height), within the catalog's ranges
    'desk': (1.2, 0.6, 0.75), 'dressing table': (1.0, 0.45, 1.4), 'office chair': (0.6, 0.6, 1.0),
    'straight chair': (0.45, 0.5, 0.9), 'stool': (0.4, 0.4, 0.6), 'coffee table': (1.0, 0.6, 0.45),
    'double bed': (1.6, 2.0, 1.0), 'single bed': (1.0, 2.0, 0.8), 'stand': (0.5, 0.4, 0.6),
    'toilet': (0.4, 0.7, 0.8), 'bidet': (0.38, 0.55, 0.4), 'bathtub': (1.7, 0.75, 0.55),
    'shower': (0.9, 0.9, 2.0), 'sofa': (2.2, 0.9, 0.85), 'sofa chair': (0.8, 0.8, 0.85),
    'armchair': (0.75, 0.8, 0.9), 'tv stand': (1.5, 0.4, 0.5), 'dresser': (1.2, 0.5, 0.9),
    'television': (1.0, 0.2, 0.6), 'table lamp': (0.3, 0.3, 0.5), 'shoes cabinet': (0.8, 0.3, 1.0),
    'wardrobe': (1.2, 0.6, 2.0), 'plant': (0.2, 0.2, 0.4), 'teapot': (0.2, 0.2, 0.2),
}


def put(category, x, y, yaw_deg, support=None, name=None):
    size = SIZES[category]
    stem = category.replace(' ', '_')
    return PlacedObject(name or f'{stem}_{x:g}_{y:g}', category, f'{stem}_00', (x, y, 0.0),
                        math.radians(yaw_deg), size, support)


def room(room_type, w=4.0, d=4.0):
    return Room(room_type, ((0, 0), (w, 0), (w, d), (0, d)))


def test_every_rule_is_a_group_rule_named_once_asking_one_line():
    names = [r.name for r in groups.RULES]
    assert len(names) == len(set(names)) == 11
    for r in groups.RULES:
        assert r.family == 'groups'
        assert r.question.strip() and '\n' not in r.question, r.name
        assert r.measure(Scene(room('bedroom'))) == (0, 0), r.name


def office() -> Scene:
    """Desk A (back on the top wall) with a chair at it; desk B (right wall) whose chair has
    its back to it; a straight chair at the end of a coffee table, facing it."""
    return Scene(room('office'), [
        put('desk', 1.0, 3.7, -90, name='desk_a'),
        put('office chair', 1.2, 3.0, 90, name='chair_a'),           # 0.1 m off, facing it
        put('desk', 3.7, 1.0, 180, name='desk_b'),
        put('office chair', 3.0, 1.0, 180, name='chair_b'),          # in front, back to it
        put('coffee table', 1.2, 1.8, 0, name='table'),
        put('straight chair', 1.2, 0.85, 90, name='chair_c'),        # 0.2 m off its side
    ])


def test_desk_has_seat_counts_desks_with_a_seat_in_front_facing_them():
    scene = office()
    assert groups.desk_has_seat(scene) == (1, 2)
    scene.get('chair_b').yaw = 0.0                                    # turned to desk B
    assert groups.desk_has_seat(scene) == (2, 2)
    scene.get('chair_b').position = (3.0, 2.2, 0.0)                   # beyond B's width
    assert groups.desk_has_seat(scene) == (1, 2)
    scene.get('chair_b').position = (2.2, 1.0, 0.0)                   # 0.9 m from B's front
    assert groups.desk_has_seat(scene) == (1, 2)
    scene.objects.append(put('stool', 0.3, 0.3, 90))                   # nothing to sit at
    scene.objects.append(put('dressing table', 3.7, 3.0, 180))
    scene.objects.append(put('stool', 3.2, 3.0, 0))                    # at the vanity
    assert groups.desk_has_seat(scene) == (2, 3)


def test_chair_at_table_counts_chairs_at_a_desk_front_or_any_side_of_a_coffee_table():
    scene = office()
    assert groups.chair_at_table(scene) == (2, 3)
    scene.get('chair_c').yaw = math.radians(-90)                       # back to the table
    assert groups.chair_at_table(scene) == (1, 3)
    scene.get('chair_c').yaw = math.radians(90)
    scene.get('chair_c').position = (1.2, 0.3, 0.0)                    # 0.75 m off it
    assert groups.chair_at_table(scene) == (1, 3)
    scene.objects.append(put('stool', 2.0, 2.8, -90))                  # a stool is no case
    assert groups.chair_at_table(scene) == (1, 3)


def bedroom() -> Scene:
    """A double bed, headboard on the top wall, spanning x 1.2-2.8 and y 2.0-4.0."""
    return Scene(room('bedroom'), [put('double bed', 2.0, 3.0, -90, name='bed')])


def test_nightstand_by_bed_counts_stands_at_the_head_end_of_a_bed():
    scene = bedroom()
    scene.objects += [put('stand', 0.9, 3.8, -90, name='left'),         # 5 cm off, at the head
                      put('stand', 3.3, 3.8, -90, name='right'),        # 25 cm off
                      put('stand', 0.9, 2.2, -90, name='foot'),         # beside the foot
                      put('stand', 2.0, 1.5, -90, name='front')]        # before the foot
    assert groups.nightstand_by_bed(scene) == (2, 4)
    assert groups.double_bed_has_nightstand(scene) == (1, 1)
    scene.get('right').position = (3.4, 3.8, 0.0)                       # 35 cm off
    assert groups.nightstand_by_bed(scene) == (1, 4)
    living = Scene(room('living'), scene.objects)                       # a side cabinet there
    assert groups.nightstand_by_bed(living) == (0, 0)


def test_double_bed_has_nightstand_counts_double_beds_with_a_stand_at_their_head():
    scene = bedroom()
    scene.objects += [put('stand', 0.9, 2.2, -90), put('single bed', 3.0, 0.5, 180)]
    assert groups.double_bed_has_nightstand(scene) == (0, 1)
    scene.objects.append(put('stand', 3.05, 3.8, -90))                  # at its head
    assert groups.double_bed_has_nightstand(scene) == (1, 1)


def test_bidet_by_toilet_counts_bidets_beside_a_toilet_on_its_wall_line():
    scene = Scene(room('bathroom', 3.0, 3.0), [
        put('toilet', 1.0, 0.35, 90),                                  # back on the bottom wall
        put('bidet', 1.59, 0.275, 90, name='beside'),                  # 0.2 m off, same line
        put('bidet', 0.275, 1.0, 0, name='round_the_corner'),          # 0.27 m off, other wall
        put('bidet', 2.6, 0.275, 90, name='far')])                     # same wall, 1.2 m off
    assert groups.bidet_by_toilet(scene) == (1, 3)
    scene.get('beside').position = (1.59, 0.5, 0.0)                     # pulled 22 cm forward
    assert groups.bidet_by_toilet(scene) == (0, 3)


def test_bath_in_corner_counts_baths_and_showers_touching_two_walls():
    scene = Scene(room('bathroom', 3.0, 3.0), [
        put('bathtub', 0.86, 0.385, 90),                               # in the bottom-left corner
        put('shower', 1.5, 2.54, -90),                                 # mid-wall
        put('shower', 2.54, 0.5, 180)])                                # 5 cm off the bottom
    assert groups.bath_in_corner(scene) == (2, 3)
    # An L-shaped room: a shower by the inner (reflex) corner only grazes the end of a wall.
    ell = Room('bathroom', ((0, 0), (4, 0), (4, 2), (2, 2), (2, 4), (0, 4)))
    assert groups.bath_in_corner(Scene(ell, [put('shower', 2.5, 1.5, -90)])) == (0, 1)
    assert groups.bath_in_corner(Scene(ell, [put('shower', 3.5, 1.5, -90)])) == (1, 1)


def living() -> Scene:
    """A sofa on the bottom wall facing up with a coffee table before it, a TV stand with a
    TV across the room, and a second sofa on the left wall facing right."""
    return Scene(room('living', 5.0, 5.0), [
        put('sofa', 2.5, 0.45, 90, name='sofa_a'),
        put('coffee table', 2.5, 1.5, 90, name='table'),
        put('sofa', 0.45, 3.5, 0, name='sofa_b'),
        put('tv stand', 2.5, 4.8, -90, name='stand'),
        put('television', 2.5, 4.8, -90, support='stand', name='tv')])


def test_sofa_faces_table_or_tv_counts_sofas_with_one_ahead():
    scene = living()
    assert groups.sofa_faces_table_or_tv(scene) == (1, 2)       # sofa_b: table 44, TV 32 deg off
    scene.get('sofa_b').position = (0.45, 3.9, 0.0)              # TV 24 deg off its axis
    assert groups.sofa_faces_table_or_tv(scene) == (2, 2)
    far = Scene(room('living', 8.0, 8.0), [put('sofa', 4.0, 0.45, 90),
                                           put('tv stand', 4.0, 7.8, -90)])
    assert groups.sofa_faces_table_or_tv(far) == (0, 1)           # 7.35 m away


def test_coffee_table_has_seating_counts_tables_with_lounge_seats_facing_them():
    scene = living()
    scene.objects.append(put('coffee table', 4.4, 4.0, 0, name='lonely'))
    assert groups.coffee_table_has_seating(scene) == (1, 2)
    scene.objects.append(put('armchair', 4.5, 2.85, 90))           # below it, facing it
    assert groups.coffee_table_has_seating(scene) == (2, 2)
    scene.objects[-1].yaw = math.radians(-90)                       # back to it
    assert groups.coffee_table_has_seating(scene) == (1, 2)
    scene.get('sofa_a').position = (2.5, 0.45 - 1.1, 0.0)           # 1.4 m back (off the floor)
    assert groups.coffee_table_has_seating(scene) == (0, 2)


def test_tv_square_on_stand_counts_tvs_turned_with_their_parent():
    scene = living()
    scene.get('tv').yaw = math.radians(-90 + 8)
    scene.objects += [put('dresser', 4.75, 2.5, 180, name='dresser'),
                      put('television', 4.75, 2.5, 180 + 30, support='dresser'),
                      put('desk', 0.3, 1.0, 0, name='desk'),
                      put('television', 0.3, 1.0, 0, support='desk')]       # not a case
    assert groups.tv_square_on_stand(scene) == (1, 2)
    scene.objects[-3].yaw = math.radians(-180 + 4)                          # -176 vs 180
    assert groups.tv_square_on_stand(scene) == (2, 2)


def test_chairs_square_counts_seats_turned_less_than_15_degrees_off_the_room():
    scene = Scene(room('living', 5.0, 5.0), [
        put('office chair', 1.0, 1.0, 10), put('straight chair', 2.0, 1.0, 94),
        put('armchair', 3.0, 3.0, 30), put('sofa chair', 1.0, 3.5, -60),
        put('wardrobe', 4.0, 1.0, 30)])                                   # not a seat
    assert groups.chairs_square(scene) == (2, 4)
    # The room's axes turn with it: the same room turned by 20 degrees keeps the same count.
    assert groups.chairs_square(scene.moved(math.radians(20), (3.0, -1.0))) == (2, 4)


def test_plausible_support_counts_children_on_parents_a_designer_expects():
    scene = Scene(room('bedroom'), [
        put('desk', 1.0, 0.3, 90, name='desk'), put('stand', 3.0, 0.2, 90, name='stand'),
        put('shoes cabinet', 3.8, 2.0, 180, name='shoes'),
        put('television', 1.0, 0.3, 90, support='desk'),
        put('table lamp', 3.0, 0.2, 90, support='stand'),
        put('table lamp', 3.8, 2.0, 180, support='shoes'),
        put('plant', 0.8, 0.3, 0, support='desk'),
        put('teapot', 1.3, 0.3, 0, support='desk')])          # a category the table lacks
    assert groups.plausible_support(scene) == (2, 4)


@pytest.mark.parametrize('yaw', [0.7, -2.0])
def test_every_rule_counts_the_same_in_a_moved_room(yaw):
    scenes = [office(), living()]
    scene = bedroom()
    scene.objects += [put('stand', 0.9, 3.8, -90), put('stand', 0.9, 2.2, -90)]
    scenes.append(scene)
    scenes.append(Scene(room('bathroom', 3.0, 3.0), [
        put('bathtub', 0.86, 0.385, 90), put('shower', 1.5, 2.54, -90),
        put('toilet', 2.65, 1.5, 180), put('bidet', 2.725, 0.91, 180)]))
    cases = dict.fromkeys((r.name for r in groups.RULES), 0)
    for s in scenes:
        moved = s.moved(yaw, (1.5, -2.5))
        for r in groups.RULES:
            assert r.measure(moved) == r.measure(s), r.name
            cases[r.name] += r.measure(s)[1]
    assert all(cases.values()), cases            # every rule was asked somewhere


def test_footprint_gap_is_shapelys_distance_between_the_rectangles():
    rng = np.random.default_rng(3)
    for _ in range(300):
        a, b = (PlacedObject(name, 'desk', 'desk_00', (*rng.uniform(0, 3, 2), 0.0),
                             float(rng.uniform(-math.pi, math.pi)),
                             (*rng.uniform(0.1, 2.0, 2), 1.0)) for name in 'ab')
        assert footprint_gap(a, b) == pytest.approx(
            a.footprint().distance(b.footprint()), abs=1e-9)


def test_run_within_is_the_segment_inside_the_mitre_grown_footprint():
    rng = np.random.default_rng(4)
    for _ in range(300):
        obj = PlacedObject('a', 'bathtub', 'bathtub_00', (*rng.uniform(0, 3, 2), 0.0),
                           float(rng.uniform(-math.pi, math.pi)), (*rng.uniform(0.3, 2, 2), 1.0))
        start, end = (tuple(rng.uniform(-0.5, 3.5, 2)) for _ in range(2))
        grown = obj.footprint().buffer(0.1, join_style='mitre')
        expected = grown.intersection(LineString([start, end])).length
        assert groups.run_within(obj, start, end, 0.1) == pytest.approx(expected, abs=1e-9)
    # a segment along a side, in line with an edge: counted in full
    obj = PlacedObject('a', 'shower', 'shower_00', (0.5, 0.5, 0.0), 0.0, (1.0, 1.0, 2.0))
    assert groups.run_within(obj, (-1.0, -0.1), (3.0, -0.1), 0.1) == pytest.approx(1.2)


@pytest.mark.parametrize('room_type', ['bedroom', 'living', 'office', 'bathroom'])
def test_partner_zone_holds_every_piece_that_keeps_its_group_rule(room_type):
    """Synthesis draws a group piece's location only inside ``partner_zone``: in corpus rooms,
    every piece that keeps its rule has its centre in the zone computed from the rest of the
    room, and the zone is a part of the room, not all of it."""
    from scene_synth_ros.corpus.generate import generate_room
    verdicts = {'chair_at_table': groups.chair_verdicts,
                'nightstand_by_bed': groups.nightstand_verdicts,
                'bidet_by_toilet': groups.bidet_verdicts,
                'coffee_table_has_seating': groups.coffee_table_verdicts}
    inside = cases = 0
    area = []
    for i in range(80):
        scene = generate_room(room_type, 7, i)
        for rule, verdict in verdicts.items():
            for oid, ok in verdict(scene).items():
                piece = scene.get(oid)
                rest = Scene(scene.room, [o for o in scene.objects if o.id != oid])
                zone = groups.partner_zone(rest, rule, piece.category)
                assert zone is not None, (rule, piece.category)
                if ok:
                    cases += 1
                    inside += zone.covers(shapely.Point(piece.position[:2]))
                    area.append(zone.area / scene.room.area)
    assert cases >= 20 and inside == cases
    assert np.median(area) < 0.5
    # A category no group rule asks about, or a stand outside a bedroom, has no zone.
    empty = Scene(room(room_type))
    assert groups.partner_zone(empty, 'chair_at_table', 'wardrobe') is None
    assert (groups.partner_zone(empty, 'nightstand_by_bed', 'stand') is None) == (
        room_type != 'bedroom')


def test_a_coffee_table_may_wait_for_its_seats_which_then_go_by_it():
    r = room('bedroom', 5.0, 5.0)
    table = put('coffee table', 2.5, 2.5, 0)
    rule = 'coffee_table_has_seating'
    assert groups.partner_zone(Scene(r), rule, 'coffee table') is None
    assert groups.partner_zone(Scene(r), rule, 'armchair') is None
    ring = groups.partner_zone(Scene(r, [table]), rule, 'armchair')
    assert ring.covers(shapely.Point(2.5, 1.4)) and not ring.covers(shapely.Point(0.5, 0.5))
    # Once a seat serves the table, the next seat goes anywhere again.
    seat = put('armchair', 2.5, 1.4, 90)
    assert groups.coffee_table_verdicts(Scene(r, [table, seat])) == {table.id: True}
    assert groups.partner_zone(Scene(r, [table, seat]), rule, 'sofa chair') is None
    assert groups.seating_verdicts(Scene(r, [table])) == {}


def test_owed_counts_broken_cases_of_the_owed_rules_and_their_partners():
    rules = tuple(groups.OWED_PARTNERS)
    scene = living()
    assert groups.owed(scene, rules) == (0, frozenset())               # sofa_a serves it
    scene.objects.append(put('coffee table', 4.4, 4.0, 0, name='lonely'))
    assert groups.owed(scene, rules) == (1, frozenset(groups.LOUNGE_SEATS))
    beds = bedroom()
    beds.objects.append(put('single bed', 3.0, 0.5, 180))              # owes nothing
    assert groups.owed(beds, rules) == (1, frozenset({'stand'}))
    assert groups.owed(beds, ('coffee_table_has_seating',)) == (0, frozenset())
    beds.objects += [put('stand', 0.9, 3.8, -90), put('coffee table', 2.0, 1.0, 0)]
    assert groups.owed(beds, rules) == (1, frozenset(groups.LOUNGE_SEATS))


def test_withdrawable_coffee_tables_are_those_without_seating_or_a_chair_at_them():
    rules = tuple(groups.OWED_PARTNERS)
    scene = living()
    assert groups.withdrawable(scene, rules) == []                    # sofa_a serves it
    scene.objects.append(put('coffee table', 4.4, 4.0, 0, name='lonely'))
    assert groups.withdrawable(scene, rules) == ['lonely']
    assert groups.withdrawable(scene, ('double_bed_has_nightstand',)) == []
    scene.objects.append(put('straight chair', 4.4, 3.0, 90))        # seated at its side
    assert groups.withdrawable(scene, rules) == []
    beds = bedroom()                                                  # a bed owed a stand
    assert groups.owed(beds, rules)[0] == 1 and groups.withdrawable(beds, rules) == []
