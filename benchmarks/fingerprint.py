"""Hashes of what a change meant to leave alone: corpus rooms, training batches of each
module, and rooms synthesized with the shipped weights in torch and in onnxruntime. Run it at
the commit before a change and after it: equal lines, equal behaviour.

    .venv/bin/python benchmarks/fingerprint.py [--rooms 60] [--synthesized 8] > AFTER.txt
    diff BEFORE.txt AFTER.txt

Prints one line per room type and what was hashed (16 hex digits of a SHA-256). About a
minute with the defaults on one core.
"""
import argparse
import hashlib
import json

import numpy as np
import torch

from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.corpus.generate import empty_room, generate_room
from scene_synth_ros.networks.examples import ExampleSource
from scene_synth_ros.networks.train import batches
from scene_synth_ros.synth import SynthConfig, Synthesizer

MODULES = ('category', 'location', 'orientation', 'dimensions')


def digest(parts) -> str:
    h = hashlib.sha256()
    for part in parts:
        h.update(part)
    return h.hexdigest()[:16]


def batch_bytes(batch: dict):
    for key in sorted(batch):
        value = batch[key]
        array = value.numpy() if torch.is_tensor(value) else np.asarray(value)
        yield key.encode()
        yield np.ascontiguousarray(array).tobytes()


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--rooms', type=int, default=60, help='corpus rooms per type (seed 0)')
    ap.add_argument('--synthesized', type=int, default=8,
                    help='rooms per type synthesized in each runtime (held-out shells)')
    args = ap.parse_args()
    torch.set_num_threads(1)
    for rt in ROOM_TYPES:
        rooms = [generate_room(rt, 0, i) for i in range(args.rooms)]
        corpus = json.dumps([r.to_dict() for r in rooms], sort_keys=True)
        print('corpus', rt, digest([corpus.encode()]))
        source = ExampleSource(rt, rooms, 64, 64)
        for module in MODULES:
            batch = next(batches(source, module, seed=7, size=4, start=3, stop=4))
            print('batch', rt, module, digest(batch_bytes(batch)))
    for runtime in ('torch', 'onnxruntime'):
        synth = Synthesizer(config=SynthConfig(runtime=runtime))
        for rt in ROOM_TYPES:
            scenes = [synth.generate(empty_room(rt, 1, seed), seed=seed).scene.to_dict()
                      for seed in range(args.synthesized)]
            print('synth', runtime, rt, digest([json.dumps(scenes, sort_keys=True).encode()]))
    return 0


if __name__ == '__main__':
    raise SystemExit(main())
