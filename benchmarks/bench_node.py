"""The node issue's targets, measured on a running scene_synth_node over Fast DDS (loopback).

1. Latency: publishing a bedroom layout -> its MarkerArray received (median <= 1 s).
2. ``~/next_object`` round trip (median <= 0.2 s).
3. 200 layouts in a row, valid and invalid mixed: the node survives, answers every valid one,
   and its resident memory grows by no more than 50 MB (measured after a warm-up).

    .venv/bin/python benchmarks/bench_node.py [--rooms 40] [--calls 60] [--soak 200]
        [--torch-threads 1] [--domain-id N]
"""
import argparse
import os
import platform
import random
import signal
import statistics
import sys
import tempfile
import time

from benchlib import invalid_layout, layout_text, rss_mb

from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.ros_client import SceneSynthClient, start_node, stop_node


def pct(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q * (len(values) - 1))))]


def main() -> int:
    # The node and its clients find each other on this machine only (loopback); the
    # node's process and the clients' inherit it.
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--rooms', type=int, default=40, help='bedroom layouts timed')
    ap.add_argument('--calls', type=int, default=60, help='next_object calls timed')
    ap.add_argument('--soak', type=int, default=200, help='layouts in the memory run')
    ap.add_argument('--invalid-every', type=int, default=4)
    ap.add_argument('--torch-threads', type=int, default=1)
    ap.add_argument('--domain-id', type=int, default=random.Random().randrange(150, 230))
    args = ap.parse_args()

    log = tempfile.NamedTemporaryFile('w', prefix='bench_node_', suffix='.log', delete=False)
    proc = start_node(args.domain_id, {'torch_threads': args.torch_threads}, log)
    print(f'{platform.processor() or platform.machine()}, {os.cpu_count()} cores, torch '
          f'threads {args.torch_threads}, ROS_DOMAIN_ID {args.domain_id}, node log {log.name}')
    code = 1
    try:
        with SceneSynthClient(domain_id=args.domain_id) as client:
            client.spin_until(lambda: proc.poll() is not None or client.ready(), 90, 'node')
            assert proc.poll() is None, f'node exited at start-up, see {log.name}'

            # 1. layout -> markers
            for k in range(3):     # warm-up: first rooms pay for lazy allocations
                client.publish_layout(layout_text('bedroom', 1000 + k), timeout=60)
            latencies, objects = [], []
            for k in range(args.rooms):
                text = layout_text('bedroom', k)
                n = client.count('markers')
                t0 = time.perf_counter()
                client.publish_layout(text, wait=False, check=False)
                client.spin_until(lambda n=n: client.count('markers') > n, 60, 'markers')
                latencies.append(time.perf_counter() - t0)
                objects.append(sum(1 for m in client.latest('markers').markers
                                   if m.ns == 'labels'))
            print(f'\nlayout -> MarkerArray, {args.rooms} bedrooms (held-out shells): median '
                  f'{statistics.median(latencies):.3f} s, mean {statistics.mean(latencies):.3f}, '
                  f'p90 {pct(latencies, 0.9):.3f}, max {max(latencies):.3f} '
                  f'({statistics.mean(objects):.1f} objects/room)  [target: median <= 1 s]')

            # 2. next_object round trips, on empty rooms filled one object at a time
            refused = client.set_parameters({'auto_generate': False})
            assert not refused, refused
            trips, k, misses = [], 0, 0
            while len(trips) < args.calls:
                client.publish_layout(layout_text('bedroom', 2000 + k), timeout=60)
                k += 1
                for _ in range(6):
                    t0 = time.perf_counter()
                    ok, message = client.call('next_object')
                    if not ok:
                        misses += 1
                        break
                    trips.append(time.perf_counter() - t0)
            client.set_parameters({'auto_generate': True})
            print(f'next_object round trip, {len(trips)} calls in {k} rooms: median '
                  f'{statistics.median(trips):.3f} s, mean {statistics.mean(trips):.3f}, '
                  f'p90 {pct(trips, 0.9):.3f}, max {max(trips):.3f} ({misses} rooms where '
                  f'nothing more fitted)  [target: median <= 0.2 s]')

            # 3. soak: valid and invalid layouts mixed
            rng = random.Random(0)
            for k in range(10):
                client.publish_layout(layout_text(ROOM_TYPES[k % len(ROOM_TYPES)], 3000 + k),
                                      timeout=60)
            start = rss_mb(proc.pid)
            valid = answered = rejected_sent = 0
            rejected0 = int(client.diagnostics()['inputs rejected'])
            t0 = time.perf_counter()
            for k in range(args.soak):
                if k % args.invalid_every == args.invalid_every - 1:
                    client.publish_layout(invalid_layout(rng, k), wait=False, check=False)
                    rejected_sent += 1
                    continue
                valid += 1
                d = client.publish_layout(layout_text(ROOM_TYPES[k % len(ROOM_TYPES)], 4000 + k),
                                          timeout=60)
                answered += d is not None
            client.spin_until(lambda: int(client.diagnostics()['inputs rejected'])
                              >= rejected0 + rejected_sent, 30, 'all rejections')
            end = rss_mb(proc.pid)
            alive = proc.poll() is None and client.call('reset')[0]
            print(f'soak: {args.soak} layouts ({valid} valid, {rejected_sent} invalid) in '
                  f'{time.perf_counter() - t0:.0f} s: answered {answered}/{valid} valid, '
                  f'rejected {int(client.diagnostics()["inputs rejected"]) - rejected0}/'
                  f'{rejected_sent} invalid, node alive: {alive}; RSS {start:.0f} -> {end:.0f} MB '
                  f'({end - start:+.1f} MB)  [target: <= +50 MB]')
            code = 0
    finally:
        exit_code = stop_node(proc, signal.SIGINT)
        log.close()
        print(f'node stopped with SIGINT: exit code {exit_code}')
    return code


if __name__ == '__main__':
    sys.exit(main())
