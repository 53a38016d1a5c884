"""The ``scene-synth`` command line. A thin adapter over the library: no ROS import here.

One module per group of commands (``corpus``, ``synthesis``, ``export``, ``catalog``,
``training``, ``evaluation``, ``ros``), each with ``add_parser(subparsers)`` and its
handlers; ``common`` holds what they share. Heavy libraries (torch, rclpy, matplotlib, the
synthesizer, the evaluation) are imported inside the handlers, because building the parser
imports every group and ``scene-synth --help`` should answer in well under a second.
"""
from __future__ import annotations

import argparse
import sys

from ..errors import SceneSynthError
from . import catalog, corpus, datasets, evaluation, export, ros, synthesis, training
from .common import EXIT_BAD_INPUT, weights_vocabulary

GROUPS = (synthesis, export, training, evaluation, corpus, datasets, catalog, ros)
DESCRIPTION = ('Furnish empty rooms for robot simulation: furnish one room or thousands, '
               'complete partial rooms, export them for simulators, train and evaluate the '
               'networks, and talk to a running scene_synth_node.')
EPILOG = "Each verb has its own --help. The guide: docs/cli.md in the package's repository."


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog='scene-synth', description=DESCRIPTION, epilog=EPILOG)
    sub = p.add_subparsers(dest='command', required=True)
    for group in GROUPS:
        group.add_parser(sub)
    return p


def main(argv: list[str] | None = None) -> int:
    """Run one command; a ``SceneSynthError`` is printed as its one sentence, exit code 2."""
    args = build_parser().parse_args(argv)
    try:
        # What the weights in use know (a data set's room types and categories): every
        # command reads room types and scenes with it.
        args.vocabulary = weights_vocabulary(args)
        return args.func(args)
    except SceneSynthError as e:
        print(f'scene-synth: {e}', file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        return 130


__all__ = ['build_parser', 'main']
