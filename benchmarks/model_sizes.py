"""How large the furniture of synthesized rooms is against the corpus's: which catalog models
insertion retrieves, and what footprints the dimensions module asked for.

    .venv/bin/python benchmarks/model_sizes.py [-n 200] [--room-type bedroom]
                                              [--weights-dir DIR] [--min-count 30]
                                              [--fit-slack S]

Synthesized rooms are the held-out shells furnished with synthesis seed = index, as in
``design_rules.py``; corpus rooms are those held-out rooms themselves. Per category with at
least ``--min-count`` objects in the corpus rooms, by corpus count:

- objects, synthesized / corpus;
- the mean rank of the model among its category's catalog models (0: the narrowest; the
  catalog's models are ordered by width), synthesized / corpus;
- the share of objects among the wider half of the catalog's models, synthesized / corpus;
- the width the dimensions module drew (every draw, tried or not: its 10th, 50th and 90th
  percentile) against the catalog's narrowest, median and widest model.

``--fit-slack`` sets ``SynthConfig.fit_slack`` (default SynthConfig's). The dimensions
module is counted by wrapping ``Synthesizer._dimensions`` on the instance
(this process only); it changes no room.
"""
import argparse
from collections import Counter, defaultdict
from pathlib import Path
import sys

import numpy as np
import torch

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scene_synth_ros import catalog  # noqa: E402
from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import empty_room, generate_room  # noqa: E402
from scene_synth_ros.synth import SynthConfig, Synthesizer  # noqa: E402


def ranks(scenes, room_type: str) -> dict[str, list[int]]:
    """Each object's model rank among its category's catalog models, per category."""
    out = defaultdict(list)
    order = {}
    for s in scenes:
        for o in s.objects:
            if o.category not in order:
                order[o.category] = {v.model_id: k for k, v in
                                     enumerate(catalog.variants(o.category, room_type))}
            if o.model_id in order[o.category]:
                out[o.category].append(order[o.category][o.model_id])
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=200, help='held-out rooms')
    ap.add_argument('--room-type', default='bedroom')
    ap.add_argument('--weights-dir', default=None, help="default: the package's weights/")
    ap.add_argument('--min-count', type=int, default=30)
    ap.add_argument('--fit-slack', type=float, default=None)
    args = ap.parse_args()
    torch.set_num_threads(1)
    rt = args.room_type
    cfg = SynthConfig()
    if args.fit_slack is not None:
        cfg.fit_slack = args.fit_slack
    syn = Synthesizer(args.weights_dir, cfg)
    drawn = defaultdict(list)
    dimensions = syn._dimensions

    def counted(ctx, scene, c, points, yaws):
        out = dimensions(ctx, scene, c, points, yaws)
        drawn[ctx.spec.names[c]] += [width for _depth, width in out]
        return out

    syn._dimensions = counted
    synthesized = [syn.generate(empty_room(rt, HELDOUT_SEED, i), seed=i).scene
                   for i in range(args.n)]
    corpus = [generate_room(rt, HELDOUT_SEED, i) for i in range(args.n)]
    a, b = ranks(synthesized, rt), ranks(corpus, rt)
    counts = Counter({c: len(v) for c, v in b.items()})
    print(f'{rt}: {args.n} held-out shells synthesized (seed = index) / the held-out corpus '
          f'rooms\n')
    print(f'  {"category":16s} {"objects":>11s} {"mean rank":>11s} {"wider half":>13s}   '
          f'drawn width q10 / q50 / q90    catalog widths min / median / max')
    for c, _ in counts.most_common():
        if counts[c] < args.min_count:
            break
        models = catalog.variants(c, rt)
        widths = np.array([v.width for v in models])
        half = len(models) // 2
        sa, sb = np.asarray(a.get(c, []), float), np.asarray(b[c], float)
        mean_a = f'{sa.mean():4.2f}' if len(sa) else '   –'
        wide_a = f'{np.mean(sa >= half):5.1%}' if len(sa) else '    –'
        w = np.asarray(drawn.get(c, []))
        spread = (' / '.join(f'{q:4.2f}' for q in np.percentile(w, [10, 50, 90]))
                  if len(w) else '–')
        print(f'  {c:16s} {len(sa):5d}/{len(sb):5d} {mean_a}/{sb.mean():4.2f}  '
              f'{wide_a}/{np.mean(sb >= half):5.1%}   {spread:28s}   '
              f'{widths.min():4.2f} / {np.median(widths):4.2f} / {widths.max():4.2f}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
