"""What real rooms do that the strict validity checks of ``geometry`` would refuse.

Real rooms tuck chairs under tables and stools under counters, stand things inside shelves,
on a sofa's seat or in a fridge, and a data set may spawn small objects a few centimetres
above their support for its simulator to drop. Read as boxes, the first is a collision and
the others are under-supported objects. An ``Allowance`` names what a room may do instead:

* ``tucks``: (tucked category, host category, metres): the tucked footprint may enter the
  host's by up to that depth (the overlap's shorter side), either way round;
* ``inside``: (parent category, fraction): a second-tier object may rest inside its parent's
  box, its base at least that fraction of the parent's height above the parent's base
  (shelves, seats, the inside of a fridge), not only on its top;
* ``settle``: metres a second-tier object may hover above its support surface;
* ``door_depth``: metres of clear floor a door's zone needs at most (None: the strict zone,
  ``geometry.door_zone``); the robot must still drive between the doors.

``STRICT`` allows none of it: what the procedural corpus and synthesis with the shipped
bundles are held to. A data set's own allowance is derived from its rooms by
``datasets.allowance.derive`` at import (``dataset.yaml``'s ``allowance``), and the
evaluation holds that data set's held-out and synthesized rooms to the same allowance.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .errors import DatasetError


@dataclass(frozen=True)
class Allowance:
    tucks: tuple[tuple[str, str, float], ...] = ()
    inside: tuple[tuple[str, float], ...] = ()
    settle: float = 0.0
    door_depth: float | None = None

    def tuck_depth(self, a: str, b: str) -> float:
        """Metres the footprints of categories ``a`` and ``b`` may overlap (0: not at all)."""
        return max((depth for t, h, depth in self.tucks if {t, h} == {a, b}), default=0.0)

    def lowest_inside(self, parent: str) -> float | None:
        """The lowest base, as a fraction of the parent's height above its base, at which an
        object may rest inside a ``parent`` (None: only on its top)."""
        return next((low for p, low in self.inside if p == parent), None)

    def to_dict(self) -> dict[str, Any]:
        return {'tucks': [{'tucked': t, 'host': h, 'depth': round(d, 3)}
                          for t, h, d in self.tucks],
                'inside': {p: round(low, 3) for p, low in self.inside},
                'settle': round(self.settle, 3),
                'door_depth': None if self.door_depth is None else round(self.door_depth, 3)}

    @classmethod
    def from_dict(cls, d: Any, where: str = 'allowance') -> 'Allowance':
        """An allowance from ``to_dict``'s form (possibly edited by hand); a problem raises
        ``DatasetError`` naming the field."""
        if not isinstance(d, dict):
            raise DatasetError(f'{where} must be a mapping with tucks, inside and settle')
        tucks = []
        for i, t in enumerate(d.get('tucks') or []):
            if not (isinstance(t, dict) and isinstance(t.get('tucked'), str)
                    and isinstance(t.get('host'), str) and _metres(t.get('depth'))):
                raise DatasetError(f'{where}.tucks[{i}] must have a tucked and a host '
                                   'category and a depth of 0 to 5 metres')
            tucks.append((t['tucked'], t['host'], float(t['depth'])))
        inside = d.get('inside') or {}
        if not isinstance(inside, dict) or not all(
                isinstance(p, str) and _fraction(v) for p, v in inside.items()):
            raise DatasetError(f'{where}.inside must map parent categories to fractions '
                               'of their height from 0 to 1')
        settle = d.get('settle', 0.0)
        if not _metres(settle):
            raise DatasetError(f'{where}.settle must be a number of metres from 0 to 5')
        door = d.get('door_depth')
        if door is not None and not _metres(door):
            raise DatasetError(f'{where}.door_depth must be empty or a number of metres '
                               'from 0 to 5')
        return cls(tuple(tucks), tuple((p, float(v)) for p, v in inside.items()),
                   float(settle), None if door is None else float(door))


def of_scene(meta: dict[str, Any]) -> Allowance:
    """The allowance a synthesized scene was furnished under (its ``meta``'s ``allowance``,
    which ``Synthesizer`` writes for networks trained on a data set); ``STRICT`` without
    one."""
    return STRICT if meta.get('allowance') is None else Allowance.from_dict(
        meta['allowance'], 'the scene\'s meta.allowance')


def _metres(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and 0.0 <= v <= 5.0


def _fraction(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and 0.0 <= v <= 1.0


STRICT = Allowance()
