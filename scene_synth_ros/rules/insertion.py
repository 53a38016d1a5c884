"""The design rules that synthesis keeps at insertion (a departure from the paper): for each,
the function that gives a scene's verdicts case by case, and which insertions can change them.
"""
from __future__ import annotations

from ..categories import PAPER, Vocabulary
from ..scene import PlacedObject, Scene
from . import access, groups, home, walls

# Design rules insertion can keep: each gives, for a scene, whether each of its cases (a
# window by its index, a piece of storage by its index among the first tier, a piece of a
# group by its id) keeps the rule. The group rules and some home rules also narrow where
# such a piece's location is drawn (``partner_zone``).
INSERTION_RULES = {'windows_clear': walls.window_verdicts,
                   'storage_clearance': access.storage_verdicts,
                   'wall_contact': walls.wall_contact_verdicts,
                   'fixture_clearance': access.fixture_verdicts,
                   'bath_in_corner': groups.corner_verdicts,
                   'chair_at_table': groups.chair_verdicts,
                   'nightstand_by_bed': groups.nightstand_verdicts,
                   'bidet_by_toilet': groups.bidet_verdicts,
                   'coffee_table_has_seating': groups.seating_verdicts,
                   'work_triangle': home.triangle_verdicts,
                   'fronts_open': home.front_verdicts,
                   'dining_seats': home.seat_verdicts,
                   'hallway_path': home.path_verdicts}

# Rules whose verdicts a new piece changes only where it enters a case's clear strip or zone:
# insertion asks for those cases alone (the verdict functions' ``new``), the same answer for
# less work.
INCREMENTAL_RULES = frozenset({'windows_clear', 'storage_clearance', 'fixture_clearance',
                               'fronts_open', 'dining_seats'})

# The only categories whose insertion can change a rule's verdicts (a rule not named here can
# be changed by any piece): a chair's place at a table depends on chairs and tables alone,
# and so on. Insertion skips the other rules, which is the same answer for less work.
# Wall contact's categories depend on the room type (``rule_categories``).
RULE_CATEGORIES: dict[str, frozenset[str]] = {
    'bath_in_corner': frozenset({'bathtub', 'shower'}),
    'chair_at_table': frozenset(groups.CHAIRS + groups.TABLES),
    'nightstand_by_bed': frozenset(('stand',) + groups.BEDS_WITH_HEAD),
    'bidet_by_toilet': frozenset({'bidet', 'toilet'}),
    'coffee_table_has_seating': frozenset(('coffee table',) + groups.LOUNGE_SEATS),
    'work_triangle': frozenset(home.PARTNER_RULES['work_triangle']),
}


def rule_categories(rule: str, room_type: str, vocabulary: Vocabulary = PAPER
                    ) -> frozenset[str] | None:
    """The categories whose insertion can change ``rule``'s verdicts in a room of
    ``room_type`` (None: any). Wall furniture is the room type's own in ``vocabulary``: a
    data set says which of its categories stand against a wall."""
    if rule == 'wall_contact':
        return walls.wall_categories(room_type, vocabulary)[0]
    return RULE_CATEGORIES.get(rule)


# Rules whose verdicts read the room type's category set (which pieces stand against a wall).
VOCABULARY_RULES = frozenset({'wall_contact'})


# Rules whose broken cases get one more draw among their partners at a STOP
# (``SynthConfig.owed_partners``): the group rules', and a kitchen's essentials.
OWED_RULES = tuple(groups.OWED_PARTNERS) + tuple(home.OWED_PARTNERS)
# Rules that a draw owed one of these categories at a STOP need not keep where it found no
# place keeping them: a small kitchen whose walls leave no place 1.2 m from its sink is
# better with its stove nearer than without one.
WAIVED_WHEN_OWED = {'work_triangle': frozenset(home.KITCHEN_ESSENTIALS)}


def waived_when_owed(partners, rules) -> frozenset[str]:
    """The rules among ``rules`` that a draw owed ``partners`` may break where it found no
    place keeping them (``WAIVED_WHEN_OWED``)."""
    return frozenset(r for r, owed_to in WAIVED_WHEN_OWED.items()
                     if r in rules and owed_to & set(partners))


def owed(scene: Scene, rules) -> tuple[int, frozenset[str]]:
    """How many cases of ``rules`` (names in ``OWED_RULES``) a finished ``scene`` still owes
    a partner, and the categories that could mend them (``groups.owed``, ``home.owed``)."""
    broken, partners = 0, frozenset()
    for family in (groups, home):
        b, p = family.owed(scene, [r for r in rules if r in family.OWED_PARTNERS])
        broken, partners = broken + b, partners | p
    return broken, partners


def partner_zone(scene: Scene, rule: str, category: str, vocabulary: Vocabulary = PAPER):
    """Where the centre of a new first-tier ``category`` piece can stand for ``rule`` to
    hold for it (``groups.partner_zone``, ``home.partner_zone``); None where the rule asks
    nothing of such a piece."""
    if rule in home.PARTNER_RULES:
        return home.partner_zone(scene, rule, category, vocabulary)
    return groups.partner_zone(scene, rule, category, vocabulary)


def verdicts(rule: str, scene: Scene, vocabulary: Vocabulary = PAPER,
             new: PlacedObject | None = None) -> dict:
    """``rule``'s verdict on each of its cases in ``scene`` (``INSERTION_RULES``), whose
    categories are those of ``vocabulary``; with ``new``, for an incremental rule, only the
    cases the newly placed ``new`` can change."""
    kw: dict = {}
    if new is not None and rule in INCREMENTAL_RULES:
        kw['new'] = new
    if rule in VOCABULARY_RULES:
        kw['vocabulary'] = vocabulary
    return INSERTION_RULES[rule](scene, **kw)
