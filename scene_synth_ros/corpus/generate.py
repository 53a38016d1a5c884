"""Generating furnished rooms: one room from a seed, or a whole corpus on all cores."""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
import json
import os
from pathlib import Path
from typing import Iterator

import numpy as np

from .. import rules as design_rules
from ..categories import CATEGORIES, CORPUS_ROOM_TYPES, ROOM_TYPE_ALIASES
from ..errors import UnknownRoomType
from ..geometry import check_scene
from ..parallel import process_pool
from ..scene import Room, Scene
from ..thresholds import DINING_CLEARANCE
from .furnish import draw_plan, pick_variant, place_first_tier, place_second_tier, tidy
from .layout import Layout
from .shell import sample_shell

CALIBRATION_FILE = Path(__file__).with_name('calibration.json')
CIRCULATION = 2.3        # floor area per m^2 of furniture footprint a room is given, at least
SEATED_AROUND = ('dining table', 'kitchen island')
MAX_ATTEMPTS = 8
# The design rules every corpus room keeps (``rules``), but two that the
# paper's table itself bounds: it has fewer seats than desks and dressing tables in bedrooms,
# and fewer coffee tables and TV stands than sofas in offices.
TABLE_BOUND = ('desk_has_seat', 'sofa_faces_table_or_tv')
KEPT_RULES = tuple(r for r in design_rules.rules() if r.name not in TABLE_BOUND)


@lru_cache(maxsize=None)
def load_calibration(path: str | None = None) -> dict[str, dict[str, float]]:
    """Per room type and category, the factor on the table's rate that makes up for objects
    that did not fit (written by ``scene-synth corpus-calibrate``)."""
    p = Path(path) if path else CALIBRATION_FILE
    if not p.is_file():
        return {}
    return json.loads(p.read_text())['factors']


@dataclass(frozen=True)
class RoomRequest:
    room_type: str
    seed: int
    index: int
    calibration: str | None = None
    real_sizes: bool = False


def room_rng(room_type: str, seed: int, index: int) -> np.random.SeedSequence:
    # One independent stream per (seed, room type, index): a room is the same whichever
    # worker makes it and however many rooms are made.
    return np.random.SeedSequence([seed, CORPUS_ROOM_TYPES.index(room_type), index])


def corpus_room_type(name: str) -> str:
    """The corpus's room type ``name`` names (``UnknownRoomType`` for any other): the
    package's room types with the package's categories (``categories.PAPER``), whatever
    vocabulary the weights in use have, and the rooms of a home whose weights are still to
    come (``categories.CORPUS_ROOM_TYPES``)."""
    key = name.strip().lower().replace('_', ' ')
    key = ROOM_TYPE_ALIASES.get(key, key)
    if key in CORPUS_ROOM_TYPES:
        return key
    raise UnknownRoomType(f'unknown room type {name[:80]!r} for the corpus; expected one of '
                          f'{", ".join(CORPUS_ROOM_TYPES)}')


def _drawn(room_type: str, rng: np.random.Generator, calibration: dict[str, float],
           real_sizes: bool = False):
    """What an attempt at a room draws before it furnishes anything: the plan (categories),
    a model of each, and the empty shell, sized for those models' footprints."""
    plan = draw_plan(room_type, rng, calibration)
    chosen = [pick_variant(c, rng) for c in plan]
    footprint = sum(v.width * v.depth for c, v in zip(plan, chosen, strict=True)
                    if CATEGORIES[c].tier == 'first')
    # A table people sit around needs its seats' floor on top (an eat-in kitchen is large).
    seated = sum((v.width + 2 * DINING_CLEARANCE) * (v.depth + 2 * DINING_CLEARANCE)
                 for c, v in zip(plan, chosen, strict=True) if c in SEATED_AROUND)
    return plan, chosen, sample_shell(room_type, rng,
                                      min_area=CIRCULATION * footprint + seated + 2.0,
                                      real_sizes=real_sizes)


def generate_room(room_type: str, seed: int = 0, index: int = 0,
                  calibration: dict[str, float] | None = None,
                  real_sizes: bool = False) -> Scene:
    """A furnished room that passes every check of ``geometry.check_scene`` and keeps every
    rule of ``KEPT_RULES`` (unless none of ``MAX_ATTEMPTS`` attempts does: then the first
    valid one). ``real_sizes``: its shell sized as real rooms of its type are
    (``shell.sample_shell``)."""
    room_type = corpus_room_type(room_type)
    if calibration is None:
        calibration = load_calibration().get(room_type, {})
    seeds = room_rng(room_type, seed, index).spawn(MAX_ATTEMPTS)
    valid = None
    for attempt, ss in enumerate(seeds):
        rng = np.random.default_rng(ss)
        plan, chosen, room = _drawn(room_type, rng, calibration, real_sizes)
        lay = Layout(room, rng, {'generator': 'procedural', 'seed': seed, 'index': index})
        items = list(zip(plan, chosen, strict=True))
        first = [(c, v) for c, v in items if CATEGORIES[c].tier == 'first']
        # Big things go on a surface first, as a person would put the TV before the vase.
        second = sorted(((c, v) for c, v in items if CATEGORIES[c].tier == 'second'),
                        key=lambda cv: -cv[1].width * cv[1].depth)
        for category, variant in first:
            place_first_tier(lay, category, variant)
        tidy(lay)
        for category, variant in second:
            place_second_tier(lay, category, variant)
        scene = lay.scene
        if attempt:
            scene.meta['attempt'] = attempt
        if check_scene(scene).ok:
            # A room a designer would send back (a rule broken) makes way for the next
            # attempt; only if every attempt is sent back is the first valid one kept.
            if not design_rules.broken(scene, KEPT_RULES):
                return scene
            if valid is None:
                valid = scene
    if valid is not None:
        return valid
    raise RuntimeError(f'could not generate a valid {room_type} for seed {seed}, '
                       f'index {index} in {MAX_ATTEMPTS} attempts')


def _work(req: RoomRequest) -> Scene:
    cal = load_calibration(req.calibration).get(req.room_type, {})
    return generate_room(req.room_type, req.seed, req.index, cal, req.real_sizes)


def generate_corpus(room_type: str, n: int, seed: int = 0, workers: int | None = None,
                    start: int = 0, calibration_path: str | None = None,
                    real_sizes: bool = False) -> Iterator[Scene]:
    """Rooms ``start`` .. ``start + n - 1`` of a corpus, in order, made on ``workers``
    processes (default: all cores); ``real_sizes`` as for ``generate_room``."""
    room_type = corpus_room_type(room_type)
    reqs = [RoomRequest(room_type, seed, i, calibration_path, real_sizes)
            for i in range(start, start + n)]
    workers = workers or os.cpu_count() or 1
    if workers <= 1 or n < 8:
        yield from map(_work, reqs)
        return
    with process_pool(workers) as pool:
        yield from pool.imap(_work, reqs, chunksize=16)


def empty_room(room_type: str, seed: int = 0, index: int = 0) -> Room:
    """The empty shell of corpus room (``seed``, ``index``): rooms shaped and sized like the
    training rooms, for synthesis from scratch. The evaluation furnishes these, so that its
    synthesized room ``i`` shares its walls, doors and windows with corpus room ``i``; that
    takes furnishing the corpus room (6-14 ms, ``docs/design/investigations.md``), to learn
    which attempt's shell it kept."""
    return generate_room(room_type, seed, index).room


def first_shell(room_type: str, seed: int = 0, index: int = 0) -> Room:
    """The shell of the first attempt at corpus room (``seed``, ``index``), drawn without
    furnishing it (under a millisecond): the corpus room's own shell (``empty_room``) but
    where that attempt was sent back and the corpus kept a later one (8 % of bedrooms, 1.5-6 %
    of the other types: ``docs/design/investigations.md``), a shell drawn
    exactly as the corpus draws its rooms' shells. The shells of batches (``generate -n``),
    which need no corpus room beside them."""
    room_type = corpus_room_type(room_type)
    rng = np.random.default_rng(room_rng(room_type, seed, index).spawn(MAX_ATTEMPTS)[0])
    return _drawn(room_type, rng, load_calibration().get(room_type, {}))[2]
