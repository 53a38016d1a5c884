"""Rooms in lockstep: several rooms furnished together, each module's forward pass batched
across them.

Every room runs the ordinary synthesis code (``Synthesizer.generate`` or ``complete``) in a
greenlet of its own (``Room``). Where that code needs a network it hands a ``Request`` to
the coordinator and waits (``ask``). The coordinator works in rounds: the rooms it has
answered run, in order, until their next request or their end; then the requests of the
bundle and module that most rooms wait on are served as one forward pass (``serve``), each
room getting its slice, while the others wait, so that rooms fallen out of step fall back
in and the batches stay full. At most ``width`` rooms are under way; when one ends the next
starts. A room alone is served the same way, as a batch of one, with no greenlet.

A room draws all its random numbers from its own seed, in the same order as alone: the
CVAEs' noise is drawn by the room before it asks (``draws.prior_noise``). So a room in
lockstep differs from the same room made alone only where a forward pass over a batch sums
in another order than over one example, about 1e-5 on this CPU
(``docs/design/investigations.md``); that can tip a draw that fell as close to a boundary, and
the room goes on differently from there. Rooms in lockstep are therefore equal in
distribution to rooms made alone, and nearly all are the same rooms to the last few digits
(``tests/test_lockstep.py`` checks both). A group of rooms (the same rooms, the same
order) always gives the same results.

Greenlets rather than threads: switching costs about a microsecond, and there is no race (a
room runs only when the coordinator switches to it). Calls and answers are numpy arrays
(``networks.runtime``); the rooms touch no torch state, and torch, where it runs the calls,
enters inference mode for each forward pass (``graphs.TorchCalls``). ``each`` gives each
room's result as the room ends, so that a batch writes it at once; ``run`` gives them all.
"""
from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import Callable, Collection, Iterator, Sequence, TypeVar

from greenlet import getcurrent, greenlet
import numpy as np

T = TypeVar('T')


@dataclass
class Request:
    """One network call of one room: ``module`` of ``networks`` (a bundle's calls, an
    ``OnnxCalls`` or a ``TorchCalls``) on ``args``, arrays with the batch first."""

    networks: Callable
    module: str
    args: tuple[np.ndarray, ...]

    @property
    def size(self) -> int:
        return self.args[0].shape[0]


def _cat(parts: list[np.ndarray]) -> np.ndarray:
    """``parts`` one after another along the batch; images laid out channels-last stay so
    (a plain concatenation would lay them out channels-first, a copy across layouts the
    networks then undo)."""
    if parts[0].ndim == 4 and np.moveaxis(parts[0], 1, -1).flags.c_contiguous:
        return np.moveaxis(np.concatenate([np.moveaxis(p, 1, -1) for p in parts]), -1, 1)
    return np.concatenate(parts)


def _by_call(requests: dict[int, Request]) -> list[list[int]]:
    """The keys of ``requests``, in order, grouped by the bundle and module they call and
    the size of their images (rooms larger than their type's square are seen larger)."""
    calls: dict[tuple, list[int]] = {}
    for k in sorted(requests):
        r = requests[k]
        calls.setdefault((id(r.networks), r.module, tuple(r.args[0].shape[2:])), []).append(k)
    return list(calls.values())


def serve(requests: Sequence[Request]) -> list[tuple[np.ndarray | None, ...]]:
    """Each request's answer, the requests of one bundle and module answered by one forward
    pass over all their examples, in the order of the requests."""
    answers: list = [None] * len(requests)
    for ks in _by_call(dict(enumerate(requests))):
        first = requests[ks[0]]
        if len(ks) == 1:
            answers[ks[0]] = first.networks(first.module, *first.args)
            continue
        args = [_cat([requests[k].args[i] for k in ks]) for i in range(len(first.args))]
        outs = first.networks(first.module, *args)
        bounds = np.cumsum([requests[k].size for k in ks])[:-1]
        parts = [np.split(o, bounds) if o is not None else [None] * len(ks) for o in outs]
        for j, k in enumerate(ks):
            answers[k] = tuple(p[j] for p in parts)
    return answers


class Room(greenlet):
    """The greenlet of one room of a lockstep group."""


def ask(networks, module: str, *args: np.ndarray) -> tuple[np.ndarray | None, ...]:
    """The answer to one network call: from the coordinator, inside a lockstep group; right
    away, as a batch of one, outside."""
    me = getcurrent()
    if isinstance(me, Room):
        return me.parent.switch(Request(networks, module, args))
    return networks(module, *args)


def _next_call(waiting: dict[int, Request]) -> list[int]:
    """The rooms whose calls are served next: those waiting on the bundle and module that
    most rooms wait on (the first such in room order on a tie), so that rooms that fell out
    of step wait for the others and the batches stay full."""
    return max(_by_call(waiting), key=len)


def each(calls: Sequence[Callable[[], T]], width: int | None = None,
         needed: Collection[int] | None = None) -> Iterator[tuple[int, T | Exception]]:
    """``(k, result)`` as each call ``k`` ends, its result or the exception it raised, the
    calls made in lockstep (see the module docstring): at most ``width`` of them at a time
    (all by default), the next one started, in order, when one ends. With ``needed``
    (indices), the run ends as soon as those calls have ended; the others that had not are
    abandoned. What happened up to then is what happens in a run of all the calls, so a
    needed call's result does not depend on ``needed``, nor on what the consumer does
    between two results. Anything but an ``Exception`` (Ctrl-C) ends the run and is raised;
    so does closing the iterator, which abandons the calls under way."""
    rooms = [Room(c) for c in calls]
    todo = set(range(len(rooms)) if needed is None else needed)
    width = len(rooms) if width is None else width
    # (room, what to switch into it with), in order: nothing to start a room, else its answer
    queue = deque((k, ()) for k in range(min(width, len(rooms))))
    started = len(queue)
    waiting: dict[int, Request] = {}
    try:
        while todo:
            ended = []
            while queue:
                k, answer = queue.popleft()
                try:
                    out = rooms[k].switch(*answer)
                except Exception as e:    # noqa: BLE001 - one room's end, not the group's
                    out = e
                if not rooms[k].dead:
                    waiting[k] = out
                    continue
                ended.append((k, out))
                todo.discard(k)
                if not todo:        # a room that never asks (a house, its own lockstep)
                    break           # ends within one pass: start none after the last needed
                if started < len(rooms):
                    queue.append((started, ()))
                    started += 1
            if waiting and todo:
                ks = _next_call(waiting)
                for k, answer in zip(ks, serve([waiting.pop(k) for k in ks]), strict=True):
                    queue.append((k, (answer,)))
            yield from ended
            if not waiting and not queue:
                break
    finally:
        for room in rooms:      # abandoned (or left by Ctrl-C): unwound now
            if room and not room.dead:
                room.throw()


def run(calls: Sequence[Callable[[], T]], width: int | None = None,
        needed: Collection[int] | None = None) -> list[T | Exception | None]:
    """Each call's result, or the exception it raised (None for a call abandoned after the
    ``needed`` ones ended), the calls made in lockstep as by ``each``."""
    results: list = [None] * len(calls)
    for k, out in each(calls, width, needed):
        results[k] = out
    return results
