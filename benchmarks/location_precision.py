"""How close to a wall a *perfect* location module could put wall furniture, at the shipped
location grid: the ceiling that the grid and the training target set on ``wall_contact``.

    .venv/bin/python benchmarks/location_precision.py [-n 300] [--room-type all] [--radius 1]

For every piece of wall furniture in held-out corpus rooms (seed ``corpus.HELDOUT_SEED``) the
piece is moved to a location drawn the way the synthesizer draws one from a location
distribution equal to the training target (a pixel of the (2r+1)^2 block around the
centroid's pixel, then a uniform point inside it; ``--radius`` is the config's
``location_target_radius``), keeping its true orientation and size. The rate of
``wall_contact`` (back within 10 cm of its wall) is printed for: the true positions; such
draws from the target; the centroid's own pixel (the paper's one-pixel target); and each of
those after ``synth.against_walls`` (15 cm reach), the step the synthesizer applies. The
metres per pixel of the grid are printed alongside.
"""
import argparse
from dataclasses import replace
from pathlib import Path
import sys

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from scene_synth_ros.categories import CATEGORIES, ROOM_TYPES  # noqa: E402
from scene_synth_ros.corpus import HELDOUT_SEED  # noqa: E402
from scene_synth_ros.corpus.generate import generate_corpus  # noqa: E402
from scene_synth_ros.evaluation.design_rules.walls import measure_wall_contact  # noqa: E402
from scene_synth_ros.networks.config import PipelineConfig  # noqa: E402
from scene_synth_ros.render import Frame  # noqa: E402
from scene_synth_ros.scene import Scene  # noqa: E402
from scene_synth_ros.synth import SynthConfig, against_walls  # noqa: E402


def moved(scene: Scene, grid: Frame, rng: np.random.Generator, radius: int | None,
          push: bool) -> Scene:
    """The scene with every wall piece moved to a location drawn from its target (radius
    None: left where it is), then pushed onto the walls if ``push``."""
    out = []
    for o in scene.objects:
        if o.support is None and CATEGORIES[o.category].against_wall:
            if radius is not None:
                i, j = grid.world_to_pixel(o.position[:2])
                ij = np.array([i, j]) + rng.integers(-radius, radius + 1, size=2)
                xy = grid.pixel_to_world(ij + rng.uniform(-0.5, 0.5, size=2))
                o = replace(o, position=(float(xy[0]), float(xy[1]), o.position[2]))
            if push:
                o = against_walls(scene.room, o, SynthConfig().wall_reach, rng)
        out.append(o)
    return Scene(scene.room, out, scene.meta)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=300, help='held-out rooms per room type')
    ap.add_argument('--room-type', default='all')
    ap.add_argument('--radius', type=int, default=1, help='target radius in pixels')
    ap.add_argument('--config', default=str(ROOT / 'config' / 'compact.yaml'))
    args = ap.parse_args()
    resolution = PipelineConfig.from_yaml(args.config).model.location_resolution
    room_types = ROOM_TYPES if args.room_type == 'all' else (args.room_type,)
    print(f'wall_contact of wall furniture at a {resolution} px location grid, {args.n} '
          'held-out corpus rooms per type')
    print(f'{"room type":10s} {"cm/px":>6s} {"true":>7s} {"target":>7s} {"+push":>7s} '
          f'{"pixel":>7s} {"+push":>7s}')
    for rt in room_types:
        rooms = list(generate_corpus(rt, args.n, seed=HELDOUT_SEED))
        rng = np.random.default_rng(0)
        kept = np.zeros((5, 2), dtype=int)
        cm = []
        for s in rooms:
            grid = Frame.for_room(s.room, resolution)
            cm.append(100 * grid.metres_per_pixel)
            variants = [(None, False), (args.radius, False), (args.radius, True), (0, False),
                        (0, True)]
            for k, (radius, push) in enumerate(variants):
                kept[k] += measure_wall_contact(moved(s, grid, rng, radius, push))
        rates = [f'{k / n:7.1%}' if n else f'{"–":>7s}' for k, n in kept]
        print(f'{rt:10s} {np.median(cm):6.1f} ' + ' '.join(rates))
    return 0


if __name__ == '__main__':
    sys.exit(main())
