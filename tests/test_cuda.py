"""The CUDA path (``device: cuda``): the networks, synthesis and training on a GPU. Skipped
where torch sees no CUDA device (CI has none); run on a GPU machine with
``python -m pytest tests/test_cuda.py``."""
from dataclasses import replace

from conftest import tiny_config
import pytest
import torch

from scene_synth_ros import lockstep
from scene_synth_ros.categories import PASSAGE_ROOM_TYPES, ROOM_TYPES
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.networks import NETWORKS
from scene_synth_ros.networks.bundle import build_networks, load_bundle
from scene_synth_ros.networks.examples import ExampleSource
from scene_synth_ros.networks.train import batch_loss, load_corpus, train_module
from scene_synth_ros.paths import weights_dir
from scene_synth_ros.synth import SynthConfig, Synthesizer

pytestmark = pytest.mark.skipif(not torch.cuda.is_available(), reason='no CUDA device')


def _close(a: torch.Tensor, b: torch.Tensor) -> float:
    """The relative difference ||a - b|| / ||b|| in float64."""
    a, b = a.double().cpu(), b.double().cpu()
    return float((a - b).norm() / b.norm().clamp_min(1e-12))


@pytest.mark.parametrize('room_type', ROOM_TYPES)
def test_shipped_networks_answer_on_cuda_as_on_the_cpu(room_type):
    cpu = load_bundle(weights_dir() / f'{room_type}.pt', 'cpu')
    gpu = load_bundle(weights_dir() / f'{room_type}.pt', 'cuda')
    rooms = load_corpus(room_type, replace(tiny_config(), train=replace(
        tiny_config().train, train_rooms=8, val_rooms=0)), workers=1).train
    m = cpu.config.model
    source = ExampleSource(room_type, rooms, m.resolution, m.location_resolution)
    for name in NETWORKS:
        batch = source.batch(name, [0, NETWORKS.index(name), 1], 8)
        a, b = cpu.networks[name], gpu.networks[name]
        assert next(b.parameters()).is_cuda
        with torch.no_grad():
            if name == 'category':
                out = [n(batch['image'].to(d), batch['counts'].to(d))
                       for n, d in ((a, 'cpu'), (b, 'cuda'))]
            elif name == 'location':
                out = [n.predict(batch['image'].to(d))[0] for n, d in ((a, 'cpu'), (b, 'cuda'))]
            elif name == 'snap':
                out = [n(batch['image'].to(d), batch['category'].to(d))
                       for n, d in ((a, 'cpu'), (b, 'cuda'))]
            else:               # the CVAEs decoded from the prior's mean
                out = [n.decode(n.condition(batch['image'].to(d), batch['category'].to(d)),
                                batch['category'].to(d), torch.zeros(8, m.latent, device=d))
                       for n, d in ((a, 'cpu'), (b, 'cuda'))]
        # float32 convolutions; cuDNN may use TF32 (about 3e-4)
        assert _close(out[1], out[0]) < 2e-3, name


def test_synthesis_on_cuda_is_valid_and_reproducible():
    synth = Synthesizer(config=SynthConfig(device='cuda'))
    for rt in ROOM_TYPES:
        room = empty_room(rt, 100)
        a = synth.generate(room, seed=3).scene
        b = synth.generate(room, seed=3).scene
        assert len(a.objects) >= (1 if rt in PASSAGE_ROOM_TYPES else 2), rt   # a hall: 1-5
        assert check_scene(a).ok, (rt, check_scene(a).summary())
        assert [o.to_dict() for o in a.objects] == [o.to_dict() for o in b.objects], rt


def test_rooms_in_lockstep_on_cuda_are_valid_and_nearly_all_the_rooms_made_alone():
    synth = Synthesizer(config=SynthConfig(device='cuda'))
    rooms = [empty_room(ROOM_TYPES[i % len(ROOM_TYPES)], 100 + i) for i in range(8)]
    alone = [synth.generate(r, seed=i).scene for i, r in enumerate(rooms)]
    grouped = [s.scene for s in lockstep.run(
        [lambda r=r, i=i: synth.generate(r, seed=i) for i, r in enumerate(rooms)], width=4)]
    for g in grouped:
        assert check_scene(g).ok and g.objects
    same = sum([(o.category, o.model_id) for o in a.objects] ==
               [(o.category, o.model_id) for o in g.objects]
               for a, g in zip(alone, grouped, strict=True))
    assert same >= 6, f'{same} of 8 rooms the same'


def test_a_batch_on_cuda_furnishes_every_room(tmp_path):
    """Batch workers on CUDA are spawned (a forked child cannot use the CUDA its parent
    initialised: every room failed before)."""
    from scene_synth_ros.batch import BatchConfig, Source, run_batch
    cfg = BatchConfig(out=tmp_path / 'out', source=Source.shells(['bedroom']), n=8, workers=2,
                      lockstep=4, synthesis=SynthConfig(device='cuda', runtime='torch'))
    summary = run_batch(cfg, echo=lambda s: None)
    assert summary.rooms_ok == 8 and summary.valid == 8, summary


def test_training_steps_on_cuda_with_pinned_loader_workers(tmp_path):
    cfg = tiny_config(steps=3)
    cfg = replace(cfg, device='cuda', train=replace(cfg.train, loader_workers=2))
    corpus = load_corpus('bathroom', cfg, workers=1)
    src = ExampleSource('bathroom', corpus.train, 64, 64, target_radius=1)
    val = ExampleSource('bathroom', corpus.val, 64, 64, target_radius=1)
    nets = build_networks('bathroom', cfg.model, seed=0)
    for name in ('location', 'dimensions'):
        metrics = train_module(name, nets[name], src, val, cfg, torch.device('cuda'),
                               tmp_path, lambda e: None, False)
        assert all(torch.isfinite(torch.tensor(v)) for v in metrics.values()), name
        assert next(nets[name].parameters()).is_cuda
        loss, _ = batch_loss(name, nets[name], src.batch(name, [1, 2, 3], 4), cfg, 'cuda')
        assert loss.is_cuda and torch.isfinite(loss)
