"""scene-synth generate / complete / suggest / train / gallery / demo, through the command
line's ``main(argv)`` (the ``cli`` fixture)."""
import json

from conftest import EXAMPLES
import pytest

from scene_synth_ros.categories import PASSAGE_ROOM_TYPES, ROOM_TYPES
from scene_synth_ros.geometry import check_scene
from scene_synth_ros.networks.bundle import load_bundle
from scene_synth_ros.schema import load_scene


def test_generate_from_a_layout_and_from_a_room_type(cli, tmp_path):
    out, png = tmp_path / 'living.json', tmp_path / 'living.png'
    proc = cli('generate', '--layout', EXAMPLES / 'lshaped_living_layout.json', '--seed', 3,
               '--out', out, '--png', png)
    scene = load_scene(out)
    assert len(scene.room.floor) == 6 and len(scene) >= 2 and check_scene(scene).ok
    assert scene.meta['seed'] == 3 and png.stat().st_size > 10_000
    assert 'ms per module: render' in proc.stdout and 'physical check: valid' in proc.stdout
    cli('generate', '--room-type', 'bathroom', '--seed', 0, '--out', tmp_path / 'a.json')
    cli('generate', '--room-type', 'bathroom', '--seed', 0, '--out', tmp_path / 'b.json')
    assert (tmp_path / 'a.json').read_text() == (tmp_path / 'b.json').read_text()


def test_complete_keeps_the_objects_and_suggest_proposes(cli, tmp_path):
    out = tmp_path / 'done.json'
    cli('complete', EXAMPLES / 'partial_bedroom.json', '--seed', 1, '--out', out)
    partial = load_scene(EXAMPLES / 'partial_bedroom.json')
    done = load_scene(out)
    assert [o.to_dict() for o in done.objects[:len(partial)]] == \
        [o.to_dict() for o in partial.objects]
    assert len(done) > len(partial) and check_scene(done).ok
    proc = cli('suggest', EXAMPLES / 'partial_bedroom.json', '-k', 3, '--out',
               tmp_path / 'next.json', '--png', tmp_path / 'next.png')
    proposals = json.loads((tmp_path / 'next.json').read_text())
    assert 1 <= len(proposals) <= 3 and 'proposals for the next object' in proc.stdout
    assert (tmp_path / 'next.png').is_file()


def test_synthesis_bad_input_is_one_sentence(cli, tmp_path):
    for args, words in [
            (('generate', '--room-type', 'garage'), 'unknown room type'),
            (('generate', '--room-type', 'all'), 'one --room-type'),
            (('generate', '--weights-dir', tmp_path), 'no such weights file'),
            (('generate', '--temperature', '0'), '--temperature must be between 0.05 and 5'),
            (('complete', tmp_path / 'nothing.json'), 'no such file'),
            (('suggest', EXAMPLES / 'partial_bedroom.json', '-k', '0'), 'at least 1')]:
        proc = cli(*args, ok=False)
        assert proc.returncode == 2, (args, proc.stderr)
        assert words in proc.stderr and 'Traceback' not in proc.stderr
        assert len(proc.stderr.strip().splitlines()) == 1
    broken = tmp_path / 'w'
    broken.mkdir()
    (broken / 'bedroom.pt').write_bytes(b'not a weights file')
    proc = cli('generate', '--weights-dir', broken, ok=False)
    assert proc.returncode == 2 and 'bedroom.pt: not a readable weights file' in proc.stderr


def test_synthesis_flags_are_the_settings_and_refuse_what_the_node_refuses(cli):
    # Every setting with a flag is on each verb that furnishes, with its range in its help,
    # and a value outside the range the node's parameter has is refused in one sentence
    # naming the flag, before any weights load.
    from scene_synth_ros.cli import build_parser
    from scene_synth_ros.server import PARAMETERS
    from scene_synth_ros.synth_config import ROBOT_SETTINGS, flag_settings
    table = {**flag_settings(), **ROBOT_SETTINGS}
    assert {'location_temperature', 'max_objects', 'device', 'runtime', 'catalog',
            'robot_radius'} <= set(table)
    sub = build_parser()._subparsers._group_actions[0].choices
    for verb in ('generate', 'complete', 'suggest'):
        flags = {a.option_strings[0]: a for a in sub[verb]._actions if a.option_strings}
        for name, (s, _) in table.items():
            assert flags[s.flag].help.startswith(s.description), (verb, s.flag)
            if s.bounds is not None:
                assert s.limits_text() in flags[s.flag].help
                if name in PARAMETERS:            # the node's range is the flag's
                    assert PARAMETERS[name][1] == s.bounds
            if s.choices is not None:
                assert tuple(flags[s.flag].choices) == s.choices
    for flag, value in (('--temperature', '0.04'), ('--temperature', '5.5'),
                        ('--max-objects', '0'), ('--max-objects', '101'),
                        ('--robot-radius', '0.9'), ('--robot-reach', '0')):
        proc = cli('suggest', EXAMPLES / 'partial_bedroom.json', flag, value, ok=False)
        assert proc.returncode == 2, proc.stderr
        assert proc.stderr.startswith(f'scene-synth: {flag} must be between ')
        assert len(proc.stderr.strip().splitlines()) == 1
    proc = cli('generate', '--device', 'tpu', ok=False)
    assert proc.returncode == 2 and "invalid choice: 'tpu'" in proc.stderr


@pytest.mark.slow
def test_train_command_writes_a_loadable_bundle(cli, tmp_path):
    cfg = tmp_path / 'tiny.yaml'
    cfg.write_text('''name: tiny
device: cpu
model:
  category_encoder: {blocks: [1, 1], widths: [8, 16]}
  location_encoder: {blocks: [1, 1], widths: [8, 16]}
  location_decoder_widths: [16, 8, 8]
  local_encoder: {blocks: [1, 1], widths: [8, 16]}
  hidden: 32
  latent: 4
train:
  train_rooms: 20
  val_rooms: 5
  val_examples: 8
  threads: 1
  category: {steps: 2, batch_size: 4}
  location: {steps: 2, batch_size: 4}
  orientation: {steps: 2, batch_size: 4}
  snap: {steps: 2, batch_size: 4}
  dimensions: {steps: 2, batch_size: 4}
''')
    # Some modules alone: trained, nothing exported; then all of them: the bundle.
    proc = cli('train', '--room-type', 'bathroom', '--config', cfg, '--run-dir',
               tmp_path / 'run', '--weights-dir', tmp_path / 'w', '--quiet',
               '--modules', 'location,snap')
    assert 'run again over all modules to export' in proc.stdout
    assert sorted(p.name for p in (tmp_path / 'run' / 'bathroom').glob('*.ckpt')) == \
        ['location.ckpt', 'snap.ckpt']
    assert not (tmp_path / 'w').exists()
    proc = cli('train', '--room-type', 'bathroom', '--config', cfg, '--run-dir',
               tmp_path / 'run', '--weights-dir', tmp_path / 'w', '--quiet')
    assert 'category top-1 accuracy' in proc.stdout
    b = load_bundle(tmp_path / 'w' / 'bathroom.pt')
    assert b.config.name == 'tiny'
    log = [json.loads(line) for line in (tmp_path / 'run' / 'bathroom' / 'log.jsonl')
           .read_text().splitlines()]
    assert {e.get('module') for e in log} >= {'category', 'location', 'orientation', 'snap',
                                              'dimensions'}
    bad = tmp_path / 'bad.yaml'
    bad.write_text('model: {resolution: [64}\n')
    proc = cli('train', '--config', bad, ok=False)
    assert proc.returncode == 2 and 'not valid YAML' in proc.stderr
    proc = cli('train', '--config', cfg, '--modules', 'colour', ok=False)
    assert proc.returncode == 2 and "unknown module 'colour'" in proc.stderr
    proc = cli('train', '--config', tmp_path / 'none.yaml', ok=False)
    assert proc.returncode == 2 and 'no such configuration file' in proc.stderr


def test_galleries(cli, tmp_path):
    cli('gallery', '--source', 'completions', '--per-type', 2, '--out', tmp_path / 'c.png')
    assert (tmp_path / 'c.png').stat().st_size > 10_000


@pytest.mark.slow
def test_demo_furnishes_every_kind_of_room(cli, tmp_path):
    proc = cli('demo', '--out', tmp_path, '--per-type', 1)
    names = ['bedroom_layout', 'lshaped_living_layout', 'kitchen_layout',
             'partial_bedroom_completed'] + [f'{rt}_0' for rt in ROOM_TYPES]
    for name in names:
        scene = load_scene(tmp_path / f'{name}.json')
        # a hallway may rightly hold one piece or none
        least = 0 if scene.room.room_type in PASSAGE_ROOM_TYPES else 2
        assert check_scene(scene).ok and len(scene) >= least, name
        assert (tmp_path / f'{name}.png').is_file()
    assert (tmp_path / 'gallery.png').is_file()
    assert proc.stdout.count(' yes ') == len(names)
