"""Bounds on what the package reads from outside, checked before any other work is done.

A real room has tens of floor vertices, a few doors and windows and tens of objects; its
JSON is a few kilobytes, five levels deep. The bounds below are generous for such rooms and
keep a hostile or broken input from costing more than a fraction of a second or exhausting
the interpreter (recursion, integer conversion, memory): an input past one of them is
refused with one sentence before it is parsed further.

* the payload: at most ``MAX_PAYLOAD_BYTES`` of UTF-8 text;
* the document: at most ``MAX_DEPTH`` levels of nested arrays and objects, and
  ``MAX_NODES`` values in all;
* a number: a literal of at most ``MAX_NUMBER_CHARS`` characters, finite;
* a string or a key: at most ``MAX_STRING`` characters;
* YAML text (read only where a person types the input, see ``loads_yaml``): at most
  ``MAX_YAML_BYTES``, no anchors or aliases, JSON's kinds of values only;
* a room: the counts and coordinate range in ``msg_schemas/`` (``maxItems``, ``maximum``),
  which the JSON Schema check applies next: ``MAX_FLOOR_VERTICES`` floor vertices,
  ``MAX_OPENINGS`` doors and as many windows, ``MAX_OBJECTS`` objects, coordinates within
  ``MAX_COORDINATE`` metres of the origin.
"""
from __future__ import annotations

from collections.abc import Mapping
import json
import math
from typing import Any, Callable

import numpy as np
import yaml

from .errors import MAX_QUOTE, number, quoted

MAX_PAYLOAD_BYTES = 1 << 20       # 1 MiB: a furnished room's scene is about 20 KB
MAX_DEPTH = 32                    # a layout is 4 levels deep; the rest is for meta
MAX_NODES = 20_000                # values in a document: bounds the schema check's work
MAX_NUMBER_CHARS = 1000           # characters of one number literal (Python refuses 4300 digits)
MAX_STRING = 4096                 # characters of one string or key
MAX_YAML_BYTES = 64 << 10         # YAML is parsed in pure Python: a typed room is under 2 KB
# Mirrored in msg_schemas/ (a test checks that the two agree).
MAX_FLOOR_VERTICES = 256
MAX_OPENINGS = 64
MAX_OBJECTS = 256
MAX_COORDINATE = 1e5              # metres from the origin, for floor vertices and openings


class LimitExceeded(ValueError):
    """An input past one of the bounds: ``path`` names where (``""``: the document)."""

    def __init__(self, message: str, path: str = ''):
        super().__init__(message)
        self.path = path


def key_text(key: object) -> str:
    """A mapping key as it reads inside a path: itself when short and printable, else
    quoted and cut."""
    s = str(key)
    return s if len(s) <= MAX_QUOTE and s.isprintable() and s else quoted(s)


def join(prefix: str, key: str | int) -> str:
    """The path of ``key`` inside ``prefix`` (``floor[2]``, ``objects[0].size``)."""
    if isinstance(key, int):
        return f'{prefix}[{key}]'
    key = key_text(key)
    return f'{prefix}.{key}' if prefix else key


def _name(path: str) -> str:
    return path or 'the payload'


def _bounded_literal(kind: Callable[[str], Any]) -> Callable[[str], Any]:
    def parse(text: str) -> Any:
        if len(text) > MAX_NUMBER_CHARS:
            raise LimitExceeded(
                f'the payload has a number of {len(text)} characters ({quoted(text)}); at '
                f'most {MAX_NUMBER_CHARS} are read')
        return kind(text)
    return parse


_PARSE_INT = _bounded_literal(int)
_PARSE_FLOAT = _bounded_literal(float)


def loads(text: str | bytes | bytearray) -> Any:
    """JSON text (or UTF-8 bytes) as Python values, within the payload and number bounds.
    Raises ``LimitExceeded``, ``UnicodeDecodeError`` or ``json.JSONDecodeError``."""
    size = len(text) if isinstance(text, (bytes, bytearray)) else None
    if size is None:
        # A str of n characters encodes to at most 4n bytes: measure only when it may be over.
        size = len(text) if len(text) * 4 <= MAX_PAYLOAD_BYTES else \
            len(text.encode('utf-8', 'surrogatepass'))
    if size > MAX_PAYLOAD_BYTES:
        raise LimitExceeded(f'the payload is {size} bytes; at most {MAX_PAYLOAD_BYTES} are read')
    if isinstance(text, (bytes, bytearray)):
        text = bytes(text).decode('utf-8')
    return json.loads(text, parse_int=_PARSE_INT, parse_float=_PARSE_FLOAT)


class YamlError(ValueError):
    """Text that is not YAML of JSON's kinds of values: one sentence, without the text."""


def loads_yaml(text: str) -> Any:
    """YAML text (a superset of JSON; its flow style is what people type at ``ros2 topic
    pub``) as Python values of the kinds JSON has. Raises ``LimitExceeded`` past the bounds
    and ``YamlError`` for anything else."""
    size = len(text.encode('utf-8', 'surrogatepass'))
    if size > MAX_YAML_BYTES:
        raise LimitExceeded(f'the payload is {size} bytes, and YAML is read only up to '
                            f'{MAX_YAML_BYTES} bytes (JSON up to {MAX_PAYLOAD_BYTES})')
    try:
        value = yaml.load(text, Loader=_JsonKindsLoader)
    except yaml.MarkedYAMLError as e:
        where = f' at line {e.problem_mark.line + 1} column {e.problem_mark.column + 1}' \
            if e.problem_mark else ''
        raise YamlError(f'{e.problem or e.context}{where}') from None
    except yaml.YAMLError as e:
        raise YamlError(' '.join(str(e).split())) from None
    except RecursionError:
        raise YamlError('it is nested too deeply') from None
    except ValueError:               # an integer past Python's digit limit
        raise YamlError('it has a number too long to read') from None
    _check_json_kinds(value)
    return value


class _JsonKindsLoader(yaml.SafeLoader):
    """The safe loader without aliases (a few bytes of them expand to millions of values)
    and without dates, which JSON does not have (they stay text)."""

    def compose_node(self, parent, index):
        if self.check_event(yaml.AliasEvent):
            raise yaml.composer.ComposerError(
                None, None, 'YAML aliases (*name) are not accepted',
                self.peek_event().start_mark)
        return super().compose_node(parent, index)


_JsonKindsLoader.yaml_implicit_resolvers = {
    first: [(tag, rx) for tag, rx in resolvers if not tag.endswith(':timestamp')]
    for first, resolvers in yaml.SafeLoader.yaml_implicit_resolvers.items()}


def _check_json_kinds(value: Any) -> None:
    """YamlError at the first value JSON cannot hold (binary, a set, a key that is not
    text); iterative, and the text is at most ``MAX_YAML_BYTES``."""
    stack: list[tuple[Any, str]] = [(value, '')]
    while stack:
        item, where = stack.pop()
        if isinstance(item, dict):
            for k, v in item.items():
                if not isinstance(k, str):
                    raise YamlError(f'{_name(where)} has a key that is not text '
                                    f'({quoted(str(k))}); quote it')
                stack.append((v, join(where, k)))
        elif isinstance(item, list):
            stack.extend((v, join(where, i)) for i, v in enumerate(item))
        elif not (item is None or isinstance(item, (str, int, float, bool))):
            kind = {bytes: 'binary data', set: 'a set'}.get(type(item), type(item).__name__)
            raise YamlError(f'{_name(where)} is {kind}, which JSON does not have')


def _leaf(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def _resolve(where: Any) -> str:
    """A path kept as (parent, key) pairs while walking, written out only when reported."""
    keys = []
    while isinstance(where, tuple):
        where, key = where
        keys.append(key)
    for key in reversed(keys):
        where = join(where, key)
    return where


def _scalar_problem(item: Any) -> str | None:
    """What is wrong with a number or string (``{name}`` stands for its path), or None."""
    if isinstance(item, bool) or item is None:
        return None
    if isinstance(item, float) and not math.isfinite(item):
        return f'{{name}} must be a finite number, got {number(item)}'
    if isinstance(item, int) and item.bit_length() > 1000:   # past 1e300: not a measure
        digits = int(item.bit_length() * math.log10(2)) + 1
        return f'{{name}} must be a finite number, got an integer of about {digits} digits'
    if isinstance(item, str) and len(item) > MAX_STRING:
        return f'{{name}} is a string of {len(item)} characters; at most {MAX_STRING} are read'
    return None


def check_tree(value: Any, path: str = '') -> None:
    """Raise ``LimitExceeded`` at the first value past a bound: nesting deeper than
    ``MAX_DEPTH``, more than ``MAX_NODES`` values, a number that is not finite or an integer
    beyond a float's range, a string or key longer than ``MAX_STRING``. Iterative, so any
    depth is safe to inspect."""
    stack: list[tuple[Any, Any, int]] = [(value, path, 0)]
    seen = 0

    def fail(text: str, where: Any) -> LimitExceeded:
        where = _resolve(where)
        return LimitExceeded(text.format(name=_name(where)), where)

    while stack:
        item, where, depth = stack.pop()
        item = _leaf(item)
        seen += 1
        if seen > MAX_NODES:
            raise LimitExceeded(f'the payload has more than {MAX_NODES} values')
        if not isinstance(item, (Mapping, list, tuple)):
            problem = _scalar_problem(item)
            if problem:
                raise fail(problem, where)
            continue
        if depth >= MAX_DEPTH:
            raise fail(f'{{name}} is nested more than {MAX_DEPTH} levels deep; at most '
                       f'{MAX_DEPTH} are read', where)
        if isinstance(item, Mapping):
            children = []
            for k, v in item.items():
                if isinstance(k, str) and len(k) > MAX_STRING:
                    raise fail(f'{{name}} has a key of {len(k)} characters; at most '
                               f'{MAX_STRING} are read', where)
                children.append((v, (where, str(k)), depth + 1))
        else:
            children = [(v, (where, i), depth + 1) for i, v in enumerate(item)]
        stack.extend(reversed(children))
