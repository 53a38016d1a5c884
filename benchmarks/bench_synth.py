"""How good and how fast the synthesized rooms are: the pipeline issue's targets.

For every room type, ``-n`` rooms (default 500) are synthesized from empty into the shells of
held-out corpus rooms (corpus seed 1, which training never saw) and compared with
``--corpus-rooms`` rooms (default 2,000) of the training corpus (seed 0):
KL(synthesized || corpus) over categories, mean objects per room, and every physical
violation. Then ``--timing-rooms`` bedrooms are synthesized one after another in this process
alone, for the wall time per room, the time per module and the peak memory.

    .venv/bin/python benchmarks/bench_synth.py [-n 500] [--corpus-rooms 2000]
        [--timing-rooms 100] [--room-type all] [--workers 2] [--device cpu|cuda]
        [--runtime auto|torch|onnxruntime] [--threads N]
"""
import argparse
from collections import Counter
import os
import platform
import resource
import statistics
import time

from scene_synth_ros.categories import ROOM_TYPES, kl_divergence
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room, generate_corpus
from scene_synth_ros.corpus.stats import collect
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.parallel import process_pool

_SYNTH = None


def _init_worker(weights):
    import torch
    torch.set_num_threads(1)
    global _SYNTH
    from scene_synth_ros.synth import Synthesizer
    _SYNTH = Synthesizer(weights)


def _synthesize(job):
    rt, i = job
    room = empty_room(rt, HELDOUT_SEED, i)
    result = _SYNTH.generate(room, seed=i)
    r = check_scene(result.scene)
    return (rt, Counter(o.category for o in result.scene.objects), len(result.scene.objects),
            {'collisions': len(r.collisions), 'off_floor': len(r.off_floor),
             'blocked_doors': len(r.blocked_doors), 'under_supported': len(r.under_supported),
             'disconnected': int(not r.doors_connected)}, result.stopped)


def quality(room_types, n, corpus_rooms, workers, weights):
    jobs = [(rt, i) for rt in room_types for i in range(n)]
    out = {rt: {'counts': Counter(), 'objects': 0, 'violations': Counter(), 'stopped': Counter()}
           for rt in room_types}
    t0 = time.perf_counter()
    with process_pool(workers, _init_worker, (weights,)) as pool:
        for k, (rt, counts, nobj, viol, stopped) in enumerate(
                pool.imap_unordered(_synthesize, jobs, chunksize=4)):
            o = out[rt]
            o['counts'].update(counts)
            o['objects'] += nobj
            o['violations'].update(viol)
            o['stopped'][stopped] += 1
            if (k + 1) % 200 == 0:
                print(f'  {k + 1}/{len(jobs)} rooms synthesized '
                      f'({time.perf_counter() - t0:.0f} s)', flush=True)
    print(f'\n{"room type":10s} {"KL(syn||corpus)":>15s} {"obj/room":>8s} {"corpus":>7s} '
          f'{"diff":>7s} {"collide":>7s} {"off":>4s} {"doors":>5s} {"support":>7s} '
          f'{"path":>4s} {"stopped (stop/full/nothing fits)":>32s}')
    for rt in room_types:
        corpus = collect(rt, generate_corpus(rt, corpus_rooms, seed=0), check=False)
        o = out[rt]
        total = sum(o['counts'].values())
        syn = {c: v / total for c, v in o['counts'].items()}
        kl = kl_divergence(syn, corpus.distribution())
        per_room = o['objects'] / n
        ref = corpus.objects_per_room
        v, s = o['violations'], o['stopped']
        print(f'{rt:10s} {kl:15.4f} {per_room:8.2f} {ref:7.2f} {per_room / ref - 1:+7.1%} '
              f'{v["collisions"]:7d} {v["off_floor"]:4d} {v["blocked_doors"]:5d} '
              f'{v["under_supported"]:7d} {v["disconnected"]:4d} '
              f'{s["stop"]:>14d}/{s["max_objects"]}/{s["nothing_fits"]}')


def timing(rooms, weights, device='cpu', runtime='auto'):
    from scene_synth_ros.synth import SynthConfig, Synthesizer
    synth = Synthesizer(weights, SynthConfig(device=device, runtime=runtime))
    synth.prepare('bedroom')
    synth.generate(empty_room('bedroom', HELDOUT_SEED, 10_000), seed=0)   # warm-up
    seconds, modules, objects = [], Counter(), 0
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    cpu = time.process_time()
    for i in range(rooms):
        room = empty_room('bedroom', HELDOUT_SEED, i)
        t0 = time.perf_counter()
        result = synth.generate(room, seed=i)
        seconds.append(time.perf_counter() - t0)
        modules.update(result.timings)
        objects += len(result.added)
    cpu = time.process_time() - cpu
    faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults
    import torch

    from scene_synth_ros.networks.runtime import threads
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f'\ncomplete bedrooms from empty, {rooms} rooms, {objects / rooms:.1f} objects each, '
          f'{os.cpu_count()} cores ({platform.processor() or platform.machine()}), '
          f'torch {torch.__version__}, {threads()} threads, '
          f'networks on {synth.device} run by {synth.runtime}:')
    print(f'  median {statistics.median(seconds):.3f} s, mean {statistics.mean(seconds):.3f} s, '
          f'p90 {sorted(seconds)[int(0.9 * len(seconds))]:.3f} s, max {max(seconds):.3f} s '
          f'per room (paper: 1.86 s on a GTX 1080 Ti)')
    print('  per module, mean ms per room: ' + ', '.join(
        f'{k} {v / rooms * 1000:.0f}' for k, v in modules.items()))
    print(f'  process CPU time {cpu / rooms:.3f} s per room (less sensitive to other load than '
          f'wall time); minor page faults {faults / rooms:.0f} per room')
    print(f'  peak resident memory of this process: {peak:.0f} MB')


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=500, help='synthesized rooms per room type')
    ap.add_argument('--corpus-rooms', type=int, default=2000)
    ap.add_argument('--timing-rooms', type=int, default=100)
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--workers', type=int, default=os.cpu_count() or 1)
    ap.add_argument('--weights-dir', default=None)
    ap.add_argument('--device', default='cpu', choices=('cpu', 'cuda'),
                    help='where the timed rooms run their networks')
    ap.add_argument('--runtime', default='auto', choices=('auto', 'torch', 'onnxruntime'),
                    help='what runs the timed rooms\' networks')
    ap.add_argument('--threads', type=int, default=None,
                    help="torch's (and onnxruntime's) threads for the timed rooms "
                    "(default: torch's own choice, one per core)")
    args = ap.parse_args()
    if args.threads is not None:
        import torch
        torch.set_num_threads(args.threads)
    rts = list(ROOM_TYPES) if args.room_type == 'all' else [args.room_type]
    if args.n:
        quality(rts, args.n, args.corpus_rooms, args.workers, args.weights_dir)
    if args.timing_rooms:
        timing(args.timing_rooms, args.weights_dir, args.device, args.runtime)


if __name__ == '__main__':
    main()
