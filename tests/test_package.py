"""The ROS 2 package is laid out and installs as ament_python / colcon expect."""
from pathlib import Path
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile

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


def test_wheel_installs_the_ament_data_files(tmp_path):
    subprocess.run([sys.executable, '-m', 'pip', 'wheel', '-q', '--no-deps',
                    '--no-build-isolation', '-w', str(tmp_path), str(ROOT)],
                   check=True, timeout=300, capture_output=True)
    wheel = next(tmp_path.glob('scene_synth_ros-*.whl'))
    names = zipfile.ZipFile(wheel).namelist()
    data = 'scene_synth_ros-0.1.0.data/data/'
    assert data + 'share/ament_index/resource_index/packages/scene_synth_ros' in names
    assert data + 'share/scene_synth_ros/package.xml' in names
    for schema in ('room_layout', 'placed_object', 'scene'):
        assert f'{data}share/scene_synth_ros/msg_schemas/{schema}.schema.json' in names
    assert any(n.startswith(data + 'share/scene_synth_ros/examples/') for n in names)
    assert 'scene_synth_ros/corpus/calibration.json' in names
    for rt in ('bedroom', 'living', 'office', 'bathroom'):
        assert f'scene_synth_ros/weights/{rt}.pt' in names
    for cfg in ('compact', 'paper', 'scene_synth_node'):
        assert f'{data}share/scene_synth_ros/config/{cfg}.yaml' in names
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
