"""Worker processes (parallel.py)."""
from pathlib import Path
import subprocess
import sys
import time

import pytest

from scene_synth_ros.parallel import PARENT_POLL

SCRIPT = '''
import os, signal, time
from scene_synth_ros.parallel import process_executor
ex = process_executor(2, spawn={spawn})
for _ in range(4):
    ex.submit(time.sleep, 600)
while len(ex._processes) < 2:
    time.sleep(0.05)
time.sleep(1.0)
print(' '.join(str(p) for p in ex._processes), flush=True)
os.kill(os.getpid(), signal.SIGKILL)
'''


def _running(pid: int) -> bool:
    """Whether ``pid`` is a live process (a zombie left to an init that does not reap
    is not)."""
    try:
        state = Path(f'/proc/{pid}/stat').read_text().rsplit(')', 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return False
    return state not in ('Z', 'X')


@pytest.mark.skipif(not Path('/proc/self/stat').exists(), reason='reads /proc')
@pytest.mark.parametrize('spawn', [False, True])
def test_workers_end_when_their_parent_is_killed_outright(spawn):
    done = subprocess.run([sys.executable, '-c', SCRIPT.format(spawn=spawn)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == -9, done.stderr
    pids = [int(p) for p in done.stdout.split()]
    assert len(pids) == 2
    deadline = time.monotonic() + 10 * PARENT_POLL + 10
    while any(_running(p) for p in pids):
        assert time.monotonic() < deadline, f'workers {pids} outlived their parent'
        time.sleep(0.1)
