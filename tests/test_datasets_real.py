"""The importers on the real files of ``../shared/data/real`` (beside the repository; not
part of the package): every file imports with a report and no crash, every scene passes
the JSON schema, and the front and handedness conventions hold on the data.

The convention tests measure, for furniture that stands with its back to a wall (beds,
wardrobes, dressers, ...), the share whose back faces the nearest wall
(``description.back_to_nearest_wall``). A front axis off by 90 or 180 degrees fails it;
so does a mirror applied to positions but not to rotations (or the other way round),
which is what a y-up -> z-up conversion gets wrong: with the positions mirrored and the
yaws kept, the share of objects turned by 90 degrees falls to about nothing.
"""
from functools import lru_cache
import math
from pathlib import Path

import pytest
from shapely.geometry import Polygon

from scene_synth_ros import schema
from scene_synth_ros.datasets import ImportConfig, description, import_dataset, load_room_types
from scene_synth_ros.datasets.description import back_to_nearest_wall
from scene_synth_ros.datasets.importer import FILE_PATTERNS, NOT_SCENES

REAL = Path(__file__).resolve().parent.parent.parent / 'shared' / 'data' / 'real'
pytestmark = pytest.mark.skipif(not REAL.is_dir(), reason=f'no real data in {REAL}')

FORMATS = ('3dfront', 'suncg', 'procthor')
# The data's categories of furniture that stands with its back to a wall.
WALL_FURNITURE = {
    '3dfront': {'king-size bed', 'double bed', 'single bed', 'bed frame', 'kids bed',
                'wardrobe', 'nightstand', 'tv stand', 'bookcase / jewelry armoire',
                'sideboard / side cabinet / console table', 'sideboard / side cabinet / console',
                'drawer chest / corner cabinet', 'dressing table', 'shoe cabinet',
                'wine cabinet', 'children cabinet', 'shelf'},
    'suncg': {'double bed', 'single bed', 'wardrobe cabinet', 'dressing table', 'dresser',
              'tv stand', 'shelving'},
    'procthor': {'bed', 'dresser', 'fridge', 'counter top', 'shelving unit', 'tv stand'},
}


@pytest.fixture(scope='module')
def imported(tmp_path_factory):
    """Each format's folder imported with the default filters, written to disk."""
    out = {}
    for fmt in FORMATS:
        folder = tmp_path_factory.mktemp(fmt)
        out[fmt] = (import_dataset(fmt, [REAL / fmt], out=folder, keep_scenes=True,
                                   layouts=True), folder)
    return out


@pytest.fixture(scope='module')
def unfiltered():
    """Each format with no room-size filter: the most rooms to measure conventions on."""
    return {fmt: import_dataset(fmt, [REAL / fmt], config=ImportConfig(
        room_types=load_room_types(fmt), room_size={})) for fmt in FORMATS}


@pytest.mark.parametrize('fmt', FORMATS)
def test_every_real_file_imports_with_a_report(imported, fmt):
    result, folder = imported[fmt]
    files = {str(f) for pattern in FILE_PATTERNS[fmt] for f in (REAL / fmt).rglob(pattern)
             if f.name not in NOT_SCENES}
    assert set(result.report.files) == files and files
    t = result.report.totals()
    assert t['files_dropped'] == 0 and t['houses_dropped'] == 0
    assert t['rooms_seen'] == t['rooms_kept'] + t['rooms_dropped'] > 0
    assert t['rooms_kept'] == len(result.scenes) > 0
    written = sorted(p.stem for p in folder.glob(f'{fmt}_*.json'))
    assert written == sorted(result.scenes)
    for name in written:
        schema.check_against_schema(schema.read_payload((folder / f'{name}.json').read_text()),
                             'scene')
    text = (folder / 'report.txt').read_text()
    assert text.startswith(result.report.summary())
    assert len(text.splitlines()) >= 3 + len(result.report.lines)
    loaded = description.load(folder / 'dataset.yaml')
    assert set(loaded.room_types) == set(result.report.rooms_kept)


def _shares(result, fmt):
    """(kept share, objects, share with positions mirrored and yaws kept, objects turned
    by about 90 degrees) over the format's wall furniture standing on the floor."""
    n = ok = turned = ok_mirrored = 0
    for s in result.scenes.values():
        floor = Polygon(s['room']['floor'])
        mirrored = Polygon([(x, -y) for x, y in s['room']['floor']])
        for o in s['objects']:
            if o['category'] not in WALL_FURNITURE[fmt] or o['position'][2] > 0.1:
                continue
            n += 1
            ok += back_to_nearest_wall(o, floor)
            if abs(math.sin(o['yaw'])) > 0.5:
                turned += 1
                x, y, z = o['position']
                ok_mirrored += back_to_nearest_wall(dict(o, position=[x, -y, z]), mirrored)
    return ok / max(n, 1), n, ok_mirrored / max(turned, 1), turned


def test_wall_furniture_has_its_back_to_the_nearest_wall(unfiltered):
    pooled = [0, 0]
    for fmt in FORMATS:
        share, n, share_mirrored, turned = _shares(unfiltered[fmt], fmt)
        pooled[0] += share * n
        pooled[1] += n
        assert n > 0, fmt
        if n >= 10:        # SUNCG's one house has two such objects: pooled only
            assert share >= 0.9, (fmt, share, n)
        if turned >= 5:
            assert share_mirrored <= 0.1, (fmt, share_mirrored, turned)
    assert pooled[0] / pooled[1] >= 0.9


def test_procthor_paintings_never_overlap_an_opening(unfiltered):
    """Holes are measured from the first point of their wall's polygon: with that, no
    painting on a wall covers a window or door of the same wall."""
    from scene_synth_ros.scene import Room
    paintings = clashes = 0
    for s in unfiltered['procthor'].scenes.values():
        room = Room('x', tuple(map(tuple, s['room']['floor'])))
        spans = []
        for kind in ('doors', 'windows'):
            for op in s['room'][kind]:
                wall = min(room.walls, key=lambda w: w.distance_to(op['position']))
                c = wall.offset_of(op['position'])
                sill = op.get('sill', 0.0)
                spans.append((wall.index, c - op['width'] / 2, c + op['width'] / 2, sill,
                              sill + op['height']))
        for o in s['objects']:
            if o['category'] != 'painting':
                continue
            paintings += 1
            wall = min(room.walls, key=lambda w: w.distance_to(o['position'][:2]))
            c, half = wall.offset_of(o['position'][:2]), o['size'][0] / 2
            bottom, top = o['position'][2], o['position'][2] + o['size'][2]
            clashes += any(i == wall.index and min(c + half, hi) - max(c - half, lo) > 0.05
                           and min(top, t) - max(bottom, b) > 0.05
                           for i, lo, hi, b, t in spans)
    assert paintings > 100 and clashes == 0


def test_procthor_children_stand_on_their_parents(unfiltered):
    children = 0
    for s in unfiltered['procthor'].scenes.values():
        ids = {o['id']: o for o in s['objects']}
        for o in s['objects']:
            if o.get('support'):
                children += 1
                parent = ids[o['support']]
                assert o['position'][2] >= parent['position'][2]
    assert children > 1000


@lru_cache(maxsize=1)
def _worker_synthesizer():
    # One a worker process: its networks' sessions, one per image size, are made once.
    import torch

    from scene_synth_ros.synth import Synthesizer
    torch.set_num_threads(1)
    return Synthesizer()


def _furnish_group(job):
    """``(first seed, rooms)`` furnished in lockstep (a worker of the test below): for each
    room, whether it is valid with the robot promise kept, whether it holds anything, or the
    error."""
    from scene_synth_ros import lockstep
    from scene_synth_ros.geometry import check_scene
    k, rooms = job
    synth = _worker_synthesizer()
    done = lockstep.run([lambda r=r, i=k + j: synth.generate(r, seed=i)
                         for j, r in enumerate(rooms)])
    return [(r.room.room_type, repr(r)) if isinstance(r, Exception)
            else (check_scene(r.scene).ok and r.robot.kept, bool(r.scene.objects))
            for r in done]


@pytest.mark.slow
def test_every_real_room_of_a_known_type_is_accepted_and_furnished_validly(imported):
    # Real rooms up to 8.8 m (ProcTHOR's bedrooms, living rooms and kitchens, larger than the
    # paper's squares) are kept by the importer and their emptied shells furnished: no
    # collision, on the floor, doors clear, supported, and the robot promise kept. Groups of
    # 16 in lockstep, on two processes.
    from scene_synth_ros.categories import ROOM_TYPES
    from scene_synth_ros.parallel import process_pool
    from scene_synth_ros.render import room_frame_box
    from scene_synth_ros.scene import Scene

    rooms, larger = [], 0
    for fmt in FORMATS:
        result, _ = imported[fmt]
        assert not result.report.dropped('room').get('room too large')
        for d in result.scenes.values():
            room = Scene.from_dict(d).room
            if room.room_type in ROOM_TYPES:
                schema.parse_room_layout(d['room'])     # accepted as a layout
                rooms.append(room)
                larger += not room_frame_box(room).in_square
    assert len(rooms) > 450 and larger > 150
    assert {r.room_type for r in rooms} >= {'bedroom', 'living', 'kitchen'}
    jobs = [(k, rooms[k:k + 16]) for k in range(0, len(rooms), 16)]
    with process_pool(2) as pool:
        results = [v for group in pool.map(_furnish_group, jobs) for v in group]
    furnished = 0
    for room, (valid, holds) in zip(rooms, results, strict=True):
        assert valid is True, (room.room_type, valid, holds)
        furnished += holds
    # a 1.7 m wide bedroom may rightly stay empty; nearly every room gets furniture
    assert furnished >= 0.95 * len(rooms)


@pytest.mark.parametrize('fmt', ['3dfront', 'suncg'])
def test_the_real_houses_of_several_rooms_are_furnished_validly_room_by_room(imported, fmt):
    """Every room of each real house written back as a house layout, furnished together
    (``house_synth.furnish_house``): valid in every room, with the robot promise kept."""
    import json

    from scene_synth_ros.geometry import check_scene
    from scene_synth_ros.house_synth import furnish_house
    from scene_synth_ros.schema import parse_house_layout
    from scene_synth_ros.synth import Synthesizer
    _, folder = imported[fmt]
    synth = Synthesizer()
    for path in sorted((folder / 'houses').glob('*.json')):
        house = parse_house_layout(json.loads(path.read_text()))
        result = furnish_house(synth, house, seed=0)
        for rid, r in result.rooms.items():
            check = check_scene(r.scene, r.allowance)
            assert check.ok, (path.name, rid, check.summary())
            assert r.robot.kept, (path.name, rid, r.robot.sentence())


@pytest.mark.parametrize('fmt', FORMATS)
def test_each_real_house_is_written_back_as_an_empty_house_layout(imported, fmt):
    """``scene-synth import ... --layouts``: a house's kept rooms, in its frame, joined by
    their doors (back to back through the data's thick walls), as a valid house layout;
    a room no door reaches is left out with a report line."""
    import json

    from scene_synth_ros.schema import parse_house_layout
    result, folder = imported[fmt]
    houses = {p.stem: json.loads(p.read_text()) for p in (folder / 'houses').glob('*.json')}
    assert houses == result.houses and houses
    floors = sorted(str(scene['room']['floor']) for scene in result.scenes.values())
    in_houses = []
    for layout in houses.values():
        house = parse_house_layout(layout)
        assert house.entrances and set(house.reachable()) == set(house.rooms)
        in_houses += [str([list(p) for p in r.floor]) for r in house.rooms.values()]
    left_out = [line for line in result.report.lines if line.what == 'layout']
    assert len(in_houses) + len(left_out) == len(floors)
    if fmt == 'procthor':                # one-room houses, their doors lead outside
        assert len(houses) == len(result.scenes) and not left_out
    if fmt == '3dfront':                 # rooms of one house open onto each other
        assert any(len(d['rooms']) == 2 for layout in houses.values()
                   for d in layout['doors'])
