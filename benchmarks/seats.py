"""Why seats break the design rules: how the corpus turns them, how the orientation module
turns them where the corpus put them, and why a synthesized desk has no seat.

    .venv/bin/python benchmarks/seats.py [--room-type bedroom] [-n 120] [--weights-dir DIR]
                                         [--desks-only]

1. Corpus (training seed): per seat category, the share of yaws within 1 and within 10
   degrees of the room's axes, i.e. what the snap classifier's label calls snapped at the
   old and at the current ``SNAP_TOLERANCE``.
2. Held-out rooms (``-n``): every seat is removed and its orientation drawn 8 times at its
   true place, with the rest of the room around it: the snap classifier's mean probability,
   the share of draws 15 degrees or more off the axes (``chairs_square``'s threshold) and
   their median angle off the axes.
3. The same held-out shells synthesized (seed = index): for every desk or dressing table
   without a seat (``desk_has_seat``), whether the room has no seat at all, has seats but
   none in front of the desk, or one in front but farther than the rule's reach; and beside
   it the desks, the seated desks and the seats of the held-out corpus rooms themselves
   (more desks for as many seats is the category module's doing, not insertion's); how far
   seated seats sit from the middle of the desk's front; how each placed desk was drawn
   (first in its step, or after a category that found no place); what came of every seat
   draw made beside a desk without a seat (placed at it, elsewhere, or failed, and then
   whether a scan of seated placements before the desk, every model of the category, 5 cm
   steps out to the rule's reach and nine places along the front, finds one that fits); and
   which of ``fits``'s checks refused the seat placements.
   ``--desks-only``: this section alone.
"""
import argparse
from collections import Counter, defaultdict
import math
from pathlib import Path
import sys

import numpy as np
import torch

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / 'benchmarks'))

from shortfall import watch_fits_checks  # noqa: E402

from scene_synth_ros import catalog, robot  # noqa: E402
from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import empty_room, generate_room  # noqa: E402
from scene_synth_ros.evaluation.design_rules.groups import (  # noqa: E402
    DESKS,
    SEAT_REACH,
    SEATS,
    SQUARE_SEATS,
    local_xy,
    seated_at,
    within_reach,
)
from scene_synth_ros.render import Frame  # noqa: E402
from scene_synth_ros.scene import PlacedObject, Scene, wrap_angle  # noqa: E402
from scene_synth_ros.synth import Synthesizer  # noqa: E402

DRAWS = 8


def off_axes_degrees(yaw: float, frame_yaw: float) -> float:
    r = (yaw - frame_yaw) % (math.pi / 2)
    return math.degrees(min(r, math.pi / 2 - r))


def corpus_turns(rt: str, n: int) -> None:
    offs = defaultdict(list)
    for i in range(n):
        s = generate_room(rt, 0, i)
        fy = Frame.for_room(s.room, 64).yaw
        for o in s.objects:
            if o.category in SQUARE_SEATS:
                offs[o.category].append(off_axes_degrees(o.yaw, fy))
    print(f'1. corpus {rt}s (training seed, {n} rooms): seats within 1 / 10 degrees of an axis')
    for c, v in sorted(offs.items(), key=lambda kv: -len(kv[1])):
        v = np.array(v)
        print(f'   {c:15s} {len(v):5d}  {np.mean(v < 1):6.1%} {np.mean(v < 10):6.1%}')


def drawn_turns(syn: Synthesizer, rt: str, n: int) -> None:
    offs, snaps = defaultdict(list), defaultdict(list)
    for i in range(n):
        s = generate_room(rt, HELDOUT_SEED, i)
        ctx = syn._context(s.room, i)
        for o in s.objects:
            if o.category not in SQUARE_SEATS:
                continue
            rest = Scene(s.room, [p for p in s.objects if p.id != o.id and p.support != o.id])
            c = ctx.spec.index(o.category)
            pts = np.array([o.position[:2]] * DRAWS)
            x = syn._local_images(ctx, rest, pts, [ctx.frame.yaw] * DRAWS)
            with torch.no_grad():
                p = torch.sigmoid(ctx.bundle.networks['snap'](x, torch.full((DRAWS,), c)))
            snaps[o.category] += p.tolist()
            offs[o.category] += [off_axes_degrees(y, ctx.frame.yaw)
                                 for y in syn._orientation(ctx, rest, c, pts)]
    print(f'\n2. held-out {rt}s ({n} rooms): {DRAWS} orientation draws per seat at its true place')
    print(f'   {"category":15s} {"draws":>5s} {"snap p":>7s} {">=15 deg":>9s} {"median":>7s}')
    for c, v in sorted(offs.items(), key=lambda kv: -len(kv[1])):
        v = np.array(v)
        print(f'   {c:15s} {len(v):5d} {np.mean(snaps[c]):7.2f} {np.mean(v >= 15):9.1%} '
              f'{np.median(v):6.1f}°')


class SeatDraws:
    """Wraps the synthesizer's steps on the instance (this process only) to count, per step,
    which categories were drawn and whether they went in; per seat draw made while the room
    holds a desk without a seat, what came of it and, when it failed, whether any seated
    placement before one of those desks would have fitted; and why seat placements were
    refused (the check of ``fits`` that refused, ``shortfall.watch_fits_checks``)."""

    def __init__(self, syn: Synthesizer):
        self.syn = syn
        self.orig = {k: getattr(syn, k) for k in ('_insert_one', '_insert_category', 'fits')}
        self.tries: list[tuple[str, bool]] = []
        self.desk_draws = Counter()       # first draw / after a failed one
        self.failed_before_desk = Counter()
        self.seat_draws = Counter()
        self.refused = Counter()
        self.check = ''                      # the last check ``fits`` began
        syn._insert_one, syn._insert_category = self._insert_one, self._insert_category
        syn.fits = self._fits
        watch_fits_checks(lambda label: setattr(self, 'check', label),
                          lambda name: f'rule {name}')

    def _insert_one(self, ctx, scene, allow_stop=True, only=None):
        self.tries = []
        obj, why = self.orig['_insert_one'](ctx, scene, allow_stop, only)
        if obj is not None and obj.category in DESKS:
            if len(self.tries) == 1:
                self.desk_draws['drawn first'] += 1
            else:
                self.desk_draws['drawn after a failed category'] += 1
                self.failed_before_desk[self.tries[0][0]] += 1
        return obj, why

    def _insert_category(self, ctx, scene, c, location, small):
        obj = self.orig['_insert_category'](ctx, scene, c, location, small)
        name = ctx.spec.names[c]
        self.tries.append((name, obj is not None))
        if name in SEATS:
            unseated = unseated_desks(scene)
            if not unseated:
                self.seat_draws['no desk without a seat'] += 1
            elif obj is None:
                found = self._seated_fit(ctx, scene, name, unseated)
                self.seat_draws['beside an unseated desk: failed, a seated placement fits'
                                if found else 'beside an unseated desk: failed, none fits'] += 1
            elif any(seated_at(obj, d) for d in unseated):
                self.seat_draws['beside an unseated desk: placed at it'] += 1
            else:
                self.seat_draws['beside an unseated desk: placed elsewhere'] += 1
        return obj

    def _fits(self, ctx, scene, obj, parent=None):
        self.check = 'floor'
        ok = self.orig['fits'](ctx, scene, obj, parent)
        if not ok and obj.category in SEATS and obj.support is None:
            why = self.check
            if why == 'path':
                why = robot_refusal(self.syn, ctx, scene, obj)
            self.refused[REFUSALS.get(why, why)] += 1
        return ok

    def _seated_fit(self, ctx, scene, name, desks) -> bool:
        for d in desks:
            ahead = np.array([math.cos(d.yaw), math.sin(d.yaw)])
            side = np.array([-ahead[1], ahead[0]])
            for v in catalog.load(self.syn.config.catalog).variants(name, ctx.spec.room_type):
                for gap in np.arange(0.0, SEAT_REACH + 1e-9, 0.05):
                    for off in np.linspace(-d.width / 2, d.width / 2, 9):
                        xy = (np.asarray(d.position[:2]) + ahead * (d.depth / 2 + gap
                                                                    + v.depth / 2) + side * off)
                        o = PlacedObject(scene.new_id(name), name, v.model_id,
                                         (float(xy[0]), float(xy[1]), 0.0),
                                         wrap_angle(d.yaw + math.pi), v.size)
                        if seated_at(o, d) and self.orig['fits'](ctx, scene, o, None):
                            return True
        return False


def unseated_desks(scene: Scene) -> list:
    seats = [o for o in scene.first_tier if o.category in SEATS]
    return [d for d in scene.first_tier
            if d.category in DESKS and not any(seated_at(s, d) for s in seats)]


# ``watch_fits_checks``'s labels as this table prints them.
REFUSALS = {'floor': 'off the floor', 'collide': 'collides', 'door': "in a door's zone"}


def robot_refusal(syn: Synthesizer, ctx, scene: Scene, obj) -> str:
    """What of the robot promise ``obj`` (first tier, refused by it) breaks."""
    after = Scene(scene.room, scene.objects + [obj])
    before = syn._robot_state(ctx, scene)
    now = robot.state_after(before, after, syn.config.robot)
    if before.doors_connected and not now.doors_connected:
        return 'robot: doors cut apart'
    lost = before.reached - now.reached
    if not lost:
        return 'robot: the seat itself out of reach'
    cats = {scene.first_tier[k].category for k in lost}
    return 'robot: a desk\'s front lost' if cats & set(DESKS) else 'robot: another object lost'


def lateral(seat, desk) -> float:
    """How far a seat sits from the middle of its desk's front, in half-widths of the desk."""
    return abs(local_xy(desk, seat.position)[1]) / (desk.width / 2)


def desks_without_seats(syn: Synthesizer, rt: str, n: int) -> None:
    why = Counter()
    draws = SeatDraws(syn)
    offsets = {'synthesized': [], 'corpus': []}
    for i in range(n):
        scene = syn.generate(empty_room(rt, HELDOUT_SEED, i), seed=i).scene
        seats = [o for o in scene.first_tier if o.category in SEATS]
        for d in (o for o in scene.first_tier if o.category in DESKS):
            why['desks'] += 1
            at = [s for s in seats if seated_at(s, d)]
            if at:
                why['with a seat'] += 1
                offsets['synthesized'].append(min(lateral(s, d) for s in at))
            elif not seats:
                why['room without a seat'] += 1
            else:
                front = [s for s in seats if local_xy(d, s.position)[0] >= d.depth / 2
                         and abs(local_xy(d, s.position)[1]) <= d.width / 2]
                if not front:
                    why['seats, none in front'] += 1
                elif any(within_reach(s, d, SEAT_REACH) for s in front):
                    why['in front and near, turned away'] += 1
                else:
                    why['in front, too far'] += 1
        why['seats'] += len(seats)
    corpus = Counter()
    for i in range(n):
        scene = generate_room(rt, HELDOUT_SEED, i)
        seats = [o for o in scene.first_tier if o.category in SEATS]
        desks = [o for o in scene.first_tier if o.category in DESKS]
        corpus['desks'] += len(desks)
        for d in desks:
            at = [s for s in seats if seated_at(s, d)]
            corpus['with a seat'] += bool(at)
            if at:
                offsets['corpus'].append(min(lateral(s, d) for s in at))
        corpus['seats'] += len(seats)
    print(f'\n3. {rt}s ({n} held-out shells): desks and dressing tables, synthesized / '
          f'held-out corpus')
    for k, v in why.items():
        print(f'   {k:32s} {v:5d}' + (f' {corpus[k]:5d}' if k in corpus else ''))
    print('   seated: seat from the middle of the desk\'s front, in half-widths of the desk '
          '(share under 0.25 / 0.25-0.5 / over 0.5), synthesized / corpus')
    for src, values in offsets.items():
        v = np.asarray(values)
        if len(v):
            print(f'     {src:12s} {np.mean(v < 0.25):6.1%} {np.mean((v >= 0.25) & (v < 0.5)):6.1%}'
                  f' {np.mean(v >= 0.5):6.1%}  ({len(v)} seated desks)')
    print('   desks placed, by how their step drew them: '
          + ', '.join(f'{k} {v}' for k, v in draws.desk_draws.items())
          + ('; the category that failed first: ' + ', '.join(
              f'{k} {v}' for k, v in draws.failed_before_desk.most_common())
             if draws.failed_before_desk else ''))
    print('   seat draws (any seat category drawn, first draw or not):')
    for k, v in sorted(draws.seat_draws.items()):
        print(f'     {k:60s} {v:5d}')
    print('   seat placements refused, by the first check that refused them: ' + ', '.join(
        f'{k} {v}' for k, v in draws.refused.most_common()))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--room-type', default='bedroom')
    ap.add_argument('-n', type=int, default=120, help='held-out rooms')
    ap.add_argument('--corpus-rooms', type=int, default=300)
    ap.add_argument('--weights-dir', default=None, help="default: the package's weights/")
    ap.add_argument('--desks-only', action='store_true', help='section 3 alone')
    args = ap.parse_args()
    torch.set_num_threads(1)
    syn = Synthesizer(args.weights_dir)
    if not args.desks_only:
        corpus_turns(args.room_type, args.corpus_rooms)
        drawn_turns(syn, args.room_type, args.n)
    desks_without_seats(syn, args.room_type, args.n)
    return 0


if __name__ == '__main__':
    sys.exit(main())
