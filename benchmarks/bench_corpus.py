"""How fast the procedural corpus is made: the issue's reference job, 5,000 bedrooms written
as JSON with `scene-synth corpus --room-type bedroom -n 5000 --out DIR --seed 0`.

    .venv/bin/python benchmarks/bench_corpus.py [-n 5000] [--room-type bedroom]
"""
import argparse
import os
from pathlib import Path
import subprocess
import sys
import tempfile
import time

ROOT = Path(__file__).resolve().parent.parent


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('-n', type=int, default=5000)
    ap.add_argument('--room-type', default='bedroom')
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as out:
        cmd = [sys.executable, '-m', 'scene_synth_ros.cli', 'corpus', '--room-type',
               args.room_type, '-n', str(args.n), '--out', out, '--seed', '0', '--quiet']
        t0 = time.perf_counter()
        subprocess.run(cmd, check=True, cwd=ROOT)
        elapsed = time.perf_counter() - t0
        files = list(Path(out).glob('*.json'))
        size = sum(f.stat().st_size for f in files)
    print(f'{args.n} {args.room_type} rooms on {os.cpu_count()} cores: {elapsed:.1f} s '
          f'({1000 * elapsed / args.n:.1f} ms a room, {len(files)} files, '
          f'{size / 1e6:.1f} MB of JSON)')


if __name__ == '__main__':
    main()
