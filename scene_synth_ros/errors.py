"""The base of every error the package raises for bad input.

Its message is one sentence saying what was wrong and where; every front end (command line,
node, evaluation) reports it as that sentence, without a traceback, and goes on serving.
"""
from __future__ import annotations


class SceneSynthError(Exception):
    """Bad input or an impossible request, described in one sentence."""


class UnknownRoomType(SceneSynthError, ValueError):
    """A room type that is not one of ``categories.ROOM_TYPES`` (nor an alias of one)."""
