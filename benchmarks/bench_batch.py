"""Batches of rooms (``scene_synth_ros.batch``): rooms per second with 1 and 2 worker
processes and R = 1, 8, 32 rooms in lockstep, peak memory per worker, and a memory soak.

For each ``--workers`` count and each ``--lockstep`` R, ``-n`` complete rooms of
``--room-type`` (default bedrooms, from corpus-like empty shells) are furnished into a fresh
directory exactly as ``scene-synth generate -n N --out DIR --workers W --lockstep R`` does,
start-up included; the runs are interleaved (every R for one worker count, then the next
count). ``--location-batch`` sets ``SynthConfig.location_batch`` (candidate placements decoded
together; default that of SynthConfig). ``--runtime`` names what runs the networks
(``SynthConfig.runtime``, default auto); several are run in turn for each R. ``--device``
is where the networks run (``SynthConfig.device``; on a GPU machine, ``cuda``). In lockstep
a room's seconds are its group's wall time since the room before it ended, so only their
mean is printed: the group's time shared equally among its rooms (rooms often end in the
same round, a few microseconds apart).
With ``--soak N``, a batch of N rooms on ``--soak-workers`` workers, and each worker's
resident memory after its 100th room and after its last (the issue's target: no growth
beyond 50 MB after the first 100 rooms); ``--soak-report DIR`` says the same of a soak
directory kept with ``--keep``, also of one stopped before its end. The machine's load
average is printed beside the figures: on a shared machine they are only as good as the
cores were free.

    .venv/bin/python benchmarks/bench_batch.py [-n 200] [--workers 1 2] [--lockstep 1 8 32]
        [--room-type bedroom] [--location-batch N] [--runtime auto|torch|onnxruntime ...]
        [--device cpu|cuda]
        [--soak 10000] [--soak-workers 2] [--weights-dir DIR] [--keep DIR]
    .venv/bin/python benchmarks/bench_batch.py --soak-report DIR/soak
    .venv/bin/python benchmarks/bench_batch.py --room-type house -n 40 --workers 1 2 --ray

``--room-type house`` furnishes procedural house plans (``generate -n N --houses``), a whole
house a row, each house's rooms in lockstep (so ``--lockstep`` is 1); ``--ray`` runs each
worker count on a Ray started on this machine for the batch, besides the processes.
"""
import argparse
from collections import defaultdict
import json
import os
from pathlib import Path
import resource
import sys
import tempfile

from scene_synth_ros.batch import BatchConfig, Manifest, Source, run_batch
from scene_synth_ros.errors import SceneSynthError
from scene_synth_ros.synth import SynthConfig

WARM = 100          # rooms after which a worker's memory should stay flat


def _load() -> str:
    one, five, _ = os.getloadavg()
    return f'load average {one:.1f} (1 min), {five:.1f} (5 min) on {os.cpu_count()} cores'


def _rows(out: Path) -> list[dict]:
    return [json.loads(line) for line in (out / 'manifest.jsonl').read_text().splitlines()]


def _batch(out: Path, room_type: str, n: int, workers: int, weights: str | None,
           progress: bool = False, lockstep: int | None = None,
           location_batch: int | None = None, runtime: str = 'auto', device: str = 'cpu',
           ray: str | None = None):
    synthesis = SynthConfig(runtime=runtime, device=device)
    if location_batch is not None:
        synthesis.location_batch = location_batch
    source = Source.plans() if room_type == 'house' else Source.shells([room_type])
    cfg = BatchConfig(out=out, source=source, n=n, workers=workers, ray=ray,
                      weights_dir=weights, progress=progress, synthesis=synthesis,
                      **({} if lockstep is None else {'lockstep': lockstep}))
    return run_batch(cfg, echo=lambda s: None)


def throughput(room_type: str, n: int, workers: int, lockstep: int, weights: str | None,
               root: Path, location_batch: int | None, runtime: str = 'auto',
               device: str = 'cpu', ray: str | None = None) -> None:
    print(f'  before: {_load()}', flush=True)
    out = root / f'speed_{workers}_{lockstep}_{runtime}_{device}_{"ray" if ray else "pool"}'
    s = _batch(out, room_type, n, workers, weights, lockstep=lockstep,
               location_batch=location_batch, runtime=runtime, device=device, ray=ray)
    chosen = json.loads((out / 'batch.json').read_text())['synthesis']['runtime']
    if device != 'cpu':
        chosen += f' on {device}'
    if ray:
        chosen += ', Ray actors'
    rows = _rows(out)
    ok = [r for r in rows if r['status'] == 'ok']
    if not ok:
        print(f'{workers} worker(s), lockstep {lockstep}, {chosen}: no room was furnished; '
              f'the first error: {rows[0]["error"] if rows else "none written"}', flush=True)
        return
    secs = sorted(r['seconds'] for r in ok)
    cpu = [r['cpu_seconds'] for r in ok]
    print(f'{workers} worker(s), lockstep {lockstep}, {chosen}: {n} {room_type}s in '
          f'{s.seconds:.1f} s = {s.rooms_per_second:.2f} {room_type}s/s (start-up included); '
          f'{len(ok)} ok, '
          f'{s.objects_per_room:.2f} objects a {room_type}, {s.valid} valid, '
          f'{s.robot_kept} robot promise kept; per {room_type} in a worker: '
          + (f'median {secs[len(secs) // 2]:.3f} s, ' if lockstep == 1 else '')
          + f'mean {sum(secs) / len(secs):.3f} s, CPU {sum(cpu) / len(cpu):.3f} s; peak resident '
          f'memory per worker: {", ".join(f"{v:.0f}" for v in s.peak_mb.values())} MB',
          flush=True)
    print(f'  after: {_load()}', flush=True)


def soak(room_type: str, n: int, workers: int, weights: str | None, root: Path) -> None:
    print(f'soak: {n} {room_type}s on {workers} workers; {_load()}', flush=True)
    s = _batch(root / 'soak', room_type, n, workers, weights, progress=True)
    print(f'  {s.seconds:.0f} s, {s.rooms_per_second:.2f} rooms/s, {s.rooms_ok} ok, '
          f'{s.rooms_failed} failed; {_load()}')
    soak_report(root / 'soak')
    driver = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f'  peak resident memory of the driver: {driver:.0f} MB')


def soak_report(out: Path) -> None:
    """Each worker's resident memory over the rooms it made, from the manifest of the batch
    in ``out`` (also of one that was stopped before its end)."""
    by_worker: dict[str, list[dict]] = defaultdict(list)
    for r in sorted(Manifest(out / 'manifest.jsonl').rows.values(), key=lambda r: r['index']):
        by_worker[r['worker']].append(r)
    rooms = sum(len(v) for v in by_worker.values())
    print(f'  {rooms} rooms in {out}')
    worst = 0.0
    for worker, rows in by_worker.items():
        rss = [r['rss_mb'] for r in rows]
        if len(rss) <= WARM:
            print(f'  worker {worker}: only {len(rss)} rooms')
            continue
        marks = [rss[k] for k in range(0, len(rss), max(1, len(rss) // 10))]
        growth = max(rss[WARM:]) - rss[WARM - 1]
        worst = max(worst, growth)
        print(f'  worker {worker}: {len(rss)} rooms; resident MB after room 1: {rss[0]:.1f}, '
              f'after room {WARM}: {rss[WARM - 1]:.1f}, after the last: {rss[-1]:.1f}, '
              f'most after room {WARM}: {max(rss[WARM:]):.1f} (growth {growth:+.1f} MB); '
              f'peak {rows[-1]["peak_mb"]:.1f} MB; every tenth: '
              + ' '.join(f'{m:.0f}' for m in marks))
    print(f'  largest growth after room {WARM}: {worst:+.1f} MB (target: under 50 MB)')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('-n', type=int, default=200, help='rooms per throughput run (0: none)')
    ap.add_argument('--workers', type=int, nargs='+', default=[1, 2])
    ap.add_argument('--lockstep', type=int, nargs='+', default=[1, 8, 32])
    ap.add_argument('--location-batch', type=int, default=None)
    ap.add_argument('--room-type', default='bedroom', help='a room type, or house')
    ap.add_argument('--ray', action='store_true', help='each worker count on Ray actors too')
    ap.add_argument('--runtime', nargs='+', default=['auto'],
                    choices=('auto', 'torch', 'onnxruntime'))
    ap.add_argument('--device', default='cpu', choices=('cpu', 'cuda', 'auto'))
    ap.add_argument('--soak', type=int, default=0, help='rooms of the memory soak (0: none)')
    ap.add_argument('--soak-workers', type=int, default=2)
    ap.add_argument('--weights-dir', default=None)
    ap.add_argument('--keep', help='write the batches here (default: a temporary directory)')
    ap.add_argument('--soak-report', metavar='DIR', help='only report the soak batch in DIR '
                    '(one that was stopped too), from its manifest')
    args = ap.parse_args()
    if args.soak_report:
        soak_report(Path(args.soak_report))
        return
    with tempfile.TemporaryDirectory(prefix='bench-batch-') as tmp:
        root = Path(args.keep or tmp)
        lockstep = [1] if args.room_type == 'house' else args.lockstep
        if args.n:
            for w in args.workers:
                for r in lockstep:
                    for runtime in args.runtime:
                        for ray in (None, 'local') if args.ray else (None,):
                            throughput(args.room_type, args.n, w, r, args.weights_dir,
                                       root, args.location_batch, runtime, args.device, ray)
        if args.soak:
            soak(args.room_type, args.soak, args.soak_workers, args.weights_dir, root)


if __name__ == '__main__':
    try:
        main()
    except SceneSynthError as e:        # a device that is not there, a bad weights dir...
        sys.exit(f'bench_batch.py: {e}')
