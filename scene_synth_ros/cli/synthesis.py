"""``scene-synth generate``, ``complete``, ``suggest``, ``gallery`` and ``demo``: rooms
furnished by the trained pipeline, printed as tables and written as JSON and pictures."""
from __future__ import annotations

import json
from pathlib import Path

from ..categories import ROOM_TYPES
from ..corpus import HELDOUT_SEED
from .common import (
    WEIGHTS_DIR_HELP,
    UserError,
    load_scene_file,
    object_table,
    robot_from,
    robot_options,
    room_types,
    write_scene,
)


def add_parser(sub) -> None:
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

    c = sub.add_parser('gallery', help='a grid of corpus rooms, synthesized rooms (one row '
                       'per room type) or completions of one partial room')
    c.add_argument('--source', choices=('corpus', 'synthesized', 'completions'),
                   default='corpus')
    c.add_argument('--out', default='docs/gallery/corpus.png')
    c.add_argument('--per-type', type=int, default=3, help='columns of the grid')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--partial', help='completions: the partial room (default: '
                   'examples/partial_bedroom.json)')
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.set_defaults(func=cmd_gallery)

    c = sub.add_parser('demo', help='furnish example rooms with the pipeline and show them')
    c.add_argument('--out', default='demo_out')
    c.add_argument('--per-type', type=int, default=1, help='empty rooms per room type')
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.set_defaults(func=cmd_demo)


def _synthesis_options(c, out: bool = True) -> None:
    c.add_argument('--seed', type=int, default=0)
    c.add_argument('--temperature', type=float, help='location temperature (default 0.8)')
    c.add_argument('--max-objects', type=int, help='cap on objects in the room (default 30)')
    c.add_argument('--weights-dir', help=WEIGHTS_DIR_HELP)
    c.add_argument('--device', choices=('cpu', 'cuda', 'auto'))
    robot_options(c)
    if out:
        c.add_argument('--out', help='write the scene JSON here')
    c.add_argument('--png', help='write a top-down picture here')


def _synthesizer(args):
    """A Synthesizer with the options of ``args`` (gallery and demo have only some)."""
    from ..synth import SynthConfig, Synthesizer
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
    if hasattr(args, 'robot_radius'):
        cfg.robot = robot_from(args)
    return Synthesizer(args.weights_dir, cfg)


def _timing_line(result) -> str:
    parts = ', '.join(f'{k} {v * 1000:.0f}' for k, v in result.timings.items())
    return (f'{len(result.added)} objects added in {result.seconds:.3f} s (stopped: '
            f'{result.stopped}); ms per module: {parts}')


def cmd_generate(args) -> int:
    from ..geometry import check_scene
    synth = _synthesizer(args)
    if args.layout:
        room = load_scene_file(args.layout).room
        title = f'{Path(args.layout).stem} (seed {args.seed})'
    else:
        from ..corpus.generate import empty_room
        rt = room_types(args.room_type)
        if len(rt) != 1:
            raise UserError('generate furnishes one room: give one --room-type, not all')
        room = empty_room(rt[0], args.seed)
        title = f'{rt[0]} (seed {args.seed})'
    result = synth.generate(room, args.seed)
    print(object_table(result.scene.objects, f'{room.room_type}, {room.area:.1f} m2:'))
    print(_timing_line(result))
    print(f'physical check: {check_scene(result.scene).summary()}')
    print(f'robot: {result.robot.sentence()}')
    write_scene(result.scene, args.out, args.png, title)
    return 0


def cmd_complete(args) -> int:
    from ..geometry import check_scene
    synth = _synthesizer(args)
    scene = load_scene_file(args.scene)
    result = synth.complete(scene, args.seed)
    print(object_table(scene.objects, f'kept ({len(scene.objects)}):'))
    print(object_table(result.added, f'added ({len(result.added)}):'))
    print(_timing_line(result))
    print(f'physical check: {check_scene(result.scene).summary()}')
    print(f'robot: {result.robot.sentence()}')
    write_scene(result.scene, args.out, args.png,
                f'{Path(args.scene).stem} completed (seed {args.seed})')
    return 0


def cmd_suggest(args) -> int:
    if args.k < 1:
        raise UserError(f'-k must be at least 1, got {args.k}')
    synth = _synthesizer(args)
    scene = load_scene_file(args.scene)
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
        save_grid(shown, args.png, ncols=min(len(shown), 3) or 1,
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
            'completions': _completions_grid}[args.source]
    scenes, titles = grid(args)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    save_grid(scenes, out, ncols=args.per_type, titles=titles)
    print(f'wrote {out}')
    return 0


def _demo_jobs(per_type: int) -> list[tuple[str, str, object]]:
    """(name, 'generate' or 'complete', scene): the example layouts, the example partial
    room, and ``per_type`` held-out shells of every room type."""
    from ..corpus.generate import empty_room
    from ..paths import examples_dir
    from ..scene import Scene
    jobs = []
    for f in ('bedroom_layout.json', 'lshaped_living_layout.json'):
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
        print(f'{name:26s} {s.room.area:6.1f}m2 {kept:4d} {len(result.added):5d} '
              f'{result.seconds:7.2f} {"yes" if check_scene(s).ok else "NO":>5s}  '
              f'{_added_categories(result.added)}')
    save_grid(scenes, out / 'gallery.png', ncols=3, titles=titles)
    print(f'\nwrote {len(scenes)} scenes (JSON + PNG) and {out / "gallery.png"}')
    return 0
