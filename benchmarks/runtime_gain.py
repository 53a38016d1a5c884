"""What onnxruntime buys synthesis over torch (``networks.runtime``), on this CPU.

    .venv/bin/python benchmarks/runtime_gain.py [-n 80] [--room-type bedroom]
                                                [--sizes 1,16] [--threads 1]
                                                [--onnx-max-batch B]

First each network call of the room type's shipped bundle, as synthesis makes it (batch
norms folded, images channels-last, for onnxruntime with the zero channels its graphs take),
on random images at each batch size: milliseconds per
pass in torch and in onnxruntime, the best of three medians of 30 passes, the two runtimes
timed in turn. Then ``-n`` complete rooms from empty (the held-out shells the timing of
``bench_synth.py`` furnishes, the same seeds), each made by both runtimes one after the other
in this process, which goes first alternating: the median and mean wall and CPU seconds a
room of each, the median of the rooms' ratios, and how many rooms are the same to the
millimetre (the two sum in other orders, so a draw can tip; see the module docstring).
"""
import argparse
from pathlib import Path
import statistics
import sys
import time

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from batch_gain import median_ms  # noqa: E402  (this folder, the script's own)


def calls(synths: dict, room_type: str, sizes: list[int]) -> None:
    import numpy as np
    import torch

    from scene_synth_ros.categories import room_spec
    from scene_synth_ros.lockstep import forward
    from scene_synth_ros.render import FIRST_CATEGORY
    torch_synth = synths['torch']
    nets = torch_synth.bundle(room_type).networks
    n = torch_synth.bundle(room_type).config.model.resolution
    k = len(room_spec(room_type).names)
    print(f'{room_type}: milliseconds per pass, torch -> onnxruntime (gain)')
    print(f'{"batch":>5s} ' + ' '.join(f'{m:>22s}' for m in
                                       ('category', 'location', 'orientation', 'dimensions')))
    for b in sizes:
        cats = torch.zeros(b, dtype=torch.long)
        z = torch.randn(b, nets['orientation'].latent)
        # Each runtime's images as synthesis draws them: for onnxruntime, with its zero
        # channels (``runtime.padded_channels``).
        drawn = torch.rand(b, FIRST_CATEGORY + k, n, n).round()
        images = {}
        for name, synth in synths.items():
            image = torch.from_numpy(np.stack([
                synth._image(n, FIRST_CATEGORY + k, calls=synth.calls(room_type))
                for _ in range(b)]))
            image[:, :FIRST_CATEGORY + k] = drawn
            images[name] = image.contiguous(memory_format=torch.channels_last)
        cells = []
        for module in ('category', 'location', 'orientation', 'dimensions'):
            best = {}
            for _ in range(3):
                for name, synth in synths.items():
                    c, image = synth.calls(room_type), images[name]
                    a = {'category': (image, torch.zeros(b, k)), 'location': (image,),
                         'orientation': (image, cats, z), 'dimensions': (image, cats, z)}[module]
                    ms = median_ms(lambda c=c, a=a, module=module: forward(c, module, *a), 30)
                    best[name] = min(best.get(name, ms), ms)
            t, o = best['torch'], best['onnxruntime']
            cells.append(f'{t:6.2f} -> {o:6.2f} x{t / o:4.2f}')
        print(f'{b:5d} ' + ' '.join(f'{c:>22s}' for c in cells))


def rooms(synths: dict, room_type: str, n: int) -> None:
    from scene_synth_ros.corpus import HELDOUT_SEED
    from scene_synth_ros.corpus.generate import empty_room
    wall = {name: [] for name in synths}
    cpu = {name: [] for name in synths}
    shapes = {name: [] for name in synths}
    for synth in synths.values():       # warm-up: loading, and onnxruntime's export
        synth.generate(empty_room(room_type, HELDOUT_SEED, 10_000), seed=0)
    for i in range(n):
        room = empty_room(room_type, HELDOUT_SEED, i)
        order = list(synths) if i % 2 == 0 else list(reversed(synths))
        for name in order:
            c0, t0 = time.process_time(), time.perf_counter()
            result = synths[name].generate(room, seed=i)
            wall[name].append(time.perf_counter() - t0)
            cpu[name].append(time.process_time() - c0)
            shapes[name].append([(o.category, o.model_id, round(o.position[0], 3),
                                  round(o.position[1], 3), round(o.yaw, 3))
                                 for o in result.scene.objects])
    print(f'\n{n} complete {room_type}s from empty, both runtimes in turn, one process:')
    for name in synths:
        print(f'  {name:>11s}: median {statistics.median(wall[name]):.3f} s, mean '
              f'{statistics.mean(wall[name]):.3f} s, CPU median '
              f'{statistics.median(cpu[name]):.3f} s a room; '
              f'{sum(map(len, shapes[name])) / n:.2f} objects a room')
    ratios = sorted(o / t for o, t in zip(wall['onnxruntime'], wall['torch'], strict=True))
    same = sum(a == b for a, b in zip(shapes['torch'], shapes['onnxruntime'], strict=True))
    print(f'  onnxruntime / torch, a room: median {statistics.median(ratios):.3f} '
          f'(quartiles {ratios[n // 4]:.3f}, {ratios[(3 * n) // 4]:.3f}); '
          f'{same} of {n} rooms the same to the millimetre')


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=80, help='rooms made by each runtime (0: none)')
    ap.add_argument('--room-type', default='bedroom')
    ap.add_argument('--sizes', default='1,16', help='batch sizes of the passes timed')
    ap.add_argument('--threads', type=int, default=1)
    ap.add_argument('--weights-dir', default=None)
    ap.add_argument('--onnx-max-batch', type=int, default=None,
                    help='let onnxruntime run batches up to this size (default: '
                    'runtime.ONNX_MAX_BATCH), to measure where it stops gaining')
    args = ap.parse_args()
    import torch
    torch.set_num_threads(args.threads)
    if args.onnx_max_batch is not None:
        from scene_synth_ros.networks import runtime
        runtime.ONNX_MAX_BATCH = args.onnx_max_batch
    from scene_synth_ros.synth import SynthConfig, Synthesizer
    synths = {name: Synthesizer(args.weights_dir, SynthConfig(runtime=name))
              for name in ('torch', 'onnxruntime')}
    print(f'torch {torch.__version__}, {torch.get_num_threads()} thread(s)')
    if args.sizes:
        calls(synths, args.room_type, [int(s) for s in args.sizes.split(',')])
    if args.n:
        rooms(synths, args.room_type, args.n)
    return 0


if __name__ == '__main__':
    sys.exit(main())
