"""``scene-synth generate``, ``complete``, ``suggest``, ``gallery`` and ``demo``: rooms
furnished by the trained pipeline, printed as tables and written as JSON and pictures."""
from __future__ import annotations

import json
from pathlib import Path

from ..categories import ROOM_TYPES
from ..corpus import HELDOUT_SEED
from ..errors import quoted
from ..synth_config import SynthConfig, flag_settings
from .common import (
    WEIGHTS_DIR_HELP,
    UserError,
    flag_value,
    load_catalog,
    load_layout_file,
    load_scene_file,
    object_table,
    robot_from,
    robot_options,
    room_types,
    setting_flag,
    write_scene,
)

# The flags of the synthesis settings (the robot's: ``robot_options``).
_SETTING_FLAGS = flag_settings()


def add_parser(sub) -> None:
    c = sub.add_parser('generate', help='furnish an empty room, or a batch of rooms',
                       description='Furnish an empty room: a layout file, or a corpus-like '
                       'empty room drawn from the seed. The same seed gives the same room. '
                       'With -n or --layouts, furnish a batch of rooms into a directory.')
    c.add_argument('--room-type', default='bedroom', help=f'{"|".join(ROOM_TYPES)}')
    c.add_argument('--layout', help='a room or house layout JSON (default: a corpus-like '
                   'empty room drawn from the seed)')
    c.add_argument('--houses', action='store_true', help='with -n: whole houses, procedural '
                   'house plan i of the seed furnished with seed --seed + i (--lockstep 1 '
                   'unless given: the rooms of each house are in lockstep)')
    _synthesis_options(c, batch=True)
    _batch_options(c, layouts=True)
    c.set_defaults(func=cmd_generate)

    c = sub.add_parser('complete', help='add the missing objects to a partial room',
                       description='Keep the objects of a partial room and furnish the rest. '
                       'A directory or JSON-lines file of partial rooms is a batch.')
    c.add_argument('scene', help='a room layout or scene JSON with the objects to keep (a '
                   'directory of them, or a JSON-lines file: a batch)')
    _synthesis_options(c, batch=True)
    _batch_options(c, layouts=False)
    c.set_defaults(func=cmd_complete)

    c = sub.add_parser('suggest', help='propose k distinct next objects for a room',
                       description='Propose k distinct objects that could go into the room '
                       'next, without changing it.')
    c.add_argument('scene', help='a room layout or scene JSON')
    c.add_argument('-k', type=int, default=5, help='number of proposals')
    _synthesis_options(c, out=False)
    c.add_argument('--out', help='write the proposals (JSON list of objects) here')
    c.set_defaults(func=cmd_suggest)

    c = sub.add_parser('gallery', help='a grid of corpus rooms, synthesized rooms (one row '
                       'per room type), completions of one partial room, or an imported data '
                       "set's held-out rooms beside rooms synthesized in the same shells")
    c.add_argument('--source', choices=('corpus', 'synthesized', 'completions', 'data'),
                   default='corpus')
    c.add_argument('--data', help='data: the imported data set the --weights-dir were '
                   'trained on (scene-synth train --data)')
    c.add_argument('--out', default='docs/gallery/corpus.png', help='the picture to write '
                   '(default: docs/gallery/corpus.png)')
    c.add_argument('--per-type', type=int, default=3, help='columns of the grid')
    c.add_argument('--seed', type=int, default=0, help='corpus: the corpus seed; otherwise '
                   'the seed of the first room')
    c.add_argument('--partial', help='completions: the partial room (default: '
                   'examples/partial_bedroom.json)')
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.set_defaults(func=cmd_gallery)

    c = sub.add_parser('demo', help='furnish the example rooms and show them, without ROS',
                       description='Furnish the example layouts, complete the example '
                       'partial room and furnish empty rooms of every type, then show them: '
                       'a table in the terminal, and a JSON file and a picture of each room.')
    c.add_argument('--out', default='demo_out', help='folder for the scenes and pictures '
                   '(default: demo_out)')
    c.add_argument('--per-type', type=int, default=1, help='empty rooms per room type')
    c.add_argument('--seed', type=int, default=0, help='seed of the first room')
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.set_defaults(func=cmd_demo)


def _synthesis_options(c, out: bool = True, batch: bool = False) -> None:
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    # The synthesis settings' flags, from their table (``synth_config``); not given, a
    # setting keeps SynthConfig's default.
    for s, default in _SETTING_FLAGS.values():
        setting_flag(c, s, default)
    robot_options(c)
    if out:
        c.add_argument('--out', help='write the scene JSON here (a batch: its directory)')
    if batch:
        # A batch names its own thumbnails, so there --png is a switch.
        c.add_argument('--png', nargs='?', const=True, metavar='PNG',
                       help='write a top-down picture here (a batch: a thumbnail per room '
                       'in DIR/png/, no file name)')
    else:
        c.add_argument('--png', help='write a top-down picture here')


def _batch_options(c, layouts: bool) -> None:
    g = c.add_argument_group('batches', 'many rooms into one directory (--out DIR); the same '
                             'command run again resumes it (docs/cli.md)')
    g.add_argument('-n', type=int, help='rooms in the batch: room i is furnished with seed '
                   '--seed + i' + (', in the corpus-like shell i of the seed (or in --layout, '
                                   'or layout i of --layouts)' if layouts else
                                   ' (with a directory or JSON-lines file: its first N rooms)'))
    if layouts:
        g.add_argument('--layouts', help="the user's own rooms: a directory of layouts (JSON "
                       'or YAML, in name order) or a JSON-lines file (one layout a line)')
    g.add_argument('--workers', type=int, help='worker processes, one torch thread each '
                   '(default: one per core; with --ray, one per CPU of the cluster)')
    g.add_argument('--lockstep', type=int, metavar='R', help='rooms furnished together by '
                   "a worker, each network's pass batched across them (default 8; 1: one at a "
                   'time); part of what the batch is, like --seed')
    g.add_argument('--ray', nargs='?', const='local', metavar='ADDRESS',
                   help='furnish on Ray actors: with no ADDRESS a Ray started on this machine '
                   "for the batch; else a cluster's address (host:port, or auto)")
    g.add_argument('--export', metavar='FORMATS', help='write each room for simulators too: '
                   'a comma list of formats (sdf, gltf, mjcf, urdf, usd)')
    g.add_argument('-q', '--quiet', action='store_true', help='no progress bar')


def _synth_config(args):
    """The SynthConfig of the options of ``args`` (gallery and demo have only some); a value
    out of its setting's range is one sentence naming the flag."""
    given = {name: value for name, (s, _) in _SETTING_FLAGS.items()
             if (value := flag_value(s, args)) is not None}
    if hasattr(args, 'robot_radius'):
        given['robot'] = robot_from(args)
    if given.get('catalog'):
        # a bad file is one sentence before any work
        load_catalog(given['catalog'], args.vocabulary)
        given['catalog'] = str(Path(given['catalog']).resolve())
    elif 'catalog' in given:                 # --catalog '': the procedural catalog
        del given['catalog']
    return SynthConfig(**given)


def _catalog_line(args, room_type: str, vocabulary) -> str | None:
    """Which of the room type's categories the user's catalog furnishes, and which fall
    back to the procedural models; None without --catalog."""
    if not getattr(args, 'catalog', None):
        return None
    names = vocabulary.spec(room_type).names
    models = load_catalog(args.catalog, vocabulary)
    fallback = models.fallback(names)
    own = [c for c in names if c not in fallback]
    return (f'catalog {args.catalog}: your models for {", ".join(own) or "no category"}; '
            f'procedural models for {", ".join(fallback) or "no category"}')


def _synthesizer(args):
    """A Synthesizer with the options of ``args``."""
    from ..synth import Synthesizer
    return Synthesizer(args.weights_dir, _synth_config(args))


def _timing_line(result) -> str:
    parts = ', '.join(f'{k} {v * 1000:.0f}' for k, v in result.timings.items())
    return (f'{len(result.added)} objects added in {result.seconds:.3f} s (stopped: '
            f'{result.stopped}); ms per module: {parts}')


def cmd_generate(args) -> int:
    from ..geometry import check_scene
    if args.n is not None or args.layouts:
        return _cmd_batch(args, 'generate')
    _one_room_only(args)
    synth = _synthesizer(args)
    if args.layout:
        from ..house import HouseScene
        layout = load_layout_file(args.layout, vocabulary=synth.vocabulary)
        if isinstance(layout, HouseScene):        # objects given are dropped, as a room's
            return _furnish_house(args, synth, layout.house, args.layout)
        room = layout.room
        title = f'{Path(args.layout).stem} (seed {args.seed})'
    else:
        from ..corpus.generate import first_shell
        rt = room_types(args.room_type, synth.vocabulary)
        if len(rt) != 1:
            raise UserError('generate furnishes one room: give one --room-type, not all')
        if synth.vocabulary.defines(rt[0]):
            raise UserError(f'{rt[0]} is a room type of the data set the weights were trained '
                            f'on, and the corpus makes only the package\'s own: give --layout')
        room = first_shell(rt[0], args.seed)
        title = f'{rt[0]} (seed {args.seed})'
    result = synth.generate(room, args.seed)
    print(object_table(result.scene.objects, f'{room.room_type}, {room.area:.1f} m2:'))
    print(_timing_line(result))
    print(f'physical check: {check_scene(result.scene, result.allowance).summary()}')
    print(f'robot: {result.robot.sentence()}')
    if line := _catalog_line(args, room.room_type, synth.vocabulary):
        print(line)
    write_scene(result.scene, args.out, args.png, title,
                load_catalog(args.catalog, synth.vocabulary), synth.vocabulary)
    return 0


def _furnish_house(args, synth, house, source: str) -> int:
    """``generate --layout`` of a house layout (a ``House``: every room furnished from
    empty) or ``complete`` of a house scene (a ``HouseScene``: its objects kept), the rooms of
    a type in lockstep; ``source`` is the file, for the picture's title."""
    from ..geometry import check_scene
    from ..house_synth import furnish_house
    result = furnish_house(synth, house, args.seed)
    house = result.scene.house
    for rid, r in result.rooms.items():
        room = house.rooms[rid]
        print(f'{rid} ({room.room_type}, {room.area:.1f} m2): {len(r.scene.objects)} objects; '
              f'physical check: {check_scene(r.scene, r.allowance).summary()}')
    print(f'{len(result.scene.objects())} objects in {len(house.rooms)} rooms, '
          f'{result.seconds:.3f} s')
    print(f'robot: {result.robot_sentence()}')
    models = load_catalog(args.catalog, synth.vocabulary)
    if args.out:
        from ..files import write_atomic
        from ..schema import dump_house_scene
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        write_atomic(args.out, dump_house_scene(result.scene, models, synth.vocabulary) + '\n')
        print(f'wrote {args.out}')
    if args.png:
        from ..plot import save_house_png
        Path(args.png).parent.mkdir(parents=True, exist_ok=True)
        save_house_png(result.scene, args.png, title=f'{Path(source).stem} (seed '
                       f'{args.seed})', vocabulary=synth.vocabulary)
        print(f'wrote {args.png}')
    return 0


def cmd_complete(args) -> int:
    from ..geometry import check_scene
    if args.n is not None or Path(args.scene).is_dir() or \
            Path(args.scene).suffix.lower() == '.jsonl':
        return _cmd_batch(args, 'complete')
    _one_room_only(args)
    synth = _synthesizer(args)
    models = load_catalog(args.catalog, synth.vocabulary)
    scene = load_layout_file(args.scene, models, synth.vocabulary)
    from ..house import HouseScene
    if isinstance(scene, HouseScene):
        return _furnish_house(args, synth, scene, args.scene)
    result = synth.complete(scene, args.seed)
    print(object_table(scene.objects, f'kept ({len(scene.objects)}):'))
    print(object_table(result.added, f'added ({len(result.added)}):'))
    print(_timing_line(result))
    print(f'physical check: {check_scene(result.scene, result.allowance).summary()}')
    print(f'robot: {result.robot.sentence()}')
    if line := _catalog_line(args, scene.room.room_type, synth.vocabulary):
        print(line)
    write_scene(result.scene, args.out, args.png,
                f'{Path(args.scene).stem} completed (seed {args.seed})', models,
                synth.vocabulary)
    return 0


def _one_room_only(args) -> None:
    """UserError for a batch's options given to the one-room command."""
    if getattr(args, 'houses', False):
        raise UserError('--houses is for batches: add -n N and --out DIR')
    for flag, value in (('--workers', args.workers), ('--ray', args.ray),
                        ('--export', args.export), ('--lockstep', args.lockstep)):
        if value is not None:
            raise UserError(f'{flag} is for batches: add -n N and --out DIR')
    if args.png is True:
        raise UserError('--png needs a file name for one room (a batch, -n N --out DIR, '
                        'names its thumbnails)')


def _cmd_batch(args, mode: str) -> int:
    """``generate``/``complete`` over many rooms (``batch.run_batch``)."""
    from ..batch import BatchConfig, Source, run_batch
    if not args.out:
        raise UserError('a batch needs --out DIR, the directory its rooms go to')
    if args.png not in (None, True):
        raise UserError(f'a batch names its thumbnails: give --png without a file name, not '
                        f'--png {quoted(args.png)}')
    if mode == 'complete':
        source = Source.at(args.scene)
    elif args.layouts and args.layout:
        raise UserError('give --layout (one room, -n times) or --layouts (many), not both')
    elif args.houses and (args.layouts or args.layout):
        raise UserError('--houses draws house plans: give it without --layout and --layouts')
    elif args.layouts or args.layout:
        source = Source.at(args.layouts or args.layout)
    elif args.houses:
        source = Source.plans()
    else:
        source = Source.shells(room_types(args.room_type, args.vocabulary), args.vocabulary)
    from ..export import parse_formats
    exports = parse_formats(args.export) if args.export is not None else ()
    if args.export is not None and not exports:
        raise UserError('--export needs at least one format, e.g. --export sdf,gltf')
    summary = run_batch(BatchConfig(
        out=args.out, source=source, mode=mode, n=args.n, seed=args.seed,
        synthesis=_synth_config(args), weights_dir=args.weights_dir, workers=args.workers,
        png=args.png is True, exports=exports, ray=args.ray, progress=not args.quiet,
        **_lockstep(args)))
    print(summary.report())
    return 1 if summary.failed else 0


def _lockstep(args) -> dict:
    """The batch's lockstep R, where the command line gives or implies one: a house's rooms
    are furnished in lockstep already, so houses go one to a worker at a time (R = 1),
    spread over every worker."""
    if args.lockstep is not None:
        return {'lockstep': args.lockstep}
    return {'lockstep': 1} if getattr(args, 'houses', False) else {}


def cmd_suggest(args) -> int:
    if args.k < 1:
        raise UserError(f'-k must be at least 1, got {args.k}')
    synth = _synthesizer(args)
    scene = load_scene_file(args.scene, load_catalog(args.catalog, synth.vocabulary),
                            synth.vocabulary)
    found = synth.suggest(scene, args.k, args.seed)
    print(object_table(found, f'{len(found)} proposals for the next object of '
                              f'{Path(args.scene).name}:'))
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text(json.dumps([o.to_dict() for o in found], indent=2) + '\n')
        print(f'wrote {args.out}')
    if args.png:
        from ..plot import save_grid
        from ..scene import Scene
        shown = [Scene(scene.room, scene.objects + [o]) for o in found]
        save_grid(shown, args.png, ncols=min(len(shown), 3) or 1, vocabulary=synth.vocabulary,
                  titles=[f'+ {o.category}' for o in found])
        print(f'wrote {args.png}')
    return 0


# ---- pictures of many rooms ------------------------------------------------------------------
def _corpus_grid(args) -> tuple[list, list[str]]:
    from ..corpus.generate import generate_room
    scenes, titles = [], []
    for rt in ROOM_TYPES:
        for i in range(args.per_type):
            scenes.append(generate_room(rt, args.seed, i))
            titles.append(f'{rt} #{i} (seed {args.seed})')
    return scenes, titles


def _synthesized_grid(args) -> tuple[list, list[str]]:
    from ..corpus.generate import empty_room
    synth = _synthesizer(args)
    scenes, titles = [], []
    for rt in ROOM_TYPES:
        for i in range(args.per_type):
            room = empty_room(rt, HELDOUT_SEED, i)
            scenes.append(synth.generate(room, args.seed + i).scene)
            titles.append(f'{rt} #{i} (seed {args.seed + i})')
    return scenes, titles


def _data_grid(args) -> tuple[list, list[str]]:
    """Per room type of the weights, ``per_type`` held-out rooms of the data set, then the
    rooms synthesized in their empty shells."""
    from ..datasets.training import describe_dir, split_rooms
    if not args.data or not args.weights_dir:
        raise UserError('--source data needs --data and --weights-dir: the imported data set '
                        'and the weights trained on it')
    in_data = describe_dir(args.data).room_types
    synth = _synthesizer(args)
    scenes, titles = [], []
    for rt in synth.room_types:
        if rt not in in_data:
            continue
        seed = synth.networks.served(rt).config.train.corpus_seed
        split = split_rooms(args.data, synth.vocabulary.spec(rt), seed,
                            held_out_rooms=args.per_type)
        for name, real in zip(split.held_out_names, split.held_out, strict=True):
            scenes.append(real)
            titles.append(f'{rt}: {Path(name).stem} (held out)')
        for i, real in enumerate(split.held_out):
            scenes.append(synth.generate(real.room, args.seed + i).scene)
            titles.append(f'{rt}: synthesized, same shell (seed {args.seed + i})')
    if not scenes:
        raise UserError(f'{args.data} holds none of the room types of the weights '
                        f'({", ".join(synth.room_types)})')
    return scenes, titles


def _completions_grid(args) -> tuple[list, list[str]]:
    from ..paths import examples_dir
    synth = _synthesizer(args)
    partial = load_scene_file(args.partial or str(examples_dir() / 'partial_bedroom.json'))
    scenes, titles = [partial], [f'partial room ({len(partial)} objects)']
    for i in range(args.per_type * 2 - 1):
        scenes.append(synth.complete(partial, args.seed + i).scene)
        titles.append(f'completion, seed {args.seed + i}')
    return scenes, titles


def cmd_gallery(args) -> int:
    from ..plot import save_grid
    grid = {'corpus': _corpus_grid, 'synthesized': _synthesized_grid,
            'completions': _completions_grid, 'data': _data_grid}[args.source]
    scenes, titles = grid(args)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    cols = args.per_type * (2 if args.source == 'data' else 1)
    save_grid(scenes, out, ncols=cols, titles=titles, vocabulary=args.vocabulary)
    print(f'wrote {out}')
    return 0


def _demo_jobs(per_type: int) -> list[tuple[str, str, object]]:
    """(name, 'generate' or 'complete', scene): the example layouts, the example partial
    room, and ``per_type`` held-out shells of every room type."""
    from ..corpus.generate import empty_room
    from ..paths import examples_dir
    from ..scene import Scene
    jobs = []
    for f in ('bedroom_layout.json', 'lshaped_living_layout.json', 'kitchen_layout.json'):
        jobs.append((Path(f).stem, 'generate', load_scene_file(str(examples_dir() / f))))
    jobs.append(('partial_bedroom_completed', 'complete',
                 load_scene_file(str(examples_dir() / 'partial_bedroom.json'))))
    for rt in ROOM_TYPES:
        for i in range(per_type):
            jobs.append((f'{rt}_{i}', 'generate', Scene(empty_room(rt, HELDOUT_SEED, i), [])))
    return jobs


def _added_categories(objects) -> str:
    """``2x stand, double bed``: the categories of ``objects`` with their counts."""
    added: dict[str, int] = {}
    for o in objects:
        added[o.category] = added.get(o.category, 0) + 1
    return ', '.join(f'{n}x {c}' if n > 1 else c for c, n in added.items())


def cmd_demo(args) -> int:
    """The main job: furnish the example layouts, complete the example partial room and
    furnish empty rooms of every type with the trained pipeline, then show them (JSON, one
    picture each, a contact sheet, a table in the terminal)."""
    from ..geometry import check_scene
    from ..plot import save_grid, save_png
    from ..schema import save_scene
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    synth = _synthesizer(args)
    jobs = _demo_jobs(args.per_type)
    scenes, titles = [], []
    print(f'{"room":26s} {"floor":>8s} {"kept":>4s} {"added":>5s} {"seconds":>7s} '
          f'{"valid":>5s}  categories added')
    for k, (name, mode, scene) in enumerate(jobs):
        seed = args.seed + k
        fn = synth.generate if mode == 'generate' else synth.complete
        result = fn(scene, seed)
        s = result.scene
        save_scene(s, out / f'{name}.json')
        save_png(s, out / f'{name}.png', title=f'{name} (seed {seed})')
        scenes.append(s)
        titles.append(f'{name} (seed {seed})')
        kept = len(s) - len(result.added)
        valid = check_scene(s, result.allowance).ok
        print(f'{name:26s} {s.room.area:6.1f}m2 {kept:4d} {len(result.added):5d} '
              f'{result.seconds:7.2f} {"yes" if valid else "NO":>5s}  '
              f'{_added_categories(result.added)}')
    save_grid(scenes, out / 'gallery.png', ncols=3, titles=titles)
    print(f'\nwrote {len(scenes)} scenes (JSON + PNG) and {out / "gallery.png"}')
    return 0
