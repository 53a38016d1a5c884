"""Batches of furnished rooms: thousands of rooms on every core of one machine, or on a Ray
cluster, written into one directory that a second run resumes.

Room ``i`` of a batch (``i`` = 0 .. n-1) is furnished with the synthesis seed ``seed + i``,
in the ``i``-th room of its source (``Source``; the manifest's ``layout`` in brackets):

- shells (``generate -n``): the shell of the first attempt at corpus room (type, ``seed``,
  ``i``), ``corpus.generate.first_shell`` (the corpus room's own shell in 92-98.5 % of rooms,
  drawn without furnishing the corpus room); several room types (``all``) are cycled, room
  ``i`` being of the ``i % k``-th (``bedroom shell: corpus seed 0, room 42``);
- one layout or partial room (``generate --layout F -n``, ``complete F -n``): that room every
  time (``F``);
- a directory (``--layouts DIR``, ``complete DIR``): its ``*.json``, ``*.yaml`` and ``*.yml``
  files in name order (the file's name);
- a JSON-lines file (``*.jsonl``): its non-blank lines (``rooms.jsonl:17``, the line).

So room 0 of ``generate -n N --seed S`` is the room of ``generate --seed S``, and any room is
made again alone from its scene file and seed (``generate --layout
DIR/scenes/room_000042.json --seed 42``): to the last digit with ``--lockstep 1`` when torch
has one thread there too (the one-room command uses every core, which changes the last digits
of the networks' sums), and in lockstep nearly always the same room (see Determinism).
``generate`` furnishes from empty (objects in the input are dropped); ``complete`` keeps them
and adds the rest.

The directory::

    batch.json        what the rooms are: command, seed, source, synthesis options, lockstep
                      R, weights.
                      A later run into the directory must ask for the same rooms; -n, the
                      workers, the thumbnails and the exports may change.
    manifest.jsonl    one JSON row per room, appended as its worker sends it back, when
                      the room ends (also in lockstep), so a killed run loses only the
                      rooms under way; sorted by index when a run ends
    summary.json      the counts of the manifest and the last run's speed and memory
    scenes/room_000042.json
    png/room_000042.png              (--png: a 240-pixel thumbnail)
    <format>/room_000042.<ext>       (--export: the suffixes of ``export.FORMATS``)
    <format>/meshes/                 the catalog models of that format's files, written once
                                     and named relatively, so each format's folder moves whole

A row: ``index``, ``room``, ``status`` (``ok`` or ``error``), ``seed``, ``layout``, then for
a room furnished ``room_type``, ``area``, ``objects``, ``added``, ``stopped``, ``valid``
(``geometry.check_scene``), ``robot_kept`` (the robot promise) and ``files``; for one that
failed ``error``, the package's one-sentence reason. Every row has ``seconds`` (wall time),
``cpu_seconds`` (the worker process's CPU time over the same span: on a shared machine a
steadier measure of what a room costs) and the ``worker`` (host:pid) with its resident and
peak memory (``rss_mb``, ``peak_mb``).

Rooms in lockstep (``lockstep``, ``--lockstep R``): the rooms of index ``kG`` to ``kG + G -
1`` form group ``k`` (``G = GROUP_ROUNDS * R``; ``G = 1`` for R = 1), furnished by one worker
R at a time, in index order, the next room starting when one ends, each module's forward
pass batched across the rooms under way (``lockstep.each``). A room's ``seconds`` in the
manifest is then the group's wall time from the end of the room before it (from the start of
the group for the first), so that the rooms of a group add up to its time (``cpu_seconds``
likewise).

Determinism: a room depends only on its index, the seed, its source, the synthesis options,
the lockstep R and the weights, never on which worker furnished it or when. Every worker has a
Synthesizer of its own and one torch thread, synthesis draws everything from the room's seed,
and a group is always the same rooms, run from its first: a group of which only some rooms
are to be written (a run that resumes it, the last one, cut by ``-n``) is run as far as those
need, which is how far it would run whole. Timings live in the manifest, not in the scene
files, so the same batch made by 1 or 2 processes or by Ray actors, with any ``-n``, gives
byte-identical scene files. Rooms in lockstep are equal in distribution to rooms made one at a
time, and nearly all are the same rooms (``lockstep``); with ``--lockstep 1`` each is the very
room of the one-room command.

Resumption: a room is skipped when the manifest has an ``ok`` row for it and every file this
run asks for (scene, thumbnail, exports) exists; a room's row is appended only after its
files are in place. A room that failed is tried again.

Workers: ``parallel.process_executor`` processes, or Ray actors (``ray``, an optional
dependency), one group of rooms at a time each. Workers send back each room as it ends (a
process through a queue, an actor as a Ray generator), with the bytes of its files, and the
driver alone writes them (atomically, ``files.write_atomic``), so the output
directory need exist only where the command runs, also on a cluster.
"""
from __future__ import annotations

from collections import deque
from contextlib import closing
from dataclasses import asdict, dataclass, field, replace
import json
import os
from pathlib import Path
import pickle
import signal
import socket
import sys
import tempfile
import time
from typing import Callable, Iterator

from . import lockstep
from .categories import PAPER, Vocabulary
from .errors import SceneSynthError, quoted, sentence
from .files import write_atomic
from .limits import MAX_PAYLOAD_BYTES
from .networks.config import resolve_device, resolve_runtime
from .synth import SynthConfig
from .user_catalog import load_catalog

LAYOUT_SUFFIXES = ('.json', '.yaml', '.yml')
SCENES, THUMBNAILS = 'scenes', 'png'
MESHES = 'meshes'                  # a format folder's shared models
THUMBNAIL = {'figsize': (3.0, 3.0), 'dpi': 80, 'legend': False}   # 240 x 240 px
# tqdm's bar with the rate always in rooms per second (its default turns slow rates over).
PROGRESS = ('{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} '
            '[{elapsed}<{remaining}, {rate_noinv_fmt}{postfix}]')
# Rooms in lockstep beyond this gain nothing on a CPU (``benchmarks/bench_batch.py``) and only
# hold more rooms' memory.
MAX_LOCKSTEP = 64
# A group is this many times R rooms: enough that the rounds in which the group's last rooms
# finish, with fewer rooms under way, are few among its rounds; few enough that a resumed
# group redoes little.
GROUP_ROUNDS = 8
# Groups of rooms queued at each worker, so that it starts the next group while the driver
# is still writing the last one's files.
IN_FLIGHT = 2
# How long the driver waits for a room before it looks at which groups have ended.
POLL_SECONDS = 0.1
LOST = ('its worker process died while this room or another one was in flight (killed, or '
        'out of memory?); run the batch again to retry it')


class BatchError(SceneSynthError):
    """A batch that cannot start (bad options, an unusable directory), in one sentence."""


def available_formats() -> list[str]:
    """The export formats a batch can write (``export.FORMATS``)."""
    from .export import FORMATS
    return list(FORMATS)


def room_name(index: int) -> str:
    return f'room_{index:06d}'


def output_files(name: str, png: bool, exports: tuple[str, ...]) -> list[str]:
    """The files of room ``name`` that a run asks for, relative to the batch directory; the
    scene last (see ``Worker.files``)."""
    from .export import FORMATS
    files = [f'{THUMBNAILS}/{name}.png'] if png else []
    files += [f'{fmt}/{name}{FORMATS[fmt].suffix}' for fmt in exports]
    return files + [f'{SCENES}/{name}.json']


def _shared(rel: str) -> bool:
    """Whether ``rel`` is one of a format folder's shared model files."""
    parts = rel.split('/')
    return len(parts) > 2 and parts[1] == MESHES


# ---- sources ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class RoomJob:
    """Everything a worker needs to furnish room ``index``: a shell to draw, or a document."""

    index: int
    seed: int
    layout: str                     # where the room comes from, as the manifest names it
    room_type: str | None = None    # a shell of this type (corpus seed ``shell_seed``)...
    shell_seed: int = 0
    data: bytes | None = None       # ...or a layout or scene, JSON or YAML
    problem: str | None = None      # why the document could not be read

    @property
    def name(self) -> str:
        return room_name(self.index)


def _read_document(path: Path) -> tuple[bytes | None, str | None]:
    # One byte past the limit is enough for the schema's reader to refuse it in one sentence.
    try:
        with open(path, 'rb') as f:
            return f.read(MAX_PAYLOAD_BYTES + 1), None
    except OSError as e:
        return None, f'{path.name} cannot be read: {e.strerror or e}'


def _jsonl_lines(path: Path) -> Iterator[tuple[int, bytes]]:
    """(line number, text) of every non-blank line; a line past the payload limit is cut
    there (the reader then refuses it) and the rest of it skipped."""
    with open(path, 'rb') as f:
        number = 0
        while True:
            line = f.readline(MAX_PAYLOAD_BYTES + 1)
            if not line:
                return
            number += 1
            if len(line) > MAX_PAYLOAD_BYTES and not line.endswith(b'\n'):
                rest = line
                while rest and not rest.endswith(b'\n'):
                    rest = f.readline(MAX_PAYLOAD_BYTES)
            if line.strip():
                yield number, line


@dataclass(frozen=True)
class Source:
    """Where a batch's rooms come from (see the module docstring)."""

    kind: str                       # 'shells', 'file', 'directory' or 'jsonl'
    room_types: tuple[str, ...] = ()
    path: str = ''

    @classmethod
    def shells(cls, room_types, vocabulary: Vocabulary = PAPER) -> Source:
        types = tuple(vocabulary.resolve(t) for t in room_types)
        if not types:
            raise BatchError('shells need at least one room type')
        own = [t for t in types if vocabulary.defines(t)]
        if own:
            raise BatchError(f'{own[0]} is a room type of the data set the weights were '
                             f'trained on, and the corpus makes only the paper\'s rooms: '
                             f'give --layouts')
        return cls('shells', types)

    @classmethod
    def at(cls, path: str | os.PathLike) -> Source:
        """A directory of layouts, a JSON-lines file or one layout or scene file."""
        p = Path(path)
        if p.is_dir():
            return cls('directory', path=str(p.resolve()))
        if not p.is_file():
            raise BatchError(f'{path}: no such file or directory')
        return cls('jsonl' if p.suffix.lower() == '.jsonl' else 'file', path=str(p.resolve()))

    @property
    def finite(self) -> bool:
        """Whether the source has a number of rooms of its own (else -n is needed)."""
        return self.kind in ('directory', 'jsonl')

    def identity(self) -> dict:
        # Shells name how they are drawn: a directory whose rooms are the corpus rooms' own
        # shells (before first_shell) must not be resumed with others.
        return ({'kind': self.kind, 'room_types': list(self.room_types),
                 'shells': 'first attempt'}
                if self.kind == 'shells' else {'kind': self.kind, 'path': self.path})

    def jobs(self, seed: int, n: int | None) -> list[RoomJob]:
        """Rooms 0 .. n-1 (every room of a finite source when ``n`` is None); documents of a
        directory are read later, by ``load``, for the rooms still to do."""
        path = Path(self.path)
        if self.kind == 'shells':
            k = len(self.room_types)
            return [RoomJob(i, seed + i, f'{self.room_types[i % k]} shell: corpus seed {seed}, '
                            f'room {i}', room_type=self.room_types[i % k], shell_seed=seed)
                    for i in range(n)]
        if self.kind == 'file':
            return [RoomJob(i, seed + i, str(path)) for i in range(n)]
        if self.kind == 'directory':
            try:
                names = sorted(p.name for p in path.iterdir()
                               if p.suffix.lower() in LAYOUT_SUFFIXES and p.is_file())
            except OSError as e:
                raise BatchError(f'{path}: cannot be listed: {e.strerror or e}') from None
            if not names:
                raise BatchError(f'{path} holds no room layouts (*.json, *.yaml, *.yml)')
            return [RoomJob(i, seed + i, name) for i, name in enumerate(names[:n])]
        jobs = []
        try:
            for i, (number, line) in enumerate(_jsonl_lines(path)):
                if n is not None and i >= n:
                    break
                jobs.append(RoomJob(i, seed + i, f'{path.name}:{number}', data=line))
        except OSError as e:
            raise BatchError(f'{path}: cannot be read: {e.strerror or e}') from None
        if not jobs:
            raise BatchError(f'{path} holds no room layouts (one JSON layout a line)')
        return jobs

    def load(self, job: RoomJob) -> RoomJob:
        """``job`` with its document read, or with why it could not be."""
        if self.kind not in ('file', 'directory'):
            return job
        path = Path(self.path) if self.kind == 'file' else Path(self.path) / job.layout
        data, problem = _read_document(path)
        return RoomJob(job.index, job.seed, job.layout, data=data, problem=problem)


def scene_from_document(data: bytes, models=None, vocabulary: Vocabulary = PAPER):
    """A scene or room layout (JSON or YAML) as a validated Scene, as ``schema.load_scene``
    reads a file; model ids are those of ``models`` (a ``catalog.Catalog``, default the
    procedural one), room types and categories those of ``vocabulary``."""
    from .schema import parse_room_layout, parse_scene, read_payload
    d = read_payload(data)
    if isinstance(d, dict) and 'room' not in d:
        return parse_room_layout(d, models, vocabulary)
    return parse_scene(d, models, vocabulary)


# ---- workers ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class WorkerSpec:
    """What every worker is started with."""

    mode: str                       # 'generate' or 'complete'
    weights_dir: str | None
    synthesis: SynthConfig
    png: bool = False
    exports: tuple[str, ...] = ()


@dataclass(frozen=True)
class RoomGroup:
    """A lockstep group for one worker: its rooms, the indices of those to furnish (the run
    ends when they are done), and how many rooms are under way at a time."""

    jobs: list[RoomJob]
    needed: frozenset[int]
    width: int

    def lost(self, back: frozenset[int] | set[int] = frozenset()) -> list[RoomResult]:
        """The rows of its needed rooms but those that came ``back`` from its worker, for a
        worker that died with the group in flight."""
        return [_lost(j) for j in self.jobs if j.index in self.needed - back]


@dataclass
class RoomResult:
    row: dict
    files: dict[str, bytes]         # relative path -> content, in the order to write them


def _memory_mb() -> tuple[float | None, float | None]:
    """(resident, peak resident) memory of this process in MB, where the platform says."""
    try:
        import resource
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024   # KB on Linux
    except ImportError:                                                     # Windows
        peak = None
    try:
        with open('/proc/self/statm') as f:
            rss = int(f.read().split()[1]) * os.sysconf('SC_PAGE_SIZE') / 2**20
    except (OSError, ValueError, IndexError):
        rss = None
    return rss, peak


class Worker:
    """Furnishes one room at a time with a Synthesizer of its own and one torch thread."""

    def __init__(self, spec: WorkerSpec):
        import torch

        from .synth import Synthesizer
        # One thread each: the workers are the parallelism, and threads fighting over the
        # same cores are slower than one each.
        torch.set_num_threads(1)
        self.spec = spec
        self.synth = Synthesizer(spec.weights_dir, spec.synthesis)
        self.name = f'{socket.gethostname()}:{os.getpid()}'
        self.shipped: set[str] = set()      # shared model files already sent to the driver

    def furnish_group(self, group: RoomGroup) -> Iterator[RoomResult]:
        """The rooms of ``group`` furnished in lockstep (see the module docstring), each as
        it ends: the needed ones, and any other that ended before the needed ones had. A
        room's ``seconds`` is the group's wall time since the room before it ended (since
        the start for the first), so that a group's rooms add up to its time."""
        jobs = group.jobs
        last, last_cpu = time.perf_counter(), time.process_time()
        for _, result in lockstep.each([lambda job=job: self.furnish(job) for job in jobs],
                                       group.width,
                                       [k for k, j in enumerate(jobs) if j.index in group.needed]):
            now, cpu = time.perf_counter(), time.process_time()
            result.row.update(seconds=round(now - last, 4), cpu_seconds=round(cpu - last_cpu, 4))
            last, last_cpu = now, cpu
            yield result

    def furnish(self, job: RoomJob) -> RoomResult:
        """Room ``job`` and its files, or a row saying in one sentence why it failed."""
        t0, cpu0 = time.perf_counter(), time.process_time()
        row: dict = {'index': job.index, 'room': job.name, 'seed': job.seed,
                     'layout': job.layout}
        files: dict[str, bytes] = {}
        try:
            row.update(status='ok', **self._furnish(job, files))
        except SceneSynthError as e:
            row.update(status='error', error=str(e))
            files = {}
        except Exception as e:   # noqa: BLE001 - one broken room must not end a batch of thousands
            row.update(status='error', error=sentence(f'internal error: {type(e).__name__}: {e}'))
            files = {}
        rss, peak = _memory_mb()
        row.update(seconds=round(time.perf_counter() - t0, 4),
                   cpu_seconds=round(time.process_time() - cpu0, 4), worker=self.name,
                   rss_mb=None if rss is None else round(rss, 1),
                   peak_mb=None if peak is None else round(peak, 1))
        return RoomResult(row, files)

    def _furnish(self, job: RoomJob, files: dict[str, bytes]) -> dict:
        from .geometry import check_scene
        from .scene import Scene
        if job.problem:
            raise BatchError(job.problem)
        if job.room_type is not None:
            from .corpus.generate import first_shell
            scene = Scene(first_shell(job.room_type, job.shell_seed, job.index), [])
        else:
            vocabulary = self.synth.vocabulary
            scene = scene_from_document(
                job.data, load_catalog(self.spec.synthesis.catalog, vocabulary), vocabulary)
        furnish = self.synth.generate if self.spec.mode == 'generate' else self.synth.complete
        result = furnish(scene, job.seed)
        files.update(self.files(job.name, result.scene))
        report = check_scene(result.scene)
        out = {'room_type': result.scene.room.room_type,
               'area': round(result.scene.room.area, 2), 'objects': len(result.scene.objects),
               'added': len(result.added), 'stopped': result.stopped, 'valid': report.ok,
               'robot_kept': result.robot.kept}
        if not report.ok:
            out['problems'] = report.summary()
        out['files'] = output_files(job.name, self.spec.png, self.spec.exports)
        return out

    def files(self, name: str, scene) -> dict[str, bytes]:
        """The room's files: shared models first, then what refers to them, the scene last,
        so that a reader who finds a file finds what it names."""
        from . import export
        from .schema import dump_scene
        models = load_catalog(self.spec.synthesis.catalog, self.synth.vocabulary)
        shared, own = {}, {}
        with tempfile.TemporaryDirectory(prefix='scene-synth-batch-') as tmp:
            root = Path(tmp)
            if self.spec.png:
                from .plot import save_png
                (root / THUMBNAILS).mkdir()
                save_png(scene, root / THUMBNAILS / f'{name}.png', title=name,
                         vocabulary=self.synth.vocabulary, **THUMBNAIL)
            for fmt in self.spec.exports:
                export.write(scene, fmt, root / fmt / f'{name}{export.FORMATS[fmt].suffix}',
                             root / fmt / MESHES, catalog=models)
            primary = set(output_files(name, self.spec.png, self.spec.exports))
            for p in sorted(root.rglob('*')):
                rel = p.relative_to(root).as_posix()
                if not p.is_file() or rel in self.shipped:
                    continue
                if _shared(rel):
                    shared[rel] = p.read_bytes()
                    self.shipped.add(rel)
                elif rel not in primary:
                    own[rel] = p.read_bytes()
            for rel in sorted(primary - {f'{SCENES}/{name}.json'}):
                own[rel] = (root / rel).read_bytes()
        own[f'{SCENES}/{name}.json'] = (dump_scene(scene, models, self.synth.vocabulary)
                                        + '\n').encode('utf-8')
        return {**shared, **own}


_WORKER: Worker | None = None
_RESULTS = None         # the queue through which a pool worker sends each room as it ends
_STOP = None            # set by the driver when it stops early: the groups under way end


def _start_pool_worker(spec: WorkerSpec, results, stop) -> None:
    global _WORKER, _RESULTS, _STOP
    # Ctrl-C goes to the whole process group; the driver alone handles it (it stops the pool).
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # The driver reads every room before it stops the pool, except when it stops early; then
    # what was not read must not keep the worker from exiting.
    results.cancel_join_thread()
    _WORKER, _RESULTS, _STOP = Worker(spec), results, stop


def _pool_furnish(group: RoomGroup) -> int:
    """Furnishes ``group``, sending each room to the driver as it ends, until the group ends
    or the driver stops; how many rooms it sent."""
    sent = 0
    for result in _WORKER.furnish_group(group):
        if _STOP.is_set():
            break               # the rooms under way are abandoned (``lockstep.each``)
        # Pickled here, not by the queue's thread, which would drop a room it cannot pickle
        # and leave the driver waiting for it: here that fails the task, which says why.
        _RESULTS.put(pickle.dumps((_key(group), result), pickle.HIGHEST_PROTOCOL))
        sent += 1
    return sent


def _key(group: RoomGroup) -> int:
    return group.jobs[0].index


class RayWorker:
    """A Ray actor's state: one ``Worker``."""

    def __init__(self, spec: WorkerSpec):
        self.worker = Worker(spec)

    def furnish_group(self, group: RoomGroup) -> Iterator[RoomResult]:
        # A generator: Ray streams each room to the driver as it ends.
        yield from self.worker.furnish_group(group)


def _lost(job: RoomJob) -> RoomResult:
    """The row of a room whose worker process died while it was in flight."""
    return RoomResult({'index': job.index, 'room': job.name, 'seed': job.seed,
                       'layout': job.layout, 'status': 'error',
                       'error': LOST, 'seconds': None, 'cpu_seconds': None, 'worker': None,
                       'rss_mb': None, 'peak_mb': None}, {})


def _pool_results(spec: WorkerSpec, groups: list[RoomGroup], workers: int,
                  spawn: bool | None = None) -> Iterator[RoomResult]:
    """The rooms of ``groups`` furnished by ``workers`` processes, a group at a time each,
    each room as it ends, each worker's in the order it made them (so that models it sends
    once come before a later room that names them). A worker that dies (killed, out of
    memory) costs the rooms in flight that had not come back, which fail with ``LOST``; the
    others go on in new processes, unless a pool dies before furnishing anything. The
    workers are spawned, not forked, where they use CUDA (``spawn`` None: as the synthesis
    device says; see ``parallel``)."""
    from concurrent.futures.process import BrokenProcessPool
    from queue import Empty

    from .parallel import process_event, process_executor, process_queue
    if spawn is None:
        spawn = resolve_device(spec.synthesis.device).type == 'cuda'
    remaining = deque(groups)
    while remaining:
        results, stop = process_queue(spawn), process_event(spawn)
        pool = process_executor(workers, _start_pool_worker, (spec, results, stop), spawn)
        inflight: dict = {}             # future -> group
        received: dict[int, set[int]] = {}  # group key -> indices of its rooms that came back
        produced = broken = False
        try:
            while (remaining or inflight) and not broken:
                while remaining and len(inflight) < IN_FLIGHT * workers:
                    group = remaining.popleft()
                    received[_key(group)] = set()
                    inflight[pool.submit(_pool_furnish, group)] = group
                try:
                    key, result = pickle.loads(results.get(timeout=POLL_SECONDS))
                except Empty:
                    pass
                else:
                    received[key].add(result.row['index'])
                    produced = True
                    yield result
                for future in [f for f in inflight if f.done()]:
                    try:
                        sent = future.result()
                    except BrokenProcessPool:
                        broken = True
                        break
                    if len(received[_key(inflight[future])]) == sent:
                        del inflight[future]
        finally:
            # Also when the driver stops early (an error, Ctrl-C): the groups under way end
            # at their next room, the queued ones are dropped.
            stop.set()
            pool.shutdown(wait=True, cancel_futures=True)
        # The pool broke: what its workers sent and was not read is not read now (a worker
        # killed while sending leaves half a message that would block the reader for ever).
        for group in inflight.values():
            yield from group.lost(received[_key(group)])
        if broken and not produced:
            for group in remaining:
                yield from group.lost()
            return


def _ray_results(spec: WorkerSpec, groups: list[RoomGroup], workers: int | None,
                 address: str) -> Iterator[RoomResult]:
    """The rooms of ``groups`` furnished by Ray actors, a group at a time each, each room as
    it ends, each actor's in the order it made them (see ``_pool_results``). ``address``:
    'local' starts a Ray of ``workers`` CPUs on this machine for the batch (and stops it
    after); anything else is given to ``ray.init`` (a cluster's address, or 'auto'). A
    driver already connected to Ray uses that connection."""
    try:
        import ray
    except ImportError:
        raise BatchError('--ray needs the ray package (pip install ray, pinned in '
                         'requirements.txt)') from None
    started = False
    if not ray.is_initialized():
        kwargs = {'address': address, 'include_dashboard': False, 'logging_level': 'WARNING'}
        if address == 'local':
            kwargs['num_cpus'] = workers or _cores()
        try:
            ray.init(**kwargs)
        except (ConnectionError, ValueError, RuntimeError, TimeoutError) as e:
            raise BatchError(f'cannot start or reach Ray at {quoted(address)}: {e}') from None
        started = True
    actors = []
    try:
        n = workers or max(1, int(ray.cluster_resources().get('CPU', 1)))
        actor_class = ray.remote(num_cpus=1)(RayWorker)
        actors = [actor_class.remote(spec) for _ in range(min(n, len(groups)))]
        todo = iter(groups)
        # Each actor's groups in the order given to it, each a stream of its rooms.
        queued: list[deque] = [deque() for _ in actors]

        def feed(k: int) -> None:
            group = next(todo, None)
            if group is not None:
                queued[k].append(actors[k].furnish_group.remote(group))

        for _ in range(IN_FLIGHT):          # a group for every actor before a second one
            for k in range(len(actors)):
                feed(k)
        while any(queued):
            heads = [k for k, q in enumerate(queued) if q]
            ready, _ = ray.wait([queued[k][0] for k in heads], num_returns=1)
            k = next(k for k in heads if queued[k][0] is ready[0])
            try:
                try:
                    room = next(queued[k][0])
                except StopIteration:       # the group has ended
                    queued[k].popleft()
                    feed(k)
                    continue
                result = ray.get(room)
            except ray.exceptions.RayError as e:
                raise BatchError(f'a Ray worker failed ({sentence(e, 200)}); run the same '
                                 f'command again to resume') from None
            yield result
    finally:
        for a in actors:
            ray.kill(a)
        if started:
            ray.shutdown()


# ---- the batch -------------------------------------------------------------------------------
@dataclass
class BatchConfig:
    """One batch (see the module docstring)."""

    out: str | os.PathLike
    source: Source
    mode: str = 'generate'          # 'generate' or 'complete'
    n: int | None = None            # rooms; None: every room of a finite source
    seed: int = 0
    synthesis: SynthConfig = field(default_factory=SynthConfig)
    weights_dir: str | None = None
    workers: int | None = None      # None: one per core (with Ray: one per CPU of the cluster)
    png: bool = False
    exports: tuple[str, ...] = ()
    ray: str | None = None          # None: worker processes; 'local' or an address: Ray
    # Rooms furnished together (``lockstep``; 1: one at a time): with the networks in
    # onnxruntime 8 made 1-2 % more rooms a second than 16 on two workers, at 413-426 MB a
    # worker against 542-561 (``benchmarks/bench_batch.py --runtime torch onnxruntime``).
    lockstep: int = 8
    progress: bool = True           # a progress bar on stderr


@dataclass
class BatchSummary:
    """What a run did (``this run``) and what the directory holds (every row)."""

    out: str
    requested: int
    furnished: int                  # this run
    failed: int                     # this run
    skipped: int                    # already there
    seconds: float                  # this run's wall time
    workers: int
    backend: str                    # 'processes' or 'ray'
    peak_mb: dict[str, float]       # peak resident memory of each of this run's workers
    rooms_ok: int = 0               # in the whole manifest
    rooms_failed: int = 0
    objects_per_room: float = 0.0
    valid: int = 0
    robot_kept: int = 0

    @property
    def rooms_per_second(self) -> float:
        done = self.furnished + self.failed
        return done / self.seconds if self.seconds > 0 else 0.0

    def to_dict(self) -> dict:
        return {**asdict(self), 'rooms_per_second': round(self.rooms_per_second, 3)}

    def report(self) -> str:
        """A few lines for people."""
        lines = [f'{self.out}: {self.requested} rooms asked for; {self.furnished} furnished '
                 f'and {self.failed} failed in {self.seconds:.1f} s '
                 f'({self.rooms_per_second:.2f} rooms/s on {self.workers} '
                 f'{"Ray worker" if self.backend == "ray" else "worker process"}'
                 f'{"" if self.workers == 1 else "es" if self.backend != "ray" else "s"}), '
                 f'{self.skipped} already there']
        if self.rooms_ok:
            lines.append(f'the directory holds {self.rooms_ok} rooms, '
                         f'{self.objects_per_room:.2f} objects each; physically valid: '
                         f'{self.valid}, robot promise kept: {self.robot_kept}')
        if self.peak_mb:
            lines.append(f'peak memory per worker: {max(self.peak_mb.values()):.0f} MB at most')
        if self.rooms_failed:
            lines.append(f'{self.rooms_failed} rooms failed: their rows in manifest.jsonl say '
                         'why')
        return '\n'.join(lines)


class Manifest:
    """``manifest.jsonl``: rows appended as rooms finish, the last row of an index counting."""

    def __init__(self, path: Path):
        self.path = path
        self.rows: dict[int, dict] = {}
        if path.is_file():
            with open(path, 'rb') as f:
                for line in f:
                    try:
                        row = json.loads(line)
                        self.rows[int(row['index'])] = row
                    except (ValueError, KeyError, TypeError):
                        continue      # the torn last line of a killed run
        self._file = None

    def append(self, row: dict) -> None:
        if self._file is None:
            self._file = open(self.path, 'ab')
            # A killed run may have left half a line; the next row starts on a line of its own.
            if self._file.tell() and not self._ends_with_newline():
                self._file.write(b'\n')
        self._file.write(json.dumps(row, ensure_ascii=False).encode('utf-8') + b'\n')
        self._file.flush()
        self.rows[row['index']] = row

    def _ends_with_newline(self) -> bool:
        with open(self.path, 'rb') as f:
            f.seek(-1, os.SEEK_END)
            return f.read(1) == b'\n'

    def close(self) -> None:
        if self._file is not None:
            self._file.close()
            self._file = None

    def compact(self) -> None:
        """The file as one row per room, by index."""
        self.close()
        text = ''.join(json.dumps(self.rows[i], ensure_ascii=False) + '\n'
                       for i in sorted(self.rows))
        write_atomic(self.path, text)


def _runtime_chosen(cfg: BatchConfig) -> BatchConfig:
    """``cfg`` with the runtime ``auto`` chooses here: the batch's, named in batch.json and
    sent to the workers, so that a directory furnished by onnxruntime is not resumed, nor its
    rooms made, by torch on a machine without it. On the CPU ``auto`` is onnxruntime in
    lockstep too (``benchmarks/bench_batch.py --runtime torch onnxruntime``: 2 workers, 8 in
    lockstep, 18.17 / 19.32 against 14.60 / 15.95 rooms/s in two runs)."""
    try:
        runtime = resolve_runtime(cfg.synthesis.runtime, resolve_device(cfg.synthesis.device))
    except ValueError as e:
        raise BatchError(str(e)) from None
    return replace(cfg, synthesis=replace(cfg.synthesis, runtime=runtime))


def _identity(cfg: BatchConfig, weights: Path) -> dict:
    """What determines the rooms (batch.json): not how many, by whom, nor what else is
    written."""
    return json.loads(json.dumps({
        'command': cfg.mode, 'seed': cfg.seed, 'source': cfg.source.identity(),
        'synthesis': asdict(cfg.synthesis), 'lockstep': cfg.lockstep,
        'weights': str(weights)}))


def _difference(old, new, where: str = '') -> str | None:
    if isinstance(old, dict) and isinstance(new, dict):
        for k in sorted(set(old) | set(new), key=str):
            d = _difference(old.get(k), new.get(k), f'{where}.{k}' if where else str(k))
            if d:
                return d
        return None
    return None if old == new else f'{where} {quoted(old, 60)} there, {quoted(new, 60)} now'


def _check_directory(out: Path, identity: dict) -> None:
    """Create ``out`` and its batch.json, or check that the batch there is this one."""
    try:
        out.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise BatchError(f'{out} is a file, not a directory for the batch') from None
    except OSError as e:
        raise BatchError(f'{out} cannot be created: {e.strerror or e}') from None
    if not out.is_dir():
        raise BatchError(f'{out} is a file, not a directory for the batch')
    path = out / 'batch.json'
    if path.is_file():
        try:
            old = json.loads(path.read_text(encoding='utf-8'))
        except (OSError, ValueError) as e:
            raise BatchError(f'{path} is not a batch description ({sentence(e, 120)}): '
                             f'furnish into another directory') from None
        diff = _difference(old, identity)
        if diff:
            raise BatchError(f'{out} holds a batch of other rooms ({diff}): ask for the same '
                             f'rooms to resume it, or furnish into another directory')
        return
    try:
        write_atomic(path, json.dumps(identity, indent=2) + '\n')
    except OSError as e:
        raise BatchError(f'{out} is not writable: {e.strerror or e}') from None


def _check_weights(cfg: BatchConfig) -> Path:
    """The weights directory, its bundles for the shells' room types loaded once here so that
    a missing or broken file is one sentence before any worker starts."""
    from .synth import Synthesizer
    Synthesizer(cfg.weights_dir, cfg.synthesis)        # a device that is not there
    synth = Synthesizer(cfg.weights_dir, replace(cfg.synthesis, device='cpu'))
    if not synth.weights_dir.is_dir():
        raise BatchError(f'{synth.weights_dir}: no such weights directory')
    for rt in cfg.source.room_types:
        synth.bundle(rt)
    return synth.weights_dir.resolve()


def group_size(r: int) -> int:
    """The rooms of a lockstep group of ``r`` rooms at a time (see the module docstring)."""
    return 1 if r == 1 else GROUP_ROUNDS * r


def _groups(jobs: list[RoomJob], pending: set[int], r: int) -> list[RoomGroup]:
    """The lockstep groups that hold a pending room: room ``i`` is in group ``i // G``."""
    size = group_size(r)
    groups: dict[int, list[RoomJob]] = {}
    for j in jobs:
        groups.setdefault(j.index // size, []).append(j)
    out = []
    for _, g in sorted(groups.items()):
        needed = frozenset(j.index for j in g if j.index in pending)
        if needed:
            out.append(RoomGroup(g, needed, r))
    return out


def _cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, 'sched_getaffinity'):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def _done(row: dict | None, out: Path, files: list[str]) -> bool:
    return bool(row) and row.get('status') == 'ok' and all((out / f).is_file() for f in files)


def _write(out: Path, result: RoomResult) -> None:
    for rel, data in result.files.items():
        path = out / rel
        if _shared(rel) and path.is_file() and path.read_bytes() == data:
            continue
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(path, data)


def run_batch(cfg: BatchConfig, echo: Callable[[str], None] = print) -> BatchSummary:
    """Furnish the batch's rooms that are not there yet into ``cfg.out``; BatchError (or
    another SceneSynthError) before anything is furnished when it cannot start."""
    if cfg.mode not in ('generate', 'complete'):
        raise BatchError(f"mode must be 'generate' or 'complete', got {quoted(cfg.mode)}")
    if cfg.n is not None and cfg.n < 1:
        raise BatchError(f'-n must be at least 1, got {cfg.n}')
    if cfg.n is None and not cfg.source.finite:
        raise BatchError('how many rooms? give -n N')
    if cfg.workers is not None and cfg.workers < 1:
        raise BatchError(f'--workers must be at least 1, got {cfg.workers}')
    if not 1 <= cfg.lockstep <= MAX_LOCKSTEP:
        raise BatchError(f'--lockstep must be between 1 and {MAX_LOCKSTEP}, got {cfg.lockstep}')
    if cfg.mode == 'complete' and cfg.source.kind == 'shells':
        raise BatchError('complete needs partial rooms: a file, a directory or a JSON-lines '
                         'file of them')
    from .export import parse_formats
    exports = parse_formats(','.join(cfg.exports))
    out = Path(cfg.out)
    weights = _check_weights(cfg)
    cfg = _runtime_chosen(cfg)
    # A group is always the same rooms (see the module docstring): the last one goes on
    # beyond -n with rooms that start while the last needed ones are under way.
    r, g = cfg.lockstep, group_size(cfg.lockstep)
    everything = cfg.source.jobs(cfg.seed, None if cfg.n is None else -(-cfg.n // g) * g)
    jobs = everything[:cfg.n]
    if cfg.n is not None and len(jobs) < cfg.n:
        echo(f'{cfg.source.path} holds {len(jobs)} rooms: furnishing those, not {cfg.n}')
    _check_directory(out, _identity(cfg, weights))
    manifest = Manifest(out / 'manifest.jsonl')
    pending = [j for j in jobs
               if not _done(manifest.rows.get(j.index), out,
                            output_files(j.name, cfg.png, exports))]
    groups = _groups(everything, {j.index for j in pending}, r)
    spec = WorkerSpec(cfg.mode, cfg.weights_dir, cfg.synthesis, cfg.png, exports)
    workers = cfg.workers or (None if cfg.ray else _cores())
    skipped = len(jobs) - len(pending)
    if skipped:
        echo(f'{out}: {skipped} of {len(jobs)} rooms already there, {len(pending)} to furnish')
    t0 = time.perf_counter()
    furnished = failed = 0
    peaks: dict[str, float] = {}
    try:
        if pending:
            groups = [replace(g, jobs=[cfg.source.load(j) for j in g.jobs]) for g in groups]
            if cfg.ray:
                results = _ray_results(spec, groups, workers, cfg.ray)
            else:
                results = _pool_results(spec, groups, min(workers, len(groups)))
            wanted = {j.index for j in pending}
            from tqdm import tqdm
            # closing: an error here stops the workers now, not when the traceback goes.
            with closing(results), tqdm(
                    total=len(pending), unit=' rooms', desc='furnishing', file=sys.stderr,
                    disable=not cfg.progress, mininterval=1.0, smoothing=0.1,
                    bar_format=PROGRESS) as bar:
                for result in results:
                    row = result.row
                    if row['index'] not in wanted:
                        # Made for its group only: of its files, just the shared models its
                        # worker sends once, which later rooms name.
                        _write(out, RoomResult(row, {k: v for k, v in result.files.items()
                                                     if _shared(k)}))
                        continue
                    _write(out, result)
                    manifest.append(row)
                    if row['status'] == 'ok':
                        furnished += 1
                    else:
                        failed += 1
                        bar.set_postfix(failed=failed, refresh=False)
                    if row['worker'] is not None:       # None: its worker died
                        peaks[row['worker']] = max(peaks.get(row['worker'], 0.0),
                                                   row['peak_mb'] or 0.0)
                    bar.update()
    finally:
        manifest.compact()
        seconds = time.perf_counter() - t0
        summary = _summarize(cfg, manifest, len(jobs), furnished, failed, skipped, seconds,
                             len(peaks) or (workers or 0), peaks)
        write_atomic(out / 'summary.json', json.dumps(summary.to_dict(), indent=2) + '\n')
    return summary


def _summarize(cfg: BatchConfig, manifest: Manifest, requested: int, furnished: int,
               failed: int, skipped: int, seconds: float, workers: int,
               peaks: dict[str, float]) -> BatchSummary:
    ok = [r for r in manifest.rows.values() if r.get('status') == 'ok']
    return BatchSummary(
        out=str(cfg.out), requested=requested, furnished=furnished, failed=failed,
        skipped=skipped, seconds=round(seconds, 3), workers=workers,
        backend='ray' if cfg.ray else 'processes', peak_mb=peaks,
        rooms_ok=len(ok), rooms_failed=len(manifest.rows) - len(ok),
        objects_per_room=round(sum(r.get('objects', 0) for r in ok) / len(ok), 3) if ok else 0.0,
        valid=sum(bool(r.get('valid')) for r in ok),
        robot_kept=sum(bool(r.get('robot_kept')) for r in ok))
