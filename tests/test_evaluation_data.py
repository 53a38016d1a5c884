"""``scene-synth evaluate --data`` (evaluation/dataset.py): synthesized rooms against the
rooms of an imported data set that training held out.

A tiny data set is cut from the real ProcTHOR file (ten bedrooms and three kitchens), tiny
bedroom weights are trained on it, and one evaluation of two synthesized rooms per held-out
shell is shared by the tests. The data set's bedroom is its vocabulary's, passed where it is
needed; the paper's bedroom stays the paper's in the same process.
"""
import json
import math
from pathlib import Path

from conftest import tiny_config
import pytest
import torch

from scene_synth_ros import categories
from scene_synth_ros import rules as design_rules
from scene_synth_ros.datasets import description, import_dataset
from scene_synth_ros.datasets.training import split
from scene_synth_ros.errors import UnknownRoomType
from scene_synth_ros.evaluation.dataset import DataEvalConfig, run_data_evaluation
from scene_synth_ros.networks.bundle import bundle_specs
from scene_synth_ros.rules import walls
from scene_synth_ros.synth import SynthConfig

REAL = Path(__file__).resolve().parent.parent.parent / 'shared' / 'data' / 'real' / 'procthor'
pytestmark = pytest.mark.skipif(not REAL.is_dir(), reason=f'no real data in {REAL}')

ROOMS = {'bedroom': 10, 'kitchen': 3}
CONFIG = DataEvalConfig(rooms_per_shell=2, seed=3, synth=SynthConfig(max_objects=4))


@pytest.fixture(scope='module')
def data(tmp_path_factory) -> Path:
    """The first rooms of each type of ``ROOMS`` and their own ``dataset.yaml``."""
    scenes = import_dataset('procthor', [REAL], keep_scenes=True).scenes
    kept = {}
    for rt, n in ROOMS.items():
        names = sorted(k for k, s in scenes.items() if s['room']['room_type'] == rt)[:n]
        kept.update((k, scenes[k]) for k in names)
    folder = tmp_path_factory.mktemp('data')
    for name, scene in kept.items():
        (folder / f'{name}.json').write_text(json.dumps(scene))
    description.write(description.describe(kept.values(), 'procthor'),
                      folder / description.FILE_NAME)
    return folder


@pytest.fixture(scope='module')
def weights(data, tmp_path_factory) -> Path:
    """Tiny bedroom weights trained on ``data`` (no kitchen bundle)."""
    from scene_synth_ros.networks.train import train
    root = tmp_path_factory.mktemp('weights')
    threads = torch.get_num_threads()
    try:
        train(['bedroom'], tiny_config(), root / 'run', root / 'weights', progress=False,
              echo=lambda s: None, data_dir=data)
    finally:
        torch.set_num_threads(threads)
    return root / 'weights'


@pytest.fixture(scope='module')
def evaluated(data, weights, tmp_path_factory):
    out = tmp_path_factory.mktemp('report')
    results = run_data_evaluation(data, weights, 'all', CONFIG, out, workers=1,
                                  progress=False, echo=lambda s: None,
                                  markdown_copy=out / 'copy' / 'evaluation.md')
    return results, out


def _bedroom_names(data: Path) -> list[str]:
    return sorted(p.name for p in data.glob('*.json')
                  if json.loads(p.read_text())['room']['room_type'] == 'bedroom')


def test_the_report_has_the_room_types_with_a_bundle(evaluated):
    results, _ = evaluated
    assert results['mode'] == 'dataset'
    assert list(results['room_types']) == ['bedroom']
    assert results['without_bundle'] == ['kitchen']


def test_the_category_kls_are_finite_and_not_negative(evaluated):
    d = evaluated[0]['room_types']['bedroom']['distribution']
    for key in ('kl_synthesized', 'kl_training', 'kl_uniform'):
        assert math.isfinite(d[key]) and d[key] >= 0, key
    # Every frequency table covers the same categories, the bundle's set first.
    f = d['frequencies']
    assert list(f['synthesized']) == list(f['heldout']) == list(f['training'])


def test_the_heldout_rooms_are_those_training_held_out(evaluated, data):
    r = evaluated[0]['room_types']['bedroom']
    t = tiny_config().train
    names = _bedroom_names(data)
    train_idx, val_idx = split(names, t.corpus_seed)
    assert r['heldout_names'] == [names[k] for k in val_idx[:t.val_rooms]]
    assert r['split'] == {'corpus_seed': t.corpus_seed, 'rooms': ROOMS['bedroom'],
                          'training': len(train_idx[:t.train_rooms]),
                          'heldout': len(r['heldout_names']),
                          'objects_removed': r['split']['objects_removed']}
    assert not set(r['heldout_names']) & {names[k] for k in train_idx}


def test_every_heldout_shell_is_furnished_k_times(evaluated):
    r = evaluated[0]['room_types']['bedroom']
    k, shells = CONFIG.rooms_per_shell, r['heldout_names']
    assert r['rooms'] == {'shells': len(shells), 'synthesized': len(shells) * k, 'failed': 0}
    rows = r['synthesized']
    assert [row['shell'] for row in rows] == [s for s in shells for _ in range(k)]
    assert [row['seed'] for row in rows] == [CONFIG.seed_of(i, c)
                                             for i in range(len(shells)) for c in range(k)]
    assert all(row['objects'] <= CONFIG.synth.max_objects for row in rows)
    o = r['distribution']['objects_per_room']
    assert o['synthesized'] == pytest.approx(sum(row['objects'] for row in rows) / len(rows))
    assert r['distribution']['objects_relative_difference'] == pytest.approx(
        o['synthesized'] / o['heldout'] - 1)


def test_validity_and_design_rules_of_both_sides(evaluated):
    r = evaluated[0]['room_types']['bedroom']
    assert r['validity']['synthesized']['rooms'] == r['rooms']['synthesized']
    assert r['validity']['heldout']['rooms'] == r['split']['heldout']
    assert all(0 <= v['valid'] <= 1 for v in r['validity'].values())
    rules = r['design_rules']
    assert set(rules) == {rule.name for rule in design_rules.rules()}
    # The data set's beds and dressers stand against the wall (its own category set says
    # so), so the wall rule has cases in real rooms though 'bed' is no paper category.
    kept, cases = rules['wall_contact']['corpus']
    assert cases > 0 and 0 <= kept <= cases
    # The bidet rule has no case in a bedroom on either side: not applicable.
    assert rules['bidet_by_toilet']['corpus'] == rules['bidet_by_toilet']['synthesized'] == [0, 0]


def test_wall_rules_read_the_room_types_own_category_set(weights):
    for rt in categories.ROOM_TYPES:
        assert walls.wall_categories(rt) == (walls.WALL_FURNITURE, walls.LARGE_PIECES)
    spec = bundle_specs(weights)['bedroom']
    own = {c.name for c in spec.categories if c.info.tier == 'first' and c.info.against_wall}
    wall, large = walls.wall_categories('bedroom', categories.PAPER.with_specs([spec]))
    assert 'bed' in own and own <= wall and 'bed' in large
    assert not (wall - own) & set(spec.names)       # the data set's flags, not the paper's
    assert walls.wall_categories('bedroom') == (walls.WALL_FURNITURE, walls.LARGE_PIECES)


def test_the_report_files_and_report_only(evaluated, cli):
    results, out = evaluated
    assert json.loads((out / 'results.json').read_text())['room_types'].keys() == {'bedroom'}
    text = (out / 'index.md').read_text()
    assert (out / 'copy' / 'evaluation.md').read_text() == text
    assert '| bedroom | ' in text and 'KL(training‖held-out)' in text
    assert 'Not applicable in bedroom:' in text and 'bidet_by_toilet' in text
    (out / 'index.md').unlink()
    run = cli('evaluate', '--report-only', '--out', out)
    assert (out / 'index.md').read_text() == text
    assert 'KL training' in run.stdout and 'bedroom' in run.stdout


def test_the_paper_room_types_stay_the_papers_after_the_run(evaluated):
    assert not categories.PAPER.defines('bedroom')
    assert categories.room_spec('bedroom') == categories.paper_spec('bedroom')
    with pytest.raises(UnknownRoomType):
        categories.resolve_room_type('garage')


@pytest.mark.parametrize('args, words', [
    (['--data', 'NODATA', '--weights-dir', 'W'], 'no dataset.yaml'),
    (['--data', 'DATA', '--weights-dir', 'W', '--room-type', 'kitchen'],
     "holds no bundle for room type 'kitchen'"),
    (['--data', 'DATA', '--weights-dir', 'W', '--room-type', 'garage'],
     "unknown room type 'garage'"),
    (['--data', 'DATA', '--weights-dir', 'EMPTY'], 'holds no bundle for any room type'),
    (['--data', 'DATA', '--weights-dir', 'NOWEIGHTS'], 'no such weights directory'),
    (['--data', 'DATA'], '--data needs --weights-dir'),
    (['--data', 'DATA', '--weights-dir', 'W', '--rooms-per-shell', '0'],
     '--rooms-per-shell must be at least 1'),
    (['--data', 'DATA', '--weights-dir', 'W', '--quick'], '--quick has no meaning'),
    (['--rooms-per-shell', '2'], '--rooms-per-shell needs --data'),
])
def test_bad_input_is_one_sentence_and_exit_2(cli, data, weights, tmp_path, args, words):
    (tmp_path / 'empty').mkdir()
    paths = {'DATA': data, 'W': weights, 'NODATA': tmp_path, 'EMPTY': tmp_path / 'empty',
             'NOWEIGHTS': tmp_path / 'none'}
    run = cli('evaluate', *[paths.get(a, a) for a in args], '--out', tmp_path / 'out',
              ok=False)
    assert run.returncode == 2
    assert words in run.stderr and run.stderr.strip().count('\n') == 0
    assert not (tmp_path / 'out' / 'results.json').exists()
