"""What the shipped networks get right on held-out corpus rooms (corpus seed 5, never seen in
training), beyond the component table: whether the category module's STOP is calibrated
(mean predicted probability against the observed rate, overall and by objects present),
how often a sampled orientation is more than 90 degrees off, and the relative error of
sampled footprints.

    .venv/bin/python benchmarks/module_diagnostics.py [--room-type all] [--rooms 200]
"""
import argparse
import math
from pathlib import Path
import sys

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import torch  # noqa: E402

from scene_synth_ros.categories import ROOM_TYPES  # noqa: E402
from scene_synth_ros.corpus.generate import generate_corpus  # noqa: E402
from scene_synth_ros.networks.examples import ExampleSource  # noqa: E402
from scene_synth_ros.networks.orientation import decode_angle  # noqa: E402
from scene_synth_ros.synth import Synthesizer  # noqa: E402

DIAGNOSTIC_SEED = 5   # corpus rooms neither training (0) nor the evaluation (1) uses


def diagnose(synth: Synthesizer, rt: str, rooms: int) -> None:
    b = synth.bundle(rt)
    m = b.config.model
    src = ExampleSource(rt, list(generate_corpus(rt, rooms, seed=DIAGNOSTIC_SEED)),
                        m.resolution, m.location_resolution)
    with torch.inference_mode():
        cat = src.batch('category', [DIAGNOSTIC_SEED, 0], 1024)
        p_stop = torch.softmax(b.networks['category'](cat['image'], cat['counts']), -1)[:, -1]
        stop = (cat['target'] == src.num_categories).float()
        present = cat['counts'].sum(1)
        ori = src.batch('orientation', [DIAGNOSTIC_SEED, 1], 512)
        out = b.networks['orientation'].sample(ori['image'], ori['category'],
                                               torch.Generator().manual_seed(0))
        theta = decode_angle(out, torch.Generator().manual_seed(1))
        dim = src.batch('dimensions', [DIAGNOSTIC_SEED, 2], 512)
        log_dims = b.networks['dimensions'].sample(dim['image'], dim['category'],
                                                   torch.Generator().manual_seed(0))
    err = (torch.remainder(theta - ori['theta'] + math.pi, 2 * math.pi) - math.pi).abs()
    rel = (log_dims - dim['target']).abs().exp() - 1
    print(f'{rt}: STOP predicted {p_stop.mean():.3f} vs observed {stop.mean():.3f} '
          f'(1,024 examples); orientation median error {math.degrees(err.median()):.1f} deg, '
          f'{(err > math.pi / 2).float().mean():.1%} off by more than 90 deg; footprint '
          f'median relative error {rel.median():.1%}')
    bins = [(lo, lo + 2) for lo in range(0, 12, 2)]
    cells = []
    for lo, hi in bins:
        sel = (present >= lo) & (present < hi)
        if sel.sum() >= 20:
            cells.append(f'{lo}-{hi - 1}: {p_stop[sel].mean():.2f}/{stop[sel].mean():.2f}')
    print('  STOP predicted/observed by objects present: ' + ', '.join(cells))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--rooms', type=int, default=200)
    args = ap.parse_args()
    torch.set_num_threads(1)
    synth = Synthesizer()
    for rt in (ROOM_TYPES if args.room_type == 'all' else [args.room_type]):
        diagnose(synth, rt, args.rooms)


if __name__ == '__main__':
    main()
