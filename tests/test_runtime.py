"""What runs synthesis's networks (``networks.runtime``): onnxruntime answers every call as
torch does to the last digits, at a batch of one and of several, whichever way the images are
laid out, with and without location offsets, and leaves larger batches to torch; its rooms
are torch's but where those digits tip a draw, and the same seed gives the same room;
``auto`` chooses it on the CPU, torch where it cannot run; a runtime that cannot be is one
sentence."""
import copy
import os
import subprocess
import sys

import numpy as np
import pytest
import torch

from scene_synth_ros import lockstep
from scene_synth_ros.categories import room_spec
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.errors import ConfigError
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.networks import runtime
from scene_synth_ros.networks.config import resolve_runtime
from scene_synth_ros.networks.graphs import TorchCalls, weights_hash
from scene_synth_ros.networks.runtime import (
    CACHE_ENV,
    MODULE_CALLS,
    ONNX_MAX_BATCH,
    OnnxCalls,
    graph_cache_dir,
    graph_key,
    padded_channels,
)
from scene_synth_ros.render import FIRST_CATEGORY
from scene_synth_ros.synth import SynthConfig, SynthesisError, Synthesizer


@pytest.fixture(scope='module')
def one_thread():
    threads = torch.get_num_threads()
    runtime.set_threads(1)              # as a batch worker runs: torch and onnxruntime
    assert torch.get_num_threads() == runtime.threads() == 1
    yield
    runtime.set_threads(None)
    torch.set_num_threads(threads)


@pytest.fixture(scope='module')
def synth(one_thread):
    return Synthesizer(config=SynthConfig(runtime='onnxruntime'))


def calls_of(synth, room_type: str, batch: int, channels_last: bool, seed: int) -> list:
    """One (module, args) of each network call, on random inputs of ``batch`` examples, as
    synthesis hands them over: numpy arrays, the images laid out either way."""
    nets = synth.bundle(room_type).networks
    k = len(room_spec(room_type).names)
    n = synth.bundle(room_type).config.model.resolution
    g = torch.Generator().manual_seed(seed)
    layout = torch.channels_last if channels_last else torch.contiguous_format
    image = torch.rand(batch, FIRST_CATEGORY + k, n, n, generator=g).round()
    image = image.contiguous(memory_format=layout).numpy()
    counts = torch.randint(0, 3, (batch, k), generator=g).float().numpy()
    cats = torch.randint(0, k, (batch,), generator=g).numpy()
    z = torch.randn(batch, nets['orientation'].latent, generator=g).numpy()
    return [('category', (image, counts)), ('location', (image,)),
            ('orientation', (image, cats, z)), ('dimensions', (image, cats, z))]


@pytest.mark.parametrize('weights', ['shipped', 'tiny'])
def test_onnxruntime_answers_every_call_as_torch_does(synth, tiny_weights, weights, one_thread):
    # The tiny bundles regress location offsets, the shipped ones do not.
    s = synth if weights == 'shipped' else Synthesizer(
        tiny_weights, SynthConfig(runtime='onnxruntime'))
    for room_type in ('bedroom', 'bathroom'):
        # The calls before ``prepare`` (which a synthesizer runs at a room type's first use).
        calls, nets = s.networks.calls(room_type), s.bundle(room_type).networks
        assert isinstance(calls, OnnxCalls) and calls.exported == ()
        # The first call exports at a batch of three; the others run the same graph.
        for batch, channels_last in [(3, True), (1, True), (2, False), (1, False)]:
            for module, args in calls_of(s, room_type, batch, channels_last, seed=batch):
                got = calls(module, *args)
                want = TorchCalls(nets)(module, *args)
                assert len(got) == len(want), module
                for a, b in zip(got, want, strict=True):
                    if b is None:
                        assert a is None, module
                        continue
                    assert isinstance(a, np.ndarray) and a.dtype == b.dtype, module
                    assert a.shape == b.shape and a.shape[0] == batch, module
                    scale = float(np.abs(b).max()) or 1.0
                    assert float(np.abs(a - b).max()) <= 1e-4 * scale, (module, batch)
        assert calls.exported == ('category', 'dimensions', 'location', 'orientation')
        offsets = TorchCalls(nets)('location', *calls_of(s, room_type, 1, True, 0)[1][1])[1]
        assert (offsets is not None) == (weights == 'tiny')
        # A batch larger than onnxruntime's limit is torch's to the last digit.
        for module, args in calls_of(s, room_type, ONNX_MAX_BATCH + 1, True, 9):
            got, want = calls(module, *args), TorchCalls(nets)(module, *args)
            assert all(a is b is None or np.array_equal(a, b)
                       for a, b in zip(got, want, strict=True)), module
    with pytest.raises(ValueError, match='no network call'):
        s.calls('bedroom')('colour', np.zeros(1))


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
    # The same seed gives the same room, in a synthesizer that reads its graphs from the
    # cache, and in lockstep with other rooms.
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
    with pytest.raises(ConfigError, match='runtime must be one of auto, torch, onnxruntime'):
        SynthConfig(runtime='tpu')
    # Where onnxruntime is not installed (an import of it fails), auto is torch and asking
    # for it says what to install.
    monkeypatch.setitem(sys.modules, 'onnxruntime', None)
    assert resolve_runtime('auto', cpu) == 'torch'
    assert Synthesizer().runtime == 'torch'
    with pytest.raises(SynthesisError, match='needs the onnxruntime package'):
        Synthesizer(config=SynthConfig(runtime='onnxruntime'))


def test_graphs_are_kept_on_disk_and_read_back_without_an_export(synth, tmp_path, monkeypatch):
    nets = synth.bundle('bedroom').networks
    args = calls_of(synth, 'bedroom', 1, True, seed=3)
    first = OnnxCalls(nets, cache_dir=tmp_path)
    want = {module: first(module, *a) for module, a in args}
    assert first.loaded == [] and first.exported == tuple(sorted(MODULE_CALLS))
    kept = sorted(p.name.split('-')[0] for p in tmp_path.glob('*.onnx'))
    assert kept == sorted(MODULE_CALLS) and not list(tmp_path.glob('.*'))

    # Another process's calls (a fresh OnnxCalls) read the graphs back: exporting fails
    # here, and every answer is the very one the exported graph gave.
    def no_export(*a, **k):
        raise AssertionError('exported again')
    monkeypatch.setattr(torch.onnx, 'export', no_export)
    again = OnnxCalls(nets, cache_dir=tmp_path)
    for module, a in args:
        assert all(np.array_equal(x, y) for x, y in zip(again(module, *a), want[module],
                                                         strict=True) if y is not None)
    assert sorted(again.loaded) == sorted(MODULE_CALLS)
    monkeypatch.undo()

    # A damaged graph is exported again and replaced; its answers are unchanged.
    damaged = next(tmp_path.glob('location-*.onnx'))
    damaged.write_bytes(b'not a graph' * 100)
    third = OnnxCalls(nets, cache_dir=tmp_path)
    got = third('location', *args[1][1])
    assert 'location' not in third.loaded and np.array_equal(got[0], want['location'][0])
    assert damaged.read_bytes()[:20] != b'not a graph' * 2

    # A cache that cannot be written (its directory is a file) costs only the export.
    blocked = tmp_path / 'a file'
    blocked.write_text('x')
    fourth = OnnxCalls(nets, cache_dir=blocked / 'graphs')
    assert np.array_equal(fourth('dimensions', *args[3][1])[0], want['dimensions'][0])
    assert blocked.read_text() == 'x'

    # Beyond CACHE_GRAPHS the least recently used graphs go; a graph read back was used.
    monkeypatch.setattr(runtime, 'CACHE_GRAPHS', 2)
    small = tmp_path / 'small'
    small.mkdir()
    for k in (1, 2):
        (small / f'category-stale{k}.onnx').write_bytes(b'old')
        os.utime(small / f'category-stale{k}.onnx', (1000 * k, 1000 * k))
    # Files of others in the directory are not the cache's to prune.
    (small / 'theirs.onnx').write_bytes(b'not ours')
    os.utime(small / 'theirs.onnx', (1, 1))
    OnnxCalls(nets, cache_dir=small)('dimensions', *args[3][1])
    dims = next(small.glob('dimensions-*.onnx'))
    assert sorted(p.name for p in small.glob('*.onnx')) == sorted(
        [dims.name, 'category-stale2.onnx', 'theirs.onnx'])
    os.utime(dims, (500, 500))
    reader = OnnxCalls(nets, cache_dir=small)
    reader('dimensions', *args[3][1])
    reader('category', *args[0][1])
    assert reader.loaded == ['dimensions']
    assert {p.name.split('-')[0] for p in small.glob('*.onnx')} == \
        {'dimensions', 'category', 'theirs.onnx'}


def test_a_graph_is_named_by_the_weights_and_the_inputs(synth):
    nets = synth.bundle('bedroom').networks
    image = np.zeros((1, 64, 64, 48), dtype=np.float32)
    weights = weights_hash(nets, 'location')
    key = graph_key(weights, 'location', (image,))
    assert key == graph_key(weights_hash(nets, 'location'), 'location', (image.copy(),))
    assert key != graph_key(weights, 'location', (np.zeros((1, 32, 32, 48), np.float32),))
    assert key != graph_key(weights, 'location', (image.astype(np.float64),))
    assert weights != weights_hash(synth.bundle('bathroom').networks, 'location')
    # One weight changed by a little: other weights. Only the networks a call runs count.
    changed = {name: copy.deepcopy(net) if name == 'location' else net
               for name, net in nets.items()}
    with torch.no_grad():
        weight = next(changed['location'].parameters())
        weight[(0,) * weight.dim()] += 1e-6
    assert weights != weights_hash(changed, 'location')
    assert weights_hash(nets, 'category') == weights_hash(changed, 'category')
    # A bundle's calls are named by its file's bytes instead: no weight is read for it.
    calls = synth.calls('bedroom')
    assert calls.weights == synth.networks.served('bedroom').weights
    assert len(calls.weights) == 32


_WITHOUT_TORCH = """
import json, sys
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.synth import Synthesizer
synth = Synthesizer()
scene = synth.generate(empty_room('bedroom', 7, 3), seed=3).scene
print(json.dumps([[o.category, o.model_id, o.position, o.yaw] for o in scene.objects]))
print('torch' in sys.modules, synth.calls('bedroom').loaded)
"""


def test_with_its_graphs_and_records_cached_a_process_furnishes_rooms_without_torch(tmp_path):
    # The node's start-up: importing torch alone is longer than the rest of it. The first
    # process exports the graphs and keeps the bundles' records; the next reads both and
    # makes the very same room without importing torch.
    env = dict(os.environ, **{CACHE_ENV: str(tmp_path / 'cache')})

    def run() -> list[str]:
        out = subprocess.run([sys.executable, '-c', _WITHOUT_TORCH], env=env, text=True,
                             capture_output=True, timeout=300, check=True)
        return out.stdout.splitlines()

    first, again = run(), run()
    assert first[1].startswith('True')
    assert again == [first[0], "False ['category', 'location', 'orientation', 'dimensions']"]
    # The bedroom's record, and a note of every bundle's room type.
    records = sorted((tmp_path / 'cache').glob('bundle-*.npz'))
    notes = sorted((tmp_path / 'cache').glob('spec-*.json'))
    assert (len(records), len(notes)) == (1, len(Synthesizer().room_types))
    # A record that cannot be read is made again from the bundle, and changes no room.
    for r in records:
        r.write_bytes(b'damaged')
    assert run()[0] == first[0]
    assert all(r.read_bytes() != b'damaged' for r in records)


def test_the_cache_directory_follows_the_environment(monkeypatch, tmp_path):
    monkeypatch.setenv(CACHE_ENV, 'off')
    assert graph_cache_dir() is None
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / 'mine'))
    assert graph_cache_dir() == tmp_path / 'mine'
    monkeypatch.delenv(CACHE_ENV)
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'xdg'))
    assert graph_cache_dir() == tmp_path / 'xdg' / 'scene_synth_ros' / 'onnx'
    monkeypatch.delenv('XDG_CACHE_HOME')
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    assert graph_cache_dir() == tmp_path / 'home' / '.cache' / 'scene_synth_ros' / 'onnx'


def test_images_drawn_with_zero_channels_are_taken_as_they_are(synth):
    calls = synth.calls('bedroom')
    c = calls.channels
    assert c == FIRST_CATEGORY + len(room_spec('bedroom').names)
    assert calls.image_channels == padded_channels(c) and calls.image_channels % 16 == 0
    # What the synthesizer draws for onnxruntime: the zero channels already there.
    image = synth.networks.image(64, c, calls=calls)
    assert image.shape == (calls.image_channels, 64, 64)
    assert not image[c:].any()
    module, args = calls_of(synth, 'bedroom', 1, True, seed=5)[1]
    image[:c] = args[0][0]
    drawn = image[None]
    assert calls._image(drawn).base is not None          # no copy: a view of the drawing
    a, b = calls(module, drawn)[0], calls(module, *args)[0]
    assert np.array_equal(a, b)
    with pytest.raises(ValueError, match='an image of 40 channels for networks that take'):
        calls(module, np.zeros((1, 40, 64, 64), np.float32))
    # torch draws the channels the networks take, no more.
    by_torch = Synthesizer(config=SynthConfig(runtime='torch'))
    assert by_torch.networks.image(64, c, calls=by_torch.calls('bedroom')).shape[0] == c


def test_loading_every_bundle_readies_every_call(tiny_weights, one_thread):
    # The evaluation readies every bundle before its first room (the node its room type's):
    # in onnxruntime that also exports (or reads back) each call's graph, so no room pays
    # for it, and it changes no room.
    ready = Synthesizer(tiny_weights, SynthConfig(runtime='onnxruntime'))
    ready.load_all()
    for room_type in ready.room_types:
        assert ready.calls(room_type).exported == tuple(sorted(MODULE_CALLS))
    fresh = Synthesizer(tiny_weights, SynthConfig(runtime='onnxruntime'))
    room = empty_room('bedroom', HELDOUT_SEED, 3)
    a, b = ready.generate(room, seed=3).scene, fresh.generate(room, seed=3).scene
    assert [(o.category, o.position, o.yaw) for o in a.objects] == \
        [(o.category, o.position, o.yaw) for o in b.objects]
    by_torch = Synthesizer(tiny_weights, SynthConfig(runtime='torch'))
    by_torch.load_all()
    assert not isinstance(by_torch.calls('bedroom'), OnnxCalls)


def test_networks_onnxruntime_cannot_run_are_torchs_under_auto(tiny_weights, monkeypatch,
                                                                one_thread):
    # Loading every bundle finds out at once: under auto such a room type runs torch, and
    # its rooms are made; asked for by name, onnxruntime's failure is one sentence.
    def broken(graph, module):
        raise RuntimeError('unsupported operator ' + 'x' * 10_000)
    monkeypatch.setattr(runtime, '_session', broken)
    monkeypatch.setenv(CACHE_ENV, 'off')
    auto = Synthesizer(tiny_weights)
    assert auto.runtime == 'onnxruntime'
    auto.load_all()
    assert not isinstance(auto.calls('bedroom'), OnnxCalls)
    result = auto.generate(empty_room('bedroom', HELDOUT_SEED, 2), seed=2)
    assert check_scene(result.scene).ok and result.scene.objects
    with pytest.raises(SynthesisError) as e:
        Synthesizer(tiny_weights, SynthConfig(runtime='onnxruntime')).load_all()
    message = str(e.value)
    assert message.startswith('onnxruntime cannot run the ')
    assert "networks' category call (RuntimeError: unsupported operator" in message
    assert message.endswith('runtime torch runs them')
    assert len(message) < 300 and '\n' not in message


def test_weights_replaced_while_in_use_are_refused_not_cached_under_the_old_name(
        tmp_path, monkeypatch):
    from scene_synth_ros.networks.served import BundleError, keep_record
    from scene_synth_ros.paths import weights_dir
    monkeypatch.setenv(CACHE_ENV, str(tmp_path / 'cache'))
    weights = tmp_path / 'weights'
    weights.mkdir()
    for rt in ('bedroom', 'bathroom'):
        (weights / f'{rt}.pt').write_bytes((weights_dir() / f'{rt}.pt').read_bytes())
    s = Synthesizer(weights, SynthConfig(runtime='onnxruntime'))
    s.networks.served('bedroom')            # its record; its graphs not exported yet
    # Other weights copied over the file: the graphs are not exported from them under the
    # name of the weights the record was made of, whatever was loaded meanwhile.
    (weights / 'bedroom.pt').write_bytes((weights_dir() / 'office.pt').read_bytes())
    with pytest.raises(BundleError, match='bedroom.pt: the file changed while it was in use'):
        s.calls('bedroom')
    assert not list((tmp_path / 'cache').glob('*.onnx'))
    # A record of networks that take other images than this code draws is refused, not
    # served: one sentence naming the file.
    fresh = Synthesizer(weights, SynthConfig(runtime='onnxruntime'))
    record = fresh.networks.served('bathroom')
    record.channels += 1
    keep_record(record)
    with pytest.raises(BundleError, match=r'bathroom.pt: weights do not match the networks '
                                          r'of this version \(they take images of'):
        Synthesizer(weights, SynthConfig(runtime='onnxruntime')).networks.served('bathroom')


def test_the_threads_asked_for_reach_onnxruntime_and_torch(monkeypatch):
    threads = torch.get_num_threads()
    try:
        runtime.set_threads(1)
        assert runtime.threads() == torch.get_num_threads() == 1
        runtime.set_threads(None)
        # Nothing asked for: torch's count where torch is loaded (it is, here).
        torch.set_num_threads(2)
        assert runtime.threads() == 2
    finally:
        runtime.set_threads(None)
        torch.set_num_threads(threads)
    # Without torch: OMP_NUM_THREADS where it is set, else the CPUs the process may use.
    code = ('import sys; from scene_synth_ros.networks import runtime; '
            'print(runtime.threads(), "torch" in sys.modules)')
    for omp, want in (('1', '1'), ('', str(len(os.sched_getaffinity(0))))):
        env = dict(os.environ, OMP_NUM_THREADS=omp)
        out = subprocess.run([sys.executable, '-c', code], env=env, text=True,
                             capture_output=True, check=True).stdout.split()
        assert out == [want, 'False']
