"""Furnishing a whole house: every room of a house layout by its own room type's networks,
the rooms of each type in lockstep (``lockstep``), so that their forward passes are batched
together.

Each room is furnished as a room alone would be, with the doors on its walls: a door between
two rooms is in both rooms' layouts, so its clearance is kept on both of its sides, and each
room's robot promise (the robot drives between all its doors and reaches every object) joined
with the house's doors, which ``schema.parse_house_layout`` checked lead from an entrance into
every room, makes the house's: every room reachable from an entrance, every object's front
reachable.
"""
from __future__ import annotations

from dataclasses import dataclass
import time
from typing import Callable

import numpy as np

from . import lockstep
from .errors import SceneSynthError, quoted
from .house import House, HouseScene
from .scene import Scene
from .synth import SynthConfig, Synthesis, Synthesizer, check_room_fits


class HouseSynthesisError(SceneSynthError, ValueError):
    """A room of the house could not be furnished; the sentence names the room."""


def check_house_fits(house: House, vocabulary) -> None:
    """``synth.check_room_fits`` of every room (a room too small or too large for its type's
    furniture), as HouseSynthesisError naming the first room that does not fit."""
    for rid, room in house.rooms.items():
        try:
            check_room_fits(room, vocabulary)
        except SceneSynthError as e:
            raise HouseSynthesisError(f'room {quoted(rid)}: {e}') from e


def room_seed(seed: int, index: int) -> int:
    """The synthesis seed of room ``index`` (layout order) of a house furnished with
    ``seed``: distinct for every room and house seed, the same on every machine."""
    return int(np.random.SeedSequence([seed, index]).generate_state(1)[0])


@dataclass
class HouseSynthesis:
    """The outcome of ``furnish_house``: the furnished house and each room's synthesis."""

    scene: HouseScene
    rooms: dict[str, Synthesis]
    seconds: float

    @property
    def robot_kept(self) -> bool:
        return all(r.robot is None or r.robot.kept for r in self.rooms.values())

    def robot_sentence(self) -> str:
        """One line: the promise kept in every room, or the first room that breaks it."""
        for rid, r in self.rooms.items():
            if r.robot is not None and not r.robot.kept:
                return f'room {quoted(rid)}: {r.robot.sentence()}'
        first = next(iter(self.rooms.values())).robot
        who = first.who if first is not None else 'the robot'
        return (f'{who} comes in through the entrance, drives between the doors of every '
                f'room and reaches every object')


def furnish_house(synth: Synthesizer, house: House | HouseScene, seed: int = 0,
                  cancel: Callable[[], bool] | None = None, width: int | None = None,
                  config: SynthConfig | None = None) -> HouseSynthesis:
    """Every room of ``house`` furnished, room ``k`` (layout order) with
    ``room_seed(seed, k)``, the rooms of each room type in lockstep (at most ``width`` at a
    time; all by default), one type after another:
    from empty, or for a HouseScene around the objects its rooms hold. A room that cannot
    be furnished (too large for its type, no weights for its type) raises
    HouseSynthesisError naming it; ``cancel`` and ``config`` (as for
    ``Synthesizer.complete``) are handed to every room."""
    if width is not None and width < 1:
        raise ValueError(f'width must be at least 1, not {width}')
    t0 = time.perf_counter()
    given = house if isinstance(house, HouseScene) else None
    house = house.house if isinstance(house, HouseScene) else house
    check_house_fits(house, synth.vocabulary)       # before any room is furnished
    ids = list(house.rooms)

    def furnish(k: int) -> Callable[[], Synthesis]:
        room = house.rooms[ids[k]]
        held = list(given.scenes[ids[k]].objects) if given is not None else []

        def run() -> Synthesis:
            return synth.complete(Scene(room, held), room_seed(seed, k), cancel, config)
        return run

    # Rooms of one type in lockstep, one type after another: rooms of different types
    # share no forward pass, and taking turns between their networks only evicts each
    # other's weights from the caches (docs/design/speed.md).
    by_type: dict[str, list[int]] = {}
    for k, rid in enumerate(ids):
        by_type.setdefault(house.rooms[rid].room_type, []).append(k)
    results: list = [None] * len(ids)
    for ks in by_type.values():
        for k, out in zip(ks, lockstep.run([furnish(k) for k in ks], width), strict=True):
            results[k] = out
    rooms: dict[str, Synthesis] = {}
    for rid, out in zip(ids, results, strict=True):
        # A room's bad input, named; a cancel or a bug goes up as it is.
        if isinstance(out, SceneSynthError):
            raise HouseSynthesisError(f'room {quoted(rid)}: {out}') from out
        if isinstance(out, BaseException):
            raise out
        rooms[rid] = out
    meta = {**(given.meta if given is not None else {}), **house.meta,
            'generator': 'scene_synth_ros', 'seed': seed}
    scenes = {rid: Scene(house.rooms[rid], r.scene.objects, {}) for rid, r in rooms.items()}
    return HouseSynthesis(HouseScene(house, scenes, meta), rooms, time.perf_counter() - t0)
