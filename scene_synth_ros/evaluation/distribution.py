"""Category distribution (paper, table 1): KL(rooms || training corpus) over categories.

Three rows per room type: the synthesized rooms; a uniform distribution over the room
type's categories (the paper's reference); and held-out corpus rooms of another seed, the
noise floor: what KL a sample of the same size from the corpus itself scores.
"""
from __future__ import annotations

from collections import Counter
from typing import Iterable, Sequence

from ..categories import kl_divergence, room_spec
from ..scene import Scene


def category_counts(scenes: Iterable[Scene]) -> tuple[Counter, int]:
    """Objects per category over ``scenes``, and the number of rooms."""
    counts, rooms = Counter(), 0
    for s in scenes:
        counts.update(o.category for o in s.objects)
        rooms += 1
    return counts, rooms


def distribution(scenes: Iterable[Scene]) -> dict[str, float]:
    """Fraction of all objects that are of each category."""
    counts, _ = category_counts(scenes)
    total = sum(counts.values())
    return {c: n / total for c, n in counts.items()} if total else {}


def frequencies(scenes: Sequence[Scene], names: Sequence[str]) -> dict[str, float]:
    """Objects per room of every category in ``names`` (0 where absent)."""
    counts, rooms = category_counts(scenes)
    return {c: counts.get(c, 0) / max(rooms, 1) for c in names}


def category_kl(scenes: Sequence[Scene], reference: Sequence[Scene]) -> float:
    """KL(categories of ``scenes`` || categories of ``reference``); infinite when
    ``scenes`` hold no object at all."""
    p = distribution(scenes)
    return kl_divergence(p, distribution(reference)) if p else float('inf')


def compare(room_type: str, synthesized: Sequence[Scene], corpus: Sequence[Scene],
            heldout: Sequence[Scene]) -> dict:
    """The table-1 row of one room type and the per-category frequencies of its bar chart."""
    names = room_spec(room_type).names
    reference = distribution(corpus)
    uniform = {c: 1.0 / len(names) for c in names}
    synth = distribution(synthesized)
    n_objects = [sum(len(s) for s in group) / max(len(group), 1)
                 for group in (synthesized, corpus, heldout)]
    return {
        'kl_model': kl_divergence(synth, reference) if synth else float('inf'),
        'kl_uniform': kl_divergence(uniform, reference),
        'kl_heldout': kl_divergence(distribution(heldout), reference),
        'objects_per_room': dict(zip(('synthesized', 'corpus', 'heldout'), n_objects,
                                     strict=True)),
        'rooms': {'synthesized': len(synthesized), 'corpus': len(corpus),
                  'heldout': len(heldout)},
        'frequencies': {'synthesized': frequencies(synthesized, names),
                        'corpus': frequencies(corpus, names)},
    }
