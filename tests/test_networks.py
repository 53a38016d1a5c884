"""The networks, their training examples, configuration, training loop and weight bundles."""
from dataclasses import replace
import math

from conftest import tiny_config
import numpy as np
import pytest
import torch

from scene_synth_ros.categories import room_spec
from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.networks.bundle import BundleError, build_networks, load_bundle, save_bundle
from scene_synth_ros.networks.config import PipelineConfig, resolve_device
from scene_synth_ros.networks.cvae import kl_to_prior
from scene_synth_ros.networks.dimensions import box_sdf, dimensions_elbo
from scene_synth_ros.networks.draws import (
    LocationDraws,
    blob_centre,
    category_probabilities,
    decode_angle,
    location_distribution,
    prior_noise,
    sample_pixel,
    snap_angle,
)
from scene_synth_ros.networks.examples import (
    ExampleSource,
    SizeBuckets,
    insertion_order,
    placeable,
    rotate_scene,
)
from scene_synth_ros.networks.orientation import is_snapped
from scene_synth_ros.paths import config_dir
from scene_synth_ros.render import COS, SIN, Frame, TopDownRenderer
from scene_synth_ros.scene import Scene


@pytest.fixture(scope='module')
def rooms():
    return [generate_room('bedroom', 0, i) for i in range(6)] + \
        [generate_room('living', 0, i) for i in range(4)]


# ---- configuration ---------------------------------------------------------------------------
def test_shipped_configs_parse_and_build():
    compact = PipelineConfig.from_yaml(config_dir() / 'compact.yaml')
    paper = PipelineConfig.from_yaml(config_dir() / 'paper.yaml')
    assert (compact.model.resolution, paper.model.resolution) == (64, 256)
    assert paper.model.category_encoder.widths == (64, 128, 256, 512)
    assert paper.model.location_encoder.blocks == (3, 4, 6, 3)
    # The paper's location network reads 256 px and answers on the 64 x 64 grid.
    net = build_networks('bathroom', paper.model)['location'].eval()
    with torch.no_grad():
        out = net(torch.zeros(1, 28, 256, 256))
    assert out.shape == (1, 21, 64, 64)


def test_config_rejects_unknown_and_mistyped_settings(tmp_path):
    bad = tmp_path / 'bad.yaml'
    bad.write_text('model:\n  resolutoin: 64\n')
    with pytest.raises(ValueError, match="config.model: unknown setting 'resolutoin'"):
        PipelineConfig.from_yaml(bad)
    bad.write_text('train:\n  category: {steps: many}\n')
    with pytest.raises(ValueError, match='config.train.category.steps: expected a number'):
        PipelineConfig.from_yaml(bad)
    # Partial mappings keep the defaults of what they do not mention.
    ok = tmp_path / 'ok.yaml'
    ok.write_text('train:\n  location: {batch_size: 16}\n')
    cfg = PipelineConfig.from_yaml(ok)
    assert cfg.train.location.batch_size == 16
    assert cfg.train.location.steps == PipelineConfig().train.location.steps
    assert PipelineConfig.from_dict(cfg.to_dict()) == cfg


def test_device_resolution():
    assert resolve_device('cpu').type == 'cpu'
    assert resolve_device('auto').type in ('cpu', 'cuda')
    with pytest.raises(ValueError):
        resolve_device('tpu')
    if not torch.cuda.is_available():
        with pytest.raises(ValueError, match='no CUDA device'):
            resolve_device('cuda')


# ---- training examples -------------------------------------------------------------------------
def test_insertion_order_rules(rooms):
    rng = np.random.default_rng(0)
    for scene in rooms:
        rank = {n: k for k, n in enumerate(room_spec(scene.room.room_type).importance_order())}
        for by_importance in (True, False):
            order = insertion_order(scene, rng, by_importance)
            assert sorted(o.id for o in order) == sorted(o.id for o in scene.objects)
            tiers = [o.support is not None for o in order]
            assert tiers == sorted(tiers), 'a second-tier object came before a first-tier one'
            seen = set()
            for o in order:
                assert o.support is None or o.support in seen, 'child before its parent'
                seen.add(o.id)
            if by_importance:
                for tier in (False, True):
                    ranks = [rank[o.category] for o, t in zip(order, tiers, strict=True)
                             if t == tier]
                    assert ranks == sorted(ranks)
    # Random order really is random: two draws of a room with many objects differ.
    big = max(rooms, key=len)
    draws = {tuple(o.id for o in insertion_order(big, np.random.default_rng(s), False))
             for s in range(5)}
    assert len(draws) > 1


def test_placeable_needs_the_parent(rooms):
    scene = next(s for s in rooms if s.second_tier)
    child = scene.second_tier[0]
    parent = scene.get(child.support)
    others = [o for o in scene.first_tier if o is not parent]
    assert child not in placeable([child], others)
    assert child in placeable([child], others + [parent])
    assert parent in placeable([parent], [])


def test_category_examples_are_drawn_uniformly_over_the_states_synthesis_visits(rooms):
    # A room of N objects is N + 1 states; STOP is the target of one of them. Drawn per
    # state, STOP is the target in (rooms / states) of the examples; drawn per room first,
    # it would be the mean of 1 / (N + 1), which is larger.
    large = max(rooms, key=len)
    small = Scene(large.room, list(large.first_tier[:1]))
    src = ExampleSource('bedroom', [small, large], 64, 64, augment=False)
    stop = src.num_categories
    rng = np.random.default_rng(0)
    n = 4000
    share = sum(src.category_example(rng)[2] == stop for _ in range(n)) / n
    per_state = 2 / (len(small) + len(large) + 2)
    per_room = (1 / (len(small) + 1) + 1 / (len(large) + 1)) / 2
    noise = math.sqrt(per_state * (1 - per_state) / n)
    assert per_room - per_state > 8 * noise          # the two are told apart
    assert abs(share - per_state) < 4 * noise


def test_location_target_marks_placeable_centroids(rooms):
    src = ExampleSource('bedroom', rooms[:6], 64, 64, augment=False)
    scene = next(s for s in rooms[:6] if s.second_tier)
    child = scene.second_tier[0]
    kept = [o for o in scene.first_tier if o.id != child.support][:1]
    removed = [o for o in scene.objects if o not in kept]
    frame = Frame.for_room(scene.room, 64)
    target, _ = src.location_target(frame, placeable(removed, kept))
    labels = set(np.unique(target)) - {0}
    expect = {1 + src.index[o.category] for o in placeable(removed, kept)}
    assert labels == expect
    i, j = frame.world_to_pixel(child.position[:2])
    parent_pixel = frame.world_to_pixel(scene.get(child.support).position[:2])
    if tuple(parent_pixel) != (i, j):
        assert target[i, j] != 1 + src.index[child.category]


def test_location_target_radius(rooms):
    scene = rooms[0]
    frame = Frame.for_room(scene.room, 64)
    obj = scene.first_tier[0]
    i, j = frame.world_to_pixel(obj.position[:2])
    for r in (0, 1, 2):
        src = ExampleSource('bedroom', rooms[:6], 64, 64, augment=False, target_radius=r)
        target, offset = src.location_target(frame, [obj])
        assert (target > 0).sum() == (2 * r + 1) ** 2
        assert (target[i - r:i + r + 1, j - r:j + r + 1] == 1 + src.index[obj.category]).all()
        # every marked pixel's offset points at the centroid's continuous pixel coordinates
        rows, cols = np.nonzero(target)
        centroid = frame.world_to_pixel(obj.position[:2], continuous=True)
        assert np.allclose(np.stack([rows, cols], -1) + offset[:, rows, cols].T, centroid,
                           atol=1e-5)
        assert not offset[:, target == 0].any()
        assert np.abs(offset).max() <= r + 0.5 + 1e-6


def test_location_draws_are_those_of_rng_choice_and_keep_the_blob_centres():
    # The synthesizer draws a category's retries from one LocationDraws, which keeps the
    # cumulative sum that rng.choice would make again at every call: the same pixels from
    # the same random numbers, so the rooms are those of rng.choice.
    rng = np.random.default_rng(7)
    for trial in range(40):
        p = rng.random((16, 16)) ** rng.uniform(1, 12)
        p[rng.random((16, 16)) < rng.uniform(0, 0.95)] = 0.0
        p[rng.integers(16), rng.integers(16)] = 1e-3
        p /= p.sum()
        draws, ours, theirs = LocationDraws(p), np.random.default_rng(trial), \
            np.random.default_rng(trial)
        for n in (1, 3, 1, 12, 1):
            assert np.array_equal(draws.pixels(ours, n),
                                  theirs.choice(p.size, size=n, p=p.ravel()))
        assert ours.random() == theirs.random()      # both streams used alike
        # Its block sums and draws, kept across calls, are those made afresh at each call.
        starts = rng.integers(0, 16, size=(5, 2)).astype(float)
        assert np.array_equal(blob_centre(p, starts, draws.blocks), blob_centre(p, starts))
        a, b = np.random.default_rng(trial), np.random.default_rng(trial)
        for mode in (True, True, False):
            assert np.array_equal(draws.sample(a, 2, mode=mode),
                                  sample_pixel(p, b, 2, mode=mode))


def test_offsets_put_sampled_locations_on_the_centroid(rooms):
    src = ExampleSource('bedroom', rooms[:6], 64, 64, augment=False, target_radius=1)
    scene = rooms[0]
    frame = Frame.for_room(scene.room, 64)
    obj = scene.first_tier[0]
    target, offset = src.location_target(frame, [obj])
    p = (target > 0).astype(float)
    pts = sample_pixel(p / p.sum(), np.random.default_rng(0), 50, offset)
    centroid = frame.world_to_pixel(obj.position[:2], continuous=True)
    assert np.allclose(pts, centroid, atol=1e-5)
    # without offsets a draw lands anywhere in the 3 x 3 block
    loose = sample_pixel(p / p.sum(), np.random.default_rng(0), 50)
    assert np.abs(loose - centroid).max() > 0.5


def test_draws_move_to_the_centre_of_their_blob():
    p = np.zeros((16, 16))
    p[4:7, 9:12] = 1.0                      # a 3 x 3 blob centred on pixel (5, 10)
    p[12, 2] = 0.5                          # a lone pixel elsewhere
    p /= p.sum()
    starts = np.array([[4, 9], [6, 11], [5, 10], [4, 11], [12, 2]], dtype=float)
    assert np.allclose(blob_centre(p, starts), [[5, 10]] * 4 + [[12, 2]])
    # a blob weighted to one side: its weighted centre, between pixels
    q = np.zeros((16, 16))
    q[5, 9:12] = [0.0, 1.0, 1.0]
    assert np.allclose(blob_centre(q / q.sum(), np.array([[5.0, 10.0]])), [[5, 10.5]])
    pts = sample_pixel(p, np.random.default_rng(1), 200, mode=True)
    assert {tuple(np.round(x, 9)) for x in pts} <= {(5.0, 10.0), (12.0, 2.0)}
    # with offsets, the offset at the blob's centre pixel says where in it the centroid is
    offsets = np.zeros((2, 16, 16))
    offsets[:, 5, 10] = (0.3, -0.2)
    pts = sample_pixel(p, np.random.default_rng(1), 50, offsets, mode=True)
    assert {tuple(np.round(x, 9)) for x in pts} <= {(5.3, 9.8), (12.0, 2.0)}


def test_the_offset_head_and_its_loss():
    from dataclasses import replace

    from scene_synth_ros.networks.location import LocationModel, offset_loss
    cfg = PipelineConfig.from_yaml(config_dir() / 'compact.yaml').model
    plain, with_offsets = (LocationModel(5, 7, replace(cfg, location_offsets=f))
                           for f in (False, True))
    image = torch.zeros(2, 5, cfg.resolution, cfg.resolution)
    n = cfg.location_resolution
    assert plain.predict(image)[1] is None
    logits, offsets = with_offsets.eval().predict(image)
    assert logits.shape == (2, 8, n, n) and offsets.shape == (2, 2, n, n)
    assert with_offsets(image).shape == logits.shape
    target = torch.zeros(2, 2, n, n)
    marked = torch.zeros(2, n, n, dtype=torch.bool)
    marked[0, 3, 4] = True
    target[0, :, 3, 4] = torch.tensor([0.5, -1.0])
    pred = torch.zeros(2, 2, n, n)
    assert float(offset_loss(pred, target, marked)) == pytest.approx(0.75)
    assert float(offset_loss(pred, target, torch.zeros_like(marked))) == 0.0


def test_network_shapes_and_seeded_initialisation():
    cfg = PipelineConfig.from_yaml(config_dir() / 'compact.yaml').model
    a = build_networks('bedroom', cfg, seed=3)
    b = build_networks('bedroom', cfg, seed=3)
    for name in a:
        sa, sb = a[name].state_dict(), b[name].state_dict()
        assert all(torch.equal(sa[k], sb[k]) for k in sa)
    # One module's architecture does not change another's initial weights.
    other = build_networks('bedroom', replace(cfg, location_skips=False), seed=3)
    assert torch.equal(other['orientation'].head.weight, a['orientation'].head.weight)
    x = torch.zeros(2, 46, 64, 64)
    with torch.no_grad():
        for net in a.values():
            net.eval()
        assert a['category'](x, torch.zeros(2, 38)).shape == (2, 39)
        assert a['location'](x).shape == (2, 39, 64, 64)
        assert other['location'].eval()(x).shape == (2, 39, 64, 64)
        cat = torch.tensor([0, 5])
        assert a['orientation'].sample(x, cat).shape == (2, 2)
        assert a['snap'](x, cat).shape == (2,)
        assert a['dimensions'](x, cat, torch.zeros(2, 2))[0].shape == (2, 2)


def test_folded_batch_norms_give_the_networks_outputs():
    from scene_synth_ros.networks.blocks import fold_batch_norms
    cfg = PipelineConfig.from_yaml(config_dir() / 'compact.yaml').model
    nets = build_networks('bedroom', cfg, seed=5)
    gen = torch.Generator().manual_seed(0)
    for net in nets.values():
        # Batch norms as training leaves them, far from the identity they start as.
        for m in net.modules():
            if isinstance(m, torch.nn.BatchNorm2d):
                m.running_mean.copy_(torch.randn(m.num_features, generator=gen))
                m.running_var.copy_(torch.rand(m.num_features, generator=gen) + 0.2)
                m.weight.data.copy_(torch.randn(m.num_features, generator=gen))
                m.bias.data.copy_(torch.randn(m.num_features, generator=gen))
        net.eval()
    x = (torch.rand(3, 46, 64, 64, generator=gen) > 0.8).float()
    cat, counts, z = torch.tensor([0, 4, 9]), torch.rand(3, 38, generator=gen), \
        torch.randn(3, cfg.latent, generator=gen)
    calls = {'category': lambda n: n(x, counts), 'location': lambda n: n(x),
             'orientation': lambda n: n.condition(x, cat), 'snap': lambda n: n(x, cat),
             'dimensions': lambda n: n.decode(n.condition(x, cat), cat, z)}
    with torch.no_grad():
        before = {name: call(nets[name]) for name, call in calls.items()}
        with pytest.raises(ValueError, match='evaluation mode'):
            fold_batch_norms(build_networks('bedroom', cfg, seed=5)['location'])
        for net in nets.values():
            assert fold_batch_norms(net) is net
            assert not any(isinstance(m, torch.nn.BatchNorm2d) for m in net.modules())
        for name, call in calls.items():
            after = call(nets[name])
            scale = before[name].abs().max()
            assert scale > 0.1
            assert (after - before[name]).abs().max() <= 1e-5 * scale, name
    # Folding twice is folding once: nothing is left to fold.
    again = fold_batch_norms(nets['location'])
    with torch.no_grad():
        assert torch.equal(again(x), nets['location'](x))


def test_rotation_augmentation_is_exact(rooms):
    r = TopDownRenderer(64)
    for scene in rooms[:3]:
        back = rotate_scene(rotate_scene(scene, 3), 1)
        assert back.room.polygon.equals_exact(scene.room.polygon, 1e-9)
        for a, b in zip(back.objects, scene.objects, strict=True):
            assert np.allclose(a.position, b.position, atol=1e-9)
            assert math.isclose(math.remainder(a.yaw - b.yaw, 2 * math.pi), 0, abs_tol=1e-9)
        base = r.render(scene, Frame.for_room(scene.room, 64))
        turned = rotate_scene(scene, 1)
        img = r.render(turned, Frame.for_room(turned.room, 64))
        # A quarter turn counter-clockwise of the world is a quarter turn of the image
        # (rows grow with +y, columns with +x)...
        rb = np.rot90(base, 1, axes=(2, 1))
        fixed = [c for c in range(img.shape[0]) if c not in (SIN, COS)]
        assert np.abs(img[fixed] - rb[fixed]).max() < 1e-5
        # ...and the yaw channels turn with it: sin' = cos, cos' = -sin.
        assert np.allclose(img[SIN], rb[COS], atol=1e-5)
        assert np.allclose(img[COS], -rb[SIN], atol=1e-5)


def test_size_buckets_group_rooms_of_like_size_and_keep_each_rooms_chance():
    rng = np.random.default_rng(0)
    sides = rng.choice([64, 64, 64, 72, 80, 96, 128, 160], size=200)
    states = rng.integers(1, 12, size=200).astype(float)
    buckets = SizeBuckets(list(sides), states, least=30)
    ranges = [(sides[g.index].min(), sides[g.index].max()) for g in buckets.groups]
    assert len(ranges) > 2
    assert sorted(k for g in buckets.groups for k in g.index) == list(range(200))
    assert all(len(g.index) >= 30 for g in buckets.groups)
    assert all(hi < lo for (_, hi), (lo, _) in zip(ranges[:-1], ranges[1:], strict=True))
    for per_state in (False, True):
        seen = np.zeros(200)
        for _ in range(20_000):
            pool = buckets.pool(rng, per_state)
            seen[pool.draw(rng, per_state)] += 1
        want = states / states.sum() if per_state else np.full(200, 1 / 200)
        grouped = [(seen[g.index].sum() / seen.sum(), want[g.index].sum())
                   for g in buckets.groups]
        assert all(abs(a - b) < 0.02 for a, b in grouped), grouped
        assert abs(seen[states > 8].sum() / seen.sum() - want[states > 8].sum()) < 0.02
    one = SizeBuckets([64] * 5 + [96] * 5, np.ones(10), least=30)
    assert len(one.groups) == 1
    with pytest.raises(ValueError, match='train.size_buckets'):
        SizeBuckets([64] * 5, np.ones(5), least=-3)
    # a last group too small joins the one before it; no room is left out
    tail = SizeBuckets([64] * 50 + [72] * 50 + [80] * 10, np.ones(110), least=40)
    assert [len(g.index) for g in tail.groups] == [50, 60]
    assert sorted(k for g in tail.groups for k in g.index) == list(range(110))


def test_a_batch_of_size_buckets_holds_rooms_of_one_group(rooms):
    wide = rooms[0]
    big = Scene(replace(wide.room, floor=[(0, 0), (9.0, 0), (9.0, 4.0), (0, 4.0)],
                        doors=(), windows=()), list(wide.first_tier[:2]))
    scenes = rooms[:6] + [big] * 6
    src = ExampleSource('bedroom', scenes, 64, 64, augment=False, size_buckets=6)
    plain = ExampleSource('bedroom', scenes, 64, 64, augment=False)
    for module in ('category', 'location'):      # still a pure function of its seed
        a, b = src.batch(module, [7, 1], 8), src.batch(module, [7, 1], 8)
        assert all(torch.equal(a[k], b[k]) for k in a)
    assert len(src._buckets.groups) == 2
    sides = {src.batch('location', [s], 8)['image'].shape[-1] for s in range(30)}
    assert sides == {64, src._frame(big.room).resolution}
    mixed = {plain.batch('location', [s], 8)['image'].shape[-1] for s in range(30)}
    assert mixed == {src._frame(big.room).resolution}
    # held-out batches are drawn from every room as before
    a = src.batch('category', [3], 8, by_size=False)
    b = plain.batch('category', [3], 8)
    assert all(torch.equal(a[k], b[k]) for k in a)


def test_example_batches_are_pure_functions_of_their_seed(rooms):
    src = ExampleSource('bedroom', rooms[:6], 64, 64)
    for module in ('category', 'location', 'orientation', 'dimensions'):
        a, b = src.batch(module, [1, 2, 3], 4), src.batch(module, [1, 2, 3], 4)
        c = src.batch(module, [1, 2, 4], 4)
        assert all(torch.equal(a[k], b[k]) for k in a)
        assert not all(torch.equal(a[k], c[k]) for k in a)
    cat = src.batch('category', [0], 64)
    assert cat['target'].max() <= src.num_categories
    assert (cat['target'] == src.num_categories).any(), 'no STOP examples in 64'


# ---- location distribution, snapping, SDF ------------------------------------------------------
def test_location_distribution_masks_and_tempers():
    torch.manual_seed(0)
    logits = torch.randn(5, 8, 8).numpy()
    mask = np.zeros((8, 8), dtype=bool)
    mask[2:6, 1:7] = True
    p1 = location_distribution(logits, 2, mask, 1.0)
    assert p1.sum() == pytest.approx(1.0) and (p1[~mask] == 0).all() and (p1[mask] > 0).all()
    soft = torch.softmax(torch.from_numpy(logits), 0)[3].numpy().astype(float)
    expect = np.where(mask, soft, 0)
    assert np.allclose(p1, expect / expect.sum())
    p08 = location_distribution(logits, 2, mask, 0.8)
    expect08 = np.where(mask, soft ** (1 / 0.8), 0)
    assert np.allclose(p08, expect08 / expect08.sum())
    # Lower temperature sharpens: the most likely pixel gains mass.
    assert p08.max() > p1.max()
    assert location_distribution(logits, 2, np.zeros((8, 8), bool), 0.8) is None
    with pytest.raises(ValueError):
        location_distribution(logits, 2, mask, 0.0)
    pts = sample_pixel(p08, np.random.default_rng(0), 500)
    rows, cols = np.floor(pts + 0.5).astype(int).T
    assert mask[rows, cols].all()


def test_snap_and_angle_decoding():
    assert snap_angle(math.radians(88)) == pytest.approx(math.pi / 2)
    assert snap_angle(math.radians(-179)) == pytest.approx(-math.pi)
    assert snap_angle(math.radians(44)) == 0.0
    theta = torch.tensor([0.0, math.pi / 2 + 0.01, math.radians(45), -math.pi + 0.001,
                          math.radians(98), math.radians(-12)])
    assert is_snapped(theta).tolist() == [True, True, False, True, True, False]
    out = np.array([[10.0, 10.0], [-10.0, -10.0], [0.0, 10.0]])
    ang = decode_angle(out, np.random.default_rng(0))
    assert abs(ang[0]) < 0.1 and abs(abs(ang[1]) - math.pi) < 0.1
    assert ang[2] == pytest.approx(math.pi / 2, abs=1e-3)
    # The sign of sin is drawn with the decoder's probability: about half each way at 0.
    signs = np.sign(decode_angle(np.tile([[0.3, 0.0]], (4000, 1)), np.random.default_rng(1)))
    assert abs((signs > 0).mean() - 0.5) < 0.03


def test_the_category_draw_and_the_prior_noise_are_those_torch_would_give():
    logits = np.array([2.0, -1.0, 0.5, 3.0])
    allowed = np.array([True, False, True, True])
    p = category_probabilities(logits, allowed)
    want = torch.softmax(torch.tensor(logits).masked_fill(~torch.tensor(allowed),
                                                          float('-inf')), -1).numpy()
    assert p.dtype == np.float64 and np.allclose(p, want) and p[1] == 0.0
    assert np.allclose(category_probabilities(logits), torch.softmax(torch.tensor(logits), -1))
    z = prior_noise(np.random.default_rng(3), 20000, 4)
    assert z.shape == (20000, 4) and z.dtype == np.float32
    assert np.allclose(z.mean(0), 0, atol=0.03) and np.allclose(z.std(0), 1, atol=0.03)
    assert np.array_equal(z, prior_noise(np.random.default_rng(3), 20000, 4))


def test_box_sdf_sign_and_gradient():
    dims = torch.log(torch.tensor([[2.0, 1.0]])).requires_grad_()
    sdf = box_sdf(dims, 64, 6.4)   # 0.1 m pixels
    assert sdf.shape == (1, 1, 64, 64)
    assert sdf[0, 0, 32, 32] < 0                 # centre: inside
    assert sdf[0, 0, 32, 45] > 0                 # 1.25 m along the depth axis: outside
    assert sdf[0, 0, 32, 41] < 0                 # 0.85 m: inside the 2 m depth
    assert sdf[0, 0, 41, 32] > 0                 # 0.85 m across: outside the 1 m width
    sdf.sum().backward()
    assert dims.grad is not None and dims.grad.abs().sum() > 0


def test_dimensions_likelihood_with_a_learned_spread():
    # With a spread learned per category, the dimensions' negative ELBO is the Gaussian
    # negative log-likelihood (less its constant) plus the KL; without, sigma is 0.1.
    g = torch.Generator().manual_seed(0)
    out, target = torch.randn(5, 2, generator=g), torch.randn(5, 2, generator=g)
    mu, logvar = torch.randn(5, 8, generator=g), torch.randn(5, 8, generator=g)
    log_sigma = torch.randn(5, 2, generator=g) * 0.5 - 2
    _, nelbo = dimensions_elbo(out, target, mu, logvar, 1.0, log_sigma)
    nll = -torch.distributions.Normal(out, log_sigma.exp()).log_prob(target).sum(1)
    assert torch.allclose(nelbo, nll - math.log(2 * math.pi) + kl_to_prior(mu, logvar),
                          atol=1e-4)
    _, fixed = dimensions_elbo(out, target, mu, logvar, 1.0)
    _, at_fixed = dimensions_elbo(out, target, mu, logvar, 1.0,
                                  torch.full_like(log_sigma, math.log(0.1)))
    assert torch.allclose(fixed, at_fixed - 2 * math.log(0.1), atol=1e-3)
    # The loss weighs the KL, not the likelihood.
    loss, _ = dimensions_elbo(out, target, mu, logvar, 0.5, log_sigma)
    assert torch.isclose(loss, (nelbo - 0.5 * kl_to_prior(mu, logvar)).mean(), atol=1e-4)


def test_learned_spread_starts_at_the_spread_of_the_first_targets():
    from scene_synth_ros.networks.train import SPREAD_BATCHES, _initial_spread
    model = replace(tiny_config().model, dimensions_noise=True)
    net = build_networks('bathroom', model)['dimensions']
    assert net.log_sigma.requires_grad
    assert build_networks('bathroom', tiny_config().model)['dimensions'].log_sigma is None
    rng = np.random.default_rng(0)
    data = [{'category': torch.tensor([0] * 6 + [1] * 2),
             'target': torch.tensor(rng.normal([0.0, 0.5], [0.05, 0.2], (8, 2)),
                                    dtype=torch.float32)}
            for _ in range(SPREAD_BATCHES + 4)]     # the batches after the first are unread
    _initial_spread(net, data)
    y = np.concatenate([d['target'].numpy() for d in data[:SPREAD_BATCHES]])
    cats = np.concatenate([d['category'].numpy() for d in data[:SPREAD_BATCHES]])
    for c in (0, 1):
        np.testing.assert_allclose(net.log_sigma[c].detach().numpy(),
                                   np.log(y[cats == c].std(axis=0, ddof=1)), rtol=1e-5)
    # Categories the batches do not show keep the fixed likelihood's sigma.
    assert torch.allclose(net.log_sigma[2:], torch.tensor(math.log(0.1)))


# ---- training and bundles ----------------------------------------------------------------------
@pytest.mark.slow
def test_training_resumes_exactly(tmp_path):
    from scene_synth_ros.networks.train import ExampleSource as _ES
    from scene_synth_ros.networks.train import load_corpus, train_module
    cfg = tiny_config(steps=4)
    corpus = load_corpus('bathroom', cfg, workers=1)
    src = _ES('bathroom', corpus.train, 64, 64)
    val = _ES('bathroom', corpus.val, 64, 64)
    results = {}
    for label, stops in (('straight', [None]), ('resumed', [2, None])):
        run = tmp_path / label
        run.mkdir()
        for module in ('category', 'dimensions'):
            torch.manual_seed(0)
            net = build_networks('bathroom', cfg.model)[module]
            for until in stops:
                if until is not None:
                    assert train_module(module, net, src, val, cfg, 'cpu', run, lambda e: None,
                                        False, until) is None
                    torch.manual_seed(123)   # a fresh process: other initial weights
                    net = build_networks('bathroom', cfg.model)[module]
                else:
                    train_module(module, net, src, val, cfg, 'cpu', run, lambda e: None, False)
            results[(label, module)] = {k: v.clone() for k, v in net.state_dict().items()}
    for module in ('category', 'dimensions'):
        a, b = results[('straight', module)], results[('resumed', module)]
        assert all(torch.allclose(a[k].float(), b[k].float(), atol=1e-6) for k in a), module


@pytest.mark.slow
def test_loader_workers_make_the_same_batches_and_weights(tmp_path):
    """``loader_workers``: batches made ahead by DataLoader processes are those the training
    process makes itself, in step order, so a resumed run with workers ends with the same
    weights as a straight run without."""
    from dataclasses import replace

    from scene_synth_ros.networks.train import ExampleSource as _ES
    from scene_synth_ros.networks.train import batches, load_corpus, train_module
    cfg = tiny_config(steps=4)
    corpus = load_corpus('bathroom', cfg, workers=1)
    src = _ES('bathroom', corpus.train, 64, 64, target_radius=1)
    val = _ES('bathroom', corpus.val, 64, 64)
    here = list(batches(src, 'location', 3, 5, 1, 4))
    ahead = list(batches(src, 'location', 3, 5, 1, 4, workers=2))
    assert len(here) == len(ahead) == 3
    for a, b in zip(here, ahead, strict=True):
        assert a.keys() == b.keys() and all(torch.equal(a[k], b[k]) for k in a)
    assert not torch.equal(here[0]['image'], here[1]['image'])
    weights = {}
    for label, workers, stops in (('here', 0, [None]), ('ahead', 2, [2, None])):
        c = replace(cfg, train=replace(cfg.train, loader_workers=workers))
        run = tmp_path / label
        run.mkdir()
        for k, until in enumerate(stops):
            torch.manual_seed(123 * k)          # a resumed process: other initial weights
            net = build_networks('bathroom', c.model)['location']
            train_module('location', net, src, val, c, 'cpu', run, lambda e: None, False,
                         until)
        weights[label] = net.state_dict()
    assert all(torch.allclose(weights['here'][k].float(), weights['ahead'][k].float(),
                              atol=1e-6) for k in weights['here'])


def test_one_module_retrained_keeps_the_others_of_a_bundle(tiny_weights, tmp_path):
    from scene_synth_ros.networks.train import train
    cfg = tiny_config(steps=2)
    cfg.train.seed = 7                 # another category network than the bundle's
    train(['bathroom'], cfg, tmp_path / 'run', tmp_path / 'out', progress=False,
          echo=lambda s: None, modules=('category',), others_from=tiny_weights)
    base = load_bundle(tiny_weights / 'bathroom.pt')
    new = load_bundle(tmp_path / 'out' / 'bathroom.pt')
    for name, net in new.networks.items():
        same = all(torch.equal(v, base.networks[name].state_dict()[k])
                   for k, v in net.state_dict().items())
        assert same == (name != 'category'), name
    other = tiny_config(steps=2)
    other.model.hidden = 16
    with pytest.raises(ValueError, match='another model configuration.*hidden differs'):
        train(['bathroom'], other, tmp_path / 'run2', tmp_path / 'out2', progress=False,
              echo=lambda s: None, modules=('category',), others_from=tiny_weights)
    # A setting only the retrained module reads may differ (config.OWN_SETTINGS); one that
    # a kept module reads may not.
    own = tiny_config(steps=2)
    own.model.location_offsets = False
    train(['bathroom'], own, tmp_path / 'run3', tmp_path / 'out3', progress=False,
          echo=lambda s: None, modules=('location',), others_from=tiny_weights)
    mixed = load_bundle(tmp_path / 'out3' / 'bathroom.pt')
    assert mixed.networks['location'].offset is None
    assert mixed.config.model.location_offsets is False
    with pytest.raises(ValueError, match='location_offsets differs'):
        train(['bathroom'], own, tmp_path / 'run4', tmp_path / 'out4', progress=False,
              echo=lambda s: None, modules=('category',), others_from=tiny_weights)


def test_bundle_round_trip_and_errors(tiny_weights, tmp_path):
    b = load_bundle(tiny_weights / 'bathroom.pt')
    assert b.room_type == 'bathroom' and set(b.networks) == {
        'category', 'location', 'orientation', 'snap', 'dimensions'}
    assert not any(n.training for n in b.networks.values())
    assert b.cooccurrence.shape == (len(b.models), len(b.models))
    table = b.metrics['components']
    assert set(table['category']) >= {'trained_top1', 'random_top1', 'trained_top5'}
    # A pickle-free load: the file opens with weights_only=True.
    torch.load(tiny_weights / 'bathroom.pt', weights_only=True)
    save_bundle(b, tmp_path / 'copy.pt')
    again = load_bundle(tmp_path / 'copy.pt')
    for name, net in b.networks.items():
        sa, sb = net.state_dict(), again.networks[name].state_dict()
        assert all(torch.equal(sa[k], sb[k]) for k in sa)
    with pytest.raises(BundleError, match='no such weights file'):
        load_bundle(tmp_path / 'missing.pt')
    broken = tmp_path / 'broken.pt'
    broken.write_bytes((tiny_weights / 'bathroom.pt').read_bytes()[:5000])
    with pytest.raises(BundleError, match='broken.pt: not a readable weights file'):
        load_bundle(broken)
    other = tmp_path / 'other.pt'
    torch.save({'format': 1, 'room_type': 'bathroom', 'config': '{}'}, other)
    with pytest.raises(BundleError, match='other.pt: weights do not match'):
        load_bundle(other)


def test_rooms_larger_than_their_square_train_and_answer_at_the_same_pixel_size(rooms):
    # A 7.5 m bedroom (larger than the 6 m square) is seen at 96 px, like synthesis sees it;
    # in a batch with a room of the square it is padded to, the smaller one in the middle.
    small = rooms[0]
    wide = Scene(replace(small.room, floor=((0, 0), (7.5, 0), (7.5, 3.8), (0, 3.8)),
                         doors=(), windows=()), [])
    big = Scene(wide.room, [replace(o, position=(o.position[0] + 0.5, o.position[1],
                                                 o.position[2]))
                            for o in small.objects
                            if 0.2 < o.position[0] + 0.5 < 7.3 and o.position[1] < 3.6])
    assert big.objects
    cfg = PipelineConfig.from_yaml(config_dir() / 'compact.yaml')
    nets = build_networks('bedroom', cfg.model, seed=0)
    src = ExampleSource('bedroom', [small, big], 64, 64, augment=False,
                        multiple=nets['location'].multiple)
    frame = Frame.for_room(big.room, 64, multiple=src.multiple)
    assert frame.resolution == 96
    target, _ = src.location_target(frame, big.objects)
    assert target.shape == (96, 96)
    for o in big.objects:
        i, j = frame.world_to_pixel(o.position[:2])
        assert target[i, j] == 1 + src.index[o.category]
    sizes = set()
    for seed in range(6):
        batch = src.batch('location', seed, 4)
        assert batch['image'].shape[-2:] == batch['target'].shape[-2:]
        sizes.add(batch['image'].shape[-1])
        # every image holds a whole room (the floor channel), never cut by the padding
        assert all(img[0].sum() > 100 for img in batch['image'])
    assert 96 in sizes
    image = torch.from_numpy(src.location_example(np.random.default_rng(1))[0])[None]
    nets['location'].eval()
    nets['category'].eval()
    with torch.no_grad():
        for x in (batch['image'], image):
            assert nets['location'](x).shape[-2:] == x.shape[-2:]
            assert nets['category'](x, torch.zeros(len(x), src.num_categories)).shape == \
                (len(x), src.num_categories + 1)
