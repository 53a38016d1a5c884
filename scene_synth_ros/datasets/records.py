"""What a format reader hands to the room assembly (``assemble.py``): one ``RawRoom`` per
room of the source, already in REP-103 (metres, z up), with the objects the reader could
not read at all kept as ``RawObject``s that carry the reason (so every one is a report
line, never an exception)."""
from __future__ import annotations

from dataclasses import dataclass, field
import math
import re

from shapely.geometry import Polygon
from shapely.geometry.base import BaseGeometry


def normalise_category(name: str) -> str:
    """A data set's category as our scenes carry it: lower case, words split by single
    spaces ('Coffee_Table' and 'CoffeeTable' both give 'coffee table'; 'TVStand' gives
    'tv stand')."""
    s = re.sub(r'(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])', ' ', str(name))
    return ' '.join(s.replace('_', ' ').lower().split())


@dataclass
class RawObject:
    """One object of a source room. ``problem`` set: it cannot be placed, and why."""

    source_id: str                        # the data set's id of the object (for the report)
    model_id: str = ''
    category: str = ''                    # normalised (``normalise_category``)
    position: tuple[float, float, float] = (0.0, 0.0, 0.0)   # footprint centre, bottom z
    yaw: float = 0.0
    size: tuple[float, float, float] = (0.0, 0.0, 0.0)       # width, depth, height
    scale: tuple[float, float, float] = (1.0, 1.0, 1.0)      # |scale| along the same axes
    parent: str | None = None             # source id of the object it stands on (data's link)
    problem: str = ''                     # why it cannot be placed ('' if it can)
    reason: str = ''                      # the short key of the problem, for the totals
    note: str = ''                        # kept, but with a guess the report should mention


@dataclass
class RawOpening:
    """A door or window of the source: its footprint on the floor plane (a polygon, or a
    segment on the wall line, whose extent along a wall is the opening's width) and its
    vertical span."""

    kind: str                             # 'door' or 'window'
    footprint: BaseGeometry
    bottom: float
    top: float
    source_id: str = ''
    own: bool = False                     # the room's own (not one of the house's: report it
                                          # when it is on none of the room's walls)


@dataclass
class RawRoom:
    """One room of a source file, in REP-103."""

    source: str                           # the file it came from
    house_id: str
    room_id: str
    room_type: str                        # the data set's own room type
    floor: Polygon | None                 # None: the source has no floor for it
    wall_height: float | None = None
    openings: list[RawOpening] = field(default_factory=list)
    objects: list[RawObject] = field(default_factory=list)
    floor_problem: str = ''               # why there is no floor, when there is none
    parent_links: bool = False            # the data links children to parents (else geometry)
    notes: list[str] = field(default_factory=list)   # mapped-with-a-guess lines


def footprint(obj: RawObject) -> Polygon:
    """The object's footprint rectangle (front along its yaw)."""
    w, d = obj.size[0], obj.size[1]
    c, s = math.cos(obj.yaw), math.sin(obj.yaw)
    x, y = obj.position[0], obj.position[1]
    corners = [(dx * d / 2, dy * w / 2) for dx, dy in ((1, 1), (-1, 1), (-1, -1), (1, -1))]
    return Polygon([(x + c * u - s * v, y + s * u + c * v) for u, v in corners])
