"""The ROS 2 package is laid out and installs as ament_python / colcon expect."""
import json
import os
from pathlib import Path
import re
import shutil
import subprocess
import sys
import venv
import xml.etree.ElementTree as ET
import zipfile

import pytest

from scene_synth_ros.categories import ROOM_TYPES

ROOT = Path(__file__).resolve().parent.parent
ROS_DEPS = {'rclpy', 'std_msgs', 'geometry_msgs', 'visualization_msgs', 'std_srvs',
            'diagnostic_msgs'}


def test_package_xml_is_format_3_ament_python_with_the_ros_dependencies():
    root = ET.parse(ROOT / 'package.xml').getroot()
    assert root.tag == 'package' and root.get('format') == '3'
    assert root.findtext('name') == 'scene_synth_ros'
    assert root.find('export/build_type').text == 'ament_python'
    assert ROS_DEPS <= {e.text for e in root.findall('exec_depend')}


def test_ros_dependencies_import_in_this_environment():
    # What package.xml promises must be importable here, or nothing ROS-side will run.
    code = ('import rclpy, std_msgs.msg, geometry_msgs.msg, visualization_msgs.msg, '
            'std_srvs.srv, diagnostic_msgs.msg')
    subprocess.run([sys.executable, '-c', code], check=True, timeout=60)


def test_core_library_does_not_import_rclpy():
    code = ('import sys, pkgutil, importlib, scene_synth_ros\n'
            'for m in pkgutil.walk_packages(scene_synth_ros.__path__, "scene_synth_ros."):\n'
            '    if m.name not in ("scene_synth_ros.node", "scene_synth_ros.ros_client"):\n'
            '        importlib.import_module(m.name)\n'
            'assert "rclpy" not in sys.modules, "the core library imported rclpy"\n')
    subprocess.run([sys.executable, '-c', code], check=True, timeout=120)


# What a checkout accumulates that is not source: setuptools would pack a stale build/lib
# (modules since deleted) into the wheel, and the rest is large and irrelevant.
NOT_SOURCE = shutil.ignore_patterns('.git', '.venv', 'build', 'dist', 'install', 'log', 'logs',
                                    'out', 'runs', 'report', 'demo_out', '*.egg-info',
                                    '__pycache__', '.pytest_cache', '.ruff_cache')


@pytest.fixture(scope='module')
def wheel(tmp_path_factory) -> Path:
    """The package's wheel, built once for the tests below from a clean copy of the sources,
    as on a fresh clone."""
    src = tmp_path_factory.mktemp('src') / 'scene_synth_ros'
    shutil.copytree(ROOT, src, ignore=NOT_SOURCE)
    out = tmp_path_factory.mktemp('wheels')
    subprocess.run([sys.executable, '-m', 'pip', 'wheel', '-q', '--no-deps',
                    '--no-build-isolation', '-w', str(out), str(src)],
                   check=True, timeout=300, capture_output=True)
    return next(out.glob('scene_synth_ros-*.whl'))


@pytest.mark.slow
def test_wheel_installs_the_ament_data_files(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    data = 'scene_synth_ros-0.1.0.data/data/'
    assert data + 'share/ament_index/resource_index/packages/scene_synth_ros' in names
    assert data + 'share/scene_synth_ros/package.xml' in names
    for schema in ('room_layout', 'placed_object', 'scene', 'house_layout', 'house_scene'):
        assert f'{data}share/scene_synth_ros/msg_schemas/{schema}.schema.json' in names
    assert any(n.startswith(data + 'share/scene_synth_ros/examples/') for n in names)
    assert 'scene_synth_ros/corpus/calibration.json' in names
    assert 'scene_synth_ros/datasets/room_types.yaml' in names    # the import's room types
    for rt in ROOM_TYPES:
        assert f'scene_synth_ros/weights/{rt}.pt' in names
    for cfg in ('compact', 'paper', 'scene_synth_node'):
        assert f'{data}share/scene_synth_ros/config/{cfg}.yaml' in names
    for shared in ('launch/scene_synth.launch.py', 'launch/scene_synth.launch.xml',
                   'rviz/scene_synth.rviz'):
        assert f'{data}share/scene_synth_ros/{shared}' in names
    # The catalog meshes that mesh markers name as package://scene_synth_ros/meshes/<model>.obj
    from scene_synth_ros import catalog
    meshes = [n for n in names if n.startswith(f'{data}share/scene_synth_ros/meshes/')]
    assert len([n for n in meshes if n.endswith('.obj')]) == len(catalog.all_variants())
    assert len([n for n in meshes if n.endswith('.mtl')]) == len(catalog.all_variants())
    info = next(n for n in names if n.endswith('.dist-info/entry_points.txt'))
    entry_points = zipfile.ZipFile(wheel).read(info).decode()
    assert 'scene_synth_node = scene_synth_ros.node:main' in entry_points  # for `ros2 run`
    entry_points = zipfile.ZipFile(wheel).read(
        'scene_synth_ros-0.1.0.dist-info/entry_points.txt').decode()
    assert 'scene-synth = scene_synth_ros.cli:main' in entry_points


def test_resource_marker_and_setup_cfg_script_dir():
    assert (ROOT / 'resource' / 'scene_synth_ros').is_file()
    cfg = (ROOT / 'setup.cfg').read_text()
    # ros2 run looks for executables in lib/<package>
    assert 'install_scripts=$base/lib/scene_synth_ros' in cfg


def _source_modules() -> set[str]:
    """Every Python file of the package, as its path inside a wheel."""
    pkg = ROOT / 'scene_synth_ros'
    return {p.relative_to(ROOT).as_posix() for p in pkg.rglob('*.py')
            if '__pycache__' not in p.parts}


def _source_packages() -> set[str]:
    """Every directory of Python modules under scene_synth_ros/, as a dotted package name."""
    pkg = ROOT / 'scene_synth_ros'
    return {'.'.join(d.relative_to(ROOT).parts) for d in [pkg, *pkg.rglob('*')]
            if d.is_dir() and any(d.glob('*.py'))}


def test_every_directory_of_modules_is_a_package():
    # find_packages() skips a directory without __init__.py, and so would every wheel and
    # colcon install (networks/ was once left out that way).
    missing = sorted(p for p in _source_packages()
                     if not (ROOT / p.replace('.', '/') / '__init__.py').is_file())
    assert not missing, f'no __init__.py in {missing}'


@pytest.mark.slow
def test_the_wheel_works_installed_outside_the_source_tree(wheel, tmp_path):
    """Install the wheel (not editable) into a fresh virtual environment and use it from a
    directory outside the checkout, as a user of `pip install .` or of a plain `colcon build`
    would. The fresh environment borrows this one's pinned dependencies through a path
    entry, which does not run the editable install's import hook."""
    # (share/ holds a .py too, the launch file: data, not a module)
    in_wheel = {n for n in zipfile.ZipFile(wheel).namelist()
                if n.endswith('.py') and '.data/' not in n}
    # Every module of the sources and nothing else (no stale module from an old build).
    assert in_wheel == _source_modules(), sorted(in_wheel ^ _source_modules())

    env_dir = tmp_path / 'fresh'
    venv.create(env_dir, with_pip=False)
    py = env_dir / 'bin' / 'python'
    site = Path(subprocess.run([str(py), '-c', 'import sysconfig; print(sysconfig.get_path('
                                '"purelib"))'], check=True, capture_output=True,
                               text=True).stdout.strip())
    deps = [p for p in map(Path, sys.path) if p.name == 'site-packages' and p.is_dir()]
    (site / '_borrowed_dependencies.pth').write_text(''.join(f'{p}\n' for p in deps))
    subprocess.run([sys.executable, '-m', 'pip', '--python', str(py), 'install', '-q',
                    '--no-deps', '--no-index', str(wheel)],
                   check=True, timeout=300, capture_output=True)

    work = tmp_path / 'elsewhere'
    work.mkdir()
    env = {k: v for k, v in os.environ.items()
           if k not in ('PYTHONPATH', 'AMENT_PREFIX_PATH', 'COLCON_PREFIX_PATH')}

    def run(*argv):
        done = subprocess.run(argv, cwd=work, env=env, capture_output=True, text=True,
                              timeout=300)
        assert done.returncode == 0, done.stderr
        return done.stdout

    run(str(env_dir / 'bin' / 'scene-synth'), 'generate', '--room-type', 'bedroom', '--seed',
        '0', '--out', 'x.json')
    check = (
        'import json, sys\n'
        'import scene_synth_ros, scene_synth_ros.node\n'
        'from scene_synth_ros import paths\n'
        'from scene_synth_ros.schema import load_scene\n'
        'scene = load_scene("x.json")\n'
        'share = paths.share_dir()\n'
        'print(json.dumps({"package": scene_synth_ros.__file__, "share": str(share),\n'
        '    "objects": len(scene.objects),\n'
        '    "files": sorted(p.name for p in share.iterdir()),\n'
        '    "schemas": sorted(p.name for p in paths.schema_dir().glob("*.json")),\n'
        '    "configs": sorted(p.name for p in paths.config_dir().glob("*.yaml")),\n'
        '    "weights": sorted(p.name for p in paths.weights_dir().glob("*.pt")),\n'
        '    "node": scene_synth_ros.node.__file__}))\n')
    seen = json.loads(run(str(py), '-c', check))
    prefix = str(env_dir.resolve())
    assert seen['package'].startswith(prefix) and seen['node'].startswith(prefix)
    assert seen['share'] == str(env_dir.resolve() / 'share' / 'scene_synth_ros')
    assert {'package.xml', 'msg_schemas', 'config', 'examples', 'launch', 'rviz'} \
        <= set(seen['files'])
    assert 'meshes' in seen['files']
    assert {'room_layout.schema.json', 'scene.schema.json'} <= set(seen['schemas'])
    assert {'compact.yaml', 'paper.yaml', 'scene_synth_node.yaml'} <= set(seen['configs'])
    assert seen['weights'] == sorted(f'{rt}.pt' for rt in ROOM_TYPES)
    assert seen['objects'] > 0
    assert (env_dir / 'bin' / 'scene_synth_node').is_file()


def test_setup_py_runs_without_warnings():
    # colcon's ament_python build runs setup.py directly; a warning there is shown to every
    # user of `colcon build` (once: "Unknown distribution option: 'tests_require'").
    done = subprocess.run([sys.executable, 'setup.py', '--name', '--version'], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and done.stdout.split() == ['scene_synth_ros', '0.1.0']
    assert 'warn' not in done.stderr.lower(), done.stderr


def test_the_interface_package_declares_every_interface_file():
    """scene_synth_msgs/: format 3, an interface package, and CMakeLists.txt generating
    exactly the .msg, .srv and .action files that are there."""
    pkg = ROOT / 'scene_synth_msgs'
    root = ET.parse(pkg / 'package.xml').getroot()
    assert root.get('format') == '3' and root.findtext('name') == 'scene_synth_msgs'
    assert root.findtext('member_of_group') == 'rosidl_interface_packages'
    assert root.find('export').findtext('build_type') == 'ament_cmake'
    files = {str(p.relative_to(pkg)) for p in pkg.glob('*/*')
             if p.suffix in ('.msg', '.srv', '.action')}
    listed = set(re.findall(r'"((?:msg|srv|action)/\w+\.\w+)"',
                            (pkg / 'CMakeLists.txt').read_text()))
    assert files == listed and len(files) == 12
    # Every message type the files use comes from a package they declare.
    used = {m for p in files for m in re.findall(r'^(\w+)/\w+', (pkg / p).read_text(), re.M)}
    assert used <= {d.text for d in root.findall('depend')}
    # The node's package depends on it.
    node_pkg = ET.parse(ROOT / 'package.xml').getroot()
    assert 'scene_synth_msgs' in {e.text for e in node_pkg.findall('exec_depend')}
