"""A design rule, its rate over rooms, and the comparison of two sets of rooms."""
from __future__ import annotations

from dataclasses import dataclass
import math
from typing import Callable

from ..categories import PAPER, CategoryInfo, Vocabulary, members
from ..errors import UnknownRoomType
from ..scene import Scene

Outcome = tuple[int, int]          # (cases that keep the rule, cases) in one room

# Every kind of bed, for the rules of every family that ask about beds.
BEDS = members('bed')


def category_of(name: str, room_type: str, vocabulary: Vocabulary = PAPER
                ) -> CategoryInfo | None:
    """What is known of category ``name`` in a room of ``room_type``: the room type's own
    category set in ``vocabulary`` first (a data set's categories, sizes and wall flags live
    there), then the paper's table; None when neither knows it. For the paper's room types
    this is ``categories.CATEGORIES[name]``."""
    try:
        try:
            return vocabulary.info(name, room_type)
        except UnknownRoomType:     # a room of a type the vocabulary does not know
            return vocabulary.info(name)
    except KeyError:
        return None


@dataclass(frozen=True)
class Rule:
    """One design rule: ``measure(scene)`` answers ``question`` for every case in a room."""

    name: str                              # short identifier, e.g. 'wall_contact'
    family: str                            # 'walls', 'groups' or 'access'
    question: str                          # one sentence: the case and what "yes" means
    measure: Callable[..., Outcome]
    # Whether ``measure`` reads the room type's category set: it then takes the vocabulary
    # the room's categories belong to (``outcome``).
    reads_vocabulary: bool = False

    def outcome(self, scene: Scene, vocabulary: Vocabulary = PAPER) -> Outcome:
        """``measure(scene)``, with the categories of ``vocabulary`` where the rule reads
        them."""
        if self.reads_vocabulary:
            return self.measure(scene, vocabulary)
        return self.measure(scene)


@dataclass(frozen=True)
class Rate:
    kept: int
    cases: int

    @property
    def value(self) -> float:
        return self.kept / self.cases if self.cases else math.nan


@dataclass(frozen=True)
class Comparison:
    rule: Rule
    corpus: Rate
    synthesized: Rate

    @property
    def difference(self) -> float:
        """Synthesized minus corpus rate, in [-1, 1] (NaN when either has no case)."""
        return self.synthesized.value - self.corpus.value

    @property
    def p_value(self) -> float:
        return two_proportion_p(self.corpus.kept, self.corpus.cases,
                                self.synthesized.kept, self.synthesized.cases)


def two_proportion_p(k1: int, n1: int, k2: int, n2: int) -> float:
    """Two-sided p-value of the z-test that two binomial proportions are equal (pooled
    variance); 1.0 where it is undefined (a sample without cases, or both proportions 0 or 1)."""
    if n1 == 0 or n2 == 0:
        return 1.0
    p = (k1 + k2) / (n1 + n2)
    se = math.sqrt(p * (1 - p) * (1 / n1 + 1 / n2))
    if se == 0:
        return 1.0
    z = (k1 / n1 - k2 / n2) / se
    return math.erfc(abs(z) / math.sqrt(2))
