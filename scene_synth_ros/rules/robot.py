"""The robot promise: what a round robot of a given size can get to in a furnished room.

A room keeps the promise for a ``Robot`` when

- the robot can stand just inside every door and drive from each door to every other
  (``geometry.doors_connected`` for the robot's width), and
- it can bring its body within ``Robot.reach`` (its arm's reach) of every first-tier
  object: straight in front of the front for what is operated at its front
  (``OPERATED_FRONT``: storage, fixtures, desks...), anywhere around the footprint for the
  rest (beds, seats, tables, lamps: used from a side, or moved to be used).

The robot drives keeping ``Robot.clearance`` between its body and furniture or walls, so its
centre stays ``radius + clearance`` away from them (``geometry.free_space``). A room without
doors has no place the robot comes in from: only the doors half of the promise applies, and
it holds trivially. Second-tier objects stand on their parents: reaching the parent is
reaching them.

Synthesis keeps the promise by rejecting placements that break it (``Synthesizer.fits``),
as it rejects collisions; ``RobotState`` is the little a step needs to know about the room
before it. ``report`` measures a finished room: the promise, the objects it misses, and the
share of the free floor the robot can drive over from the doors.
"""
from __future__ import annotations

from dataclasses import dataclass
import math

import numpy as np
import shapely
from shapely.geometry import Polygon
from shapely.prepared import prep

from ..categories import members
from ..geometry import door_parts, free_space, free_space_less, owners_connected
from ..scene import PlacedObject, Scene, box_corners
from ..thresholds import ROBOT_RADIUS, ROBOT_REACH

# What is used at its front: one must stand before it (open doors and drawers, sit on a WC,
# work at a desk). The design rules' access module asks the same of the same categories.
OPERATED_FRONT = members('operated front')

# A reach zone that the free space meets only along its edge is touched, not entered.
INSET = 1e-3

# Bounds that keep the promise meaningful: a robot narrower than 10 cm is a point, one over
# 1 m across fits through no door; arms from 5 cm (a bumper) to 1.5 m.
RADIUS_RANGE = (0.05, 0.5)
REACH_RANGE = (0.05, 1.5)
CLEARANCE_RANGE = (0.0, 0.5)


@dataclass(frozen=True)
class Robot:
    """A round robot: its radius, how close its body must come to an object to use it (arm's
    reach), and the clearance it keeps from obstacles while driving (all metres)."""

    # The defaults are the product's robot (``thresholds``), which the design rules judge
    # rooms for too (``rules.access.RULE_ROBOT``).
    radius: float = ROBOT_RADIUS
    reach: float = ROBOT_REACH
    clearance: float = 0.0

    def __post_init__(self):
        for name, (lo, hi) in (('radius', RADIUS_RANGE), ('reach', REACH_RANGE),
                               ('clearance', CLEARANCE_RANGE)):
            value = getattr(self, name)
            if (isinstance(value, bool) or not isinstance(value, (int, float))
                    or not math.isfinite(value) or not lo <= value <= hi):
                raise ValueError(f'robot {name} must be between {lo} and {hi} m, '
                                 f'got {value!r}')
        if self.clearance >= self.reach:
            raise ValueError(f'robot clearance ({self.clearance} m) must be less than its '
                             f'reach ({self.reach} m), or it could never reach anything')

    @property
    def width(self) -> float:
        """The width of floor the robot needs to drive: its body and clearance."""
        return 2 * (self.radius + self.clearance)

    def to_dict(self) -> dict[str, float]:
        return {'radius': self.radius, 'reach': self.reach, 'clearance': self.clearance}


def reach_zone(obj: PlacedObject, robot: Robot) -> Polygon:
    """Where the robot's centre may be to use ``obj``: within its radius plus reach of the
    front side and straight before it (``OPERATED_FRONT``), or of the footprint (others)."""
    return obj.remembered(('reach zone', robot), lambda: _reach_zone(obj, robot))


def _reach_zone(obj: PlacedObject, robot: Robot) -> Polygon:
    r = robot.radius + robot.reach - INSET
    if obj.category not in OPERATED_FRONT:
        return obj.footprint().buffer(r)
    centre = np.asarray(obj.position[:2]) + obj.front * (obj.depth + r) / 2
    return Polygon(box_corners(centre[0], centre[1], obj.yaw, obj.width - 2 * INSET, r))


@dataclass(frozen=True)
class RobotState:
    """What the robot can do in one room: whether the doors are connected, and which
    first-tier objects (indices into ``scene.first_tier``) it reaches from a door."""

    doors_connected: bool
    reached: frozenset[int]
    space: object                     # the free space the robot reaches from the doors
    free: object = None               # all the free space (``geometry.free_space``)


def state(scene: Scene, robot: Robot, free=None) -> RobotState:
    """The robot in ``scene``: one free-space computation for both halves of the promise
    (``free``: the room's free space, when the caller has it)."""
    objects = scene.first_tier
    doors = scene.room.doors
    if not doors:
        return RobotState(True, frozenset(range(len(objects))), shapely.Polygon())
    if free is None:
        free = free_space(scene, robot.width)
    parts, owners = door_parts(scene.room, free, robot.width)
    connected = owners_connected(owners)
    owned = [parts[k] for k in set(owners) if k is not None]
    # One piece holds every door in nearly every room: it is the space (a union of one
    # polygon would only copy it).
    space = owned[0] if len(owned) == 1 else shapely.union_all(owned)
    fast = prep(space)
    reached = frozenset(k for k, o in enumerate(objects)
                        if not space.is_empty and fast.intersects(reach_zone(o, robot)))
    return RobotState(connected, reached, space, free)


def state_after(before: RobotState, after: Scene, robot: Robot) -> RobotState:
    """The robot in ``after``, the room of ``before`` with one more first-tier object (its
    last): its free space is that of ``before`` less the new object (``free_space_less``),
    which saves the union of every footprint that costs most of a step's robot check."""
    if before.free is None or not after.room.doors:
        return state(after, robot)
    return state(after, robot, free_space_less(before.free, after.first_tier[-1], robot.width))


def kept(before: RobotState, now: RobotState, added: int) -> bool:
    """Whether ``now``, the room of ``before`` with first-tier object ``added`` (its index)
    in it, keeps what held ``before``: connected doors stay connected, every object reached
    stays reached, and the new one is reached too."""
    if before.doors_connected and not now.doors_connected:
        return False
    return before.reached | {added} <= now.reached


@dataclass(frozen=True)
class RobotReport:
    """The promise measured on a room."""

    robot: Robot
    doors: int
    doors_connected: bool
    unreachable: tuple[str, ...]          # ids of first-tier objects the robot cannot reach
    reachable_floor: float | None         # share of the free floor it drives over from a door
                                          # (None without doors: it comes in nowhere)

    @property
    def kept(self) -> bool:
        return self.doors_connected and not self.unreachable

    @property
    def who(self) -> str:
        """The robot as the sentences name it."""
        who = f'a robot of radius {self.robot.radius:g} m'
        if self.robot.clearance:
            who += f' keeping {self.robot.clearance:g} m clear'
        return who

    def sentence(self) -> str:
        """One line: the promise kept, or what breaks it."""
        who = self.who
        if not self.doors:
            return f'no doors: {who} has no way in, so only the doors half of the promise ' \
                   f'applies'
        if self.kept:
            doors = ('comes in through the door' if self.doors == 1
                     else f'drives between all {self.doors} doors')
            return (f'{who} {doors} and reaches every object '
                    f'within {self.robot.reach:g} m; {100 * self.reachable_floor:.0f} % of the '
                    f'free floor is reachable')
        broken = []
        if not self.doors_connected:
            broken.append('cannot drive between the doors')
        if self.unreachable:
            shown = ', '.join(self.unreachable[:5])
            more = len(self.unreachable) - 5
            broken.append(f'cannot reach {shown}' + (f' and {more} more' if more > 0 else ''))
        return f'{who} ' + ' and '.join(broken)

    def to_dict(self) -> dict:
        return {**self.robot.to_dict(), 'promise_kept': self.kept,
                'doors_connected': self.doors_connected,
                'unreachable': list(self.unreachable),
                'reachable_floor': (None if self.reachable_floor is None
                                    else round(self.reachable_floor, 4))}


def driven_floor(scene: Scene, robot: Robot, now: RobotState | None = None):
    """The floor the robot's body passes over from the doors: its reachable centres grown
    by its radius."""
    now = now or state(scene, robot)
    if now.space.is_empty:
        return now.space
    return now.space.buffer(robot.radius).intersection(scene.room.polygon)


def report(scene: Scene, robot: Robot, now: RobotState | None = None) -> RobotReport:
    """The promise measured on ``scene`` (``now``: the robot's state in it, when the caller
    has it)."""
    now = now or state(scene, robot)
    objects = scene.first_tier
    unreached = tuple(o.id for k, o in enumerate(objects) if k not in now.reached)
    floor = scene.room.polygon
    if objects:
        floor = floor.difference(shapely.union_all([o.footprint() for o in objects]))
    share = None
    if scene.room.doors:
        share = driven_floor(scene, robot, now).area / floor.area if floor.area > 0 else 0.0
        share = min(share, 1.0)
    return RobotReport(robot, len(scene.room.doors), now.doors_connected, unreached, share)
