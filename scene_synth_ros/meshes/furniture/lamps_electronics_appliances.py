"""Builders for lamps, electronics and appliances: floor and table lamps, loudspeakers,
pedestal fans, televisions, laptops, game consoles, washing machines and water dispensers.

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import math

from ..builder import Builder, builds, rot_x, rot_y, rot_z
from .fittings import legs_box


@builds('floor lamp')
def floor_lamp(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    pole = b.pick('metal', 'wood', 'metal_dark')
    if s == 1:
        zt = H - 0.3
        for k in range(3):
            a = math.radians(90 + 120 * k)
            b.seg('leg', pole, (R * 0.9 * math.cos(a), R * 0.9 * math.sin(a), 0.0),
                  (0.0, 0.0, zt * 0.75), 0.014, n=8)
        b.seg('pole', pole, (0, 0, zt * 0.7), (0, 0, H - 0.15), 0.012, n=8)
        b.frustum('shade', 'shade', 0, 0, H - 0.34, H, R * 0.95, R * 0.95, n=24)
    elif s == 2:
        b.cyl('base', pole, 0, 0, 0.0, 0.03, R * 0.6, n=24)
        b.cyl('pole', pole, 0, 0, 0.03, H - 0.12, 0.013, n=10)
        b.frustum('shade', 'shade', 0, 0, H - 0.16, H, R * 0.25, R, n=24)
        b.sphere('bulb', 'bulb', (0, 0, H - 0.14), R * 0.18)
    else:
        b.cyl('base', 'metal_dark', 0, 0, 0.0, 0.035, R * 0.7, n=24)
        b.cyl('pole', pole, 0, 0, 0.035, H - 0.2, 0.012, n=10)
        b.frustum('shade', 'shade', 0, 0, H - 0.36, H, R, R * 0.72, n=24)
        b.cyl('switch', 'plastic_black', 0, 0, 0.8, 0.86, 0.02, n=10)


@builds('table lamp')
def table_lamp(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    zs = 0.48 * H
    if s == 0:
        rb = R * 0.45
        b.lathe('base', 'teal', [(0, 0), (rb * 0.6, 0), (rb, zs * 0.35), (rb * 0.9, zs * 0.7),
                                 (rb * 0.35, zs * 0.9), (0.0, zs * 0.9)], n=20)
        b.cyl('stem', 'brass', 0, 0, zs * 0.88, zs + 0.12 * H, 0.01, n=8)
        b.frustum('shade', 'shade', 0, 0, zs, H, R, R * 0.62, n=24)
    elif s == 1:
        b.cyl('base', 'metal', 0, 0, 0.0, 0.02, R * 0.5, n=20)
        b.cyl('stem', 'metal', 0, 0, 0.02, zs + 0.1 * H, 0.009, n=8)
        b.frustum('shade', 'fabric_grey_light', 0, 0, zs, H, R, R, n=24)
        b.sphere('finial', 'metal', (0, 0, zs + 0.08 * H), 0.015)
    else:
        bw = R * 0.7
        b.box('base', 'wood_light', -bw / 2, bw / 2, -bw / 2, bw / 2, 0.0, zs * 0.6)
        b.cyl('stem', 'metal_dark', 0, 0, zs * 0.6, zs + 0.1 * H, 0.01, n=8)
        b.frustum('shade', 'shade', 0, 0, zs, H, R, R * 0.35, n=24)


@builds('loudspeaker')
def loudspeaker(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('plastic_black', 'wood_dark', 'wood_white')
    xf = x1 - 0.012
    base = 0.04
    if s == 0:
        for xa in (x0 + 0.03, xf - 0.03):
            for ya in (y0 + 0.03, y1 - 0.03):
                b.frustum('spike', 'metal', xa, ya, 0.0, base, 0.004, 0.015, n=8)
    else:
        b.box('plinth', 'plastic_black', x0, xf, y0, y1, 0.0, base)
    b.box('cabinet', mat, x0, xf - (0.004 if s == 2 else 0.0), y0 + (0.0 if s else 0.005),
          y1 - (0.0 if s else 0.005), base, H)
    if s == 2:
        b.box('baffle', 'fabric_dark', xf - 0.004, xf, y0 + 0.01, y1 - 0.01, base + 0.04, H - 0.03)
    rw = min(W * 0.36, 0.1)
    rt = min(W * 0.13, 0.03)
    zt = H - 0.08
    b.xdisc('tweeter', 'rubber', xf, x1, 0.0, zt, rt, n=16)
    b.sphere('tweeter_dome', 'metal', (xf + 0.004, 0.0, zt), (0.008, rt * 0.6, rt * 0.6))
    nw = 2 if H > 0.9 else 1
    for k in range(nw):
        zc = zt - rt - 0.04 - rw - k * (2 * rw + 0.04)
        b.xdisc('woofer_surround', 'rubber', xf, x1, 0.0, zc, rw, n=20)
        b.xdisc('woofer_cone', 'metal_dark', xf + 0.001, x1 + 0.001, 0.0, zc, rw * 0.75, n=20)
        b.xdisc('woofer_cap', 'metal', xf + 0.002, x1 + 0.002, 0.0, zc, rw * 0.25, n=12)
    b.xdisc('port', 'shadow', xf, x1, 0.0, base + 0.08, 0.025, n=12)


@builds('pedestal fan')
def pedestal_fan(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1 = b.x0, b.x1
    body = b.pick('plastic_white', 'plastic_black', 'metal')
    R = W / 2
    zc = H - R
    rb = min(W, D) / 2
    if s == 0:
        b.cyl('base', body, 0, 0, 0.0, 0.04, rb, n=24)
    elif s == 1:
        b.box('foot', body, x0, x1, -0.03, 0.03, 0.0, 0.04)
        b.box('foot', body, -0.03, 0.03, -rb, rb, 0.0, 0.04)
    else:
        b.box('base', body, -rb * 0.8, rb * 0.8, -rb * 0.8, rb * 0.8, 0.0, 0.04)
    xm = -0.05
    b.cyl('pole', 'chrome', xm, 0, 0.03, zc - 0.6 * R, 0.016, n=10)
    b.cyl('pole', body, xm, 0, zc - 0.65 * R, zc - 0.06, 0.011, n=10)
    b.seg('motor', body, (xm - 0.12, 0, zc), (0.01, 0, zc), 0.075, n=16)
    b.xdisc('hub', body, 0.01, 0.05, 0.0, zc, 0.035, n=12)
    for k in range(3):
        a = math.radians(90 + 120 * k)
        rr = R * 0.5
        b.obox('blade', b.pick('glass', 'plastic_grey', 'glass'), (0.03, rr * math.cos(a),
                                                                    zc + rr * math.sin(a)),
               (0.006, R * 0.32, R * 0.78), rot_x(a - math.pi / 2) @ rot_z(0.25))
    b.ring('guard', 'plastic_grey', 0.0, 0.0, 0.0, 0.016, R - 0.016, R, n=28)
    b.transform_last(1, rot_y(math.pi / 2), shift=(0.03, 0.0, zc))
    b.xdisc('grille', 'glass', 0.07, 0.074, 0.0, zc, R - 0.02, n=28)
    b.xdisc('badge', body, 0.074, 0.08, 0.0, zc, 0.04, n=12)
    for k in range(2):
        a = math.radians(45 + 90 * k)
        b.seg('guard_wire', 'plastic_grey', (0.074, (R - 0.02) * math.cos(a),
                                            zc + (R - 0.02) * math.sin(a)),
              (0.074, -(R - 0.02) * math.cos(a), zc - (R - 0.02) * math.sin(a)), 0.004, n=6)


@builds('television')
def television(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    fh = b.pick(0.08, 0.1, 0.09)
    pt0, pt1 = -0.035, 0.02
    if s == 0:
        b.box('foot', 'metal_dark', x0, x1, -0.2 * W, 0.2 * W, 0.0, 0.018)
        b.box('neck', 'metal_dark', pt0 - 0.01, pt0 + 0.02, -0.05, 0.05, 0.018, fh + 0.1)
    elif s == 1:
        for sgn in (-1, 1):
            yc = sgn * 0.38 * W
            b.box('foot', 'plastic_black', x0, x1, yc - 0.02, yc + 0.02, 0.0, 0.015)
            b.box('foot_post', 'plastic_black', -0.02, 0.02, yc - 0.02, yc + 0.02, 0.015, fh + 0.05)
    else:
        r = D / 2
        b.cyl('foot', 'metal', 0, 0, 0.0, 0.016, r, r * 1.6, n=24)
        b.box('neck', 'metal', pt0 - 0.02, pt0, -0.03, 0.03, 0.016, fh + 0.12)
        b.box('back_cover', 'plastic_black', pt0 - 0.045, pt0, -0.3 * W, 0.3 * W, fh + 0.08,
              H - 0.08)
    b.box('panel', 'plastic_black', pt0, pt1, y0, y1, fh, H)
    b.box('screen', b.pick('screen', 'screen', 'screen_on'), pt1, pt1 + 0.004, y0 + 0.012,
          y1 - 0.012, fh + 0.03, H - 0.012)
    b.box('logo', 'metal', pt1, pt1 + 0.005, -0.03, 0.03, fh + 0.008, fh + 0.02)


@builds('laptop')
def laptop(b: Builder):
    D, H, s = b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    shell = b.pick('metal', 'plastic_black', 'plastic_grey')
    tb = 0.018
    h = H - tb
    a = max(0.0, (D * D - h * h) / (2 * D))
    length = math.hypot(a, h)
    xh = x0 + a
    b.box('base', shell, xh, x1, y0, y1, 0.0, tb)
    b.box('keyboard', 'plastic_black' if s != 1 else 'plastic_grey', xh + 0.02, x1 - 0.085,
          y0 + 0.02, y1 - 0.02, tb - 0.001, tb + 0.0015)
    b.box('trackpad', 'plastic_grey' if s != 2 else 'metal', x1 - 0.075, x1 - 0.015, -0.05, 0.05,
          tb - 0.001, tb + 0.001)
    tilt = math.atan2(a, h)
    t = 0.007
    b.box('lid', shell, -t, 0.0, y0, y1, 0.0, length)
    b.box('screen', 'screen_on' if s == 0 else 'screen', 0.0, 0.0015, y0 + 0.012, y1 - 0.012,
          0.012, length - 0.012)
    n = 2
    if s == 2:
        # a logo on the back of the lid and a webcam above the screen
        b.box('logo', 'plastic_white', -t - 0.001, -t, -0.02, 0.02, length * 0.5 - 0.02,
              length * 0.5 + 0.02)
        b.box('webcam', 'plastic_black', 0.0, 0.0015, -0.004, 0.004, length - 0.009,
              length - 0.003)
        n = 4
    b.transform_last(n, rot_y(-tilt), shift=(xh, 0.0, tb * 0.6))
    if s == 1:
        b.seg('hinge', 'plastic_black', (xh + 0.004, y0 + 0.03, tb * 0.6),
              (xh + 0.004, y1 - 0.03, tb * 0.6), 0.006, n=10)



@builds('console')
def console(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_black', 'plastic_white', 'plastic_grey')
    feet = 0.008
    legs_box(b, 'rubber', x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, feet, t=0.02)
    b.box('body', body, x0, x1 - 0.004, y0, y1, feet, H - 0.002)
    b.box('top_panel', b.pick('plastic_grey', 'plastic_black', 'plastic_black'), x0 + 0.02,
          x1 - 0.03, y0 + 0.02, y1 - 0.1, H - 0.003, H)
    b.box('disc_slot', 'shadow', x1 - 0.004, x1, y0 + 0.04, y0 + 0.04 + W * 0.45,
          feet + (H - feet) * 0.5, feet + (H - feet) * 0.5 + 0.005)
    b.box('power_light', 'screen_on', x1 - 0.004, x1, y1 - 0.04, y1 - 0.025, feet + 0.01,
          feet + 0.016)
    if s == 1:
        b.box('light_bar', 'screen_on', x1 - 0.004, x1, y0 + 0.02, y1 - 0.06, H - 0.012,
              H - 0.008)
    elif s == 2:
        b.box('vent', 'shadow', x0 + 0.02, x1 - 0.03, y1 - 0.08, y1 - 0.02, H - 0.003, H)


@builds('washer')
def washer(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_white', 'plastic_white', 'metal')
    xf = x1 - 0.012
    legs_box(b, 'plastic_grey', x0 + 0.03, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, 0.02, t=0.04)
    b.box('body', body, x0, xf, y0, y1, 0.02, H - (0.012 if s == 2 else 0.0))
    b.box('control_panel', 'plastic_grey' if s != 2 else 'plastic_black', xf, xf + 0.005,
          y0 + 0.01, y1 - 0.01, H - 0.12, H - 0.015)
    b.box('detergent_drawer', body, xf + 0.005, x1 - 0.003, y0 + 0.03, y0 + 0.2, H - 0.1,
          H - 0.035)
    b.box('display', 'screen_on', xf + 0.005, xf + 0.007, 0.02, 0.12, H - 0.09, H - 0.05)
    b.xdisc('knob', 'chrome', xf + 0.005, x1, y1 - 0.09, H - 0.068, 0.03, n=16)
    R = min(0.2, W * 0.33)
    zc = 0.02 + (H - 0.14) / 2 + 0.01
    if s == 1:
        # a dark round panel behind the door and a row of buttons
        b.xdisc('door_panel', 'plastic_grey', xf - 0.002, xf + 0.002, 0.0, zc, R * 1.12, n=28)
        for k in range(3):
            yc = -0.02 - 0.035 * k
            b.box('button', 'plastic_white', xf + 0.005, xf + 0.009, yc - 0.012, yc + 0.012,
                  H - 0.075, H - 0.06)
    elif s == 2:
        # washer-dryer: worktop, a second knob and a kick plate
        b.box('worktop', 'plastic_black', x0, xf, y0, y1, H - 0.012, H)
        b.xdisc('knob', 'chrome', xf + 0.005, x1, y0 + 0.25, H - 0.068, 0.02, n=12)
        b.box('kick_plate', 'plastic_grey', xf, xf + 0.004, y0 + 0.02, y1 - 0.02, 0.03, 0.09)
    b.ring('door_ring', 'chrome' if s != 1 else 'plastic_grey', 0, 0, 0, 0.018, R * 0.72, R,
           n=28)
    b.transform_last(1, rot_y(math.pi / 2), shift=(xf - 0.006, 0.0, zc))
    b.xdisc('door_glass', 'glass_dark', xf - 0.004, xf + 0.004, 0.0, zc, R * 0.74, n=28)
    b.box('door_handle', 'plastic_grey', xf + 0.004, x1 - 0.004, R - 0.01, R + 0.03, zc - 0.05,
          zc + 0.05)


@builds('water machine')
def water_machine(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_white', 'plastic_grey', 'plastic_white')
    ch = 0.64 * H
    xf = x1 - 0.03
    b.box('plinth', 'plastic_grey', x0 + 0.01, xf - 0.01, y0 + 0.01, y1 - 0.01, 0.0, 0.04)
    b.box('cabinet', body, x0, xf, y0, y1, 0.04, ch)
    if s == 2:
        b.box('front_panel', 'plastic_black', xf, xf + 0.004, y0 + 0.02, y1 - 0.02, 0.06,
              ch * 0.5)
    b.box('dispense_recess', 'shadow', xf - 0.002, xf + 0.002, -0.09, 0.09, ch * 0.58, ch * 0.82)
    b.box('drip_tray', 'plastic_grey', xf, x1, -0.09, 0.09, ch * 0.58, ch * 0.61)
    b.box('tap', 'red', xf, x1, -0.06, -0.02, ch * 0.76, ch * 0.81)
    b.box('tap', 'blue', xf, x1, 0.02, 0.06, ch * 0.76, ch * 0.81)
    R = 0.44 * min(W, D)
    cx = (x0 + xf) / 2
    b.cyl('collar', body, cx, 0, ch, ch + 0.03, R * 0.5, n=16)
    bz = ch + 0.02
    bh = H - bz
    b.lathe('bottle', 'water', [(0, bz), (0.04, bz), (0.04, bz + 0.05), (R, bz + 0.14 * bh),
                                (R, bz + 0.5 * bh), (R * 0.93, bz + 0.56 * bh), (R, bz + 0.62 * bh),
                                (R, H - 0.04), (R * 0.8, H), (0, H)], cx, 0, n=20)
