"""How fast each module trains alone on one core, and what that makes of a whole schedule.

Runs ``--steps`` training steps of every module of one room type (default bedroom, the room
type with the most categories) with one torch thread, exactly as ``scene-synth train`` does
(same batches, losses and, for dimensions, the discriminator), and projects the
configuration's schedule from the measured rates: one room type and all four, sequentially
on one core. Corpus generation and validation are not included. The training rooms are
``--rooms`` corpus rooms (sizes as the corpus draws them); ``--size-buckets N`` batches the
category and location modules' rooms by size, at least N rooms a group (default: the
configuration's ``train.size_buckets``; 0: batches of any rooms); ``--real-sizes`` draws
the rooms at real rooms' sizes (``train.real_sizes``), up to 16 m.

    .venv/bin/python benchmarks/bench_training.py [--room-type bedroom] [--steps 30]
        [--config config/compact.yaml] [--rooms 300] [--size-buckets N] [--modules ...]
"""
import argparse
from pathlib import Path
import tempfile
import time

import torch

from scene_synth_ros.networks.bundle import NETWORKS, build_networks
from scene_synth_ros.networks.config import PipelineConfig
from scene_synth_ros.networks.examples import ExampleSource
from scene_synth_ros.networks.train import load_corpus, train_module
from scene_synth_ros.paths import default_config_path


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--room-type', default='bedroom')
    ap.add_argument('--steps', type=int, default=30)
    ap.add_argument('--config', default=str(default_config_path()))
    ap.add_argument('--rooms', type=int, default=300)
    ap.add_argument('--size-buckets', type=int, default=None)
    ap.add_argument('--real-sizes', action='store_true',
                    help='corpus rooms sized as real rooms (train.real_sizes)')
    ap.add_argument('--modules', default=','.join(NETWORKS))
    args = ap.parse_args()
    torch.set_num_threads(1)
    cfg = PipelineConfig.from_yaml(args.config)
    cfg.train.train_rooms, cfg.train.val_rooms = args.rooms, 10
    cfg.train.real_sizes = cfg.train.real_sizes or args.real_sizes
    buckets = cfg.train.size_buckets if args.size_buckets is None else args.size_buckets
    corpus = load_corpus(args.room_type, cfg, workers=1)
    m = cfg.model
    nets = build_networks(args.room_type, m, seed=0)
    multiple = nets['location'].multiple
    src = ExampleSource(args.room_type, corpus.train, m.resolution, m.location_resolution,
                        target_radius=cfg.train.location_target_radius, multiple=multiple,
                        size_buckets=buckets)
    val = ExampleSource(args.room_type, corpus.val, m.resolution, m.location_resolution,
                        multiple=multiple)
    sides = sorted(src._frame(s.room).resolution for s in src.scenes)
    total = 0.0
    print(f'{args.room_type}, {cfg.name} configuration, 1 thread, {args.steps} steps each, '
          f'{len(sides)} rooms (image sides: median {sides[len(sides) // 2]} px, '
          f'largest {sides[-1]} px), size buckets {buckets or "off"}:')
    with tempfile.TemporaryDirectory() as run:
        for name in args.modules.split(','):
            t0 = time.perf_counter()
            train_module(name, nets[name], src, val, cfg, 'cpu', Path(run), lambda e: None,
                         progress=False, until=args.steps)
            rate = args.steps / (time.perf_counter() - t0)
            steps = getattr(cfg.train, name).steps
            total += steps / rate
            print(f'  {name:12s} {rate:5.2f} steps/s -> {steps:5d} steps in '
                  f'{steps / rate / 60:5.1f} min')
    print(f'one room type: {total / 60:.0f} min; all four sequentially on one core: '
          f'about {4 * total / 3600:.1f} h (smaller room types train a little faster)')


if __name__ == '__main__':
    main()
