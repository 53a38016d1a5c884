"""Simulator exports: the architecture every format shares, the Gazebo SDF world, the glTF of
a whole room, and the `scene-synth export` command for every format."""
import math
from xml.etree import ElementTree as ET

from conftest import EXAMPLES
import numpy as np
import pytest
import trimesh

from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.export import (
    export_gltf,
    export_sdf,
    floor_box,
    floor_slab,
    scene_bodies,
    wall_boxes,
)
from scene_synth_ros.schema import load_scene


@pytest.fixture(scope='module')
def rooms():
    return [generate_room('bedroom', 0, 1), generate_room('living', 0, 2),
            load_scene(EXAMPLES / 'lshaped_living_layout.json')]


def test_walls_leave_the_openings_open(rooms):
    for scene in rooms:
        room = scene.room
        boxes = wall_boxes(room)
        # Solid area = walls x height minus every opening (all openings fit their walls).
        solid = sum(b.size[0] * b.size[2] for b in boxes)
        full = sum(w.length for w in room.walls) * room.wall_height
        holes = sum(o.width * (min(o.sill + o.height, room.wall_height) - o.sill)
                    for o in room.openings)
        assert solid == pytest.approx(full - holes, rel=1e-6)
        # Nothing solid in front of a door below its top.
        for door in room.doors:
            for b in boxes:
                d = math.dist(b.centre[:2], door.position)
                bottom = b.centre[2] - b.size[2] / 2
                if d < door.width / 2 - 1e-6:
                    assert bottom >= door.height - 1e-6


def test_floor_slab_is_the_outline(rooms):
    for scene in rooms:
        slab = floor_slab(scene.room)
        assert slab.is_watertight
        assert slab.volume == pytest.approx(scene.room.area * 0.05, rel=1e-6)


def test_floor_box_covers_the_floor_with_its_top_at_zero(rooms):
    from shapely.geometry import Polygon

    from scene_synth_ros.scene import box_corners
    for scene in rooms:
        box = floor_box(scene.room)
        rect = Polygon(box_corners(box.centre[0], box.centre[1], box.yaw, box.size[1],
                                   box.size[0]))
        assert rect.buffer(1e-6).covers(scene.room.polygon)
        assert box.centre[2] + box.size[2] / 2 == pytest.approx(0.0)


def test_sdf_world_has_every_object_at_its_pose(rooms, tmp_path):
    scene = rooms[1]
    path = export_sdf(scene, tmp_path / 'world.sdf')
    root = ET.parse(path).getroot()
    assert root.tag == 'sdf' and root.get('version') == '1.9'
    models = {m.get('name'): m for m in root.find('world').findall('model')}
    walls = wall_boxes(scene.room)
    assert len(models) == 1 + len(walls) + len(scene.objects)
    for obj, body in zip(scene.objects, scene_bodies(scene), strict=True):
        m = models[obj.id]
        assert m.findtext('static') == 'false'          # dynamic furniture by default
        x, y, z, r, p, yaw = map(float, m.findtext('pose').split())
        assert np.allclose([x, y, z], obj.position, atol=1e-5) and r == p == 0
        assert math.isclose(math.remainder(yaw - obj.yaw, 2 * math.pi), 0, abs_tol=1e-5)
        collisions = m.findall('link/collision')
        assert len(collisions) == len(body.pieces)
        for c, piece in zip(collisions, body.pieces, strict=True):
            size = list(map(float, c.find('geometry/box/size').text.split()))
            assert np.allclose(size, piece.size, rtol=1e-5)
        assert float(m.findtext('link/inertial/mass')) == pytest.approx(body.mass, rel=1e-5)
        uri = m.findtext('link/visual/geometry/mesh/uri')
        assert (tmp_path / uri).is_file() and uri.endswith('.obj')
    floor = models['floor'].findall('link/visual/geometry/polyline/point')
    assert len(floor) == len(scene.room.floor)
    fixed = ET.parse(export_sdf(scene, tmp_path / 'fixed.sdf', fixed=True)).getroot()
    assert {m.findtext('static') for m in fixed.find('world').findall('model')} == {'true'}


def test_gltf_is_y_up_with_room_and_objects(rooms, tmp_path):
    scene = rooms[2]
    path = export_gltf(scene, tmp_path / 'room.glb')
    loaded = trimesh.load(path)
    names = set(loaded.graph.nodes)
    assert 'floor' in names and any(n.startswith('wall_') for n in names)
    assert all(o.id in names for o in scene.objects) or not scene.objects
    lo, hi = loaded.bounds
    assert hi[1] == pytest.approx(scene.room.wall_height, abs=1e-3)   # y is up
    assert lo[1] == pytest.approx(-0.05, abs=1e-3)


def test_export_command(cli, tmp_path):
    scene = EXAMPLES / 'partial_bedroom.json'
    proc = cli('export', scene, '--sdf', tmp_path / 'w.sdf', '--gltf', tmp_path / 'r.glb')
    assert 'wrote' in proc.stdout
    assert (tmp_path / 'w.sdf').is_file() and (tmp_path / 'r.glb').stat().st_size > 1000
    assert (tmp_path / 'w_meshes').is_dir()
    proc = cli('export', scene, ok=False)
    assert proc.returncode == 2 and 'needs --sdf' in proc.stderr


def test_export_command_writes_every_format_into_one_self_contained_folder(cli, tmp_path):
    out = tmp_path / 'out'
    cli('export', EXAMPLES / 'partial_bedroom.json', '--mjcf', out / 'room.xml', '--urdf',
        out / 'room.urdf', '--usd', out / 'room.usda', '--sdf-model', out / 'model.sdf',
        '--mesh-dir', out / 'meshes', '--fixed')
    assert {p.name for p in out.iterdir()} == {
        'room.xml', 'room.urdf', 'room_objects', 'room.poses.json', 'room.usda', 'model.sdf',
        'model_labels.json', 'meshes'}
    # Every mesh reference is relative and resolves inside the folder.
    text = (out / 'room.xml').read_text() + (out / 'room.urdf').read_text()
    assert str(tmp_path) not in text and 'meshes/' in text
    assert ET.parse(out / 'room.xml').getroot().find('.//freejoint') is None     # --fixed


def test_export_command_bad_input_is_one_sentence(cli, tmp_path):
    scene = EXAMPLES / 'partial_bedroom.json'
    blocker = tmp_path / 'file'
    blocker.write_text('not a folder')
    for flag in ('--sdf', '--mjcf', '--urdf', '--usd', '--gltf'):
        proc = cli('export', scene, flag, blocker / 'x' / 'room.out', ok=False)
        assert proc.returncode == 2, flag
        assert proc.stderr.startswith('scene-synth: cannot write') and \
            len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    bad = tmp_path / 'bad.json'
    bad.write_text('{"room": {"room_type": "bedroom"}, "objects": []}')
    proc = cli('export', bad, '--mjcf', tmp_path / 'r.xml', ok=False)
    assert proc.returncode == 2 and str(bad) in proc.stderr and 'Traceback' not in proc.stderr


def test_node_export_formats_are_written_to_export_dir(tmp_path):
    import threading

    from scene_synth_ros.export import FORMATS
    from scene_synth_ros.server import ConfigError, SceneServer, ServerConfig, check
    assert ServerConfig().export_formats == 'sdf,gltf'
    assert check('export_formats', ' USD, mjcf ,usd') == 'usd,mjcf'
    with pytest.raises(ConfigError, match="export format 'obj' is not one of sdf, gltf, mjcf"):
        check('export_formats', 'sdf,obj')
    served = threading.Event()
    server = SceneServer(ServerConfig(auto_generate=False, export_dir=str(tmp_path),
                                      export_formats=','.join(FORMATS)),
                         lambda s: served.set())
    try:
        server.submit_layout((EXAMPLES / 'partial_bedroom.json').read_text())
        assert served.wait(60)
        server.request('reset')          # the export of room 1 is done before reset runs
    finally:
        server.close()
    names = {p.name for p in tmp_path.iterdir()}
    assert {f'room_00001{f.suffix}' for f in FORMATS.values()} | {'room_00001.json'} <= names
    assert {'meshes', 'room_00001_objects', 'room_00001.poses.json'} <= names
    text = (tmp_path / 'room_00001.xml').read_text()
    assert 'file="meshes/' in text and str(tmp_path) not in text
