"""Shared fixtures: a tiny trained bundle, so that synthesis can be tested end to end without
depending on the quality of the shipped weights; the command line run in this process; and
where the repository and its example files are."""
from dataclasses import dataclass
import itertools
import os
from pathlib import Path
import random
import signal

import pytest
import torch

from scene_synth_ros.networks.config import (
    EncoderConfig,
    ModelConfig,
    ModuleSchedule,
    PipelineConfig,
    TrainConfig,
)


def tiny_config(steps: int = 4) -> PipelineConfig:
    enc = EncoderConfig(blocks=(1, 1), widths=(8, 16))
    sched = ModuleSchedule(steps, batch_size=8)
    return PipelineConfig(
        name='tiny', device='cpu',
        model=ModelConfig(category_encoder=enc, location_encoder=enc, local_encoder=enc,
                          location_decoder_widths=(16, 8, 8), hidden=32, latent=4,
                          count_features=16, discriminator_widths=(8, 16),
                          location_offsets=True),
        train=TrainConfig(train_rooms=30, val_rooms=8, val_examples=16, val_every=2,
                          checkpoint_every=2, threads=1, category=sched, location=sched,
                          orientation=sched, snap=sched, dimensions=sched))


@pytest.fixture(scope='session', autouse=True)
def graph_cache(tmp_path_factory) -> Path:
    """The exported onnxruntime graphs of this run (``runtime.graph_cache_dir``) go to a
    directory of its own, for this process and the processes it starts: the suite neither
    reads a user's cache nor leaves files in it, and exports every graph once."""
    from scene_synth_ros.networks.runtime import CACHE_ENV
    path = tmp_path_factory.mktemp('graphs')
    with pytest.MonkeyPatch.context() as mp:
        mp.setenv(CACHE_ENV, str(path))
        yield path


@pytest.fixture(scope='session')
def tiny_weights(tmp_path_factory) -> Path:
    """A weights directory with tiny, briefly trained bundles for bathroom and bedroom."""
    from scene_synth_ros.networks.train import train
    root = tmp_path_factory.mktemp('tiny')
    threads = torch.get_num_threads()
    try:
        train(['bathroom', 'bedroom'], tiny_config(), root / 'run', root / 'weights',
              progress=False, echo=lambda s: None)
    finally:
        torch.set_num_threads(threads)
    return root / 'weights'


ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / 'examples'


@dataclass
class CliRun:
    """One command's exit code and output, with the names ``subprocess.run`` gives them."""

    returncode: int
    stdout: str
    stderr: str


@pytest.fixture
def cli(capsys):
    """``cli(*args, ok=True)`` runs ``scene-synth *args`` through ``main(argv)`` in this
    process and returns a ``CliRun``; with ``ok`` it also asserts exit code 0."""
    from scene_synth_ros.cli import main

    def run(*args, ok: bool = True) -> CliRun:
        capsys.readouterr()                 # drop output from before, so this is the command's
        threads = torch.get_num_threads()
        try:
            code = main([str(a) for a in args])
        except SystemExit as e:             # argparse: usage errors and --help
            code = int(e.code or 0)
        finally:
            # `train` sets the thread count of what would be its own process.
            torch.set_num_threads(threads)
        out, err = capsys.readouterr()
        if ok:
            assert code == 0, err
        return CliRun(code, out, err)

    return run


# A pytest-xdist worker ignores SIGINT (its controller takes Ctrl-C), and a program it starts
# inherits the ignoring: `ros2 topic pub` would never end on the Ctrl-C a test sends it.
if os.environ.get('PYTEST_XDIST_WORKER'):
    signal.signal(signal.SIGINT, signal.default_int_handler)


def ros_domains(lo: int, hi: int):
    """ROS domains of [lo, hi) for the nodes and tools of this test process, in an order of
    its own: under pytest-xdist a worker takes every W-th domain (W workers), so that tests
    running side by side never share a domain; a random order keeps test runs apart."""
    count = int(os.environ.get('PYTEST_XDIST_WORKER_COUNT', '1'))
    index = int(os.environ.get('PYTEST_XDIST_WORKER', 'gw0').removeprefix('gw'))
    mine = list(range(lo, hi))[index::count]
    if not mine:
        raise RuntimeError(f'{count} test workers share the {hi - lo} ROS domains from {lo} '
                           f'to {hi - 1}: run fewer (make test TEST_WORKERS=N)')
    random.Random().shuffle(mine)
    return itertools.cycle(mine)
