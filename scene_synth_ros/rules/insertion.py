"""The design rules that synthesis keeps at insertion (a departure from the paper): for each,
the function that gives a scene's verdicts case by case, and which insertions can change them.
"""
from __future__ import annotations

from . import access, groups, walls

# Design rules insertion can keep: each gives, for a scene, whether each of its cases (a
# window by its index, a piece of storage by its index among the first tier, a piece of a
# group by its id) keeps the rule. The group rules also narrow where such a piece's location
# is drawn (``groups.partner_zone``).
INSERTION_RULES = {'windows_clear': walls.window_verdicts,
                   'storage_clearance': access.storage_verdicts,
                   'wall_contact': walls.wall_contact_verdicts,
                   'fixture_clearance': access.fixture_verdicts,
                   'bath_in_corner': groups.corner_verdicts,
                   'chair_at_table': groups.chair_verdicts,
                   'nightstand_by_bed': groups.nightstand_verdicts,
                   'bidet_by_toilet': groups.bidet_verdicts,
                   'coffee_table_has_seating': groups.seating_verdicts}

# Rules whose verdicts a new piece changes only where it enters a case's clear strip or zone:
# insertion asks for those cases alone (the verdict functions' ``new``), the same answer for
# less work.
INCREMENTAL_RULES = frozenset({'windows_clear', 'storage_clearance', 'fixture_clearance'})

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
}

def rule_categories(rule: str, room_type: str) -> frozenset[str] | None:
    """The categories whose insertion can change ``rule``'s verdicts in a room of
    ``room_type`` (None: any). Wall furniture is the room type's own: a data set says which
    of its categories stand against a wall."""
    if rule == 'wall_contact':
        return walls.wall_categories(room_type)[0]
    return RULE_CATEGORIES.get(rule)
