"""Where the location module puts a seat when a desk is there, and a nightstand when a bed is
there: the share of its distribution that falls where the design rule wants the piece.

    .venv/bin/python benchmarks/location_heatmaps.py [-n 150] [--weights-dir DIR]
                                                     [--figure out.png]

In held-out corpus rooms (seed ``corpus.HELDOUT_SEED``) with an office chair seated at a desk
(offices) or a stand at the head of a bed (bedrooms), that piece is removed and the location
module is asked, for its category, where it goes in the room that remains. The *share* is the
mass of the masked, tempered distribution (masked to the free floor only, as with no design
rule kept at insertion) whose pixel centres lie
in the rule's zone: in front of the desk, within its width and up to 0.9 m out (a seat's centre
0.6 m from the desk plus half a seat); beside the bed's first 0.6 m from the headboard, up to
0.6 m out from its side. The mean share over the rooms is printed (a network that learnt the
relation puts most of the mass there; 1.0 at most), with ``--figure`` four examples of each.
"""
import argparse
from pathlib import Path
import sys

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import torch  # noqa: E402

from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import generate_corpus  # noqa: E402
from scene_synth_ros.evaluation.design_rules import groups  # noqa: E402
from scene_synth_ros.networks.location import location_distribution  # noqa: E402
from scene_synth_ros.scene import Scene  # noqa: E402
from scene_synth_ros.synth import SynthConfig, Synthesizer  # noqa: E402

CASES = {   # room type: (category removed, partner categories, zone test in the partner's frame)
    'office': ('office chair', ('desk',),
               lambda x, y, p: (x >= p.depth / 2) & (x <= p.depth / 2 + 0.9)
               & (np.abs(y) <= p.width / 2)),
    'bedroom': ('stand', groups.BEDS_WITH_HEAD,
                lambda x, y, p: (x <= -p.depth / 2 + groups.HEAD_END)
                & (np.abs(y) >= p.width / 2) & (np.abs(y) <= p.width / 2 + 0.6)),
}


def pairs(scene: Scene, room_type: str):
    """(piece, partner) pairs of the case in one room."""
    category, partners, _ = CASES[room_type]
    for piece in scene.first_tier:
        if piece.category != category:
            continue
        for partner in scene.first_tier:
            if partner.category in partners and (
                    groups.seated_at(piece, partner) if room_type == 'office'
                    else groups.at_head_of(piece, partner)):
                yield piece, partner
                break


def share(synth: Synthesizer, scene: Scene, piece, partner, room_type: str):
    """The distribution over the grid for the piece's category in the room without it, and
    the mass of it in the zone beside the partner."""
    rest = Scene(scene.room, [o for o in scene.objects
                              if o.id != piece.id and o.support != piece.id])
    ctx = synth._context(scene.room, 0, rest.objects)
    image, small = synth._top_down(ctx, rest)
    with torch.no_grad():
        logits = ctx.bundle.networks['location'](image)[0]
    c = ctx.spec.index(piece.category)
    p = location_distribution(logits, c, synth._mask(ctx, rest, piece.category, small)[0],
                              synth.config.location_temperature)
    if p is None:
        return None, 0.0
    n = p.shape[0]
    ii, jj = np.meshgrid(np.arange(n), np.arange(n), indexing='ij')
    xy = ctx.grid.pixel_to_world(np.stack([ii, jj], -1)).reshape(-1, 2)
    d = xy - np.asarray(partner.position[:2])
    cos, sin = np.cos(partner.yaw), np.sin(partner.yaw)
    x, y = d[:, 0] * cos + d[:, 1] * sin, d[:, 1] * cos - d[:, 0] * sin
    zone = CASES[room_type][2](x, y, partner).reshape(n, n)
    return p, float(p[zone].sum())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=150, help='held-out rooms per room type')
    ap.add_argument('--weights-dir', default=None, help="default: the package's weights/")
    ap.add_argument('--figure', default=None, help='PNG with four examples per case')
    args = ap.parse_args()
    torch.set_num_threads(1)
    # No design rule kept at insertion: its mask would confine a group piece to where a
    # partner could have it, and the share would measure the mask, not the module.
    synth = Synthesizer(args.weights_dir, SynthConfig(insertion_rules=()))
    examples = []
    print(f'location mass in the rule\'s zone, {args.n} held-out rooms per type')
    for rt in CASES:
        shares = []
        for scene in generate_corpus(rt, args.n, seed=HELDOUT_SEED, workers=1):
            for piece, partner in pairs(scene, rt):
                p, s = share(synth, scene, piece, partner, rt)
                shares.append(s)
                if p is not None and len([e for e in examples if e[0] == rt]) < 4:
                    examples.append((rt, piece, p, s))
        print(f'{rt:8s} {CASES[rt][0]:13s} at its {CASES[rt][1][0]}: mean share '
              f'{np.mean(shares):.3f} over {len(shares)} cases (median {np.median(shares):.3f})')
    if args.figure:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(2, 4, figsize=(12, 6.4))
        for ax, (rt, piece, p, s) in zip(axes.ravel(), examples, strict=False):
            ax.imshow(p, cmap='magma')
            ax.set_title(f'{rt}: {piece.category}, share {s:.2f}', fontsize=9)
            ax.axis('off')
        fig.tight_layout()
        fig.savefig(args.figure, dpi=80)
        print(f'figure: {args.figure}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
