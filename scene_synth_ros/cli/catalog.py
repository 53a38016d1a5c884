"""``scene-synth catalog``: the 3D model catalog listed, exported as GLB or OBJ files, or
drawn as a contact sheet."""
from __future__ import annotations


def add_parser(sub) -> None:
    c = sub.add_parser('catalog', help='list, export or preview the 3D model catalog')
    c.add_argument('action', choices=['list', 'export', 'preview'])
    c.add_argument('--out', default='catalog_out')
    c.add_argument('--format', choices=['glb', 'obj'], default='glb')
    c.add_argument('--categories', help='comma-separated categories (default: all)')
    c.set_defaults(func=cmd_catalog)


def cmd_catalog(args) -> int:
    from .. import catalog
    if args.action == 'list':
        for v in catalog.all_variants():
            w, d, h = v.size
            print(f'{v.model_id:20s} {v.category:16s} {w:6.3f} x {d:6.3f} x {h:6.3f} m')
        return 0
    from ..meshes import export_catalog, save_contact_sheet
    if args.action == 'export':
        cats = [c.strip() for c in args.categories.split(',')] if args.categories else None
        paths = export_catalog(args.out, fmt=args.format, categories=cats)
        print(f'wrote {len(paths)} {args.format} models to {args.out}')
    else:
        save_contact_sheet(args.out)
        print(f'wrote {args.out}')
    return 0
