"""What one batch is asked for: its rooms, where they go, and what makes them."""
from __future__ import annotations

from dataclasses import dataclass, field
import os

from ..synth import SynthConfig
from .sources import Source

# Rooms in lockstep beyond this gain nothing on a CPU and only hold more rooms' memory.
MAX_LOCKSTEP = 64


@dataclass
class BatchConfig:
    """One batch (see ``scene_synth_ros.batch``)."""

    out: str | os.PathLike
    source: Source
    mode: str = 'generate'          # 'generate' or 'complete'
    n: int | None = None            # rooms; None: every room of a finite source
    seed: int = 0
    synthesis: SynthConfig = field(default_factory=SynthConfig)
    weights_dir: str | None = None
    workers: int | None = None      # None: one per core (with Ray: one per CPU of the cluster)
    png: bool = False
    exports: tuple[str, ...] = ()
    ray: str | None = None          # None: worker processes; 'local' or an address: Ray
    # Rooms furnished together (``lockstep``; 1: one at a time): 8 make as many rooms a second
    # as 16 in less memory a worker (``benchmarks/bench_batch.py --runtime torch onnxruntime``).
    lockstep: int = 8
    progress: bool = True           # a progress bar on stderr
