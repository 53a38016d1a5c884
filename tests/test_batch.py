"""Batches of rooms (``scene_synth_ros.batch``) through ``scene-synth generate -n`` /
``--layouts`` and ``complete DIR``: the same rooms whatever the number of workers, resumption
after a killed run, bad layouts as manifest rows, bad options as one sentence, thumbnails and
exports, and the Ray path on a local Ray."""
import json
import os
from pathlib import Path
import shutil
import time

from conftest import EXAMPLES
import pytest
import torch

from scene_synth_ros.batch import available_formats
from scene_synth_ros.schema import load_scene

# What differs between two runs of the same room: when and where it was made.
RUN_FIELDS = ('seconds', 'cpu_seconds', 'worker', 'rss_mb', 'peak_mb')


def rows(out: Path) -> list[dict]:
    return [json.loads(line) for line in (out / 'manifest.jsonl').read_text().splitlines()]


def stable(row: dict) -> dict:
    return {k: v for k, v in row.items() if k not in RUN_FIELDS}


def scenes(out: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted((out / 'scenes').iterdir())}


def batch(tiny_weights, *args):
    return ('generate', '--room-type', 'bathroom', '--weights-dir', tiny_weights, '--seed', 5,
            '-q', *args)


def test_same_rooms_on_one_and_two_workers_and_a_killed_run_resumes(cli, tiny_weights,
                                                                    tmp_path):
    # Two rooms at a time in lockstep, in groups of 16: rooms 0-15 on one worker, 16-17 on
    # the other, which starts room 18 (not written) while they are under way.
    a, b = tmp_path / 'a', tmp_path / 'b'
    cli(*batch(tiny_weights, '-n', 18, '--workers', 1, '--lockstep', 2, '--out', a))
    proc = cli(*batch(tiny_weights, '-n', 18, '--workers', 2, '--lockstep', 2, '--out', b))
    assert '18 furnished and 0 failed' in proc.stdout and 'on 2 worker processes' in proc.stdout
    assert scenes(a) == scenes(b) and len(scenes(a)) == 18
    assert [stable(r) for r in rows(a)] == [stable(r) for r in rows(b)]
    made = rows(a)
    assert [r['index'] for r in made] == list(range(18))
    assert [r['seed'] for r in made] == list(range(5, 23))
    assert made[2]['layout'] == 'bathroom shell: corpus seed 5, room 2'
    for r in made:
        scene = load_scene(a / 'scenes' / f'{r["room"]}.json')
        assert r['status'] == 'ok' and r['valid'] and r['objects'] == len(scene)
        assert r['seconds'] > 0 and 0 < r['cpu_seconds'] and r['peak_mb'] > 0
    assert sum(r['objects'] for r in made) > 0
    summary = json.loads((b / 'summary.json').read_text())
    assert summary['rooms_ok'] == 18 and summary['workers'] == 2

    # Without lockstep, room 0 is the room of the one-room command (with one torch thread, as
    # a worker has).
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    try:
        cli('generate', '--room-type', 'bathroom', '--weights-dir', tiny_weights, '--seed', 5,
            '--out', tmp_path / 'one.json')
    finally:
        torch.set_num_threads(threads)
    cli(*batch(tiny_weights, '-n', 1, '--lockstep', 1, '--out', tmp_path / 'alone'))
    assert (tmp_path / 'one.json').read_bytes() == scenes(tmp_path / 'alone')['room_000000.json']

    # A run killed while writing room 4's row: its scene is there, its row half-written;
    # room 5 was never finished, the rows after it never written. Resumed with more rooms.
    lines = (a / 'manifest.jsonl').read_text().splitlines(keepends=True)
    (a / 'manifest.jsonl').write_text(''.join(lines[:4]) + lines[4][:30])
    (a / 'scenes' / 'room_000005.json').unlink()
    proc = cli(*batch(tiny_weights, '-n', 20, '--workers', 2, '--lockstep', 2, '--out', a))
    assert '4 of 20 rooms already there, 16 to furnish' in proc.stdout
    assert '16 furnished and 0 failed' in proc.stdout
    resumed = rows(a)
    assert [r['index'] for r in resumed] == list(range(20))
    assert [stable(r) for r in resumed[:18]] == [stable(r) for r in made]
    assert {k: v for k, v in scenes(a).items() if k < 'room_000018'} == scenes(b)
    proc = cli(*batch(tiny_weights, '-n', 20, '--lockstep', 2, '--out', a))
    assert '0 furnished and 0 failed' in proc.stdout and '20 already there' in proc.stdout
    # One room of a group lost: the group is run again as far as that room needs, that room
    # alone written, the same as before.
    before = scenes(a)
    (a / 'scenes' / 'room_000001.json').unlink()
    proc = cli(*batch(tiny_weights, '-n', 20, '--lockstep', 2, '--out', a))
    assert '1 furnished and 0 failed' in proc.stdout and scenes(a) == before
    assert len(rows(a)) == 20
    # The lockstep R is part of what the batch is.
    proc = cli(*batch(tiny_weights, '-n', 20, '--out', a), ok=False)
    assert proc.returncode != 0 and 'lockstep 2 there, 8 now' in proc.stderr


def test_bad_layouts_are_manifest_rows_and_the_batch_goes_on(cli, tiny_weights, tmp_path):
    layouts = tmp_path / 'layouts'
    layouts.mkdir()
    shutil.copy(EXAMPLES / 'bedroom_layout.json', layouts / 'a_example.json')
    (layouts / 'b_broken.json').write_text('{"room_type": "bedroom", "floor": [')
    (layouts / 'c_kitchen.yaml').write_text('room_type: kitchen\nfloor: [[0, 0], [3, 0], '
                                            '[3, 3], [0, 3]]\n')
    (layouts / 'd_bath.yml').write_text('room_type: bathroom\nfloor: [[0, 0], [3, 0], '
                                        '[3, 2.5], [0, 2.5]]\n')
    (layouts / 'notes.txt').write_text('not a layout')
    out = tmp_path / 'out'
    proc = cli('generate', '--layouts', layouts, '--out', out, '--weights-dir', tiny_weights,
               '--workers', 2, '-q', ok=False)
    assert proc.returncode == 1 and '2 furnished and 2 failed' in proc.stdout
    got = {r['layout']: r for r in rows(out)}
    assert list(got) == ['a_example.json', 'b_broken.json', 'c_kitchen.yaml', 'd_bath.yml']
    assert got['a_example.json']['status'] == got['d_bath.yml']['status'] == 'ok'
    assert 'neither JSON' in got['b_broken.json']['error']
    assert 'kitchen' in got['c_kitchen.yaml']['error']
    for r in got.values():
        if r['status'] == 'error':
            assert 'Traceback' not in r['error'] and '\n' not in r['error']
            assert not (out / 'scenes' / f'{r["room"]}.json').exists()
    assert load_scene(out / 'scenes' / 'room_000000.json').room == \
        load_scene(EXAMPLES / 'bedroom_layout.json').room

    # A JSON-lines file: blank lines skipped, rooms named by line; an office has no tiny
    # weights, which fails that room alone.
    good = json.dumps(json.loads((EXAMPLES / 'bedroom_layout.json').read_text()))
    office = json.dumps({'room_type': 'office', 'floor': [[0, 0], [4, 0], [4, 3], [0, 3]]})
    (tmp_path / 'rooms.jsonl').write_text(f'{good}\n\n[1, 2]\n{office}\n{good}\n')
    out = tmp_path / 'lines'
    proc = cli('generate', '--layouts', tmp_path / 'rooms.jsonl', '--out', out, '--seed', 2,
               '--weights-dir', tiny_weights, '--workers', 1, '-q', ok=False)
    got = rows(out)
    assert [r['layout'] for r in got] == ['rooms.jsonl:1', 'rooms.jsonl:3', 'rooms.jsonl:4',
                                          'rooms.jsonl:5']
    assert [r['status'] for r in got] == ['ok', 'error', 'error', 'ok']
    assert 'office.pt: no such weights file' in got[2]['error']
    assert [r['seed'] for r in got] == [2, 3, 4, 5]


def test_complete_a_directory_and_one_room_many_times(cli, tiny_weights, tmp_path):
    partials = tmp_path / 'partials'
    partials.mkdir()
    shutil.copy(EXAMPLES / 'partial_bedroom.json', partials / 'p.json')
    partial = load_scene(EXAMPLES / 'partial_bedroom.json')
    out = tmp_path / 'done'
    cli('complete', partials, '--out', out, '--weights-dir', tiny_weights, '--workers', 1, '-q')
    done = load_scene(out / 'scenes' / 'room_000000.json')
    assert [o.to_dict() for o in done.objects[:len(partial)]] == \
        [o.to_dict() for o in partial.objects]
    assert rows(out)[0]['added'] == len(done) - len(partial)
    # One partial room, three completions with seeds 0, 1, 2.
    out = tmp_path / 'three'
    cli('complete', EXAMPLES / 'partial_bedroom.json', '-n', 3, '--out', out,
        '--weights-dir', tiny_weights, '--workers', 2, '-q')
    assert [r['seed'] for r in rows(out)] == [0, 1, 2]
    assert len(set(scenes(out).values())) == 3


def test_thumbnails_and_exports_per_room(cli, tiny_weights, tmp_path):
    out = tmp_path / 'out'
    cli(*batch(tiny_weights, '-n', 2, '--workers', 1, '--out', out))
    first = scenes(out)
    formats = available_formats()
    assert {'sdf', 'gltf', 'mjcf', 'urdf', 'usd'} <= set(formats)
    # Asking for more files redoes the rooms that lack them: the same rooms.
    proc = cli(*batch(tiny_weights, '-n', 2, '--workers', 2, '--out', out, '--png',
                      '--export', ','.join(formats)))
    assert '2 furnished' in proc.stdout and scenes(out) == first
    assert (out / 'png' / 'room_000001.png').read_bytes()[:4] == b'\x89PNG'
    assert (out / 'gltf' / 'room_000000.glb').read_bytes()[:4] == b'glTF'
    world = (out / 'sdf' / 'room_000000.sdf').read_text()
    uris = [u.split('</uri>')[0] for u in world.split('<uri>')[1:]]
    meshes = [u for u in uris if u.endswith('.obj')]
    assert meshes and all(not u.startswith(('/', 'file:')) for u in meshes)
    assert all((out / 'sdf' / u).is_file() for u in meshes)
    made = rows(out)[0]['files']
    assert made[-1] == 'scenes/room_000000.json' and all((out / f).is_file() for f in made)
    assert len(made) == len(formats) + 2


def test_batch_bad_input_is_one_sentence(cli, tiny_weights, tmp_path):
    a_file = tmp_path / 'file.txt'
    a_file.write_text('x')
    empty = tmp_path / 'empty'
    empty.mkdir()
    d = tmp_path / 'd'
    for args, words in [
            (('-n', 0, '--out', d), 'at least 1'),
            (('-n', -3, '--out', d), 'at least 1'),
            (('-n', 2, '--workers', 0, '--out', d), '--workers must be at least 1'),
            (('-n', 2), 'needs --out'),
            (('--layouts', tmp_path / 'missing', '--out', d), 'no such file or directory'),
            (('--layouts', empty, '--out', d), 'holds no room layouts'),
            (('-n', 2, '--out', a_file), 'is a file'),
            (('-n', 2, '--out', a_file / 'sub'), 'cannot be created'),
            (('-n', 2, '--out', d, '--png', 'x.png'), 'names its thumbnails'),
            (('-n', 2, '--out', d, '--export', 'obj'), "'obj' is not one of"),
            (('-n', 2, '--out', d, '--export', ','), 'at least one format'),
            (('-n', 2, '--out', d, '--lockstep', 0), '--lockstep must be between 1 and 64'),
            (('--workers', 2), 'is for batches'),
            (('--lockstep', 4), 'is for batches'),
            (('--png',), 'needs a file name'),
            (('-n', 2, '--out', d, '--room-type', 'garage'), 'unknown room type'),
            (('-n', 2, '--out', d, '--runtime', 'onnxruntime', '--device', 'cuda'),
             'runs on the CPU, not on cuda' if torch.cuda.is_available()
             else 'torch sees no CUDA device')]:
        proc = cli('generate', '--weights-dir', tiny_weights, *args, ok=False)
        assert proc.returncode == 2, (args, proc.stderr)
        assert words in proc.stderr and 'Traceback' not in proc.stderr, (args, proc.stderr)
        assert len(proc.stderr.strip().splitlines()) == 1, (args, proc.stderr)
        assert not d.exists(), args
    proc = cli('complete', tmp_path / 'missing.jsonl', '--out', d, ok=False)
    assert proc.returncode == 2 and 'no such file or directory' in proc.stderr
    proc = cli('generate', '-n', 1, '--out', d, '--weights-dir', empty, ok=False)
    assert proc.returncode == 2 and 'no such weights file' in proc.stderr and not d.exists()
    # The directory of another batch is not resumed with other rooms.
    cli(*batch(tiny_weights, '-n', 1, '--workers', 1, '--out', d))
    proc = cli(*batch(tiny_weights, '-n', 1, '--out', d, '--temperature', 0.5), ok=False)
    assert proc.returncode == 2 and 'holds a batch of other rooms' in proc.stderr
    assert 'location_temperature 0.8 there, 0.5 now' in proc.stderr
    # Nor by another runtime: batch.json names the one auto chose, onnxruntime on the CPU,
    # in lockstep (the default) and one room at a time.
    assert json.loads((d / 'batch.json').read_text())['synthesis']['runtime'] == 'onnxruntime'
    proc = cli(*batch(tiny_weights, '-n', 1, '--out', d, '--runtime', 'torch'), ok=False)
    assert proc.returncode == 2 and "runtime 'onnxruntime' there, 'torch' now" in proc.stderr
    one = tmp_path / 'one'
    cli(*batch(tiny_weights, '-n', 1, '--workers', 1, '--lockstep', 1, '--out', one))
    assert json.loads((one / 'batch.json').read_text())['synthesis']['runtime'] == 'onnxruntime'
    # A directory of shells drawn before first_shell (batch.json without its name) is not
    # resumed with first_shell's.
    described = json.loads((d / 'batch.json').read_text())
    del described['source']['shells']
    (d / 'batch.json').write_text(json.dumps(described))
    proc = cli(*batch(tiny_weights, '-n', 2, '--out', d), ok=False)
    assert proc.returncode == 2 and "source.shells None there, 'first attempt' now" in proc.stderr


def _descendants() -> set[int]:
    """Live (not zombie) processes below this one."""
    parent: dict[int, int] = {}
    for p in Path('/proc').iterdir():
        if not p.name.isdigit():
            continue
        try:
            fields = (p / 'stat').read_text().rsplit(')', 1)[1].split()
        except OSError:
            continue
        if fields[0] != 'Z':
            parent[int(p.name)] = int(fields[1])
    found, frontier = set(), {os.getpid()}
    while frontier:
        frontier = {pid for pid, pp in parent.items() if pp in frontier} - found
        found |= frontier
    return found


def _gone(before: set[int], seconds: float = 20.0) -> set[int]:
    deadline = time.monotonic() + seconds
    while (left := _descendants() - before) and time.monotonic() < deadline:
        time.sleep(0.2)
    return left


@pytest.mark.slow
def test_ray_gives_the_rooms_of_the_process_pool(cli, tiny_weights, tmp_path):
    ray = pytest.importorskip('ray')
    assert not ray.is_initialized()
    before = _descendants()
    pool, on_ray = tmp_path / 'pool', tmp_path / 'ray'
    # One room at a time, so that 3 rooms are work for 2 workers (lockstep groups are the
    # same on Ray: ``Worker.furnish_group``).
    cli(*batch(tiny_weights, '-n', 5, '--workers', 2, '--lockstep', 1, '--out', pool))
    # With no address the batch starts a Ray of --workers CPUs for itself, and stops it.
    proc = cli(*batch(tiny_weights, '-n', 3, '--workers', 2, '--lockstep', 1, '--ray',
                      '--out', on_ray))
    assert 'on 2 Ray workers' in proc.stdout and not ray.is_initialized()
    assert not _gone(before), 'Ray left processes behind'
    # A driver already on a Ray uses it (here a local one of 1 CPU: one actor) and resumes.
    ray.init(num_cpus=1, include_dashboard=False, logging_level='WARNING')
    try:
        proc = cli(*batch(tiny_weights, '-n', 5, '--lockstep', 1, '--ray', '--out', on_ray))
        assert '3 already there' in proc.stdout and 'on 1 Ray worker)' in proc.stdout
        assert ray.is_initialized()
    finally:
        ray.shutdown()
    assert not _gone(before), 'Ray left processes behind'
    assert scenes(on_ray) == scenes(pool)
    assert [stable(r) for r in rows(on_ray)] == [stable(r) for r in rows(pool)]


def _workers(pid: int) -> list[int]:
    """The forked worker processes of ``pid``: its children with its own command line."""
    own = Path(f'/proc/{pid}/cmdline').read_bytes()
    out = []
    for task in Path(f'/proc/{pid}/task').iterdir():
        for child in map(int, (task / 'children').read_text().split()):
            try:
                if Path(f'/proc/{child}/cmdline').read_bytes() == own:
                    out.append(child)
            except OSError:             # gone already
                pass
    return out


@pytest.mark.skipif(not Path('/proc/self/task').is_dir(), reason='needs Linux /proc')
def test_a_killed_worker_costs_its_rooms_not_the_batch(tiny_weights, tmp_path):
    """A worker process killed mid-batch (as the out-of-memory killer would) fails the
    rooms it had in flight, with a sentence; the batch goes on in a new process and ends,
    and a second run furnishes what was lost."""
    import signal
    import subprocess
    import sys
    out = tmp_path / 'out'
    cmd = [sys.executable, '-m', 'scene_synth_ros.cli', *map(str, batch(
        tiny_weights, '-n', 40, '--workers', 2, '--lockstep', 1, '--out', out))]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while not ((out / 'manifest.jsonl').is_file() and len(rows(out)) >= 3):
            assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
            time.sleep(0.05)
        victim = _workers(proc.pid)[0]
        os.kill(victim, signal.SIGKILL)
        stdout, stderr = proc.communicate(timeout=180)     # it ends: no hang
    finally:
        proc.kill()
    assert proc.returncode == 1, stderr
    made = rows(out)
    assert sorted(r['index'] for r in made) == list(range(40))
    lost = [r for r in made if r['status'] != 'ok']
    assert 1 <= len(lost) <= 4                             # at most IN_FLIGHT x 2 workers
    assert all('worker process died' in r['error'] for r in lost)
    assert any(r['index'] > max(x['index'] for x in lost) for r in made if r['status'] == 'ok')
    again = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    assert again.returncode == 0, again.stderr
    assert f'{len(lost)} furnished and 0 failed' in again.stdout
    assert all(r['status'] == 'ok' for r in rows(out))


def test_rooms_come_back_one_by_one_and_ctrl_c_mid_group_keeps_them(tiny_weights, tmp_path):
    """A worker sends each room of a lockstep group as it ends: the manifest grows room by
    room, and a run interrupted inside a group keeps the rooms already written; the next run
    furnishes the others, the same rooms as a run never interrupted."""
    import signal
    import subprocess
    import sys
    out, whole = tmp_path / 'out', tmp_path / 'whole'
    args = batch(tiny_weights, '-n', 24, '--workers', 1, '--lockstep', 3)   # one group of 24
    cmd = [sys.executable, '-m', 'scene_synth_ros.cli', *map(str, args)]
    # Ctrl-C as a terminal delivers it, also where the tests themselves run with SIGINT
    # ignored (a background job of a non-interactive shell), which the command would inherit.
    proc = subprocess.Popen([*cmd, '--out', str(out)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        deadline = time.monotonic() + 120
        while not ((out / 'manifest.jsonl').is_file() and len(rows(out)) >= 2):
            assert proc.poll() is None and time.monotonic() < deadline, proc.communicate()
            time.sleep(0.01)
        assert len(rows(out)) < 24 and proc.poll() is None      # the group is under way
        proc.send_signal(signal.SIGINT)
        stdout, stderr = proc.communicate(timeout=120)
    finally:
        proc.kill()
    assert proc.returncode == 130, (stdout, stderr)
    kept = rows(out)
    assert 2 <= len(kept) < 24 and all(r['status'] == 'ok' for r in kept)
    assert all((out / 'scenes' / f'{r["room"]}.json').is_file() for r in kept)
    again = subprocess.run([*cmd, '--out', str(out)], capture_output=True, text=True,
                           timeout=180)
    assert again.returncode == 0, again.stderr
    assert f'{len(kept)} of 24 rooms already there' in again.stdout
    subprocess.run([*cmd, '--out', str(whole)], check=True, capture_output=True, timeout=180)
    assert scenes(out) == scenes(whole) and len(scenes(out)) == 24
    assert [stable(r) for r in rows(out)] == [stable(r) for r in rows(whole)]


def test_spawned_workers_furnish_the_rooms_of_forked_ones(tiny_weights):
    """Workers that use CUDA are spawned, not forked (``parallel``): a spawned worker starts
    from nothing but what it is sent, and furnishes the same rooms."""
    from scene_synth_ros.batch import Source, WorkerSpec
    from scene_synth_ros.batch.pool import pool_results
    from scene_synth_ros.batch.worker import lockstep_groups
    from scene_synth_ros.synth import SynthConfig
    source = Source.shells(['bathroom'])
    jobs = [source.load(j) for j in source.jobs(5, 3)]
    groups = lockstep_groups(jobs, {j.index for j in jobs}, 1)
    spec = WorkerSpec('generate', str(tiny_weights), SynthConfig(runtime='torch'))
    made = {spawn: {r.row['index']: (stable(r.row), r.files)
                    for r in pool_results(spec, groups, 1, spawn=spawn)}
            for spawn in (False, True)}
    assert sorted(made[True]) == [0, 1, 2]
    assert all(row['status'] == 'ok' for row, _ in made[True].values())
    assert made[True] == made[False]
