"""Rooms furnished by Ray actors (``--ray``), on this machine or a cluster, one lockstep group
at a time each.

An actor streams back each room as it ends (a Ray generator), with the bytes of its files;
the driver alone writes them, so the output directory need exist only where the command runs.
"""
from __future__ import annotations

from collections import deque
from typing import Iterator

from ..errors import quoted, sentence
from .pool import IN_FLIGHT, cores
from .sources import BatchError
from .worker import RoomGroup, RoomResult, Worker, WorkerSpec


class RayWorker:
    """A Ray actor's state: one ``Worker``."""

    def __init__(self, spec: WorkerSpec):
        self.worker = Worker(spec)

    def furnish_group(self, group: RoomGroup) -> Iterator[RoomResult]:
        # A generator: Ray streams each room to the driver as it ends.
        yield from self.worker.furnish_group(group)


def ray_results(spec: WorkerSpec, groups: list[RoomGroup], workers: int | None,
                address: str) -> Iterator[RoomResult]:
    """The rooms of ``groups`` furnished by Ray actors, a group at a time each, each room as
    it ends, each actor's in the order it made them (see ``pool.pool_results``). ``address``:
    'local' starts a Ray of ``workers`` CPUs on this machine for the batch (and stops it
    after); anything else is given to ``ray.init`` (a cluster's address, or 'auto'). A
    driver already connected to Ray uses that connection."""
    try:
        import ray  # here: an optional dependency, and a heavy import that only --ray needs
    except ImportError:
        raise BatchError('--ray needs the ray package (pip install ray, pinned in '
                         'requirements.txt)') from None
    started = False
    if not ray.is_initialized():
        kwargs = {'address': address, 'include_dashboard': False, 'logging_level': 'WARNING'}
        if address == 'local':
            kwargs['num_cpus'] = workers or cores()
        try:
            ray.init(**kwargs)
        except (ConnectionError, ValueError, RuntimeError, TimeoutError) as e:
            raise BatchError(f'cannot start or reach Ray at {quoted(address)}: {e}') from None
        started = True
    actors = []
    try:
        n = workers or max(1, int(ray.cluster_resources().get('CPU', 1)))
        actor_class = ray.remote(num_cpus=1)(RayWorker)
        actors = [actor_class.remote(spec) for _ in range(min(n, len(groups)))]
        todo = iter(groups)
        # Each actor's groups in the order given to it, each a stream of its rooms.
        queued: list[deque] = [deque() for _ in actors]

        def feed(k: int) -> None:
            group = next(todo, None)
            if group is not None:
                queued[k].append(actors[k].furnish_group.remote(group))

        for _ in range(IN_FLIGHT):          # a group for every actor before a second one
            for k in range(len(actors)):
                feed(k)
        while any(queued):
            heads = [k for k, q in enumerate(queued) if q]
            ready, _ = ray.wait([queued[k][0] for k in heads], num_returns=1)
            k = next(k for k in heads if queued[k][0] is ready[0])
            try:
                try:
                    room = next(queued[k][0])
                except StopIteration:       # the group has ended
                    queued[k].popleft()
                    feed(k)
                    continue
                result = ray.get(room)
            except ray.exceptions.RayError as e:
                raise BatchError(f'a Ray worker failed ({sentence(e, 200)}); run the same '
                                 f'command again to resume') from None
            yield result
    finally:
        for a in actors:
            ray.kill(a)
        if started:
            ray.shutdown()
