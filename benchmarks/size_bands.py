"""Synthesized rooms by size band: rooms as today, up to 10 m and up to 16 m on the longer side.

For every room type, ``-n`` held-out corpus shells (corpus seed 1) are taken as they are
(the band of the type's square) and scaled up (doors and windows keep their sizes, their
places scale with their walls) so that the longer side is drawn uniformly in (square, 10 m]
and in (10 m, 16 m]; each is furnished from empty (seed = its index) in one process, one
thread. Printed per room type and band: rooms, rooms valid (``geometry.check_scene``) and
keeping the robot promise, objects per room and per 10 m² of floor, the design rules kept
over all their cases, and the median seconds per room.

    .venv/bin/python benchmarks/size_bands.py [-n 20] [--room-type all]
"""
import argparse
import statistics
import sys
import time

import numpy as np
import torch

from scene_synth_ros import rules
from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.render import room_frame_box
from scene_synth_ros.scene import Opening, Room
from scene_synth_ros.synth import Synthesizer

BANDS = (('square', None), ('up to 10 m', 10.0), ('up to 16 m', 16.0))


def scaled(room: Room, factor: float) -> Room:
    """``room`` with its floor scaled by ``factor`` about the origin; openings keep their
    sizes, their centres scale with their walls."""
    def move(o: Opening) -> Opening:
        return Opening(o.kind, (o.position[0] * factor, o.position[1] * factor), o.width,
                       o.height, o.sill)
    floor = tuple((x * factor, y * factor) for x, y in room.floor)
    return Room(room.room_type, floor, room.wall_height, tuple(map(move, room.doors)),
                tuple(map(move, room.windows)))


def shells(room_type: str, n: int) -> dict[str, list[Room]]:
    rng = np.random.default_rng(7)
    out = {name: [] for name, _ in BANDS}
    for i in range(n):
        room = empty_room(room_type, HELDOUT_SEED, i)
        box = room_frame_box(room)
        side = max(box.span)
        lo = box.cap
        for name, bound in BANDS:
            if bound is None:
                out[name].append(room)
                continue
            target = rng.uniform(lo, bound)
            out[name].append(scaled(room, target / side))
            lo = bound
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=20, help='rooms per room type and band')
    ap.add_argument('--room-type', default='all')
    args = ap.parse_args(argv)
    torch.set_num_threads(1)
    synth = Synthesizer()
    types = [t for t in ROOM_TYPES if t in synth.room_types] if args.room_type == 'all' \
        else [args.room_type]
    print(f'{"room type":<10} {"band":<11} {"rooms":>5} {"valid":>5} {"robot":>5} '
          f'{"obj/room":>8} {"obj/10m2":>8} {"rules kept":>10} {"median s":>8}')
    for rt in types:
        for band, rooms in shells(rt, args.n).items():
            valid = robot = objects = 0
            density, seconds, kept, cases = [], [], 0, 0
            for i, room in enumerate(rooms):
                t0 = time.perf_counter()
                result = synth.generate(room, seed=i)
                seconds.append(time.perf_counter() - t0)
                valid += check_scene(result.scene).ok
                robot += result.robot.kept
                objects += len(result.scene.objects)
                density.append(10 * len(result.scene.objects) / room.polygon.area)
                for k, c in rules.measure(result.scene, vocabulary=synth.vocabulary).values():
                    kept, cases = kept + k, cases + c
            print(f'{rt:<10} {band:<11} {len(rooms):>5} {valid:>5} {robot:>5} '
                  f'{objects / len(rooms):8.1f} {statistics.mean(density):8.2f} '
                  f'{100 * kept / max(cases, 1):9.1f}% {statistics.median(seconds):8.3f}',
                  flush=True)
    return 0


if __name__ == '__main__':
    sys.exit(main())
