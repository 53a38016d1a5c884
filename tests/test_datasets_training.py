"""Training on an imported data set: its room types' category sets (from dataset.yaml), its
rooms reduced to what the pipeline places, the held-out split, bundles that carry their
category sets, and the commands and the server using such weights. The data are the real
ProcTHOR rooms of ../shared/data/real/procthor, imported in the test."""
import json
from pathlib import Path

from conftest import tiny_config
import pytest

from scene_synth_ros import catalog
from scene_synth_ros.categories import (
    PAPER,
    ROOM_TYPES,
    RoomTypeSpec,
    paper_spec,
    resolve_room_type,
    room_spec,
)
from scene_synth_ros.datasets import import_dataset
from scene_synth_ros.datasets.training import (
    describe_dir,
    load_rooms,
    room_type_specs,
    split,
)
from scene_synth_ros.errors import RoomTypeConflict, UnknownRoomType

PROCTHOR = Path(__file__).resolve().parents[2] / 'shared/data/real/procthor'
pytestmark = pytest.mark.skipif(not (PROCTHOR / 'procthor_1room_train.jsonl.gz').is_file(),
                                reason='the real ProcTHOR file is not beside the repository')


@pytest.fixture(scope='module')
def data(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp('procthor') / 'data'
    import_dataset('procthor', [PROCTHOR / 'procthor_1room_train.jsonl.gz'], out)
    return out


@pytest.fixture(scope='module')
def kitchen_weights(data, tmp_path_factory) -> Path:
    """Tiny kitchen networks trained on the imported kitchens (a room type the paper lacks)."""
    from scene_synth_ros.networks.train import train
    root = tmp_path_factory.mktemp('kitchen')
    train(['kitchen'], tiny_config(), root / 'run', root / 'weights', progress=False,
          echo=lambda s: None, data_dir=data)
    return root / 'weights'


def test_a_spec_round_trips_through_plain_data():
    spec = paper_spec('bedroom')
    again = RoomTypeSpec.from_dict(json.loads(json.dumps(spec.to_dict())))
    assert again == spec
    assert again.importance_order() == spec.importance_order()
    # names and positions are cached on the (frozen) spec; lookups agree with the table
    assert spec.names == tuple(c.name for c in spec.categories)
    assert [spec.index(n) for n in spec.names] == list(range(len(spec.names)))
    assert spec['double bed'].name == 'double bed' and 'toilet' not in spec
    with pytest.raises(ValueError, match="'toilet' is not a category of bedroom"):
        spec.index('toilet')
    assert again == spec and hash(again) == hash(spec)


def test_specs_from_the_description_hold_what_the_pipeline_places(data):
    desc = describe_dir(data)
    specs = room_type_specs(desc)
    assert set(specs) == {'bedroom', 'kitchen', 'living'}
    for rt, spec in specs.items():
        d = desc.room_types[rt]
        tiers = {c.name: c.tier for c in d.categories}
        assert 'painting' in tiers and 'painting' not in spec    # mounted: left out
        for name in spec.names:
            info = spec.info(name)
            assert info.tier == tiers[name]
            if info.tier == 'second':
                assert info.supported_by and all(tiers[p] == 'first' for p in info.supported_by)
        # the description's order, less what was left out
        assert spec.importance_order() == tuple(n for n in d.importance_order if n in spec)
        assert spec.size_cap == d.size_cap and spec.rooms == d.rooms


def test_rooms_keep_only_placeable_objects(data):
    spec = room_type_specs(describe_dir(data))['living']
    rooms = load_rooms(data, spec)
    assert len(rooms.scenes) == spec.rooms == len(rooms.names)
    assert rooms.removed['category not placed by the pipeline'] > 0      # the paintings
    for scene in rooms.scenes:
        ids = {o.id: o for o in scene.objects}
        for o in scene.objects:
            assert o.category in spec
            if o.support is None:
                assert spec.info(o.category).tier == 'first'
            else:
                assert ids[o.support].category in spec.supports(o.category)


def test_the_held_out_split_is_seeded_and_disjoint():
    names = [f'room_{k}.json' for k in range(50)]
    train_idx, held = split(names, 0)
    assert len(held) == 10 and not set(train_idx) & set(held)
    assert sorted(train_idx + held) == list(range(50))
    assert split(list(reversed(names)), 0)[1] == [49 - k for k in reversed(held)]  # by name
    assert split(names, 1)[1] != held


def test_a_data_sets_vocabulary_knows_its_room_types_and_the_papers_does_not(data):
    specs = room_type_specs(describe_dir(data))
    vocabulary = PAPER.with_specs(specs.values())
    # ProcTHOR's kitchens, a data set's own category set in place of the package's
    assert vocabulary.room_types == tuple(dict.fromkeys(ROOM_TYPES + ('kitchen',)))
    assert vocabulary.spec('bedroom') == specs['bedroom'] != paper_spec('bedroom')
    assert vocabulary.spec('Kitchen').names == specs['kitchen'].names
    assert vocabulary.defines('kitchen') and specs['kitchen'] != paper_spec('kitchen')
    assert vocabulary.defines('bedroom') and not vocabulary.defines('office')
    v = catalog.variants('fridge', 'kitchen', vocabulary)[0]
    assert v.model_id == 'kitchen__fridge_00' and catalog.get(v.model_id, vocabulary) == v
    with pytest.raises(RoomTypeConflict, match="'bedroom' is already defined"):
        vocabulary.with_specs([RoomTypeSpec.from_dict({**specs['bedroom'].to_dict(),
                                                       'rooms': 1})])
    assert vocabulary.with_specs([specs['bedroom']]) == vocabulary     # the same set: no change
    # The paper's vocabulary, in the same process, is untouched.
    with pytest.raises(UnknownRoomType, match="unknown room type 'garage'"):
        resolve_room_type('garage')
    assert room_spec('bedroom') == paper_spec('bedroom') and PAPER.room_types == ROOM_TYPES
    assert room_spec('kitchen') == paper_spec('kitchen') != specs['kitchen']
    with pytest.raises(KeyError):
        catalog.get('kitchen__fridge_00')


def test_a_data_sets_own_categories_are_known_where_its_vocabulary_is_passed(data):
    from scene_synth_ros.categories import CATEGORIES
    from scene_synth_ros.plot import UNKNOWN_COLOR, category_color
    from scene_synth_ros.user_catalog.spec import category_of
    vocabulary = PAPER.with_specs(room_type_specs(describe_dir(data)).values())
    own = next(n for n in vocabulary.spec('kitchen').names if n not in CATEGORIES)
    assert vocabulary.info(own) == vocabulary.spec('kitchen').info(own)
    assert category_of(own.replace(' ', '_'), vocabulary) == own      # a user's catalog folder
    assert category_of(own) is None
    assert category_color(own, vocabulary) != UNKNOWN_COLOR == category_color(own)
    with pytest.raises(KeyError):
        PAPER.info(own)


def test_trained_bundles_carry_their_category_set_and_furnish_rooms(data, kitchen_weights):
    from scene_synth_ros.geometry import check_scene
    from scene_synth_ros.networks.bundle import load_bundle
    from scene_synth_ros.synth import Synthesizer
    spec = room_type_specs(describe_dir(data))['kitchen']
    bundle = load_bundle(kitchen_weights / 'kitchen.pt')
    assert bundle.spec == spec == bundle.vocabulary.spec('kitchen')
    # and the data set's allowance, which the rooms it furnishes are judged by
    assert bundle.allowance == describe_dir(data).allowance
    synth = Synthesizer(kitchen_weights)
    assert synth.room_types == ['kitchen'] and synth.vocabulary.spec('kitchen') == spec
    shell = load_rooms(data, spec).scenes[0].room
    # tiny networks: a seed may draw a first category that fits nowhere; over five, some fit
    results = [synth.generate(shell, seed=seed) for seed in range(5)]
    assert any(r.scene.objects for r in results), 'the tiny networks placed nothing'
    for result in results:
        for o in result.scene.objects:
            assert o.category in spec and o.model_id.startswith('kitchen__')
        assert result.allowance == bundle.allowance
        assert check_scene(result.scene, result.allowance).ok
    assert synth.generate(shell, seed=3).scene.to_dict() == results[3].scene.to_dict()


@pytest.mark.slow
def test_training_side_by_side_gives_the_bundle_of_one_process(data, kitchen_weights, tmp_path):
    """``train --data --jobs``: the modules in processes side by side, the data set's rooms
    read once and handed to them; the bundle is the one a single process trains."""
    from scene_synth_ros.networks.jobs import train_side_by_side
    lines = []
    out = train_side_by_side(['kitchen'], tiny_config(), tmp_path / 'run', tmp_path / 'w', 2,
                             echo=lines.append, data_dir=data)
    assert out == [tmp_path / 'w' / 'kitchen.pt']
    assert out[0].read_bytes() == (kitchen_weights / 'kitchen.pt').read_bytes()
    assert any(line.startswith('kitchen/location: finished') for line in lines)


def test_two_synthesizers_in_one_process_keep_their_own_room_types(data, kitchen_weights):
    """Loading weights of a data set changes nothing for anyone else in the process: each
    synthesizer's vocabulary parses its own layouts with its own category set (a data set's
    kitchen is not the package's), and refuses a room type it does not know with the
    sentence it always had."""
    from scene_synth_ros.corpus.generate import first_shell
    from scene_synth_ros.render import num_channels
    from scene_synth_ros.schema import SceneValidationError, parse_room_layout
    from scene_synth_ros.synth import Synthesizer
    specs = room_type_specs(describe_dir(data))
    shipped = Synthesizer()
    before = parse_room_layout(first_shell('bedroom', 0).to_dict(),
                               vocabulary=shipped.vocabulary)
    kitchen = Synthesizer(kitchen_weights)
    layout = load_rooms(data, specs['kitchen']).scenes[0].room.to_dict()
    assert parse_room_layout(layout, vocabulary=kitchen.vocabulary).room.room_type == 'kitchen'
    assert kitchen.vocabulary.spec('kitchen') == specs['kitchen']
    assert shipped.vocabulary.spec('kitchen') == PAPER.spec('kitchen') != specs['kitchen']
    garage = dict(layout, room_type='garage')
    refused = ("room_type 'garage' is not a known room type (expected one of bedroom, "
               "living, office, bathroom, kitchen, dining, hallway, or an alias such as "
               "'living room')")
    for vocabulary in (shipped.vocabulary, PAPER):
        with pytest.raises(SceneValidationError) as e:
            parse_room_layout(garage, vocabulary=vocabulary)
        assert str(e.value) == refused
    # The shipped synthesizer's bedroom is still the paper's, after the kitchen weights.
    after = parse_room_layout(first_shell('bedroom', 0).to_dict(),
                              vocabulary=shipped.vocabulary)
    assert after.to_dict() == before.to_dict() == parse_room_layout(
        first_shell('bedroom', 0).to_dict()).to_dict()
    assert shipped.vocabulary == PAPER
    # A data set's own bedroom lives in its vocabulary only.
    own = PAPER.with_specs([specs['bedroom']])
    assert num_channels('bedroom', own) != num_channels('bedroom')
    assert num_channels('bedroom', shipped.vocabulary) == num_channels('bedroom')


def test_the_commands_take_the_data_sets_room_types_from_the_weights(
        data, kitchen_weights, tmp_path, cli):
    spec = room_type_specs(describe_dir(data))['kitchen']
    layout = tmp_path / 'kitchen_layout.json'
    layout.write_text(json.dumps(load_rooms(data, spec).scenes[0].room.to_dict()))
    out = tmp_path / 'kitchen.json'
    cli('generate', '--layout', layout, '--weights-dir', kitchen_weights, '--out', out,
        '--seed', 1)
    assert json.loads(out.read_text())['room']['room_type'] == 'kitchen'
    r = cli('validate', out, ok=False)       # the package's kitchen has other models
    assert r.returncode == 2 and 'is not a catalog model id' in r.stderr
    r = cli('validate', out, '--weights-dir', kitchen_weights)
    assert 'physically valid' in r.stdout
    r = cli('generate', '--room-type', 'kitchen', '--weights-dir', kitchen_weights, ok=False)
    assert r.returncode == 2 and "corpus makes only the package's own: give --layout" in r.stderr
    r = cli('generate', '-n', 2, '--room-type', 'kitchen', '--weights-dir', kitchen_weights,
            '--out', tmp_path / 'batch', ok=False)
    assert r.returncode == 2 and 'give --layouts' in r.stderr
    r = cli('evaluate', '--room-type', 'kitchen', '--weights-dir', kitchen_weights,
            '--out', tmp_path / 'ev', ok=False)
    assert r.returncode == 2 and 'evaluate them with --data' in r.stderr
    # the corpus makes the package's rooms (its own kitchens among them), not a data set's
    r = cli('corpus', '--room-type', 'garage', '-n', 1, '--out', tmp_path / 'c', ok=False)
    assert r.returncode == 2 and "unknown room type 'garage'" in r.stderr
    r = cli('train', '--data', data, ok=False)
    assert r.returncode == 2 and '--data needs --weights-dir' in r.stderr
    r = cli('train', '--data', tmp_path, '--weights-dir', tmp_path / 'w', ok=False)
    assert r.returncode == 2 and 'no dataset.yaml' in r.stderr


def test_the_server_serves_a_data_sets_room_type(data, kitchen_weights):
    import threading

    from scene_synth_ros.server import ConfigError, SceneServer, ServerConfig
    served, done = [], threading.Event()

    def publish(s):
        served.append(s)
        done.set()
    spec = room_type_specs(describe_dir(data))['kitchen']
    with pytest.raises(ConfigError, match="room_type 'bedroom' has no weights in .*; they "
                       'have kitchen'):
        SceneServer(ServerConfig(weights_dir=str(kitchen_weights)), publish)
    srv = SceneServer(ServerConfig(weights_dir=str(kitchen_weights), room_type='kitchen',
                                   auto_generate=False, next_category='fridge'), publish)
    try:
        room = load_rooms(data, spec).scenes[0].room.to_dict()
        assert srv.submit_layout(json.dumps(room))
        assert done.wait(60)
        ok, message = srv.request('next_object')
        assert ok, message
        scene = srv.scene
        assert scene.room.room_type == 'kitchen'
        assert [o.category for o in scene.objects] == ['fridge']
        srv.reconfigure({'next_category': 'counter_top'})      # the data set's category
        with pytest.raises(ConfigError, match="next_category 'spaceship' is not a category"):
            srv.reconfigure({'next_category': 'spaceship'})
    finally:
        srv.close()


def test_the_gallery_shows_held_out_rooms_beside_synthesized_ones(data, kitchen_weights,
                                                                   tmp_path, cli):
    out = tmp_path / 'gallery.png'
    cli('gallery', '--source', 'data', '--data', data, '--weights-dir', kitchen_weights,
        '--per-type', 2, '--out', out)
    from matplotlib.image import imread
    h, w = imread(out).shape[:2]
    assert w > 1.5 * h                       # one row of 2 real + 2 synthesized rooms
    r = cli('gallery', '--source', 'data', '--weights-dir', kitchen_weights, '--out', out,
            ok=False)
    assert r.returncode == 2 and 'needs --data and --weights-dir' in r.stderr
