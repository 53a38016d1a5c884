"""Speed (paper, table 3): seconds per complete room and per module, on this machine."""
from __future__ import annotations

import os
import platform
import statistics
from typing import Sequence

import torch

from ..synth import MODULES
from .data import SynthRecord


def cpu_model() -> str:
    """The processor's marketing name (from /proc/cpuinfo on Linux)."""
    try:
        with open('/proc/cpuinfo', encoding='utf-8') as f:
            for line in f:
                if line.lower().startswith('model name'):
                    return line.split(':', 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or 'unknown CPU'


def hardware(workers: int) -> dict:
    return {'cpu': cpu_model(), 'machine': platform.machine(), 'cores': os.cpu_count(),
            'workers': workers, 'torch_threads_per_worker': 1,
            'torch': torch.__version__, 'python': platform.python_version()}


def summarize(records: Sequence[SynthRecord]) -> dict:
    """Mean, median and 90th percentile seconds per room; mean seconds per module."""
    seconds = sorted(r.seconds for r in records)
    n = len(seconds)
    if not n:
        return {'rooms': 0}
    modules = {m: sum(r.timings.get(m, 0.0) for r in records) / n for m in MODULES}
    stopped: dict[str, int] = {}
    for r in records:
        stopped[r.stopped] = stopped.get(r.stopped, 0) + 1
    return {'rooms': n, 'mean': statistics.fmean(seconds),
            'median': statistics.median(seconds),
            'p90': seconds[min(n - 1, int(0.9 * n))], 'max': seconds[-1],
            'objects_per_room': sum(len(r.scene) for r in records) / n,
            'modules': modules, 'stopped': stopped}
