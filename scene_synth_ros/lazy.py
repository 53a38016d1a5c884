"""Names a package exports from its modules, each module imported when one of its names is
first asked for (PEP 562): the package's import stays light for those who need little."""
from __future__ import annotations

from importlib import import_module
import sys
from typing import Callable


def lazy_names(package: str, where: dict[str, str]) -> Callable[[str], object]:
    """The module ``__getattr__`` of ``package``: ``where`` maps each name to the module of
    the package that defines it; a name is imported at its first use and kept in the
    package."""
    def __getattr__(name: str):
        if name not in where:
            raise AttributeError(f'module {package!r} has no attribute {name!r}')
        value = getattr(import_module(f'.{where[name]}', package), name)
        setattr(sys.modules[package], name, value)
        return value
    return __getattr__
