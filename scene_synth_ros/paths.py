"""Where the package's data files are, in a source checkout and in a colcon install."""
from __future__ import annotations

from functools import lru_cache
from pathlib import Path
import sys

PACKAGE = 'scene_synth_ros'
_SOURCE_ROOT = Path(__file__).resolve().parent.parent


@lru_cache(maxsize=None)
def share_dir() -> Path:
    """The directory holding msg_schemas/, config/ and examples/.

    A source checkout (or editable install) has them beside the package; a colcon or pip
    install has them in ``share/scene_synth_ros`` under its prefix, found through the ament
    index when the workspace is sourced, else from where the package itself was installed
    (``<prefix>/lib/pythonX.Y/site-packages/scene_synth_ros``) or the interpreter's prefix.
    """
    if (_SOURCE_ROOT / 'msg_schemas').is_dir() and (_SOURCE_ROOT / 'package.xml').is_file():
        return _SOURCE_ROOT
    try:
        from ament_index_python.packages import get_package_share_directory  # ROS installs only
        return Path(get_package_share_directory(PACKAGE))
    except Exception:
        pass
    candidates = [_SOURCE_ROOT.parent.parent.parent / 'share' / PACKAGE,
                  Path(sys.prefix) / 'share' / PACKAGE]
    for candidate in candidates:
        if (candidate / 'msg_schemas').is_dir():
            return candidate
    raise FileNotFoundError(
        f'cannot find the {PACKAGE} data files (msg_schemas/): looked in {_SOURCE_ROOT}, '
        f'the ament index, {candidates[0]} and {candidates[1]}')


def schema_dir() -> Path:
    return share_dir() / 'msg_schemas'


def examples_dir() -> Path:
    return share_dir() / 'examples'


def config_dir() -> Path:
    return share_dir() / 'config'


def meshes_dir() -> Path:
    """The catalog meshes that markers refer to as ``package://scene_synth_ros/meshes/...``."""
    return share_dir() / 'meshes'


def default_config_path() -> Path:
    return config_dir() / 'compact.yaml'


def weights_dir() -> Path:
    """The shipped weights, inside the Python package (found wherever it is installed)."""
    return Path(__file__).resolve().parent / 'weights'
