"""``python -m scene_synth_ros.cli``: the same command line as the ``scene-synth`` script."""
import sys

from . import main

# Guarded because tools that import every module of the package (pkgutil.walk_packages in
# the tests) import this one too, and must not run a command.
if __name__ == '__main__':
    sys.exit(main())
