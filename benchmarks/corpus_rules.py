"""The procedural corpus against the design rules and the paper's table, per room type.

    .venv/bin/python benchmarks/corpus_rules.py [-n 500] [--room-type all] [--seed 0]
                                                [--before REV] [--workers 2]

Generates rooms 0..n-1 of corpus ``--seed`` (seed 0 is the training data) and prints, per room
type, every design rule's rate, KL(corpus || table), objects per room against the table's
mean, invalid rooms and milliseconds per room. With ``--before REV`` it also generates the same
rooms with the corpus code of git revision REV (in a temporary worktree, in a subprocess) and
measures them with today's rules, so each figure is printed before and after. Issue 11's
targets for the corpus: KL <= 0.01 and objects per room within 5 % of the table.
"""
import argparse
import json
from pathlib import Path
import subprocess
import sys
import tempfile
import time

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scene_synth_ros.categories import ROOM_TYPES, room_spec  # noqa: E402
from scene_synth_ros.corpus.stats import collect  # noqa: E402
from scene_synth_ros.evaluation.design_rules import measure, rules, totals  # noqa: E402
from scene_synth_ros.parallel import process_pool  # noqa: E402
from scene_synth_ros.scene import Scene  # noqa: E402

# Run inside the old revision's worktree: its corpus code, rooms out as JSON lines.
_DUMP = '''
import json, sys
from scene_synth_ros.corpus.generate import generate_corpus
rt, n, seed, workers = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
for s in generate_corpus(rt, n, seed=seed, workers=workers):
    print(json.dumps(s.to_dict()))
'''


def _measure(d: dict) -> dict:
    return measure(Scene.from_dict(d))


def current_rooms(rt: str, n: int, seed: int, workers: int) -> tuple[list[dict], float]:
    from scene_synth_ros.corpus.generate import generate_corpus
    t0 = time.perf_counter()
    rooms = [s.to_dict() for s in generate_corpus(rt, n, seed=seed, workers=workers)]
    return rooms, time.perf_counter() - t0


def old_rooms(tree: Path, rt: str, n: int, seed: int, workers: int) -> tuple[list[dict], float]:
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, '-c', _DUMP, rt, str(n), str(seed), str(workers)],
                         cwd=tree, env={'PYTHONPATH': str(tree), 'PATH': '/usr/bin:/bin'},
                         check=True, capture_output=True, text=True).stdout
    return [json.loads(line) for line in out.splitlines()], time.perf_counter() - t0


def summary(rt: str, rooms: list[dict], seconds: float, workers: int) -> dict:
    with process_pool(workers) as pool:
        rows = pool.map(_measure, rooms, chunksize=8)
    stats = collect(rt, (Scene.from_dict(d) for d in rooms))
    return {'rates': totals(rows, rules()), 'kl': stats.kl_to_table,
            'objects': stats.objects_per_room, 'invalid': stats.invalid,
            'ms': 1000 * seconds * workers / max(len(rooms), 1)}


def _cell(rate) -> str:
    return f'{rate.value:7.1%} ({rate.cases:5d})' if rate.cases else f'{"–":>7s} ({0:5d})'


def report(rt: str, after: dict, before: dict | None) -> None:
    spec = room_spec(rt)
    table = spec.mean_objects_per_room
    cols = ['before', 'after'] if before else ['corpus']
    sides = [before, after] if before else [after]
    print(f'\n{rt}\n  {"":30s} ' + ' '.join(f'{c:>15s}' for c in cols))
    for r in rules():
        if not any(s['rates'][r.name].cases for s in sides):
            continue
        print(f'  {r.name:30s} ' + ' '.join(_cell(s['rates'][r.name]) for s in sides))
    print(f'  {"KL(corpus||table) <= 0.01":30s} ' + ' '.join(f'{s["kl"]:15.4f}' for s in sides))
    print(f'  {f"objects/room (table {table:.2f})":30s} ' + ' '.join(
        f'{s["objects"]:8.2f} ({100 * (s["objects"] / table - 1):+4.1f}%)' for s in sides))
    print(f'  {"invalid rooms":30s} ' + ' '.join(f'{s["invalid"]:15d}' for s in sides))
    print(f'  {"ms per room per core":30s} ' + ' '.join(f'{s["ms"]:15.1f}' for s in sides))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=500, help='rooms per room type')
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--seed', type=int, default=0)
    ap.add_argument('--before', metavar='REV', help='also measure the corpus of this revision')
    ap.add_argument('--workers', type=int, default=2)
    args = ap.parse_args()
    room_types = ROOM_TYPES if args.room_type == 'all' else (args.room_type,)
    with tempfile.TemporaryDirectory() as scratch:
        tree = None
        if args.before:
            tree = Path(scratch) / 'before'
            subprocess.run(['git', 'worktree', 'add', '--detach', '-q', str(tree), args.before],
                           cwd=ROOT, check=True)
        try:
            print(f'corpus seed {args.seed}, rooms 0..{args.n - 1} per type'
                  + (f'; before = {args.before}, after = working tree' if tree else ''))
            for rt in room_types:
                after = summary(rt, *current_rooms(rt, args.n, args.seed, args.workers),
                                args.workers)
                before = (summary(rt, *old_rooms(tree, rt, args.n, args.seed, args.workers),
                                  args.workers) if tree else None)
                report(rt, after, before)
        finally:
            if tree:
                subprocess.run(['git', 'worktree', 'remove', '--force', str(tree)], cwd=ROOT,
                               check=False)
    return 0


if __name__ == '__main__':
    sys.exit(main())
