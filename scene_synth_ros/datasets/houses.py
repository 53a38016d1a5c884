"""A data set's houses as empty house layouts (``msg_schemas/house_layout.schema.json``):
the rooms an import kept, in their house's frame, joined by their doors (``scene-synth
import ... --layouts``), so that real floor plans can be furnished again and again.

A door of a room joins it to the room behind its wall, the one whose floor its width
reaches through that wall, back to back at most a wall's thickness away (``house.Floors``,
``house.across``; a data set's house has thick walls, and each room of it
has the door on its own wall face); a door with no kept room behind it leads out of the
house's kept rooms (to the outside, or into a room the import left out) and counts as an
entrance. Rooms that no entrance reaches are left out, with a note.
"""
from __future__ import annotations

from ..house import Floors, House, HouseDoor, across
from ..scene import Room
from ..thresholds import OPENING_TOLERANCE


def _same(a, b) -> bool:
    """Whether two openings on one wall line are one door (their spans overlap)."""
    gap = sum((p - q) ** 2 for p, q in zip(a.position, b.position, strict=True)) ** 0.5
    return gap < (a.width + b.width) / 2


def house_of(rooms: dict[str, Room], house_id: str = '') -> tuple[House | None, list[str]]:
    """The house of a house's imported ``rooms`` (by id, in the house's frame), without
    their doors' duplicates, and a note for each room or house left out."""
    doors: list[HouseDoor] = []
    ids = list(rooms)
    floors = Floors(rooms.values())
    taken: dict[str, list] = {rid: [] for rid in rooms}      # door copies already joined
    for k, (rid, room) in enumerate(rooms.items()):
        for door in room.doors:
            if any(door is t for t in taken[rid]):
                continue
            wall = room.wall_of(door, OPENING_TOLERANCE)
            # The first room behind the wall whose own wall takes the door.
            other = moved = None
            for j in floors.behind(door, wall, k):
                moved = (door if rooms[ids[j]].wall_of(door, OPENING_TOLERANCE) is not None
                         else across(rooms[ids[j]], door, wall))
                if moved is not None:
                    other = ids[j]
                    break
            if moved is None:
                doors.append(HouseDoor((rid,), door))
                continue
            twin = next((d for d in rooms[other].doors if _same(d, moved)
                         and not any(d is t for t in taken[other])), None)
            if twin is not None:
                taken[other].append(twin)
            doors.append(HouseDoor((rid, other), door, {rid: door, other: moved}))
    house = House(dict(rooms), tuple(doors), {'house_id': house_id} if house_id else {})
    notes = []
    if not house.entrances:
        return None, [f'house {house_id}: no door leads out of its kept rooms']
    reached = set(house.reachable())
    for rid in rooms:
        if rid not in reached:
            notes.append(f'house {house_id}: room {rid} is reached by no door, left out')
    if len(reached) < len(rooms):
        kept = {rid: r for rid, r in rooms.items() if rid in reached}
        house = House(kept, tuple(d for d in doors if set(d.rooms) <= reached), house.meta)
    return house, notes

