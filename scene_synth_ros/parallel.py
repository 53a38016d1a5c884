"""Worker processes, started the same way by everything that fans work out (the corpus, the
evaluation, the benchmarks)."""
from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
import multiprocessing as mp
from multiprocessing.pool import Pool
from typing import Callable, Iterable


def _context():
    # Forked where the platform can fork: a worker then starts at once with the modules and
    # data its parent already loaded. Spawned elsewhere (macOS, Windows), where a worker
    # imports what it needs itself.
    return mp.get_context('fork' if 'fork' in mp.get_all_start_methods() else 'spawn')


def process_pool(workers: int, initializer: Callable | None = None,
                 initargs: Iterable = ()) -> Pool:
    """A pool of ``workers`` processes, each running ``initializer(*initargs)`` first."""
    return _context().Pool(workers, initializer, tuple(initargs))


def process_executor(workers: int, initializer: Callable | None = None,
                     initargs: Iterable = ()) -> ProcessPoolExecutor:
    """``process_pool`` as an executor: a worker that dies (killed, out of memory) breaks
    it with ``BrokenProcessPool`` where a ``Pool`` would wait for ever for its task."""
    return ProcessPoolExecutor(workers, _context(), initializer, tuple(initargs))


def process_queue() -> mp.Queue:
    """A queue that the processes of ``process_executor`` can be given at their start
    (``initargs``), to send results before their task ends."""
    return _context().Queue()


def process_event():
    """An event that the processes of ``process_executor`` can be given at their start, to
    be told to stop early."""
    return _context().Event()
