"""How long one room takes in a fresh process, as ``scene-synth generate`` makes it: what the
cache of exported graphs (``networks.runtime.graph_cache_dir``) saves a process that
furnishes one room.

    .venv/bin/python benchmarks/first_room.py [-n 5] [--room-type bedroom]

Each timed run is a fresh ``python -m scene_synth_ros.cli generate --room-type T --seed i
--out F`` (the console script's code, without its wrapper), in three settings taken in turn:
torch; onnxruntime with no cache (``SCENE_SYNTH_ROS_CACHE=off``: the process exports its
graphs); onnxruntime with the graphs cached (a directory filled by one untimed run first).
Prints the median and the range of the wall seconds of each, start-up and imports included.
"""
import argparse
import os
from pathlib import Path
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = Path(__file__).resolve().parent.parent


def run(room_type: str, seed: int, out: Path, runtime: str, cache: str) -> float:
    env = dict(os.environ, SCENE_SYNTH_ROS_CACHE=cache, OMP_NUM_THREADS='1')
    cmd = [sys.executable, '-m', 'scene_synth_ros.cli', 'generate', '--room-type', room_type,
           '--seed', str(seed), '--runtime', runtime, '--out', str(out)]
    t = time.perf_counter()
    subprocess.run(cmd, env=env, cwd=ROOT, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('-n', type=int, default=5, help='runs of each setting')
    ap.add_argument('--room-type', default='bedroom')
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        cache = tmp / 'graphs'
        settings = {'torch': ('torch', 'off'), 'onnxruntime, no cache': ('onnxruntime', 'off'),
                    'onnxruntime, cached': ('onnxruntime', str(cache))}
        run(args.room_type, 0, tmp / 'room.json', 'onnxruntime', str(cache))   # fills it
        seconds: dict[str, list[float]] = {name: [] for name in settings}
        for i in range(args.n):
            for name, (runtime, where) in settings.items():
                seconds[name].append(run(args.room_type, i, tmp / 'room.json', runtime, where))
    print(f'one {args.room_type} in a fresh process (scene-synth generate), {args.n} runs each, '
          'wall seconds:')
    for name, s in seconds.items():
        print(f'  {name:>22s}: median {statistics.median(s):.2f} (range {min(s):.2f}-'
              f'{max(s):.2f})')
    return 0


if __name__ == '__main__':
    sys.exit(main())
