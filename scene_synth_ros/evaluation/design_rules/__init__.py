"""Design rules: what an interior designer checks in a furnished room, measured.

Each rule is a question asked of every *case* it applies to in a room (an object of some
categories, a window, a bed, a pair…), answered yes (the room keeps the rule there) or no.
A rule's rate over a set of rooms is the fraction of its cases answered yes; rooms with no
case of a rule do not count for it. Rates of the corpus and of synthesized rooms are put side
by side with a two-sided test of equal proportions (``compare``).

The rules live in one module per family, each a ``Rule`` whose docstring-like ``question``
says exactly what is counted:

- ``walls``: wall furniture against its wall, near misses, large pieces floating mid-room,
  windows not covered by tall furniture, beds not across windows;
- ``groups``: functional groups (seats at desks and tables, nightstands by beds, a bidet by
  the toilet, bath and shower in a corner, sofas facing a table or TV, coffee tables with
  seating, a TV square on its stand), chairs square to the walls, plausible supports;
- ``access``: clearance in front of storage and fixtures, beds' sides and foot free, fronts
  not facing a wall, every object's front reachable by the robot from a door.

Geometry shared by the families is in ``spatial``; a family computes a faster twin of it
where it needs one, and says so.
"""
from __future__ import annotations

from dataclasses import dataclass
import math
from typing import Callable, Iterable, Sequence

from ...categories import CategoryInfo, category_info
from ...errors import UnknownRoomType
from ...scene import Scene

Outcome = tuple[int, int]          # (cases that keep the rule, cases) in one room

# Every kind of bed, for the rules of every family that ask about beds.
BEDS = ('double bed', 'single bed', 'bunker bed', 'baby bed', 'daybed')


def category_of(name: str, room_type: str) -> CategoryInfo | None:
    """What is known of category ``name`` in a room of ``room_type``: the room type's own
    category set first (a data set's categories, sizes and wall flags live there), then the
    paper's table; None when neither knows it. For the paper's room types this is
    ``categories.CATEGORIES[name]``."""
    try:
        try:
            return category_info(name, room_type)
        except UnknownRoomType:     # a room of a type this process does not define
            return category_info(name)
    except KeyError:
        return None


@dataclass(frozen=True)
class Rule:
    """One design rule: ``measure(scene)`` answers ``question`` for every case in a room."""

    name: str                              # short identifier, e.g. 'wall_contact'
    family: str                            # 'walls', 'groups' or 'access'
    question: str                          # one sentence: the case and what "yes" means
    measure: Callable[[Scene], Outcome]


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


def rules() -> tuple[Rule, ...]:
    """Every rule, family by family (imported here, not at module load, so that each family
    module can import ``Rule`` from this one)."""
    from . import access, groups, walls
    return walls.RULES + groups.RULES + access.RULES


def measure(scene: Scene, selected: Sequence[Rule] | None = None) -> dict[str, Outcome]:
    """Every rule's outcome in one room."""
    return {r.name: r.measure(scene) for r in (selected or rules())}


def broken(scene: Scene, selected: Sequence[Rule] | None = None) -> list[str]:
    """The names of the rules the room breaks in at least one case."""
    return [name for name, (kept, cases) in measure(scene, selected).items() if kept < cases]


def totals(rows: Iterable[dict[str, Outcome]], selected: Sequence[Rule]) -> dict[str, Rate]:
    """Every selected rule's rate from per-room outcomes (``measure`` of each room)."""
    kept = dict.fromkeys((r.name for r in selected), 0)
    cases = dict.fromkeys(kept, 0)
    for row in rows:
        for name in kept:
            k, n = row.get(name, (0, 0))
            kept[name] += k
            cases[name] += n
    return {name: Rate(kept[name], cases[name]) for name in kept}


def rates(scenes: Iterable[Scene], selected: Sequence[Rule] | None = None) -> dict[str, Rate]:
    """Every rule's rate over ``scenes``."""
    selected = tuple(selected or rules())
    return totals((measure(scene, selected) for scene in scenes), selected)


def compare(corpus: Iterable[Scene], synthesized: Iterable[Scene]) -> list[Comparison]:
    """Every rule's rate in the corpus and in synthesized rooms, side by side."""
    selected = rules()
    a, b = rates(corpus, selected), rates(synthesized, selected)
    return [Comparison(r, a[r.name], b[r.name]) for r in selected]


def summarize(corpus_rows: Iterable[dict[str, Outcome]],
              synthesized_rows: Iterable[dict[str, Outcome]]) -> dict[str, dict]:
    """The evaluation's record of every rule from per-room outcomes (``measure`` of each
    room): its family and question, (kept, cases) on each side and the p-value."""
    selected = rules()
    a, b = totals(corpus_rows, selected), totals(synthesized_rows, selected)
    return {r.name: {'family': r.family, 'question': r.question,
                     'corpus': [a[r.name].kept, a[r.name].cases],
                     'synthesized': [b[r.name].kept, b[r.name].cases],
                     'p': two_proportion_p(a[r.name].kept, a[r.name].cases,
                                           b[r.name].kept, b[r.name].cases)}
            for r in selected}
