"""Semantic labels of what the exports hold, for the simulators' segmentation cameras.

Every object carries its category; the floor and the walls carry ``floor`` and ``wall``.
Gazebo's Label system takes a number from 0 to 255 (``semantic_label``): 0 is left to what
carries none, 1 and 2 are the floor and the walls, the package's categories follow in the
order of ``categories.CATEGORIES`` (the same number in every export, whatever the room), and
a category of an imported data set outside them gets a number from its name in the rest of
the range (two such names may share one). USD carries the category's name itself.
"""
from __future__ import annotations

import zlib

from ..categories import CATEGORIES

FLOOR, WALL = ARCHITECTURE = ('floor', 'wall')
_KNOWN = {name: k + 1 for k, name in enumerate(ARCHITECTURE + tuple(CATEGORIES))}
_FIRST_FREE = len(_KNOWN) + 1


def semantic_label(category: str) -> int:
    """The number, 1 to 255, of ``category`` (or ``floor``, ``wall``) in segmentation images."""
    known = _KNOWN.get(category)
    if known is not None:
        return known
    return _FIRST_FREE + zlib.crc32(category.encode('utf-8')) % (256 - _FIRST_FREE)


def label_table(categories) -> dict[str, int]:
    """The numbers of the floor, the walls and ``categories``, by name."""
    return {name: semantic_label(name) for name in (*ARCHITECTURE, *categories)}
