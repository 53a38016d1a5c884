"""What real rooms do: heights in the validity checks, a data set's allowance (tucks, things
inside their parent, objects spawned above their support, door zones) and its derivation,
on hand-made rooms and on the real ProcTHOR rooms beside the repository."""
import math
from pathlib import Path
import random

import pytest

from scene_synth_ros import geometry
from scene_synth_ros.allowance import STRICT, Allowance
from scene_synth_ros.datasets import description, import_dataset
from scene_synth_ros.datasets.allowance import AllowanceConfig, derive
from scene_synth_ros.errors import DatasetError
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene
from scene_synth_ros.thresholds import DOOR_ZONE_LEAST_DEPTH

ROOM = Room('dining', ((0, 0), (5, 0), (5, 4), (0, 4)), 2.6,
            (Opening('door', (2.5, 0.0), 0.9, 2.05),))
REAL = Path(__file__).resolve().parent.parent.parent / 'shared' / 'data' / 'real'


def obj(oid, cat, x, y, w, d, h=0.8, yaw=0.0, z=0.0, support=None):
    return PlacedObject(oid, cat, 'm', (x, y, z), yaw, (w, d, h), support)


def table_and_chair(into: float, x: float = 2.5, y: float = 2.5):
    """A 1.6 x 0.9 m table (its depth along x) and a chair facing it from +x, its seat
    ``into`` metres under the table's edge."""
    table = obj('t', 'dining table', x, y, 1.6, 0.9, h=0.75)
    chair = obj('c', 'chair', x + 0.45 + 0.25 - into, y, 0.45, 0.5, h=0.9, yaw=math.pi)
    return table, chair


TUCK = Allowance(tucks=(('chair', 'dining table', 0.35),))


def test_a_picture_above_a_bed_does_not_collide_and_beside_a_door_does_not_block_it():
    bed = obj('b', 'bed', 2.5, 3.0, 1.6, 2.0, h=0.6)
    picture = obj('p', 'painting', 2.5, 3.9, 1.0, 0.05, h=0.6, z=1.3)
    low = obj('p', 'painting', 2.5, 3.9, 1.0, 0.05, h=0.6, z=0.3)      # behind the headboard
    assert geometry.collisions(Scene(ROOM, [bed, picture])) == []
    assert geometry.collisions(Scene(ROOM, [bed, low])) == [('b', 'p')]
    # x 3.0..3.5: in the floor zone's side margin (to 3.05), beside the opening (to 2.95)
    beside = obj('p', 'painting', 3.25, 0.03, 0.5, 0.05, h=0.5, z=1.2)
    in_swing = obj('p', 'painting', 2.5, 0.5, 0.6, 0.05, h=0.5, z=1.2)
    above = obj('p', 'painting', 2.5, 0.5, 0.6, 0.05, h=0.5, z=2.1)
    on_floor = obj('p', 'box', 3.15, 0.2, 0.3, 0.3, h=0.3)
    assert geometry.blocked_doors(Scene(ROOM, [beside])) == []
    assert geometry.blocked_doors(Scene(ROOM, [in_swing])) == [0]
    assert geometry.blocked_doors(Scene(ROOM, [above])) == []
    assert geometry.blocked_doors(Scene(ROOM, [on_floor])) == [0]


def test_a_chair_tucked_under_a_table_is_allowed_only_as_deep_as_the_allowance():
    for into in (0.1, 0.3):
        scene = Scene(ROOM, list(table_and_chair(into)))
        assert geometry.collisions(scene) == [('t', 'c')]
        assert geometry.collisions(scene, allowance=TUCK) == []
        assert geometry.check_scene(scene, TUCK).ok
    assert geometry.overlap_depth(*table_and_chair(0.3)) == pytest.approx(0.3)
    deep = Scene(ROOM, list(table_and_chair(0.45)))
    assert geometry.collisions(deep, allowance=TUCK) == [('t', 'c')]
    # the allowance names the pair either way round, and no other pair
    table, chair = table_and_chair(0.3)
    stool = PlacedObject('c', 'stool', 'm', chair.position, chair.yaw, chair.size)
    assert geometry.collisions(Scene(ROOM, [table, stool]), allowance=TUCK) == [('t', 'c')]


def test_things_inside_a_shelf_rest_on_it_only_where_the_allowance_says_so():
    shelf = obj('s', 'shelving unit', 2.5, 3.7, 1.0, 0.4, h=1.8, yaw=-math.pi / 2)
    book = obj('k', 'book', 2.5, 3.7, 0.2, 0.15, h=0.25, z=0.9, support='s')
    floor_level = obj('k', 'book', 2.5, 3.7, 0.2, 0.15, h=0.25, z=0.05, support='s')
    inside = Allowance(inside=(('shelving unit', 0.1),))
    assert geometry.under_supported(Scene(ROOM, [shelf, book])) == ['k']
    assert geometry.under_supported(Scene(ROOM, [shelf, book]), allowance=inside) == []
    assert geometry.under_supported(Scene(ROOM, [shelf, floor_level]), allowance=inside) \
        == ['k']
    # the allowance is per parent category
    dresser = obj('s', 'dresser', 2.5, 3.7, 1.0, 0.4, h=1.8, yaw=-math.pi / 2)
    assert geometry.under_supported(Scene(ROOM, [dresser, book]), allowance=inside) == ['k']


def test_an_object_spawned_above_its_support_rests_within_the_settle_allowance():
    table = obj('t', 'dining table', 2.5, 2.5, 1.6, 0.9, h=0.75)
    bowl = obj('b', 'bowl', 2.5, 2.5, 0.2, 0.2, h=0.1, z=0.80, support='t')
    assert geometry.under_supported(Scene(ROOM, [table, bowl])) == ['b']
    assert geometry.under_supported(Scene(ROOM, [table, bowl]),
                                    allowance=Allowance(settle=0.06)) == []
    assert geometry.under_supported(Scene(ROOM, [table, bowl]),
                                    allowance=Allowance(settle=0.03)) == ['b']


def test_a_door_zone_is_as_deep_as_the_allowance_but_never_shallower_than_a_robot_needs():
    # 0.6 m from the door
    near = obj('d', 'dresser', 2.5, 0.6 + 0.2, 1.0, 0.4, yaw=math.pi / 2)
    scene = Scene(ROOM, [near])
    assert geometry.blocked_doors(scene) == [0]
    assert geometry.blocked_doors(scene, allowance=Allowance(door_depth=0.55)) == []
    assert geometry.blocked_doors(scene, allowance=Allowance(door_depth=0.65)) == [0]
    closer = Scene(ROOM, [obj('d', 'dresser', 2.5, 0.45 + 0.2, 1.0, 0.4, yaw=math.pi / 2)])
    assert DOOR_ZONE_LEAST_DEPTH > 0.45
    assert geometry.blocked_doors(closer, allowance=Allowance(door_depth=0.0)) == [0]


def tucked_room(i: int, into: float) -> Scene:
    return Scene(ROOM, [*table_and_chair(into, x=2.0 + 0.01 * i),
                        obj('s', 'sofa', 1.0, 3.5, 1.8, 0.8)])


def test_a_habit_seen_in_enough_rooms_becomes_an_allowance_and_an_accident_does_not():
    rooms = [tucked_room(i, 0.2 + 0.01 * i) for i in range(10)]
    tucks = derive(rooms).tucks
    assert [(t, h) for t, h, _ in tucks] == [('chair', 'dining table')]
    assert 0.27 <= tucks[0][2] <= 0.29                      # the 95th percentile of 0.2..0.29
    # two rooms of ten: fewer than min_rooms
    few = [tucked_room(i, 0.3) if i < 2 else tucked_room(i, 0.0) for i in range(10)]
    assert derive(few).tucks == ()
    assert derive(few, AllowanceConfig(min_rooms=2, min_share=0.1)).tucks != ()
    assert derive([Scene(ROOM)] * 5) == STRICT


def test_inside_settle_and_door_depth_are_derived_from_the_rooms():
    rooms = []
    for i in range(6):
        shelf = obj('s', 'shelving unit', 2.5, 3.7, 1.0, 0.4, h=2.0, yaw=-math.pi / 2)
        table = obj('t', 'dining table', 2.5, 1.4, 1.6, 0.9, h=0.75)   # 0.6 m from the door
        rooms.append(Scene(ROOM, [
            shelf, table,
            obj('k', 'book', 2.5, 3.7, 0.2, 0.15, h=0.25, z=0.4 + 0.1 * i, support='s'),
            obj('b', 'bowl', 2.5, 1.4, 0.2, 0.2, h=0.1, z=0.80, support='t')]))
    a = derive(rooms)
    assert 0.2 <= dict(a.inside)['shelving unit'] <= 0.25       # the 5th percentile
    assert 'dining table' not in dict(a.inside)
    assert a.settle == pytest.approx(0.05)
    assert a.door_depth == pytest.approx(0.6, abs=0.01)
    # the quantile leaves out the lowest book of the six, as it leaves out outliers
    assert [geometry.check_scene(s, a).ok for s in rooms] == [False] + [True] * 5
    assert not any(geometry.check_scene(s).ok for s in rooms)


def test_an_allowance_round_trips_and_a_bad_one_is_one_sentence():
    a = Allowance((('chair', 'dining table', 0.33),), (('sofa', 0.4),), 0.05, 0.55)
    assert Allowance.from_dict(a.to_dict()) == a
    assert Allowance.from_dict(STRICT.to_dict()) == STRICT
    for bad, field in (([], 'allowance must'), ({'tucks': [{'tucked': 'chair'}]}, 'tucks[0]'),
                       ({'inside': {'sofa': 2.0}}, 'inside'), ({'settle': -1}, 'settle'),
                       ({'door_depth': 'deep'}, 'door_depth')):
        with pytest.raises(DatasetError, match=field.replace('[', r'\[')) as e:
            Allowance.from_dict(bad)
        assert '\n' not in str(e.value) and len(str(e.value)) < 200


@pytest.mark.skipif(not (REAL / 'procthor').is_dir(), reason=f'no real data in {REAL}')
def test_real_procthor_rooms_pass_with_the_allowance_of_the_other_rooms(tmp_path):
    """Judged strictly almost no ProcTHOR room is valid (chairs under tables, things on
    seats and in shelves, objects spawned above their support); with the allowance derived
    from the other half of the rooms, most are. The import writes the allowance of all of
    them into dataset.yaml."""
    result = import_dataset('procthor', [REAL / 'procthor'], out=tmp_path, keep_scenes=True)
    scenes = [Scene.from_dict(result.scenes[n]) for n in sorted(result.scenes)]
    random.Random(0).shuffle(scenes)
    halves = scenes[::2], scenes[1::2]
    allowed = [derive(h) for h in halves]
    strict = sum(geometry.check_scene(s).ok for s in scenes) / len(scenes)
    valid = sum(geometry.check_scene(s, a).ok
                for half, a in zip(halves, reversed(allowed), strict=True)
                for s in half) / len(scenes)
    assert strict < 0.05 and valid > 0.7, (strict, valid)
    written = description.load(tmp_path / description.FILE_NAME).allowance
    assert ('chair', 'dining table') in [(t, h) for t, h, _ in written.tucks]
    assert written.settle > 0 and written.lowest_inside('shelving unit') is not None


@pytest.fixture(scope='module')
def allowed_weights(tmp_path_factory):
    """The shipped dining bundle, as if trained on a data set that tucks its dining chairs
    0.35 m under the table and keeps 0.55 m before its doors."""
    from dataclasses import replace

    from scene_synth_ros.networks.bundle import bundle_path, load_bundle, save_bundle
    from scene_synth_ros.paths import weights_dir
    folder = tmp_path_factory.mktemp('weights')
    allowance = Allowance(tucks=(('dining chair', 'dining table', 0.35),), door_depth=0.55)
    save_bundle(replace(load_bundle(bundle_path(weights_dir(), 'dining')), allowance=allowance),
                folder / 'dining.pt')
    return folder, allowance


def test_networks_trained_on_a_data_set_furnish_rooms_with_its_allowance(allowed_weights):
    """The bundle carries its data set's allowance: insertion lets a dining chair tuck under
    the table as deep as it says, and the result is judged, and marked, by it."""
    from scene_synth_ros.allowance import of_scene
    from scene_synth_ros.networks.bundle import load_bundle
    from scene_synth_ros.synth import Synthesizer
    folder, allowance = allowed_weights
    assert load_bundle(folder / 'dining.pt').allowance == allowance
    strict, allowed = Synthesizer(), Synthesizer(folder)
    table = obj('t', 'dining table', 2.5, 2.5, 1.6, 0.9, h=0.75)
    for into, ok in ((0.3, True), (0.45, False)):
        chair = PlacedObject('c', 'dining chair', 'm', (2.5 + 0.45 + 0.25 - into, 2.5, 0.0),
                             math.pi, (0.45, 0.5, 0.9))
        for synth, expected in ((strict, False), (allowed, ok)):
            ctx = synth._context(ROOM, 0, [table])
            assert synth._refusal(ctx, Scene(ROOM, [table]), chair, None) == \
                (None if expected else 'collision'), (into, synth.weights_dir)
    # the door zone is as deep as the data keeps it
    assert allowed._context(ROOM, 0).zones[0].area < strict._context(ROOM, 0).zones[0].area
    result = allowed.generate(ROOM, seed=0)
    assert result.allowance == allowance
    assert of_scene(result.scene.meta) == allowance
    assert geometry.check_scene(result.scene, result.allowance).ok
    assert strict.generate(ROOM, seed=0).allowance == STRICT
    assert 'allowance' not in strict.generate(ROOM, seed=0).scene.meta
