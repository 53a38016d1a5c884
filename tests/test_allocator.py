"""The allocator settings of long-running processes (``allocator.py``)."""
import os
import subprocess
import sys

import pytest

# In a fresh interpreter: free a 4 MiB block, then hold a 3 MiB one, and say how many bytes
# glibc keeps in mappings of their own (mallinfo2().hblkhd) while it is held.
PROBE = '''
import ctypes, sys
from scene_synth_ros.allocator import steady_allocator
set_up = sys.argv[1] == 'steady' and steady_allocator()
class Info(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in ('arena', 'ordblks', 'smblks', 'hblks',
                'hblkhd', 'usmblks', 'fsmblks', 'uordblks', 'fordblks', 'keepcost')]
libc = ctypes.CDLL(None)
libc.mallinfo2.restype = Info
first = bytearray(4 << 20)
del first
held = bytearray(3 << 20)
print(int(set_up), libc.mallinfo2().hblkhd)
'''


@pytest.mark.skipif(not sys.platform.startswith('linux'), reason='glibc only')
def test_blocks_of_megabytes_stay_in_mappings_returned_when_freed():
    def probe(mode, env=None):
        r = subprocess.run([sys.executable, '-c', PROBE, mode], capture_output=True,
                           text=True, timeout=60, check=True, env=env)
        return [int(v) for v in r.stdout.split()]

    # glibc by default: the freed 4 MiB block raised the threshold, the 3 MiB one is on the
    # heap (kept after it is freed); set up, it has a mapping of its own.
    assert probe('default')[1] < 3 << 20
    set_up, mapped = probe('steady')
    assert set_up == 1 and mapped >= 3 << 20
    # What the user set in the environment wins.
    env = dict(os.environ, MALLOC_MMAP_THRESHOLD_=str(64 << 20))
    assert probe('steady', env)[1] < 3 << 20
