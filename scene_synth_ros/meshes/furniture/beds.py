"""Builders for beds: double and single beds, bunker beds, baby cots and daybeds.

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import numpy as np

from ..builder import Builder, builds
from .fittings import legs_box


@builds('double bed', 'single bed')
def bed(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    frame = b.pick('wood', 'fabric_grey', 'wood_white')
    hb = 0.09 if s == 1 else 0.05
    base_top = min(0.34, 0.42 * H)
    mtop = min(base_top + 0.22, H - 0.16)
    foot = 0.05 if s == 2 else 0.0
    if s == 1:
        b.box('headboard', frame, x0, x0 + hb, y0, y1, 0.0, H)
        b.box('headboard_pad', 'fabric_grey_light', x0 + hb, x0 + hb + 0.03, y0 + 0.09, y1 - 0.09,
              mtop + 0.03, H - 0.07)
    else:
        p = 0.07
        b.box('headboard', frame, x0, x0 + hb, y0, y0 + p, 0.0, H)
        b.box('headboard', frame, x0, x0 + hb, y1 - p, y1, 0.0, H)
        b.box('headboard', frame, x0 + 0.008, x0 + hb - 0.008, y0 + p, y1 - p, base_top - 0.05,
              H - 0.03)
    xr0, xr1 = x0 + hb, x1 - foot
    if s == 1:
        b.box('base', frame, xr0, xr1, y0, y1, 0.03, base_top)
        b.box('plinth', 'wood_dark', xr0 + 0.06, xr1 - 0.06, y0 + 0.06, y1 - 0.06, 0.0, 0.03)
    else:
        leg = 0.12
        b.box('frame', frame, xr0, xr1, y0, y1, leg, base_top)
        legmat = b.pick('wood_dark', 'wood_dark', 'wood_white')
        b.box('leg', legmat, xr1 - 0.07, xr1, y0, y0 + 0.07, 0.0, leg)
        b.box('leg', legmat, xr1 - 0.07, xr1, y1 - 0.07, y1, 0.0, leg)
    if foot:
        b.box('footboard', frame, x1 - foot, x1, y0, y1, 0.0, min(base_top + 0.26, mtop + 0.1))
    b.box('mattress', 'mattress', xr0 + 0.01, xr1 - 0.01, y0 + 0.025, y1 - 0.025, base_top, mtop)
    blanket = b.pick('blanket_blue', 'blanket_rose', 'blanket_green')
    bx0 = xr0 + 0.36 * (xr1 - xr0)
    b.box('blanket', blanket, bx0, xr1, y0 + 0.01, y1 - 0.01, base_top + 0.05, mtop + 0.02)
    b.box('blanket_fold', 'linen', bx0 - 0.006, bx0 + 0.13, y0 + 0.012, y1 - 0.012, mtop - 0.01,
          mtop + 0.035)
    n = 2 if W >= 1.25 else 1
    pw = (W - 0.14) / n
    for i in range(n):
        yc = y0 + 0.07 + pw * (i + 0.5)
        b.sphere('pillow', 'linen', (xr0 + 0.2, yc, mtop + 0.05),
                 (0.15, min(pw / 2 - 0.03, 0.36), 0.065), subdiv=2)


@builds('bunker bed')
def bunker_bed(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'metal_dark')
    p = 0.07
    legs_box(b, mat, x0, x1, y0, y1, 0.0, H, t=p, name='post')
    up = H - 0.62
    for z0, z1 in ((0.15, 0.3), (up, up + 0.14)):
        b.box('deck', mat, x0 + 0.01, x1 - 0.01, y0 + 0.01, y1 - 0.01, z0, z1)
        b.box('mattress', 'mattress', x0 + p, x1 - p, y0 + 0.03, y1 - 0.03, z1, z1 + 0.14)
        b.box('blanket', b.pick('blanket_blue', 'blanket_green', 'blanket_rose'),
              x0 + 0.75, x1 - p + 0.01, y0 + 0.02, y1 - 0.02, z1 + 0.06, z1 + 0.16)
        b.sphere('pillow', 'linen', (x0 + p + 0.17, 0.0, z1 + 0.18), (0.14, W / 2 - 0.18, 0.05))
        b.box('head_panel', mat, x0 + 0.015, x0 + 0.045, y0 + p, y1 - p, z1,
              min(z1 + 0.4, H - 0.04))
    rail_z = (H - 0.2, H - 0.12)
    b.box('guard_rail', mat, x0 + p, x1 - p, y0 + 0.01, y0 + 0.05, *rail_z)
    ladder_top = up + 0.2
    r = 0.016
    if s == 0:
        b.box('guard_rail', mat, x0 + p, x1 - p, y1 - 0.05, y1 - 0.01, *rail_z)
        b.box('foot_panel', mat, x1 - 0.045, x1 - 0.015, y0 + p, y1 - p, 0.3, 0.5)
        xl = x1 - 0.02
        ya, yb = y1 - p - 0.4, y1 - p - 0.03
        b.seg('ladder', mat, (xl, ya, 0.0), (xl, ya, ladder_top), r)
        b.seg('ladder', mat, (xl, yb, 0.0), (xl, yb, ladder_top), r)
        for z in np.arange(0.28, ladder_top - 0.1, 0.26):
            b.seg('ladder_rung', mat, (xl, ya, z), (xl, yb, z), r * 0.8)
    else:
        b.box('guard_rail', mat, x0 + p, x1 - p - 0.52, y1 - 0.05, y1 - 0.01, *rail_z)
        b.box('foot_panel', mat, x1 - 0.045, x1 - 0.015, y0 + p, y1 - p, 0.3, 0.5)
        b.box('foot_panel', mat, x1 - 0.045, x1 - 0.015, y0 + p, y1 - p, up + 0.14, H - 0.12)
        yl = y1 - 0.025
        xa, xb = x1 - p - 0.46, x1 - p - 0.06
        b.seg('ladder', mat, (xa, yl, 0.0), (xa, yl, ladder_top), r)
        b.seg('ladder', mat, (xb, yl, 0.0), (xb, yl, ladder_top), r)
        for z in np.arange(0.28, ladder_top - 0.1, 0.26):
            b.seg('ladder_rung', mat, (xa, yl, z), (xb, yl, z), r * 0.8)


@builds('baby bed')
def baby_bed(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood_light', 'wood')
    p = 0.045
    legs_box(b, mat, x0, x1, y0, y1, 0.0, H, t=p, name='post')
    zb = 0.32
    b.box('base', mat, x0 + p, x1 - p, y0 + p, y1 - p, zb - 0.04, zb)
    b.box('mattress', b.pick('blanket_blue', 'mattress', 'blanket_rose'), x0 + p, x1 - p,
          y0 + p, y1 - p, zb, zb + 0.1)
    b.sphere('pillow', 'linen', (x0 + p + 0.12, 0, zb + 0.12), (0.09, 0.18, 0.04))
    t = 0.028
    for yc in (y0 + p / 2, y1 - p / 2):
        for z0, z1 in ((zb - 0.08, zb - 0.02), (H - 0.045, H - 0.005)):
            b.box('rail', mat, x0 + p, x1 - p, yc - t / 2, yc + t / 2, z0, z1)
        n = max(6, int((D - 2 * p) / 0.075))
        for xc in np.linspace(x0 + p, x1 - p, n + 2)[1:-1]:
            b.box('bar', mat, xc - 0.011, xc + 0.011, yc - 0.011, yc + 0.011, zb - 0.02, H - 0.045)
    for xc in (x0 + p / 2, x1 - p / 2):
        if s == 2:
            b.box('end_panel', mat, xc - 0.012, xc + 0.012, y0 + p, y1 - p, zb - 0.08, H - 0.01)
            continue
        for z0, z1 in ((zb - 0.08, zb - 0.02), (H - 0.045, H - 0.005)):
            b.box('rail', mat, xc - t / 2, xc + t / 2, y0 + p, y1 - p, z0, z1)
        n = max(4, int((W - 2 * p) / 0.075))
        for yc in np.linspace(y0 + p, y1 - p, n + 2)[1:-1]:
            b.box('bar', mat, xc - 0.011, xc + 0.011, yc - 0.011, yc + 0.011, zb - 0.02, H - 0.045)


@builds('daybed')
def daybed(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    ha = min(0.74 * H, H - 0.1)
    soft = b.pick('fabric_beige', 'fabric_blue', 'fabric_grey_light')
    if s == 0:
        mat, t, r = 'metal_dark', 0.05, 0.018
        for xa, top in ((x0 + t / 2, H - r), (x1 - t / 2, ha - r)):
            for ya in (y0 + t / 2, y1 - t / 2):
                b.seg('post', mat, (xa, ya, 0.0), (xa, ya, top), r * 1.4)
        b.seg('back_rail', mat, (x0 + t / 2, y0 + t / 2, H - r), (x0 + t / 2, y1 - t / 2, H - r), r)
        for yc in np.arange(y0 + 0.15, y1 - 0.1, 0.12):
            b.seg('back_bar', mat, (x0 + t / 2, yc, 0.3), (x0 + t / 2, yc, H - r), r * 0.6, n=8)
        for ya in (y0 + t / 2, y1 - t / 2):
            b.seg('arm_rail', mat, (x0 + t / 2, ya, ha - r), (x1 - t / 2, ya, ha - r), r)
            for xc in np.arange(x0 + 0.15, x1 - 0.1, 0.12):
                b.seg('arm_bar', mat, (xc, ya, 0.3), (xc, ya, ha - r), r * 0.6, n=8)
        b.box('frame', mat, x0 + t, x1 - t, y0 + t, y1 - t, 0.24, 0.3)
    else:
        mat = b.pick('metal_dark', 'wood', soft)
        t = 0.07 if s == 1 else 0.13
        b.box('back', mat, x0, x0 + t, y0, y1, 0.06, H)
        b.box('arm', mat, x0, x1, y0, y0 + t, 0.06, ha)
        b.box('arm', mat, x0, x1, y1 - t, y1, 0.06, ha)
        b.box('base', mat, x0 + t, x1, y0 + t, y1 - t, 0.06, 0.3)
        legs_box(b, 'wood_dark', x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, 0.06, t=0.05)
    b.box('mattress', b.pick('mattress', 'mattress', soft), x0 + t, x1 - 0.01, y0 + t, y1 - t,
          0.3, 0.46)
    inner = W - 2 * t
    zc = min(0.62, H - 0.2)
    for i in range(3):
        yc = y0 + t + inner * (i + 0.5) / 3
        b.sphere('cushion', b.pick('fabric_blue', 'fabric_mustard', 'fabric_green'),
                 (x0 + t + 0.1, yc, zc), (0.09, inner / 6 - 0.02, 0.16), subdiv=2)
