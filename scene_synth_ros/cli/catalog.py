"""``scene-synth catalog``: the 3D model catalog listed, exported as GLB or OBJ files, or
drawn as a contact sheet; or a catalog of the user's own meshes built from a folder."""
from __future__ import annotations

from pathlib import Path

from .common import UserError, data_set_option, load_catalog


def add_parser(sub) -> None:
    c = sub.add_parser('catalog', help='list, export or preview the 3D model catalog, or '
                       "build a catalog of your own meshes")
    c.add_argument('action', choices=['list', 'export', 'preview', 'build'])
    c.add_argument('folder', nargs='?', help='build: the folder of mesh files (with a '
                   'manifest.yaml, a 3D-FUTURE model_info.json, or one sub-folder per category)')
    c.add_argument('--out', help='export: the folder (default catalog_out); preview: the '
                   'picture; build: the catalog file (default FOLDER/catalog.json)')
    c.add_argument('--format', choices=['glb', 'obj'], default='glb')
    c.add_argument('--categories', help='comma-separated categories (default: all)')
    c.add_argument('--manifest', help='build: the manifest (YAML or JSON; default '
                   'FOLDER/manifest.yaml)')
    c.add_argument('--category-map', help='build: the 3D-FUTURE category map (YAML; default: '
                   'the one shipped in scene_synth_ros/user_catalog/)')
    c.add_argument('--catalog', help='list: a catalog file of your own models (catalog build)')
    data_set_option(c)
    c.set_defaults(func=cmd_catalog)


def cmd_catalog(args) -> int:
    if args.action == 'build':
        return _build(args)
    if args.action == 'list':
        models = load_catalog(args.catalog, args.vocabulary)
        for v in models.all_variants():
            w, d, h = v.size
            print(f'{v.model_id:20s} {v.category:16s} {w:6.3f} x {d:6.3f} x {h:6.3f} m')
        return 0
    from ..meshes import export_catalog, save_contact_sheet
    out = args.out or 'catalog_out'
    if args.action == 'export':
        cats = [c.strip() for c in args.categories.split(',')] if args.categories else None
        paths = export_catalog(out, fmt=args.format, categories=cats)
        print(f'wrote {len(paths)} {args.format} models to {out}')
    else:
        save_contact_sheet(out)
        print(f'wrote {out}')
    return 0


def _build(args) -> int:
    from ..user_catalog import build_catalog, write_catalog
    if not args.folder:
        raise UserError('catalog build needs the folder of your mesh files')
    report = build_catalog(args.folder, args.manifest, args.category_map, args.vocabulary)
    print(report.text())
    out = Path(args.out) if args.out else Path(args.folder) / 'catalog.json'
    if not report.models:
        print(f'nothing to write: no model of {args.folder} could be used')
        return 1
    try:
        write_catalog(out, report.models, report.lines)
    except OSError as e:
        raise UserError(f'cannot write {out}: {e.strerror or e}') from None
    print(f'wrote {out} (and the meshes RViz shows, in {out.parent / "markers"})')
    return 0
