"""Whole houses furnished (``house_synth.furnish_house``): procedural house plans furnished
in one process of one thread, the rooms in lockstep and, beside it, one room at a time.

    .venv/bin/python benchmarks/house_synth.py [-n 20] [--plan-seed 0] [--rooms N]
    .venv/bin/python benchmarks/house_synth.py --layout examples/apartment_layout.json -n 20

House plan ``i`` of ``--plan-seed`` (``corpus/house_plan.py``; with ``--rooms N``, the plans
of N rooms only, drawn until ``-n`` are found) is furnished with seed ``i``, in lockstep
and one room at a time, in turn, every room type's networks readied first. Printed per
house: rooms, floor area, objects, seconds each way, rooms valid (``geometry.check_scene``
with the bundle's allowance) and keeping the robot promise; then the medians, and the share
of houses whose every room is valid and keeps the promise. With ``--layout``, that house
layout furnished ``-n`` times, with seeds 0 .. n-1. With ``--warm``, each house is furnished
once untimed first (another seed), as a long-running node or batch worker has: onnxruntime
opens a graph for each image size a room type meets (a room larger than its type's square
is seen larger), about 15 ms each, once per process.
"""
import argparse
import statistics
import sys
import time

import torch

from scene_synth_ros.corpus.house_plan import house_plan
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.house_synth import furnish_house
from scene_synth_ros.synth import Synthesizer


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('-n', type=int, default=20)
    ap.add_argument('--plan-seed', type=int, default=0)
    ap.add_argument('--rooms', type=int, default=None, help='only plans of this many rooms')
    ap.add_argument('--layout', help='a house layout file furnished -n times instead')
    ap.add_argument('--warm', action='store_true', help='furnish each house once untimed '
                    'first')
    args = ap.parse_args(argv)
    given = None
    if args.layout:
        from scene_synth_ros.schema import load_layout
        given = load_layout(args.layout).house
    torch.set_num_threads(1)
    synth = Synthesizer()
    synth.load_all()                 # every room type's networks ready: no house pays for it
    furnish_house(synth, house_plan(args.plan_seed, 0), 0)       # warm up
    together, alone, whole = [], [], 0
    i = found = 0
    while found < args.n:
        if i >= 100 * args.n:
            print(f'no more plans of {args.rooms} rooms among the first {i}')
            return 1
        house = given or house_plan(args.plan_seed, i)
        i += 1
        if args.rooms is not None and len(house.rooms) != args.rooms:
            continue
        if args.warm:
            furnish_house(synth, house, 10_000 + found)
        t0 = time.perf_counter()
        result = furnish_house(synth, house, found)
        t1 = time.perf_counter()
        furnish_house(synth, house, found, width=1)
        t2 = time.perf_counter()
        together.append(t1 - t0)
        alone.append(t2 - t1)
        valid = sum(check_scene(r.scene, r.allowance).ok for r in result.rooms.values())
        kept = sum(r.robot is not None and r.robot.kept for r in result.rooms.values())
        whole += valid == kept == len(house.rooms)
        what = f'seed {found}' if given else f'plan {i - 1}'
        print(f'house {found} ({what}): {len(house.rooms)} rooms, {house.area:.0f} m², '
              f'{len(result.scene.objects())} objects; {t1 - t0:.3f} s in lockstep, '
              f'{t2 - t1:.3f} s one room at a time; {valid} rooms valid, {kept} keep the '
              f'robot promise', flush=True)
        found += 1
    print(f'{found} houses: median {statistics.median(together):.3f} s in lockstep, '
          f'{statistics.median(alone):.3f} s one room at a time; {whole} of {found} with '
          f'every room valid and keeping the robot promise')
    return 0


if __name__ == '__main__':
    sys.exit(main())
