"""The procedural corpus as hashes, to tell whether a change altered any corpus room (the
shipped weights' training data), and how batches' shells (``corpus.generate.first_shell``)
compare with the corpus rooms' own (``empty_room``).

For each room type and each ``--blocks`` entry SEED:N (default: the training rooms, seed 0
rooms 0..5199, and the held-out ones, seed 1 rooms 0..999), prints the SHA-256 over the rooms'
``Scene.to_dict`` JSON and the CPU milliseconds a room took to make. Run it at two commits:
equal hashes, equal corpus. With ``--first-shells N``, then for rooms 0..N-1 of seed 0 of each
type: how many first shells differ from the corpus room's own shell, and the CPU
milliseconds a first shell takes.

    .venv/bin/python benchmarks/corpus_hash.py [--room-type all] [--blocks 0:5200 1:1000]
                                               [--first-shells 400]
"""
import argparse
import hashlib
import json
from pathlib import Path
import sys
import time

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scene_synth_ros.categories import ROOM_TYPES  # noqa: E402
from scene_synth_ros.corpus.generate import generate_room  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--blocks', nargs='*', default=['0:5200', '1:1000'],
                    help='SEED:N, rooms 0..N-1 of corpus seed SEED')
    ap.add_argument('--first-shells', type=int, default=0)
    args = ap.parse_args()
    room_types = ROOM_TYPES if args.room_type == 'all' else (args.room_type,)
    for rt in room_types:
        for block in args.blocks:
            seed, n = (int(v) for v in block.split(':'))
            digest = hashlib.sha256()
            t0 = time.process_time()
            for i in range(n):
                room = generate_room(rt, seed, i)
                digest.update(json.dumps(room.to_dict(), sort_keys=True).encode())
            ms = (time.process_time() - t0) / max(n, 1) * 1e3
            print(f'{rt:9s} seed {seed} rooms 0..{n - 1}: {digest.hexdigest()}  '
                  f'{ms:.2f} ms a room', flush=True)
    if args.first_shells > 0:
        # Imported here, so that the hashes can be made at commits before first_shell.
        from scene_synth_ros.corpus.generate import first_shell
    for rt in room_types:
        if args.first_shells <= 0:
            break
        n, differ, spent = args.first_shells, 0, 0.0
        for i in range(n):
            t0 = time.process_time()
            shell = first_shell(rt, 0, i)
            spent += time.process_time() - t0
            differ += shell != generate_room(rt, 0, i).room
        print(f'{rt:9s} first shells of seed 0 rooms 0..{n - 1}: {differ} of {n} '
              f'({differ / n:.2%}) differ from the corpus room\'s own; '
              f'{spent / n * 1e3:.2f} ms a first shell', flush=True)
    return 0


if __name__ == '__main__':
    sys.exit(main())
