"""Worker processes, started the same way by everything that fans work out (the corpus, the
evaluation, the benchmarks)."""
from __future__ import annotations

import multiprocessing as mp
from multiprocessing.pool import Pool
from typing import Callable, Iterable


def process_pool(workers: int, initializer: Callable | None = None,
                 initargs: Iterable = ()) -> Pool:
    """A pool of ``workers`` processes, each running ``initializer(*initargs)`` first.

    Forked where the platform can fork: a worker then starts at once with the modules and
    data its parent already loaded. Spawned elsewhere (macOS, Windows), where a worker
    imports what it needs itself."""
    ctx = mp.get_context('fork' if 'fork' in mp.get_all_start_methods() else 'spawn')
    return ctx.Pool(workers, initializer, tuple(initargs))
