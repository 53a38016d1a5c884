"""The evaluation suite (scene-synth evaluate): each measurement on cases with a known
answer, and the quick report of one room type end to end."""
from dataclasses import replace
from itertools import permutations
import json
import math

import numpy as np
import pytest
import torch

from scene_synth_ros import rules as design_rules
from scene_synth_ros.corpus.generate import generate_corpus
from scene_synth_ros.errors import UnknownRoomType
from scene_synth_ros.evaluation import (
    classifier,
    components,
    distribution,
    plausibility,
)
from scene_synth_ros.evaluation import similarity as sim
from scene_synth_ros.evaluation.perturb import perturb_all, perturb_scene
from scene_synth_ros.evaluation.run import (
    EvalConfig,
    EvaluationError,
    finite_numbers,
    prepare_out_dir,
    run_evaluation,
)
from scene_synth_ros.networks.bundle import bundle_path, load_bundle
from scene_synth_ros.paths import weights_dir
from scene_synth_ros.scene import Room, Scene


@pytest.fixture(scope='module')
def bedrooms():
    return list(generate_corpus('bedroom', 40, seed=0, workers=1))


# ---- category distribution ------------------------------------------------------------------
def test_kl_is_zero_for_identical_rooms_and_larger_for_uniform(bedrooms):
    assert distribution.category_kl(bedrooms, bedrooms) == pytest.approx(0.0, abs=1e-4)
    row = distribution.compare('bedroom', bedrooms[:20], bedrooms, bedrooms[20:])
    assert row['kl_model'] < row['kl_uniform'] and row['kl_heldout'] < row['kl_uniform']
    freq = row['frequencies']['corpus']
    assert sum(freq.values()) == pytest.approx(sum(len(s) for s in bedrooms) / len(bedrooms))
    empty = [Scene(s.room, []) for s in bedrooms[:3]]
    assert math.isinf(distribution.category_kl(empty, bedrooms))


# ---- similarity -------------------------------------------------------------------------------
def _mirrored(scene: Scene) -> Scene:
    x0, _, x1, _ = scene.room.bounds
    objs = [replace(o, position=(x0 + x1 - o.position[0], *o.position[1:]),
                    yaw=math.pi - o.yaw) for o in scene.objects]
    return Scene(scene.room, objs)


def _scaled(scene: Scene, f: float) -> Scene:
    room = scene.room
    s = lambda p: (p[0] * f, p[1] * f)  # noqa: E731
    big = Room(room.room_type, [s(p) for p in room.floor], room.wall_height,
               [replace(d, position=s(d.position)) for d in room.doors],
               [replace(w, position=s(w.position)) for w in room.windows])
    return Scene(big, [replace(o, position=(*s(o.position), o.position[2]))
                       for o in scene.objects])


def test_similarity_is_one_to_itself_and_lower_to_other_rooms(bedrooms):
    a, b = bedrooms[0], bedrooms[1]
    assert sim.scene_similarity(a, a) == pytest.approx(1.0)
    assert sim.scene_similarity(a, Scene(a.room, [])) == 0.0
    assert sim.scene_similarity(Scene(a.room, []), Scene(b.room, [])) == 1.0
    assert sim.scene_similarity(a, Scene(a.room, a.objects[:len(a) // 2])) < 1.0
    assert sim.scene_similarity(a, b) < 1.0
    # Invariant to mirror images and to the size of the shell.
    assert sim.scene_similarity(a, _mirrored(a)) == pytest.approx(1.0)
    assert sim.scene_similarity(a, _scaled(a, 1.3)) == pytest.approx(1.0)
    # Moving every object lowers it, the more so the further.
    near = sim.scene_similarity(a, perturb_all([a], 0.05, 1)[0])
    far = sim.scene_similarity(a, perturb_all([a], 0.5, 1)[0])
    assert 1.0 > near > far


def test_matching_is_optimal_and_max_similarity_finds_the_room_itself(bedrooms, monkeypatch):
    rng = np.random.default_rng(3)
    for a in range(1, 5):
        for m in range(1, 5):
            w = rng.random((4, a, m))
            brute = [max(sum(x[i, p[i]] for i in range(a)) for p in permutations(range(m), a))
                     if a <= m else
                     max(sum(x[p[j], j] for j in range(m)) for p in permutations(range(a), m))
                     for x in w]
            assert np.allclose(sim.best_matching(w), brute)
            monkeypatch.setattr(sim, 'MAX_ENUMERATION', 1)     # force the greedy fallback
            greedy = sim.best_matching(w)
            monkeypatch.undo()
            assert np.all(greedy <= np.array(brute) + 1e-12)
            assert np.all(greedy >= 0.5 * np.array(brute) - 1e-12)
    refs = sim.References.from_scenes(bedrooms)
    best, index = sim.max_similarity(bedrooms[5:8], refs, progress=False)
    assert np.allclose(best, 1.0) and list(index) == [5, 6, 7]


# ---- perturbation -----------------------------------------------------------------------------
def test_perturbation_moves_objects_by_the_expected_scale(bedrooms):
    moved = perturb_all(bedrooms, 0.10, 0)
    along, across = [], []
    for s, p in zip(bedrooms, moved, strict=True):
        for o, q in zip(s.objects, p.objects, strict=True):
            d = np.subtract(q.position[:2], o.position[:2])
            along.append(d @ o.front / o.depth)
            across.append(d @ np.array([-o.front[1], o.front[0]]) / o.width)
            assert q.position[2] == o.position[2] and q.yaw == o.yaw and q.size == o.size
    assert len(along) > 200
    for x in (np.array(along), np.array(across)):
        assert abs(x.mean()) < 0.02 and 0.085 < x.std() < 0.115
    same = perturb_scene(bedrooms[0], 0.0, np.random.default_rng(0))
    assert [o.position for o in same.objects] == [o.position for o in bedrooms[0].objects]


# ---- plausibility -----------------------------------------------------------------------------
def test_plausibility_metrics_see_collisions_and_objects_off_the_floor(bedrooms):
    good = plausibility.room_metrics(bedrooms[0])
    assert good['colliding_pairs'] == 0 and good['valid'] == 1.0
    s = bedrooms[0]
    first = s.first_tier[:2]
    stacked = Scene(s.room, [first[0], replace(first[1], position=first[0].position)])
    assert plausibility.room_metrics(stacked)['colliding_pairs'] == 1.0
    x0, y0, _, _ = s.room.bounds
    outside = Scene(s.room, [replace(first[0], position=(x0 - 2.0, y0 - 2.0, 0.0))])
    m = plausibility.room_metrics(outside)
    assert m['off_floor'] == 1.0 and m['valid'] == 0.0 and math.isnan(m['colliding_pairs'])
    summary = plausibility.summarize([good, m])
    assert summary['rooms'] == 2 and summary['off_floor'] == 0.5


# ---- classifier -------------------------------------------------------------------------------
@pytest.mark.slow
def test_classifier_learns_perfectly_separable_inputs():
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    try:
        gen = torch.Generator().manual_seed(0)
        x = torch.rand(192, 6, 16, 16, generator=gen)
        y = np.arange(192) % 2
        x[:, 0] = torch.from_numpy(y).float()[:, None, None]   # channel 0 gives it away
        cfg = classifier.ClassifierConfig(widths=(8, 16, 32, 32), epochs=6, batch_size=8,
                                          lr=3e-3)
        net, _ = classifier.train_classifier(classifier.TensorImages(x[:128], y[:128]), cfg, 0)
        acc = classifier.accuracy(net, classifier.TensorImages(x[128:], y[128:]))
    finally:
        torch.set_num_threads(threads)
    assert acc > 0.9
    assert sum(p.numel() for p in net.parameters()) > 0
    assert [len(stage) for stage in net.encoder.stages] == [3, 4, 6, 3]   # ResNet-34 layout


# ---- component metrics and configuration ------------------------------------------------------
def test_component_rows_of_the_shipped_weights_improve_on_random():
    comp = load_bundle(bundle_path(weights_dir(), 'bathroom')).metrics['components']
    rows = {r['metric']: r for r in components.component_rows('bathroom', comp)}
    assert len(rows) == 6
    assert rows['category top-1 accuracy']['improvement'] > 0.3
    assert rows['location cross-entropy']['improvement'] < -50       # percent
    assert rows['snap accuracy']['paper_improvement'] == pytest.approx(0.4419)


def test_eval_config_defaults_are_the_paper_sizes_and_bad_sizes_are_refused(tmp_path):
    full = EvalConfig()
    assert (full.classifier_train, full.classifier_test, full.synth_rooms,
            full.corpus_rooms, full.similarity_queries) == (1600, 320, 1000, 5000, 1000)
    full.validate()
    EvalConfig.quick().validate()
    with pytest.raises(ValueError, match='classifier needs|at least the'):
        EvalConfig(synth_rooms=10).validate()
    with pytest.raises(ValueError, match='even'):
        EvalConfig(classifier_test=33).validate()
    blocker = tmp_path / 'file'
    blocker.write_text('')
    with pytest.raises(EvaluationError, match='cannot write'):
        prepare_out_dir(blocker / 'report')
    with pytest.raises(UnknownRoomType, match='unknown room type'):
        run_evaluation(['garage'], EvalConfig.quick(), tmp_path, progress=False)


# ---- the whole run ----------------------------------------------------------------------------
@pytest.mark.slow
def test_quick_report_of_one_room_type_is_written_with_finite_numbers(cli, tmp_path):
    out = tmp_path / 'report'
    results = run_evaluation(['bathroom'], EvalConfig.quick(seed=2), out, workers=1,
                             progress=False, echo=lambda s: None)
    index = (out / 'index.md').read_text()
    for heading in ('## Summary', 'Category distribution', 'Real vs synthetic classifier',
                    'Speed', 'Physical plausibility', 'Generalisation', 'Component metrics',
                    'Design rules', 'Gallery'):
        assert heading in index
    for name in ('categories', 'similarity', 'gallery'):
        png = out / f'{name}_bathroom.png'
        assert png.read_bytes()[:8] == b'\x89PNG\r\n\x1a\n' and f'({png.name})' in index
    # corpus bathrooms keep every design rule, so there is no worst offender to draw
    assert not (out / 'rules_corpus_bathroom.png').exists()
    assert 'bathroom corpus: no room breaks any rule.' in index
    saved = json.loads((out / 'results.json').read_text())
    # synthesized ones get a picture exactly when one of them breaks a rule somewhere
    broken = any(d['synthesized'][0] < d['synthesized'][1]
                 for d in saved['room_types']['bathroom']['design_rules'].values())
    png = out / 'rules_synthesized_bathroom.png'
    assert png.exists() == broken == ('(rules_synthesized_bathroom.png)' in index)
    assert broken != ('bathroom synthesized: no room breaks any rule.' in index)
    assert finite_numbers(saved) == [] and finite_numbers(results) == []
    r = saved['room_types']['bathroom']
    assert set(r['classifier']) == {'synthesized', 'perturbed_0', 'perturbed_1',
                                    'perturbed_5', 'perturbed_10'}
    assert r['speed']['rooms'] == 24 and r['speed']['median'] > 0
    assert len(r['similarity']['synthesized']['values']) == 16
    assert r['similarity']['references'] == 32
    assert 0 <= r['classifier']['synthesized']['accuracy'] <= 1
    assert '**bathroom**: category KL' in index               # the plain-words reading
    rules = r['design_rules']
    assert set(rules) == {rule.name for rule in design_rules.rules()}
    assert rules['fixture_clearance']['corpus'][1] > 0 or rules['bath_in_corner']['corpus'][1] > 0
    for d in rules.values():
        for side in ('corpus', 'synthesized'):
            assert 0 <= d[side][0] <= d[side][1]

    # The report again from results.json alone, plus a copy elsewhere linking to out/.
    (out / 'index.md').unlink()
    copy = tmp_path / 'docs' / 'evaluation.md'
    copy.parent.mkdir()
    proc = cli('evaluate', '--report-only', '--out', out, '--markdown', copy, ok=False)
    assert proc.returncode == 0, proc.stderr
    assert (out / 'index.md').read_text() == index
    assert '(../report/gallery_bathroom.png)' in copy.read_text()


def test_cli_bad_input_is_one_sentence(cli, tmp_path):
    blocker = tmp_path / 'file'
    blocker.write_text('')
    for args, words in ((('--room-type', 'garage'), 'unknown room type'),
                        (('--out', blocker / 'report'), 'cannot write the report'),
                        (('--workers', '0'), 'at least 1')):
        proc = cli('evaluate', '--quick', *args, ok=False)
        assert proc.returncode == 2, proc.stderr
        assert words in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
