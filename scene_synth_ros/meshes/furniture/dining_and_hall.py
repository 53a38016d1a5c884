"""Builders for the dining room and the hallway: dining tables and chairs, sideboards, shoe
benches, console tables and wall-standing coat racks.

A round dining table is a style of the category, not a category: its top is the ellipse
inscribed in the model's box (a circle when the box is square), so the box the scene model
knows still bounds it. Builders sketch in the object frame of ``meshes.builder`` and
declare their categories with ``@builds``.
"""
from __future__ import annotations

import math

import numpy as np

from ..builder import Builder, builds, rot_y
from ..materials import BOOK_COVERS
from .fittings import FRONT, HANDLE, door, drawer, legs_box, legs_round


def _ellipse(hx: float, hy: float, n: int = 32) -> np.ndarray:
    """Counter-clockwise outline of the ellipse with half axes ``hx``, ``hy``."""
    a = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    return np.column_stack((hx * np.cos(a), hy * np.sin(a)))


@builds('dining table')
def dining_table(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'wood_dark')
    t = 0.035
    zt = H - t
    if s == 1:
        # round (oval when long): on a pedestal, or two when the top is long
        b.prism('top', mat, _ellipse(D / 2, W / 2, 40), zt, H)
        b.prism('apron', mat, _ellipse(D / 2 - 0.08, W / 2 - 0.08, 28), zt - 0.06, zt)
        feet = (0.0,) if W < 1.5 else (-W * 0.25, W * 0.25)
        for yc in feet:
            b.cyl('pedestal', mat, 0.0, yc, 0.06, zt - 0.06, 0.06, n=16)
            b.frustum('pedestal_foot', mat, 0.0, yc, 0.0, 0.06, min(0.3, D * 0.32), 0.07, n=20)
        if len(feet) == 2:
            b.box('stretcher', mat, -0.03, 0.03, feet[0], feet[1], 0.1, 0.14)
        return
    b.box('top', mat, x0, x1, y0, y1, zt, H)
    if s == 2:
        # trestle ends joined by a stretcher
        for ya in (y0 + 0.12, y1 - 0.18):
            b.box('trestle', 'metal_dark', x0 + 0.08, x1 - 0.08, ya, ya + 0.06, zt - 0.04, zt)
            b.box('trestle', 'metal_dark', -0.03, 0.03, ya, ya + 0.06, 0.05, zt - 0.04)
            b.box('trestle_foot', 'metal_dark', x0 + 0.06, x1 - 0.06, ya, ya + 0.06, 0.0, 0.05)
        b.box('stretcher', 'metal_dark', -0.025, 0.025, y0 + 0.18, y1 - 0.18, 0.3, 0.35)
        return
    leg = 0.07
    legs_box(b, mat, x0 + 0.04, x1 - 0.04, y0 + 0.04, y1 - 0.04, 0.0, zt, t=leg)
    if W > 2.2:
        # a long table gets a middle pair of legs
        for xa in (x0 + 0.04, x1 - 0.04 - leg):
            b.box('leg', mat, xa, xa + leg, -leg / 2, leg / 2, 0.0, zt)
    for xa, xb in ((x0 + 0.04, x0 + 0.06), (x1 - 0.06, x1 - 0.04)):
        b.box('apron', mat, xa, xb, y0 + 0.04 + leg, y1 - 0.04 - leg, zt - 0.1, zt)
    for ya, yb in ((y0 + 0.04, y0 + 0.06), (y1 - 0.06, y1 - 0.04)):
        b.box('apron', mat, x0 + 0.04 + leg, x1 - 0.04 - leg, ya, yb, zt - 0.1, zt)


@builds('dining chair')
def dining_chair(b: Builder):
    H, s = b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    wood = b.pick('wood_dark', 'wood_light', 'wood')
    fab = b.pick('fabric_beige', 'fabric_green', 'leather')
    hs = 0.46
    t = 0.04
    for ya in (y0, y1 - t):
        b.box('back_leg', wood, x0, x0 + t, ya, ya + t, 0.0, H - 0.02)
        b.box('front_leg', wood, x1 - t, x1, ya, ya + t, 0.0, hs)
    b.box('seat_frame', wood, x0, x1, y0, y1, hs - 0.06, hs - 0.02)
    b.box('seat', fab, x0 + 0.02, x1 - 0.005, y0 + 0.005, y1 - 0.005, hs - 0.02, hs + 0.03)
    if s == 0:
        # an upholstered back between the back legs, slightly reclined
        b.obox('backrest', fab, (x0 + 0.03, 0.0, (hs + 0.08 + H) / 2), (0.05, (y1 - y0) - 2 * t,
                                                                         H - hs - 0.08),
               rot_y(-math.radians(6)))
    elif s == 1:
        # spindles under a curved top rail
        b.box('top_rail', wood, x0, x0 + t, y0 + t, y1 - t, H - 0.1, H)
        for yc in np.linspace(y0 + t, y1 - t, 7)[1:-1]:
            b.cyl('spindle', wood, x0 + t / 2, yc, hs + 0.03, H - 0.1, 0.009, n=8)
    else:
        # a carver: arms on posts, a padded back
        b.box('top_rail', wood, x0, x0 + t, y0 + t, y1 - t, H - 0.07, H)
        b.box('back_pad', fab, x0 + 0.005, x0 + t + 0.015, y0 + t, y1 - t, hs + 0.14, H - 0.09)
        for ya in (y0, y1 - t):
            b.box('arm', wood, x0 + t, x1, ya, ya + t, hs + 0.2, hs + 0.23)
            b.box('arm_post', wood, x1 - t - 0.02, x1 - 0.02, ya + 0.005, ya + t - 0.005, hs,
                  hs + 0.2)
    for ya in (y0 + t / 2, y1 - t / 2):
        b.box('stretcher', wood, x0 + t, x1 - t, ya - 0.01, ya + 0.01, 0.13, 0.16)


@builds('sideboard')
def sideboard(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'wood_dark')
    front = b.pick('wood_light', 'paint_grey', 'wood')
    hmat = b.pick('brass', 'chrome', 'metal_dark')
    xf = x1
    base = 0.16 if s == 1 else 0.08
    if s == 1:
        legs_round(b, 'wood_dark', x0 + 0.03, xf - 0.05, y0 + 0.04, y1 - 0.04, 0.0, base + 0.01,
                   r=0.02, taper=0.55, n=8)
    else:
        b.box('plinth', 'shadow', x0 + 0.02, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, base)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, base, H - 0.03)
    b.box('top', mat, x0, xf - HANDLE + 0.004, y0, y1, H - 0.03, H)
    zs = H - 0.03
    n = 3 if W < 1.7 else 4
    cw = W / n
    for k in range(n):
        ya, yb = y0 + k * cw, y0 + (k + 1) * cw
        if s == 1 and 0 < k < n - 1:
            # drawers in the middle, doors at the ends
            dh = (zs - base) / 3
            for r in range(3):
                drawer(b, front, hmat, ya, yb, base + r * dh, base + (r + 1) * dh, xf, 'knob')
        elif s == 2:
            drawer(b, front, hmat, ya, yb, zs - 0.15, zs, xf, 'bar')
            door(b, 'glass' if k in (0, n - 1) else front, hmat, ya, yb, base, zs - 0.15, xf,
                 handle_side=-1 if k % 2 else 1, handle_len=0.12)
        else:
            door(b, front, hmat, ya, yb, base, zs, xf, handle_side=-1 if k % 2 else 1,
                 handle_len=0.14)


@builds('shoe bench')
def shoe_bench(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_light', 'metal_dark', 'wood_white')
    t = 0.02
    zs = H - (0.06 if s != 2 else 0.025)         # top of the seat board, under the cushion
    b.box('side', mat, x0, x1, y0, y0 + t, 0.0, zs)
    b.box('side', mat, x0, x1, y1 - t, y1, 0.0, zs)
    b.box('seat_board', 'wood' if s == 1 else mat, x0, x1, y0, y1, zs - 0.025, zs)
    if s != 2:
        b.box('cushion', b.pick('fabric_grey', 'fabric_mustard', 'fabric_blue'), x0 + 0.01,
              x1 - 0.01, y0 + 0.01, y1 - 0.01, zs, H)
    else:
        b.box('seat_pad', 'fabric_beige', x0 + 0.03, x1 - 0.03, y0 + 0.05, y1 - 0.05, zs, H)
    shelves = (0.04, (zs - 0.025) * 0.5) if s == 1 else (0.04,)
    for z in shelves:
        if s == 1:
            # a slatted metal shelf
            for xc in np.linspace(x0 + 0.03, x1 - 0.03, 5):
                b.box('shelf_slat', mat, xc - 0.008, xc + 0.008, y0 + t, y1 - t, z, z + 0.015)
        else:
            b.box('shelf', mat, x0, x1, y0 + t, y1 - t, z, z + 0.018)
    if s == 2:
        # cubbies: dividers between pairs of shoes
        cubbies = max(2, int(round((W - 2 * t) / 0.3)))
        for yc in np.linspace(y0 + t, y1 - t, cubbies + 1)[1:-1]:
            b.box('divider', mat, x0, x1, yc - 0.009, yc + 0.009, 0.058, zs - 0.025)
    # pairs of shoes on the bottom shelf, toes to the front
    pairs = max(1, int((W - 2 * t) / 0.24))
    pw = (W - 2 * t) / pairs
    for k in range(pairs):
        shoe = BOOK_COVERS[(k * 3 + s) % len(BOOK_COVERS)]
        for dy in (-0.045, 0.045):
            yc = y0 + t + pw * (k + 0.5) + dy
            b.sphere('shoe', shoe, (0.0, yc, 0.058 + 0.04), (min(0.13, D / 2 - 0.02), 0.038, 0.04))


@builds('console table')
def console_table(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_dark', 'wood', 'wood_light')
    t = 0.03
    zt = H - t
    b.box('top', mat if s != 2 else 'stone', x0, x1, y0, y1, zt, H)
    if s == 0:
        legs_round(b, mat, x0 + 0.01, x1 - 0.01, y0 + 0.02, y1 - 0.02, 0.0, zt, r=0.018,
                   taper=0.6, n=8)
        b.box('apron', mat, x0 + 0.02, x1 - 0.02, y0 + 0.04, y1 - 0.04, zt - 0.08, zt)
        b.box('shelf', mat, x0 + 0.02, x1 - 0.02, y0 + 0.04, y1 - 0.04, 0.16, 0.18)
    elif s == 1:
        legs_box(b, mat, x0, x1, y0, y1, 0.0, zt, t=0.04)
        b.box('apron', mat, x0 + 0.04, x1 - 0.04, y0 + 0.04, y1 - 0.04, zt - 0.12, zt)
        for k in range(2):
            ya = y0 + 0.05 + k * (W - 0.1) / 2
            drawer(b, mat, 'brass', ya, ya + (W - 0.1) / 2, zt - 0.12, zt, x1 - 0.004, 'knob')
    else:
        # a metal frame: two end frames and a stretcher shelf
        for ya in (y0, y1 - 0.025):
            b.box('frame_leg', 'metal_dark', x0, x0 + 0.025, ya, ya + 0.025, 0.0, zt)
            b.box('frame_leg', 'metal_dark', x1 - 0.025, x1, ya, ya + 0.025, 0.0, zt)
            b.box('frame_foot', 'metal_dark', x0, x1, ya, ya + 0.025, 0.0, 0.025)
        b.box('shelf', 'wood_light', x0 + 0.025, x1 - 0.025, y0 + 0.025, y1 - 0.025, 0.2, 0.22)


@builds('coat rack')
def coat_rack(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'metal_dark', 'wood_white')
    hook = b.pick('metal_dark', 'brass', 'chrome')
    u = 0.04
    # two uprights against the wall on feet that reach forward, a hat shelf on top
    for ya in (y0, y1 - u):
        b.box('upright', mat, x0, x0 + u, ya, ya + u, 0.0, H - 0.03)
        b.box('foot', mat, x0, x1, ya, ya + u, 0.0, 0.04)
    b.box('hat_shelf', mat, x0, x1, y0, y1, H - 0.03, H)
    zr = H - 0.28
    b.box('hook_rail', mat, x0, x0 + 0.025, y0 + u, y1 - u, zr - 0.05, zr + 0.05)
    if s == 0:
        b.box('back_panel', mat, x0, x0 + 0.012, y0 + u, y1 - u, 0.5, zr - 0.05)
    if s != 1:
        b.box('shoe_shelf', mat, x0, x1 - 0.02, y0 + u, y1 - u, 0.1, 0.12)
    n = max(3, int((W - 2 * u) / 0.15))
    coats = {1: (0, 2, 4), 0: (1,)}.get(s, ())
    for k, yc in enumerate(np.linspace(y0 + u + 0.06, y1 - u - 0.06, n)):
        b.seg('hook', hook, (x0 + 0.025, yc, zr), (x0 + 0.12, yc, zr + 0.05), 0.011, n=8)
        b.sphere('hook_tip', hook, (x0 + 0.12, yc, zr + 0.05), 0.018, subdiv=1)
        if s == 2:
            # double hooks: a lower, shorter arm for bags
            b.seg('hook', hook, (x0 + 0.025, yc, zr - 0.03), (x0 + 0.07, yc, zr - 0.07), 0.009,
                  n=8)
        if k in coats:
            colour = ('fabric_beige', 'fabric_blue', 'fabric_red')[(k // 2) % 3]
            b.box('coat', colour, x0 + 0.04, min(x1, x0 + 0.22), max(y0 + u, yc - 0.17),
                  min(y1 - u, yc + 0.17), zr - 0.85, zr - 0.02)
