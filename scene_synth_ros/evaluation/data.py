"""The three sets of rooms the evaluation compares.

* the training corpus: corpus rooms of seed ``CORPUS_SEED`` (0), the seed the shipped
  weights were trained on (its rooms 0..2999 are exactly their training rooms);
* held-out corpus rooms: seed ``corpus.HELDOUT_SEED`` (1), which training never saw;
* synthesized rooms: the empty shells of those held-out rooms, furnished by the pipeline,
  room ``i`` with synthesis seed ``seed * SEED_STRIDE + i``. Room ``i`` of the held-out
  corpus and synthesized room ``i`` therefore share their walls, doors and windows.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from tqdm import tqdm

from ..corpus import HELDOUT_SEED
from ..corpus.generate import empty_room, generate_corpus
from ..scene import Scene
from ..synth import Synthesizer
from .parallel import pmap

CORPUS_SEED = 0
SEED_STRIDE = 100_000
WARMUP_INDEX = 10 ** 6      # a shell used only to warm a worker up, never evaluated


@dataclass
class SynthRecord:
    """One synthesized room and what it cost."""

    index: int
    scene: Scene
    seconds: float                       # wall time of the complete room
    timings: dict[str, float] = field(default_factory=dict)   # seconds per module
    stopped: str = 'stop'


def corpus_rooms(room_type: str, n: int, seed: int, workers: int = 1,
                 progress: bool = True) -> list[Scene]:
    """Corpus rooms 0..n-1 of ``seed``."""
    rooms = generate_corpus(room_type, n, seed=seed, workers=workers)
    return list(tqdm(rooms, total=n, desc=f'{room_type} corpus seed {seed}', unit='room',
                     disable=not progress, leave=False))


_SYNTH = None
_WARM: set[str] = set()


def _init_synthesizer(weights_dir) -> None:
    global _SYNTH
    _SYNTH = Synthesizer(weights_dir)
    _WARM.clear()


def _synthesize(job) -> SynthRecord:
    room_type, index, seed = job
    if room_type not in _WARM:
        # Load the bundle and run once untimed, so no room pays for start-up.
        _SYNTH.generate(empty_room(room_type, HELDOUT_SEED, WARMUP_INDEX), seed=0)
        _WARM.add(room_type)
    result = _SYNTH.generate(empty_room(room_type, HELDOUT_SEED, index), seed=seed)
    return SynthRecord(index, result.scene, result.seconds, dict(result.timings),
                       result.stopped)


def synthesize(room_type: str, n: int, seed: int, workers: int = 1, weights_dir=None,
               progress: bool = True) -> list[SynthRecord]:
    """Held-out shells 0..n-1 furnished from empty, in order."""
    jobs = [(room_type, i, seed * SEED_STRIDE + i) for i in range(n)]
    return pmap(_synthesize, jobs, workers, _init_synthesizer, (weights_dir,),
                desc=f'{room_type} synthesis', progress=progress)
