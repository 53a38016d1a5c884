"""House layouts (msg_schemas/house_layout.schema.json, schema.parse_house_layout) and the
procedural house plans (corpus/house_plan.py)."""
import copy
import json
import re

import pytest

from scene_synth_ros.corpus.house_plan import PlanConfig, house_plan
from scene_synth_ros.house import House
from scene_synth_ros.schema import SceneValidationError, parse_house_layout

# A hallway with a bedroom above it and a kitchen below, a door to each, an entrance.
HOUSE = {
    'wall_height': 2.6,
    'rooms': [
        {'id': 'hall', 'room_type': 'hallway', 'floor': [[0, 0], [6, 0], [6, 1.4], [0, 1.4]]},
        {'id': 'bed', 'room_type': 'bedroom', 'floor': [[0, 1.4], [4, 1.4], [4, 5], [0, 5]],
         'windows': [{'position': [2, 5], 'width': 1.2, 'height': 1.2, 'sill': 0.9}]},
        {'id': 'kitchen', 'room_type': 'kitchen',
         'floor': [[0, -3.5], [4, -3.5], [4, 0], [0, 0]], 'wall_height': 2.8},
    ],
    'doors': [
        {'rooms': ['hall'], 'position': [0, 0.7], 'width': 0.9, 'height': 2.05},
        {'rooms': ['hall', 'bed'], 'position': [2, 1.4], 'width': 0.8, 'height': 2.05},
        {'rooms': ['kitchen', 'hall'], 'position': [3, 0], 'width': 0.8, 'height': 2.05},
    ],
}


def one_sentence(err: SceneValidationError, path: str) -> str:
    msg = str(err)
    assert err.path == path, (err.path, msg)
    assert '\n' not in msg and not re.search(r'[.!?]\s+[A-Z]', msg), msg
    assert 10 < len(msg) < 600, msg
    return msg


def test_a_house_layout_becomes_rooms_with_their_doors_and_round_trips():
    house = parse_house_layout(HOUSE)
    assert isinstance(house, House) and list(house.rooms) == ['hall', 'bed', 'kitchen']
    assert [len(r.doors) for r in house.rooms.values()] == [3, 1, 1]
    assert house.rooms['kitchen'].wall_height == 2.8 and house.rooms['bed'].wall_height == 2.6
    assert [d.rooms for d in house.entrances] == [('hall',)]
    assert house.reachable() == ['hall', 'bed', 'kitchen']
    assert parse_house_layout(house.to_dict()).to_dict() == house.to_dict()
    assert parse_house_layout(json.dumps(HOUSE)).to_dict() == house.to_dict()


def _broken(change) -> dict:
    d = copy.deepcopy(HOUSE)
    change(d)
    return d


@pytest.mark.parametrize('change,path,words', [
    (lambda d: d['rooms'][2].update(id='bed'), 'rooms[2].id', 'unique'),
    (lambda d: d['rooms'][2].update(floor=[[0, -3.5], [4, -3.5], [4, 0.5], [0, 0.5]]),
     'rooms[2].floor', 'overlaps rooms[0]'),
    (lambda d: d['doors'][1]['rooms'].__setitem__(1, 'garage'), 'doors[1].rooms[1]',
     'not the id of a room'),
    (lambda d: d['doors'][1].update(position=[5, 1.4]), 'doors[1]',
     "on a wall of rooms[0] ('hall') that rooms[1] ('bed') does not share"),
    (lambda d: d['doors'][2].update(rooms=['kitchen', 'bed']), 'doors[2]',
     "does not share"),
    (lambda d: d['doors'][1].update(position=[2, 7]), 'doors[1]', "not on a wall of rooms[0]"),
    (lambda d: d['doors'][0].update(rooms=['hall'], position=[2, 1.4]), 'doors[0]',
     'shares with'),
    (lambda d: d['doors'][1].update(rooms=['hall', 'hall']), 'doors[1]', 'twice'),
    # an entrance whose width runs past the end of the kitchen's wall, half into it
    (lambda d: d['doors'].append({'rooms': ['hall'], 'position': [4.2, 0], 'width': 0.9,
                                  'height': 2.05}), 'doors[3]', "shares with rooms[2]"),
    (lambda d: d['rooms'][1]['windows'].append({'position': [3.2, 1.4], 'width': 0.8,
                                                'height': 1.0, 'sill': 1.0}),
     'rooms[1].windows[1]', 'windows go on outside walls'),
    # a 0.4 m strip of a room between the hallway and the kitchen, 0.4 m further down
    (lambda d: (d['rooms'][2].update(floor=[[0, -3.9], [4, -3.9], [4, -0.4], [0, -0.4]]),
                d['rooms'].append({'id': 'strip', 'room_type': 'hallway',
                                   'floor': [[0, -0.4], [6, -0.4], [6, 0], [0, 0]]}),
                d['doors'].append({'rooms': ['strip'], 'position': [6, -0.2], 'width': 0.35,
                                   'height': 2.0})),
     'doors[2]', "also opens into rooms[3] ('strip')"),
    (lambda d: d['doors'].pop(0), 'doors', 'no entrance'),
    (lambda d: d['doors'].pop(2), 'rooms[2]', 'cannot be reached'),
    (lambda d: d['doors'].append(dict(d['doors'][2], position=[3.5, 0])), 'doors[3]',
     'overlaps doors[2] on the same wall'),
    (lambda d: d['doors'][1].update(height=2.7), 'doors[1]', 'above the 2.6 m wall height'),
    (lambda d: d['rooms'][1].update(room_type='garage'), 'rooms[1].room_type',
     'not a known room type'),
    (lambda d: d['rooms'].append(dict(d['rooms'][1], id='x', floor=[[0, 9], [20, 9], [20, 12],
                                                                     [0, 12]])),
     'rooms[3].floor', 'longer than the 16 m'),
    (lambda d: d.update(rooms=[]), 'rooms', 'at least 1'),
    (lambda d: d.update(doors=[d['doors'][0]] * 257), 'doors', 'at most 256'),
])
def test_a_bad_house_layout_is_refused_in_one_sentence_naming_the_field(change, path, words):
    with pytest.raises(SceneValidationError) as e:
        parse_house_layout(_broken(change))
    assert words in one_sentence(e.value, path)


def test_house_plans_are_valid_varied_and_the_same_for_the_same_seed():
    sizes, types = [], set()
    for i in range(60):
        house = house_plan(seed=0, index=i)
        again = parse_house_layout(house.to_dict())          # a valid house layout
        assert again.to_dict() == house.to_dict()
        assert len(house.entrances) == 1
        assert house.reachable() == list(house.rooms) or \
            set(house.reachable()) == set(house.rooms)
        hall = [r for r in house.rooms.values() if r.room_type == 'hallway']
        assert len(hall) == 1 and len(hall[0].doors) == len(house.rooms)
        # every room but the hallway opens onto it
        assert all(any(rid in d.rooms and 'hallway_1' in d.rooms for d in house.doors)
                   for rid in house.rooms if rid != 'hallway_1')
        sizes.append(len(house.rooms))
        types |= {r.room_type for r in house.rooms.values()}
    assert min(sizes) == 5 and max(sizes) >= 8
    assert types == {'hallway', 'living', 'kitchen', 'bedroom', 'bathroom', 'dining', 'office'}
    assert house_plan(3, 7).to_dict() == house_plan(3, 7).to_dict()
    assert house_plan(3, 7).to_dict() != house_plan(4, 7).to_dict()


def test_a_plan_of_given_rooms_has_those_rooms_and_day_rooms_open_onto_each_other():
    house = house_plan(1, 0, PlanConfig(rooms=('living', 'kitchen', 'dining', 'bedroom')))
    assert sorted(r.room_type for r in house.rooms.values()) == \
        ['bedroom', 'dining', 'hallway', 'kitchen', 'living']
    joined = {frozenset(d.rooms) for d in house.doors if 'hallway_1' not in d.rooms}
    assert frozenset(('living_1', 'kitchen_1')) in joined
    assert frozenset(('kitchen_1', 'dining_1')) in joined


def test_the_command_writes_house_plans_and_refuses_an_unknown_room_type(cli, tmp_path):
    r = cli('house-plans', '-n', '3', '--seed', '5', '--out', str(tmp_path))
    assert r.stdout.count('house_0') == 3, r
    for i in range(3):
        text = (tmp_path / f'house_{i:05d}.json').read_text()
        assert parse_house_layout(text).to_dict() == house_plan(5, i).to_dict()
    r = cli('house-plans', '-n', '1', '--rooms', 'living,garage', '--out', str(tmp_path),
            ok=False)
    assert r.returncode == 2 and "'garage'" in r.stderr and r.stderr.count('\n') == 1, r


def test_rooms_whose_walls_stand_back_to_back_a_wall_apart_share_the_door_between_them():
    """Real walls have a thickness: the bedroom's floor ends 0.2 m above the hallway's, and
    the door given on the hallway's wall is the bedroom's door on its own wall."""
    d = copy.deepcopy(HOUSE)
    d['rooms'][1]['floor'] = [[0, 1.6], [4, 1.6], [4, 5], [0, 5]]
    house = parse_house_layout(d)
    door = house.doors[1]
    assert door.openings['hall'].position == (2.0, 1.4)
    assert door.openings['bed'].position == pytest.approx((2.0, 1.6))
    assert house.rooms['bed'].doors[0].position == pytest.approx((2.0, 1.6))
    assert parse_house_layout(house.to_dict()).to_dict() == house.to_dict()
    d['rooms'][1]['floor'] = [[0, 2.0], [4, 2.0], [4, 5], [0, 5]]       # 0.6 m: no wall
    with pytest.raises(SceneValidationError) as e:
        parse_house_layout(d)
    assert "rooms[1] ('bed') does not share" in one_sentence(e.value, 'doors[1]')
    # an entrance on a wall with a room behind it, a wall's thickness away, leads into it
    d = copy.deepcopy(HOUSE)
    d['rooms'][1]['floor'] = [[0, 1.6], [4, 1.6], [4, 5], [0, 5]]
    d['doors'][1]['rooms'] = ['hall']
    with pytest.raises(SceneValidationError) as e:
        parse_house_layout(d)
    assert 'shares with rooms[1]' in one_sentence(e.value, 'doors[1]')


def test_a_plan_of_day_rooms_or_one_room_has_its_hallway_on_one_side_and_too_many_are_refused():
    from scene_synth_ros.corpus.house_plan import PlanError
    for rooms in (('living', 'kitchen'), ('bedroom',)):
        house = house_plan(0, 0, PlanConfig(rooms=rooms))
        assert len(house.rooms) == len(rooms) + 1
    with pytest.raises(PlanError, match='do not fit along a hallway of at most 16 m'):
        house_plan(0, 0, PlanConfig(rooms=('bedroom',) * 8))
