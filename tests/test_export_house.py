"""A whole house exported as one world in every format: each room's floor, each wall once
(a wall two rooms share written by one of them, the door through it open), every room's
objects; the semantic labels Gazebo's and Isaac Sim's segmentation cameras read; the rest
test in MuJoCo and PyBullet."""
from functools import lru_cache
import itertools
import json
from xml.etree import ElementTree as ET

import numpy as np
import pytest
import shapely
from test_house import HOUSE

from scene_synth_ros.corpus.house_plan import PlanConfig, house_plan
from scene_synth_ros.export import FORMATS, write
from scene_synth_ros.export.architecture import (
    WALL_THICKNESS,
    architecture_of,
    house_wall_boxes,
    wall_boxes,
)
from scene_synth_ros.export.labels import semantic_label
from scene_synth_ros.export.physics import world_bodies
from scene_synth_ros.files import safe_name
from scene_synth_ros.house import HouseScene
from scene_synth_ros.house_synth import furnish_house
from scene_synth_ros.schema import parse_house_layout


@lru_cache(maxsize=None)
def furnished(which: str):
    from scene_synth_ros.synth import Synthesizer
    house = (parse_house_layout(HOUSE) if which == 'three rooms' else
             house_plan(2, 0, PlanConfig(('bedroom', 'bedroom', 'living', 'kitchen',
                                          'bathroom'))))
    return furnish_house(Synthesizer(), house, seed=1).scene


def _footprint(box):
    c, s = np.cos(box.yaw), np.sin(box.yaw)
    hx, hy = box.size[0] / 2, box.size[1] / 2
    corners = [(box.centre[0] + c * x - s * y, box.centre[1] + s * x + c * y)
               for x, y in ((-hx, -hy), (hx, -hy), (hx, hy), (-hx, hy))]
    return shapely.Polygon(corners)


@pytest.mark.parametrize('which', ['three rooms', 'six rooms'])
def test_a_house_has_each_wall_once_its_doors_open_and_no_wall_on_a_floor(which):
    house = furnished(which).house
    walls = house_wall_boxes(house)
    rooms = list(house.rooms.values())
    # two pieces of wall overlap at most where two walls meet, in a corner as thick as they
    # are (a shared wall written twice would overlap along its length)
    for a, b in itertools.combinations(walls, 2):
        za, zb = (a.centre[2] - a.size[2] / 2, a.centre[2] + a.size[2] / 2), \
                 (b.centre[2] - b.size[2] / 2, b.centre[2] + b.size[2] / 2)
        if min(za[1], zb[1]) - max(za[0], zb[0]) > 1e-6:
            overlap = _footprint(a).intersection(_footprint(b)).area
            assert overlap <= WALL_THICKNESS ** 2 + 1e-9, (a.name, b.name, overlap)
    # a wall stands on no floor by more than half the thinnest partition
    for w in walls:
        for room in rooms:
            inside = _footprint(w).intersection(room.polygon.buffer(-0.006)).area
            assert inside < 1e-6, (w.name, room.room_type)
    # every door is open to the robot: no wall piece below 2 m at its centre
    for door in house.doors:
        point = shapely.Point(door.opening.position).buffer(0.05)
        for w in walls:
            if w.centre[2] - w.size[2] / 2 < 2.0:
                assert not _footprint(w).intersects(point), (w.name, door.rooms)
    # outside walls as a room's own; fewer pieces than every room's walls together
    assert len(walls) < sum(len(wall_boxes(r)) for r in rooms)
    assert any(b.size[1] == pytest.approx(WALL_THICKNESS) for b in walls)
    shared = [b for b in walls if b.size[1] < WALL_THICKNESS - 1e-9]
    assert shared


@pytest.mark.parametrize('fmt', sorted(FORMATS))
def test_every_format_writes_a_house_as_one_world(fmt, tmp_path):
    scene = furnished('three rooms')
    path = write(scene, fmt, tmp_path / f'house{FORMATS[fmt].suffix}', tmp_path / 'meshes')
    assert path.is_file()
    ids = [f'{rid}/{o.id}' for rid, o in scene.objects()]
    assert [b.id for b in world_bodies(scene)] == ids
    built = architecture_of(scene)
    assert [n for n, _ in built.floors] == ['floor_0', 'floor_1', 'floor_2']
    if fmt == 'sdf':
        root = ET.parse(path).getroot()
        models = {m.get('name'): m for m in root.find('world').findall('model')}
        assert {'floor_0', 'floor_1', 'floor_2'} <= set(models)
        assert sum(n.startswith('wall_') for n in models) == len(built.walls)
        assert len(models) == 3 + len(built.walls) + len(ids)
    if fmt == 'mjcf':
        mujoco = pytest.importorskip('mujoco')
        model = mujoco.MjModel.from_xml_path(str(path))
        assert model.nbody == 1 + len(ids)


def test_every_object_carries_its_category_as_a_semantic_label(tmp_path):
    scene = furnished('three rooms')
    sdf = write(scene, 'sdf', tmp_path / 'house.sdf')
    world = ET.parse(sdf).getroot().find('world')
    by_name = {m.get('name'): m for m in world.findall('model')}
    bodies = world_bodies(scene)
    for body in bodies + [None]:
        plugin = by_name['floor_0' if body is None else safe_name(body.id)].find('plugin')
        assert plugin.get('filename') == 'gz-sim-label-system'
        assert plugin.get('name') == 'gz::sim::systems::Label'
        want = semantic_label('floor' if body is None else body.category)
        assert int(plugin.find('label').text) == want and 0 < want <= 255
    labels = json.loads((tmp_path / 'house_labels.json').read_text())
    assert labels['floor'] == 1 and labels['wall'] == 2
    assert {b.category for b in bodies} <= set(labels)
    assert len(set(labels.values())) == len(labels)        # one number a name
    pxr = pytest.importorskip('pxr')
    from pxr import Usd, UsdSemantics
    usd = write(scene, 'usd', tmp_path / 'house.usda')
    stage = Usd.Stage.Open(str(usd))
    objects = stage.GetPrimAtPath('/World/Objects').GetChildren()
    assert len(objects) == len(bodies)
    for prim in objects:
        category = prim.GetAttribute('scene_synth:category').Get()
        labels = UsdSemantics.LabelsAPI(prim, 'class').GetLabelsAttr().Get()
        assert list(labels) == [category]
        assert prim.GetAttribute('semantic:Semantics:params:semanticData').Get() == category
    floor = stage.GetPrimAtPath('/World/Room/Floor_0')
    assert list(UsdSemantics.LabelsAPI(floor, 'class').GetLabelsAttr().Get()) == ['floor']
    assert pxr


@pytest.mark.parametrize('which', ['three rooms', 'six rooms'])
def test_a_house_stands_still_in_mujoco_and_pybullet(which, tmp_path):
    pytest.importorskip('mujoco')
    pytest.importorskip('pybullet')
    from scene_synth_ros.export import export_mjcf, export_urdf
    from scene_synth_ros.export.rest import mujoco_rest, pybullet_rest
    scene = furnished(which)
    n = len(scene.objects())
    for report in (mujoco_rest(export_mjcf(scene, tmp_path / 'house.xml')),
                   pybullet_rest(export_urdf(scene, tmp_path / 'house.urdf'))):
        assert report.bodies == n
        assert report.passed(), (report.engine, report.failures())


def test_object_names_stay_apart_whatever_the_ids_of_rooms_and_objects(tmp_path):
    from dataclasses import replace
    mujoco = pytest.importorskip('mujoco')
    scene = furnished('three rooms')
    hall, bed, kitchen = (scene.scenes[r] for r in ('hall', 'bed', 'kitchen'))
    # room 'a/b' holding 'c' and room 'a' holding 'b/c' would both be 'a/b/c' if joined
    odd = HouseScene(scene.house, {
        'a/b': replace(hall, objects=[replace(hall.objects[0], id='c')] + hall.objects[1:]),
        'a': replace(bed, objects=[replace(bed.objects[0], id='b/c')] + bed.objects[1:]),
        'kitchen': kitchen})
    ids = [b.id for b in world_bodies(odd)]
    assert len(set(ids)) == len(ids) == len(scene.objects())
    model = mujoco.MjModel.from_xml_path(str(write(odd, 'mjcf', tmp_path / 'odd.xml')))
    assert model.nbody == 1 + len(ids)
