"""Rooms in lockstep (``scene_synth_ros.lockstep``): a group's network calls served as one
batch per bundle and module, each room's answers those of its own examples; rooms in lockstep
the rooms made alone but where a batch's last digits tip a draw; one room's failure its own."""
import numpy as np
import pytest
import torch

from scene_synth_ros import lockstep
from scene_synth_ros.categories import room_spec
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.networks import runtime
from scene_synth_ros.networks.runtime import padded_channels
from scene_synth_ros.render import FIRST_CATEGORY
from scene_synth_ros.scene import Room
from scene_synth_ros.synth import SynthConfig, SynthesisError, Synthesizer


@pytest.fixture(scope='module')
def synth():
    threads = torch.get_num_threads()
    runtime.set_threads(1)              # as a batch worker runs: torch and onnxruntime
    yield Synthesizer()
    runtime.set_threads(None)
    torch.set_num_threads(threads)


def objects(scene) -> list[tuple]:
    """What a room is, to a millimetre and a thousandth of a radian."""
    return [(o.category, o.model_id, round(o.position[0], 3), round(o.position[1], 3),
             round(o.yaw, 3)) for o in scene.objects]


def test_serve_answers_each_request_with_its_own_examples(synth):
    requests = []
    g = torch.Generator().manual_seed(1)
    for rt in ('bedroom', 'bathroom', 'bedroom'):
        calls, k = synth.calls(rt), len(room_spec(rt).names)
        channels = FIRST_CATEGORY + k
        image = torch.rand(1, channels, 64, 64, generator=g).numpy()
        counts = torch.randint(0, 3, (1, k), generator=g).float().numpy()
        crops = torch.rand(3, channels, 64, 64, generator=g).numpy()
        cats = torch.randint(0, k, (3,), generator=g).numpy()
        z = torch.randn(3, synth.networks.served(rt).latents['orientation'],
                        generator=g).numpy()
        requests += [lockstep.Request(calls, 'category', (image, counts)),
                     lockstep.Request(calls, 'location', (image,)),
                     lockstep.Request(calls, 'orientation', (crops, cats, z)),
                     lockstep.Request(calls, 'dimensions', (crops, cats, z))]
    served = lockstep.serve(requests)
    for r, answer in zip(requests, served, strict=True):
        alone = r.networks(r.module, *r.args)
        assert len(answer) == len(alone)
        for a, b in zip(answer, alone, strict=True):
            if b is None:
                assert a is None
                continue
            assert a.shape == b.shape and a.shape[0] == r.size
            assert np.allclose(a, b, atol=1e-4, rtol=1e-4), r.module
    with pytest.raises(ValueError, match='no network call'):
        lockstep.ask(synth.calls('bedroom'), 'colour', np.zeros(1))


def test_a_room_alone_in_lockstep_is_the_room_made_alone(synth):
    room = empty_room('bedroom', HELDOUT_SEED, 3)
    alone = synth.generate(room, seed=3)
    [grouped] = lockstep.run([lambda: synth.generate(room, seed=3)])
    assert objects(grouped.scene) == objects(alone.scene) and alone.scene.objects


def test_rooms_in_lockstep_are_the_rooms_made_alone_but_for_the_last_digits(synth):
    # Bedrooms and bathrooms mixed in one group: each bundle's calls are batched apart.
    rooms = [empty_room('bedroom' if i % 3 else 'bathroom', HELDOUT_SEED, i) for i in range(16)]
    alone = [synth.generate(r, seed=i) for i, r in enumerate(rooms)]
    grouped = lockstep.run([lambda r=r, i=i: synth.generate(r, seed=i)
                            for i, r in enumerate(rooms)])
    same = sum(objects(a.scene) == objects(g.scene) for a, g in zip(alone, grouped, strict=True))
    # A batch sums in another order than one example (about 1e-5): a draw that falls that
    # close to a boundary goes the other way, rarely.
    assert same >= 14, f'{same} of 16 rooms the same'
    for g in grouped:
        assert check_scene(g.scene).ok and g.robot.kept and g.scene.objects
    assert [g.scene.room.room_type for g in grouped] == [r.room_type for r in rooms]


def test_rooms_of_several_sizes_in_lockstep_are_batched_by_image_size(synth):
    # Bedrooms of the 6 m square (64 px) and larger ones (96 and 128 px) in one group: the
    # category and location calls are batched by image size, so each room is the one made
    # alone but for the last digits.
    sizes = [(4.0, 3.5), (7.5, 3.8), (5.0, 4.0), (10.0, 4.0), (7.0, 5.0), (4.5, 4.5)]
    rooms = [Room('bedroom', ((0, 0), (w, 0), (w, d), (0, d)), 2.6) for w, d in sizes]
    alone = [synth.generate(r, seed=i) for i, r in enumerate(rooms)]
    grouped = lockstep.run([lambda r=r, i=i: synth.generate(r, seed=i)
                            for i, r in enumerate(rooms)])
    same = sum(objects(a.scene) == objects(g.scene) for a, g in zip(alone, grouped, strict=True))
    assert same >= 5, f'{same} of 6 rooms the same'
    for g in grouped:
        assert check_scene(g.scene).ok and g.robot.kept and g.scene.objects


def test_rooms_in_lockstep_are_equal_in_distribution_to_rooms_made_alone(synth):
    # Other seeds on each side, so that the rooms are independent draws: the mean objects
    # per room and the share of each category agree within what 48 rooms a side allow.
    rooms = [empty_room('bedroom', HELDOUT_SEED, i) for i in range(48)]
    alone = [synth.generate(r, seed=1000 + i).scene for i, r in enumerate(rooms)]
    grouped = []
    for k in range(0, 48, 8):
        grouped += [s.scene for s in lockstep.run(
            [lambda r=r, i=i: synth.generate(r, seed=2000 + i)
             for i, r in list(enumerate(rooms))[k:k + 8]])]
    a = torch.tensor([len(s.objects) for s in alone], dtype=torch.float64)
    g = torch.tensor([len(s.objects) for s in grouped], dtype=torch.float64)
    se = (a.var() / len(a) + g.var() / len(g)).sqrt()
    assert abs(a.mean() - g.mean()) < 3 * se, (a.mean(), g.mean())
    for category in ('double bed', 'wardrobe', 'stand'):
        pa = sum(o.category == category for s in alone for o in s.objects) / a.sum()
        pg = sum(o.category == category for s in grouped for o in s.objects) / g.sum()
        assert abs(pa - pg) < 0.06, (category, pa, pg)


def test_a_room_that_fails_is_its_own_result_and_the_group_goes_on(synth):
    sliver = Room('bedroom', ((0, 0), (6, 0), (6, 0.12), (0, 0.12)))
    good = empty_room('bedroom', HELDOUT_SEED, 0)
    results = lockstep.run([lambda: synth.generate(good, seed=0),
                            lambda: synth.generate(sliver, seed=1),
                            lambda: synth.generate(good, seed=2)])
    assert isinstance(results[1], SynthesisError) and 'too small or narrow' in str(results[1])
    assert objects(results[0].scene) and objects(results[2].scene)
    assert objects(results[0].scene) == objects(synth.generate(good, seed=0).scene)


def test_lockstep_serves_complete_and_next_object_too(synth):
    room = empty_room('office', HELDOUT_SEED, 5)
    partial = synth.generate(room, seed=5).scene
    partial.objects = partial.objects[:2]
    config = SynthConfig()
    assert config.location_batch == 1       # candidates decoded one at a time by default
    results = lockstep.run([lambda: synth.complete(partial, seed=7),
                            lambda: synth.next_object(partial, seed=8)])
    assert results[0].scene.objects[:2] == partial.objects
    assert results[1] is not None and results[1].id not in {o.id for o in partial.objects}


def test_a_run_cut_short_at_the_rooms_needed_gives_them_as_a_whole_run_does(synth):
    rooms = [empty_room('bedroom', HELDOUT_SEED, i) for i in range(6)]
    calls = [lambda r=r, i=i: synth.generate(r, seed=i) for i, r in enumerate(rooms)]
    whole = lockstep.run(calls, width=2)
    cut = lockstep.run(calls, width=2, needed=[2])
    assert objects(cut[2].scene) == objects(whole[2].scene)
    assert cut[5] is None                   # never started, or abandoned under way
    # The abandoned rooms were unwound inside the group: the caller's torch is as it was.
    assert not torch.is_inference_mode_enabled() and torch.is_grad_enabled()
    assert all(r is not None for r in whole)
    # Two at a time is not all at once: the rooms' calls are batched differently, yet the
    # rooms are (nearly always) the same.
    assert sum(objects(a.scene) == objects(b.scene)
               for a, b in zip(whole, lockstep.run(calls), strict=True)) >= 5


def test_each_gives_a_room_as_it_ends_with_the_consumer_outside_inference_mode(synth):
    rooms = [empty_room('bathroom', HELDOUT_SEED, i) for i in range(5)]
    started: list[int] = []

    def furnish(i):
        started.append(i)
        return synth.generate(rooms[i], seed=i)

    calls = [lambda i=i: furnish(i) for i in range(5)]
    whole = lockstep.run(calls, width=2)
    order, seen = [], []
    started.clear()
    for k, result in lockstep.each(calls, width=2):
        # The first room comes back while the group is still under way (two at a time: the
        # last room has not started), and the consumer runs as the caller does.
        seen.append(len(started))
        order.append(k)
        assert not torch.is_inference_mode_enabled()
        assert objects(result.scene) == objects(whole[k].scene)
    assert sorted(order) == list(range(5)) and seen[0] < 5
    # Closing the iterator mid-group abandons the rooms under way, unwound in the group.
    rooms_left = lockstep.each(calls, width=2)
    next(rooms_left)
    rooms_left.close()
    assert not torch.is_inference_mode_enabled() and torch.is_grad_enabled()


def test_images_are_drawn_channels_last_as_the_networks_take_them(synth):
    # On the CPU the renderer draws into channels-last memory (no copy before the networks),
    # the very pixels of a channels-first image; a batch of them stays channels-last when
    # the rooms' requests are put together.
    scene = synth.generate(empty_room('bedroom', HELDOUT_SEED, 1), seed=1).scene
    renderer = synth._renderer(64)
    channels = FIRST_CATEGORY + len(room_spec('bedroom').names)
    # For onnxruntime zero channels follow the drawn ones (``runtime.padded_channels``).
    full = synth.networks.image(64, channels, calls=synth.calls('bedroom'))
    assert full.shape[0] == (padded_channels(channels) if synth.runtime == 'onnxruntime'
                             else channels)
    drawn = renderer.render(scene, out=full[:channels])
    assert (drawn == renderer.render(scene)).all() and not full[channels:].any()
    image = full[None]
    assert np.moveaxis(image, 1, -1).flags.c_contiguous           # channels-last
    batch = lockstep._cat([image, image])
    assert np.moveaxis(batch, 1, -1).flags.c_contiguous
    assert np.array_equal(batch, np.concatenate([image, image]))
    conv = next(m for m in synth.bundle('bedroom').networks['location'].modules()
                if isinstance(m, torch.nn.Conv2d))
    assert conv.weight.is_contiguous(memory_format=torch.channels_last)
