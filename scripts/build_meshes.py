#!/usr/bin/env python3
"""Write the catalog meshes shipped with the package into ``meshes/`` (or ``--out``).

One Wavefront OBJ and the MTL it names per catalog model: setup.py installs the folder to
``share/scene_synth_ros/meshes``, where RViz finds the files that mesh markers name as
``package://scene_synth_ros/meshes/<model id>.obj``. The output is a pure function of the
catalog (same bytes on every run and machine), and tests/test_markers.py fails when the
committed folder differs from it: run this after changing the catalog, a builder or the
palette, and commit the result.

    .venv/bin/python scripts/build_meshes.py
"""
from __future__ import annotations

import argparse
from pathlib import Path
import sys

ROOT = Path(__file__).resolve().parent.parent


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--out', type=Path, default=ROOT / 'meshes',
                   help='folder to write (default: the repository\'s meshes/)')
    p.add_argument('--keep-stale', action='store_true',
                   help='keep .obj/.mtl files there that the catalog no longer has')
    args = p.parse_args(argv)
    sys.path.insert(0, str(ROOT))      # the checkout's package, also without an install
    from scene_synth_ros.meshes import write_shipped_meshes
    paths = write_shipped_meshes(args.out, prune=not args.keep_stale)
    size = sum(path.stat().st_size for path in paths)
    print(f'{len(paths)} files, {size / 1e6:.2f} MB in {args.out}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
