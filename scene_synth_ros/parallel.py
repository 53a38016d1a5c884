"""Worker processes, started the same way by everything that fans work out (the corpus, the
evaluation, the benchmarks)."""
from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor
import multiprocessing as mp
from multiprocessing.pool import Pool
import os
import threading
import time
from typing import Callable, Iterable

# Seconds between a worker's looks at whether its parent is still there.
PARENT_POLL = 1.0


def _context(spawn: bool = False):
    # Forked where the platform can fork: a worker then starts at once with the modules and
    # data its parent already loaded. Spawned elsewhere (macOS, Windows), where a worker
    # imports what it needs itself, and for workers that use CUDA: asking torch whether there
    # is a device initialises the CUDA driver, which a forked child cannot use again (every
    # room of a batch on cuda failed, seen on an H200).
    fork = not spawn and 'fork' in mp.get_all_start_methods()
    return mp.get_context('fork' if fork else 'spawn')


def _exit_with(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(PARENT_POLL)
    os._exit(1)


def _watched(parent: int, initializer: Callable | None, initargs: tuple) -> None:
    # A parent killed outright (SIGTERM, SIGKILL, out of memory) runs no clean-up: its
    # workers, reparented, went on with their tasks for as long as they took (a training
    # module: hours), writing into a run another process may resume. They end instead.
    threading.Thread(target=_exit_with, args=(parent,), name='parent-watch', daemon=True).start()
    if initializer is not None:
        initializer(*initargs)


def process_pool(workers: int, initializer: Callable | None = None,
                 initargs: Iterable = ()) -> Pool:
    """A pool of ``workers`` processes, each running ``initializer(*initargs)`` first; a
    worker whose parent is gone ends, as ``process_executor``'s do."""
    return _context().Pool(workers, _watched, (os.getpid(), initializer, tuple(initargs)))


def process_executor(workers: int, initializer: Callable | None = None,
                     initargs: Iterable = (), spawn: bool = False) -> ProcessPoolExecutor:
    """``process_pool`` as an executor: a worker that dies (killed, out of memory) breaks
    it with ``BrokenProcessPool`` where a ``Pool`` would wait for ever for its task.
    ``spawn``: spawned workers even where the platform can fork (workers that use CUDA).
    A worker whose parent is gone without shutting it down ends within ``PARENT_POLL``
    seconds."""
    return ProcessPoolExecutor(workers, _context(spawn), _watched,
                               (os.getpid(), initializer, tuple(initargs)))


def process_queue(spawn: bool = False) -> mp.Queue:
    """A queue that the processes of ``process_executor`` (as ``spawn``) can be given at
    their start (``initargs``), to send results before their task ends."""
    return _context(spawn).Queue()


def process_event(spawn: bool = False):
    """An event that the processes of ``process_executor`` (as ``spawn``) can be given at
    their start, to be told to stop early."""
    return _context(spawn).Event()
