"""glibc's allocator set up for a long-running process that reads messages of megabytes.

By default glibc raises its mmap threshold to the size of the largest block freed (up to
32 MiB), so once one multi-megabyte message has been freed the next ones come from the heap,
which fragments and does not shrink, and every thread that meets contention gets a heap of
its own. Over 1,000 mixed inputs (``benchmarks/node_load.py --clients 0 --fuzz 0 --mixed
1000``) the node grew by 40.3 MB so, and by 21.4 MB with the settings below: a fixed 1 MiB
threshold keeps every block that large in a mapping of its own, returned to the system when
freed, while the arrays of a synthesis (under 1 MiB) stay on the heap; two arenas bound the
heaps of the executor's threads. Settings given in the environment (``MALLOC_*_``) win.
"""
from __future__ import annotations

import ctypes
import os
import sys

M_MMAP_THRESHOLD = -3          # mallopt parameters, from glibc's <malloc.h>
M_ARENA_MAX = -8
SETTINGS = {M_MMAP_THRESHOLD: (1 << 20, 'MALLOC_MMAP_THRESHOLD_'),
            M_ARENA_MAX: (2, 'MALLOC_ARENA_MAX')}


def steady_allocator() -> bool:
    """Apply ``SETTINGS`` with glibc's ``mallopt``; False where that is not possible (not
    Linux, not glibc, or a setting refused), with nothing else changed."""
    if not sys.platform.startswith('linux'):
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes, mallopt.restype = [ctypes.c_int, ctypes.c_int], ctypes.c_int
    ok = True
    for param, (value, env) in SETTINGS.items():
        if env not in os.environ:
            ok = mallopt(param, value) == 1 and ok
    return ok
