"""Exported rooms loaded and simulated in the real engines: MuJoCo (MJCF) and PyBullet (URDF).

The rest test (``export.rest``): 2 s under gravity from the exported poses, then no object
moved more than 1 cm or turned more than 1 degree, no contact ever penetrated more than
5 mm, nothing sank below the floor. Over corpus rooms and synthesized rooms of every type
(L-shaped ones among them) and the example scenes; and it fails a room that is wrong.
"""
from functools import lru_cache
import json
import math
from xml.etree import ElementTree as ET

from conftest import EXAMPLES
import numpy as np
import pytest

from scene_synth_ros.categories import ROOM_TYPES
from scene_synth_ros.corpus import HELDOUT_SEED
from scene_synth_ros.corpus.generate import empty_room, generate_room
from scene_synth_ros.export import export_mjcf, export_urdf, scene_bodies, wall_boxes
from scene_synth_ros.export.rest import (
    RestLimits,
    RestReport,
    _origin,
    load_pybullet,
    mujoco_rest,
    pybullet_rest,
)
from scene_synth_ros.export.urdf import poses_path
from scene_synth_ros.scene import PlacedObject
from scene_synth_ros.schema import load_scene

mujoco = pytest.importorskip('mujoco')
pybullet = pytest.importorskip('pybullet')

# name -> how to make it: ('corpus', type, index) rooms of corpus seed 5, ('synth', type,
# index) held-out shells furnished by the shipped weights, ('example', file, seed).
ROOMS = {
    'corpus-bedroom': ('corpus', 'bedroom', 0), 'corpus-bedroom-L': ('corpus', 'bedroom', 4),
    'corpus-living-L': ('corpus', 'living', 0), 'corpus-living': ('corpus', 'living', 1),
    'corpus-office': ('corpus', 'office', 0), 'corpus-office-L': ('corpus', 'office', 5),
    'corpus-bathroom': ('corpus', 'bathroom', 0),
    'corpus-bathroom-L': ('corpus', 'bathroom', 10),
    'synth-bedroom-L': ('synth', 'bedroom', 1), 'synth-living-L': ('synth', 'living', 0),
    'synth-office': ('synth', 'office', 0), 'synth-bathroom-L': ('synth', 'bathroom', 2),
    'corpus-kitchen': ('corpus', 'kitchen', 0), 'synth-kitchen': ('synth', 'kitchen', 1),
    'synth-dining': ('synth', 'dining', 0), 'synth-hallway': ('synth', 'hallway', 0),
    'example-bedroom': ('example', 'bedroom_layout.json', 0),
    'example-lshaped-living': ('example', 'lshaped_living_layout.json', 1),
    'example-partial-bedroom': ('example', 'partial_bedroom.json', None),
}


@lru_cache(maxsize=1)
def _synthesizer():
    from scene_synth_ros.synth import Synthesizer
    return Synthesizer()


@lru_cache(maxsize=None)
def room(name: str):
    source, what, k = ROOMS[name]
    if source == 'corpus':
        return generate_room(what, 5, k)
    if source == 'synth':
        return _synthesizer().generate(empty_room(what, HELDOUT_SEED, k), seed=k).scene
    scene = load_scene(EXAMPLES / what)
    return scene if k is None else _synthesizer().generate(scene.room, seed=k).scene


def test_the_rooms_cover_every_type_and_l_shapes():
    scenes = [room(n) for n in ROOMS]
    assert {s.room.room_type for s in scenes} == set(ROOM_TYPES)
    assert sum(len(s.room.floor) > 4 for s in scenes) >= 6
    assert sum(len(s.second_tier) for s in scenes) >= 5
    assert all(len(s.objects) >= 2 for s in scenes)


@pytest.mark.parametrize('name', ROOMS)
def test_rooms_stand_still_in_mujoco(name, tmp_path):
    report = mujoco_rest(export_mjcf(room(name), tmp_path / 'room.xml'))
    assert report.bodies == len(room(name).objects)
    assert report.passed(), report.failures()


@pytest.mark.parametrize('name', ROOMS)
def test_rooms_stand_still_in_pybullet(name, tmp_path):
    report = pybullet_rest(export_urdf(room(name), tmp_path / 'room.urdf'))
    assert report.bodies == len(room(name).objects)
    assert report.passed(), report.failures()


def test_mjcf_compiles_to_the_scene(tmp_path):
    scene = room('corpus-living-L')
    path = export_mjcf(scene, tmp_path / 'room.xml')
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    assert model.nbody == 1 + len(scene.objects)
    assert model.njnt == len(scene.objects)
    assert all(t == mujoco.mjtJoint.mjJNT_FREE for t in model.jnt_type)
    assert model.opt.gravity[2] == pytest.approx(-9.81)
    walls = [g for g in range(model.ngeom) if model.geom(g).name.startswith('wall_')]
    assert len(walls) == len(wall_boxes(scene.room))
    for obj, body in zip(scene.objects, scene_bodies(scene), strict=True):
        b = model.body(obj.id)
        assert np.allclose(data.xpos[b.id], obj.position, atol=1e-6)
        assert math.isclose(math.remainder(
            2 * math.atan2(data.xquat[b.id][3], data.xquat[b.id][0]) - obj.yaw, 2 * math.pi),
            0, abs_tol=1e-6)
        assert b.mass[0] == pytest.approx(body.mass, rel=1e-6)
        geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] == b.id]
        collide = [g for g in geoms if model.geom_contype[g]]
        visual = [g for g in geoms if not model.geom_contype[g]]
        assert len(collide) == len(body.pieces) and len(visual) >= 1
        assert all(model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH for g in visual)


def test_urdf_objects_load_at_their_poses_with_their_mass(tmp_path):
    scene = room('corpus-office')
    path = export_urdf(scene, tmp_path / 'room.urdf')
    poses = json.loads(poses_path(path).read_text())
    assert [e['id'] for e in poses['objects']] == [o.id for o in scene.objects]
    client = pybullet.connect(pybullet.DIRECT)
    try:
        bodies = load_pybullet(path, client)
        for obj, body in zip(scene.objects, scene_bodies(scene), strict=True):
            pos, orn = _origin(pybullet, bodies[obj.id], client)
            assert np.allclose(pos, obj.position, atol=1e-6)
            yaw = pybullet.getEulerFromQuaternion(orn)[2]
            assert math.isclose(math.remainder(yaw - obj.yaw, 2 * math.pi), 0, abs_tol=1e-6)
            info = pybullet.getDynamicsInfo(bodies[obj.id], -1, physicsClientId=client)
            assert info[0] == pytest.approx(body.mass, rel=1e-5)
            assert np.allclose(sorted(info[2]), body.principal_inertia()[0], rtol=1e-4)
    finally:
        pybullet.disconnect(client)


def test_fixed_furniture_is_welded_in_both_engines(tmp_path):
    scene = room('corpus-bedroom')
    xml = ET.parse(export_mjcf(scene, tmp_path / 'room.xml', fixed=True)).getroot()
    assert xml.find('.//freejoint') is None
    assert mujoco_rest(tmp_path / 'room.xml').bodies == 0
    path = export_urdf(scene, tmp_path / 'room.urdf', fixed=True)
    assert all(e['fixed'] for e in json.loads(poses_path(path).read_text())['objects'])
    assert pybullet_rest(path).bodies == 0


def _moved(scene, z: float):
    out = scene.copy()
    o = out.objects[0]
    out.objects[0] = PlacedObject(o.id, o.category, o.model_id, (*o.position[:2], z), o.yaw,
                                  o.size)
    for child in out.children_of(o.id):       # what stood on it goes with it
        child.position = (*child.position[:2], z + o.height)
    return out


def test_the_rest_test_fails_an_object_exported_in_the_air(tmp_path):
    # A thing 5 cm above its parent's top (a first-tier object above the floor hangs on its
    # wall, ``geometry.raised``, and is exported fixed).
    scene = room('corpus-bedroom').copy()
    k, o = next((k, o) for k, o in enumerate(scene.objects) if o.support is not None)
    scene.objects[k] = PlacedObject(o.id, o.category, o.model_id,
                                    (*o.position[:2], o.position[2] + 0.05), o.yaw, o.size,
                                    o.support)
    mj = mujoco_rest(export_mjcf(scene, tmp_path / 'room.xml'))
    pb = pybullet_rest(export_urdf(scene, tmp_path / 'room.urdf'))
    for report in (mj, pb):
        assert not report.passed()
        assert any('moved' in f for f in report.failures())
        assert report.displacement == pytest.approx(0.05, abs=0.005)


def test_the_rest_test_fails_an_object_exported_into_the_floor(tmp_path):
    scene = _moved(room('corpus-bedroom'), -0.02)
    for report in (mujoco_rest(export_mjcf(scene, tmp_path / 'room.xml')),
                   pybullet_rest(export_urdf(scene, tmp_path / 'room.urdf'))):
        assert any('penetrated' in f for f in report.failures()), report


def test_rest_report_names_each_failure():
    r = RestReport('x', 2, 2.0, displacement=0.02, rotation=3.0, penetration=0.006,
                   lowest=-0.01, moved={'a': 0.02, 'b': 0.0})
    failures = r.failures()
    assert failures == ['a moved 20.0 mm', 'an object turned 3.00 degrees',
                        'a contact penetrated 6.0 mm', 'a body sank 10.0 mm below the floor']
    assert r.passed(RestLimits(0.05, 5.0, 0.01, 0.02))


def test_odd_rooms_export_in_every_format_and_still_rest(tmp_path):
    from scene_synth_ros.export import FORMATS, write
    turned = room('corpus-living-L').moved(0.52, (3.0, -7.0))      # 30 degrees, off origin
    base = room('corpus-bedroom')
    stranger = base.copy()                      # a category of someone else's data set
    o = stranger.objects[0]
    stranger.objects[0] = PlacedObject(o.id, 'grandfather clock', 'clock_01', o.position,
                                       o.yaw, o.size)
    for k, scene in enumerate((turned, stranger)):
        for fmt, f in FORMATS.items():
            assert write(scene, fmt, tmp_path / f'{k}' / f'room{f.suffix}').is_file()
        assert mujoco_rest(tmp_path / f'{k}' / 'room.xml').passed()
        assert pybullet_rest(tmp_path / f'{k}' / 'room.urdf').passed()


def test_every_category_stands_alone_in_both_engines(tmp_path):
    # One model of each category in its own cell: its pieces, mass and inertia stand it up.
    from scene_synth_ros import catalog
    from scene_synth_ros.categories import CATEGORIES
    from scene_synth_ros.scene import Room, Scene
    cells = math.ceil(math.sqrt(len(CATEGORIES)))          # a square of cells holds them all
    room = Room('living', ((0, 0), (3.0 * cells, 0), (3.0 * cells, 3.0 * cells),
                           (0, 3.0 * cells)))
    objects = [PlacedObject(f'o{k}', c, v.model_id, (1.5 + 3 * (k % cells), 1.5 + 3 * (k // cells),
                                                      0.0), 0.4 * k, v.size)
               for k, c in enumerate(CATEGORIES) for v in catalog.variants(c)[k % 3:k % 3 + 1]]
    scene = Scene(room, objects)
    for report in (mujoco_rest(export_mjcf(scene, tmp_path / 'all.xml')),
                   pybullet_rest(export_urdf(scene, tmp_path / 'all.urdf'))):
        assert report.bodies == len(CATEGORIES)
        assert report.passed(), report.failures()


def _tucked(host: str, host_size, seat: str, seat_size, into: float, yaw: float):
    """A ``seat`` facing ``host`` with ``into`` metres of its footprint under the host's
    edge, the pair turned by ``yaw`` about the room's centre."""
    from scene_synth_ros.scene import Opening, Room, Scene
    room = Room('dining', ((0, 0), (5, 0), (5, 4), (0, 4)), 2.6,
                (Opening('door', (2.5, 0.0), 0.9, 2.05),))
    c, s = math.cos(yaw), math.sin(yaw)
    centre = np.array([2.5, 2.0])
    offset = host_size[1] / 2 + seat_size[1] / 2 - into        # along the host's depth (+x)
    spot = centre + offset * np.array([c, s])
    return Scene(room, [
        PlacedObject('host', host, '', (*centre, 0.0), yaw, host_size),
        PlacedObject('seat', seat, '', (*spot, 0.0), yaw + math.pi, seat_size)])


@pytest.mark.parametrize('host,host_size,seat,seat_size,cut', [
    ('dining table', (1.6, 0.9, 0.75), 'dining chair', (0.45, 0.5, 0.9), True),
    # a stool fits under the island's front overhang as it is
    ('kitchen island', (1.8, 0.9, 0.9), 'bar stool', (0.4, 0.4, 0.75), False)])
def test_a_seat_tucked_under_its_table_rests_in_both_engines(host, host_size, seat,
                                                              seat_size, cut, tmp_path):
    """Tucked as a data set's allowance lets it be (``allowance.Allowance.tucks``), the seat's
    collision pieces are cut out of the table's where they would start inside them, so both
    start apart and stand still."""
    from shapely.geometry import Polygon

    from scene_synth_ros.export.physics import _world_box, body_of
    from scene_synth_ros.geometry import collisions

    def inside(a, b) -> bool:          # does a piece of body a start inside one of b's?
        for p in a.pieces:
            pa, pa0, pa1 = _world_box(p, a)
            for q in b.pieces:
                qa, qa0, qa1 = _world_box(q, b)
                if min(pa1, qa1) - max(pa0, qa0) > 1e-4 and \
                        Polygon(pa).intersection(Polygon(qa)).area > 1e-6:
                    return True
        return False

    for k, (into, yaw) in enumerate(((0.25, 0.0), (0.3, 0.7))):
        scene = _tucked(host, host_size, seat, seat_size, into, yaw)
        assert collisions(scene) == [('host', 'seat')]
        table, chair = scene_bodies(scene)
        # the model's own pieces would start inside the table's; the exported ones do not
        uncut = body_of(scene.objects[1], scene.room)
        assert inside(uncut, table) == cut
        assert (chair.pieces != uncut.pieces) == cut
        assert not inside(chair, table)
        mj = mujoco_rest(export_mjcf(scene, tmp_path / f'{k}.xml'))
        pb = pybullet_rest(export_urdf(scene, tmp_path / f'{k}.urdf'))
        assert mj.passed(), mj.failures()
        assert pb.passed(), pb.failures()


def test_things_inside_a_shelf_and_a_mounted_cabinet_rest_in_both_engines(tmp_path):
    """A book on a shelf board and a bottle inside a fridge (below their parent's top, as a
    data set's allowance lets them be: ``allowance.Allowance.inside``) rest in a cavity cut
    out of their parent; a wall cabinet 1.5 m up is exported fixed, as a wall is."""
    from shapely.geometry import Polygon

    from scene_synth_ros.export.physics import _world_box
    from scene_synth_ros.scene import Opening, Room, Scene
    room = Room('living', ((0, 0), (5, 0), (5, 4), (0, 4)), 2.6,
                (Opening('door', (2.5, 0.0), 0.9, 2.05),))
    scene = Scene(room, [
        PlacedObject('shelf', 'shelving', '', (0.2, 2.0, 0.0), 0.0, (0.9, 0.35, 1.9)),
        PlacedObject('book', 'book', '', (0.2, 1.8, 0.8), 0.3, (0.2, 0.15, 0.25),
                     support='shelf'),
        PlacedObject('vase', 'vase', '', (0.2, 2.25, 1.9), 0.0, (0.12, 0.12, 0.3),
                     support='shelf'),
        PlacedObject('fridge', 'fridge', '', (4.6, 2.0, 0.0), math.pi, (0.6, 0.65, 1.7)),
        PlacedObject('bottle', 'bottle', '', (4.6, 2.1, 0.5), 0.0, (0.08, 0.08, 0.3),
                     support='fridge'),
        PlacedObject('cabinet', 'cabinet', '', (2.5, 3.8, 1.5), math.pi, (0.8, 0.35, 0.6))])
    bodies = {b.id: b for b in scene_bodies(scene)}
    assert [b.id for b in bodies.values() if b.fixed] == ['cabinet']
    for parent, child in (('shelf', 'book'), ('fridge', 'bottle')):
        host, inner = bodies[parent], bodies[child]
        assert len(host.pieces) > 1                      # hollowed: a box is one piece
        # nothing of the parent is left where the child stands, and the child's base sits
        # on what is left below it
        tops = []
        for p in inner.pieces:
            pa, p0, p1 = _world_box(p, inner)
            for q in host.pieces:
                qa, q0, q1 = _world_box(q, host)
                overlap = Polygon(pa).intersection(Polygon(qa)).area
                assert not (min(p1, q1) - max(p0, q0) > 1e-4 and overlap > 1e-6)
                if overlap > 1e-6 and q1 <= p0 + 1e-6:
                    tops.append(q1)
        assert max(tops) == pytest.approx(scene.get(child).position[2], abs=1e-6)
    assert len(bodies['vase'].pieces) == 1 and bodies['shelf'].mass > 0
    mj = mujoco_rest(export_mjcf(scene, tmp_path / 'room.xml'))
    pb = pybullet_rest(export_urdf(scene, tmp_path / 'room.urdf'))
    for report in (mj, pb):
        assert report.passed(), report.failures()
        assert report.bodies == 5                        # all but the mounted cabinet
