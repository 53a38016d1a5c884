"""House plans and house layouts: procedural plans drawn and checked, the slowest house layout
within the limits checked, and a data set's houses written back as layouts.

    .venv/bin/python benchmarks/house_plans.py [-n 200] [--seed 0]
                                               [--import FORMAT PATH [PATH ...]]

Prints: how many of ``-n`` procedural plans (``corpus/house_plan.py``, plan seed ``--seed``)
are valid house layouts (``schema.parse_house_layout``), their rooms (mean, fewest, most) and
floor area (median m²), and the median milliseconds to draw a plan (its own check included)
and to check its layout again; the seconds to check a layout at the limits (64 rooms of 60
vertices, 256 doors on one wall: refused in one sentence, after every room and door is
read); and with ``--import``, the data set's files imported with ``--layouts`` (the default
filters): houses, their rooms, the layouts written and the rooms or houses left out, so the
houses of a full download, which this repository does not hold, can be checked too.
"""
import argparse
import statistics
import sys
import tempfile
import time

from scene_synth_ros.corpus.house_plan import house_plan
from scene_synth_ros.schema import SceneValidationError, parse_house_layout


def plans(n: int, seed: int) -> None:
    valid, rooms, areas, draw, check = 0, [], [], [], []
    for i in range(n):
        t0 = time.perf_counter()
        house = house_plan(seed, i)
        t1 = time.perf_counter()
        layout = house.to_dict()
        try:
            parse_house_layout(layout)
            valid += 1
        except SceneValidationError as e:
            print(f'plan {i}: {e}')
        check.append(time.perf_counter() - t1)
        draw.append(t1 - t0)
        rooms.append(len(house.rooms))
        areas.append(house.area)
    print(f'plans: {valid} of {n} valid house layouts; rooms {statistics.mean(rooms):.1f} '
          f'({min(rooms)}-{max(rooms)}), median {statistics.median(areas):.0f} m²; median '
          f'{1000 * statistics.median(draw):.1f} ms to draw, '
          f'{1000 * statistics.median(check):.1f} ms to check')


def _zigzag(x0: float, y0: float, vertices: int) -> list[list[float]]:
    """A 4 m x 3 m room whose bottom wall zigzags through ``vertices`` points."""
    bottom = [[round(x0 + 4 * k / (vertices - 3), 4), round(y0 + 0.02 * (k % 2), 4)]
              for k in range(vertices - 2)]
    return bottom + [[x0 + 4, y0 + 3], [x0, y0 + 3]]


def at_the_limits() -> None:
    rooms = [{'id': f'r{i}', 'room_type': 'bedroom',
              'floor': _zigzag((i % 8) * 5.0, (i // 8) * 4.0, 60)} for i in range(64)]
    doors = [{'rooms': ['r0'], 'position': [round(0.5 + 3.0 * j / 256, 4), 3.0],
              'width': 0.31, 'height': 2.0} for j in range(256)]
    t0 = time.perf_counter()
    try:
        parse_house_layout({'rooms': rooms, 'doors': doors})
        outcome = 'accepted'
    except SceneValidationError as e:
        outcome = f'refused: {e}'
    print(f'at the limits (64 rooms of 60 vertices, 256 doors): {time.perf_counter() - t0:.2f} '
          f's, {outcome}')


def imported(fmt: str, paths: list[str]) -> None:
    from scene_synth_ros.datasets import import_dataset
    with tempfile.TemporaryDirectory() as out:
        result = import_dataset(fmt, paths, out=out, layouts=True)
    rooms = sum(len(h['rooms']) for h in result.houses.values())
    left = [line for line in result.report.lines if line.what == 'layout']
    print(f'{fmt}: {result.report.totals()["rooms_kept"]} rooms kept, {len(result.houses)} '
          f'house layouts of {rooms} rooms, {len(left)} rooms or houses left out')
    for line in left[:10]:
        print(f"  {line.text}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=200, help='procedural plans')
    ap.add_argument('--seed', type=int, default=0, help='plan seed')
    ap.add_argument('--import', dest='data', nargs='+', metavar=('FORMAT', 'PATH'),
                    help='a format (3dfront, suncg, procthor) and its files or folders')
    args = ap.parse_args(argv)
    plans(args.n, args.seed)
    at_the_limits()
    if args.data:
        if len(args.data) < 2:
            ap.error('--import takes a format and at least one path')
        imported(args.data[0], args.data[1:])
    return 0


if __name__ == '__main__':
    sys.exit(main())
