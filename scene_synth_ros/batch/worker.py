"""A worker: furnishes rooms with a Synthesizer of its own and makes their files, and the
lockstep groups it furnishes them in.

A room's manifest row: ``index``, ``room``, ``status`` (``ok`` or ``error``), ``seed``,
``layout``, then for a room furnished ``room_type``, ``area``, ``objects``, ``added``,
``stopped``, ``valid`` (``geometry.check_scene``), ``robot_kept`` (the robot promise) and
``files``; for one that failed ``error``, the package's one-sentence reason. Every row has
``seconds`` (wall time), ``cpu_seconds`` (the worker process's CPU time over the same span: on
a shared machine a steadier measure of what a room costs) and the ``worker`` (host:pid) with
its resident and peak memory (``rss_mb``, ``peak_mb``).

Rooms in lockstep (``--lockstep R``): the rooms of index ``kG`` to ``kG + G - 1`` form group
``k`` (``G = GROUP_ROUNDS * R``; ``G = 1`` for R = 1), furnished by one worker R at a time, in
index order, the next room starting when one ends, each module's forward pass batched across
the rooms under way (``lockstep.each``). A room's ``seconds`` is then the group's wall time
from the end of the room before it (from the start of the group for the first), so that the
rooms of a group add up to its time (``cpu_seconds`` likewise).

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
"""
from __future__ import annotations

from dataclasses import dataclass
import os
from pathlib import Path
import socket
import tempfile
import time
from typing import Iterator

from .. import export, lockstep
from ..corpus.generate import first_shell
from ..corpus.house_plan import house_plan
from ..errors import SceneSynthError, sentence
from ..geometry import check_scene
from ..house import House, HouseScene
from ..house_synth import furnish_house
from ..networks.runtime import set_threads
from ..plot import save_house_png, save_png
from ..scene import Scene
from ..schema import dump_house_scene, dump_scene
from ..synth import SynthConfig, Synthesizer
from ..user_catalog import load_catalog
from .sources import BatchError, RoomJob, scene_from_document

try:
    import resource
except ImportError:                 # Windows
    resource = None

SCENES, THUMBNAILS = 'scenes', 'png'
MESHES = 'meshes'                  # a format folder's shared models
THUMBNAIL = {'figsize': (3.0, 3.0), 'dpi': 80, 'legend': False}   # 240 x 240 px
# A group is this many times R rooms: enough that the rounds in which the group's last rooms
# finish, with fewer rooms under way, are few among its rounds; few enough that a resumed
# group redoes little.
GROUP_ROUNDS = 8
LOST = ('its worker process died while this room or another one was in flight (killed, or '
        'out of memory?); run the batch again to retry it')


def available_formats() -> list[str]:
    """The export formats a batch can write (``export.FORMATS``)."""
    return list(export.FORMATS)


def output_files(name: str, png: bool, exports: tuple[str, ...]) -> list[str]:
    """The files of room ``name`` that a run asks for, relative to the batch directory; the
    scene last (see ``Worker.files``)."""
    files = [f'{THUMBNAILS}/{name}.png'] if png else []
    files += [f'{fmt}/{name}{export.FORMATS[fmt].suffix}' for fmt in exports]
    return files + [f'{SCENES}/{name}.json']


def is_shared(rel: str) -> bool:
    """Whether ``rel`` is one of a format folder's shared model files."""
    parts = rel.split('/')
    return len(parts) > 2 and parts[1] == MESHES


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


def group_size(r: int) -> int:
    """The rooms of a lockstep group of ``r`` rooms at a time (see the module docstring)."""
    return 1 if r == 1 else GROUP_ROUNDS * r


def lockstep_groups(jobs: list[RoomJob], pending: set[int], r: int) -> list[RoomGroup]:
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


@dataclass
class RoomResult:
    row: dict
    files: dict[str, bytes]         # relative path -> content, in the order to write them


def _lost(job: RoomJob) -> RoomResult:
    """The row of a room whose worker process died while it was in flight."""
    return RoomResult({'index': job.index, 'room': job.name, 'seed': job.seed,
                       'layout': job.layout, 'status': 'error',
                       'error': LOST, 'seconds': None, 'cpu_seconds': None, 'worker': None,
                       'rss_mb': None, 'peak_mb': None}, {})


def _memory_mb() -> tuple[float | None, float | None]:
    """(resident, peak resident) memory of this process in MB, where the platform says."""
    peak = (None if resource is None
            else resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)   # KB on Linux
    try:
        with open('/proc/self/statm') as f:
            rss = int(f.read().split()[1]) * os.sysconf('SC_PAGE_SIZE') / 2**20
    except (OSError, ValueError, IndexError):
        rss = None
    return rss, peak


class Worker:
    """Furnishes one room at a time with a Synthesizer of its own and one torch thread."""

    def __init__(self, spec: WorkerSpec):
        # One thread each: the workers are the parallelism, and threads fighting over the
        # same cores are slower than one each.
        set_threads(1)
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
        if job.problem:
            raise BatchError(job.problem)
        if job.house_plan:
            return self._furnish_house(job, house_plan(job.shell_seed, job.index), files)
        if job.room_type is not None:
            scene = Scene(first_shell(job.room_type, job.shell_seed, job.index), [])
        else:
            vocabulary = self.synth.vocabulary
            scene = scene_from_document(
                job.data, load_catalog(self.spec.synthesis.catalog, vocabulary), vocabulary)
            if isinstance(scene, HouseScene):
                return self._furnish_house(
                    job, scene.house if self.spec.mode == 'generate' else scene, files)
        furnish = self.synth.generate if self.spec.mode == 'generate' else self.synth.complete
        result = furnish(scene, job.seed)
        files.update(self.files(job.name, result.scene))
        report = check_scene(result.scene, result.allowance)
        out = {'room_type': result.scene.room.room_type,
               'area': round(result.scene.room.area, 2), 'objects': len(result.scene.objects),
               'added': len(result.added), 'stopped': result.stopped, 'valid': report.ok,
               'robot_kept': result.robot.kept}
        if not report.ok:
            out['problems'] = report.summary()
        out['files'] = output_files(job.name, self.spec.png, self.spec.exports)
        return out

    def _furnish_house(self, job: RoomJob, house: House | HouseScene,
                       files: dict[str, bytes]) -> dict:
        """A whole house in one row: ``room_type`` ``house``, its ``rooms``, and ``valid``
        and ``robot_kept`` for every room of it."""
        result = furnish_house(self.synth, house, job.seed, config=self.spec.synthesis)
        files.update(self.files(job.name, result.scene))
        reports = {rid: check_scene(r.scene, r.allowance) for rid, r in result.rooms.items()}
        out = {'room_type': 'house', 'rooms': len(reports),
               'area': round(result.scene.house.area, 2),
               'objects': len(result.scene.objects()),
               'added': sum(len(r.added) for r in result.rooms.values()), 'stopped': 'stop',
               'valid': all(r.ok for r in reports.values()), 'robot_kept': result.robot_kept}
        broken = [f'{rid}: {r.summary()}' for rid, r in reports.items() if not r.ok]
        if broken:
            out['problems'] = '; '.join(broken)
        out['files'] = output_files(job.name, self.spec.png, self.spec.exports)
        return out

    def files(self, name: str, scene) -> dict[str, bytes]:
        """The room's files: shared models first, then what refers to them, the scene last,
        so that a reader who finds a file finds what it names."""
        models = load_catalog(self.spec.synthesis.catalog, self.synth.vocabulary)
        shared, own = {}, {}
        with tempfile.TemporaryDirectory(prefix='scene-synth-batch-') as tmp:
            root = Path(tmp)
            if self.spec.png:
                (root / THUMBNAILS).mkdir()
                png = root / THUMBNAILS / f'{name}.png'
                if isinstance(scene, HouseScene):
                    save_house_png(scene, png, title=name, vocabulary=self.synth.vocabulary,
                                   dpi=THUMBNAIL['dpi'])
                else:
                    save_png(scene, png, title=name, vocabulary=self.synth.vocabulary,
                             **THUMBNAIL)
            for fmt in self.spec.exports:
                export.write(scene, fmt, root / fmt / f'{name}{export.FORMATS[fmt].suffix}',
                             root / fmt / MESHES, catalog=models)
            primary = set(output_files(name, self.spec.png, self.spec.exports))
            for p in sorted(root.rglob('*')):
                rel = p.relative_to(root).as_posix()
                if not p.is_file() or rel in self.shipped:
                    continue
                if is_shared(rel):
                    shared[rel] = p.read_bytes()
                    self.shipped.add(rel)
                elif rel not in primary:
                    own[rel] = p.read_bytes()
            for rel in sorted(primary - {f'{SCENES}/{name}.json'}):
                own[rel] = (root / rel).read_bytes()
        dump = dump_house_scene if isinstance(scene, HouseScene) else dump_scene
        own[f'{SCENES}/{name}.json'] = (dump(scene, models, self.synth.vocabulary)
                                        + '\n').encode('utf-8')
        return {**shared, **own}
