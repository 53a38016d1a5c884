"""Which first-tier objects of an imported data set overlap each other's footprints: the
package's validity refuses such overlaps (in a simulator their box colliders would push
apart), so a data set that tucks chairs under tables teaches a placement synthesis then
refuses.

    .venv/bin/python benchmarks/data_overlaps.py runs/procthor/data [--top 5]

Prints, per room type, the first-tier objects that overlap another one (by more than
1 cm^2), and the category pairs that do so most often.
"""
from __future__ import annotations

import argparse
from collections import Counter
import sys

from scene_synth_ros.datasets.training import describe_dir, load_rooms, room_type_specs
from scene_synth_ros.errors import SceneSynthError

MIN_AREA = 1e-4      # m^2: touching is not overlapping


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('data', help='an imported data set (scene-synth import --out)')
    ap.add_argument('--top', type=int, default=5, help='category pairs shown per room type')
    args = ap.parse_args()
    try:
        specs = room_type_specs(describe_dir(args.data))
    except SceneSynthError as e:
        sys.exit(f'data_overlaps: {e}')
    for rt, spec in specs.items():
        rooms = load_rooms(args.data, spec)
        objects = overlapping = 0
        by_category: Counter = Counter()
        in_category: Counter = Counter()
        pairs: Counter = Counter()
        for scene in rooms.scenes:
            first = scene.first_tier
            shapes = [o.footprint() for o in first]
            for i, o in enumerate(first):
                objects += 1
                in_category[o.category] += 1
                hits = {first[j].category for j in range(len(first)) if j != i
                        and shapes[i].intersection(shapes[j]).area > MIN_AREA}
                if hits:
                    overlapping += 1
                    by_category[o.category] += 1
                    pairs.update((o.category, h) for h in hits)
        print(f'{rt}: {overlapping} of {objects} first-tier objects in {len(rooms.scenes)} '
              f'rooms overlap another one')
        for c, n in by_category.most_common(args.top):
            print(f'  {c}: {n} of {in_category[c]}')
        for (a, b), n in pairs.most_common(args.top):
            print(f'  {a} over {b}: {n}')


if __name__ == '__main__':
    main()
