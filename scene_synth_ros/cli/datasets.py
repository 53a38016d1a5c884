"""``scene-synth import``: real scene data sets (3D-FRONT, SUNCG, ProcTHOR) as our Scene
JSON, one room per scene, with the import report and the data-set description."""
from __future__ import annotations

from pathlib import Path

from ..datasets.config import FORMATS, ImportConfig
from ..thresholds import MAX_ROOM_SIDE

TABLE_HELP = {
    '3dfront': "3D-FUTURE's category mapping (CSV) or model_info.json",
    'suncg': 'ModelCategoryMapping.csv',
}


def add_parser(sub) -> None:
    d = ImportConfig()
    c = sub.add_parser(
        'import', help='read 3D-FRONT, SUNCG or ProcTHOR files into scenes, one per room',
        description='Read the files (or the folders of files) of one data set into Scene '
        'JSON files, one per room, in --out, with report.txt / report.json (what was kept, '
        'mapped and dropped, and why) and dataset.yaml (what the rooms hold, per room type).')
    c.add_argument('format', choices=FORMATS)
    c.add_argument('inputs', nargs='+', metavar='INPUT', help='files or folders')
    c.add_argument('--out', required=True, help='output folder')
    c.add_argument('--room-types', metavar='FILE',
                   help="room-type mapping (YAML, format -> {theirs: ours}; default: the "
                   "package's datasets/room_types.yaml)")
    c.add_argument('--category-map', metavar='FILE',
                   help='model id -> category: ' + '; '.join(
                       f'{k}: {v}' for k, v in TABLE_HELP.items())
                   + ' (default: found beside the inputs)')
    c.add_argument('--asset-sizes', metavar='FILE',
                   help='ProcTHOR: asset id -> objectType and boundingBox '
                   '(default: procthor_asset_boxes.json beside the inputs)')
    c.add_argument('--models', metavar='DIR',
                   help='3D-FUTURE model folder (<jid>/raw_model.obj) or SUNCG folder '
                   '(object/<id>/<id>.obj, room/<house>/<id>f.obj): sizes and floors from '
                   'the meshes')
    c.add_argument('--scale-range', nargs=2, type=float, metavar=('MIN', 'MAX'),
                   default=d.scale_range, help='objects scaled outside this are dropped '
                   f'(default {d.scale_range[0]:g} {d.scale_range[1]:g})')
    c.add_argument('--object-count', nargs=2, type=int, metavar=('MIN', 'MAX'),
                   default=d.object_count, help='rooms keeping fewer or more objects are '
                   f'dropped (default {d.object_count[0]} {d.object_count[1]})')
    c.add_argument('--room-size', action='append', default=[], metavar='TYPE=METRES',
                   help='longest side a room of TYPE may have, repeatable (default: '
                   f'{MAX_ROOM_SIDE:g} for the package\'s room types, other types unlimited)')
    c.add_argument('--no-room-size', action='store_true',
                   help='keep rooms of any size')
    c.add_argument('--floor-tolerance', type=float, default=d.floor_tolerance,
                   help='metres an object\'s centre may lie outside the floor (default '
                   f'{d.floor_tolerance:g})')
    c.add_argument('--layouts', action='store_true', help="also write each house's kept "
                   'rooms as an empty house layout (msg_schemas/house_layout.schema.json) to '
                   'OUT/houses/, to furnish real floor plans again')
    c.add_argument('--quiet', action='store_true', help='print only the summary line')
    c.set_defaults(func=cmd_import)


def cmd_import(args) -> int:
    from ..datasets.config import load_room_types, parse_room_size
    from ..datasets.importer import import_dataset
    from ..errors import DatasetError
    if args.format == 'procthor' and args.category_map:
        raise DatasetError('ProcTHOR takes its categories from --asset-sizes, not '
                           '--category-map')
    if args.format != 'procthor' and args.asset_sizes:
        raise DatasetError(f'--asset-sizes is for ProcTHOR; {args.format} takes '
                           f'--category-map')
    room_size = {} if args.no_room_size else (
        parse_room_size(args.room_size) if args.room_size else None)
    config = ImportConfig(scale_range=tuple(args.scale_range),
                          object_count=tuple(args.object_count), room_size=room_size,
                          floor_tolerance=args.floor_tolerance,
                          room_types=load_room_types(args.format, args.room_types))
    result = import_dataset(args.format, args.inputs, out=args.out, config=config,
                            table=args.asset_sizes or args.category_map, models=args.models,
                            layouts=args.layouts)
    summary = result.report.summary()
    print(summary.splitlines()[0] if args.quiet else summary)
    if not args.quiet:
        print(f'wrote {result.report.totals()["rooms_kept"]} scene(s), report.txt, report.json '
              f'and dataset.yaml to {args.out}')
        if args.layouts:
            print(f'wrote {len(result.houses)} house layout(s) to {Path(args.out) / "houses"}')
    return 0
