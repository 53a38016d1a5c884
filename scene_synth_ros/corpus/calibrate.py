"""Calibration of the corpus' request rates.

Some planned objects do not fit (no free wall, no supporting surface in the room), so a
category is realised less often than it is requested. Calibration generates rooms, compares
each category's realised rate with the table's, and scales the request rate by the ratio,
a few times over. The factors are written to ``calibration.json`` beside this module, which
``generate_room`` reads; re-run with ``scene-synth corpus-calibrate``.
"""
from __future__ import annotations

import json
from pathlib import Path
import tempfile

from ..categories import ROOM_TYPES, paper_spec
from ..files import write_atomic
from .generate import CALIBRATION_FILE, generate_corpus, load_calibration
from .stats import collect

MIN_FACTOR, MAX_FACTOR = 0.5, 4.0


def calibrate(rooms: int = 2000, iterations: int = 3, seed: int = 12345,
              room_types=ROOM_TYPES, out: Path = CALIBRATION_FILE,
              workers: int | None = None, log=print) -> dict[str, dict[str, float]]:
    """Fit the factors and write them to ``out``. Uses a seed of its own so that the rooms
    it fits on are not the rooms of the default corpus (seed 0)."""
    factors = {rt: {c.name: 1.0 for c in paper_spec(rt).categories} for rt in room_types}
    with tempfile.TemporaryDirectory() as scratch:
        # The factors of the pass under way, where the corpus workers read them.
        current = Path(scratch) / 'calibration.json'
        for it in range(iterations):
            for rt in room_types:
                _write(current, factors, rooms, iterations, seed)
                load_calibration.cache_clear()
                corpus = generate_corpus(rt, rooms, seed=seed + it, workers=workers,
                                         calibration_path=str(current))
                stats = collect(rt, corpus, check=False)
                for name, here, table in stats.category_table():
                    ratio = table / here if here > 0 else MAX_FACTOR
                    factors[rt][name] = min(max(factors[rt][name] * ratio, MIN_FACTOR),
                                            MAX_FACTOR)
                log(f'calibration pass {it + 1}/{iterations} {rt}: KL(corpus||table) = '
                    f'{stats.kl_to_table:.4f}, objects/room {stats.objects_per_room:.2f} '
                    f'(table {paper_spec(rt).mean_objects_per_room:.2f})')
    _write(Path(out), factors, rooms, iterations, seed)
    load_calibration.cache_clear()
    return factors


def _write(path: Path, factors, rooms, iterations, seed) -> None:
    write_atomic(path, json.dumps({
        'about': 'request-rate factors of the procedural corpus; made by '
                 f'`scene-synth corpus-calibrate --rooms {rooms} --iterations {iterations} '
                 f'--seed {seed}`',
        'factors': {rt: {k: round(v, 4) for k, v in f.items()} for rt, f in factors.items()},
    }, indent=1, sort_keys=True) + '\n')
