"""Builders for desks and coffee tables.

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

from ..builder import Builder, builds
from ..materials import BOOK_COVERS
from .fittings import FRONT, HANDLE, drawer, legs_box, rounded_rect


@builds('desk')
def desk(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    top = b.pick('wood_light', 'wood_white', 'wood')
    t = 0.03
    b.box('top', top, x0, x1, y0, y1, H - t, H)
    zt = H - t
    if s == 0:
        legs_box(b, 'metal_dark', x0 + 0.03, x1 - 0.03, y0 + 0.03, y1 - 0.03, 0.0, zt, t=0.04)
        b.box('apron', 'metal_dark', x0 + 0.03, x0 + 0.05, y0 + 0.07, y1 - 0.07, zt - 0.22, zt)
        b.box('apron', 'metal_dark', x0 + 0.07, x1 - 0.07, y0 + 0.03, y0 + 0.05, zt - 0.06, zt)
        b.box('apron', 'metal_dark', x0 + 0.07, x1 - 0.07, y1 - 0.05, y1 - 0.03, zt - 0.06, zt)
    elif s == 1:
        b.box('panel_leg', top, x0 + 0.02, x1 - 0.02, y0 + 0.01, y0 + 0.04, 0.0, zt)
        b.box('panel_leg', top, x0 + 0.02, x1 - 0.02, y1 - 0.04, y1 - 0.01, 0.0, zt)
        b.box('modesty_panel', top, x0 + 0.03, x0 + 0.05, y0 + 0.04, y1 - 0.04, 0.3, zt)
    else:
        hmat = 'metal'
        pw = min(0.42, W * 0.35)
        xf = x1 - 0.03
        b.box('panel_leg', top, x0 + 0.02, x1 - 0.03, y0 + 0.01, y0 + 0.04, 0.0, zt)
        b.box('pedestal', top, x0 + 0.02, xf - HANDLE - FRONT, y1 - pw, y1 - 0.01, 0.0, zt)
        b.box('modesty_panel', top, x0 + 0.03, x0 + 0.05, y0 + 0.04, y1 - pw, 0.35, zt)
        n = 3
        dh = (zt - 0.03) / n
        for k in range(n):
            drawer(b, top, hmat, y1 - pw, y1 - 0.01, 0.03 + k * dh, 0.03 + (k + 1) * dh, xf,
                    'bar')


@builds('coffee table')
def coffee_table(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    if s == 0:
        mat = 'wood'
        b.box('top', mat, x0, x1, y0, y1, H - 0.04, H)
        legs_box(b, mat, x0 + 0.03, x1 - 0.03, y0 + 0.03, y1 - 0.03, 0.0, H - 0.04, t=0.05)
        b.box('apron', mat, x0 + 0.05, x1 - 0.05, y0 + 0.05, y1 - 0.05, H - 0.1, H - 0.04)
    elif s == 1:
        # rounded-end (stadium) glass top on a metal frame with a wooden lower shelf
        r = D / 2
        core = max(W - 2 * r, 0.0)

        def stadium(name, mat, z0, z1, shrink):
            b.prism(name, mat, rounded_rect(D / 2 - shrink, W / 2 - shrink, r - shrink, 8),
                    z0, z1)

        stadium('top', 'glass', H - 0.018, H, 0.0)
        stadium('frame', 'metal', H - 0.04, H - 0.018, 0.02)
        stadium('shelf', 'wood_light', 0.1, 0.125, 0.06)
        for sgn in (-1, 1):
            for xa in (-r * 0.55, r * 0.55):
                b.cyl('leg', 'metal', xa, sgn * (core / 2 + r * 0.3), 0.0, H - 0.04, 0.015, n=10)
    else:
        mat = 'wood_dark'
        b.box('top', mat, x0, x1, y0, y1, H - 0.035, H)
        b.box('panel_leg', mat, x0 + 0.02, x1 - 0.02, y0 + 0.04, y0 + 0.075, 0.0, H - 0.035)
        b.box('panel_leg', mat, x0 + 0.02, x1 - 0.02, y1 - 0.075, y1 - 0.04, 0.0, H - 0.035)
        b.box('shelf', 'wood_light', x0 + 0.03, x1 - 0.03, y0 + 0.075, y1 - 0.075, 0.08, 0.1)
        for k in range(3):
            yc = -0.15 + 0.12 * k
            b.box('magazine', BOOK_COVERS[k], -0.1, 0.12, yc - 0.05, yc + 0.05, 0.1,
                  0.11 + 0.008 * k)
