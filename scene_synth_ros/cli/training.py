"""``scene-synth train`` and ``components``: training the four networks of a room type into
a weights bundle, and the paper's component table of trained bundles."""
from __future__ import annotations

from pathlib import Path

from ..categories import CORPUS
from .common import WEIGHTS_DIR_HELP, UserError, room_types


def add_parser(sub) -> None:
    c = sub.add_parser('train', help='train the four networks of a room type (resumable)')
    c.add_argument('--room-type', default='all', help='a room type (bedroom, living, office, '
                   'bathroom, kitchen, dining, hallway), a comma list of them, or all')
    c.add_argument('--config', help='model and training configuration (YAML; default: '
                   'config/compact.yaml)')
    c.add_argument('--device', choices=('cpu', 'cuda', 'auto'), help='overrides the config')
    c.add_argument('--threads', type=int, help='torch threads (default: the config; 0 = all)')
    c.add_argument('--loader-workers', type=int, help='processes making the batches ahead of '
                   'each step (default: the config; 0 = none; the weights do not change)')
    c.add_argument('--run-dir', help='checkpoints and logs (default: runs/<config name>); '
                   'an interrupted run started again with the same directory resumes')
    c.add_argument('--weights-dir', help='where the trained bundles go (default: the '
                   "package's weights/)")
    c.add_argument('--modules', help='comma-separated subset of category, location, '
                   'orientation, snap, dimensions to train (no export); several processes '
                   'may train different modules of one room type at once')
    c.add_argument('--others-from', help='with --modules: take the other modules from the '
                   'bundles in this directory (same model configuration, e.g. the shipped '
                   'weights) and export')
    c.add_argument('--data', help='an imported data set (the --out of scene-synth import): '
                   'train its room types (all of them by default) on its rooms; the bundles '
                   'carry its category sets')
    c.add_argument('--jobs', type=int, help='train the modules of the room types in this many '
                   'processes side by side (one torch thread each unless --threads), each '
                   'bundle exported when its modules are done, progress as time-stamped lines; '
                   'what `make weights` runs')
    c.add_argument('--quiet', action='store_true', help='no progress bars')
    # training writes into --weights-dir: the vocabulary is the data set's (or the paper's),
    # not that of the old bundles there
    c.set_defaults(func=cmd_train, defines_room_types=False)

    c = sub.add_parser('components', help="the paper's component table of trained weights, "
                       'beside randomly initialised networks (held-out corpus rooms)')
    c.add_argument('--room-type', default='all', help='a room type of the weights, or all')
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.add_argument('--markdown', action='store_true', help='a Markdown table')
    c.set_defaults(func=cmd_components)


def _pipeline_config(path: str | None, device: str | None = None):
    """The configuration in ``path`` (default: the shipped one); every error names the file,
    which the parser's own messages do not."""
    from ..networks.config import PipelineConfig
    from ..paths import default_config_path
    path = path or str(default_config_path())
    try:
        cfg = PipelineConfig.from_yaml(path)
    except FileNotFoundError:
        raise UserError(f'{path}: no such configuration file') from None
    except (ValueError, TypeError) as e:
        raise UserError(f'{path}: {e}') from None
    except Exception as e:  # a YAML syntax error names its own line
        raise UserError(f'{path}: not valid YAML ({str(e).splitlines()[0]})') from None
    if device:
        cfg.device = device
    return cfg


def cmd_train(args) -> int:
    from ..networks.config import resolve_device
    from ..networks.train import train
    from ..paths import weights_dir
    cfg = _pipeline_config(args.config, args.device)
    if args.jobs is not None:
        if args.jobs < 1:
            raise UserError(f'--jobs {args.jobs}: expected 1 or more processes')
        if args.modules or args.others_from:
            raise UserError('--jobs trains every module of each room type and exports the '
                            'bundles; leave out --modules and --others-from')
        cfg.train.threads = 1
    if args.threads is not None:
        cfg.train.threads = args.threads
    if args.loader_workers is not None:
        if args.loader_workers < 0:
            raise UserError(f'--loader-workers {args.loader_workers}: expected 0 or more')
        cfg.train.loader_workers = args.loader_workers
    try:
        resolve_device(cfg.device)
    except ValueError as e:     # a plain ValueError, which main() does not catch
        raise UserError(str(e)) from None
    run_root = Path(args.run_dir or f'runs/{cfg.name}')
    out = Path(args.weights_dir) if args.weights_dir else weights_dir()
    data = None
    if args.data:
        from ..datasets.training import describe_dir, room_type_specs
        if not args.weights_dir:
            raise UserError('--data needs --weights-dir: weights of an imported data set do '
                            "not replace the package's own")
        data = Path(args.data)
        known = list(room_type_specs(describe_dir(data)))
        types = known if args.room_type == 'all' else \
            [part.strip().lower() for part in args.room_type.split(',')]
    else:
        # the corpus's room types: the rooms of a home whose weights are to come too
        types = list(dict.fromkeys(rt for part in args.room_type.split(',')
                                   for rt in room_types(part.strip(), CORPUS)))
    if args.jobs is not None:
        from ..networks.jobs import train_side_by_side
        try:
            train_side_by_side(types, cfg, run_root, out, args.jobs, data_dir=data)
        except ValueError as e:
            raise UserError(str(e)) from None
        return 0
    print(f'training {", ".join(types)} with the {cfg.name} '
          f'configuration; checkpoints and logs in {run_root}, weights to {out}')
    modules = tuple(m.strip() for m in args.modules.split(',')) if args.modules else None
    if args.others_from and not modules:
        raise UserError('--others-from needs --modules: the modules to train')
    try:
        train(types, cfg, run_root, out, progress=not args.quiet,
              **({'modules': modules} if modules else {}),
              others_from=Path(args.others_from) if args.others_from else None, data_dir=data)
    except ValueError as e:     # bad arguments, refused with plain ValueErrors
        raise UserError(str(e)) from None
    return 0


def cmd_components(args) -> int:
    from ..networks.bundle import bundle_path, load_bundle
    from ..networks.train import format_components
    from ..paths import weights_dir
    tables = {}
    for rt in room_types(args.room_type, args.vocabulary):
        path = bundle_path(args.weights_dir or weights_dir(), rt, args.vocabulary)
        b = load_bundle(path)
        if 'components' not in b.metrics:
            raise UserError(f'{path}: the bundle carries no component metrics')
        tables[rt] = b.metrics['components']
    print(format_components(tables, markdown=args.markdown))
    return 0
