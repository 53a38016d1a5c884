"""scene_synth_node under load and hostile input, over Fast DDS (loopback): issue 12's targets.

    .venv/bin/python benchmarks/node_load.py [--clients 10] [--calls 50] [--fuzz 10000]
                                             [--mixed 1000] [--retry both|on|off]
                                             [--domain-id N]

1. Load: ``--clients`` processes each make ``--calls`` service calls (next_object 50 %,
   generate 30 %, reset 20 %) back to back, and every tenth call publish a layout (valid, or
   one of the bad inputs). A call is lost when no answer comes within 60 s. Run twice
   (``--retry both``): with "busy" answers returned to the caller, then retried by the client
   until served. Prints, per service, answers, "busy" answers, other failures, lost calls,
   median / p95 / max latency (of all answers and of the non-busy ones), and the calls per
   second the run took.
2. Fuzz: ``--fuzz`` layouts drawn from ``tests/fuzz.py`` published to the node (every 500th
   followed by a ``reset`` call that must be answered); then the node must still furnish a
   valid layout. Prints node deaths, wedges, and the largest /diagnostics message.
3. Memory: the node's resident memory before and after ``--mixed`` inputs (valid layouts,
   bad ones, payloads of 1-7 MB, service calls) past a warm-up of 100.
4. SIGTERM with three calls in flight: exit code and seconds to exit.
"""
import argparse
from collections import Counter
import json
import multiprocessing as mp
import os
from pathlib import Path
import random
import signal
import statistics
import sys
import tempfile
import threading
import time

from benchlib import invalid_layout, layout_text, rss_mb, tests_module

from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.ros_client import (
    ClientError,
    SceneSynthClient,
    start_node,
    stop_node,
)

SERVICES = ('next_object', 'generate', 'reset')
WEIGHTS = (0.5, 0.3, 0.2)
CALL_TIMEOUT = 60.0


def _client(args) -> list[tuple[str, float, str, str]]:
    """One client process: (service, seconds, outcome, why it failed) per call; outcome is
    'ok', 'busy', 'failed' or 'lost'."""
    domain, index, calls, retry = args
    rng = random.Random(index)
    out = []
    with SceneSynthClient(domain_id=domain) as client:
        client.spin_until(client.ready, 60.0, 'services')
        for k in range(calls):
            if k % 10 == 9:
                text = (layout_text(rng.choice(ROOM_TYPES), rng.randrange(50))
                        if rng.random() < 0.7 else invalid_layout(rng, k))
                client.publish_layout(text, wait=False, check=False)
            service = rng.choices(SERVICES, WEIGHTS)[0]
            t0 = time.perf_counter()
            why = ''
            try:
                ok, message = client.call(service, timeout=CALL_TIMEOUT, retry_busy=retry)
                outcome = 'ok' if ok else 'busy' if message.startswith('busy:') else 'failed'
                if outcome == 'failed':
                    why = ' '.join(message.split()[:2])
            except ClientError:
                outcome = 'lost'
            out.append((service, time.perf_counter() - t0, outcome, why))
    return out


def _p95(values: list[float]) -> float:
    return sorted(values)[min(len(values) - 1, int(0.95 * len(values)))] if values else 0.0


def load(domain: int, clients: int, calls: int, retry: bool) -> None:
    counters = ('rooms served', 'requests superseded', 'requests answered busy')
    before = _counters(domain, counters)
    ctx = mp.get_context('spawn')
    with ctx.Pool(clients) as pool:
        t0 = time.perf_counter()
        results = pool.map(_client, [(domain, i, calls, retry) for i in range(clients)])
        wall = time.perf_counter() - t0
    records = [r for rs in results for r in rs]
    print(f'\n1. load: {clients} clients x {calls} calls, "busy" answers '
          f'{"retried by the client until answered" if retry else "counted as answers"}; '
          f'{wall:.1f} s, {len(records) / wall:.1f} calls/s (start-up included)')
    print(f'   {"service":12s} {"answers":>7s} {"busy":>5s} {"failed":>6s} {"lost":>5s} '
          f'{"median":>7s} {"p95":>7s} {"max":>7s}   (s; non-busy: median p95 max)')
    for s in SERVICES:
        mine = [r for r in records if r[0] == s]
        answered = [t for _, t, o, _ in mine if o != 'lost']
        served = [t for _, t, o, _ in mine if o in ('ok', 'failed')]
        n = {o: sum(1 for _, _, x, _ in mine if x == o) for o in ('ok', 'busy', 'failed', 'lost')}
        print(f'   {s:12s} {len(answered):7d} {n["busy"]:5d} {n["failed"]:6d} {n["lost"]:5d} '
              + (f'{statistics.median(answered):7.3f} {_p95(answered):7.3f} '
                 f'{max(answered):7.3f}' if answered else f'{"–":>7s}' * 3)
              + (f'   {statistics.median(served):.3f} {_p95(served):.3f} {max(served):.3f}'
                 if served else ''))
    busy = [t for _, t, o, _ in records if o == 'busy']
    if busy:
        print(f'   "busy" answers: {len(busy)}, median {statistics.median(busy):.3f} s, '
              f'p95 {_p95(busy):.3f} s')
    whys = Counter(f'{s} {why}' for s, _, o, why in records if o == 'failed')
    print('   failed: ' + ', '.join(f'{k} ({n})' for k, n in whys.most_common()))
    after = _counters(domain, counters)
    print('   the node, over the run: ' + ', '.join(f'{k} {after[k] - before[k]}'
                                                  for k in counters))


def _counters(domain: int, names) -> dict[str, int]:
    """The node's counters from /diagnostics."""
    with SceneSynthClient(domain_id=domain) as client:
        diag = client.diagnostics(timeout=10.0)
    return {k: int(diag[k]) for k in names}


def _diag_bytes(client: SceneSynthClient) -> int:
    worst = 0
    for *_, msg in client.received['diagnostics']:
        for st in msg.status:
            size = len(st.message.encode()) + sum(len(v.key.encode()) + len(v.value.encode())
                                                 for v in st.values)
            worst = max(worst, size)
    return worst


def fuzz(domain: int, proc, n: int) -> None:
    from hypothesis import HealthCheck, given, settings
    if n <= 0:
        return
    layouts = tests_module('fuzz').layouts
    deaths = wedges = sent = 0
    worst_diag = 0
    t0 = time.perf_counter()
    with SceneSynthClient(domain_id=domain) as client:
        client.spin_until(client.ready, 60.0, 'services')

        @settings(max_examples=n, database=None, deadline=None,
                  suppress_health_check=list(HealthCheck))
        @given(layouts(wild=False) | layouts())
        def send(layout):
            nonlocal sent, wedges, worst_diag
            try:
                text = json.dumps(layout)
            except ValueError:
                text = '{"room_type": "bedroom", "floor": [[0, 0], [1' + '0' * 4400 + ', 0]]}'
            client.publish_layout(text, wait=False, check=False)
            sent += 1
            client.executor.spin_once(timeout_sec=0.0)
            if sent % 500 == 0:
                try:
                    client.call('reset', timeout=CALL_TIMEOUT)
                except ClientError:
                    wedges += 1
                worst_diag = max(worst_diag, _diag_bytes(client))
        send()
        alive = proc.poll() is None
        deaths += not alive
        if alive:
            try:
                client.call('reset', timeout=CALL_TIMEOUT)
                client.publish_layout(layout_text('bedroom', 0), timeout=CALL_TIMEOUT)
            except ClientError:
                wedges += 1
        worst_diag = max(worst_diag, _diag_bytes(client))
    print(f'\n2. fuzz: {sent} fuzzed layouts through the node in {time.perf_counter() - t0:.0f} s: '
          f'{deaths} deaths, {wedges} wedges; largest /diagnostics status '
          f'{worst_diag} bytes')


def memory(domain: int, proc, n: int) -> None:
    if n <= 0:
        return
    rng = random.Random(1)
    with SceneSynthClient(domain_id=domain) as client:
        client.spin_until(client.ready, 60.0, 'services')

        def one(k):
            r = rng.random()
            if r < 0.4:
                client.publish_layout(layout_text(rng.choice(ROOM_TYPES), rng.randrange(200)),
                                      timeout=CALL_TIMEOUT, check=False)
            elif r < 0.67:
                client.publish_layout(invalid_layout(rng, k), wait=False, check=False)
            elif r < 0.7:                   # past the payload limit: refused unread
                client.publish_layout('{"room_type": "' + 'x' * rng.randrange(1, 8) * 2**20,
                                      wait=False, check=False)
            else:
                client.call(rng.choice(SERVICES), timeout=CALL_TIMEOUT)
        for k in range(100):
            one(k)
        before = rss_mb(proc.pid)
        for k in range(n):
            one(k)
        client.call('reset', timeout=CALL_TIMEOUT)
        after = rss_mb(proc.pid)
    print(f'\n3. memory: resident {before:.0f} MB after 100 warm-up inputs, {after:.0f} MB after '
          f'{n} more: growth {after - before:+.1f} MB')


def sigterm(domain: int, proc) -> None:
    with SceneSynthClient(domain_id=domain) as client:
        client.spin_until(client.ready, 60.0, 'services')
        client.publish_layout(layout_text('living', 3), timeout=CALL_TIMEOUT)
    callers = [threading.Thread(target=_call_quietly, args=(domain,)) for _ in range(3)]
    for t in callers:
        t.start()
    time.sleep(1.0)
    t0 = time.perf_counter()
    code = stop_node(proc, signal.SIGTERM, timeout=30.0)
    print(f'\n4. SIGTERM with 3 calls in flight: exit code {code} after '
          f'{time.perf_counter() - t0:.2f} s')
    for t in callers:
        t.join(10)


def _call_quietly(domain: int) -> None:
    try:
        with SceneSynthClient(domain_id=domain) as client:
            client.spin_until(client.ready, 30.0, 'services')
            client.call('generate', timeout=10.0)
    except ClientError:
        pass


def main() -> int:
    # The node and its clients find each other on this machine only (loopback); the
    # node's process and the clients' inherit it.
    os.environ.setdefault('ROS_AUTOMATIC_DISCOVERY_RANGE', 'LOCALHOST')
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--clients', type=int, default=10)
    ap.add_argument('--calls', type=int, default=50)
    ap.add_argument('--fuzz', type=int, default=10000)
    ap.add_argument('--mixed', type=int, default=1000)
    ap.add_argument('--retry', choices=('both', 'on', 'off'), default='both',
                    help='load run with "busy" answers retried by the client (on), returned '
                         '(off), or one of each (both)')
    ap.add_argument('--domain-id', type=int, default=random.randrange(150, 230))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        log = open(Path(tmp) / 'node.log', 'w')
        proc = start_node(args.domain_id, {'torch_threads': 1}, log)
        try:
            with SceneSynthClient(domain_id=args.domain_id) as client:
                client.spin_until(client.ready, 120.0, 'services')
                client.publish_layout(layout_text('bedroom', 0), timeout=CALL_TIMEOUT)
            print(f'node pid {proc.pid}, domain {args.domain_id}, resident '
                  f'{rss_mb(proc.pid):.0f} MB after its first room')
            if args.clients > 0:
                for retry in {'both': (False, True), 'on': (True,), 'off': (False,)}[args.retry]:
                    load(args.domain_id, args.clients, args.calls, retry)
            fuzz(args.domain_id, proc, args.fuzz)
            memory(args.domain_id, proc, args.mixed)
            sigterm(args.domain_id, proc)
        finally:
            stop_node(proc)
            log.close()
            text = (Path(tmp) / 'node.log').read_text()
            print(f'\nnode log: {text.count("Traceback")} tracebacks, '
                  f'{text.count("[ERROR]")} errors, {text.count("[WARN]")} warnings, '
                  f'{len(text.encode())} bytes')
    return 0


if __name__ == '__main__':
    sys.exit(main())
