"""``scene-synth evaluate``: the paper's evaluation of synthesized rooms, written as a
report (``index.md``, ``results.json``, figures) and summarised in the terminal. With
``--data``, the evaluation against an imported data set's held-out rooms instead
(``evaluation.dataset``)."""
from __future__ import annotations

import json
from pathlib import Path

from ..categories import ROOM_TYPES
from .common import WEIGHTS_DIR_HELP, UserError, room_types


def add_parser(sub) -> None:
    c = sub.add_parser('evaluate', help="the paper's evaluation of synthesized rooms: "
                       'category KL, real-vs-synthetic classifier, speed, physical '
                       'plausibility, similarity to the training rooms, component metrics')
    c.add_argument('--room-type', default='all', help=f'{"|".join(ROOM_TYPES)}|all; with '
                   '--data, a room type of the data set or all')
    c.add_argument('--out', default='report', help='directory for index.md, results.json '
                   'and the figures')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--quick', action='store_true', help='tiny sizes: a smoke test of the '
                   'whole run, not a measurement')
    c.add_argument('--workers', type=int, default=None, help='processes of one torch thread '
                   'each (default: all cores)')
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.add_argument('--quiet', action='store_true', help='no progress bars or stage lines')
    c.add_argument('--markdown', help='also write the report here (its figure links point '
                   'into --out), e.g. docs/evaluation.md')
    c.add_argument('--report-only', action='store_true', help='measure nothing: write the '
                   'report again from --out/results.json of an earlier run')
    c.add_argument('--data', help='an imported data set (the --out of scene-synth import): '
                   'compare with its rooms that training held out, their empty shells '
                   'furnished by --weights-dir (the weights trained on it)')
    c.add_argument('--rooms-per-shell', type=int, default=None, help='with --data: '
                   'synthesized rooms per held-out shell (default 4)')
    c.set_defaults(func=cmd_evaluate)


def cmd_evaluate(args) -> int:
    return _report_only(args) if args.report_only else _evaluate(args)


def _report_only(args) -> int:
    from ..evaluation import dataset_report, report
    path = Path(args.out) / 'results.json'
    try:
        results = json.loads(path.read_text(encoding='utf-8'))
        # A data-set evaluation's results have their own report.
        kind = dataset_report if results.get('mode') == 'dataset' else report
        kind.write(results, Path(args.out), Path(args.markdown) if args.markdown else None)
    except FileNotFoundError:
        raise UserError(f'{path}: no such file; run the evaluation first') from None
    except (ValueError, KeyError, TypeError, AttributeError) as e:
        raise UserError(f'{path} is not the results of an evaluation ({e})') from None
    print(kind.terminal_summary(results))
    print(f'\nwrote {Path(args.out) / "index.md"} from {path}')
    return 0


def _command(args) -> str:
    """The command line the report quotes: what reproduces its numbers."""
    return ' '.join(['scene-synth evaluate', '--room-type', args.room_type, '--out',
                     args.out, '--seed', str(args.seed)]
                    + (['--quick'] if args.quick else [])
                    + (['--markdown', args.markdown] if args.markdown else []))


def _workers(args) -> int:
    import os
    if args.workers is not None and args.workers < 1:
        raise UserError(f'--workers must be at least 1, got {args.workers}')
    return args.workers or os.cpu_count() or 1


def _evaluate(args) -> int:
    if args.data:
        return _evaluate_data(args)
    if args.rooms_per_shell is not None:
        raise UserError('--rooms-per-shell needs --data: the paper-corpus evaluation '
                        'furnishes each held-out shell once')
    from ..evaluation.report import terminal_summary
    from ..evaluation.run import EvalConfig, run_evaluation
    rts = room_types(args.room_type, args.vocabulary)
    own = [rt for rt in rts if args.vocabulary.defines(rt)]
    if own:
        raise UserError(f'the {own[0]} weights were trained on an imported data set, not '
                        f'on the procedural corpus: evaluate them with --data (that data set)')
    workers = _workers(args)
    cfg = EvalConfig.quick(args.seed) if args.quick else EvalConfig(seed=args.seed)
    results = run_evaluation(rts, cfg, args.out, workers,
                             args.weights_dir, progress=not args.quiet,
                             echo=(lambda s: None) if args.quiet else print,
                             command=_command(args), markdown_copy=args.markdown)
    print()
    print(terminal_summary(results))
    print(f'\nwrote {Path(args.out) / "index.md"} ({results["seconds"] / 60:.1f} min)')
    return 0


def _data_command(args, k: int) -> str:
    """The command line the data-set report quotes."""
    return ' '.join(['scene-synth evaluate', '--data', args.data, '--weights-dir',
                     args.weights_dir, '--room-type', args.room_type, '--rooms-per-shell',
                     str(k), '--seed', str(args.seed), '--out', args.out]
                    + (['--markdown', args.markdown] if args.markdown else []))


def _evaluate_data(args) -> int:
    from ..evaluation.dataset import DataEvalConfig, run_data_evaluation
    from ..evaluation.dataset_report import terminal_summary
    if not args.weights_dir:
        raise UserError('--data needs --weights-dir: the weights trained on that data set '
                        '(scene-synth train --data DIR --weights-dir W)')
    if args.quick:
        raise UserError('--quick has no meaning with --data: the held-out rooms and '
                        '--rooms-per-shell are the sizes')
    k = 4 if args.rooms_per_shell is None else args.rooms_per_shell
    cfg = DataEvalConfig(rooms_per_shell=k, seed=args.seed)
    results = run_data_evaluation(args.data, args.weights_dir, args.room_type, cfg, args.out,
                                  _workers(args), progress=not args.quiet,
                                  echo=(lambda s: None) if args.quiet else print,
                                  command=_data_command(args, k),
                                  markdown_copy=args.markdown)
    print()
    print(terminal_summary(results))
    print(f'\nwrote {Path(args.out) / "index.md"} ({results["seconds"] / 60:.1f} min)')
    return 0
