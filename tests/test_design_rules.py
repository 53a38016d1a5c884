"""The design-rule framework: rates, the test of equal proportions, the registry."""
import math

import pytest

from scene_synth_ros import rules as design_rules
from scene_synth_ros.rules import Rate, Rule, rates, two_proportion_p
from scene_synth_ros.scene import Room, Scene


def test_two_proportion_p_matches_known_values():
    # 50/100 vs 50/100: no evidence of a difference.
    assert two_proportion_p(50, 100, 50, 100) == pytest.approx(1.0)
    # 60/100 vs 40/100: z = 0.2 / sqrt(0.5 * 0.5 * 0.02) = 2.828, two-sided p = 0.00468.
    assert two_proportion_p(60, 100, 40, 100) == pytest.approx(0.004678, rel=1e-3)
    assert two_proportion_p(60, 100, 40, 100) == two_proportion_p(40, 100, 60, 100)
    # Undefined: no cases, or both samples all yes.
    assert two_proportion_p(0, 0, 3, 4) == 1.0
    assert two_proportion_p(5, 5, 9, 9) == 1.0


def test_rates_sum_cases_over_rooms_and_skip_rooms_without_cases():
    rooms = [Scene(Room('bedroom', ((0, 0), (w, 0), (w, 3), (0, 3)))) for w in (3, 4, 5)]
    wide = Rule('wide', 'walls', 'A room wider than 3.5 m counts; it keeps the rule at 4.5 m.',
                lambda s: (int(s.room.bounds[2] > 4.5), int(s.room.bounds[2] > 3.5)))
    r = rates(rooms, [wide])['wide']
    assert (r.kept, r.cases) == (1, 2) and r.value == 0.5
    assert math.isnan(Rate(0, 0).value)


def test_every_rule_is_named_once_and_asks_one_question():
    rules = design_rules.rules()
    names = [r.name for r in rules]
    assert len(names) == len(set(names)) and len(rules) >= 15
    for r in rules:
        assert r.family in ('walls', 'groups', 'access', 'home')
        assert r.question.strip() and '\n' not in r.question, r.name


def test_every_rule_measures_an_empty_room_without_cases_or_errors():
    empty = Scene(Room('bedroom', ((0, 0), (4, 0), (4, 3), (0, 3))))
    for name, (kept, cases) in design_rules.measure(empty).items():
        assert 0 <= kept <= cases, name
