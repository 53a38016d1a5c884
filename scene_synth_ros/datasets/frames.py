"""From the data sets' frames to REP-103 (metres, right-handed, z up, yaw about +z).

Two kinds of source frame, one conversion each:

* **right-handed, y up** (3D-FRONT, SUNCG): ``(x, y, z) -> (x, -z, y)``, the rotation of
  +90 degrees about x (determinant +1). The plain axis swap ``(x, z, y)`` would be a
  *mirror* (determinant -1): it turns every counter-clockwise floor clockwise and puts a
  bed's left nightstand on its right. ``tests/test_datasets_frames.py`` keeps the two apart.
* **left-handed, y up** (ProcTHOR, i.e. Unity): ``(x, y, z) -> (x, z, y)``. Unity's x is
  east, z north and y up, so this swap is the right map; the mirror it contains as a matrix
  is exactly Unity's own left-handedness. A Unity rotation of ``a`` degrees about y turns
  clockwise seen from above, so it is a yaw of ``-a``.

An object is placed by the linear part ``M`` of its transform (rotation times scale, in
the source frame) and its translation. Its *front* is a model axis ``f`` (3D-FUTURE and
SUNCG models face +z, Unity assets +z); the yaw is the direction of ``C·M·f`` in the floor
plane (``C`` the conversion above). A negative scale is a mirror of the model: along the
front axis it turns the front around (``M·f`` points back), across it it only swaps left
and right, which a footprint does not see. ``size`` is (width, depth, height): the model's
extents along its lateral axis, ``f`` and its up axis, each times the length of ``M``'s
column for that axis (the scale).
"""
from __future__ import annotations

from dataclasses import dataclass
import math
from typing import Sequence

import numpy as np

# Right-handed y-up -> REP-103: +90 degrees about x.
RH_YUP_TO_ZUP = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
# Unity (left-handed y-up) -> REP-103: the axis swap.
UNITY_TO_ZUP = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]])

# Model axes (source frame) of the formats' models: x lateral, y up, z front.
LATERAL, UP, FRONT = 0, 1, 2

MAX_TILT_DEG = 10.0          # an object leaning more than this is not standing upright
MIN_DETERMINANT = 1e-9       # |det M| below this: the transform squashes the model flat


class BrokenTransform(ValueError):
    """A transform that places nothing: not finite, singular, or tipping the object over."""


def quaternion_matrix(q: Sequence[float]) -> np.ndarray:
    """Rotation matrix of a quaternion given as (x, y, z, w), normalised first."""
    x, y, z, w = (float(v) for v in q)
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if not math.isfinite(n) or n < 1e-9:
        raise BrokenTransform(f'the rotation quaternion has length {n:.3g}')
    x, y, z, w = x / n, y / n, z / n, w / n
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def column_major(values: Sequence[float]) -> np.ndarray:
    """A 4x4 matrix from 16 numbers in column-major order (SUNCG's ``transform``)."""
    a = np.asarray(values, dtype=float)
    if a.shape != (16,):
        raise BrokenTransform(f'a transform needs 16 numbers, got {a.size}')
    return a.reshape(4, 4).T


def unity_euler_matrix(x_deg: float, y_deg: float, z_deg: float) -> np.ndarray:
    """Unity's rotation of Euler angles in degrees (applied z, then x, then y), in Unity's
    own axes."""
    ax, ay, az = (math.radians(float(v)) for v in (x_deg, y_deg, z_deg))
    cx, sx, cy, sy, cz, sz = (math.cos(ax), math.sin(ax), math.cos(ay), math.sin(ay),
                              math.cos(az), math.sin(az))
    # Unity's matrices act on left-handed coordinates; the formulas are the usual ones.
    rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return ry @ rx @ rz


@dataclass(frozen=True)
class Placement:
    """What a transform says about an object in REP-103."""

    yaw: float                  # radians, direction of the model's front
    scale: tuple[float, float, float]   # |M| along (lateral, front, up), metres per unit
    mirrored: bool              # det M < 0: the model is a mirror image


def placement(m: np.ndarray, conversion: np.ndarray, front_axis: int = FRONT,
              up_axis: int = UP) -> Placement:
    """Yaw and scale of an object whose model-to-source linear map is ``m`` (3x3)."""
    m = np.asarray(m, dtype=float)
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        raise BrokenTransform('the transform has numbers that are not finite')
    det = float(np.linalg.det(m))
    if abs(det) < MIN_DETERMINANT:
        raise BrokenTransform('the transform is singular (it squashes the model flat)')
    lateral_axis = 3 - front_axis - up_axis
    cols = np.linalg.norm(m, axis=0)
    up = conversion @ m[:, up_axis]
    up = up / np.linalg.norm(up)
    tilt = math.degrees(math.acos(max(-1.0, min(1.0, float(up[2])))))
    if tilt > MAX_TILT_DEG:
        raise BrokenTransform(f'the object leans {tilt:.0f} degrees off the vertical '
                              f'(at most {MAX_TILT_DEG:.0f} are read as standing)')
    front = conversion @ m[:, front_axis]
    if math.hypot(front[0], front[1]) < 1e-9:
        raise BrokenTransform('the object faces straight up or down')
    return Placement(math.atan2(front[1], front[0]),
                     (float(cols[lateral_axis]), float(cols[front_axis]),
                      float(cols[up_axis])),
                     det < 0)
