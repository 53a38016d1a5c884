"""How far first-tier furniture stands from the walls: corpus rooms, and rooms synthesized
with and without the contact step (``synth.against_walls``), in the same held-out shells.

    .venv/bin/python benchmarks/wall_contact.py [-n 150] [--room-type all]
"""
import argparse
from pathlib import Path
import sys

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scene_synth_ros.categories import ROOM_TYPES  # noqa: E402
from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import empty_room, generate_room  # noqa: E402
from scene_synth_ros.evaluation.plausibility import AGAINST_WALL, NEAR_WALL  # noqa: E402
from scene_synth_ros.synth import SynthConfig, Synthesizer  # noqa: E402


def gaps(scenes) -> np.ndarray:
    return np.array([s.room.polygon.exterior.distance(o.footprint())
                     for s in scenes for o in s.first_tier])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=150, help='rooms per room type and source')
    ap.add_argument('--room-type', default='all')
    args = ap.parse_args()
    import torch
    torch.set_num_threads(2)
    room_types = ROOM_TYPES if args.room_type == 'all' else (args.room_type,)
    with_step, without = Synthesizer(), Synthesizer(config=SynthConfig(wall_reach=0.0))
    print(f'first-tier objects by distance to the nearest wall, {args.n} rooms per type and '
          f'source (held-out shells, seeds 0..{args.n - 1})')
    print(f'{"room type":10s} {"rooms":24s} {"objects":>8s} {"<= 2 cm":>8s} {"2-15 cm":>8s} '
          f'{"median":>8s}')
    for rt in room_types:
        rows = {
            'corpus': [generate_room(rt, HELDOUT_SEED, i) for i in range(args.n)],
            'synthesized, no contact': [without.generate(empty_room(rt, HELDOUT_SEED, i),
                                                         seed=i).scene for i in range(args.n)],
            'synthesized (default)': [with_step.generate(empty_room(rt, HELDOUT_SEED, i),
                                                         seed=i).scene for i in range(args.n)],
        }
        for name, scenes in rows.items():
            g = gaps(scenes)
            print(f'{rt:10s} {name:24s} {len(g):8d} {np.mean(g <= AGAINST_WALL):8.1%} '
                  f'{np.mean((g > AGAINST_WALL) & (g < NEAR_WALL)):8.1%} '
                  f'{np.median(g):7.3f}m')
    return 0


if __name__ == '__main__':
    sys.exit(main())
