"""Axis names (``+x`` ... ``-z``) and the rotation that takes a model's own axes to the
package's object frame: its front onto +x, its up onto +z (so its left lands on +y)."""
from __future__ import annotations

import numpy as np

AXES = {f'{sign}{name}': float(f'{sign}1') * np.eye(3)[k]
        for k, name in enumerate('xyz') for sign in '+-'}


def parse_axis(text: object) -> np.ndarray | None:
    """The unit vector of an axis name (``+x``, ``-z``; a bare ``y`` is ``+y``), or None."""
    if not isinstance(text, str):
        return None
    name = text.strip().lower()
    if len(name) == 1:
        name = '+' + name
    v = AXES.get(name)
    return None if v is None else v.copy()


def to_package_frame(up: np.ndarray, front: np.ndarray) -> np.ndarray:
    """The rotation R with R @ front = +x and R @ up = +z; its rows are the model's front,
    left (up x front) and up, a proper rotation because front and up are orthonormal. The
    caller checks that they are not parallel."""
    left = np.cross(up, front)
    return np.stack([front, left, up])
