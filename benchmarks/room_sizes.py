"""Synthesis time against room size: rooms larger than their type's square are seen larger
(``render.Frame.for_room``), so their time grows with their pixels.

In this process alone, one thread, rooms synthesized in turn (interleaved, so that a change
of machine load falls on every size alike), ``-n`` of each (seeds 0..n-1): bedrooms of
today's sizes (the shells of held-out corpus rooms, corpus seed 1), and rectangular rooms of
the sizes given by ``--rooms`` (TYPE:WxD, metres, one door and a window). Printed per kind:
the side of its image in pixels, median and p90 seconds per room, objects per room, seconds
per square metre of floor, and the median's ratio to the bedrooms'.

    .venv/bin/python benchmarks/room_sizes.py [-n 30]
        [--rooms living:12x8,bedroom:7.5x3.8,living:8x6,living:16x10]
"""
import argparse
import statistics
import sys
import time

import torch

from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.scene import Opening, Room
from scene_synth_ros.synth import Synthesizer

DEFAULT_ROOMS = 'living:12x8,bedroom:7.5x3.8,living:8x6,living:16x10'


def rectangle(room_type: str, w: float, d: float) -> Room:
    """A ``w`` x ``d`` room with a door near a corner and a window mid-wall."""
    door = Opening('door', (0.7, 0.0), 0.9, 2.05, 0.0)
    window = Opening('window', (w / 2, d), min(1.6, w / 3), 1.3, 0.9)
    return Room(room_type, ((0, 0), (w, 0), (w, d), (0, d)), 2.7, (door,), (window,))


def parse_rooms(text: str) -> list[tuple[str, Room]]:
    out = []
    for item in text.split(','):
        rt, _, size = item.partition(':')
        w, _, d = size.partition('x')
        out.append((f'{rt} {w} m x {d} m', rectangle(rt, float(w), float(d))))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=30, help='rooms of each kind')
    ap.add_argument('--rooms', default=DEFAULT_ROOMS, help='TYPE:WxD,... (metres)')
    args = ap.parse_args(argv)
    torch.set_num_threads(1)
    synth = Synthesizer()
    kinds = [('bedrooms of today\'s sizes', None)] + parse_rooms(args.rooms)
    for _, room in kinds:      # warm-up: bundles, graphs of every image size
        synth.generate(room or empty_room('bedroom', HELDOUT_SEED, 10_000), seed=0)
    seconds = {name: [] for name, _ in kinds}
    objects = {name: [] for name, _ in kinds}
    areas = {name: [] for name, _ in kinds}
    pixels = {}
    for i in range(args.n):
        for name, room in kinds:
            r = room or empty_room('bedroom', HELDOUT_SEED, i)
            t0 = time.perf_counter()
            result = synth.generate(r, seed=i)
            seconds[name].append(time.perf_counter() - t0)
            objects[name].append(len(result.scene.objects))
            areas[name].append(r.polygon.area)
            ctx = synth._context(r, 0)
            pixels.setdefault(name, set()).add(ctx.frame.resolution)
    base = statistics.median(seconds[kinds[0][0]])
    print(f'{args.n} rooms of each kind, interleaved, one thread, runtime {synth.runtime}')
    print(f'{"rooms":<28} {"px":>8} {"median s":>9} {"p90 s":>7} {"objects":>8} '
          f'{"s per m2":>9} {"ratio":>6}')
    for name, _ in kinds:
        s = sorted(seconds[name])
        med = statistics.median(s)
        px = '/'.join(str(p) for p in sorted(pixels[name]))
        per_m2 = med / statistics.median(areas[name])
        print(f'{name:<28} {px:>8} {med:9.3f} {s[int(0.9 * (len(s) - 1))]:7.3f} '
              f'{statistics.mean(objects[name]):8.1f} {per_m2:9.4f} {med / base:6.2f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
