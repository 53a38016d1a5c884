"""Worker processes, started the same way by everything that fans work out (the corpus, the
evaluation, the benchmarks)."""
from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
import multiprocessing as mp
from multiprocessing.pool import Pool
from typing import Callable, Iterable


def _context(spawn: bool = False):
    # Forked where the platform can fork: a worker then starts at once with the modules and
    # data its parent already loaded. Spawned elsewhere (macOS, Windows), where a worker
    # imports what it needs itself, and for workers that use CUDA: asking torch whether there
    # is a device initialises the CUDA driver, which a forked child cannot use again (every
    # room of a batch on cuda failed, seen on an H200).
    fork = not spawn and 'fork' in mp.get_all_start_methods()
    return mp.get_context('fork' if fork else 'spawn')


def process_pool(workers: int, initializer: Callable | None = None,
                 initargs: Iterable = ()) -> Pool:
    """A pool of ``workers`` processes, each running ``initializer(*initargs)`` first."""
    return _context().Pool(workers, initializer, tuple(initargs))


def process_executor(workers: int, initializer: Callable | None = None,
                     initargs: Iterable = (), spawn: bool = False) -> ProcessPoolExecutor:
    """``process_pool`` as an executor: a worker that dies (killed, out of memory) breaks
    it with ``BrokenProcessPool`` where a ``Pool`` would wait for ever for its task.
    ``spawn``: spawned workers even where the platform can fork (workers that use CUDA)."""
    return ProcessPoolExecutor(workers, _context(spawn), initializer, tuple(initargs))


def process_queue(spawn: bool = False) -> mp.Queue:
    """A queue that the processes of ``process_executor`` (as ``spawn``) can be given at
    their start (``initargs``), to send results before their task ends."""
    return _context(spawn).Queue()


def process_event(spawn: bool = False):
    """An event that the processes of ``process_executor`` (as ``spawn``) can be given at
    their start, to be told to stop early."""
    return _context(spawn).Event()
