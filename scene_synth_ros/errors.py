"""The base of every error the package raises for bad input.

Its message is one sentence saying what was wrong and where; every front end (command line,
node, evaluation) reports it as that sentence, without a traceback, and goes on serving.
Whatever the input, the sentence is one printable line of at most ``MAX_SENTENCE``
characters that encodes as UTF-8: it goes into logs and onto /diagnostics, and an input
quoted whole (a 7 MB string, a key that is a lone surrogate) must not flood them or make
them fail.
"""
from __future__ import annotations

import math

MAX_SENTENCE = 400     # characters in an error sentence
MAX_QUOTE = 40         # characters of a user's value quoted inside one


def sentence(text: object, limit: int = MAX_SENTENCE) -> str:
    """``text`` as one bounded, printable line: whitespace runs become one space, other
    unprintable characters (controls, lone surrogates) become U+FFFD, and a text longer
    than ``limit`` keeps its start and ends with an ellipsis."""
    s = str(text)
    if len(s) > 4 * limit:            # never scan a huge text whole
        s = s[:4 * limit]
    out = []
    space = False
    for ch in s:
        if ch.isspace():
            if not space:
                out.append(' ')
            space = True
            continue
        space = False
        out.append(ch if ch.isprintable() else '\ufffd')
    line = ''.join(out).strip()
    return line if len(line) <= limit else line[:limit - 1].rstrip() + '…'


def quoted(value: object, limit: int = MAX_QUOTE) -> str:
    """A user's value as a sentence quotes it: its repr, cut to ``limit`` characters."""
    if isinstance(value, str) and len(value) > limit:
        return repr(value[:limit]) + '…'
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 1] + '…'


def quoted_list(values, shown: int = 8) -> str:
    """The first ``shown`` of ``values``, each ``quoted``, and how many more there are:
    bounded whatever the number of values."""
    values = list(values)
    out = ', '.join(quoted(v) for v in values[:shown])
    return out + (f' and {len(values) - shown} more' if len(values) > shown else '')


class SceneSynthError(Exception):
    """Bad input or an impossible request, described in one sentence (``sentence``)."""

    def __init__(self, message: object = '', *args):
        super().__init__(sentence(message), *args)


class UnknownRoomType(SceneSynthError, ValueError):
    """A room type that the vocabulary in use does not know (``categories.Vocabulary``: the
    paper's ``ROOM_TYPES`` and a data set's), nor an alias of one."""


class RoomTypeConflict(SceneSynthError, ValueError):
    """A data set's category set for a room type that a vocabulary already has with another
    one (``categories.Vocabulary.with_specs``)."""


class UnknownCategory(SceneSynthError, ValueError):
    """A category name that is not one of ``categories.CATEGORIES``."""


class ConfigError(SceneSynthError, ValueError):
    """A setting's value that cannot be used (out of its range, of the wrong type): one
    sentence naming the setting (``synth_config.check_value``)."""


class DatasetError(SceneSynthError, ValueError):
    """A data set that cannot be imported or described at all (a missing or unreadable
    mapping file, a bad option, a broken data-set description); problems with single rooms
    and objects are report lines instead (``datasets.report``)."""


# The wording of numbers and nouns inside those sentences, shared by every module that
# writes them.
def number(x: float) -> str:
    """A number as a sentence shows it: at most three decimals, no trailing zeros."""
    if isinstance(x, float):
        if math.isnan(x):
            return 'NaN'
        if math.isinf(x):
            return 'Infinity' if x > 0 else '-Infinity'
    if isinstance(x, int) and x.bit_length() > 1000:      # past what a float can hold
        return f'{"-" if x < 0 else ""}10^{int(x.bit_length() * math.log10(2))}'
    if abs(float(x)) >= 1e9:          # no hundred-digit renderings of huge inputs
        return f'{float(x):.6g}'
    s = f'{float(x):.3f}'.rstrip('0').rstrip('.')
    return '0' if s in ('-0', '') else s


def with_article(noun: str) -> str:
    """The noun with its indefinite article ('a bedroom', 'an office')."""
    return f'{"an" if noun[:1] in "aeiou" else "a"} {noun}'


class CatalogError(SceneSynthError, ValueError):
    """A user catalog that cannot be built or read at all (no manifest, a manifest or
    catalog file that is not what it should be); problems with single models are report
    lines instead (``user_catalog.build``)."""
