"""A furnished room or house as an OpenUSD stage, for Isaac Sim and Omniverse.

The stage is Z up in metres (``upAxis = Z``, ``metersPerUnit = 1``, ``kilogramsPerUnit =
1``) with ``/World`` as its default prim:

- ``/World/PhysicsScene``: a ``UsdPhysics.Scene``, gravity 9.81 m/s^2 along -Z;
- ``/World/Room``: the floor (the outline's slab as a mesh, a collider with the exact
  triangles, ``approximation = none``, which PhysX allows for static colliders) and the wall
  pieces as cubes, all static colliders (no rigid body);
- ``/World/Objects/<object>``: one Xform per object at its pose (translate, rotateZ) with
  ``Visual``, a reference to its catalog model (``<model>.usdc`` in the mesh folder: one
  mesh per material, each bound to a UsdPreviewSurface), and ``Collision``, one cube per
  collision piece of ``physics`` (``CollisionAPI``, purpose ``guide`` so renderers skip
  them). A dynamic object has ``RigidBodyAPI`` and ``MassAPI`` (mass, centre of mass,
  principal moments and axes); a fixed one (``fixed=True``) is a static collider;
- ``/World/PhysicsMaterials/furniture``: friction ``PhysicsConfig.friction``, restitution 0,
  bound with the ``physics`` purpose to every collider.

Each object prim also carries its scene id and category as ``scene_synth:id`` and
``scene_synth:category`` attributes, and its category as its semantic class (``label``),
which Isaac Sim's segmentation reads; the floor's is ``floor``, the walls' ``wall``. A house is
one stage: every room's floor (``Floor_R``), each wall once, every room's objects.
"""
from __future__ import annotations

import errno
import math
from pathlib import Path

from ..catalog import Catalog
from ..house import HouseScene
from ..scene import Scene
from .architecture import FLOOR_RGBA, WALL_RGBA, Architecture, architecture_of, floor_slab
from .labels import FLOOR, WALL
from .meshfiles import MeshFolder
from .physics import DEFAULT_PHYSICS, GRAVITY, Body, PhysicsConfig, world_bodies
from .usd_prims import identifier, mesh, surface


def _place(xformable, translate, yaw: float = 0.0, scale=None) -> None:
    from pxr import Gf  # usd-core: USD exports only
    xformable.AddTranslateOp().Set(Gf.Vec3d(*(float(v) for v in translate)))
    xformable.AddRotateZOp().Set(math.degrees(yaw))
    if scale is not None:
        xformable.AddScaleOp().Set(Gf.Vec3f(*(float(v) for v in scale)))


def _collider(stage, path: str, centre, yaw: float, size, physics_material):
    from pxr import UsdGeom, UsdPhysics, UsdShade  # usd-core: USD exports only
    cube = UsdGeom.Cube.Define(stage, path)
    cube.CreateSizeAttr(1.0)
    _place(cube, centre, yaw, size)
    UsdPhysics.CollisionAPI.Apply(cube.GetPrim())
    UsdShade.MaterialBindingAPI.Apply(cube.GetPrim()).Bind(
        physics_material, UsdShade.Tokens.weakerThanDescendants, 'physics')
    return cube


def label(prim, category: str) -> None:
    """``category`` as the prim's semantic class: ``UsdSemantics.LabelsAPI`` (instance
    ``class``, Isaac Sim 5 and later) and the ``SemanticsAPI`` attributes Isaac Sim read
    before it (instance ``Semantics``), which descendants inherit in segmentation."""
    from pxr import Sdf, UsdSemantics  # usd-core: USD exports only
    UsdSemantics.LabelsAPI.Apply(prim, 'class').CreateLabelsAttr([category])
    prim.AddAppliedSchema('SemanticsAPI:Semantics')
    for key, value in (('semanticType', 'class'), ('semanticData', category)):
        prim.CreateAttribute(f'semantic:Semantics:params:{key}',
                             Sdf.ValueTypeNames.String).Set(value)


def _room(stage, built: Architecture, physics_material) -> None:
    from pxr import UsdGeom, UsdPhysics, UsdShade  # usd-core: USD exports only
    UsdGeom.Xform.Define(stage, '/World/Room')
    floor_look = surface(stage, '/World/Looks/floor', FLOOR_RGBA, 0.0, 0.9)
    wall_look = surface(stage, '/World/Looks/wall', WALL_RGBA, 0.0, 0.9)
    for name, room in built.floors:
        slab = floor_slab(room)
        floor = mesh(stage, f'/World/Room/{name.capitalize()}', slab.vertices, slab.faces)
        UsdShade.MaterialBindingAPI.Apply(floor.GetPrim()).Bind(floor_look)
        UsdPhysics.CollisionAPI.Apply(floor.GetPrim())
        UsdPhysics.MeshCollisionAPI.Apply(floor.GetPrim()).CreateApproximationAttr('none')
        UsdShade.MaterialBindingAPI(floor.GetPrim()).Bind(
            physics_material, UsdShade.Tokens.weakerThanDescendants, 'physics')
        label(floor.GetPrim(), FLOOR)
    for box in built.walls:
        cube = _collider(stage, f'/World/Room/{box.name}', box.centre, box.yaw, box.size,
                         physics_material)
        UsdShade.MaterialBindingAPI(cube.GetPrim()).Bind(wall_look)
        label(cube.GetPrim(), WALL)


def _object(stage, path: str, body: Body, model_file: str, fixed: bool,
            physics_material) -> None:
    from pxr import Gf, Sdf, UsdGeom, UsdPhysics  # usd-core: USD exports only
    xform = UsdGeom.Xform.Define(stage, path)
    _place(xform, body.position, body.yaw)
    prim = xform.GetPrim()
    prim.CreateAttribute('scene_synth:id', Sdf.ValueTypeNames.String).Set(body.id)
    prim.CreateAttribute('scene_synth:category', Sdf.ValueTypeNames.String).Set(body.category)
    label(prim, body.category)
    visual = UsdGeom.Xform.Define(stage, f'{path}/Visual')
    visual.GetPrim().GetReferences().AddReference(model_file)
    UsdGeom.Scope.Define(stage, f'{path}/Collision')
    for k, piece in enumerate(body.pieces):
        cube = _collider(stage, f'{path}/Collision/piece_{k}', piece.centre, 0.0, piece.size,
                         physics_material)
        cube.CreatePurposeAttr(UsdGeom.Tokens.guide)
    if fixed:
        return
    UsdPhysics.RigidBodyAPI.Apply(prim)
    mass = UsdPhysics.MassAPI.Apply(prim)
    mass.CreateMassAttr(float(body.mass))
    mass.CreateCenterOfMassAttr(Gf.Vec3f(*body.com))
    moments, axes = body.principal_inertia()
    mass.CreateDiagonalInertiaAttr(Gf.Vec3f(*(float(v) for v in moments)))
    q = Gf.Matrix3d(*(float(v) for v in axes.T.ravel())).ExtractRotation().GetQuat()
    mass.CreatePrincipalAxesAttr(Gf.Quatf(q))


def export_usd(scene: Scene | HouseScene, path: str | Path, mesh_dir: str | Path | None = None,
               fixed: bool = False, physics: PhysicsConfig = DEFAULT_PHYSICS,
               catalog: Catalog | None = None) -> Path:
    """Write ``scene``, a room or a whole house, as a USD stage to ``path`` (``.usda`` text,
    ``.usd``/``.usdc`` binary); each catalog model goes to ``mesh_dir`` (default
    ``<stem>_meshes/`` beside the file) as a ``.usdc`` layer the stage references by
    relative path. ``fixed`` makes the
    furniture static colliders instead of rigid bodies."""
    from pxr import Gf, Sdf, Tf, Usd, UsdGeom, UsdPhysics, UsdShade  # usd-core: USD exports only
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    meshes = MeshFolder(mesh_dir or path.parent / f'{path.stem}_meshes', path.parent)
    # Authored in a layer at its destination, so that the relative references to the model
    # files resolve while the stage composes (an anonymous layer has no folder).
    try:
        layer = Sdf.Layer.FindOrOpen(str(path)) if path.exists() else None
        if layer is None:
            layer = Sdf.Layer.CreateNew(str(path))
    except Tf.ErrorException:
        layer = None
    if layer is None:
        raise OSError(errno.EACCES, f'USD cannot create a layer at {path}')
    layer.Clear()
    stage = Usd.Stage.Open(layer)
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    UsdGeom.SetStageMetersPerUnit(stage, 1.0)
    UsdPhysics.SetStageKilogramsPerUnit(stage, 1.0)
    world = UsdGeom.Xform.Define(stage, '/World')
    stage.SetDefaultPrim(world.GetPrim())
    physics_scene = UsdPhysics.Scene.Define(stage, '/World/PhysicsScene')
    physics_scene.CreateGravityDirectionAttr(Gf.Vec3f(0, 0, -1))
    physics_scene.CreateGravityMagnitudeAttr(GRAVITY)
    physics_material = UsdShade.Material.Define(stage, '/World/PhysicsMaterials/furniture')
    surface = UsdPhysics.MaterialAPI.Apply(physics_material.GetPrim())
    surface.CreateStaticFrictionAttr(physics.friction)
    surface.CreateDynamicFrictionAttr(physics.friction)
    surface.CreateRestitutionAttr(0.0)
    _room(stage, architecture_of(scene), physics_material)
    UsdGeom.Xform.Define(stage, '/World/Objects')
    taken: set[str] = set()
    for body in world_bodies(scene, physics, catalog):
        model_file = './' + meshes.relative(meshes.usd(body.variant))
        name = identifier(body.id, taken)
        _object(stage, f'/World/Objects/{name}', body, model_file, fixed or body.fixed,
                physics_material)
    if not layer.Save():
        raise OSError(errno.EACCES, f'USD cannot save {path}')
    return path
