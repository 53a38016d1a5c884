"""What batching buys each module: milliseconds per forward pass and per sample, by batch size.

    .venv/bin/python benchmarks/batch_gain.py [--room-type bedroom] [--sizes 1,4,8,16,32]
                                              [--threads 1] [--device cpu] [--channels-last]
                                              [--fold]

Synthesis calls the category and location modules on one image per step and the orientation,
snap and dimensions modules on the few candidate placements of one location draw; rooms in
lockstep (issue 16) would stack those calls across rooms. This times the shipped networks
(float32, inference mode) on random images of the room type's channels at each batch size:
the median of 20 passes after 3 warm-ups. One torch thread by default, as a batch worker runs.
Last, how far a sample's outputs in the largest batch are from its outputs alone: zero would
let lockstep promise the very rooms of one-at-a-time synthesis; anything else, rooms equal in
distribution. ``--channels-last`` lays the networks' weights and the images out channels-last,
as synthesis does on the CPU (``Synthesizer._image``). ``--fold`` then times each pass
again with the batch norms folded into the convolutions (``blocks.fold_batch_norms``, as
synthesis runs the networks), interleaved with the unfolded pass, and prints what folding
gains per pass and how far the folded outputs are from the unfolded ones.
"""
import argparse
from functools import partial
from pathlib import Path
import statistics
import sys
import time

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


# The call synthesis makes of each module.
FORWARD = {'category': lambda net, x, counts: net(x, counts),
           'location': lambda net, x: net.predict(x),
           'orientation': lambda net, x, cat: net.sample(x, cat),
           'snap': lambda net, x, cat: net(x, cat),
           'dimensions': lambda net, x, cat: net.sample(x, cat)}


def median_ms(fn, repeats: int = 20) -> float:
    import torch
    with torch.inference_mode():
        for _ in range(3):
            fn()
        times = []
        for _ in range(repeats):
            t0 = time.perf_counter()
            fn()
            times.append(time.perf_counter() - t0)
    return statistics.median(times) * 1000


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--room-type', default='bedroom')
    ap.add_argument('--sizes', default='1,4,8,16,32')
    ap.add_argument('--threads', type=int, default=1)
    ap.add_argument('--device', default='cpu', choices=('cpu', 'cuda'))
    ap.add_argument('--channels-last', action='store_true')
    ap.add_argument('--fold', action='store_true')
    args = ap.parse_args()
    import torch
    torch.set_num_threads(args.threads)
    from scene_synth_ros.categories import room_spec
    from scene_synth_ros.networks.bundle import load_bundle
    from scene_synth_ros.paths import weights_dir
    from scene_synth_ros.render import num_channels
    bundle = load_bundle(weights_dir() / f'{args.room_type}.pt', args.device)
    nets = {name: net.float().eval() for name, net in bundle.networks.items()}
    layout = torch.channels_last if args.channels_last else torch.contiguous_format
    for net in nets.values():
        net.to(memory_format=layout)
    channels = num_channels(args.room_type)
    categories = len(room_spec(args.room_type).names)
    sizes = [int(s) for s in args.sizes.split(',')]
    print(f'{args.room_type}, {args.device}, {torch.get_num_threads()} torch thread(s), '
          f'{channels} channels, {bundle.config.model.resolution} px'
          + (', channels-last' if args.channels_last else ''))
    print(f'{"batch":>5s} ' + ' '.join(f'{m:>19s}' for m in nets))
    def inputs_for(b: int) -> dict:
        x = torch.randn(b, channels, bundle.config.model.resolution,
                        bundle.config.model.resolution, device=args.device
                        ).contiguous(memory_format=layout)
        cat = torch.zeros(b, dtype=torch.long, device=args.device)
        counts = torch.zeros(b, categories, device=args.device)
        return {'category': (x, counts), 'location': (x,), 'orientation': (x, cat),
                'snap': (x, cat), 'dimensions': (x, cat)}

    base = {}
    for b in sizes:
        cells = []
        for name, args_ in inputs_for(b).items():
            ms = median_ms(partial(FORWARD[name], nets[name], *args_))
            per = ms / b
            base.setdefault(name, per)
            cells.append(f'{ms:7.2f} {per:5.2f} x{base[name] / per:3.1f}')
        print(f'{b:5d} ' + ' '.join(f'{c:>19s}' for c in cells))
    print('each cell: milliseconds per pass, milliseconds per sample, and how many times '
          'cheaper a sample is than at the first batch size')
    # Whether a sample's outputs in a batch are those it gets alone: what rooms in lockstep
    # can promise (identical rooms, or rooms equal in distribution).
    b = max(sizes)
    x = torch.rand(b, channels, bundle.config.model.resolution,
                   bundle.config.model.resolution, device=args.device).round()
    cat = torch.arange(b, device=args.device) % categories
    counts = torch.rand(b, categories, device=args.device).round()
    deterministic = {'category': lambda i: nets['category'](x[i], counts[i]),
                     'location': lambda i: nets['location'].predict(x[i])[0],
                     'orientation': lambda i: nets['orientation'].condition(x[i], cat[i]),
                     'snap': lambda i: nets['snap'](x[i], cat[i]),
                     'dimensions': lambda i: nets['dimensions'].condition(x[i], cat[i])}
    with torch.inference_mode():
        diffs = {name: float((fn(slice(0, b)) - torch.cat(
            [fn(slice(k, k + 1)) for k in range(b)])).abs().max())
            for name, fn in deterministic.items()}
    print(f'largest difference between a batch of {b} and its samples alone (outputs, or the '
          'CVAEs\' conditions): ' + ', '.join(f'{k} {v:.2g}' for k, v in diffs.items()))
    if args.fold:
        _fold_gain(nets, deterministic, inputs_for, sizes, layout)
    return 0


def _fold_gain(nets, deterministic, inputs_for, sizes, layout) -> None:
    """Unfolded and folded passes timed in turn (three rounds, the best of each), and the
    largest difference of their outputs."""
    import copy

    import torch

    from scene_synth_ros.networks.blocks import fold_batch_norms
    folded = {name: fold_batch_norms(copy.deepcopy(net)).to(memory_format=layout)
              for name, net in nets.items()}
    print('batch norms folded: milliseconds per pass unfolded -> folded, and the gain')
    print(f'{"batch":>5s} ' + ' '.join(f'{m:>19s}' for m in nets))
    for b in sizes:
        cells = []
        for name, args_ in inputs_for(b).items():
            plain, fold = [], []
            for _ in range(3):
                plain.append(median_ms(partial(FORWARD[name], nets[name], *args_)))
                fold.append(median_ms(partial(FORWARD[name], folded[name], *args_)))
            cells.append(f'{min(plain):6.2f} {min(fold):6.2f} x{min(plain) / min(fold):4.2f}')
        print(f'{b:5d} ' + ' '.join(f'{c:>19s}' for c in cells))
    with torch.inference_mode():
        unfolded = {name: fn(slice(None)) for name, fn in deterministic.items()}
        nets.update(folded)
        diffs = {name: float((fn(slice(None)) - unfolded[name]).abs().max() /
                             unfolded[name].abs().max())
                 for name, fn in deterministic.items()}
    print('largest difference of the folded outputs from the unfolded ones, relative to the '
          'largest output: ' + ', '.join(f'{k} {v:.2g}' for k, v in diffs.items()))


if __name__ == '__main__':
    sys.exit(main())
