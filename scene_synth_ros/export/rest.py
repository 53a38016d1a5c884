"""The rest test: an exported room, loaded in a real physics engine, stands still.

A room is loaded from its exported files (MJCF in MuJoCo, URDF in PyBullet), simulated for
``seconds`` under gravity from the exported poses, and measured per object: how far its
frame (the footprint centre at its bottom) moved, how far it turned, the deepest contact
penetration seen at any step, and the lowest point of its collision pieces at the end. It
passes when every figure is inside ``RestLimits``: at most 1 cm, 1 degree, 5 mm and nothing
below the floor (by more than the penetration allowed). The furniture must be dynamic for the
test to mean anything: it must stand still by physics, not by being fixed.

The engines are imported when a test runs, so the package imports without them.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import json
import math
from pathlib import Path

import numpy as np

from .physics import GRAVITY
from .urdf import poses_path


@dataclass(frozen=True)
class RestLimits:
    """What "stands still" allows."""

    displacement: float = 0.01        # metres
    rotation: float = 1.0             # degrees
    penetration: float = 0.005        # metres, any contact at any step
    below_floor: float = 0.005        # metres a collision point may sink under z = 0


@dataclass
class RestReport:
    """What one simulation found; every figure is the worst over the room's objects."""

    engine: str
    bodies: int
    seconds: float
    displacement: float = 0.0
    rotation: float = 0.0             # degrees
    penetration: float = 0.0          # metres, positive = deeper
    lowest: float = 0.0               # lowest collision point at the end (z, metres)
    moved: dict[str, float] = field(default_factory=dict)     # object -> displacement

    def failures(self, limits: RestLimits = RestLimits()) -> list[str]:
        out = []
        if self.displacement > limits.displacement:
            worst = max(self.moved, key=self.moved.get)
            out.append(f'{worst} moved {self.displacement * 1000:.1f} mm')
        if self.rotation > limits.rotation:
            out.append(f'an object turned {self.rotation:.2f} degrees')
        if self.penetration > limits.penetration:
            out.append(f'a contact penetrated {self.penetration * 1000:.1f} mm')
        if self.lowest < -limits.below_floor:
            out.append(f'a body sank {-self.lowest * 1000:.1f} mm below the floor')
        return out

    def passed(self, limits: RestLimits = RestLimits()) -> bool:
        return not self.failures(limits)


def _angle(q0: np.ndarray, q1: np.ndarray) -> float:
    """Degrees between two unit quaternions (any component order, the same for both)."""
    c = min(1.0, abs(float(np.dot(q0, q1))))
    return math.degrees(2 * math.acos(c))


def _box_corners(centre, half, rotation: np.ndarray, position) -> np.ndarray:
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    return (signs * half + centre) @ rotation.T + position


# ---- MuJoCo -------------------------------------------------------------------------------
def mujoco_rest(path: str | Path, seconds: float = 2.0) -> RestReport:
    """Simulate the MJCF model at ``path`` and measure every body with a free joint."""
    import mujoco  # optional: only the MuJoCo rest test needs the engine
    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    free = [model.jnt_bodyid[j] for j in range(model.njnt)
            if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
    x0, q0 = data.xpos.copy(), data.xquat.copy()
    report = RestReport('mujoco', len(free), seconds)
    deepest = 0.0
    for _ in range(round(seconds / model.opt.timestep)):
        mujoco.mj_step(model, data)
        if data.ncon:
            deepest = min(deepest, float(data.contact.dist[:data.ncon].min()))
    report.penetration = -deepest
    for b in free:
        moved = float(np.linalg.norm(data.xpos[b] - x0[b]))
        report.moved[model.body(b).name] = moved
        report.displacement = max(report.displacement, moved)
        report.rotation = max(report.rotation, _angle(q0[b], data.xquat[b]))
    lows = [0.0]
    for g in range(model.ngeom):
        if model.geom_bodyid[g] in free and model.geom_contype[g]:
            corners = _box_corners(0, model.geom_size[g], data.geom_xmat[g].reshape(3, 3),
                                   data.geom_xpos[g])
            lows.append(float(corners[:, 2].min()))
    report.lowest = min(lows)
    return report


# ---- PyBullet -----------------------------------------------------------------------------
def load_pybullet(path: str | Path, client: int) -> dict[str, int]:
    """Load a URDF export (the room's URDF at ``path`` and the objects listed in its poses
    file) into the PyBullet ``client``; returns the body id of each object by its id.

    Inertia comes from the files (``URDF_USE_INERTIA_FROM_FILE``: without it PyBullet
    recomputes it from the collision shapes)."""
    import pybullet  # optional: only the PyBullet rest test needs the engine
    path = Path(path)
    pybullet.loadURDF(str(path), useFixedBase=True, physicsClientId=client)
    poses = json.loads(poses_path(path).read_text())
    out = {}
    for entry in poses['objects']:
        x, y, z, w = entry['orientation_xyzw']
        out[entry['id']] = pybullet.loadURDF(
            str(path.parent / entry['urdf']), entry['position'], (x, y, z, w),
            useFixedBase=entry['fixed'], flags=pybullet.URDF_USE_INERTIA_FROM_FILE,
            physicsClientId=client)
    return out


def _origin(pybullet, body: int, client: int) -> tuple[np.ndarray, np.ndarray]:
    """The object's frame (position, quaternion xyzw): PyBullet reports the base's centre of
    mass, so the URDF's inertial offset is taken back out."""
    com, orn = pybullet.getBasePositionAndOrientation(body, physicsClientId=client)
    local = pybullet.getDynamicsInfo(body, -1, physicsClientId=client)
    inv_pos, inv_orn = pybullet.invertTransform(local[3], local[4])
    pos, orn = pybullet.multiplyTransforms(com, orn, inv_pos, inv_orn)
    return np.array(pos), np.array(orn)


def _lowest_point(pybullet, body: int, client: int) -> float:
    """The lowest corner of a body's collision boxes (getAABB would add Bullet's margin)."""
    com, orn = pybullet.getBasePositionAndOrientation(body, physicsClientId=client)
    low = math.inf
    for shape in pybullet.getCollisionShapeData(body, -1, physicsClientId=client):
        pos, rot = pybullet.multiplyTransforms(com, orn, shape[5], shape[6])
        matrix = np.array(pybullet.getMatrixFromQuaternion(rot)).reshape(3, 3)
        corners = _box_corners(0, np.array(shape[3]) / 2, matrix, np.array(pos))
        low = min(low, float(corners[:, 2].min()))
    return low


def pybullet_rest(path: str | Path, seconds: float = 2.0, timestep: float = 1 / 240
                  ) -> RestReport:
    """Simulate a URDF export in PyBullet (DIRECT mode, 240 Hz, its default solver) and
    measure every object that is not fixed."""
    import pybullet  # optional: only the PyBullet rest test needs the engine
    client = pybullet.connect(pybullet.DIRECT)
    try:
        pybullet.setGravity(0, 0, -GRAVITY, physicsClientId=client)
        pybullet.setTimeStep(timestep, physicsClientId=client)
        bodies = load_pybullet(path, client)
        dynamic = {k: b for k, b in bodies.items()
                   if pybullet.getDynamicsInfo(b, -1, physicsClientId=client)[0] > 0}
        start = {k: _origin(pybullet, b, client) for k, b in dynamic.items()}
        report = RestReport('pybullet', len(dynamic), seconds)
        deepest = 0.0
        for _ in range(round(seconds / timestep)):
            pybullet.stepSimulation(physicsClientId=client)
            for c in pybullet.getContactPoints(physicsClientId=client):
                deepest = min(deepest, c[8])
        report.penetration = -deepest
        lows = [0.0]
        for k, b in dynamic.items():
            pos, orn = _origin(pybullet, b, client)
            moved = float(np.linalg.norm(pos - start[k][0]))
            report.moved[k] = moved
            report.displacement = max(report.displacement, moved)
            report.rotation = max(report.rotation, _angle(start[k][1], orn))
            lows.append(_lowest_point(pybullet, b, client))
        report.lowest = min(lows)
        return report
    finally:
        pybullet.disconnect(client)
