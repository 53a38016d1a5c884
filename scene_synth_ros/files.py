"""Writing files whole or not at all, under names that cannot collide.

The files others read while they may be changing (scenes, the node's exports, weight
bundles, training checkpoints, the corpus calibration) go through
``write_atomic``/``writing_together``: written under a private temporary directory beside
their destination, then renamed into place, so a reader never sees half a file and a failed
write leaves the old file as it was. A rename within one directory is atomic on POSIX and on
Windows (``os.replace``).
"""
from __future__ import annotations

from contextlib import contextmanager
import json
import os
from pathlib import Path
import re
import shutil
import tempfile
from typing import Any, Iterator, Sequence

from .errors import quoted


@contextmanager
def writing_together(directory: str | os.PathLike, names: Sequence[str]) -> Iterator[Path]:
    """A private temporary directory in which to write the files ``names`` under their final
    names; when the block ends without an error they are moved into ``directory`` in the
    order given (each move atomic), and an error in the block moves none of them.

    For files that refer to each other by name (an OBJ and its MTL): list the one referred to
    first, so that a reader never finds a file whose companion is not there yet."""
    directory = Path(directory)
    tmp = Path(tempfile.mkdtemp(prefix='.tmp-', dir=directory))
    try:
        yield tmp
        for name in names:
            os.replace(tmp / name, directory / name)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def write_atomic(path: str | os.PathLike, data: str | bytes) -> None:
    """Write ``data`` (text as UTF-8) to ``path`` whole or not at all."""
    path = Path(path)
    with writing_together(path.parent, [path.name]) as tmp:
        (tmp / path.name).write_bytes(data.encode('utf-8') if isinstance(data, str) else data)


def safe_name(text: str) -> str:
    """``text`` as a file or SDF model name: letters, digits and ``_`` stay, every other
    character becomes ``-<hex code>-`` (``a@1.5`` gives ``a-40-1-2e-5``), so the usual ids
    are their own names, and different texts never share a name (``-`` occurs only in these
    escapes, so a name decodes back to exactly one text)."""
    return re.sub(r'[^A-Za-z0-9_]', lambda m: f'-{ord(m.group()):x}-', text)


def read_json(path: str | os.PathLike, what: str, error: type[Exception],
              missing: str = '') -> Any:
    """The JSON document in ``path``, or ``error`` with one sentence naming the file as
    ``what`` (e.g. ``'the catalog'``): it does not exist (followed by ``missing``, a hint of
    where one comes from), cannot be read, or is not JSON."""
    name = quoted(str(path), 80)
    try:
        return json.loads(Path(path).read_text(encoding='utf-8'))
    except FileNotFoundError:
        raise error(f'{what} {name} does not exist{missing}') from None
    except (OSError, UnicodeDecodeError) as e:
        raise error(f'cannot read {what} {name}: {getattr(e, "strerror", None) or e}') from None
    except json.JSONDecodeError as e:
        raise error(f'{what} {name} is not valid JSON: {e.msg} at line {e.lineno}') from None
