"""Synthesized rooms exported in every format: the rest test in MuJoCo and PyBullet, and the
bytes each format takes per room.

    .venv/bin/python benchmarks/sim_rest.py [-n 50] [--room-type all] [--seconds 2]
    .venv/bin/python benchmarks/sim_rest.py --houses -n 20

For every room type, ``-n`` empty held-out corpus shells (seed ``HELDOUT_SEED``, indices
0..n-1) are furnished by the shipped weights (seed = index), exported as SDF, glTF, MJCF, URDF
and USD, each into a folder of its own with its mesh files, and the MJCF and URDF exports are
simulated for ``--seconds`` under gravity from the exported poses (``export.rest``). Printed
per format and engine: rooms passed, the largest displacement, rotation and contact
penetration over all rooms, and the mean bytes of a self-contained room (the file, its mesh
files and, for URDF, the object files and poses). One process, torch on one thread.

With ``--houses``, ``-n`` procedural house plans (``corpus.house_plan``, plan seed
``HELDOUT_SEED``, indices 0..n-1) are furnished whole (``house_synth.furnish_house``, seed =
index) and each exported as one world.
"""
import argparse
from pathlib import Path
import sys
import tempfile
import time

from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.export import FORMATS, write
from scene_synth_ros.export.rest import RestLimits, mujoco_rest, pybullet_rest
from scene_synth_ros.house import count_objects

ENGINES = {'mjcf': ('MuJoCo', mujoco_rest), 'urdf': ('PyBullet', pybullet_rest)}


def folder_bytes(folder: Path) -> int:
    return sum(p.stat().st_size for p in folder.rglob('*') if p.is_file())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('-n', type=int, default=50, help='rooms per room type')
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--seconds', type=float, default=2.0, help='simulated time per room')
    ap.add_argument('--houses', action='store_true', help='-n furnished house plans, each '
                    'one world')
    args = ap.parse_args()
    import torch
    torch.set_num_threads(1)
    from scene_synth_ros.synth import Synthesizer
    synth = Synthesizer()
    room_types = ROOM_TYPES if args.room_type == 'all' else (args.room_type,)
    if args.houses:
        room_types = ('house',)

    def scene_of(rt: str, i: int):
        if rt != 'house':
            return synth.generate(empty_room(rt, HELDOUT_SEED, i), seed=i).scene
        from scene_synth_ros.corpus.house_plan import house_plan
        from scene_synth_ros.house_synth import furnish_house
        return furnish_house(synth, house_plan(HELDOUT_SEED, i), seed=i).scene
    limits = RestLimits()
    sizes = {f: [] for f in FORMATS}
    rest = {f: {'passed': 0, 'rooms': 0, 'disp': 0.0, 'rot': 0.0, 'pen': 0.0, 'seconds': 0.0}
            for f in ENGINES}
    per_type = {rt: {f: 0 for f in ENGINES} for rt in room_types}
    objects = 0
    failures = []
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        for rt in room_types:
            for i in range(args.n):
                scene = scene_of(rt, i)
                objects += count_objects(scene)
                for fmt, f in FORMATS.items():
                    folder = Path(tmp) / f'{rt}_{i}_{fmt}'
                    path = write(scene, fmt, folder / f'room{f.suffix}', folder / 'meshes')
                    sizes[fmt].append(folder_bytes(folder))
                    if fmt not in ENGINES:
                        continue
                    t = time.perf_counter()
                    report = ENGINES[fmt][1](path, args.seconds)
                    r = rest[fmt]
                    r['seconds'] += time.perf_counter() - t
                    r['rooms'] += 1
                    r['passed'] += report.passed(limits)
                    per_type[rt][fmt] += report.passed(limits)
                    r['disp'] = max(r['disp'], report.displacement)
                    r['rot'] = max(r['rot'], report.rotation)
                    r['pen'] = max(r['pen'], report.penetration)
                    if not report.passed(limits):
                        failures.append(f'{rt} {i} {ENGINES[fmt][0]}: '
                                        + '; '.join(report.failures(limits)))
    rooms = len(room_types) * args.n
    what = (f'{rooms} furnished house plans' if args.houses else
            f'{rooms} synthesized rooms ({args.n} per type: {", ".join(room_types)})')
    print(f'{what}, '
          f'{objects / max(rooms, 1):.2f} objects per {"house" if args.houses else "room"}, '
          f'{args.seconds:g} s simulated each, '
          f'limits {limits.displacement * 1000:g} mm / {limits.rotation:g} deg / '
          f'{limits.penetration * 1000:g} mm')
    print(f'{"format":8s} {"engine":9s} {"passed":>10s} {"max move":>10s} {"max turn":>10s} '
          f'{"max pen.":>10s} {"s/room":>7s} {"bytes/room":>11s}')
    for fmt in FORMATS:
        mean = sum(sizes[fmt]) / max(len(sizes[fmt]), 1)
        if fmt in ENGINES:
            r = rest[fmt]
            print(f'{fmt:8s} {ENGINES[fmt][0]:9s} {r["passed"]:>4d} / {r["rooms"]:<3d} '
                  f'{r["disp"] * 1000:>7.2f} mm {r["rot"]:>6.3f} deg {r["pen"] * 1000:>7.2f} mm '
                  f'{r["seconds"] / max(r["rooms"], 1):>7.3f} {mean:>11,.0f}')
        else:
            print(f'{fmt:8s} {"-":9s} {"":>10s} {"":>10s} {"":>10s} {"":>10s} {"":>7s} '
                  f'{mean:>11,.0f}')
    for rt in room_types:
        print(f'  {rt:9s} ' + '  '.join(f'{ENGINES[f][0]} {per_type[rt][f]}/{args.n}'
                                         for f in ENGINES))
    for line in failures:
        print('  FAILED', line)
    print(f'total {time.perf_counter() - t0:.0f} s')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
