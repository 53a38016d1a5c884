"""Builders for case furniture, carcasses with doors, drawers or shelves: wardrobes, night
stands, dressers, dressing tables, TV stands, shelving, shoe cabinets and cabinets.

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import math

import numpy as np

from ..builder import Builder, builds, rot_z
from ..materials import BOOK_COVERS
from .fittings import FRONT, HANDLE, door, drawer, legs_box, legs_round


@builds('wardrobe')
def wardrobe(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'wood_dark')
    front = b.pick('wood_light', 'wood_white', 'wood_dark')
    hmat = b.pick('metal', 'chrome', 'brass')
    xf = x1
    plinth = 0.08
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, plinth, H - 0.04)
    b.box('cornice', mat, x0, xf - HANDLE, y0, y1, H - 0.04, H)
    if s == 1:
        legs_round(b, 'metal', x0 + 0.03, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, plinth, r=0.02)
        b.box('bottom', mat, x0, xf - HANDLE - FRONT, y0, y1, plinth, plinth + 0.03)
    else:
        b.box('plinth', 'wood_dark' if s == 0 else 'shadow', x0, xf - 0.05, y0 + 0.02, y1 - 0.02,
              0.0, plinth)
    n = 2 if W < 1.2 else (3 if W < 1.8 else 4)
    z_doors = plinth + 0.005
    if s == 0 and H > 2.0:
        z_doors = plinth + 0.28
        for k in range(2):
            drawer(b, front, hmat, y0 + k * W / 2, y0 + (k + 1) * W / 2, plinth, z_doors, xf)
    if s == 2:
        # sliding doors: two wide panels at two depths, recessed pull strips at the edges
        b.box('door', front, xf - HANDLE - FRONT - 0.012, xf - HANDLE - 0.012, y0 + 0.004,
              0.04, z_doors, H - 0.045)
        b.box('door', 'mirror', xf - HANDLE - FRONT, xf - HANDLE, -0.04, y1 - 0.004, z_doors,
              H - 0.045)
        for yh in (y0 + 0.05, y1 - 0.05):
            b.box('handle', hmat, xf - HANDLE, xf, yh - 0.01, yh + 0.01, z_doors + 0.3,
                  H - 0.4)
        return
    dw = W / n
    for k in range(n):
        ya, yb = y0 + k * dw, y0 + (k + 1) * dw
        side = +1 if k % 2 == 0 else -1
        door_mat = 'mirror' if (s == 1 and n >= 3 and k == n // 2) else front
        door(b, door_mat, hmat, ya, yb, z_doors, H - 0.045, xf, handle_side=side,
              handle_len=0.35)


@builds('stand')
def stand(b: Builder):
    H, s = b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_light', 'wood_white', 'wood_dark')
    hmat = b.pick('brass', 'chrome', 'metal')
    xf = x1
    base = 0.14 if s == 0 else 0.04
    top = 0.025
    if s == 0:
        legs_round(b, mat, x0 + 0.02, xf - HANDLE - 0.02, y0 + 0.02, y1 - 0.02, 0.0, base + 0.01,
                    r=0.018, taper=0.6, n=8)
    else:
        b.box('plinth', 'shadow', x0 + 0.02, xf - 0.05, y0 + 0.02, y1 - 0.02, 0.0, base)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, base, H - top)
    b.box('top', mat, x0, xf - HANDLE + 0.002, y0, y1, H - top, H)
    zs = H - top
    if s == 1:
        dh = min(0.16, (zs - base) * 0.4)
        drawer(b, mat, hmat, y0, y1, zs - dh, zs, xf, handle='knob')
        b.box('niche', 'shadow', xf - HANDLE - FRONT - 0.003, xf - HANDLE - FRONT + 0.002,
              y0 + 0.025, y1 - 0.025, base + 0.025, zs - dh - 0.02)
    else:
        n = 2 if s == 0 else 3
        dh = (zs - base) / n
        for k in range(n):
            drawer(b, mat, hmat, y0, y1, base + k * dh, base + (k + 1) * dh, xf,
                    handle='knob' if s == 0 else 'bar')


@builds('dresser')
def dresser(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'wood_dark')
    front = b.pick('wood_light', 'paint_cream', 'wood')
    hmat = b.pick('metal', 'brass', 'brass')
    xf = x1
    base = 0.09 if s != 1 else 0.13
    if s == 1:
        legs_round(b, 'wood_dark', x0 + 0.03, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, base + 0.01,
                    r=0.02, taper=0.6, n=8)
    else:
        b.box('plinth', mat, x0 + 0.01, xf - HANDLE - FRONT - 0.01, y0 + 0.02, y1 - 0.02, 0.0,
              base)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, base, H - 0.03)
    b.box('top', mat, x0, xf - HANDLE + 0.004, y0 - 0.0, y1, H - 0.03, H)
    zs = H - 0.03
    rows = int(min(5, max(3, round((zs - base) / 0.2))))
    cols = 2 if W >= 1.1 else 1
    dh = (zs - base) / rows
    for r in range(rows):
        za, zb = base + r * dh, base + (r + 1) * dh
        c = cols if not (s == 2 and r == rows - 1) else cols + 1
        for k in range(c):
            drawer(b, front, hmat, y0 + k * W / c, y0 + (k + 1) * W / c, za, zb, xf,
                    handle='knobs' if (s == 1 and c == 1) else ('knob' if s == 1 else 'bar'))


@builds('dressing table')
def dressing_table(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood_light', 'wood_dark')
    hmat = b.pick('brass', 'chrome', 'brass')
    th = 0.76
    xf = x1
    b.box('top', mat, x0, xf - HANDLE + 0.004, y0, y1, th - 0.03, th)
    if s == 2:
        pw = min(0.38, W * 0.3)
        for ya, yb in ((y0, y0 + pw), (y1 - pw, y1)):
            b.box('pedestal', mat, x0, xf - HANDLE - FRONT, ya, yb, 0.0, th - 0.03)
            for k in range(3):
                dh = (th - 0.05) / 3
                drawer(b, mat, hmat, ya, yb, 0.02 + k * dh, 0.02 + (k + 1) * dh, xf, 'knob')
    else:
        if s == 0:
            legs_round(b, mat, x0 + 0.02, xf - HANDLE - 0.02, y0 + 0.02, y1 - 0.02, 0.0,
                        th - 0.03, r=0.022, taper=0.55, n=10)
        else:
            legs_box(b, mat, x0 + 0.01, xf - HANDLE - 0.01, y0 + 0.01, y1 - 0.01, 0.0, th - 0.03,
                      t=0.04)
        b.box('apron', mat, x0 + 0.02, xf - HANDLE - FRONT, y0 + 0.03, y1 - 0.03, th - 0.15,
              th - 0.03)
        drawer(b, mat, hmat, -W * 0.3, W * 0.3, th - 0.15, th - 0.03, xf, 'knob')
    # mirror at the back
    zm0, zm1 = th + 0.02, H
    mw = min(W * 0.62, 0.8)
    if s == 0:
        rz, ry = (zm1 - zm0) / 2, mw / 2
        zc = (zm0 + zm1) / 2
        b.xdisc('mirror_frame', mat, x0, x0 + 0.03, 0.0, zc, ry, rz, n=28)
        b.xdisc('mirror', 'mirror', x0 + 0.03, x0 + 0.036, 0.0, zc, ry - 0.035, rz - 0.035, n=28)
        for ya in (-ry * 0.5, ry * 0.5):
            b.box('mirror_post', mat, x0, x0 + 0.03, ya - 0.015, ya + 0.015, th, zc - rz + 0.06)
    elif s == 1:
        b.box('mirror_frame', mat, x0, x0 + 0.03, -mw / 2, mw / 2, zm0, zm1)
        b.box('mirror', 'mirror', x0 + 0.03, x0 + 0.036, -mw / 2 + 0.035, mw / 2 - 0.035,
              zm0 + 0.035, zm1 - 0.035)
    else:
        cw = mw * 0.7
        b.box('mirror_frame', mat, x0, x0 + 0.03, -cw / 2, cw / 2, zm0, zm1)
        b.box('mirror', 'mirror', x0 + 0.03, x0 + 0.036, -cw / 2 + 0.03, cw / 2 - 0.03,
              zm0 + 0.03, zm1 - 0.03)
        sw = cw * 0.45
        for sgn in (-1, 1):
            ang = sgn * math.radians(28)
            yc = sgn * (cw / 2 + sw / 2 * math.cos(ang))
            xc = x0 + 0.015 + sw / 2 * abs(math.sin(ang))
            zc = (zm0 + zm1 - 0.1) / 2
            b.obox('mirror_wing', mat, (xc, yc, zc), (0.025, sw, zm1 - zm0 - 0.1), rot_z(-ang))
            b.obox('mirror', 'mirror', (xc + 0.014 * math.cos(ang), yc - 0.014 * math.sin(ang),
                                        zc), (0.006, sw - 0.05, zm1 - zm0 - 0.16), rot_z(-ang))


@builds('tv stand')
def tv_stand(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood', 'wood_dark')
    front = b.pick('wood_light', 'wood', 'paint_grey')
    hmat = b.pick('metal', 'metal_dark', 'chrome')
    xf = x1
    base = b.pick(0.12, 0.04, 0.16)
    if s == 1:
        b.box('plinth', 'shadow', x0 + 0.02, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, base)
    else:
        legs_round(b, b.pick('metal', '', 'wood_dark'), x0 + 0.03, xf - 0.05, y0 + 0.04,
                    y1 - 0.04, 0.0, base + 0.01, r=0.018, taper=0.6 if s == 2 else 1.0, n=8)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, base, H - 0.025)
    b.box('top', mat, x0, xf - HANDLE + 0.002, y0, y1, H - 0.025, H)
    zs = H - 0.025
    if s == 0:
        dw = W * 0.3
        drawer(b, front, hmat, y0, y0 + dw, base, zs, xf, 'top')
        drawer(b, front, hmat, y1 - dw, y1, base, zs, xf, 'top')
        b.box('niche', 'shadow', xf - HANDLE - FRONT - 0.003, xf - HANDLE - FRONT + 0.002,
              y0 + dw + 0.02, y1 - dw - 0.02, base + 0.02, zs - 0.02)
    elif s == 1:
        n = 3 if W > 1.3 else 2
        for k in range(n):
            door(b, front, hmat, y0 + k * W / n, y0 + (k + 1) * W / n, base, zs, xf,
                  handle_side=-1 if k % 2 else 1, handle_len=0.12)
    else:
        dh = (zs - base) * 0.35
        for k in range(2):
            drawer(b, front, hmat, y0 + k * W / 2, y0 + (k + 1) * W / 2, zs - dh, zs, xf, 'bar')
        for k in range(2):
            b.box('niche', 'shadow', xf - HANDLE - FRONT - 0.003, xf - HANDLE - FRONT + 0.002,
                  y0 + k * W / 2 + 0.025, y0 + (k + 1) * W / 2 - 0.025, base + 0.02,
                  zs - dh - 0.015)


@builds('shelving')
def shelving(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_light', 'wood_white', 'wood_dark')
    t = 0.025
    b.box('side', mat, x0, x1, y0, y0 + t, 0.0, H)
    b.box('side', mat, x0, x1, y1 - t, y1, 0.0, H)
    if s != 1:
        b.box('back', mat if s == 0 else 'paint_grey', x0, x0 + 0.008, y0 + t, y1 - t, 0.0, H)
    b.box('plinth', mat, x1 - 0.03, x1 - 0.01, y0 + t, y1 - t, 0.0, 0.06)
    n = max(2, int(round((H - 0.06) / 0.36)))
    levels = np.linspace(0.06, H - t, n + 1)
    for z in levels:
        b.box('shelf', mat, x0 + 0.008, x1 - 0.005, y0 + t, y1 - t, z, z + t)
    if s == 1 and W > 1.0:
        b.box('divider', mat, x0 + 0.008, x1 - 0.005, -t / 2, t / 2, 0.06, H - t)
    # books on some shelves, standing upright against the back
    books = 0
    for i, z in enumerate(levels[:-1]):
        if (i + s) % 2 == 1 or books > 60:
            continue
        gap = levels[i + 1] - z - t
        y = y0 + t + 0.02
        fill_end = y1 - t - (W - 2 * t) * b.rng.uniform(0.3, 0.55)
        while y < fill_end and books <= 60:
            bt = b.rng.uniform(0.02, 0.045)
            bh = min(gap - 0.03, b.rng.uniform(0.17, 0.26))
            bd = min(D - 0.04, b.rng.uniform(0.15, 0.22))
            cover = BOOK_COVERS[int(b.rng.integers(len(BOOK_COVERS)))]
            b.box('book', cover, x0 + 0.01, x0 + 0.01 + bd, y, y + bt, z + t, z + t + bh)
            y += bt + 0.002
            books += 1


@builds('shoes cabinet')
def shoes_cabinet(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood_light', 'wood')
    hmat = b.pick('chrome', 'metal_dark', 'metal')
    xf = x1
    if s == 2:
        t = 0.02
        b.box('side', mat, x0, x1, y0, y0 + t, 0.0, H)
        b.box('side', mat, x0, x1, y1 - t, y1, 0.0, H)
        b.box('top', mat, x0, x1, y0, y1, H - t, H)
        b.box('back', mat, x0, x0 + 0.008, y0 + t, y1 - t, 0.0, H)
        n = 3
        for i in range(n):
            z = 0.04 + i * (H - 0.06) / n
            b.box('shelf', mat, x0 + 0.008, x1, y0 + t, y1 - t, z, z + 0.018)
            pairs = max(1, int((W - 2 * t) / 0.26))
            pw = (W - 2 * t) / pairs
            for k in range(pairs):
                shoe = BOOK_COVERS[(k + i * 2) % len(BOOK_COVERS)]
                for dy in (-0.045, 0.045):
                    yc = y0 + t + pw * (k + 0.5) + dy
                    b.sphere('shoe', shoe, (0.0, yc, z + 0.018 + 0.045),
                             (min(0.13, D / 2 - 0.02), 0.04, 0.045))
        return
    leg = 0.1 if s == 1 else 0.0
    if s == 1:
        legs_round(b, 'metal_dark', x0 + 0.02, xf - 0.04, y0 + 0.02, y1 - 0.02, 0.0, leg + 0.01,
                    r=0.012, n=8)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, leg, H - 0.02)
    b.box('top', mat, x0, xf - HANDLE + 0.002, y0, y1, H - 0.02, H)
    rows = 2 if H < 1.0 else 3
    cols = 2 if (s == 1 and W > 0.8) else 1
    zs = H - 0.02
    dh = (zs - leg) / rows
    for r in range(rows):
        for c in range(cols):
            drawer(b, mat, hmat, y0 + c * W / cols, y0 + (c + 1) * W / cols, leg + r * dh,
                    leg + (r + 1) * dh, xf, 'top')


@builds('cabinet')
def cabinet(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood_light', 'paint_grey')
    hmat = b.pick('chrome', 'metal_dark', 'chrome')
    xf = x1
    base = 0.08
    if s == 1:
        legs_round(b, 'metal', x0 + 0.02, xf - 0.04, y0 + 0.02, y1 - 0.02, 0.0, base + 0.01,
                    r=0.014, n=8)
    else:
        b.box('plinth', 'shadow', x0 + 0.02, xf - 0.05, y0 + 0.02, y1 - 0.02, 0.0, base)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, base, H - 0.02)
    b.box('top', mat, x0, xf - HANDLE + 0.002, y0, y1, H - 0.02, H)
    zs = H - 0.02
    ncol = 1 if W < 0.45 else 2

    def doors(za, zb, glass=False):
        for k in range(ncol):
            ya, yb = y0 + k * W / ncol, y0 + (k + 1) * W / ncol
            side = -1 if (ncol == 2 and k == 1) else 1
            door(b, 'glass' if glass else mat, hmat, ya, yb, za, zb, xf,
                  handle_side=-side if ncol == 2 else 1, handle_len=min(0.2, (zb - za) * 0.3))

    if s == 2 and H > 1.1:
        niche = 0.3
        zm = base + (zs - base) * 0.45
        doors(base, zm)
        b.box('niche', 'shadow', xf - HANDLE - FRONT - 0.003, xf - HANDLE - FRONT + 0.002,
              y0 + 0.02, y1 - 0.02, zm + 0.015, zm + niche)
        b.box('shelf', mat, x0, xf - HANDLE - FRONT + 0.004, y0, y1, zm, zm + 0.018)
        doors(zm + niche + 0.005, zs)
    elif s == 1 and H > 1.2:
        zm = base + (zs - base) * 0.5
        doors(base, zm)
        doors(zm, zs, glass=True)
    else:
        doors(base, zs)
