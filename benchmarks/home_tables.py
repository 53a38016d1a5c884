"""The data-derived figures of ``scene_synth_ros/home_tables.py`` derived again from the real
files, printed beside the module's values.

    .venv/bin/python benchmarks/home_tables.py [--data ../shared/data/real]

``--data`` holds ``procthor/``, ``3dfront/`` and ``suncg/`` as ``scene-synth import`` reads
them; each folder present is imported with the package's importers (room types through
``datasets/room_types.yaml``, no room-size filter, empty rooms kept). Prints the kitchen and
dining category tables (data counts and the reference shares' counts), the hallway table
(reference only: nothing to derive), and the quantiles of every room type's longer side,
shorter side (in the room's own axes, ``datasets.assemble.room_span``) and floor area. Exits 1
when a derived figure differs from the module's, or when a category of the data has no
decision in the module's mappings. Under a minute on one core (the 500 ProcTHOR houses).
"""
from __future__ import annotations

import argparse
from collections import Counter
from pathlib import Path
import sys

import numpy as np
from shapely.geometry import Polygon

from scene_synth_ros import home_tables as ht
from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.datasets import ImportConfig, import_dataset, load_room_types
from scene_synth_ros.datasets.assemble import room_span
from scene_synth_ros.limits import MAX_OBJECTS
from scene_synth_ros.scene import Room

FORMATS = ('procthor', '3dfront', 'suncg')


def imported_scenes(real: Path) -> list[dict]:
    """Every room of the formats present under ``real`` whose type maps to ours, as Scene
    dicts: no room-size filter (sizes are what is measured) and no object-count filter
    (3D-FRONT's kitchens and aisles hold no furniture but are rooms all the same)."""
    scenes = []
    for fmt in FORMATS:
        if not (real / fmt).is_dir():
            continue
        config = ImportConfig(room_types=load_room_types(fmt), room_size={},
                              object_count=(0, MAX_OBJECTS))
        scenes += import_dataset(fmt, [real / fmt], config=config).scenes.values()
    return scenes


def _source(scene: dict) -> tuple[str, str]:
    src = scene['meta']['source']
    return src['format'], src['room_type']


def kitchen_counts(scenes: list[dict]) -> tuple[int, Counter, Counter]:
    """(kitchens, our category -> count, data categories without a decision) of ProcTHOR's
    kitchens through ``home_tables.PROCTHOR_KITCHEN``, its stools' heights and its counters'
    shapes."""
    rooms, counts, undecided = 0, Counter(), Counter()
    for scene in scenes:
        if _source(scene)[0] != 'procthor' or scene['room']['room_type'] != 'kitchen':
            continue
        rooms += 1
        for obj in scene['objects']:
            category = obj['category']
            if category in ht.PROCTHOR_COUNTER_TYPES:
                shape = obj['model_id'].split('_')[1]
                name, runs = ht.PROCTHOR_COUNTER_SHAPES[shape]
                counts[name] += runs
            elif category in ht.PROCTHOR_KITCHEN:
                counts[ht.PROCTHOR_KITCHEN[category]] += 1
            elif category in ht.PROCTHOR_KITCHEN_BY_HEIGHT:
                tall, low, high = ht.PROCTHOR_KITCHEN_BY_HEIGHT[category]
                counts[high if obj['size'][2] >= tall else low] += 1
            elif category not in ht.PROCTHOR_KITCHEN_DROPPED:
                undecided[category] += 1
    return rooms, counts, undecided


def dining_counts(scenes: list[dict]) -> tuple[int, Counter, Counter]:
    """(rooms, our category -> count, data categories without a decision) of 3D-FRONT's
    dining rooms and of the dining groups of its living-dining rooms."""
    rooms, counts, undecided = 0, Counter(), Counter()
    for scene in scenes:
        fmt, data_type = _source(scene)
        if fmt != '3dfront' or not (scene['room']['room_type'] == 'dining'
                                    or data_type in ht.FRONT_DINING_GROUP_ROOMS):
            continue
        rooms += 1
        for obj in scene['objects']:
            category = obj['category']
            if category in ht.FRONT_DINING:
                counts[ht.FRONT_DINING[category]] += 1
            elif scene['room']['room_type'] == 'dining':
                undecided[category] += 1     # a dining room's own furniture needs a decision
    return rooms, counts, undecided


def with_reference(rooms: int, counts: Counter, shares: dict[str, float]) -> dict[str, int]:
    """The data's counts and, for the categories the data lacks, the reference share of the
    rooms; most frequent first."""
    out = Counter(counts)
    for name, share in shares.items():
        out[name] = round(share * rooms)
    return dict(sorted(out.items(), key=lambda kv: (-kv[1], kv[0])))


def room_sizes(scenes: list[dict]) -> dict[str, ht.RoomSizes]:
    sides: dict[str, list] = {}
    sources: dict[str, Counter] = {}
    for scene in scenes:
        room = scene['room']
        floor = tuple(tuple(p) for p in room['floor'])
        longer, shorter = sorted(room_span(Room(room['room_type'], floor,
                                                room['wall_height'])), reverse=True)
        sides.setdefault(room['room_type'], []).append(
            (longer, shorter, Polygon(floor).area))
        sources.setdefault(room['room_type'], Counter())[_source(scene)[0]] += 1
    out = {}
    for rt in sorted(sides):
        values = np.array(sides[rt])
        q = [tuple(round(float(v), 2) for v in np.quantile(values[:, i], ht.SIZE_QUANTILES))
             for i in range(3)]
        out[rt] = ht.RoomSizes(len(values), dict(sorted(sources[rt].items())), *q)
    return out


def derive(real: Path) -> dict:
    """Every data-derived figure of ``home_tables``: {'counts': {room type: (rooms, table)},
    'sizes': {room type: RoomSizes}, 'undecided': {room type: Counter}}, and the sizes of
    each data set alone ('sizes_by_source', printed only)."""
    scenes = imported_scenes(real)
    k_rooms, k_counts, k_undecided = kitchen_counts(scenes)
    d_rooms, d_counts, d_undecided = dining_counts(scenes)
    return {
        'counts': {
            'kitchen': (k_rooms, with_reference(k_rooms, k_counts, ht.KITCHEN_REFERENCE)),
            'dining': (d_rooms, with_reference(d_rooms, d_counts, {})),
        },
        'sizes': room_sizes(scenes),
        'sizes_by_source': {fmt: room_sizes([s for s in scenes if _source(s)[0] == fmt])
                            for fmt in FORMATS},
        'undecided': {'kitchen': k_undecided, 'dining': d_undecided},
    }


def compare_table(rt: str, derived: tuple[int, dict[str, int]]) -> bool:
    rooms, table = derived
    module = ht.TABLE_COUNTS[rt]
    same = rooms == ht.ROOMS_IN_TABLE[rt] and table == module
    print(f'\n{rt}: {rooms} rooms derived, {ht.ROOMS_IN_TABLE[rt]} in the module'
          f'{"" if same else "  <-- differs"}')
    print(f'  {"category":<16} {"derived":>8} {"module":>8} {"per room":>9}')
    for name in dict.fromkeys([*table, *module]):
        d, m = table.get(name), module.get(name)
        flag = '' if d == m else '  <-- differs'
        per_room = f'{d / rooms:9.2f}' if d is not None and rooms else f'{"":9}'
        print(f'  {name:<16} {d if d is not None else "-":>8} {m if m is not None else "-":>8}'
              f' {per_room}{flag}')
    return same


def compare_sizes(derived: dict[str, ht.RoomSizes]) -> bool:
    same = derived == ht.ROOM_SIZES
    qs = ' '.join(f'{f"q{round(q * 100)}":>6}' for q in ht.SIZE_QUANTILES)
    print(f'\nroom sizes: quantiles {", ".join(f"{q:g}" for q in ht.SIZE_QUANTILES)} '
          f'(m; area m²){"" if same else "  <-- differs"}')
    print(f'  {"room type":<9} {"rooms":>5} {"what":<8} {qs}  sources')
    for rt in dict.fromkeys([*derived, *ht.ROOM_SIZES]):
        for label, sizes in (('derived', derived.get(rt)), ('module', ht.ROOM_SIZES.get(rt))):
            if sizes is None:
                print(f'  {rt:<9} {"-":>5} {label:<8} (none)')
                continue
            src = ', '.join(f'{k} {v}' for k, v in sizes.sources.items())
            for what in ('longer', 'shorter', 'area'):
                values = ' '.join(f'{v:6.2f}' for v in getattr(sizes, what))
                tail = f'  {label}: {src}' if what == 'longer' else ''
                print(f'  {rt:<9} {sizes.rooms:>5} {what:<8} {values}{tail}')
    for rt in dict.fromkeys([*ROOM_TYPES, *ht.TABLE_COUNTS]):
        if rt not in derived:
            print(f'  {rt}: no room of this type in the data')
    return same


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--data', type=Path, default=Path('../shared/data/real'),
                    help='folder with procthor/, 3dfront/ and suncg/ (default: %(default)s)')
    args = ap.parse_args()
    if not args.data.is_dir():
        print(f'{args.data}: no such folder', file=sys.stderr)
        return 1
    derived = derive(args.data)
    ok = True
    for rt, table in derived['counts'].items():
        ok &= compare_table(rt, table)
    print(f'\nhallway: {ht.ROOMS_IN_TABLE["hallway"]} rooms, reference shares only '
          f'(nothing to derive)')
    for name, count in ht.TABLE_COUNTS['hallway'].items():
        print(f'  {name:<16} {count:>8}')
    ok &= compare_sizes(derived['sizes'])
    print('\nthe same per data set (not in the module: ProcTHOR\'s houses are procedural, '
          '3D-FRONT\'s and SUNCG\'s drawn by people)')
    for fmt, sizes in derived['sizes_by_source'].items():
        for rt, s in sizes.items():
            for what in ('longer', 'area'):
                values = ' '.join(f'{v:6.2f}' for v in getattr(s, what))
                print(f'  {fmt:<8} {rt:<9} {s.rooms:>5} {what:<8} {values}')
    for rt, undecided in derived['undecided'].items():
        if undecided:
            ok = False
            print(f'\n{rt}: data categories with no decision in home_tables: '
                  f'{", ".join(f"{k} ({v})" for k, v in undecided.most_common())}')
    print('\nall derived figures equal the module\'s' if ok else
          '\nthe module differs from the data: update scene_synth_ros/home_tables.py')
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
