"""The node through its action, as a client sees it: start-up to serving, the first room's
latency and a typical room's latency.

    .venv/bin/python benchmarks/node_startup.py [-n 5] [--rooms 10] [--room-type bedroom]

Each of the ``n`` runs starts a fresh ``scene_synth_node`` (one torch thread, warm file
caches after the first run) and a client; start-up is the wall time from the process start
until the client has discovered every service and the ~/furnish action. Then the client
sends ``~/furnish`` goals of the example layout of the room type (its JSON text, seeds 0, 1,
...): the first room is the first goal's round trip (the networks' first passes included),
a typical room the median of the next ``--rooms``. Prints the median and range of each over
the runs.
"""
import argparse
import os
from pathlib import Path
import random
import statistics
import sys
import time

from scene_synth_ros.paths import examples_dir
from scene_synth_ros.ros_client import SceneSynthClient, start_node, stop_node

LAYOUTS = {'bedroom': 'bedroom_layout.json', 'kitchen': 'kitchen_layout.json',
           'living': 'lshaped_living_layout.json'}


def one_run(domain: int, layout: str, rooms: int) -> tuple[float, float, float]:
    t0 = time.perf_counter()
    proc = start_node(domain, {'torch_threads': 1})
    client = SceneSynthClient(domain_id=domain)
    try:
        client.spin_until(lambda: proc.poll() is not None or client.ready(), 120.0,
                          'services')
        if proc.poll() is not None:
            sys.exit(f'the node exited with {proc.returncode}')
        started = time.perf_counter() - t0
        t = time.perf_counter()
        client.furnish(layout, seed=0)
        first = time.perf_counter() - t
        times = []
        for seed in range(1, rooms + 1):
            t = time.perf_counter()
            client.furnish(layout, seed=seed)
            times.append(time.perf_counter() - t)
        return started, first, statistics.median(times)
    finally:
        client.close()
        stop_node(proc)


def main() -> int:
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=5, help='node starts')
    ap.add_argument('--rooms', type=int, default=10, help='typical rooms timed per start')
    ap.add_argument('--room-type', default='bedroom', choices=sorted(LAYOUTS))
    ap.add_argument('--domain-id', type=int, default=None)
    args = ap.parse_args()
    layout = (examples_dir() / LAYOUTS[args.room_type]).read_text()
    domain = args.domain_id or random.Random().randrange(100, 200)
    runs = [one_run(domain, layout, args.rooms) for _ in range(args.n)]
    print(f'scene_synth_node through ~/furnish, {args.room_type} '
          f'({Path(LAYOUTS[args.room_type]).name}), {args.n} starts, one torch thread')
    for name, values in zip(('start-up to serving', 'first room', 'typical room'),
                            zip(*runs, strict=True), strict=True):
        print(f'  {name:20s} median {statistics.median(values):6.2f} s   '
              f'range {min(values):.2f} to {max(values):.2f} s')
    return 0


if __name__ == '__main__':
    sys.exit(main())
