"""Geometry the design rules share, in the package's object frame: an object's front faces
+x of its own frame (its yaw), its depth runs back to front along x and its width across
along y (see ``scene``)."""
from __future__ import annotations

import math

import numpy as np
from shapely.geometry import LineString

from ..render import room_axis_yaw
from ..scene import PlacedObject, Room, wrap_angle


def changed_by(new: PlacedObject | None, owner: PlacedObject, strip, inset: float = 0.0
               ) -> bool:
    """Whether a verdict on ``owner``'s clear ``strip`` can have changed with ``new`` added to
    the room: ``new`` is ``owner``, or its footprint (moved in by ``inset``) enters the strip.
    A piece added changes no other piece's strip (``new`` None: every verdict counts)."""
    return new is None or new.id == owner.id or strip.intersects(new.footprint(inset))


def side(obj: PlacedObject, which: str) -> LineString:
    """One side of the footprint as a segment: 'back', 'front', 'left' or 'right' (left and
    right as seen from behind the object, looking where it faces)."""
    c = obj.corners()       # back-right, front-right, front-left, back-left (counter-clockwise)
    pairs = {'back': (3, 0), 'right': (0, 1), 'front': (1, 2), 'left': (2, 3)}
    i, j = pairs[which]
    return LineString([c[i], c[j]])


def bearing(obj: PlacedObject, target) -> float:
    """Absolute angle in radians between where ``obj`` faces and the direction to
    ``target`` (an object or an (x, y) point)."""
    xy = target.position[:2] if isinstance(target, PlacedObject) else target
    d = np.asarray(xy, dtype=float) - np.asarray(obj.position[:2])
    if not np.any(d):
        return 0.0
    return abs(wrap_angle(math.atan2(d[1], d[0]) - obj.yaw))


def off_axes(room: Room, obj: PlacedObject) -> float:
    """Absolute angle in radians between the object's yaw and the nearest of the room's four
    axis directions (those of its frame): 0 for furniture square to the walls."""
    return abs(math.remainder(obj.yaw - room_axis_yaw(room), math.pi / 2))
