"""The scene-synth command line: its commands through ``main(argv)`` in this process, and
once as a user runs it, in a process of its own (exit code and stderr included)."""
import json
import subprocess
import sys

from conftest import EXAMPLES, ROOT
import matplotlib.image as mpimg
import numpy as np

from scene_synth_ros.geometry import check_scene
from scene_synth_ros.schema import load_scene


def run_process(*args) -> subprocess.CompletedProcess:
    """``python -m scene_synth_ros.cli *args`` from the repository root."""
    return subprocess.run([sys.executable, '-m', 'scene_synth_ros.cli', *map(str, args)],
                          capture_output=True, text=True, cwd=ROOT, timeout=300)


def test_corpus_writes_valid_scenes_deterministically(cli, tmp_path):
    cli('corpus', '--room-type', 'bedroom', '-n', 12, '--out', tmp_path / 'a', '--seed', 4,
        '--quiet')
    cli('corpus', '--room-type', 'bedroom', '-n', 12, '--out', tmp_path / 'b', '--seed', 4,
        '--quiet', '--workers', 1)
    files = sorted((tmp_path / 'a').glob('bedroom_*.json'))
    assert [f.name for f in files] == [f'bedroom_{i:05d}.json' for i in range(12)]
    for f in files:
        scene = load_scene(f)
        assert scene.room.room_type == 'bedroom' and len(scene) > 0
        assert check_scene(scene).ok
        assert f.read_text() == (tmp_path / 'b' / f.name).read_text()


def test_render_png_and_channels(cli, tmp_path):
    cli('corpus', '--room-type', 'living', '-n', 1, '--out', tmp_path, '--quiet')
    scene_file = tmp_path / 'living_00000.json'
    cli('render', scene_file, '--png', tmp_path / 'room.png', '--channels',
        tmp_path / 'room.npy', '--resolution', 32)
    img = mpimg.imread(tmp_path / 'room.png')
    assert img.ndim == 3 and img.shape[0] > 100
    channels = np.load(tmp_path / 'room.npy')
    assert channels.shape[1:] == (32, 32) and channels[0].sum() > 0


def test_corpus_stats_prints_the_comparison(cli):
    out = cli('corpus-stats', '--room-type', 'bathroom', '-n', 30, '--categories').stdout
    assert 'KL(c||t)' in out and 'bathroom' in out and 'toilet' in out


def test_bad_input_gets_one_sentence_and_exit_code_2(tmp_path):
    # The one test through a real process: the exit status and stderr a user sees.
    missing = run_process('render', tmp_path / 'nope.json', '--png', tmp_path / 'x.png')
    assert missing.returncode == 2 and 'no such file' in missing.stderr
    bad = tmp_path / 'bad.json'
    layout = json.loads((EXAMPLES / 'bedroom_layout.json').read_text())
    layout['doors'][0]['position'] = [2.0, 1.5]            # in the middle of the room
    bad.write_text(json.dumps(layout))
    proc = run_process('validate', bad)
    assert proc.returncode == 2
    assert proc.stderr.count('\n') == 1 and 'doors[0]' in proc.stderr
    assert 'Traceback' not in proc.stderr
    unknown = run_process('corpus', '--room-type', 'garage', '-n', 1, '--out', tmp_path)
    assert unknown.returncode == 2 and 'garage' in unknown.stderr


def test_an_unknown_catalog_category_is_one_sentence(cli, tmp_path):
    run = cli('catalog', 'export', '--categories', 'cup,spaceship', '--out', tmp_path, ok=False)
    assert run.returncode == 2
    assert run.stderr == ("scene-synth: unknown category 'spaceship'; `scene-synth catalog "
                          "list` shows the catalog\n")
    assert not list(tmp_path.iterdir())     # nothing written before the check


def test_validate_accepts_the_examples(cli):
    out = cli('validate', *sorted(EXAMPLES.glob('*.json'))).stdout
    assert out.count('schema OK') == len(list(EXAMPLES.glob('*.json')))
