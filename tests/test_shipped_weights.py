"""The shipped weights' one command: ``config/shipped.yaml`` states what the chain of
retrainings trained, and ``make weights`` trains it the same way every time, stopped or not."""
import json
import os
from pathlib import Path
import shutil
import signal
import subprocess
import sys
import time

from conftest import ROOT, tiny_config
import pytest
import torch
import yaml

from scene_synth_ros.categories import HOME_ROOM_TYPES, PAPER_ROOM_TYPES, ROOM_TYPES
from scene_synth_ros.networks import NETWORKS
from scene_synth_ros.networks.config import PipelineConfig, TrainConfig
from scene_synth_ros.paths import config_dir, weights_dir

# The chain the shipped bundles came from (docs/training.md): each module of each room type
# and the configuration it was last trained with, with the others of its bundle kept.
CHAIN = {'category': 'compact_category_long', 'location': 'compact_long',
         'orientation': 'compact', 'snap': 'compact', 'dimensions': 'compact_dims_noise'}
CHAIN_EXCEPTIONS = {('office', 'category'): 'compact'}   # the office kept its 4,000 steps

# Settings that change no weight: how many threads and loader processes run the steps.
HOW_RUN = ('threads', 'loader_workers')


def module_settings(t: TrainConfig, module: str) -> dict:
    """What a module's training reads of ``t``: its own schedule and the shared settings."""
    shared = {k: v for k, v in vars(t).items()
              if k not in NETWORKS and k not in HOW_RUN}
    return {**shared, 'schedule': getattr(t, module)}


def shipped() -> PipelineConfig:
    return PipelineConfig.from_yaml(config_dir() / 'shipped.yaml')


def test_shipped_config_states_what_the_chain_trained():
    cfg = shipped()
    for rt in PAPER_ROOM_TYPES:
        for module in NETWORKS:
            name = CHAIN_EXCEPTIONS.get((rt, module), CHAIN[module])
            chain = PipelineConfig.from_yaml(config_dir() / f'{name}.yaml')
            assert module_settings(cfg.module_train(module, rt), module) == \
                module_settings(chain.train, module), (rt, module, name)
            assert cfg.model == chain.model, name
    # The exception is the office's alone.
    assert cfg.module_train('category', 'office').category.steps == 4000
    assert cfg.module_train('category', 'living').category.steps == 12000
    # The rooms of a home: compact.yaml's schedules on the 5,000 rooms.
    compact = PipelineConfig.from_yaml(config_dir() / 'compact.yaml').train
    for rt in HOME_ROOM_TYPES:
        for module in NETWORKS:
            t = cfg.module_train(module, rt)
            assert getattr(t, module).steps == getattr(compact, module).steps, (rt, module)


def test_shipped_bundles_record_the_settings_of_the_config():
    """Each shipped bundle records the configuration of its last training run: its model is
    shipped.yaml's, and so are the settings of the modules that run trained (all of them
    once the bundles come from shipped.yaml itself)."""
    cfg = shipped()
    last = {'compact_dims_noise': ('dimensions',), 'compact_category_long': ('category',),
            'shipped': NETWORKS}
    for rt in ROOM_TYPES:
        path = weights_dir() / f'{rt}.pt'
        if rt in HOME_ROOM_TYPES and not path.is_file():
            continue                    # the home's bundles land apart from the config
        data = torch.load(path, map_location='cpu', weights_only=True, mmap=True)
        recorded = PipelineConfig.from_dict(json.loads(data['config']))
        assert recorded.model == cfg.model, rt
        assert recorded.name in last, rt
        for module in last[recorded.name]:
            assert module_settings(recorded.module_train(module, rt), module) == \
                module_settings(cfg.module_train(module, rt), module), (rt, module)


def test_module_and_room_type_overrides(tmp_path):
    cfg = PipelineConfig.from_dict({
        'train': {'train_rooms': 100, 'val_every': 10},
        'modules': {'location': {'steps': 50, 'train_rooms': 80}},
        'room_types': {'office': {'location': {'steps': 7}, 'snap': {'lr': 0.5}}}})
    # train, then modules, then room_types; the rest as the train section says.
    assert cfg.module_train('location').location.steps == 50
    assert cfg.module_train('location', 'bedroom').train_rooms == 80
    office = cfg.module_train('location', 'office')
    assert (office.location.steps, office.train_rooms, office.val_every) == (7, 80, 10)
    assert cfg.module_train('snap', 'office').snap.lr == 0.5
    assert cfg.module_train('category', 'office') == cfg.train
    # A module's settings do not leak into another's schedule.
    assert cfg.module_train('location', 'office').snap == cfg.train.snap
    run = cfg.for_module('location', 'office')
    assert run.train == office and not run.modules and not run.room_types
    assert PipelineConfig.from_dict(json.loads(cfg.to_json())) == cfg
    # Without overrides a configuration writes what it wrote before they existed.
    assert 'modules' not in PipelineConfig().to_dict()
    bad = {
        "config.modules: unknown module 'locaton'": {'modules': {'locaton': {}}},
        "config.modules.location: unknown setting 'stpes'":
            {'modules': {'location': {'stpes': 3}}},
        'config.modules.location.steps: expected a positive whole number, got 2.5':
            {'modules': {'location': {'steps': 2.5}}},
        'config.room_types.office.snap.lr: expected a positive number, got 0':
            {'room_types': {'office': {'snap': {'lr': 0}}}},
        'config.modules.snap.weight_decay: expected a number of 0 or more, got -1':
            {'modules': {'snap': {'weight_decay': -1}}},
        'config.room_types: expected a mapping of room types, got list':
            {'room_types': ['office']},
        r'config.modules.snap.train_rooms: 4000 is more than train.train_rooms \(3000\)':
            {'modules': {'snap': {'train_rooms': 4000}}},
    }
    for message, data in bad.items():
        with pytest.raises(ValueError, match=message):
            PipelineConfig.from_dict(data)
    # Room types are those training knows: a typo is refused before anything trains.
    from scene_synth_ros.networks.train import train
    typo = tiny_config()
    typo.room_types = {'ofice': {}}
    with pytest.raises(ValueError, match="settings for room type 'ofice', which is none of"):
        train(['bathroom'], typo, tmp_path / 'run', tmp_path / 'w', progress=False)


def test_make_weights_runs_the_one_command():
    if not shutil.which('make'):
        pytest.skip('no make')
    out = subprocess.run(['make', '-n', '-o', 'install', 'weights', 'JOBS=3'], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout
    assert 'scene-synth train --config config/shipped.yaml --room-type all' in out
    assert '--device cpu --jobs 3' in out and '--run-dir runs/shipped ' in out
    assert '--weights-dir runs/shipped/weights' in out and 'runs/shipped/weights.log' in out


def _tiny_yaml(path: Path) -> Path:
    """A tiny configuration with a module and a room type's module apart from the rest."""
    d = json.loads(tiny_config(steps=12).to_json())
    d['modules'] = {'orientation': {'train_rooms': 20, 'steps': 6}}
    d['room_types'] = {'office': {'category': {'steps': 8, 'train_rooms': 24}}}
    path.write_text(yaml.safe_dump(d))
    return path


def _make_weights(conf: Path, run: Path, jobs: int) -> list:
    return ['make', '--no-print-directory', '-o', 'install', 'weights',
            f'WEIGHTS_CONFIG={conf}', f'WEIGHTS_RUN={run}', f'WEIGHTS_DIR={run}/weights',
            'ROOM_TYPES=bathroom,office', f'JOBS={jobs}',
            f'SCENE_SYNTH={sys.executable} -m scene_synth_ros.cli']


@pytest.mark.slow
def test_make_weights_gives_the_same_bundles_every_time_stopped_or_not(tmp_path):
    """``make weights`` twice (2 processes, then 1), and once killed after its first
    checkpoint and run again with the same run directory: byte-identical bundles."""
    if not shutil.which('make'):
        pytest.skip('no make')
    conf = _tiny_yaml(tmp_path / 'tiny.yaml')
    env = {**os.environ, 'PYTHONPATH': str(ROOT)}
    for name, jobs in (('a', 2), ('b', 1)):
        subprocess.run(_make_weights(conf, tmp_path / name, jobs), cwd=ROOT, env=env,
                       check=True, capture_output=True)
    stopped = tmp_path / 'c'
    proc = subprocess.Popen(_make_weights(conf, stopped, 2), cwd=ROOT, env=env,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    try:
        while not list(stopped.glob('*/*.ckpt')) and proc.poll() is None:
            time.sleep(0.02)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    cfg = PipelineConfig.from_yaml(conf)
    steps = {(p.parent.name, p.stem): torch.load(p, weights_only=True)['step']
             for p in stopped.glob('*/*.ckpt')}
    total = {k: getattr(cfg.module_train(k[1], k[0]), k[1]).steps for k in steps}
    assert any(steps[k] < total[k] for k in steps), steps   # stopped inside a module
    assert not list(stopped.glob('weights/*.pt'))
    log = subprocess.run(_make_weights(conf, stopped, 2), cwd=ROOT, env=env, check=True,
                         capture_output=True, text=True).stdout
    finished = sum(steps[k] == total[k] for k in steps)
    assert f'{10 - finished} of 10 modules to train ({finished} finished before)' in log
    for rt in ('bathroom', 'office'):
        a = (tmp_path / 'a' / 'weights' / f'{rt}.pt').read_bytes()
        assert a == (tmp_path / 'b' / 'weights' / f'{rt}.pt').read_bytes(), rt
        assert a == (stopped / 'weights' / f'{rt}.pt').read_bytes(), rt
    # The log says where each module stood (weights.log, appended to by both runs).
    assert 'bathroom/location: finished' in (stopped / 'weights.log').read_text()
