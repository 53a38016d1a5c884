"""Real rooms furnished again: every room of a real data set whose type the shipped weights
know, emptied and handed to the synthesizer.

Each format's files under DATA (default ``../shared/data/real``; point it at a full
ProcTHOR, 3D-FRONT or SUNCG download to check rooms this repository does not hold) are
imported with the default filters (``scene-synth import``'s), and every kept room of a
room type the weights know is furnished from empty (seed = its index; rooms in lockstep
groups of 16, one thread). Printed per format: rooms seen, dropped by the importer and why,
kept per room type (those of types the weights do not know are counted, not furnished);
then per room type and size band (the longer side in the room's own axes: within the type's
square, up to 10 m, up to 16 m): rooms, rooms furnished validly (no collision, on the
floor, doors clear, supported: ``geometry.check_scene``; and the robot promise kept),
rooms refused, and objects per room of the synthesized rooms beside those of the data's
own rooms. The target is every room of a known type furnished validly.

    .venv/bin/python benchmarks/real_rooms.py [DATA] [--formats procthor,3dfront,suncg]
        [--limit N]
"""
import argparse
from collections import Counter, defaultdict
from pathlib import Path
import statistics
import sys
import time

import torch

from scene_synth_ros import lockstep
from scene_synth_ros.datasets import import_dataset
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.render import room_frame_box
from scene_synth_ros.scene import Scene
from scene_synth_ros.synth import Synthesizer

FORMATS = ('procthor', '3dfront', 'suncg')
BANDS = ((10.0, 'up to 10 m'), (16.0, 'up to 16 m'))


def band(scene: Scene) -> str:
    box = room_frame_box(scene.room)
    if box.in_square:
        return f'within its {box.cap:g} m square'
    side = max(box.span)
    return next((name for bound, name in BANDS if side <= bound), 'longer')


def furnish(synth: Synthesizer, scenes: list[Scene]) -> list:
    """Each room's synthesis (or the exception that refused it), in lockstep groups."""
    out = []
    for k in range(0, len(scenes), 16):
        group = scenes[k:k + 16]
        out += list(lockstep.run([lambda s=s, i=k + j: synth.generate(s.room, seed=i)
                                  for j, s in enumerate(group)]))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('data', nargs='?', default=str(Path(__file__).resolve().parents[2]
                                                   / 'shared' / 'data' / 'real'))
    ap.add_argument('--formats', default=','.join(FORMATS))
    ap.add_argument('--limit', type=int, default=0, help='rooms per format (0: all)')
    args = ap.parse_args(argv)
    torch.set_num_threads(1)
    synth = Synthesizer()
    failures = 0
    for fmt in args.formats.split(','):
        folder = Path(args.data) / fmt
        if not folder.is_dir():
            print(f'{fmt}: no folder {folder}')
            continue
        result = import_dataset(fmt, [folder], keep_scenes=True)
        report = result.report
        scenes = [Scene.from_dict(d) for d in result.scenes.values()]
        known = [s for s in scenes if s.room.room_type in synth.room_types]
        if args.limit:
            known = known[:args.limit]
        print(f'\n{fmt}: {report.rooms_seen} rooms seen, {len(scenes)} kept')
        for reason, n in sorted(report.dropped('room').items()):
            print(f'  dropped by the importer, {reason}: {n}')
        other = Counter(s.room.room_type for s in scenes if s.room.room_type not in
                        synth.room_types)
        if other:
            print('  kept, of a room type the weights do not know: '
                  + ', '.join(f'{rt} {n}' for rt, n in sorted(other.items())))
        t0 = time.perf_counter()
        done = furnish(synth, known)
        seconds = time.perf_counter() - t0
        rows = defaultdict(lambda: {'rooms': 0, 'valid': 0, 'refused': 0, 'ours': [],
                                    'theirs': []})
        for scene, r in zip(known, done, strict=True):
            row = rows[(scene.room.room_type, band(scene))]
            row['rooms'] += 1
            row['theirs'].append(len(scene.objects))
            if isinstance(r, Exception):
                row['refused'] += 1
                print(f'  refused: a {scene.room.room_type}: {r}')
                continue
            row['ours'].append(len(r.scene.objects))
            row['valid'] += bool(check_scene(r.scene).ok and r.robot.kept)
        print(f'  furnished {len(known)} rooms in {seconds:.1f} s')
        print(f'  {"room type":<10} {"size band":<24} {"rooms":>5} {"valid":>5} '
              f'{"refused":>7} {"objects (ours)":>14} {"objects (data)":>14}')
        for (rt, name), row in sorted(rows.items()):
            ours = statistics.mean(row['ours']) if row['ours'] else float('nan')
            print(f'  {rt:<10} {name:<24} {row["rooms"]:>5} {row["valid"]:>5} '
                  f'{row["refused"]:>7} {ours:>14.1f} {statistics.mean(row["theirs"]):>14.1f}')
            failures += row['rooms'] - row['valid']
    print(f'\nrooms of a known type not furnished validly: {failures}')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
