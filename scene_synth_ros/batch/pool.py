"""Rooms furnished by worker processes on this machine (``parallel.process_executor``), one
lockstep group at a time each.

A worker sends back each room as it ends, through a queue, with the bytes of its files; the
driver alone writes them, so that the directory's files have one writer.
"""
from __future__ import annotations

from collections import deque
from concurrent.futures.process import BrokenProcessPool
import os
import pickle
from queue import Empty
import signal
from typing import Iterator

from ..networks.config import resolve_device
from ..parallel import process_event, process_executor, process_queue
from .worker import RoomGroup, RoomResult, Worker, WorkerSpec

# Groups of rooms queued at each worker, so that it starts the next group while the driver
# is still writing the last one's files.
IN_FLIGHT = 2
# How long the driver waits for a room before it looks at which groups have ended.
POLL_SECONDS = 0.1

_WORKER: Worker | None = None
_RESULTS = None         # the queue through which a pool worker sends each room as it ends
_STOP = None            # set by the driver when it stops early: the groups under way end


def cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, 'sched_getaffinity'):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def _start_pool_worker(spec: WorkerSpec, results, stop) -> None:
    global _WORKER, _RESULTS, _STOP
    # Ctrl-C goes to the whole process group; the driver alone handles it (it stops the pool).
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # The driver reads every room before it stops the pool, except when it stops early; then
    # what was not read must not keep the worker from exiting.
    results.cancel_join_thread()
    _WORKER, _RESULTS, _STOP = Worker(spec), results, stop


def _pool_furnish(group: RoomGroup) -> int:
    """Furnishes ``group``, sending each room to the driver as it ends, until the group ends
    or the driver stops; how many rooms it sent."""
    sent = 0
    for result in _WORKER.furnish_group(group):
        if _STOP.is_set():
            break               # the rooms under way are abandoned (``lockstep.each``)
        # Pickled here, not by the queue's thread, which would drop a room it cannot pickle
        # and leave the driver waiting for it: here that fails the task, which says why.
        _RESULTS.put(pickle.dumps((_key(group), result), pickle.HIGHEST_PROTOCOL))
        sent += 1
    return sent


def _key(group: RoomGroup) -> int:
    return group.jobs[0].index


def pool_results(spec: WorkerSpec, groups: list[RoomGroup], workers: int,
                 spawn: bool | None = None) -> Iterator[RoomResult]:
    """The rooms of ``groups`` furnished by ``workers`` processes, a group at a time each,
    each room as it ends, each worker's in the order it made them (so that models it sends
    once come before a later room that names them). A worker that dies (killed, out of
    memory) costs the rooms in flight that had not come back, which fail with ``worker.LOST``; the
    others go on in new processes, unless a pool dies before furnishing anything. The
    workers are spawned, not forked, where they use CUDA (``spawn`` None: as the synthesis
    device says; see ``parallel``)."""
    if spawn is None:
        spawn = resolve_device(spec.synthesis.device).type == 'cuda'
    remaining = deque(groups)
    while remaining:
        results, stop = process_queue(spawn), process_event(spawn)
        pool = process_executor(workers, _start_pool_worker, (spec, results, stop), spawn)
        inflight: dict = {}             # future -> group
        received: dict[int, set[int]] = {}  # group key -> indices of its rooms that came back
        produced = broken = False
        try:
            while (remaining or inflight) and not broken:
                while remaining and len(inflight) < IN_FLIGHT * workers:
                    group = remaining.popleft()
                    received[_key(group)] = set()
                    inflight[pool.submit(_pool_furnish, group)] = group
                try:
                    key, result = pickle.loads(results.get(timeout=POLL_SECONDS))
                except Empty:
                    pass
                else:
                    received[key].add(result.row['index'])
                    produced = True
                    yield result
                for future in [f for f in inflight if f.done()]:
                    try:
                        sent = future.result()
                    except BrokenProcessPool:
                        broken = True
                        break
                    if len(received[_key(inflight[future])]) == sent:
                        del inflight[future]
        finally:
            # Also when the driver stops early (an error, Ctrl-C): the groups under way end
            # at their next room, the queued ones are dropped.
            stop.set()
            pool.shutdown(wait=True, cancel_futures=True)
        # The pool broke: what its workers sent and was not read is not read now (a worker
        # killed while sending leaves half a message that would block the reader for ever).
        for group in inflight.values():
            yield from group.lost(received[_key(group)])
        if broken and not produced:
            for group in remaining:
                yield from group.lost()
            return
