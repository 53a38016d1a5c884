"""Training every module of several room types in processes side by side (``scene-synth
train --jobs N``, ``make weights``).

One module of one room type is one task, as ``train --modules`` runs it: the run directory
lets processes train different modules at once, and a room type's bundle is exported once
its modules are done. The rooms are made first, once a room type, on every core; then the
longest schedules start first. Started again with the same run directory, it skips the
finished modules and bundles and resumes the others from their checkpoints. The weights are
those of one process training everything in turn: each module's batches, noise and initial
weights are functions of (seed, module, step).
"""
from __future__ import annotations

from concurrent.futures import FIRST_COMPLETED, Future, wait
from dataclasses import dataclass
import json
from pathlib import Path
import sys
import time
from typing import Callable

import torch

from ..parallel import process_executor
from . import NETWORKS
from .config import PipelineConfig
from .train import check_room_types, data_vocabulary, load_corpora, train_room_type

# Seconds between two progress lines.
PROGRESS_EVERY = 60.0

# The rooms of every room type, made once before training and handed to each worker process
# at its start (load_corpora's cache).
_CORPORA: dict = {}


def _keep(corpora: dict) -> None:
    _CORPORA.update(corpora)


def stamped(line: str) -> None:
    """``line`` printed with the time of day: the progress log of ``make weights``."""
    now = time.strftime('%H:%M:%S')
    # One write of whole lines: the processes side by side share the output.
    sys.stdout.write(''.join(f'{now} {part}\n' for part in line.splitlines()))
    sys.stdout.flush()


def _work(room_type: str, cfg: PipelineConfig, run_root: Path, weights_dir: Path,
          modules: tuple[str, ...], data_dir: Path | None) -> None:
    train_room_type(room_type, cfg, run_root, weights_dir, progress=False, echo=stamped,
                    modules=modules, data_dir=data_dir, corpus_cache=_CORPORA)


def _checkpoint_step(path: Path) -> int:
    if not path.is_file():
        return 0
    return int(torch.load(path, map_location='cpu', weights_only=True, mmap=True)['step'])


def _bundle_current(path: Path, cfg: PipelineConfig, run_dir: Path) -> bool:
    """Whether the bundle at ``path`` was exported from this configuration after the last
    checkpoint in ``run_dir`` was written."""
    if not path.is_file():
        return False
    ckpts = [p.stat().st_mtime_ns for p in run_dir.glob('*.ckpt')]
    if ckpts and path.stat().st_mtime_ns < max(ckpts):
        return False
    try:
        stored = torch.load(path, map_location='cpu', weights_only=True, mmap=True)['config']
    except Exception:  # an unreadable or foreign file: made again
        return False
    return stored == cfg.to_json()


@dataclass
class _Seen:
    step: int = 0
    seconds: float = 0.0
    rate: float | None = None      # steps a second, between the last two log entries


class _Progress:
    """Where each module is, read from the room types' ``log.jsonl`` as they grow."""

    def __init__(self, run_root: Path, steps: dict[tuple[str, str], int]):
        self.run_root, self.steps = run_root, steps
        self.offsets: dict[str, int] = {}
        self.seen: dict[tuple[str, str], _Seen] = {}

    def _read(self, rt: str) -> None:
        try:
            with open(self.run_root / rt / 'log.jsonl', 'rb') as f:
                f.seek(self.offsets.get(rt, 0))
                data = f.read()
        except FileNotFoundError:
            return
        whole = data[:data.rfind(b'\n') + 1]          # a line being written waits
        self.offsets[rt] = self.offsets.get(rt, 0) + len(whole)
        for line in whole.splitlines():
            try:
                e = json.loads(line)
            except ValueError:
                continue
            if not {'module', 'step', 'seconds'} <= set(e):
                continue
            s = self.seen.setdefault((rt, e['module']), _Seen())
            if e['seconds'] > s.seconds and e['step'] > s.step:   # the same process's entries
                s.rate = (e['step'] - s.step) / (e['seconds'] - s.seconds)
            s.step, s.seconds = e['step'], e['seconds']

    def line(self, running: list[tuple[str, str]]) -> str:
        for rt in {rt for rt, _ in running}:
            self._read(rt)
        parts = []
        for key in running:
            s = self.seen.get(key)
            if s is None:
                parts.append(f'{key[0]}/{key[1]} starting')
                continue
            total = self.steps[key]
            part = f'{key[0]}/{key[1]} {s.step:,}/{total:,}'
            if s.rate:
                left = (total - s.step) / s.rate
                part += f' ({s.rate:.1f} steps/s, ' + \
                    (f'{left / 60:.0f} min left)' if left >= 90 else f'{left:.0f} s left)')
            parts.append(part)
        return '; '.join(parts)


def _check(types: list[str], cfg: PipelineConfig, jobs: int, data_dir: Path | None) -> None:
    if jobs < 1:
        raise ValueError(f'jobs {jobs}: expected 1 or more processes')
    known = data_vocabulary(data_dir).room_types
    unknown = [rt for rt in types if rt not in known]
    if unknown:
        raise ValueError(f'unknown room type {unknown[0][:40]!r}; expected some of '
                         f'{", ".join(known)}')
    check_room_types(cfg, known)


class _Pool:
    """The tasks in the worker processes: modules, then each room type's export as soon as
    its modules are done; a failure drops what has not started."""

    def __init__(self, ex, cfg: PipelineConfig, run_root: Path, weights_dir: Path,
                 data_dir: Path | None, left: dict[str, set[str]], echo: Callable[[str], None]):
        self.ex, self.cfg, self.run_root, self.weights_dir = ex, cfg, run_root, weights_dir
        self.data_dir, self.left, self.echo = data_dir, left, echo
        self.running: dict[Future, tuple[str, str | None]] = {}
        self.failed: BaseException | None = None
        self.t0 = time.monotonic()

    def submit(self, rt: str, module: str | None) -> None:
        """Train ``module`` of ``rt``, or with None export its bundle (unless up to date)."""
        if module is None and _bundle_current(self.weights_dir / f'{rt}.pt', self.cfg,
                                              self.run_root / rt):
            self.echo(f'{rt}: bundle {self.weights_dir / f"{rt}.pt"} is up to date')
            return
        modules = NETWORKS if module is None else (module,)
        f = self.ex.submit(_work, rt, self.cfg, self.run_root, self.weights_dir, modules,
                           self.data_dir)
        self.running[f] = (rt, module)

    def done(self, f: Future) -> None:
        rt, module = self.running.pop(f)
        if f.cancelled():
            return
        error = f.exception()
        if error is not None:
            self.failed = self.failed or error
            for other in self.running:
                other.cancel()
            self.echo(f'{rt}/{module or "bundle"} failed ({type(error).__name__}: {error}); '
                      'waiting for the modules running to finish, then stopping')
        elif module is not None:
            self.left[rt].discard(module)
            self.echo(f'{rt}/{module}: finished, '
                      f'{(time.monotonic() - self.t0) / 60:.1f} min in')
            if not self.left[rt] and self.failed is None:
                self.submit(rt, None)

    def busy(self) -> list[tuple[str, str]]:
        return [k for f, k in self.running.items() if k[1] is not None and f.running()]


def train_side_by_side(types: list[str], cfg: PipelineConfig, run_root: Path,
                       weights_dir: Path, jobs: int, echo: Callable[[str], None] = stamped,
                       data_dir: Path | None = None, every: float = PROGRESS_EVERY
                       ) -> list[Path]:
    """Train the modules of ``types`` in ``jobs`` processes and export their bundles to
    ``weights_dir``, saying what starts, ends and where each module is (every ``every``
    seconds) through ``echo``; the bundles' paths. Where a module fails, the modules not
    started are dropped, those running finish (keeping their checkpoints), then its error
    is raised."""
    _check(types, cfg, jobs, data_dir)
    run_root, weights_dir = Path(run_root), Path(weights_dir)
    steps = {(rt, m): getattr(cfg.module_train(m, rt), m).steps
             for rt in types for m in NETWORKS}
    todo = [k for k in steps if _checkpoint_step(run_root / k[0] / f'{k[1]}.ckpt') < steps[k]]
    todo.sort(key=lambda k: -steps[k])
    left = {rt: {m for r, m in todo if r == rt} for rt in types}
    echo(f'{len(todo)} of {len(steps)} modules to train ({len(steps) - len(todo)} finished '
         f'before), {len(types)} bundles to export, in {jobs} processes; checkpoints and '
         f'logs in {run_root}, weights to {weights_dir}')
    t0 = time.monotonic()
    # The rooms first, on every core, once a room type; a worker making them itself would
    # make them again for each room type it meets.
    corpora: dict = {}
    for rt in types:
        if left[rt] or not _bundle_current(weights_dir / f'{rt}.pt', cfg, run_root / rt):
            sizes = {cfg.module_train(m, rt).train_rooms for m in NETWORKS}
            load_corpora(rt, cfg, sizes | {cfg.train.train_rooms}, data_dir=data_dir,
                         cache=corpora, echo=echo)
    progress = _Progress(run_root, steps)
    with process_executor(jobs, _keep, (corpora,), spawn=True) as ex:
        pool = _Pool(ex, cfg, run_root, weights_dir, data_dir, left, echo)
        for rt in types:
            if not left[rt]:
                pool.submit(rt, None)
        for rt, m in todo:
            pool.submit(rt, m)
        while pool.running:
            done, _ = wait(pool.running, timeout=every, return_when=FIRST_COMPLETED)
            for f in done:
                pool.done(f)
            if not done and pool.busy():
                echo(progress.line(pool.busy()))
        if pool.failed is not None:
            raise pool.failed
    echo(f'{len(types)} bundles in {weights_dir}, {(time.monotonic() - t0) / 60:.1f} min')
    return [weights_dir / f'{rt}.pt' for rt in types]
