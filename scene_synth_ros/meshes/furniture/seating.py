"""Builders for seating: office, straight and plain chairs, stools, benches, ottomans, and the
upholstered sofa, sofa chair and armchair (one builder whose proportions depend on the
category).

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import math

import numpy as np

from ..builder import Builder, builds, rot_x, rot_y
from .fittings import legs_box, legs_round


@builds('office chair')
def office_chair(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1 = b.x0, b.x1
    base = b.pick('plastic_black', 'chrome', 'plastic_black')
    fab = b.pick('fabric_dark', 'fabric_blue', 'leather_black')
    r = 0.5 * min(W, D)
    hs = 0.47
    for k in range(5):
        a = math.radians(90 + 72 * k)
        tip = np.array([math.cos(a), math.sin(a)]) * (r - 0.035)
        b.seg('star_arm', base, (0, 0, 0.085), (tip[0], tip[1], 0.07), 0.02, n=8)
        b.sphere('caster', 'rubber', (tip[0], tip[1], 0.03), 0.03)
    b.cyl('hub', base, 0, 0, 0.05, 0.11, 0.05, n=16)
    b.cyl('gas_column', 'plastic_black', 0, 0, 0.1, 0.3, 0.032, n=16)
    b.cyl('gas_column', 'chrome', 0, 0, 0.28, hs - 0.05, 0.022, n=16)
    b.box('mechanism', 'plastic_black', -0.1, 0.1, -0.1, 0.1, hs - 0.07, hs - 0.02)
    arms = s != 2
    sy = W / 2 - (0.075 if arms else 0.03)
    b.box('seat', fab, x0 + 0.07, x1 - 0.02, -sy, sy, hs - 0.02, hs + 0.07)
    b.seg('seat_front', fab, (x1 - 0.045, -sy, hs + 0.025), (x1 - 0.045, sy, hs + 0.025), 0.045,
          n=12)
    zb0 = hs + 0.13
    top = H if s != 2 else H - 0.17
    bw = min(sy * 0.95, 0.25)
    height = top - zb0
    tilt = math.radians(9)
    bx = x0 + 0.035 + height * math.sin(tilt)
    b.obox('backrest', fab, (bx, 0, zb0 + height / 2), (0.07, 2 * bw, height), np.eye(3))
    b.transform_last(1, rot_y(-tilt), pivot=(bx, 0, zb0))
    b.seg('back_spine', 'plastic_black', (x0 + 0.16, 0, hs - 0.04), (bx + 0.02, 0, zb0 + 0.08),
          0.022, n=10)
    if s == 2:
        hz0 = H - 0.14
        hx = x0 + 0.035 + 0.02
        b.box('headrest', fab, hx - 0.03, hx + 0.03, -bw * 0.6, bw * 0.6, hz0, H)
        for yc in (-bw * 0.3, bw * 0.3):
            b.seg('headrest_post', 'chrome', (hx, yc, top - 0.05), (hx, yc, hz0 + 0.02), 0.01,
                  n=8)
    if arms:
        for sgn in (-1, 1):
            yc = sgn * (W / 2 - 0.035)
            b.box('arm_post', 'plastic_black', -0.06, -0.01, yc - 0.014, yc + 0.014, hs,
                  hs + 0.22)
            b.seg('arm_link', 'plastic_black', (-0.035, yc, hs + 0.01), (-0.035, sgn * sy * 0.6,
                                                                          hs - 0.03), 0.012, n=8)
            b.box('arm_pad', 'plastic_black', -0.17, 0.1, yc - 0.035, yc + 0.035, hs + 0.22,
                  hs + 0.25)


@builds('straight chair')
def straight_chair(b: Builder):
    H, s = b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_dark', 'wood_light')
    hs = 0.45
    t = 0.038
    for ya in (y0, y1 - t):
        b.box('back_leg', mat, x0, x0 + t, ya, ya + t, 0.0, H)
        b.box('front_leg', mat, x1 - t, x1, ya, ya + t, 0.0, hs)
    b.box('seat', mat, x0 + 0.005, x1, y0, y1, hs, hs + 0.03)
    if s == 2:
        b.box('seat_pad', 'fabric_red', x0 + t, x1 - 0.02, y0 + 0.02, y1 - 0.02, hs + 0.03,
              hs + 0.055)
    b.box('top_rail', mat, x0 + 0.005, x0 + t - 0.005, y0 + t, y1 - t, H - 0.07, H - 0.01)
    if s == 0:
        for z in np.linspace(hs + 0.15, H - 0.15, 2):
            b.box('back_slat', mat, x0 + 0.01, x0 + t - 0.01, y0 + t, y1 - t, z, z + 0.05)
    elif s == 1:
        n = 4
        for yc in np.linspace(y0 + t, y1 - t, n + 2)[1:-1]:
            b.box('back_slat', mat, x0 + 0.01, x0 + t - 0.01, yc - 0.012, yc + 0.012, hs + 0.03,
                  H - 0.07)
    else:
        b.box('back_pad', 'fabric_red', x0 + t - 0.01, x0 + t + 0.01, y0 + t, y1 - t, hs + 0.17,
              H - 0.09)
    for ya in (y0 + t / 2, y1 - t / 2):
        b.box('stretcher', mat, x0 + t, x1 - t, ya - 0.01, ya + 0.01, 0.14, 0.17)


@builds('chair')
def chair(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    hs = 0.46
    if s == 0:
        # moulded plastic shell on splayed wooden legs
        shell = 'plastic_white'
        for xa, xb in ((x0 + 0.03, x0 + 0.1), (x1 - 0.03, x1 - 0.1)):
            for ya, yb in ((y0 + 0.03, y0 + 0.1), (y1 - 0.03, y1 - 0.1)):
                b.seg('leg', 'wood_light', (xa, ya, 0.0), (xb, yb, hs - 0.04), 0.016, n=8)
        b.box('seat', shell, x0 + 0.06, x1, y0 + 0.02, y1 - 0.02, hs - 0.04, hs)
        b.obox('backrest', shell, (x0 + 0.04, 0, (hs + H) / 2 + 0.02), (0.025, W - 0.04,
                                                                           H - hs - 0.04),
               rot_y(-math.radians(10)))
        b.cyl('seat_rim', shell, 0.0, 0.0, hs - 0.06, hs - 0.04, 0.1, n=12)
    elif s == 1:
        fab = 'fabric_grey_light'
        t = 0.04
        for ya in (y0, y1 - t):
            b.box('back_leg', 'wood_dark', x0, x0 + t, ya, ya + t, 0.0, hs)
            b.box('front_leg', 'wood_dark', x1 - t, x1, ya, ya + t, 0.0, hs)
        b.box('seat', fab, x0, x1, y0, y1, hs - 0.02, hs + 0.06)
        b.box('backrest', fab, x0, x0 + 0.07, y0 + 0.01, y1 - 0.01, hs + 0.06, H)
    else:
        mat = 'wood'
        t = 0.04
        for ya in (y0, y1 - t):
            b.box('back_leg', mat, x0, x0 + t, ya, ya + t, 0.0, H)
            b.box('front_leg', mat, x1 - t - 0.03, x1 - 0.03, ya, ya + t, 0.0, hs + 0.22)
            b.box('arm', mat, x0 + t, x1, ya - 0.0, ya + t, hs + 0.2, hs + 0.235)
        b.box('seat', 'fabric_green', x0 + t, x1 - 0.02, y0 + t, y1 - t, hs - 0.03, hs + 0.04)
        b.box('backrest', 'fabric_green', x0 + 0.01, x0 + 0.05, y0 + t, y1 - t, hs + 0.08,
              H - 0.05)
        b.box('top_rail', mat, x0, x0 + t, y0 + t, y1 - t, H - 0.05, H)


@builds('stool')
def stool(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    mat = b.pick('wood', 'metal_dark', 'wood_light')
    zt = H - 0.04
    if s in (0, 1):
        n = 4 if s == 0 else 3
        for k in range(n):
            a = math.radians(45 + 360 / n * k)
            ca, sa = math.cos(a), math.sin(a)
            rt, rb = R * 0.55, R - 0.02
            b.seg('leg', mat, (rb * ca, rb * sa, 0.0), (rt * ca, rt * sa, zt), 0.017, n=8)
            zf = 0.22 * H
            rf = rb - (rb - rt) * (zf / zt)
            a2 = math.radians(45 + 360 / n * (k + 1))
            b.seg('footrest', mat, (rf * ca, rf * sa, zf), (rf * math.cos(a2), rf * math.sin(a2),
                                                            zf), 0.01, n=6)
        b.cyl('seat', b.pick('wood', 'leather_black', 'wood'), 0, 0, zt, H, R, n=24)
        if s == 1:
            b.cyl('seat_ring', 'metal_dark', 0, 0, zt - 0.02, zt, R * 0.6, n=16)
    else:
        x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
        b.box('seat', mat, x0, x1, y0, y1, zt, H)
        legs_box(b, mat, x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, zt, t=0.035)
        for z in (0.18 * H,):
            b.box('stretcher', mat, x0 + 0.03, x1 - 0.03, y0 + 0.03, y0 + 0.045, z, z + 0.02)
            b.box('stretcher', mat, x0 + 0.03, x1 - 0.03, y1 - 0.045, y1 - 0.03, z, z + 0.02)
            b.box('stretcher', mat, x0 + 0.03, x0 + 0.045, y0 + 0.03, y1 - 0.03, z + 0.04,
                  z + 0.06)
            b.box('stretcher', mat, x1 - 0.045, x1 - 0.03, y0 + 0.03, y1 - 0.03, z + 0.04,
                  z + 0.06)


@builds('bench chair')
def bench_chair(b: Builder):
    D, H, s = b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    if s == 0:
        mat = 'wood'
        b.box('seat', mat, x0, x1, y0, y1, H - 0.05, H)
        legs_box(b, mat, x0 + 0.03, x1 - 0.03, y0 + 0.05, y1 - 0.05, 0.0, H - 0.05, t=0.05)
        b.box('stretcher', mat, -0.015, 0.015, y0 + 0.1, y1 - 0.1, 0.12, 0.16)
    elif s == 1:
        b.box('frame', 'wood_dark', x0, x1, y0, y1, H - 0.13, H - 0.08)
        b.box('cushion', 'fabric_mustard', x0 + 0.005, x1 - 0.005, y0 + 0.005, y1 - 0.005,
              H - 0.08, H)
        legs_round(b, 'metal_dark', x0 + 0.02, x1 - 0.02, y0 + 0.03, y1 - 0.03, 0.0, H - 0.13,
                    r=0.015, n=8)
    else:
        mat = 'wood_light'
        for ya in (y0, y1 - 0.05):
            b.box('panel_leg', 'metal_dark', x0 + 0.02, x1 - 0.02, ya, ya + 0.05, 0.0, H - 0.04)
        n = 4
        sw = D / n
        for k in range(n):
            b.box('slat', mat, x0 + k * sw + 0.006, x0 + (k + 1) * sw - 0.006, y0, y1, H - 0.04, H)


@builds('ottoman')
def ottoman(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    fab = b.pick('fabric_blue', 'fabric_mustard', 'leather')
    if s == 0:
        legs_round(b, 'wood_dark', x0 + 0.03, x1 - 0.03, y0 + 0.03, y1 - 0.03, 0.0, 0.07,
                    r=0.018, taper=0.6, n=8)
        b.box('body', fab, x0 + 0.01, x1 - 0.01, y0 + 0.01, y1 - 0.01, 0.06, H - 0.08)
        b.box('cushion', fab, x0, x1, y0, y1, H - 0.08, H)
        nx, ny = 2, max(2, int(round(W / 0.25)))
        for i in range(nx):
            for j in range(ny):
                xc = x0 + D * (i + 0.5) / nx
                yc = y0 + W * (j + 0.5) / ny
                b.sphere('button', 'fabric_dark', (xc, yc, H - 0.012), 0.01, subdiv=0)
    elif s == 1:
        ey = W / D
        r = D / 2
        b.cyl('base', 'fabric_dark', 0, 0, 0.0, 0.04, r - 0.01, (r - 0.01) * ey, n=24)
        b.cyl('body', fab, 0, 0, 0.04, H - 0.05, r, r * ey, n=24)
        b.cyl('top', 'fabric_beige', 0, 0, H - 0.05, H, r - 0.01, (r - 0.01) * ey, n=24)
    else:
        b.box('plinth', 'wood_dark', x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, 0.05)
        b.box('body', fab, x0 + 0.008, x1 - 0.008, y0 + 0.008, y1 - 0.008, 0.05, H - 0.07)
        b.box('lid', fab, x0, x1, y0, y1, H - 0.07, H)
        b.box('seam', 'wood_dark', x0 + 0.004, x1 - 0.004, y0 + 0.004, y1 - 0.004, H - 0.08,
              H - 0.07)


@builds('sofa', 'sofa chair', 'armchair')
def upholstered(b: Builder):
    kind = b.category
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    if kind == 'sofa':
        fab = b.pick('fabric_grey', 'fabric_beige', 'fabric_blue')
        arm_w = b.pick(0.17, 0.2, 0.12)
        leg = b.pick(0.1, 0.02, 0.14)
        arm_style = b.pick('box', 'roll', 'box')
    elif kind == 'sofa chair':
        fab = b.pick('fabric_beige', 'leather', 'fabric_green')
        arm_w = b.pick(0.19, 0.2, 0.15)
        leg = b.pick(0.03, 0.1, 0.07)
        arm_style = b.pick('box', 'roll', 'box')
    else:  # armchair
        fab = b.pick('fabric_red', 'fabric_green', 'fabric_blue')
        arm_w = b.pick(0.1, 0.13, 0.1)
        leg = 0.15
        arm_style = b.pick('wood', 'wing', 'wood')
    cushion = fab
    back_t = min(0.2, 0.22 * D)
    sz = leg + 0.17
    sc = sz + 0.14
    ha = min(sc + 0.2, H - 0.1)
    # legs or skirt
    legmat = b.pick('wood_dark', 'wood', 'metal')
    if leg < 0.05:
        b.box('skirt', 'wood_dark', x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, leg)
    else:
        nl = 3 if W > 2.2 else 2
        for xa in (x0 + 0.04, x1 - 0.04):
            for ya in np.linspace(y0 + 0.05, y1 - 0.05, nl):
                if kind == 'armchair' and arm_style == 'wood':
                    b.frustum('leg', 'wood', xa, ya, 0.0, leg + 0.01, 0.012, 0.022, n=8)
                else:
                    b.cyl('leg', legmat, xa, ya, 0.0, leg + 0.01, 0.022, n=8)
    # back and arms
    b.box('back', fab, x0, x0 + back_t, y0, y1, leg, H)
    inner0, inner1 = y0 + arm_w, y1 - arm_w
    b.box('base', fab, x0 + back_t - 0.02, x1, inner0, inner1, leg, sz)
    for ya, yb in ((y0, y0 + arm_w), (y1 - arm_w, y1)):
        yc = (ya + yb) / 2
        if arm_style == 'roll':
            rr = arm_w / 2
            b.box('arm', fab, x0, x1, ya, yb, leg, ha - rr)
            b.seg('arm_roll', fab, (x0 + 0.02, yc, ha - rr), (x1, yc, ha - rr), rr, n=16)
        elif arm_style == 'wood':
            b.box('arm', fab, x0, x1 - 0.08, ya + 0.01, yb - 0.01, leg, ha - 0.03)
            b.box('arm_post', 'wood', x1 - 0.06, x1 - 0.02, yc - 0.02, yc + 0.02, leg, ha - 0.03)
            b.box('arm_cap', 'wood', x0 + back_t, x1, ya, yb, ha - 0.03, ha)
        else:
            b.box('arm', fab, x0, x1, ya, yb, leg, ha)
            if arm_style == 'wing':
                b.box('wing', fab, x0, x0 + back_t + 0.16, ya, yb, ha, H - 0.1)
    # cushions
    n = 1 if kind != 'sofa' else (3 if inner1 - inner0 > 1.7 else 2)
    cw = (inner1 - inner0) / n
    for k in range(n):
        ya, yb = inner0 + k * cw + 0.005, inner0 + (k + 1) * cw - 0.005
        b.box('seat_cushion', cushion, x0 + back_t, x1 - 0.005, ya, yb, sz, sc)
        b.box('back_cushion', cushion, x0 + back_t, x0 + back_t + 0.14, ya, yb, sc,
              min(H - 0.05, sc + 0.45))
    if kind == 'sofa' and s != 2:
        acc = b.pick('fabric_mustard', 'fabric_blue', 'fabric_red')
        for sgn in (-1, 1):
            yc = sgn * (W / 2 - arm_w - 0.2)
            b.box('throw_pillow', acc, -0.05, 0.05, -0.2, 0.2, -0.19, 0.19)
            b.transform_last(1, rot_y(-0.3) @ rot_x(-0.2 * sgn),
                             shift=(x0 + back_t + 0.14, yc, sc + 0.2))
