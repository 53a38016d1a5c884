"""The robot promise on many synthesized rooms, checked by an independent raster flood fill.

For every room type and every robot radius, ``-n`` rooms (default 100) are synthesized with
the shipped weights into the shells of held-out corpus rooms (corpus seed 1, synthesis seeds
0..n-1), for a robot of that radius with the default reach (``Robot().reach``, 0.15 m).
Each room is checked by ``tests/raster_robot.py`` (2 cm cells, no shapely, no code of
``robot``): the doors connected and every first-tier object reached. Printed per room type
and radius: rooms furnished, rooms refused because the robot cannot drive between the doors
even in the empty room (confirmed on the raster), rooms the raster finds breaking the
promise (the target is 0), objects per room, the median share of free floor the robot drives
over, and the median seconds per room.

    .venv/bin/python benchmarks/robot_promise.py [-n 100] [--radii 0.15,0.2,0.3,0.4]
        [--room-type all] [--workers 2]
"""
import argparse
import statistics
import sys
import time

from benchlib import tests_module

from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.parallel import process_pool

_SYNTHS = {}


def _init_worker():
    import torch
    torch.set_num_threads(1)


def _run(job):
    from scene_synth_ros.corpus.generate import empty_room
    from scene_synth_ros.rules.robot import OPERATED_FRONT, Robot
    from scene_synth_ros.scene import Scene
    from scene_synth_ros.synth import SynthConfig, SynthesisError, Synthesizer
    check = tests_module('raster_robot').check
    rt, radius, i = job
    if radius not in _SYNTHS:
        _SYNTHS[radius] = Synthesizer(config=SynthConfig(robot=Robot(radius=radius)))
    room = empty_room(rt, HELDOUT_SEED, i)
    t = time.perf_counter()
    try:
        result = _SYNTHS[radius].generate(room, seed=i)
    except SynthesisError:
        v = check(Scene(room, []), radius, Robot().reach, 0.0, OPERATED_FRONT, slack=-0.04)
        return rt, radius, 'refused', not v.doors_connected, 0, 0.0, 0.0
    seconds = time.perf_counter() - t
    v = check(result.scene, radius, Robot().reach, 0.0, OPERATED_FRONT)
    kept = v.doors_connected and not v.unreachable and result.robot.kept
    return (rt, radius, 'kept' if kept else 'broken', True, len(result.scene),
            result.robot.reachable_floor, seconds)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('-n', type=int, default=100, help='rooms per room type and radius')
    ap.add_argument('--radii', default='0.15,0.2,0.3,0.4')
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--workers', type=int, default=2)
    args = ap.parse_args()
    radii = [float(r) for r in args.radii.split(',')]
    types = list(ROOM_TYPES) if args.room_type == 'all' else [args.room_type]
    jobs = [(rt, r, i) for rt in types for r in radii for i in range(args.n)]
    t0 = time.perf_counter()
    with process_pool(args.workers, _init_worker, ()) as pool:
        rows = list(pool.map(_run, jobs, chunksize=4))
    from scene_synth_ros.rules.robot import Robot
    print(f'robot promise: {args.n} held-out shells per room type and radius, reach '
          f'{Robot().reach:g} m, '
          f'checked on a {2} cm raster ({time.perf_counter() - t0:.0f} s, '
          f'{args.workers} workers)\n')
    print(f'{"room type":10s} {"radius":>6s} {"furnished":>9s} {"refused":>8s} '
          f'{"confirmed":>9s} {"broken":>6s} {"obj/room":>8s} {"floor":>6s} {"s/room":>7s}')
    broken_total = 0
    for rt in types:
        for r in radii:
            mine = [x for x in rows if x[0] == rt and x[1] == r]
            done = [x for x in mine if x[2] != 'refused']
            refused = [x for x in mine if x[2] == 'refused']
            broken = sum(x[2] == 'broken' for x in done)
            broken_total += broken
            objs = statistics.mean(x[4] for x in done) if done else 0.0
            floor = statistics.median(x[5] for x in done) if done else 0.0
            secs = statistics.median(x[6] for x in done) if done else 0.0
            print(f'{rt:10s} {r:6.2f} {len(done):9d} {len(refused):8d} '
                  f'{sum(x[3] for x in refused):9d} {broken:6d} {objs:8.2f} '
                  f'{100 * floor:5.1f}% {secs:7.3f}')
    print(f'\nrooms breaking the promise on the raster: {broken_total} (target 0)')
    return 0 if broken_total == 0 else 1


if __name__ == '__main__':
    sys.exit(main())
