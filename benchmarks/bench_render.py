"""Speed of the top-down renderer on a furnished 15-object bedroom.

Prints the median milliseconds per render (over ``--repeats`` renders, default 300) at 64 and
256 px for:
the global view with a warm room cache (the synthesis loop's case), the global view with the
cache cleared before every render (cold), and ``render_local`` at a new point and yaw every
time (each one is a new frame, so the architecture is rasterised anew).

    .venv/bin/python benchmarks/bench_render.py [--repeats 300]
"""
from __future__ import annotations

import argparse
import math
import statistics
import time

from scene_synth_ros import catalog
from scene_synth_ros.render import TopDownRenderer, num_channels
from scene_synth_ros.scene import Opening, PlacedObject, Room, Scene

REPEATS = 300


def bedroom_scene() -> Scene:
    """A hand-furnished 4.6 x 4.0 m bedroom with one door, two windows and 15 objects."""
    room = Room('bedroom', ((0.0, 0.0), (4.6, 0.0), (4.6, 4.0), (0.0, 4.0)),
                doors=(Opening('door', (3.9, 0.0), 0.9, 2.1),),
                windows=(Opening('window', (2.3, 4.0), 1.4, 1.3, 0.9),
                         Opening('window', (4.6, 2.2), 1.0, 1.3, 0.9)))
    objects: list[PlacedObject] = []

    def add(category, x, y, yaw, width, depth, on=None):
        v = catalog.nearest(category, width, depth)
        z = 0.0
        if on is not None:
            parent = next(o for o in objects if o.id == on)
            z = parent.top
        oid = f'{category.replace(" ", "_")}_{len(objects)}'
        objects.append(PlacedObject(oid, category, v.model_id, (x, y, z), yaw, v.size, on))
        return oid

    down, up, left, right = -math.pi / 2, math.pi / 2, math.pi, 0.0
    add('double bed', 2.3, 2.95, down, 1.6, 2.05)
    s1 = add('stand', 1.2, 3.75, down, 0.5, 0.42)
    s2 = add('stand', 3.4, 3.75, down, 0.5, 0.42)
    add('table lamp', 1.2, 3.75, down, 0.3, 0.3, on=s1)
    add('table lamp', 3.4, 3.75, down, 0.3, 0.3, on=s2)
    add('wardrobe', 0.3, 2.6, right, 1.8, 0.6)
    d = add('desk', 4.25, 0.95, left, 1.2, 0.65)
    add('office chair', 3.7, 0.95, right, 0.6, 0.6)
    add('laptop', 4.3, 0.95, left, 0.34, 0.24, on=d)
    dr = add('dresser', 1.2, 0.25, up, 1.2, 0.48)
    add('plant', 1.6, 0.25, up, 0.3, 0.3, on=dr)
    tv = add('tv stand', 0.25, 0.9, right, 1.2, 0.42)
    add('television', 0.25, 0.9, right, 1.1, 0.22, on=tv)
    add('floor lamp', 4.3, 3.7, 0.3, 0.4, 0.4)
    add('ottoman', 2.3, 1.55, up, 0.8, 0.5)
    return Scene(room, objects)


def median_ms(fn, repeats: int = REPEATS) -> float:
    for _ in range(10):
        fn(0)
    times = []
    for k in range(repeats):
        t0 = time.perf_counter()
        fn(k)
        times.append(time.perf_counter() - t0)
    return statistics.median(times) * 1e3


def timings_line(scene: Scene, res: int, repeats: int = REPEATS) -> str:
    """The three medians at ``res`` px, as one line."""
    r = TopDownRenderer(res)

    def warm(k):
        r.render(scene)

    def cold(k):
        r.clear_cache()
        r.render(scene)

    def local(k):
        r.render_local(scene, (1.0 + 0.01 * (k % 200), 1.5), 0.037 * k)

    return (f'{res:4d} px: global warm {median_ms(warm, repeats):7.3f} ms | '
            f'global cold {median_ms(cold, repeats):7.3f} ms | '
            f'render_local {median_ms(local, repeats):7.3f} ms')


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--repeats', type=int, default=REPEATS, help='timed renders per figure')
    args = ap.parse_args()
    scene = bedroom_scene()
    assert len(scene) == 15
    print(f'bedroom scene: {len(scene)} objects, {num_channels("bedroom")} channels, '
          f'median of {args.repeats} renders')
    for res in (64, 256):
        print(timings_line(scene, res, args.repeats))


if __name__ == '__main__':
    main()
