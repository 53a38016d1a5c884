"""``scene-synth corpus``, ``corpus-stats`` and ``corpus-calibrate``: the procedural rooms
the networks train on, written as JSON, compared with the paper's table, and calibrated; and
``house-plans``: procedural empty houses."""
from __future__ import annotations

import json
from pathlib import Path
import time

from ..categories import CORPUS, CORPUS_ROOM_TYPES
from .common import UserError, load_scene_file, room_types


def add_parser(sub) -> None:
    c = sub.add_parser('corpus', help='generate procedural furnished rooms as JSON scenes')
    c.add_argument('--room-type', default='bedroom', help=f'{"|".join(CORPUS_ROOM_TYPES)}|all')
    c.add_argument('-n', type=int, default=100, help='rooms per room type')
    c.add_argument('--out', required=True, help='output directory')
    c.add_argument('--seed', type=int, default=0, help='corpus seed: the same seed gives the '
                   'same rooms')
    c.add_argument('--workers', type=int, default=None, help='processes (default: all cores)')
    c.add_argument('--quiet', action='store_true', help='no progress bar')
    c.set_defaults(func=cmd_corpus)

    c = sub.add_parser('house-plans', help='procedural house plans: empty house layouts '
                       '(msg_schemas/house_layout.schema.json) of rooms along a hallway')
    c.add_argument('-n', type=int, default=10, help='how many plans')
    c.add_argument('--out', required=True, help='output directory (house_00000.json, ...)')
    c.add_argument('--seed', type=int, default=0, help='plan seed: the same seed gives the '
                   'same plans')
    c.add_argument('--rooms', help='the room types of every plan, comma-separated (e.g. '
                   'living,kitchen,bedroom,bathroom; default: drawn from the programmes of '
                   'corpus/house_plan.py)')
    c.add_argument('--quiet', action='store_true', help='print nothing')
    c.set_defaults(func=cmd_house_plans)

    c = sub.add_parser('corpus-stats', help="compare the corpus with the paper's table")
    c.add_argument('--room-type', default='all', help=f'{"|".join(CORPUS_ROOM_TYPES)}|all')
    c.add_argument('-n', type=int, default=2000, help='rooms per type to generate')
    c.add_argument('--seed', type=int, default=0, help='corpus seed')
    c.add_argument('--dir', help='read scenes from this directory instead of generating')
    c.add_argument('--workers', type=int, default=None, help='processes (default: all cores)')
    c.add_argument('--categories', action='store_true', help='print per-category rates')
    c.add_argument('--json', help='also write the summary rows to this JSON file')
    c.set_defaults(func=cmd_corpus_stats)

    c = sub.add_parser('corpus-calibrate', help="fit how often the corpus asks for each "
                       "category, so that its rooms match the paper's table (written to "
                       "corpus/calibration.json)")
    c.add_argument('--room-type', default='all', help=f'{"|".join(CORPUS_ROOM_TYPES)}|all')
    c.add_argument('--rooms', type=int, default=2000, help='rooms per type and iteration')
    c.add_argument('--iterations', type=int, default=3, help='rounds of fitting')
    c.add_argument('--seed', type=int, default=12345, help='first corpus seed of the rooms fitted '
                   'on (the training corpus is seed 0)')
    c.add_argument('--workers', type=int, default=None, help='processes (default: all cores)')
    c.set_defaults(func=cmd_corpus_calibrate)


def cmd_house_plans(args) -> int:
    from ..corpus.house_plan import PlanConfig, PlanError, house_plan
    from ..files import write_atomic
    from ..schema import format_json
    if args.n < 1:
        raise UserError(f'-n {args.n}: expected 1 or more plans')
    rooms = None
    if args.rooms:
        rooms = tuple(r.strip() for r in args.rooms.split(','))
        unknown = [r for r in rooms if r not in CORPUS_ROOM_TYPES or r == 'hallway']
        if unknown:
            raise UserError(f'--rooms names {unknown[0][:80]!r}: expected room types among '
                            f'{", ".join(t for t in CORPUS_ROOM_TYPES if t != "hallway")} '
                            '(the hallway is always there)')
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for i in range(args.n):
        try:
            house = house_plan(args.seed, i, PlanConfig(rooms))
        except PlanError as e:
            raise UserError(str(e)) from None
        write_atomic(out / f'house_{i:05d}.json', format_json(house.to_dict()) + '\n')
        if not args.quiet:
            kinds = ', '.join(r.room_type for r in house.rooms.values())
            print(f'house_{i:05d}.json: {len(house.rooms)} rooms, {house.area:.0f} m² '
                  f'({kinds})')
    return 0


def cmd_corpus(args) -> int:
    from tqdm import tqdm

    from ..corpus.generate import generate_corpus
    from ..schema import save_scene
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for rt in room_types(args.room_type, CORPUS):
        t0 = time.perf_counter()
        rooms = generate_corpus(rt, args.n, seed=args.seed, workers=args.workers)
        for i, scene in enumerate(tqdm(rooms, total=args.n, desc=rt, unit='room',
                                       disable=args.quiet)):
            save_scene(scene, out / f'{rt}_{i:05d}.json', vocabulary=CORPUS)
        if not args.quiet:
            print(f'{rt}: {args.n} rooms in {time.perf_counter() - t0:.1f} s -> {out}')
    return 0


def _scenes(rt: str, args):
    """The rooms of ``rt`` to count: read from ``--dir``, or generated."""
    from ..corpus.generate import generate_corpus
    if not args.dir:
        return generate_corpus(rt, args.n, seed=args.seed, workers=args.workers)
    files = sorted(Path(args.dir).glob(f'{rt}_*.json'))
    if not files:
        raise UserError(f'{args.dir}: no {rt}_*.json scene files')
    return (load_scene_file(str(f), vocabulary=CORPUS) for f in files)


def _print_summary(rows: list[dict]) -> None:
    print()
    print(f'{"room type":10s} {"rooms":>6s} {"KL(c||t)":>9s} {"KL(t||c)":>9s} '
          f'{"obj/room":>9s} {"table":>6s} {"diff":>7s} {"doors":>6s} {"table":>6s} '
          f'{"windows":>7s} {"table":>6s} {"L-shaped":>8s} {"invalid":>7s}')
    for r in rows:
        diff = r['objects_per_room'] / r['table_objects_per_room'] - 1
        print(f'{r["room_type"]:10s} {r["rooms"]:6d} {r["kl_corpus_table"]:9.4f} '
              f'{r["kl_table_corpus"]:9.4f} {r["objects_per_room"]:9.2f} '
              f'{r["table_objects_per_room"]:6.2f} {diff:+7.1%} {r["doors_per_room"]:6.2f} '
              f'{r["table_doors_per_room"]:6.2f} {r["windows_per_room"]:7.2f} '
              f'{r["table_windows_per_room"]:6.2f} {r["l_shaped_fraction"]:8.1%} '
              f'{r["invalid_rooms"]:7d}')


def cmd_corpus_stats(args) -> int:
    from ..corpus.stats import collect
    rows = []
    for rt in room_types(args.room_type, CORPUS):
        stats = collect(rt, _scenes(rt, args))
        rows.append(stats.summary_row())
        if args.categories:
            print(f'\n{rt}: objects per room, corpus vs. the paper\'s table')
            for name, here, table in stats.category_table():
                print(f'  {name:16s} {here:7.3f} {table:7.3f}')
    _print_summary(rows)
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1) + '\n')
    return 0


def cmd_corpus_calibrate(args) -> int:
    from ..corpus.calibrate import calibrate
    calibrate(rooms=args.rooms, iterations=args.iterations, seed=args.seed,
              room_types=room_types(args.room_type, CORPUS), workers=args.workers)
    return 0
