"""What runs synthesis's networks (``networks.runtime``): onnxruntime answers every call as
torch does to the last digits, at a batch of one and of several, whichever way the images are
laid out, with and without location offsets, and leaves larger batches to torch; its rooms
are torch's but where those digits tip a draw, and the same seed gives the same room;
``auto`` chooses it on the CPU, torch where it cannot run; a runtime that cannot be is one
sentence."""
import sys

import pytest
import torch

from scene_synth_ros import lockstep
from scene_synth_ros.categories import room_spec
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.networks.config import resolve_runtime
from scene_synth_ros.networks.runtime import ONNX_MAX_BATCH, OnnxCalls, forward
from scene_synth_ros.render import FIRST_CATEGORY
from scene_synth_ros.synth import SynthConfig, SynthesisError, Synthesizer


@pytest.fixture(scope='module')
def one_thread():
    threads = torch.get_num_threads()
    torch.set_num_threads(1)            # as a batch worker runs
    yield
    torch.set_num_threads(threads)


@pytest.fixture(scope='module')
def synth(one_thread):
    return Synthesizer(config=SynthConfig(runtime='onnxruntime'))


def calls_of(synth, room_type: str, batch: int, channels_last: bool, seed: int) -> list:
    """One (module, args) of each network call, on random inputs of ``batch`` examples."""
    nets = synth.bundle(room_type).networks
    k = len(room_spec(room_type).names)
    n = synth.bundle(room_type).config.model.resolution
    g = torch.Generator().manual_seed(seed)
    layout = torch.channels_last if channels_last else torch.contiguous_format
    image = torch.rand(batch, FIRST_CATEGORY + k, n, n, generator=g).round()
    image = image.contiguous(memory_format=layout)
    counts = torch.randint(0, 3, (batch, k), generator=g).float()
    cats = torch.randint(0, k, (batch,), generator=g)
    z = torch.randn(batch, nets['orientation'].latent, generator=g)
    return [('category', (image, counts)), ('location', (image,)),
            ('orientation', (image, cats, z)), ('dimensions', (image, cats, z))]


@pytest.mark.parametrize('weights', ['shipped', 'tiny'])
def test_onnxruntime_answers_every_call_as_torch_does(synth, tiny_weights, weights, one_thread):
    # The tiny bundles regress location offsets, the shipped ones do not.
    s = synth if weights == 'shipped' else Synthesizer(
        tiny_weights, SynthConfig(runtime='onnxruntime'))
    for room_type in ('bedroom', 'bathroom'):
        calls, nets = s.calls(room_type), s.bundle(room_type).networks
        assert isinstance(calls, OnnxCalls) and calls.exported == ()
        # The first call exports at a batch of three; the others run the same graph.
        for batch, channels_last in [(3, True), (1, True), (2, False), (1, False)]:
            for module, args in calls_of(s, room_type, batch, channels_last, seed=batch):
                with torch.inference_mode():
                    got = calls(module, *args)
                    want = forward(nets, module, *args)
                assert len(got) == len(want), module
                for a, b in zip(got, want, strict=True):
                    if b is None:
                        assert a is None, module
                        continue
                    assert a.shape == b.shape and a.shape[0] == batch, module
                    scale = float(b.abs().max()) or 1.0
                    assert float((a - b).abs().max()) <= 1e-4 * scale, (module, batch)
        assert calls.exported == ('category', 'dimensions', 'location', 'orientation')
        offsets = forward(nets, 'location', *calls_of(s, room_type, 1, True, 0)[1][1])[1]
        assert (offsets is not None) == (weights == 'tiny')
        # A batch larger than onnxruntime's limit is torch's to the last digit.
        for module, args in calls_of(s, room_type, max(ONNX_MAX_BATCH.values()) + 1, True, 9):
            with torch.inference_mode():
                got, want = calls(module, *args), forward(nets, module, *args)
            assert all(a is b is None or torch.equal(a, b)
                       for a, b in zip(got, want, strict=True)), module
    with pytest.raises(ValueError, match='no network call'):
        s.calls('bedroom')('colour', torch.zeros(1))


def test_rooms_of_onnxruntime_are_torchs_but_for_the_last_digits(synth):
    by_torch = Synthesizer(config=SynthConfig(runtime='torch'))
    assert (synth.runtime, by_torch.runtime) == ('onnxruntime', 'torch')
    assert not isinstance(by_torch.calls('bedroom'), OnnxCalls)
    rooms = [empty_room('bedroom' if i % 4 else 'bathroom', HELDOUT_SEED, i) for i in range(16)]

    def objects(scene) -> list[tuple]:
        return [(o.category, o.model_id, round(o.position[0], 3), round(o.position[1], 3),
                 round(o.yaw, 3)) for o in scene.objects]

    ours = [synth.generate(r, seed=i) for i, r in enumerate(rooms)]
    theirs = [by_torch.generate(r, seed=i) for i, r in enumerate(rooms)]
    same = sum(objects(a.scene) == objects(b.scene) for a, b in zip(ours, theirs, strict=True))
    # The runtimes sum in other orders (about 1e-6 of an output): a draw that falls that
    # close to a boundary goes the other way, rarely.
    assert same >= 14, f'{same} of 16 rooms the same'
    for r in ours:
        assert check_scene(r.scene).ok and r.robot.kept and r.scene.objects
    # The same seed gives the same room, in a synthesizer that exports its graphs anew, and
    # in lockstep with other rooms.
    again = Synthesizer(config=SynthConfig(runtime='onnxruntime'))
    assert objects(again.generate(rooms[1], seed=1).scene) == objects(ours[1].scene)
    grouped = lockstep.run([lambda r=r, i=i: synth.generate(r, seed=i)
                            for i, r in enumerate(rooms[:8])])
    same = sum(objects(a.scene) == objects(g.scene) for a, g in zip(ours[:8], grouped, strict=True))
    assert same >= 7, f'{same} of 8 rooms in lockstep the same'


def test_auto_is_onnxruntime_on_the_cpu_and_torch_where_it_cannot_run(monkeypatch):
    cpu, cuda = torch.device('cpu'), torch.device('cuda')
    assert resolve_runtime('auto', cpu) == 'onnxruntime'
    assert resolve_runtime('auto', cuda) == 'torch'
    assert resolve_runtime('torch', cpu) == resolve_runtime('torch', cuda) == 'torch'
    assert resolve_runtime('onnxruntime', cpu) == 'onnxruntime'
    with pytest.raises(ValueError, match='runs on the CPU, not on cuda'):
        resolve_runtime('onnxruntime', cuda)
    with pytest.raises(ValueError) as e:
        resolve_runtime('x' * 100_000, cpu)
    assert 'the runtimes are auto, torch, onnxruntime' in str(e.value)
    assert len(str(e.value)) < 200 and '\n' not in str(e.value)
    with pytest.raises(SynthesisError, match='no runtime'):
        Synthesizer(config=SynthConfig(runtime='tpu'))
    # Where onnxruntime is not installed (an import of it fails), auto is torch and asking
    # for it says what to install.
    monkeypatch.setitem(sys.modules, 'onnxruntime', None)
    assert resolve_runtime('auto', cpu) == 'torch'
    assert Synthesizer().runtime == 'torch'
    with pytest.raises(SynthesisError, match='needs the onnxruntime package'):
        Synthesizer(config=SynthConfig(runtime='onnxruntime'))
