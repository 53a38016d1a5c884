"""Pieces that recur across furniture categories: drawer fronts, doors, sets of four legs and
rounded-rectangle outlines.

``HANDLE`` and ``FRONT`` fix how a front stacks along +x: its outer face lies ``HANDLE``
behind the front plane ``xf`` so that the handles, not the panels, reach the front of the
model's box.
"""
from __future__ import annotations

import math

import numpy as np

from ..builder import Builder

HANDLE = 0.014     # how far handles and knobs stand proud of a front
FRONT = 0.018      # thickness of door and drawer fronts


def drawer(b: Builder, mat, hmat, y0, y1, z0, z1, xf, handle='bar', gap=0.004):
    """A drawer front in the plane just behind ``xf`` with its handle reaching ``xf``."""
    b.box('drawer', mat, xf - HANDLE - FRONT, xf - HANDLE, y0 + gap, y1 - gap, z0 + gap, z1 - gap)
    yc, zc = (y0 + y1) / 2.0, (z0 + z1) / 2.0
    if handle == 'bar':
        hw = min(0.16, 0.4 * (y1 - y0))
        b.box('handle', hmat, xf - HANDLE, xf, yc - hw / 2, yc + hw / 2, zc - 0.008, zc + 0.008)
    elif handle == 'knob':
        b.seg('handle', hmat, (xf - HANDLE, yc, zc), (xf, yc, zc), 0.013, n=10)
    elif handle == 'knobs':
        for yk in (y0 + (y1 - y0) * 0.25, y0 + (y1 - y0) * 0.75):
            b.seg('handle', hmat, (xf - HANDLE, yk, zc), (xf, yk, zc), 0.012, n=10)
    elif handle == 'top':
        hw = min(0.2, 0.6 * (y1 - y0))
        b.box('handle', hmat, xf - HANDLE, xf, yc - hw / 2, yc + hw / 2, z1 - gap - 0.03,
              z1 - gap - 0.015)


def door(b: Builder, mat, hmat, y0, y1, z0, z1, xf, handle_side=+1, handle_z=None,
          gap=0.004, handle_len=None):
    """A door panel; a vertical bar handle near the y1 edge (``handle_side`` +1) or the y0
    edge (-1)."""
    b.box('door', mat, xf - HANDLE - FRONT, xf - HANDLE, y0 + gap, y1 - gap, z0 + gap, z1 - gap)
    hl = handle_len if handle_len is not None else min(0.28, 0.35 * (z1 - z0))
    if handle_z is None:
        handle_z = min(max(1.0, z0 + hl), z1 - hl * 0.6 - 0.05) if z1 - z0 > 0.9 \
            else z1 - 0.06 - hl / 2
    handle_z = min(max(handle_z, z0 + hl / 2 + 0.02), z1 - hl / 2 - 0.02)
    yh = y1 - 0.045 if handle_side > 0 else y0 + 0.045
    b.box('handle', hmat, xf - HANDLE, xf, yh - 0.009, yh + 0.009, handle_z - hl / 2,
          handle_z + hl / 2)


def legs_box(b: Builder, mat, x0, x1, y0, y1, z0, z1, t=0.045, inset=0.0, name='leg'):
    for xa in (x0 + inset, x1 - inset - t):
        for ya in (y0 + inset, y1 - inset - t):
            b.box(name, mat, xa, xa + t, ya, ya + t, z0, z1)


def legs_round(b: Builder, mat, x0, x1, y0, y1, z0, z1, r=0.02, inset=0.0, taper=1.0, n=10):
    for xa in (x0 + inset + r, x1 - inset - r):
        for ya in (y0 + inset + r, y1 - inset - r):
            if taper == 1.0:
                b.cyl('leg', mat, xa, ya, z0, z1, r, n=n)
            else:
                b.frustum('leg', mat, xa, ya, z0, z1, r * taper, r, n=n)


def rounded_rect(hx: float, hy: float, r: float, per_corner: int = 6) -> np.ndarray:
    """Counter-clockwise outline of a rectangle (half sizes hx, hy) with corner radius r;
    r = min(hx, hy) gives a stadium."""
    r = min(r, hx, hy)
    pts = []
    for (cx, cy, a0) in ((hx - r, hy - r, 0.0), (-hx + r, hy - r, 90.0),
                         (-hx + r, -hy + r, 180.0), (hx - r, -hy + r, 270.0)):
        for t in np.linspace(a0, a0 + 90.0, per_corner + 1):
            pts.append((cx + r * math.cos(math.radians(t)), cy + r * math.sin(math.radians(t))))
    out = [pts[0]]
    for p in pts[1:]:
        if math.dist(p, out[-1]) > 1e-9:
            out.append(p)
    if math.dist(out[0], out[-1]) < 1e-9:
        out.pop()
    return np.asarray(out)
