"""The robot promise: its definition on hand-built rooms, insertion keeping it, and every
synthesized room keeping it for robots of 0.15-0.4 m radius, checked by an independent
raster flood fill (``raster_robot``)."""
import itertools
import math

import pytest
from raster_robot import CELL
from raster_robot import check as raster_check
import torch

from scene_synth_ros import catalog
from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room, generate_room
from scene_synth_ros.parallel import process_pool
from scene_synth_ros.rules import robot
from scene_synth_ros.rules.robot import OPERATED_FRONT, Robot
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene
from scene_synth_ros.schema import dump_scene, parse_scene
from scene_synth_ros.synth import SynthConfig, SynthesisError, Synthesizer


def box(category, x, y, w, d, yaw=0.0, oid=None, h=0.8):
    model = catalog.nearest(category, w, d).model_id
    return PlacedObject(oid or category, category, model, (x, y, 0.0), yaw, (w, d, h))


ROOM = Room('bedroom', [(0, 0), (4, 0), (4, 4), (0, 4)], 2.6,
            doors=(Opening('door', (3.0, 0.0), 0.9, 2.0),))
# A wardrobe on the top wall facing down (its front at y = 3.4), a bed standing before it.
WARDROBE = box('wardrobe', 1.0, 3.7, 1.6, 0.6, yaw=-math.pi / 2, h=2.0)


def bed_at(gap):
    """A 2 m x 1.6 m bed whose head is ``gap`` metres in front of the wardrobe, across it."""
    return box('double bed', 1.0, 3.4 - gap - 0.8, 2.0, 1.6, yaw=-math.pi / 2, oid='bed',
               h=0.5)


def both(scene, r: Robot):
    """The promise's verdict and the raster's, as (doors connected, unreachable ids)."""
    found = robot.report(scene, r)
    raster = raster_check(scene, r.radius, r.reach, r.clearance, OPERATED_FRONT)
    return ((found.doors_connected, list(found.unreachable)),
            (raster.doors_connected, raster.unreachable))


def test_a_wardrobe_sealed_behind_a_bed_is_unreachable_both_ways():
    r = Robot(radius=0.2, reach=0.5)
    sealed = Scene(ROOM, [WARDROBE, bed_at(0.15)])
    promise, raster = both(sealed, r)
    assert promise == raster == (True, ['wardrobe'])
    assert not robot.report(sealed, r).kept
    assert 'cannot reach wardrobe' in robot.report(sealed, r).sentence()
    # With 0.45 m between them the 0.4 m robot drives in and stands before the doors.
    open_ = Scene(ROOM, [WARDROBE, bed_at(0.45)])
    promise, raster = both(open_, r)
    assert promise == raster == (True, [])
    # A wider robot does not fit through that gap, and an arm reaching over the bed is
    # not enough either: the wardrobe is operated from straight before it.
    assert both(open_, Robot(radius=0.3, reach=0.5)) == ((True, ['wardrobe']),) * 2
    assert both(open_, Robot(radius=0.2, reach=0.5, clearance=0.1)) == ((True, ['wardrobe']),) * 2


def test_an_object_without_an_operated_front_is_reached_from_any_side():
    # The same bed, now with a chair in the gap: a chair is used from any side.
    chair = box('chair', 1.0, 3.75, 0.5, 0.5, yaw=-math.pi / 2)
    promise, raster = both(Scene(ROOM, [chair, bed_at(0.0)]), Robot(0.2, 0.5))
    assert promise == raster == (True, [])
    promise, raster = both(Scene(ROOM, [chair, bed_at(0.0)]), Robot(0.2, 0.05))
    assert promise[1] == raster[1] == []        # its sides stand free in the room


def test_doors_cut_apart_are_reported_both_ways():
    room = Room('bedroom', [(0, 0), (5, 0), (5, 3), (0, 3)], 2.6,
                doors=(Opening('door', (1.0, 0.0), 0.9, 2.0),
                       Opening('door', (4.0, 3.0), 0.9, 2.0)))
    shelf = box('shelving', 2.5, 1.5, 3.0, 0.4)             # across the room, wall to wall
    promise, raster = both(Scene(room, [shelf]), Robot(0.2, 0.5))
    assert promise[0] is raster[0] is False
    report = robot.report(Scene(room, [shelf]), Robot(0.2, 0.5))
    assert not report.kept and 'cannot drive between the doors' in report.sentence()


def test_the_report_measures_the_free_floor_reached():
    empty = robot.report(Scene(ROOM, []), Robot())
    assert empty.kept and empty.reachable_floor > 0.98     # all but the rounded corners
    sealed = robot.report(Scene(ROOM, [WARDROBE, bed_at(0.15)]), Robot())
    assert sealed.reachable_floor < empty.reachable_floor
    d = sealed.to_dict()
    assert d['radius'] == 0.2 and d['reach'] == 0.15 and d['promise_kept'] is False
    assert d['unreachable'] == ['wardrobe']
    no_doors = Room('bedroom', ROOM.floor, 2.6)
    assert robot.report(Scene(no_doors, [WARDROBE]), Robot()).kept
    assert 'no doors' in robot.report(Scene(no_doors, []), Robot()).sentence()
    assert robot.report(Scene(no_doors, []), Robot()).to_dict()['reachable_floor'] is None


@pytest.mark.parametrize('kwargs, words', [
    ({'radius': 0.01}, 'robot radius must be between 0.05 and 0.5 m, got 0.01'),
    ({'radius': math.nan}, 'robot radius must be between'),
    ({'reach': 3.0}, 'robot reach must be between 0.05 and 1.5 m'),
    ({'clearance': 0.3, 'reach': 0.2}, 'must be less than its reach'),
    ({'radius': True}, 'robot radius must be between'),
])
def test_a_robot_that_cannot_be_is_refused_in_one_sentence(kwargs, words):
    with pytest.raises(ValueError, match=words):
        Robot(**kwargs)


# ---- insertion keeps the promise -----------------------------------------------------------
@pytest.fixture(scope='module')
def synth(tiny_weights):
    # The promise alone: no design rule kept at insertion (a 0.45 m gap before a wardrobe
    # lets the robot in but is short of the 0.5 m ``storage_clearance`` asks).
    return Synthesizer(tiny_weights, SynthConfig(insertion_rules=()))


def test_the_default_robot_is_the_design_rules_robot():
    # Rooms furnished for the default robot then keep the reachability rules by construction.
    from scene_synth_ros.rules.access import RULE_ROBOT
    assert Robot() == RULE_ROBOT == SynthConfig().robot


def test_the_state_after_one_more_object_is_the_state_of_the_room_with_it():
    # Insertion derives the robot's state after a candidate from the state before it
    # (``state_after``); it must be the state measured on the room from scratch.
    r = Robot()
    compared = changed = 0
    for rt, i in itertools.product(ROOM_TYPES, range(3)):
        furnished = generate_room(rt, HELDOUT_SEED, i)
        scene = Scene(furnished.room, [])
        before = robot.state(scene, r)
        for o in furnished.first_tier:
            after = Scene(scene.room, scene.objects + [o])
            derived, measured = robot.state_after(before, after, r), robot.state(after, r)
            assert derived.doors_connected == measured.doors_connected
            assert derived.reached == measured.reached
            assert derived.free.symmetric_difference(measured.free).area < 1e-9
            added = len(after.first_tier) - 1
            assert robot.kept(before, derived, added) == robot.kept(before, measured, added)
            changed += derived.free.area < before.free.area - 1e-3
            compared += 1
            scene, before = after, derived
    assert compared > 50 and changed > 40
    # Objects that seal a wardrobe in: the derived state says so as the measured one does.
    with_wardrobe = Scene(ROOM, [WARDROBE])
    sealed = Scene(ROOM, [WARDROBE, bed_at(0.15)])
    derived = robot.state_after(robot.state(with_wardrobe, r), sealed, r)
    assert derived.reached == robot.state(sealed, r).reached == frozenset({1})


def test_insertion_refuses_what_breaks_the_promise(synth):
    ctx = synth._context(ROOM, 0)
    # A bed that would seal the wardrobe in is refused; one that leaves it open is not.
    with_wardrobe = Scene(ROOM, [WARDROBE])
    assert not synth.fits(ctx, with_wardrobe, bed_at(0.15))
    assert synth.fits(ctx, with_wardrobe, bed_at(0.45))
    # So is a wardrobe put where its front faces the bed's head 15 cm away.
    with_bed = Scene(ROOM, [bed_at(0.15)])
    assert not synth.fits(ctx, with_bed, WARDROBE)
    # The promise is for the synthesizer's robot: one 0.1 m wide drives into the 15 cm gap.
    small = Synthesizer(synth.weights_dir, SynthConfig(robot=Robot(radius=0.05, reach=0.5),
                                                       insertion_rules=()))
    assert small.fits(small._context(ROOM, 0), with_bed, WARDROBE)


def test_a_room_that_cannot_keep_the_promise_is_refused_in_one_sentence(synth):
    # Two doors joined by a 0.5 m wide corridor: a 0.6 m robot cannot pass even when empty.
    room = Room('bathroom', [(0, 0), (2, 0), (2, 2), (1.25, 2), (1.25, 4), (0.75, 4),
                             (0.75, 2), (0, 2)], 2.6,
                doors=(Opening('door', (1.0, 0.0), 0.8, 2.0),
                       Opening('door', (1.0, 4.0), 0.45, 2.0)))
    wide = Synthesizer(synth.weights_dir, SynthConfig(robot=Robot(radius=0.3)))
    with pytest.raises(SynthesisError, match='cannot drive between the doors of this room '
                                             'even when it is empty'):
        wide.generate(room, seed=0)
    narrow = Synthesizer(synth.weights_dir, SynthConfig(robot=Robot(radius=0.15)))
    result = narrow.generate(room, seed=0)
    assert result.robot.kept and result.scene.meta['robot']['radius'] == 0.15


def test_a_completed_room_keeps_what_held_and_says_what_did_not(synth):
    # The user's own room already seals the wardrobe: completing it adds nothing that
    # breaks more, and the report says what the user's objects broke.
    user = Scene(ROOM, [WARDROBE, bed_at(0.15)])
    result = synth.complete(user, seed=1)
    assert result.robot.unreachable == ('wardrobe',)
    assert result.scene.meta['robot']['promise_kept'] is False
    added = [o for o in result.scene.first_tier if o.id not in ('wardrobe', 'bed')]
    r = synth.config.robot
    verdict = raster_check(result.scene, r.radius, r.reach, r.clearance, OPERATED_FRONT)
    assert verdict.doors_connected
    assert set(verdict.unreachable) <= {'wardrobe'}, (verdict, added)


# ---- every synthesized room, for robots of 0.15-0.4 m ---------------------------------------
RADII = (0.15, 0.2, 0.25, 0.3, 0.35, 0.4)
ROOMS_PER_TYPE = 60
_synths: dict = {}                       # a worker's Synthesizer


def _synthesize_and_check(job):
    """One held-out shell furnished for one robot, then checked on the raster: what the
    promise said and what the raster found (in a worker process)."""
    torch.set_num_threads(1)
    rt, i = job
    radius = RADII[i % len(RADII)]
    if 'synth' not in _synths:               # one per worker: the networks load once
        _synths['synth'] = Synthesizer()
    synth = _synths['synth']
    synth.config = SynthConfig(robot=Robot(radius=radius))
    room = empty_room(rt, HELDOUT_SEED, i)
    try:
        result = synth.generate(room, seed=i)
    except SynthesisError as e:                          # too narrow for this robot
        wider = raster_check(Scene(room, []), radius, Robot().reach, 0.0, OPERATED_FRONT,
                             slack=-2 * CELL)
        return rt, i, radius, 'refused', str(e), wider.doors_connected
    scene = result.scene
    meta = scene.meta['robot']
    ok_meta = (meta['radius'] == radius and meta['promise_kept'] and
               parse_scene(dump_scene(scene)).meta['robot'] == meta)
    verdict = raster_check(scene, radius, meta['reach'], 0.0, OPERATED_FRONT)
    return (rt, i, radius, 'furnished', ok_meta and result.robot.kept,
            verdict.doors_connected and not verdict.unreachable)


@pytest.mark.slow
def test_hundreds_of_synthesized_rooms_keep_the_promise_checked_on_a_raster():
    # 60 held-out shells per room type with the shipped weights, each for one robot of
    # 0.15-0.4 m radius in turn; every furnished room must pass the independent raster check,
    # and a room refused as too narrow must be too narrow on the raster as well.
    jobs = [(rt, i) for rt in ROOM_TYPES for i in range(ROOMS_PER_TYPE)]
    with process_pool(2) as pool:
        rows = pool.map(_synthesize_and_check, jobs, chunksize=5)
    refused = [r for r in rows if r[3] == 'refused']
    for rt, i, radius, _, why, connected in refused:
        assert 'even when it is empty' in why and not connected, (rt, i, radius, why)
    furnished = [r for r in rows if r[3] == 'furnished']
    assert len(furnished) >= 0.9 * len(rows)
    bad = [r[:3] for r in furnished if not (r[4] and r[5])]
    assert not bad, f'rooms breaking the promise (type, index, radius): {bad}'


def test_the_reach_command_reports_draws_and_refuses_a_robot_that_cannot_be(cli, tmp_path):
    from scene_synth_ros.schema import save_scene
    save_scene(Scene(ROOM, [WARDROBE, bed_at(0.15)]), tmp_path / 'sealed.json')
    save_scene(Scene(ROOM, [WARDROBE, bed_at(0.45)]), tmp_path / 'open.json')
    run = cli('reach', tmp_path / 'open.json', '--png', tmp_path / 'reach.png')
    assert 'comes in through the door and reaches every object within 0.15 m' in run.stdout
    assert (tmp_path / 'reach.png').read_bytes()[:4] == b'\x89PNG'
    run = cli('reach', tmp_path / 'open.json', tmp_path / 'sealed.json', ok=False)
    assert run.returncode == 1 and 'sealed.json: a robot of radius 0.2 m cannot reach ' \
                                   'wardrobe' in run.stdout
    run = cli('reach', tmp_path / 'open.json', '--robot-radius', '0.3', ok=False)
    assert run.returncode == 1
    save_scene(Scene(Room('bedroom', ROOM.floor, 2.6), [WARDROBE]), tmp_path / 'shut.json')
    run = cli('reach', tmp_path / 'shut.json', '--png', tmp_path / 'shut.png')
    assert 'no doors' in run.stdout and (tmp_path / 'shut.png').exists()
    run = cli('reach', tmp_path / 'open.json', '--robot-radius', '0.01', ok=False)
    assert run.returncode == 2 and '--robot-radius must be between 0.05 and 0.5 m' in run.stderr
    assert len(run.stderr.strip().splitlines()) == 1
