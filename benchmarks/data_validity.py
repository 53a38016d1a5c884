"""Real rooms held to the validity checks: strictly, and with the allowance that the data
set's own rooms give (``datasets.allowance``: chairs tucked under tables, things inside
shelves and on seats, objects spawned above their support, door zones as the data keeps
them).

Each format's files under DATA (default ``../shared/data/real``; point it at a full
ProcTHOR, 3D-FRONT or SUNCG download to check rooms this repository does not hold) are
imported with the default filters. The rooms are split in two halves by a seeded shuffle of
their names; the allowance is derived from one half and the other half is checked with it,
and the other way round, so that no room is judged by an allowance it helped to derive.
Printed per format and room type: rooms, valid strictly, valid with the allowance of the
other half, and per check the rooms that still fail it; then the allowance of all the rooms
(what ``scene-synth import`` writes into ``dataset.yaml``).

    .venv/bin/python benchmarks/data_validity.py [DATA] [--formats procthor,3dfront,suncg]
        [--seed 0]
"""
import argparse
from collections import defaultdict
from pathlib import Path
import random
import sys

from scene_synth_ros.datasets import import_dataset
from scene_synth_ros.datasets.allowance import derive
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.scene import Scene

FORMATS = ('procthor', '3dfront', 'suncg')
CHECKS = ('collisions', 'off_floor', 'blocked_doors', 'under_supported')


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('data', nargs='?', default=str(Path(__file__).resolve().parents[2]
                                                   / 'shared' / 'data' / 'real'))
    ap.add_argument('--formats', default=','.join(FORMATS))
    ap.add_argument('--seed', type=int, default=0)
    args = ap.parse_args(argv)
    for fmt in args.formats.split(','):
        folder = Path(args.data) / fmt
        if not folder.is_dir():
            print(f'{fmt}: no folder {folder}')
            continue
        scenes = import_dataset(fmt, [folder], keep_scenes=True).scenes
        names = sorted(scenes)
        random.Random(args.seed).shuffle(names)
        halves = (names[::2], names[1::2])
        allowances = [derive(Scene.from_dict(scenes[n]) for n in half) for half in halves]
        rows = defaultdict(lambda: defaultdict(int))
        for half, allowance in zip(halves, reversed(allowances), strict=True):
            for n in half:
                scene = Scene.from_dict(scenes[n])
                row = rows[scene.room.room_type]
                row['rooms'] += 1
                row['strict'] += check_scene(scene).ok
                r = check_scene(scene, allowance)
                row['allowed'] += r.ok
                for check in CHECKS:
                    row[check] += bool(getattr(r, check))
                row['doors_connected'] += not r.doors_connected
        print(f'\n{fmt}: {len(names)} rooms; allowance derived from one half, checked on '
              'the other')
        print(f'  {"room type":<10} {"rooms":>5} {"valid strictly":>15} '
              f'{"valid, allowed":>15}   still failing: '
              + ', '.join(CHECKS + ('doors_connected',)))
        total = defaultdict(int)
        for row in rows.values():
            for k, v in row.items():
                total[k] += v
        for rt, row in sorted(rows.items()) + [('all', total)]:
            n = row['rooms']
            print(f'  {rt:<10} {n:>5} {row["strict"]:>6} ({row["strict"] / n:6.1%}) '
                  f'{row["allowed"]:>6} ({row["allowed"] / n:6.1%})   '
                  + ', '.join(str(row[c]) for c in CHECKS + ('doors_connected',)))
        whole = derive(Scene.from_dict(scenes[n]) for n in names)
        print(f'  allowance of all {len(names)} rooms: {whole.to_dict()}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
