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
   (more desks for as many seats is the category module's doing, not insertion's).
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
from scene_synth_ros.scene import Scene  # noqa: E402
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


def desks_without_seats(syn: Synthesizer, rt: str, n: int) -> None:
    why = Counter()
    for i in range(n):
        scene = syn.generate(empty_room(rt, HELDOUT_SEED, i), seed=i).scene
        seats = [o for o in scene.first_tier if o.category in SEATS]
        for d in (o for o in scene.first_tier if o.category in DESKS):
            why['desks'] += 1
            if any(seated_at(s, d) for s in seats):
                why['with a seat'] += 1
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
        corpus['with a seat'] += sum(any(seated_at(s, d) for s in seats) for d in desks)
        corpus['seats'] += len(seats)
    print(f'\n3. {rt}s ({n} held-out shells): desks and dressing tables, synthesized / '
          f'held-out corpus')
    for k, v in why.items():
        print(f'   {k:32s} {v:5d}' + (f' {corpus[k]:5d}' if k in corpus else ''))


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
