"""What the owed partners do (``SynthConfig.owed_partners``): when the category module says
STOP while a coffee table has no seating or a double bed no nightstand, synthesis draws one
of the partners' categories instead; this counts those draws and what came of them.

    .venv/bin/python benchmarks/owed_partners.py [-n 1000] [--room-type office]
                                                [--weights-dir DIR]

Synthesized rooms are the held-out shells furnished with synthesis seed = index, as in
``design_rules.py`` and the evaluation. Printed: the coffee tables and double beds of the
rooms and how many still break their rule at the end; every owed draw, by what it placed or
why it placed nothing (``nothing_fits``: no drawn partner category found a place). The draws
are counted by wrapping ``Synthesizer._insert_one`` on the instance (this process only); it
changes no room.
"""
import argparse
from collections import Counter
from pathlib import Path
import sys

import torch

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import empty_room  # noqa: E402
from scene_synth_ros.evaluation.design_rules import groups  # noqa: E402
from scene_synth_ros.synth import Synthesizer  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=1000, help='held-out rooms')
    ap.add_argument('--room-type', default='office')
    ap.add_argument('--weights-dir', default=None, help="default: the package's weights/")
    args = ap.parse_args()
    torch.set_num_threads(1)
    syn = Synthesizer(args.weights_dir)
    draws = Counter()
    insert_one = syn._insert_one

    def counted(ctx, scene, allow_stop=True, only=None):
        obj, why = insert_one(ctx, scene, allow_stop, only)
        if only is not None:       # the owed draw: only the partners' categories
            draws[f'placed: {obj.category}' if obj is not None else why] += 1
        return obj, why

    syn._insert_one = counted
    cases = Counter()
    for i in range(args.n):
        scene = syn.generate(empty_room(args.room_type, HELDOUT_SEED, i), seed=i).scene
        for name in syn.config.owed_partners:
            kept, total = getattr(groups, name)(scene)     # the rule's measure
            cases[(name, 'cases')] += total
            cases[(name, 'broken at the end')] += total - kept
    print(f'{args.room_type}: {args.n} held-out shells synthesized (seed = index)')
    for (name, what), v in sorted(cases.items()):
        print(f'  {name:28s} {what:20s} {v:5d}')
    print('  owed draws: ' + (', '.join(f'{k} {v}' for k, v in draws.most_common())
                              or 'none'))
    return 0


if __name__ == '__main__':
    sys.exit(main())
