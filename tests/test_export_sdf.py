"""The Gazebo SDF export read by libsdformat, the parser Gazebo itself uses.

Debian's ``libsdformat-dev`` (sdformat 12, SDF up to 1.9; Gazebo Harmonic reads 1.9 files
with its sdformat 14) has no Python binding, so ``tests/sdf_check.cpp`` is compiled against
it once per session. Without the library or a C++ compiler the test is skipped and says how
to get them: ``apt-get install libsdformat-dev g++``.
"""
from pathlib import Path
import shutil
import subprocess

import pytest

from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.export import export_sdf, scene_bodies, wall_boxes

CHECKER = Path(__file__).with_name('sdf_check.cpp')


@pytest.fixture(scope='session')
def sdf_check(tmp_path_factory) -> Path:
    flags = subprocess.run(['pkg-config', '--cflags', '--libs', 'sdformat12'],
                           capture_output=True, text=True) if shutil.which('pkg-config') \
        else None
    if flags is None or flags.returncode or not shutil.which('g++'):
        pytest.skip('libsdformat is not installed (apt-get install libsdformat-dev g++)')
    exe = tmp_path_factory.mktemp('sdf') / 'sdf_check'
    subprocess.run(['g++', '-O0', str(CHECKER), *flags.stdout.split(), '-o', str(exe)],
                   check=True)
    return exe


def _read(exe: Path, path: Path) -> list[dict]:
    proc = subprocess.run([str(exe), str(path)], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    models = []
    for line in proc.stdout.splitlines():
        if line.startswith('model '):
            words = line.split()
            models.append({'name': words[1], **dict(w.split('=', 1) for w in words[2:])})
    return models


@pytest.mark.parametrize('root', ['world', 'model'])
def test_libsdformat_reads_the_world_and_the_spawnable_model(sdf_check, tmp_path, root):
    scene = generate_room('bedroom', 5, 4)              # L-shaped, with a second tier
    path = export_sdf(scene, tmp_path / 'room.sdf', root=root)
    models = {m['name']: m for m in _read(sdf_check, path)}
    depth = '1' if root == 'model' else '0'
    assert sum(m['depth'] == depth for m in models.values()) == \
        1 + len(wall_boxes(scene.room)) + len(scene.objects)
    assert models['floor']['static'] == '1'
    for body in scene_bodies(scene):
        m = models[body.id]
        assert m['static'] == '0'
        assert float(m['mass']) == pytest.approx(body.mass, rel=1e-4)
        assert float(m['ixx']) == pytest.approx(body.inertia[0, 0], rel=1e-4)
        assert int(m['collisions']) == len(body.pieces)
        assert (tmp_path / m['mesh']).is_file()


def test_libsdformat_refuses_a_broken_world(sdf_check, tmp_path):
    # The checker is not a rubber stamp: a negative mass is an error.
    path = export_sdf(generate_room('office', 5, 0), tmp_path / 'room.sdf')
    text = path.read_text()
    start = text.index('<mass>') + len('<mass>')
    path.write_text(text[:start] + '-1' + text[text.index('</mass>', start):])
    proc = subprocess.run([str(sdf_check), str(path)], capture_output=True, text=True)
    assert proc.returncode == 1 and proc.stderr
