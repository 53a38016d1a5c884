"""Simulator exports: the Gazebo SDF world and the glTF of a whole room."""
import math
from xml.etree import ElementTree as ET

from conftest import EXAMPLES
import numpy as np
import pytest
import trimesh

from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.export import export_gltf, export_sdf, floor_slab, wall_boxes
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


def test_sdf_world_has_every_object_at_its_pose(rooms, tmp_path):
    scene = rooms[1]
    path = export_sdf(scene, tmp_path / 'world.sdf')
    root = ET.parse(path).getroot()
    assert root.tag == 'sdf' and root.get('version') == '1.9'
    models = {m.get('name'): m for m in root.find('world').findall('model')}
    walls = wall_boxes(scene.room)
    assert len(models) == 1 + len(walls) + len(scene.objects)
    for obj in scene.objects:
        m = models[obj.id]
        assert m.findtext('static') == 'true'
        x, y, z, r, p, yaw = map(float, m.findtext('pose').split())
        assert np.allclose([x, y, z], obj.position, atol=1e-5) and r == p == 0
        assert math.isclose(math.remainder(yaw - obj.yaw, 2 * math.pi), 0, abs_tol=1e-5)
        size = list(map(float, m.find('link/collision/geometry/box/size').text.split()))
        assert np.allclose(size, [obj.depth, obj.width, obj.height], atol=1e-5)
        uri = m.findtext('link/visual/geometry/mesh/uri')
        assert (tmp_path / uri).is_file() and uri.endswith('.obj')
    floor = models['floor'].findall('link/visual/geometry/polyline/point')
    assert len(floor) == len(scene.room.floor)


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
    assert proc.returncode == 2 and 'needs --sdf and/or --gltf' in proc.stderr
