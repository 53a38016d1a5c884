"""An imported data set as training data: its room types' category sets and its rooms.

``room_type_specs`` turns the data-set description (``dataset.yaml``, possibly edited by
the user) into the package's ``categories.RoomTypeSpec``, one per room type. What the
synthesizer cannot place is left out, each for a stated reason:

* ``mounted`` categories (paintings, wall TVs: neither on the floor nor on an object) are
  architecture-like and out of the pipeline, as doors and windows are;
* a second-tier category keeps as parents only first-tier categories (the pipeline places
  every first-tier object before any second-tier one, so an object on another second-tier
  object cannot be inserted); one left with no parent is dropped.

``load_rooms`` reads the data set's scenes of one room type as ``Scene`` objects holding
only what the spec can place: objects of categories it lacks, objects whose tier disagrees
with their category's (a plant on the floor where most plants stand on tables), and objects
on a parent that was dropped are removed and counted. ``split`` divides the rooms into
training and held-out rooms by a seeded shuffle of their file names, so that training and
evaluation agree on which rooms were held out.
"""
from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
import json
from pathlib import Path

import numpy as np

from ..categories import CategoryInfo, RoomCategorySpec, RoomTypeSpec
from ..errors import DatasetError
from ..scene import Scene
from .description import FILE_NAME, DatasetDescription, RoomTypeDescription, load

HELD_OUT_FRACTION = 0.2


def room_type_spec(rt: RoomTypeDescription, source: str = '') -> RoomTypeSpec:
    """The category set of one room type of a data set (see the module docstring)."""
    tiers = {c.name: c.tier for c in rt.categories}
    cats = []
    for c in rt.categories:
        if c.tier == 'mounted':
            continue
        parents = tuple(p for p in c.supported_by if tiers.get(p) == 'first')
        if c.tier == 'second' and not parents:
            continue
        info = CategoryInfo(c.name, c.tier, (c.width[0], c.width[2]), (c.depth[0], c.depth[2]),
                            (c.height[0], c.height[2]), parents, c.against_wall,
                            f'{c.count} in {rt.rooms} {rt.room_type} rooms'
                            + (f' of {source}' if source else ''), c.roles)
        cats.append(RoomCategorySpec(info, c.count, c.per_room, c.importance))
    if not any(c.tier == 'first' for c in cats):
        raise DatasetError(f'room type {rt.room_type!r} of the data set has no category that '
                           f'stands on the floor, so there is nothing to place first')
    return RoomTypeSpec(rt.room_type, rt.rooms, rt.size_cap, tuple(cats), rt.doors_per_room,
                        rt.windows_per_room)


def room_type_specs(desc: DatasetDescription) -> dict[str, RoomTypeSpec]:
    return {name: room_type_spec(rt, desc.format) for name, rt in desc.room_types.items()}


def describe_dir(data_dir: str | Path) -> DatasetDescription:
    """The description of an imported data set's folder (its ``dataset.yaml``)."""
    path = Path(data_dir) / FILE_NAME
    if not path.is_file():
        raise DatasetError(f'{data_dir}: no {FILE_NAME}; import a data set there first '
                           f'(scene-synth import FORMAT INPUT... --out {data_dir})')
    return load(path)


@dataclass
class LoadedRooms:
    """The rooms of one room type as training data, and what was removed from them."""

    scenes: list[Scene]
    names: list[str]                                  # file name of each scene
    removed: Counter = field(default_factory=Counter)  # reason -> objects
    unreadable: list[str] = field(default_factory=list)


def load_rooms(data_dir: str | Path, spec: RoomTypeSpec) -> LoadedRooms:
    """Every scene of ``spec``'s room type in ``data_dir``, in file-name order, reduced to
    what the spec can place (see the module docstring)."""
    out = LoadedRooms([], [])
    for path in sorted(Path(data_dir).glob('*.json')):
        try:
            d = json.loads(path.read_text(encoding='utf-8'))
            if d.get('room', {}).get('room_type') != spec.room_type:
                continue
            scene = Scene.from_dict(d)
        except (OSError, ValueError, TypeError, KeyError, AttributeError):
            out.unreadable.append(path.name)
            continue
        out.scenes.append(_placeable(scene, spec, out.removed))
        out.names.append(path.name)
    return out


def _placeable(scene: Scene, spec: RoomTypeSpec, removed: Counter) -> Scene:
    kept: dict[str, object] = {}
    for o in scene.first_tier:
        if o.category not in spec:
            removed['category not placed by the pipeline'] += 1
        elif spec.info(o.category).tier != 'first':
            removed['on the floor, but its category stands on objects'] += 1
        else:
            kept[o.id] = o
    for o in scene.second_tier:
        parent = kept.get(o.support)
        if o.category not in spec:
            removed['category not placed by the pipeline'] += 1
        elif spec.info(o.category).tier != 'second':
            removed['on an object, but its category stands on the floor'] += 1
        elif parent is None or parent.category not in spec.supports(o.category):
            removed['on a parent that was removed or cannot hold it'] += 1
        else:
            kept[o.id] = o
    return Scene(scene.room, list(kept.values()), dict(scene.meta))


def split(names: list[str], seed: int, held_out: float = HELD_OUT_FRACTION
          ) -> tuple[list[int], list[int]]:
    """Indices of the training rooms and of the held-out rooms: a shuffle of the sorted file
    names by ``seed``, the last ``held_out`` of it (at least one room) held out."""
    order = sorted(range(len(names)), key=lambda k: names[k])
    np.random.default_rng(seed).shuffle(order)
    n_val = max(1, round(len(order) * held_out)) if len(order) > 1 else 0
    cut = len(order) - n_val
    return sorted(order[:cut]), sorted(order[cut:])


@dataclass
class DataSplit:
    """A room type's rooms of a data set, divided as training divides them."""

    train: list[Scene]
    held_out: list[Scene]
    held_out_names: list[str]
    removed: Counter


def split_rooms(data_dir: str | Path, spec: RoomTypeSpec, seed: int,
                train_rooms: int | None = None, held_out_rooms: int | None = None
                ) -> DataSplit:
    """The training rooms (at most ``train_rooms``) and held-out rooms (at most
    ``held_out_rooms``) of ``spec``'s room type in ``data_dir``: what ``scene-synth train
    --data`` trains and validates on with corpus seed ``seed``, and what the evaluation and
    the gallery compare with."""
    rooms = load_rooms(data_dir, spec)
    train_idx, held = split(rooms.names, seed)
    held = held[:held_out_rooms]
    return DataSplit([rooms.scenes[k] for k in train_idx[:train_rooms]],
                     [rooms.scenes[k] for k in held], [rooms.names[k] for k in held],
                     rooms.removed)
