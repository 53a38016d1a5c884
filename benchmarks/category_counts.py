"""First-tier objects per category: held-out corpus rooms and the same shells synthesized.

    .venv/bin/python benchmarks/category_counts.py [--room-type bedroom] [-n 150] [--workers 2]
                                                   [--rules all|none|RULE,RULE...]

Room ``i`` is the held-out corpus room (seed ``corpus.HELDOUT_SEED``) and its empty shell
furnished with synthesis seed ``i``, as in ``design_rules.py``; categories are listed by
their count in the corpus. ``--rules`` chooses the design rules kept at insertion (default
``all``: ``SynthConfig``'s), to see what each costs in the category distribution.
"""
import argparse
from collections import Counter
from pathlib import Path
import sys

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import empty_room, generate_room  # noqa: E402
from scene_synth_ros.parallel import process_pool  # noqa: E402

_synth = None


def _init_worker(rules):
    global _synth
    import torch
    torch.set_num_threads(1)
    from scene_synth_ros.synth import SynthConfig, Synthesizer
    _synth = Synthesizer(None, SynthConfig() if rules is None
                         else SynthConfig(insertion_rules=rules))


def _first_tier(job):
    rt, i = job
    scene = _synth.generate(empty_room(rt, HELDOUT_SEED, i), seed=i).scene
    return [o.category for o in scene.objects if o.support is None]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--room-type', default='bedroom')
    ap.add_argument('-n', type=int, default=150)
    ap.add_argument('--workers', type=int, default=2)
    ap.add_argument('--rules', default='all')
    args = ap.parse_args()
    rules = {'all': None, 'none': ()}.get(args.rules)
    if args.rules not in ('all', 'none'):
        rules = tuple(r for r in args.rules.split(',') if r)
    jobs = [(args.room_type, i) for i in range(args.n)]
    with process_pool(args.workers, _init_worker, (rules,)) as pool:
        synthesized = Counter(c for cats in pool.map(_first_tier, jobs) for c in cats)
    corpus = Counter(o.category for _, i in jobs
                     for o in generate_room(args.room_type, HELDOUT_SEED, i).objects
                     if o.support is None)
    print(f'first-tier objects in {args.n} {args.room_type} rooms (insertion rules: '
          f'{args.rules})\n  {"category":16s} {"corpus":>6s} {"synthesized":>11s} {"diff":>5s}')
    for c in sorted(set(corpus) | set(synthesized), key=lambda c: (-corpus[c], c)):
        print(f'  {c:16s} {corpus[c]:6d} {synthesized[c]:11d} {synthesized[c] - corpus[c]:+5d}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
