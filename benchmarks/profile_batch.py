"""Where a batch worker's time goes: ``-n`` rooms of ``--room-type`` furnished by one
``batch.Worker`` in lockstep (``--lockstep R``, one group, one torch thread), sampled every
``--interval`` seconds of CPU time (a ``SIGPROF`` timer), printed as the share of samples in
which each function of the package was on the stack (inclusive) and the functions, of any
module, that were running (self). A room in lockstep runs in a greenlet of its own: its stack
starts at its synthesis call, so the lockstep coordinator's share is that of the forward
passes it serves.

    .venv/bin/python benchmarks/profile_batch.py [-n 400] [--lockstep 8]
        [--room-type bedroom] [--interval 0.002] [--top 40]

Unlike cProfile, sampling leaves the speed of small Python functions alone; the shares are
of this run's CPU time, start-up included (the worker's first room loads the weights).
"""
import argparse
from collections import Counter
from pathlib import Path
import signal
import sys
import time

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


def _where(code) -> str:
    path = code.co_filename
    for marker in ('site-packages/', f'{ROOT.as_posix()}/'):
        if marker in path:
            path = path.split(marker, 1)[1]
    return f'{path}:{code.co_name}'


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('-n', type=int, default=400)
    ap.add_argument('--lockstep', type=int, default=8)
    ap.add_argument('--room-type', default='bedroom')
    ap.add_argument('--interval', type=float, default=0.002)
    ap.add_argument('--top', type=int, default=40)
    args = ap.parse_args()
    if args.n < 1 or args.lockstep < 1 or args.interval <= 0:
        print('-n and --lockstep must be at least 1 and --interval positive')
        return 2
    from scene_synth_ros.batch import RoomGroup, Source, Worker, WorkerSpec
    from scene_synth_ros.synth import SynthConfig
    inclusive, running = Counter(), Counter()
    samples = [0]

    def sample(_sig, frame):
        samples[0] += 1
        running[_where(frame.f_code)] += 1
        seen = set()
        while frame is not None:
            where = _where(frame.f_code)
            if where not in seen:
                seen.add(where)
                inclusive[where] += 1
            frame = frame.f_back

    jobs = Source.shells([args.room_type]).jobs(0, args.n)
    group = RoomGroup(jobs, frozenset(j.index for j in jobs), args.lockstep)
    signal.signal(signal.SIGPROF, sample)
    signal.setitimer(signal.ITIMER_PROF, args.interval, args.interval)
    t0, c0 = time.perf_counter(), time.process_time()
    worker = Worker(WorkerSpec('generate', None, SynthConfig()))
    rooms = list(worker.furnish_group(group))
    signal.setitimer(signal.ITIMER_PROF, 0, 0)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    ok = sum(r.row['status'] == 'ok' for r in rooms)
    print(f'{len(rooms)} {args.room_type}s ({ok} ok), {args.lockstep} in lockstep: '
          f'{1000 * wall / len(rooms):.1f} ms a room, {1000 * cpu / len(rooms):.1f} ms of CPU; '
          f'{samples[0]} samples')
    n = max(samples[0], 1)
    print('inclusive (functions of the package on the stack):')
    ours = [(k, v) for k, v in inclusive.most_common() if k.startswith('scene_synth_ros/')]
    for where, count in ours[:args.top]:
        print(f'  {100 * count / n:5.1f} %  {where}')
    print('self (the function running):')
    for where, count in running.most_common(args.top // 2):
        print(f'  {100 * count / n:5.1f} %  {where}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
