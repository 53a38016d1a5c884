"""The base of every error the package raises for bad input.

Its message is one sentence saying what was wrong and where; every front end (command line,
node, evaluation) reports it as that sentence, without a traceback, and goes on serving.
"""
from __future__ import annotations

import math


class SceneSynthError(Exception):
    """Bad input or an impossible request, described in one sentence."""


class UnknownRoomType(SceneSynthError, ValueError):
    """A room type that is not one of ``categories.ROOM_TYPES`` (nor an alias of one)."""


class UnknownCategory(SceneSynthError, ValueError):
    """A category name that is not one of ``categories.CATEGORIES``."""


# The wording of numbers and nouns inside those sentences, shared by every module that
# writes them.
def number(x: float) -> str:
    """A number as a sentence shows it: at most three decimals, no trailing zeros."""
    if isinstance(x, float):
        if math.isnan(x):
            return 'NaN'
        if math.isinf(x):
            return 'Infinity' if x > 0 else '-Infinity'
    s = f'{float(x):.3f}'.rstrip('0').rstrip('.')
    return '0' if s in ('-0', '') else s


def with_article(noun: str) -> str:
    """The noun with its indefinite article ('a bedroom', 'an office')."""
    return f'{"an" if noun[:1] in "aeiou" else "a"} {noun}'
