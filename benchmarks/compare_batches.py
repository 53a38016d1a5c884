"""How far the rooms of two batch directories (``scene-synth generate -n N --out DIR``) are
from each other: the rooms both hold, how many are identical file for file, how many have
the same objects (category, model) at the same places to ``--mm`` millimetres and yaws to
``--mrad`` milliradians, and which differ beyond that.

A change meant to leave the rooms alone (a faster path to the same numbers) is checked with
the same batch command at the commit before it and after it:

    .venv/bin/python benchmarks/compare_batches.py BEFORE_DIR AFTER_DIR [--mm 1] [--mrad 1]
"""
import argparse
import json
import math
from pathlib import Path
import sys


def _objects(path: Path) -> list[dict]:
    return json.loads(path.read_text(encoding='utf-8'))['objects']


def _close(a: list[dict], b: list[dict], mm: float, mrad: float) -> bool:
    """The same objects in the same order, each at the same place to ``mm`` and turned the
    same to ``mrad`` (yaws compared round the circle)."""
    if len(a) != len(b):
        return False
    for x, y in zip(a, b, strict=True):
        if any(x.get(k) != y.get(k) for k in ('category', 'model_id', 'support')):
            return False
        if max(abs(p - q) for p, q in zip(x['position'], y['position'], strict=True)) \
                > mm / 1000:
            return False
        turn = abs(math.remainder(x['yaw'] - y['yaw'], 2 * math.pi))
        if turn > mrad / 1000:
            return False
    return True


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('before', type=Path)
    ap.add_argument('after', type=Path)
    ap.add_argument('--mm', type=float, default=1.0)
    ap.add_argument('--mrad', type=float, default=1.0)
    args = ap.parse_args()
    names = {}
    for side in (args.before, args.after):
        scenes = side / 'scenes'
        if not scenes.is_dir():
            print(f'{side} is not a batch directory: it has no scenes/ folder')
            return 1
        names[side] = {p.name for p in scenes.glob('*.json')}
    both = sorted(names[args.before] & names[args.after])
    identical = near = 0
    differ = []
    for name in both:
        a, b = args.before / 'scenes' / name, args.after / 'scenes' / name
        if a.read_bytes() == b.read_bytes():
            identical += 1
        elif _close(_objects(a), _objects(b), args.mm, args.mrad):
            near += 1
        else:
            differ.append(name)
    print(f'{len(both)} rooms in both ({len(names[args.before]) - len(both)} only before, '
          f'{len(names[args.after]) - len(both)} only after): {identical} identical, '
          f'{near} with the same objects to {args.mm:g} mm and {args.mrad:g} mrad, '
          f'{len(differ)} different' + (f' ({", ".join(differ[:10])}'
                                         f'{" …" if len(differ) > 10 else ""})' if differ else ''))
    return 0


if __name__ == '__main__':
    sys.exit(main())
