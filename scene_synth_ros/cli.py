"""The ``scene-synth`` command line. A thin adapter over the library: no ROS import here."""
from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
import sys
import time

from .categories import ROOM_TYPES, resolve_room_type
from .errors import SceneSynthError

EXIT_BAD_INPUT = 2


class UserError(SceneSynthError):
    """Bad input from the user: printed as one sentence, exit code 2, no traceback."""


def _room_types(value: str) -> list[str]:
    if value == 'all':
        return list(ROOM_TYPES)
    return [resolve_room_type(value)]


def _load(path: str):
    from .schema import SceneValidationError, load_scene
    try:
        return load_scene(path)
    except FileNotFoundError:
        raise UserError(f'{path}: no such file') from None
    except SceneValidationError as e:
        raise UserError(f'{path}: {e}') from None


# ---- corpus ------------------------------------------------------------------------------
def cmd_corpus(args) -> int:
    from tqdm import tqdm

    from .corpus.generate import generate_corpus
    from .schema import save_scene
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for rt in _room_types(args.room_type):
        t0 = time.perf_counter()
        rooms = generate_corpus(rt, args.n, seed=args.seed, workers=args.workers)
        for i, scene in enumerate(tqdm(rooms, total=args.n, desc=rt, unit='room',
                                       disable=args.quiet)):
            save_scene(scene, out / f'{rt}_{i:05d}.json')
        if not args.quiet:
            print(f'{rt}: {args.n} rooms in {time.perf_counter() - t0:.1f} s -> {out}')
    return 0


def cmd_corpus_stats(args) -> int:
    from .corpus.generate import generate_corpus
    from .corpus.stats import collect
    rows = []
    for rt in _room_types(args.room_type):
        if args.dir:
            files = sorted(Path(args.dir).glob(f'{rt}_*.json'))
            if not files:
                raise UserError(f'{args.dir}: no {rt}_*.json scene files')
            scenes = (_load(str(f)) for f in files)
        else:
            scenes = generate_corpus(rt, args.n, seed=args.seed, workers=args.workers)
        stats = collect(rt, scenes)
        rows.append(stats.summary_row())
        if args.categories:
            print(f'\n{rt}: objects per room, corpus vs. the paper\'s table')
            for name, here, table in stats.category_table():
                print(f'  {name:16s} {here:7.3f} {table:7.3f}')
    print()
    print(f'{"room type":10s} {"rooms":>6s} {"KL(c||t)":>9s} {"KL(t||c)":>9s} '
          f'{"obj/room":>9s} {"table":>6s} {"diff":>7s} {"doors":>6s} {"table":>6s} '
          f'{"windows":>7s} {"table":>6s} {"L-shaped":>8s} {"invalid":>7s}')
    for r in rows:
        diff = r['objects_per_room'] / r['table_objects_per_room'] - 1
        print(f'{r["room_type"]:10s} {r["rooms"]:6d} {r["kl_corpus_table"]:9.4f} '
              f'{r["kl_table_corpus"]:9.4f} {r["objects_per_room"]:9.2f} '
              f'{r["table_objects_per_room"]:6.2f} {diff:+7.1%} {r["doors_per_room"]:6.2f} '
              f'{r["table_doors_per_room"]:6.2f} {r["windows_per_room"]:7.2f} '
              f'{r["table_windows_per_room"]:6.2f} {r["l_shaped_fraction"]:8.1%} '
              f'{r["invalid_rooms"]:7d}')
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1) + '\n')
    return 0


def cmd_corpus_calibrate(args) -> int:
    from .corpus.calibrate import calibrate
    calibrate(rooms=args.rooms, iterations=args.iterations, seed=args.seed,
              room_types=_room_types(args.room_type), workers=args.workers)
    return 0


# ---- pictures ----------------------------------------------------------------------------
def cmd_render(args) -> int:
    scene = _load(args.scene)
    if not (args.png or args.channels):
        raise UserError('render needs --png and/or --channels to know what to write')
    if args.png:
        from .plot import save_png
        save_png(scene, args.png, title=args.title or Path(args.scene).stem)
        print(f'wrote {args.png}')
    if args.channels:
        import numpy as np

        from .render import TopDownRenderer
        try:
            image = TopDownRenderer(args.resolution).render(scene)
        except ValueError as e:
            raise UserError(f'{args.scene}: {e}') from None
        np.save(args.channels, image)
        print(f'wrote {args.channels}: {image.shape[0]} channels of '
              f'{image.shape[1]}x{image.shape[2]} px')
    return 0


def _corpus_rooms(seed: int, per_type: int):
    """(name, scene) for the first ``per_type`` corpus rooms of every room type."""
    from .corpus.generate import generate_room
    for rt in ROOM_TYPES:
        for i in range(per_type):
            yield f'{rt}_{i}', generate_room(rt, seed, i)


def cmd_gallery(args) -> int:
    from .plot import save_grid
    scenes, titles = [], []
    ncols = args.per_type
    if args.source == 'corpus':
        for name, s in _corpus_rooms(args.seed, args.per_type):
            scenes.append(s)
            titles.append(f'{name.replace("_", " #")} (seed {args.seed})')
    elif args.source == 'synthesized':
        from .corpus.generate import empty_room
        synth = _synthesizer(args)
        for rt in ROOM_TYPES:
            for i in range(args.per_type):
                room = empty_room(rt, SHELL_SEED, i)
                scenes.append(_run_synthesis(synth.generate, room, args.seed + i).scene)
                titles.append(f'{rt} #{i} (seed {args.seed + i})')
    else:
        from .paths import examples_dir
        synth = _synthesizer(args)
        partial = _load(args.partial or str(examples_dir() / 'partial_bedroom.json'))
        scenes.append(partial)
        titles.append(f'partial room ({len(partial)} objects)')
        for i in range(args.per_type * 2 - 1):
            scenes.append(_run_synthesis(synth.complete, partial, args.seed + i).scene)
            titles.append(f'completion, seed {args.seed + i}')
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    save_grid(scenes, out, ncols=ncols, titles=titles)
    print(f'wrote {out}')
    return 0


def cmd_demo(args) -> int:
    """The main job: furnish the example layouts, complete the example partial room and
    furnish empty rooms of every type with the trained pipeline, then show them (JSON, one
    picture each, a contact sheet, a table in the terminal)."""
    from .corpus.generate import empty_room
    from .geometry import check_scene
    from .paths import examples_dir
    from .plot import save_grid, save_png
    from .scene import Scene
    from .schema import save_scene
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    synth = _synthesizer(args)
    jobs = []
    for f in ('bedroom_layout.json', 'lshaped_living_layout.json'):
        jobs.append((Path(f).stem, 'generate', _load(str(examples_dir() / f))))
    jobs.append(('partial_bedroom_completed', 'complete',
                 _load(str(examples_dir() / 'partial_bedroom.json'))))
    for rt in ROOM_TYPES:
        for i in range(args.per_type):
            jobs.append((f'{rt}_{i}', 'generate', Scene(empty_room(rt, SHELL_SEED, i), [])))
    scenes, titles = [], []
    print(f'{"room":26s} {"floor":>8s} {"kept":>4s} {"added":>5s} {"seconds":>7s} '
          f'{"valid":>5s}  categories added')
    for k, (name, mode, scene) in enumerate(jobs):
        seed = args.seed + k
        fn = synth.generate if mode == 'generate' else synth.complete
        result = _run_synthesis(fn, scene, seed)
        s = result.scene
        save_scene(s, out / f'{name}.json')
        save_png(s, out / f'{name}.png', title=f'{name} (seed {seed})')
        scenes.append(s)
        titles.append(f'{name} (seed {seed})')
        added: dict[str, int] = {}
        for o in result.added:
            added[o.category] = added.get(o.category, 0) + 1
        cats = ', '.join(f'{n}x {c}' if n > 1 else c for c, n in added.items())
        kept = len(s) - len(result.added)
        print(f'{name:26s} {s.room.area:6.1f}m2 {kept:4d} {len(result.added):5d} '
              f'{result.seconds:7.2f} {"yes" if check_scene(s).ok else "NO":>5s}  {cats}')
    save_grid(scenes, out / 'gallery.png', ncols=3, titles=titles)
    print(f'\nwrote {len(scenes)} scenes (JSON + PNG) and {out / "gallery.png"}')
    return 0


# ---- catalog & validation ----------------------------------------------------------------
def cmd_catalog(args) -> int:
    from . import catalog
    if args.action == 'list':
        for v in catalog.all_variants():
            w, d, h = v.size
            print(f'{v.model_id:20s} {v.category:16s} {w:6.3f} x {d:6.3f} x {h:6.3f} m')
        return 0
    from .meshes import export_catalog, save_contact_sheet
    if args.action == 'export':
        cats = [c.strip() for c in args.categories.split(',')] if args.categories else None
        paths = export_catalog(args.out, fmt=args.format, categories=cats)
        print(f'wrote {len(paths)} {args.format} models to {args.out}')
    else:
        save_contact_sheet(args.out)
        print(f'wrote {args.out}')
    return 0


def cmd_validate(args) -> int:
    from .geometry import check_scene
    for path in args.files:
        scene = _load(path)
        report = check_scene(scene)
        print(f'{path}: schema OK, {len(scene)} objects, physically {report.summary()}')
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog='scene-synth', description=__doc__.splitlines()[0])
    sub = p.add_subparsers(dest='command', required=True)

    c = sub.add_parser('corpus', help='generate procedural furnished rooms as JSON scenes')
    c.add_argument('--room-type', default='bedroom', help=f'{"|".join(ROOM_TYPES)}|all')
    c.add_argument('-n', type=int, default=100, help='rooms per room type')
    c.add_argument('--out', required=True, help='output directory')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--workers', type=int, default=None, help='processes (default: all cores)')
    c.add_argument('--quiet', action='store_true')
    c.set_defaults(func=cmd_corpus)

    c = sub.add_parser('corpus-stats', help="compare the corpus with the paper's table")
    c.add_argument('--room-type', default='all')
    c.add_argument('-n', type=int, default=2000, help='rooms per type to generate')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--dir', help='read scenes from this directory instead of generating')
    c.add_argument('--workers', type=int, default=None)
    c.add_argument('--categories', action='store_true', help='print per-category rates')
    c.add_argument('--json', help='also write the summary rows to this JSON file')
    c.set_defaults(func=cmd_corpus_stats)

    c = sub.add_parser('corpus-calibrate', help="fit the corpus' request-rate factors")
    c.add_argument('--room-type', default='all')
    c.add_argument('--rooms', type=int, default=2000)
    c.add_argument('--iterations', type=int, default=3)
    c.add_argument('--seed', type=int, default=12345)
    c.add_argument('--workers', type=int, default=None)
    c.set_defaults(func=cmd_corpus_calibrate)

    c = sub.add_parser('render', help='draw a scene JSON as a top-down picture')
    c.add_argument('scene')
    c.add_argument('--png', help='picture for people (matplotlib)')
    c.add_argument('--channels', help="the network input image as a .npy (C x N x N)")
    c.add_argument('--resolution', type=int, default=64)
    c.add_argument('--title')
    c.set_defaults(func=cmd_render)

    c = sub.add_parser('gallery', help='a grid of corpus rooms, synthesized rooms (one row '
                       'per room type) or completions of one partial room')
    c.add_argument('--source', choices=('corpus', 'synthesized', 'completions'),
                   default='corpus')
    c.add_argument('--out', default='docs/gallery/corpus.png')
    c.add_argument('--per-type', type=int, default=3, help='columns of the grid')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--partial', help='completions: the partial room (default: '
                   'examples/partial_bedroom.json)')
    c.add_argument('--weights-dir', help="trained bundles (default: the package's weights/)")
    c.set_defaults(func=cmd_gallery)

    c = sub.add_parser('demo', help='furnish example rooms with the pipeline and show them')
    c.add_argument('--out', default='demo_out')
    c.add_argument('--per-type', type=int, default=1, help='empty rooms per room type')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--weights-dir', help="trained bundles (default: the package's weights/)")
    c.set_defaults(func=cmd_demo)

    c = sub.add_parser('catalog', help='list, export or preview the 3D model catalog')
    c.add_argument('action', choices=['list', 'export', 'preview'])
    c.add_argument('--out', default='catalog_out')
    c.add_argument('--format', choices=['glb', 'obj'], default='glb')
    c.add_argument('--categories', help='comma-separated categories (default: all)')
    c.set_defaults(func=cmd_catalog)

    c = sub.add_parser('generate', help='furnish an empty room with the trained pipeline')
    c.add_argument('--room-type', default='bedroom', help=f'{"|".join(ROOM_TYPES)}')
    c.add_argument('--layout', help='a room layout JSON (default: a corpus-like empty room '
                   'drawn from the seed)')
    _synthesis_options(c)
    c.set_defaults(func=cmd_generate)

    c = sub.add_parser('complete', help='add the missing objects to a partial room')
    c.add_argument('scene', help='a room layout or scene JSON with the objects to keep')
    _synthesis_options(c)
    c.set_defaults(func=cmd_complete)

    c = sub.add_parser('suggest', help='propose k distinct next objects for a room')
    c.add_argument('scene', help='a room layout or scene JSON')
    c.add_argument('-k', type=int, default=5, help='number of proposals')
    _synthesis_options(c, out=False)
    c.add_argument('--out', help='write the proposals (JSON list of objects) here')
    c.set_defaults(func=cmd_suggest)

    c = sub.add_parser('export', help='write a scene as a Gazebo SDF world and/or one glTF')
    c.add_argument('scene', help='a scene JSON')
    c.add_argument('--sdf', help='the world file to write')
    c.add_argument('--mesh-dir', help='where the SDF\'s OBJ meshes go (default: '
                   '<world>_meshes/ beside it)')
    c.add_argument('--gltf', help='the binary glTF (.glb) to write')
    c.set_defaults(func=cmd_export)

    c = sub.add_parser('train', help='train the four networks of a room type (resumable)')
    c.add_argument('--room-type', default='all', help='bedroom, living, office, bathroom or all')
    c.add_argument('--config', help='model and training configuration (YAML; default: '
                   'config/compact.yaml)')
    c.add_argument('--device', choices=('cpu', 'cuda', 'auto'), help='overrides the config')
    c.add_argument('--threads', type=int, help='torch threads (default: the config; 0 = all)')
    c.add_argument('--run-dir', help='checkpoints and logs (default: runs/<config name>); '
                   'an interrupted run started again with the same directory resumes')
    c.add_argument('--weights-dir', help='where the trained bundles go (default: the '
                   "package's weights/)")
    c.add_argument('--modules', help='comma-separated subset of category, location, '
                   'orientation, snap, dimensions to train (no export); several processes '
                   'may train different modules of one room type at once')
    c.add_argument('--quiet', action='store_true', help='no progress bars')
    c.set_defaults(func=cmd_train)

    c = sub.add_parser('components', help="the paper's component table of trained weights, "
                       'beside randomly initialised networks (held-out corpus rooms)')
    c.add_argument('--room-type', default='all')
    c.add_argument('--weights-dir', help="trained bundles (default: the package's weights/)")
    c.add_argument('--markdown', action='store_true', help='a Markdown table')
    c.set_defaults(func=cmd_components)

    c = sub.add_parser('validate', help='check scene JSON files: schema and physics')
    c.add_argument('files', nargs='+')
    c.set_defaults(func=cmd_validate)

    c = sub.add_parser('evaluate', help="the paper's evaluation of synthesized rooms: "
                       'category KL, real-vs-synthetic classifier, speed, physical '
                       'plausibility, similarity to the training rooms, component metrics')
    c.add_argument('--room-type', default='all', help=f'{"|".join(ROOM_TYPES)}|all')
    c.add_argument('--out', default='report', help='directory for index.md, results.json '
                   'and the figures')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--quick', action='store_true', help='tiny sizes: a smoke test of the '
                   'whole run, not a measurement')
    c.add_argument('--workers', type=int, default=None, help='processes of one torch thread '
                   'each (default: all cores)')
    c.add_argument('--weights-dir', help="trained bundles (default: the package's weights/)")
    c.add_argument('--quiet', action='store_true', help='no progress bars or stage lines')
    c.add_argument('--markdown', help='also write the report here (its figure links point '
                   'into --out), e.g. docs/evaluation.md')
    c.add_argument('--report-only', action='store_true', help='measure nothing: write the '
                   'report again from --out/results.json of an earlier run')
    c.set_defaults(func=cmd_evaluate)

    from .ros_cli import add_parser as add_ros_parser
    add_ros_parser(sub)
    return p


# ---- synthesis ---------------------------------------------------------------------------
SHELL_SEED = 1   # galleries furnish the shells of corpus rooms that training never saw

def _synthesizer(args):
    from .synth import SynthConfig, Synthesizer, SynthesisError
    cfg = SynthConfig()
    if getattr(args, 'temperature', None) is not None:
        if not args.temperature > 0:
            raise UserError(f'--temperature must be positive, got {args.temperature}')
        cfg.location_temperature = args.temperature
    if getattr(args, 'max_objects', None) is not None:
        if args.max_objects < 1:
            raise UserError(f'--max-objects must be at least 1, got {args.max_objects}')
        cfg.max_objects = args.max_objects
    if getattr(args, 'device', None):
        cfg.device = args.device
    try:
        return Synthesizer(getattr(args, 'weights_dir', None), cfg)
    except SynthesisError as e:
        raise UserError(str(e)) from None


def _run_synthesis(fn, *a):
    from .networks.bundle import BundleError
    from .synth import SynthesisError
    try:
        return fn(*a)
    except (BundleError, SynthesisError) as e:
        raise UserError(str(e)) from None


def _object_table(objects, title: str = '') -> str:
    lines = [title] if title else []
    lines.append(f'  {"id":18s} {"category":16s} {"model":18s} {"x":>6s} {"y":>6s} {"z":>5s} '
                 f'{"yaw°":>6s} {"w x d x h (m)":>17s}  on')
    for o in objects:
        lines.append(f'  {o.id:18s} {o.category:16s} {o.model_id:18s} {o.position[0]:6.2f} '
                     f'{o.position[1]:6.2f} {o.position[2]:5.2f} '
                     f'{math.degrees(o.yaw):6.1f} {o.width:5.2f}x{o.depth:4.2f}x{o.height:4.2f}'
                     f'  {o.support or ""}')
    return '\n'.join(lines)


def _timing_line(result) -> str:
    parts = ', '.join(f'{k} {v * 1000:.0f}' for k, v in result.timings.items())
    return (f'{len(result.added)} objects added in {result.seconds:.3f} s (stopped: '
            f'{result.stopped}); ms per module: {parts}')


def _write_outputs(scene, args, title: str) -> None:
    from .schema import save_scene
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        save_scene(scene, args.out)
        print(f'wrote {args.out}')
    if args.png:
        from .plot import save_png
        Path(args.png).parent.mkdir(parents=True, exist_ok=True)
        save_png(scene, args.png, title=title)
        print(f'wrote {args.png}')


def cmd_generate(args) -> int:
    from .geometry import check_scene
    synth = _synthesizer(args)
    if args.layout:
        room = _load(args.layout).room
        title = f'{Path(args.layout).stem} (seed {args.seed})'
    else:
        from .corpus.generate import empty_room
        rt = _room_types(args.room_type)
        if len(rt) != 1:
            raise UserError('generate furnishes one room: give one --room-type, not all')
        room = empty_room(rt[0], args.seed)
        title = f'{rt[0]} (seed {args.seed})'
    result = _run_synthesis(synth.generate, room, args.seed)
    print(_object_table(result.scene.objects, f'{room.room_type}, {room.area:.1f} m2:'))
    print(_timing_line(result))
    print(f'physical check: {check_scene(result.scene).summary()}')
    _write_outputs(result.scene, args, title)
    return 0


def cmd_complete(args) -> int:
    from .geometry import check_scene
    synth = _synthesizer(args)
    scene = _load(args.scene)
    result = _run_synthesis(synth.complete, scene, args.seed)
    print(_object_table(scene.objects, f'kept ({len(scene.objects)}):'))
    print(_object_table(result.added, f'added ({len(result.added)}):'))
    print(_timing_line(result))
    print(f'physical check: {check_scene(result.scene).summary()}')
    _write_outputs(result.scene, args, f'{Path(args.scene).stem} completed (seed {args.seed})')
    return 0


def cmd_suggest(args) -> int:
    if args.k < 1:
        raise UserError(f'-k must be at least 1, got {args.k}')
    synth = _synthesizer(args)
    scene = _load(args.scene)
    found = _run_synthesis(synth.suggest, scene, args.k, args.seed)
    print(_object_table(found, f'{len(found)} proposals for the next object of '
                               f'{Path(args.scene).name}:'))
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text(json.dumps([o.to_dict() for o in found], indent=2) + '\n')
        print(f'wrote {args.out}')
    if args.png:
        from .plot import save_grid
        from .scene import Scene
        shown = [Scene(scene.room, scene.objects + [o]) for o in found]
        save_grid(shown, args.png, ncols=min(len(shown), 3) or 1,
                  titles=[f'+ {o.category}' for o in found])
        print(f'wrote {args.png}')
    return 0


def _synthesis_options(c, out: bool = True) -> None:
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--temperature', type=float, help='location temperature (default 0.8)')
    c.add_argument('--max-objects', type=int, help='cap on objects in the room (default 30)')
    c.add_argument('--weights-dir', help="trained bundles (default: the package's weights/)")
    c.add_argument('--device', choices=('cpu', 'cuda', 'auto'))
    if out:
        c.add_argument('--out', help='write the scene JSON here')
    c.add_argument('--png', help='write a top-down picture here')


def cmd_export(args) -> int:
    from .export import export_gltf, export_sdf
    scene = _load(args.scene)
    if not (args.sdf or args.gltf):
        raise UserError('export needs --sdf and/or --gltf to know what to write')
    if args.sdf:
        export_sdf(scene, args.sdf, args.mesh_dir)
        print(f'wrote {args.sdf} ({len(scene.objects)} objects)')
    if args.gltf:
        export_gltf(scene, args.gltf)
        print(f'wrote {args.gltf}')
    return 0


# ---- training ----------------------------------------------------------------------------
def _pipeline_config(path: str | None, device: str | None = None):
    from .networks.config import PipelineConfig
    from .paths import default_config_path
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
    from .networks.config import resolve_device
    from .networks.train import train
    from .paths import weights_dir
    cfg = _pipeline_config(args.config, args.device)
    if args.threads is not None:
        cfg.train.threads = args.threads
    try:
        resolve_device(cfg.device)
    except ValueError as e:
        raise UserError(str(e)) from None
    run_root = Path(args.run_dir or f'runs/{cfg.name}')
    out = Path(args.weights_dir) if args.weights_dir else weights_dir()
    print(f'training {", ".join(_room_types(args.room_type))} with the {cfg.name} '
          f'configuration; checkpoints and logs in {run_root}, weights to {out}')
    modules = tuple(m.strip() for m in args.modules.split(',')) if args.modules else None
    try:
        train(_room_types(args.room_type), cfg, run_root, out, progress=not args.quiet,
              **({'modules': modules} if modules else {}))
    except ValueError as e:
        raise UserError(str(e)) from None
    return 0


def cmd_components(args) -> int:
    from .networks.bundle import BundleError, bundle_path, load_bundle
    from .networks.train import format_components
    from .paths import weights_dir
    tables = {}
    for rt in _room_types(args.room_type):
        path = bundle_path(args.weights_dir or weights_dir(), rt)
        try:
            b = load_bundle(path)
        except BundleError as e:
            raise UserError(str(e)) from None
        if 'components' not in b.metrics:
            raise UserError(f'{path}: the bundle carries no component metrics')
        tables[rt] = b.metrics['components']
    print(format_components(tables, markdown=args.markdown))
    return 0


def cmd_evaluate(args) -> int:
    import os

    from .evaluation.report import terminal_summary, write
    from .evaluation.run import EvalConfig, EvaluationError, run_evaluation
    if args.report_only:
        path = Path(args.out) / 'results.json'
        try:
            results = json.loads(path.read_text(encoding='utf-8'))
            write(results, Path(args.out), Path(args.markdown) if args.markdown else None)
        except FileNotFoundError:
            raise UserError(f'{path}: no such file; run the evaluation first') from None
        except (ValueError, KeyError, TypeError) as e:
            raise UserError(f'{path} is not the results of an evaluation ({e})') from None
        print(terminal_summary(results))
        print(f'\nwrote {Path(args.out) / "index.md"} from {path}')
        return 0
    room_types = _room_types(args.room_type)
    if args.workers is not None and args.workers < 1:
        raise UserError(f'--workers must be at least 1, got {args.workers}')
    cfg = EvalConfig.quick(args.seed) if args.quick else EvalConfig(seed=args.seed)
    command = ' '.join(['scene-synth evaluate', '--room-type', args.room_type, '--out',
                        args.out, '--seed', str(args.seed)]
                       + (['--quick'] if args.quick else [])
                       + (['--markdown', args.markdown] if args.markdown else []))
    try:
        results = run_evaluation(room_types, cfg, args.out, args.workers or os.cpu_count() or 1,
                                 args.weights_dir, progress=not args.quiet,
                                 echo=(lambda s: None) if args.quiet else print,
                                 command=command, markdown_copy=args.markdown)
    except EvaluationError as e:
        raise UserError(str(e)) from None
    print()
    print(terminal_summary(results))
    print(f'\nwrote {Path(args.out) / "index.md"} ({results["seconds"] / 60:.1f} min)')
    return 0


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except SceneSynthError as e:
        print(f'scene-synth: {e}', file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        return 130


if __name__ == '__main__':
    # Through the package's module, so ``python -m`` and the console script share one
    # UserError class with the subcommand modules that import it.
    from scene_synth_ros.cli import main as _main
    sys.exit(_main())
