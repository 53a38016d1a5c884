"""``scene-synth validate``, ``render`` and ``export``: one scene file checked, drawn, or
written for a simulator (Gazebo SDF, glTF, MuJoCo MJCF, URDF for PyBullet, OpenUSD)."""
from __future__ import annotations

from pathlib import Path

from ..synth_config import MapConfig, settings_of
from .common import (
    UserError,
    data_set_option,
    flag_value,
    load_catalog,
    load_layout_file,
    load_scene_file,
    robot_from,
    robot_options,
    setting_flag,
)


def add_parser(sub) -> None:
    c = sub.add_parser('export', help='write a scene for simulators: Gazebo SDF, glTF, MuJoCo '
                       'MJCF, URDF for PyBullet, OpenUSD')
    c.add_argument('scene', help='a scene JSON, or a house scene (scene-synth generate '
                   '--layout HOUSE): one world of the whole house')
    c.add_argument('--sdf', help='the Gazebo world file to write (SDF 1.9)')
    c.add_argument('--sdf-model', help='the room as one SDF model, to spawn into a running '
                   'world (ros_gz_sim create)')
    c.add_argument('--gltf', help='the binary glTF (.glb) to write')
    c.add_argument('--mjcf', help='the MuJoCo model (.xml) to write')
    c.add_argument('--urdf', help='the room URDF to write; the objects\' URDFs go to '
                   '<stem>_objects/, their poses to <stem>.poses.json')
    c.add_argument('--usd', help='the USD stage to write (.usda text, .usd or .usdc binary)')
    c.add_argument('--mesh-dir', help='where the mesh files go (default: <stem>_meshes/ '
                   'beside each file written)')
    c.add_argument('--fixed', action='store_true', help='furniture static instead of '
                   'dynamic bodies (SDF, MJCF, URDF, USD)')
    c.add_argument('--catalog', help='the catalog of your own models the scene was furnished '
                   'from (`scene-synth catalog build`): their meshes are exported')
    data_set_option(c)
    c.set_defaults(func=cmd_export)

    c = sub.add_parser('render', help='draw a scene JSON as a top-down picture')
    c.add_argument('scene', help='a scene or room layout JSON (or a house layout or scene)')
    c.add_argument('--png', help='picture for people (matplotlib)')
    c.add_argument('--channels', help="the network input image as a .npy (C x N x N)")
    c.add_argument('--resolution', type=int, default=64, help='pixels a side of the '
                   '--channels image (default 64)')
    c.add_argument('--title', help='title of the --png picture')
    data_set_option(c)
    c.set_defaults(func=cmd_render)

    c = sub.add_parser('validate', help='check scene JSON files: schema and physics')
    c.add_argument('files', nargs='+', help='scene or room layout JSON files (or a house '
                   "layout or scene: every room's)")
    data_set_option(c)
    c.set_defaults(func=cmd_validate)

    c = sub.add_parser('map', help='write a scene as the occupancy map nav2 loads (map_server '
                       'YAML and PGM)',
                       description='Occupied where a wall or an object stands at the scan '
                       'height, free where the robot drives from the doors, unknown elsewhere '
                       '(docs/navigation.md).')
    c.add_argument('scene', help='a scene JSON, or a house scene (scene-synth generate '
                   '--layout HOUSE) for the map of the whole house')
    c.add_argument('--out', required=True, help='the map YAML to write; its PGM image goes '
                   'beside it, of the same name')
    for s, default in settings_of(MapConfig).values():
        setting_flag(c, s, default, value=default)
    robot_options(c)
    data_set_option(c)
    c.set_defaults(func=cmd_map)

    c = sub.add_parser('reach', help='check that a robot can drive between the doors and '
                       'reach every object of scene files (exit 1 when it cannot)',
                       description='For each scene file, say whether a round robot can drive '
                       'from each door to every other and reach every object, and how much '
                       'of the free floor it drives over. Exit code 1 when a file breaks it.')
    c.add_argument('files', nargs='+', help='scene JSON files')
    robot_options(c)
    c.add_argument('--png', help='a picture of the reachable floor (one file only)')
    data_set_option(c)
    c.set_defaults(func=cmd_reach)


def cmd_export(args) -> int:
    from ..export import export_sdf, write
    from ..house import count_objects
    models = load_catalog(args.catalog, args.vocabulary)
    scene = load_layout_file(args.scene, models, args.vocabulary)
    wanted = [(fmt, getattr(args, fmt)) for fmt in ('sdf', 'gltf', 'mjcf', 'urdf', 'usd')
              if getattr(args, fmt)]
    if not (wanted or args.sdf_model):
        raise UserError('export needs --sdf, --sdf-model, --gltf, --mjcf, --urdf and/or --usd '
                        'to know what to write')
    for fmt, path in wanted + ([('sdf-model', args.sdf_model)] if args.sdf_model else []):
        try:
            if fmt == 'sdf-model':
                export_sdf(scene, path, args.mesh_dir, fixed=args.fixed, root='model',
                           catalog=models)
            else:
                write(scene, fmt, path, args.mesh_dir, fixed=args.fixed, catalog=models)
        except OSError as e:
            raise UserError(f'cannot write {path}: {e.strerror or e}') from None
        print(f'wrote {path} ({fmt}, {count_objects(scene)} objects)')
    return 0


def cmd_render(args) -> int:
    from ..house import HouseScene
    scene = load_layout_file(args.scene, vocabulary=args.vocabulary)
    if not (args.png or args.channels):
        raise UserError('render needs --png and/or --channels to know what to write')
    if isinstance(scene, HouseScene):
        if args.channels:
            raise UserError(f'{args.scene} is a house: the networks see one room at a time, '
                            f'so --channels needs a room')
        from ..plot import save_house_png
        save_house_png(scene, args.png, title=args.title or Path(args.scene).stem,
                       vocabulary=args.vocabulary)
        print(f'wrote {args.png}')
        return 0
    if args.png:
        from ..plot import save_png
        save_png(scene, args.png, title=args.title or Path(args.scene).stem,
                 vocabulary=args.vocabulary)
        print(f'wrote {args.png}')
    if args.channels:
        import numpy as np

        from ..render import TopDownRenderer
        try:
            image = TopDownRenderer(args.resolution, vocabulary=args.vocabulary).render(scene)
        except ValueError as e:
            # The renderer names the problem (a room too big for the image), not the file.
            raise UserError(f'{args.scene}: {e}') from None
        np.save(args.channels, image)
        print(f'wrote {args.channels}: {image.shape[0]} channels of '
              f'{image.shape[1]}x{image.shape[2]} px')
    return 0


def cmd_validate(args) -> int:
    from ..allowance import of_scene
    from ..geometry import check_scene
    from ..house import HouseScene
    for path in args.files:
        scene = load_layout_file(path, vocabulary=args.vocabulary)
        if isinstance(scene, HouseScene):       # every room, checked as a room alone
            rooms = [(rid, check_scene(s, of_scene(scene.meta)))
                     for rid, s in scene.scenes.items()]
            bad = [f'{rid}: {r.summary()}' for rid, r in rooms if not r.ok]
            print(f'{path}: schema OK, a house of {len(rooms)} rooms, '
                  f'{len(scene.objects())} objects, physically '
                  + ('; '.join(bad) if bad else rooms[0][1].summary()))
            continue
        report = check_scene(scene, of_scene(scene.meta))
        print(f'{path}: schema OK, {len(scene)} objects, physically {report.summary()}')
    return 0


def cmd_map(args) -> int:
    from ..occupancy import FREE, OCCUPIED, occupancy_grid, write_map
    robot = robot_from(args)
    config = MapConfig(**{name: flag_value(s, args)
                          for name, (s, _) in settings_of(MapConfig).items()})
    scene = load_layout_file(args.scene, vocabulary=args.vocabulary)
    grid = occupancy_grid(scene, robot, config)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    path = write_map(grid, args.out)
    print(f'wrote {path} and {path.with_suffix(".pgm").name}: {grid.width} x {grid.height} '
          f'cells of {grid.resolution:g} m, {int((grid.data == FREE).sum())} free, '
          f'{int((grid.data == OCCUPIED).sum())} occupied')
    return 0


def cmd_reach(args) -> int:
    from ..rules.robot import report
    robot = robot_from(args)
    if args.png and len(args.files) > 1:
        raise UserError('--png draws one scene: give one file')
    broken = 0
    for path in args.files:
        scene = load_scene_file(path, vocabulary=args.vocabulary)
        found = report(scene, robot)
        broken += not found.kept
        print(f'{path}: {found.sentence()}')
        if args.png:
            from ..plot import save_reach_png
            Path(args.png).parent.mkdir(parents=True, exist_ok=True)
            save_reach_png(scene, robot, args.png, vocabulary=args.vocabulary)
            print(f'wrote {args.png}')
    return 1 if broken else 0
