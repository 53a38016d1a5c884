"""What several benchmarks share; not a benchmark itself.

The layouts the node benchmarks send (``bench_node.py``, ``node_load.py``), a process's
resident memory, and the two modules of the test suite that benchmarks run at a larger
scale: the fuzzing strategies (``tests/fuzz.py``) and the raster check of the robot promise
(``tests/raster_robot.py``). Those are not installed with the package, so they are loaded
from their files here rather than by adding ``tests/`` to ``sys.path``.
"""
from __future__ import annotations

import importlib.util
import json
from pathlib import Path
import random
import sys
from types import ModuleType

from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.scene import Scene
from scene_synth_ros.schema import dump_scene

TESTS = Path(__file__).resolve().parent.parent / 'tests'


def tests_module(name: str) -> ModuleType:
    """The module ``tests/<name>.py`` of this checkout, loaded once per process."""
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, TESTS / f'{name}.py')
        module = importlib.util.module_from_spec(spec)
        # Registered before it runs: its dataclasses look their module up by name.
        sys.modules[name] = module
        spec.loader.exec_module(module)
    return sys.modules[name]


def rss_mb(pid: int) -> float:
    """The resident memory of process ``pid`` in MB (Linux)."""
    for line in Path(f'/proc/{pid}/status').read_text().splitlines():
        if line.startswith('VmRSS:'):
            return int(line.split()[1]) / 1024
    raise RuntimeError('no VmRSS')


def layout_text(room_type: str, index: int) -> str:
    """The empty held-out corpus room ``index`` of ``room_type``, as the node's layout JSON."""
    d = json.loads(dump_scene(Scene(empty_room(room_type, HELDOUT_SEED, index), [])))
    return json.dumps(d['room'])


def invalid_layout(rng: random.Random, k: int) -> str:
    """One of the bad inputs the node must refuse in one sentence, drawn with ``rng``."""
    good = json.loads(layout_text('bedroom', k))
    kinds = [
        lambda: '{"room_type": "bedroom", "floor": [[0, 0]',                    # not JSON
        lambda: json.dumps({'room_type': 'bedroom'}),                            # schema
        lambda: json.dumps({**good, 'floor': [[0, 0], [4, 4], [4, 0], [0, 4]],
                            'doors': [], 'windows': []}),                        # crossing
        lambda: json.dumps({**good, 'wall_height': 'high'}),                     # type
        lambda: json.dumps(good).replace(str(good['wall_height']), 'NaN', 1),    # NaN
        lambda: json.dumps({**good, 'room_type': 'garage'}),                     # room type
        lambda: json.dumps({'room_type': 'bathroom', 'floor': [[0, 0], [0.5, 0], [0.5, 0.5],
                                                               [0, 0.5]]}),      # too small
    ]
    return rng.choice(kinds)()
