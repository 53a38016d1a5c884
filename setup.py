"""ament_python build of scene_synth_ros; also installable with pip for the .venv set-up."""
from glob import glob
import os

from setuptools import find_packages, setup

PACKAGE = 'scene_synth_ros'
HERE = os.path.dirname(os.path.abspath(__file__))


def _files(pattern):
    """Repository-relative files matching pattern, sorted so builds are reproducible."""
    return sorted(os.path.relpath(p, HERE) for p in glob(os.path.join(HERE, pattern)))


setup(
    name=PACKAGE,
    version='0.1.0',
    packages=find_packages(exclude=['tests', 'tests.*', 'benchmarks']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + PACKAGE]),
        ('share/' + PACKAGE, ['package.xml']),
        ('share/' + PACKAGE + '/msg_schemas', _files('msg_schemas/*.json')),
        ('share/' + PACKAGE + '/config', _files('config/*.yaml')),
        ('share/' + PACKAGE + '/examples', _files('examples/*.json')),
        ('share/' + PACKAGE + '/launch', _files('launch/*.launch.*')),
        ('share/' + PACKAGE + '/rviz', _files('rviz/*.rviz')),
        ('share/' + PACKAGE + '/meshes', _files('meshes/*')),
    ],
    # The weights live inside the Python package (found from __file__ wherever it is
    # installed), so they are not copied to share/ as well.
    package_data={PACKAGE: ['weights/*.pt', 'corpus/calibration.json',
                            'datasets/room_types.yaml',
                            'user_catalog/future_categories.yaml']},
    # Python dependencies are pinned once, in requirements.txt; colcon users get the
    # ROS ones from package.xml.
    install_requires=['setuptools'],
    # Batches on a Ray cluster (``scene-synth generate -n N --ray``); the version is pinned
    # in requirements.txt, which ``make test`` installs.
    # The CPU's forward passes in onnxruntime (scene_synth_ros/networks/runtime.py; without
    # it synthesis runs them in torch); onnx is what torch's exporter writes with.
    extras_require={'ray': ['ray'], 'onnxruntime': ['onnxruntime', 'onnx']},
    zip_safe=False,   # the weights are read as files
    maintainer='scene_synth_ros developers',
    maintainer_email='dev@scene-synth-ros.invalid',
    description='Indoor scene synthesis (Ritchie et al., CVPR 2019) as a ROS 2 node.',
    license='Apache-2.0',
    entry_points={
        'console_scripts': [
            'scene-synth = scene_synth_ros.cli:main',
            'scene_synth_node = scene_synth_ros.node:main',
        ],
    },
)
