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

from typing import Iterable, Sequence

from ..categories import PAPER, Vocabulary
from ..scene import Scene
from . import access, groups, home, walls
from .rule import BEDS, Comparison, Outcome, Rate, Rule, category_of, two_proportion_p

__all__ = ['BEDS', 'RULES', 'Comparison', 'Outcome', 'Rate', 'Rule', 'access', 'broken',
           'category_of', 'compare', 'groups', 'home', 'measure', 'rates', 'rules', 'summarize',
           'totals', 'two_proportion_p', 'walls']

RULES: tuple[Rule, ...] = walls.RULES + groups.RULES + access.RULES + home.RULES


def rules() -> tuple[Rule, ...]:
    """Every rule, family by family."""
    return RULES


def measure(scene: Scene, selected: Sequence[Rule] | None = None,
            vocabulary: Vocabulary = PAPER) -> dict[str, Outcome]:
    """Every rule's outcome in one room, whose categories are those of ``vocabulary``."""
    return {r.name: r.outcome(scene, vocabulary) for r in (selected or rules())}


def broken(scene: Scene, selected: Sequence[Rule] | None = None,
           vocabulary: Vocabulary = PAPER) -> list[str]:
    """The names of the rules the room breaks in at least one case."""
    return [name for name, (kept, cases) in measure(scene, selected, vocabulary).items()
            if kept < cases]


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
