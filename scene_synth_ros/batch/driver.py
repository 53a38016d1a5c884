"""The driver: checks a batch before any worker starts, hands its lockstep groups to worker
processes or Ray actors, and alone writes what they send back, each room's files (atomically,
``files.write_atomic``) before its manifest row, then the summary."""
from __future__ import annotations

from contextlib import closing
from dataclasses import replace
import json
from pathlib import Path
import sys
import time
from typing import Callable

from tqdm import tqdm

from ..errors import quoted
from ..export import parse_formats
from ..files import write_atomic
from ..networks.config import resolve_device, resolve_runtime
from ..synth import Synthesizer
from .config import MAX_LOCKSTEP, BatchConfig
from .manifest import Manifest, batch_identity, check_directory, done
from .pool import cores, pool_results
from .ray_actors import ray_results
from .sources import BatchError
from .summary import BatchSummary, summarize
from .worker import RoomResult, WorkerSpec, group_size, is_shared, lockstep_groups, output_files

# tqdm's bar with the rate always in rooms per second (its default turns slow rates over).
PROGRESS = ('{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} '
            '[{elapsed}<{remaining}, {rate_noinv_fmt}{postfix}]')


def _runtime_chosen(cfg: BatchConfig) -> BatchConfig:
    """``cfg`` with the runtime ``auto`` chooses here: the batch's, named in batch.json and
    sent to the workers, so that a directory furnished by onnxruntime is not resumed, nor its
    rooms made, by torch on a machine without it. On the CPU ``auto`` is onnxruntime in
    lockstep too (``benchmarks/bench_batch.py --runtime torch onnxruntime``)."""
    try:
        runtime = resolve_runtime(cfg.synthesis.runtime, resolve_device(cfg.synthesis.device))
    except ValueError as e:
        raise BatchError(str(e)) from None
    return replace(cfg, synthesis=replace(cfg.synthesis, runtime=runtime))


def _check_weights(cfg: BatchConfig) -> Path:
    """The weights directory, its bundles for the shells' room types loaded once here so that
    a missing or broken file is one sentence before any worker starts."""
    Synthesizer(cfg.weights_dir, cfg.synthesis)        # a device that is not there
    synth = Synthesizer(cfg.weights_dir, replace(cfg.synthesis, device='cpu'))
    if not synth.weights_dir.is_dir():
        raise BatchError(f'{synth.weights_dir}: no such weights directory')
    for rt in cfg.source.room_types:
        synth.networks.served(rt)
    return synth.weights_dir.resolve()


def _write(out: Path, result: RoomResult) -> None:
    for rel, data in result.files.items():
        path = out / rel
        if is_shared(rel) and path.is_file() and path.read_bytes() == data:
            continue
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(path, data)


def run_batch(cfg: BatchConfig, echo: Callable[[str], None] = print) -> BatchSummary:
    """Furnish the batch's rooms that are not there yet into ``cfg.out``; BatchError (or
    another SceneSynthError) before anything is furnished when it cannot start."""
    if cfg.mode not in ('generate', 'complete'):
        raise BatchError(f"mode must be 'generate' or 'complete', got {quoted(cfg.mode)}")
    if cfg.n is not None and cfg.n < 1:
        raise BatchError(f'-n must be at least 1, got {cfg.n}')
    if cfg.n is None and not cfg.source.finite:
        raise BatchError('how many rooms? give -n N')
    if cfg.workers is not None and cfg.workers < 1:
        raise BatchError(f'--workers must be at least 1, got {cfg.workers}')
    if not 1 <= cfg.lockstep <= MAX_LOCKSTEP:
        raise BatchError(f'--lockstep must be between 1 and {MAX_LOCKSTEP}, got {cfg.lockstep}')
    if cfg.mode == 'complete' and cfg.source.kind == 'shells':
        raise BatchError('complete needs partial rooms: a file, a directory or a JSON-lines '
                         'file of them')
    exports = parse_formats(','.join(cfg.exports))
    out = Path(cfg.out)
    weights = _check_weights(cfg)
    cfg = _runtime_chosen(cfg)
    # A group is always the same rooms (see ``worker``): the last one goes on beyond -n with
    # rooms that start while the last needed ones are under way.
    r, g = cfg.lockstep, group_size(cfg.lockstep)
    everything = cfg.source.jobs(cfg.seed, None if cfg.n is None else -(-cfg.n // g) * g)
    jobs = everything[:cfg.n]
    if cfg.n is not None and len(jobs) < cfg.n:
        echo(f'{cfg.source.path} holds {len(jobs)} rooms: furnishing those, not {cfg.n}')
    check_directory(out, batch_identity(cfg, weights))
    manifest = Manifest(out / 'manifest.jsonl')
    pending = [j for j in jobs
               if not done(manifest.rows.get(j.index), out,
                           output_files(j.name, cfg.png, exports))]
    groups = lockstep_groups(everything, {j.index for j in pending}, r)
    spec = WorkerSpec(cfg.mode, cfg.weights_dir, cfg.synthesis, cfg.png, exports)
    workers = cfg.workers or (None if cfg.ray else cores())
    skipped = len(jobs) - len(pending)
    if skipped:
        echo(f'{out}: {skipped} of {len(jobs)} rooms already there, {len(pending)} to furnish')
    t0 = time.perf_counter()
    furnished = failed = 0
    peaks: dict[str, float] = {}
    try:
        if pending:
            groups = [replace(g, jobs=[cfg.source.load(j) for j in g.jobs]) for g in groups]
            if cfg.ray:
                results = ray_results(spec, groups, workers, cfg.ray)
            else:
                results = pool_results(spec, groups, min(workers, len(groups)))
            wanted = {j.index for j in pending}
            # closing: an error here stops the workers now, not when the traceback goes.
            with closing(results), tqdm(
                    total=len(pending), unit=' rooms', desc='furnishing', file=sys.stderr,
                    disable=not cfg.progress, mininterval=1.0, smoothing=0.1,
                    bar_format=PROGRESS) as bar:
                for result in results:
                    row = result.row
                    if row['index'] not in wanted:
                        # Made for its group only: of its files, just the shared models its
                        # worker sends once, which later rooms name.
                        _write(out, RoomResult(row, {k: v for k, v in result.files.items()
                                                     if is_shared(k)}))
                        continue
                    _write(out, result)
                    manifest.append(row)
                    if row['status'] == 'ok':
                        furnished += 1
                    else:
                        failed += 1
                        bar.set_postfix(failed=failed, refresh=False)
                    if row['worker'] is not None:       # None: its worker died
                        peaks[row['worker']] = max(peaks.get(row['worker'], 0.0),
                                                   row['peak_mb'] or 0.0)
                    bar.update()
    finally:
        manifest.compact()
        seconds = time.perf_counter() - t0
        summary = summarize(cfg, manifest, len(jobs), furnished, failed, skipped, seconds,
                            len(peaks) or (workers or 0), peaks)
        write_atomic(out / 'summary.json', json.dumps(summary.to_dict(), indent=2) + '\n')
    return summary
