"""The OpenUSD export opened with pxr (usd-core): stage metadata, prims, transforms, materials
and the UsdPhysics schemas, against the scene."""
import math

import numpy as np
import pytest

from scene_synth_ros.corpus.generate import generate_room
from scene_synth_ros.export import export_usd, scene_bodies, wall_boxes

pxr = pytest.importorskip('pxr')
from pxr import Gf, Usd, UsdGeom, UsdPhysics, UsdShade  # noqa: E402


@pytest.fixture(scope='module')
def scene():
    return generate_room('living', 5, 0)                   # L-shaped, with second-tier objects


@pytest.fixture(scope='module')
def stage(scene, tmp_path_factory):
    path = export_usd(scene, tmp_path_factory.mktemp('usd') / 'room.usda')
    return Usd.Stage.Open(str(path))


def test_stage_is_z_up_in_metres_with_gravity(stage):
    assert UsdGeom.GetStageUpAxis(stage) == UsdGeom.Tokens.z
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    assert UsdPhysics.GetStageKilogramsPerUnit(stage) == 1.0
    assert stage.GetDefaultPrim().GetPath() == '/World'
    physics = UsdPhysics.Scene(stage.GetPrimAtPath('/World/PhysicsScene'))
    assert tuple(physics.GetGravityDirectionAttr().Get()) == (0, 0, -1)
    assert physics.GetGravityMagnitudeAttr().Get() == pytest.approx(9.81)


def test_prims_are_the_room_and_its_objects(stage, scene):
    room = stage.GetPrimAtPath('/World/Room')
    walls = [p for p in room.GetChildren() if p.GetName().startswith('wall_')]
    assert len(walls) == len(wall_boxes(scene.room))
    assert all(p.HasAPI(UsdPhysics.CollisionAPI) and not p.HasAPI(UsdPhysics.RigidBodyAPI)
               for p in walls)
    floor = stage.GetPrimAtPath('/World/Room/Floor')
    assert floor.HasAPI(UsdPhysics.CollisionAPI)
    assert UsdPhysics.MeshCollisionAPI(floor).GetApproximationAttr().Get() == 'none'
    objects = stage.GetPrimAtPath('/World/Objects').GetChildren()
    assert [p.GetAttribute('scene_synth:id').Get() for p in objects] == \
        [o.id for o in scene.objects]


def test_objects_are_at_their_poses_with_mass_and_colliders(stage, scene):
    for obj, body in zip(scene.objects, scene_bodies(scene), strict=True):
        prim = stage.GetPrimAtPath(f'/World/Objects/{obj.id}')
        assert prim.GetAttribute('scene_synth:category').Get() == obj.category
        m = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
        assert np.allclose(m.ExtractTranslation(), obj.position, atol=1e-6)
        x_axis = m.TransformDir(Gf.Vec3d(1, 0, 0))
        assert math.isclose(math.remainder(math.atan2(x_axis[1], x_axis[0]) - obj.yaw,
                                           2 * math.pi), 0, abs_tol=1e-6)
        assert prim.HasAPI(UsdPhysics.RigidBodyAPI) and prim.HasAPI(UsdPhysics.MassAPI)
        mass = UsdPhysics.MassAPI(prim)
        assert mass.GetMassAttr().Get() == pytest.approx(body.mass, rel=1e-6)
        assert np.allclose(mass.GetCenterOfMassAttr().Get(), body.com, atol=1e-6)
        axes = np.array(Gf.Matrix3d(Gf.Rotation(Gf.Quatd(mass.GetPrincipalAxesAttr().Get()))))
        tensor = axes.T @ np.diag(mass.GetDiagonalInertiaAttr().Get()) @ axes
        assert np.allclose(tensor, body.inertia, rtol=1e-5, atol=1e-6 * body.inertia.max())
        pieces = stage.GetPrimAtPath(f'/World/Objects/{obj.id}/Collision').GetChildren()
        assert len(pieces) == len(body.pieces)
        for cube, piece in zip(pieces, body.pieces, strict=True):
            assert cube.HasAPI(UsdPhysics.CollisionAPI)
            assert UsdGeom.Imageable(cube).GetPurposeAttr().Get() == UsdGeom.Tokens.guide
            box = UsdGeom.Boundable(cube).ComputeLocalBound(Usd.TimeCode.Default(), 'guide')
            lo, hi = box.ComputeAlignedRange().GetMin(), box.ComputeAlignedRange().GetMax()
            assert np.allclose(np.subtract(hi, lo), piece.size, atol=1e-6)


def test_visual_meshes_come_from_the_model_files_with_materials(stage, scene):
    for obj in scene.objects:
        visual = stage.GetPrimAtPath(f'/World/Objects/{obj.id}/Visual')
        meshes = [p for p in Usd.PrimRange(visual) if p.IsA(UsdGeom.Mesh)]
        assert meshes, obj.id
        for mesh in meshes:
            material, _ = UsdShade.MaterialBindingAPI(mesh).ComputeBoundMaterial()
            assert material, mesh.GetPath()
            shader = material.ComputeSurfaceSource()[0]
            assert shader.GetIdAttr().Get() == 'UsdPreviewSurface'
            assert len(UsdGeom.Mesh(mesh).GetPointsAttr().Get()) > 0
    # The models are referenced by relative paths, so the folder moves as a whole.
    layer = stage.GetRootLayer()
    refs = [a for a in layer.GetExternalReferences()]
    assert refs and all(r.startswith('./') for r in refs)


def test_fixed_furniture_is_static_colliders(scene, tmp_path):
    stage = Usd.Stage.Open(str(export_usd(scene, tmp_path / 'fixed.usd', fixed=True)))
    objects = stage.GetPrimAtPath('/World/Objects').GetChildren()
    assert objects and not any(p.HasAPI(UsdPhysics.RigidBodyAPI) for p in objects)
    assert all(c.HasAPI(UsdPhysics.CollisionAPI)
               for p in objects for c in p.GetChild('Collision').GetChildren())
