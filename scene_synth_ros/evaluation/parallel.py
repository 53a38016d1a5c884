"""An ordered map over worker processes with a progress bar, or in this process for one
worker. Every job carries its own seed, so results do not depend on the number of workers."""
from __future__ import annotations

from typing import Callable, Iterable, Sequence

import torch
from tqdm import tqdm

from ..parallel import process_pool


def _single_thread_torch() -> None:
    torch.set_num_threads(1)


def _init(initializer, initargs) -> None:
    _single_thread_torch()
    if initializer is not None:
        initializer(*initargs)


def pmap(fn: Callable, items: Sequence, workers: int = 1, initializer: Callable | None = None,
         initargs: Iterable = (), desc: str | None = None, progress: bool = True,
         chunksize: int = 1) -> list:
    """``[fn(x) for x in items]``, on ``workers`` processes of one torch thread each.
    ``initializer(*initargs)`` runs once in every process that calls ``fn``."""
    items = list(items)
    bar = dict(total=len(items), desc=desc, disable=not progress, leave=False)
    if workers <= 1 or len(items) < 2:
        _init(initializer, tuple(initargs))
        return list(tqdm(map(fn, items), **bar))
    with process_pool(min(workers, len(items)), _init, (initializer, tuple(initargs))) as pool:
        return list(tqdm(pool.imap(fn, items, chunksize), **bar))
