"""How long training took: the seconds each module's training ran, per room type, read from
the JSON-lines logs a training run writes (``<run-dir>/<room type>/log.jsonl``).

    .venv/bin/python benchmarks/training_time.py [--run-dir runs/compact]

The figure is the last run of each module (a module resumed from a checkpoint counts from
the resumption). Validation passes are included, the corpus generation is not; training
runs that share the cores with others are slower than alone.
"""
import argparse
import json
from pathlib import Path
import sys

from scene_synth_ros.networks import NETWORKS as MODULES


def module_seconds(logs: list[Path]) -> dict[str, float]:
    """Seconds of the last run of each module (the one whose weights were exported): each run
    logs its seconds since it started, so the last value logged is that run's duration."""
    out = {m: 0.0 for m in MODULES}
    for log in logs:
        for line in log.read_text().splitlines():
            e = json.loads(line)
            if e.get('module') in out and 'seconds' in e:
                out[e['module']] = e['seconds']
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--run-dir', default='runs/compact')
    args = ap.parse_args()
    if not Path(args.run_dir).is_dir():
        print(f'{args.run_dir} is not a directory: give the --run-dir of a training run '
              f'(scene-synth train --run-dir DIR)', file=sys.stderr)
        return 2
    total = 0.0
    print(f'{"room type":10s} ' + ' '.join(f'{m:>11s}' for m in MODULES) + f' {"total":>9s}')
    for room in sorted(p for p in Path(args.run_dir).iterdir() if p.is_dir()):
        # Older logs of the same room (renamed log.*.jsonl) come first.
        logs = sorted(room.glob('log*.jsonl'), key=lambda f: (f.name == 'log.jsonl', f.name))
        if not logs:
            continue
        sec = module_seconds(logs)
        total += sum(sec.values())
        print(f'{room.name:10s} ' + ' '.join(f'{sec[m] / 60:9.1f} m' for m in MODULES)
              + f' {sum(sec.values()) / 60:7.1f} m')
    print(f'all room types: {total / 3600:.2f} h of single-thread training')
    return 0


if __name__ == '__main__':
    sys.exit(main())
