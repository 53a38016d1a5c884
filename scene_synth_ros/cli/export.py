"""``scene-synth validate``, ``render`` and ``export``: one scene file checked, drawn, or
written for a simulator (a Gazebo SDF world, a binary glTF)."""
from __future__ import annotations

from pathlib import Path

from .common import UserError, load_scene_file


def add_parser(sub) -> None:
    c = sub.add_parser('export', help='write a scene as a Gazebo SDF world and/or one glTF')
    c.add_argument('scene', help='a scene JSON')
    c.add_argument('--sdf', help='the world file to write')
    c.add_argument('--mesh-dir', help='where the SDF\'s OBJ meshes go (default: '
                   '<world>_meshes/ beside it)')
    c.add_argument('--gltf', help='the binary glTF (.glb) to write')
    c.set_defaults(func=cmd_export)

    c = sub.add_parser('render', help='draw a scene JSON as a top-down picture')
    c.add_argument('scene')
    c.add_argument('--png', help='picture for people (matplotlib)')
    c.add_argument('--channels', help="the network input image as a .npy (C x N x N)")
    c.add_argument('--resolution', type=int, default=64)
    c.add_argument('--title')
    c.set_defaults(func=cmd_render)

    c = sub.add_parser('validate', help='check scene JSON files: schema and physics')
    c.add_argument('files', nargs='+')
    c.set_defaults(func=cmd_validate)


def cmd_export(args) -> int:
    from ..export import export_gltf, export_sdf
    scene = load_scene_file(args.scene)
    if not (args.sdf or args.gltf):
        raise UserError('export needs --sdf and/or --gltf to know what to write')
    if args.sdf:
        export_sdf(scene, args.sdf, args.mesh_dir)
        print(f'wrote {args.sdf} ({len(scene.objects)} objects)')
    if args.gltf:
        export_gltf(scene, args.gltf)
        print(f'wrote {args.gltf}')
    return 0


def cmd_render(args) -> int:
    scene = load_scene_file(args.scene)
    if not (args.png or args.channels):
        raise UserError('render needs --png and/or --channels to know what to write')
    if args.png:
        from ..plot import save_png
        save_png(scene, args.png, title=args.title or Path(args.scene).stem)
        print(f'wrote {args.png}')
    if args.channels:
        import numpy as np

        from ..render import TopDownRenderer
        try:
            image = TopDownRenderer(args.resolution).render(scene)
        except ValueError as e:
            # The renderer names the problem (a room too big for the image), not the file.
            raise UserError(f'{args.scene}: {e}') from None
        np.save(args.channels, image)
        print(f'wrote {args.channels}: {image.shape[0]} channels of '
              f'{image.shape[1]}x{image.shape[2]} px')
    return 0


def cmd_validate(args) -> int:
    from ..geometry import check_scene
    for path in args.files:
        scene = load_scene_file(path)
        report = check_scene(scene)
        print(f'{path}: schema OK, {len(scene)} objects, physically {report.summary()}')
    return 0
