"""Builders for bathroom fixtures: toilets, bidets, bathtubs, showers, sinks and trash cans.

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import math

from ..builder import Builder, builds, rot_y
from .fittings import FRONT, HANDLE, door, drawer


@builds('toilet')
def toilet(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    tank_d = 0.2
    seat = b.pick('ceramic', 'wood_light', 'ceramic')
    zr = 0.39
    # tank at the back
    if s == 1:
        b.box('tank', 'ceramic', x0, x0 + tank_d, y0 + 0.02, y1 - 0.02, 0.36, H - 0.03)
        b.box('tank_lid', 'ceramic', x0, x0 + tank_d + 0.01, y0, y1, H - 0.03, H)
    else:
        b.box('tank', 'ceramic', x0, x0 + tank_d, y0, y1, zr - 0.04, H)
    b.box('flush_button', 'chrome', x0 + tank_d, x0 + tank_d + 0.008, y1 - 0.09, y1 - 0.05,
          H - 0.1, H - 0.07)
    bx0 = x0 + tank_d - 0.04
    rx = (x1 - bx0) / 2
    bc = bx0 + rx
    ey = (W / 2) / rx
    b.lathe('pedestal', 'ceramic', [(0, 0), (rx * 0.55, 0), (rx * 0.5, 0.15), (rx * 0.75, 0.28),
                                    (0, 0.28)], bc - 0.03, 0, ey * 0.8, n=20)
    b.lathe('bowl', 'ceramic', [(0, 0.22), (rx * 0.75, 0.22), (rx * 0.97, zr - 0.05),
                                (rx, zr), (0, zr)], bc, 0, ey, n=24)
    b.ring('seat', seat, bc + 0.005, 0, zr, zr + 0.025, rx * 0.62, rx * 0.98, ey=ey, n=24)
    b.cyl('water', 'water', bc + 0.02, 0, zr, zr + 0.003, rx * 0.6, rx * 0.6 * ey * 0.85, n=20)
    if s == 2:
        # seat lid raised against the tank
        b.cyl('lid', seat, 0.0, 0.0, 0.0, 0.02, rx * 0.95, rx * 0.95 * ey, n=24)
        b.transform_last(1, rot_y(-math.radians(80)), shift=(x0 + tank_d + 0.03, 0.0,
                                                               zr + rx * 0.96 + 0.01))
    for sgn in (-1, 1):
        b.box('hinge', 'chrome', bx0 + 0.02, bx0 + 0.05, sgn * 0.08 - 0.015, sgn * 0.08 + 0.015,
              zr, zr + 0.03)


@builds('bidet')
def bidet(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    zr = H - 0.045
    deck = 0.12
    rx = (x1 - (x0 + deck - 0.05)) / 2
    bc = x1 - rx
    ey = (W / 2) / rx
    if s == 1:
        # wall-hung: a tall back block carries the bowl clear of the floor
        b.box('back', 'ceramic', x0, x0 + deck, y0 + 0.04, y1 - 0.04, 0.0, zr)
        b.lathe('bowl', 'ceramic', [(0, 0.12), (rx * 0.6, 0.12), (rx * 0.95, zr - 0.06), (rx, zr),
                                    (0, zr)], bc, 0, ey, n=24)
    else:
        b.box('back', 'ceramic', x0, x0 + deck, y0 + 0.02, y1 - 0.02, 0.0, zr)
        b.lathe('pedestal', 'ceramic', [(0, 0), (rx * 0.6, 0), (rx * 0.55, 0.15),
                                        (rx * 0.8, 0.25), (0, 0.25)], bc - 0.02, 0, ey * 0.8, n=20)
        b.lathe('bowl', 'ceramic', [(0, 0.2), (rx * 0.75, 0.2), (rx, zr - 0.04), (rx, zr),
                                    (0, zr)], bc, 0, ey, n=24)
    if s == 2:
        b.ring('rim', 'ceramic', bc, 0, zr - 0.01, zr + 0.004, rx * 0.78, rx, ey=ey, n=24)
    b.cyl('basin', 'ceramic_shadow', bc + 0.01, 0, zr, zr + 0.003, rx * 0.75, rx * 0.75 * ey * 0.9,
          n=20)
    b.cyl('drain', 'chrome', bc + 0.02, 0, zr + 0.003, zr + 0.005, 0.02, n=10)
    tx = x0 + 0.05
    tap = b.pick('chrome', 'chrome', 'brass')
    b.cyl('tap', tap, tx, 0, zr, H - 0.008, 0.014, n=12)
    b.seg('tap_spout', tap, (tx, 0, H - 0.02), (tx + 0.09, 0, H - 0.03), 0.009, n=8)
    if s == 2:
        for sgn in (-1, 1):
            b.box('tap_handle', tap, tx - 0.006, tx + 0.006, sgn * 0.05 - 0.02, sgn * 0.05 + 0.02,
                  H - 0.008, H)
            b.cyl('tap_valve', tap, tx, sgn * 0.05, zr, H - 0.008, 0.01, n=8)
    else:
        b.box('tap_lever', tap, tx - 0.04, tx + 0.005, -0.008, 0.008, H - 0.012, H)


@builds('bathtub')
def bathtub(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    tap = b.pick('chrome', 'chrome', 'brass')
    if s == 2:
        # free-standing roll-top tub on feet, pillar tap at the back
        zb = 0.08
        rx = (D - 0.07) / 2
        cx = x1 - rx
        ey = (W / 2) / rx
        b.lathe('tub', 'ceramic', [(0, zb), (rx * 0.8, zb), (rx * 0.97, zb + 0.2),
                                   (rx, H - 0.02), (rx * 0.93, H - 0.02), (rx * 0.9, H - 0.2),
                                   (rx * 0.74, zb + 0.06), (0, zb + 0.06)], cx, 0, ey, n=28)
        b.cyl('tub_inside', 'water', cx, 0, zb + 0.06, zb + 0.065, rx * 0.72, rx * 0.72 * ey, n=24)
        for sx in (-1, 1):
            for sy in (-1, 1):
                b.sphere('foot', 'brass', (cx + sx * rx * 0.5, sy * rx * ey * 0.65, 0.045),
                         (0.035, 0.035, 0.045))
        b.cyl('tap', tap, x0 + 0.03, 0, 0.0, H - 0.03, 0.018, n=12)
        b.seg('tap_spout', tap, (x0 + 0.03, 0, H - 0.03), (x0 + 0.16, 0, H - 0.05), 0.012, n=8)
        b.box('tap_handle', tap, x0 + 0.015, x0 + 0.045, -0.05, 0.05, H - 0.015, H)
        return
    t = 0.08
    panel = 'ceramic' if s == 0 else 'wood'
    b.box('apron', panel, x1 - t, x1, y0, y1, 0.0, H - (0.03 if s == 1 else 0.0))
    b.box('wall', 'ceramic', x0, x0 + t, y0, y1, 0.0, H)
    b.box('wall', 'ceramic', x0 + t, x1 - t, y0, y0 + t * 1.6, 0.0, H)
    b.box('wall', 'ceramic', x0 + t, x1 - t, y1 - t * 1.6, y1, 0.0, H)
    b.box('bottom', 'ceramic', x0 + t, x1 - t, y0 + t, y1 - t, 0.0, 0.12)
    b.box('inside', 'ceramic_shadow', x0 + t, x1 - t, y0 + t * 1.6, y1 - t * 1.6, 0.12, 0.125)
    b.box('water', 'water', x0 + t, x1 - t, y0 + t * 1.6, y1 - t * 1.6, 0.125, H - 0.18)
    if s == 1:
        b.box('apron_rim', 'ceramic', x1 - t, x1 + 0.0, y0, y1, H - 0.03, H)
    b.cyl('drain', 'chrome', 0.0, y1 - t * 1.6 - 0.12, 0.125, 0.13, 0.025, n=10)
    ty = y1 - t * 1.6 - 0.1
    b.seg('tap_spout', tap, (x0 + t, ty, H - 0.1), (x0 + t + 0.12, ty, H - 0.11), 0.014, n=10)
    b.box('tap_body', tap, x0 + t - 0.005, x0 + t + 0.03, ty - 0.06, ty + 0.06, H - 0.13,
          H - 0.08)


@builds('shower')
def shower(b: Builder):
    H, s = b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    tray = 0.06
    b.box('tray', 'ceramic', x0, x1, y0, y1, 0.0, tray)
    b.cyl('drain', 'chrome', 0.05, 0.0, tray, tray + 0.003, 0.04, n=12)
    frame = b.pick('chrome', 'metal_dark', 'chrome')
    p = 0.025
    b.box('post', frame, x1 - p, x1, y0, y0 + p, tray, H)
    b.box('post', frame, x1 - p, x1, y1 - p, y1, tray, H)
    b.box('rail', frame, x1 - p, x1, y0, y1, H - p, H)
    gz0, gz1 = tray, H - p
    if s == 0:
        b.box('glass', 'glass', x1 - 0.018, x1 - 0.008, y0 + p, y1 - p, gz0, gz1)
        for ya in (y0, y1 - p):
            b.box('post', frame, x0, x0 + p, ya, ya + p, tray, H)
            b.box('rail', frame, x0, x1, ya, ya + p, H - p, H)
            b.box('glass', 'glass', x0 + p, x1 - p, ya + p / 2 - 0.005, ya + p / 2 + 0.005, gz0,
                  gz1)
        b.box('door_handle', 'chrome', x1 - 0.008, x1, 0.1, 0.12, 0.9, 1.3)
    elif s == 1:
        b.box('glass', 'glass', x1 - 0.018, x1 - 0.008, y0 + p, y1 - p, gz0, gz1)
        b.box('post', frame, x0, x0 + p, y1 - p, y1, tray, H)
        b.box('rail', frame, x0, x1, y1 - p, y1, H - p, H)
        b.box('glass', 'glass', x0 + p, x1 - p, y1 - p / 2 - 0.005, y1 - p / 2 + 0.005, gz0, gz1)
        b.box('door_handle', 'chrome', x1 - 0.008, x1, -0.1, -0.08, 0.9, 1.3)
    else:
        # walk-in: one fixed glass screen along the front half, no door
        b.box('glass', 'glass', x1 - 0.018, x1 - 0.008, -0.05, y1 - p, gz0, gz1)
        b.box('rail', frame, x0, x1, y1 - p, y1, H - p, H)
        b.box('glass', 'glass', x0, x1 - p, y1 - p / 2 - 0.005, y1 - p / 2 + 0.005, gz0, gz1)
    # riser rail, arm and head on the back wall
    b.cyl('riser', 'chrome', x0 + 0.02, 0.0, 1.0, H - 0.15, 0.012, n=10)
    b.seg('shower_arm', 'chrome', (x0 + 0.02, 0.0, H - 0.15), (x0 + 0.2, 0.0, H - 0.12), 0.012,
          n=10)
    b.cyl('shower_head', 'chrome', x0 + 0.22, 0.0, H - 0.14, H - 0.115, 0.1, n=20)
    b.box('mixer', 'chrome', x0, x0 + 0.05, -0.08, 0.08, 1.0, 1.08)


@builds('sink')
def sink(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    tap = b.pick('chrome', 'chrome', 'metal_dark')
    zt = H - 0.15
    if s == 1:
        # pedestal basin
        rx = D / 2 - 0.01
        ey = (W / 2) / rx
        cx = 0.01
        b.lathe('pedestal', 'ceramic', [(0, 0), (0.11, 0), (0.08, 0.2), (0.08, zt - 0.16),
                                        (0.13, zt - 0.1), (0, zt - 0.1)], cx, 0, 1.2, n=16)
        b.lathe('basin', 'ceramic', [(0, zt - 0.16), (rx * 0.5, zt - 0.16), (rx * 0.92, zt - 0.06),
                                     (rx, zt), (0, zt)], cx, 0, ey, n=24)
        b.cyl('basin_recess', 'ceramic_shadow', cx + 0.02, 0, zt, zt + 0.003, rx * 0.72,
              rx * 0.72 * ey * 0.85, n=24)
        b.box('deck', 'ceramic', x0, x0 + 0.12, -0.12, 0.12, zt - 0.06, zt)
    else:
        wood = b.pick('wood_white', '', 'wood')
        xf = x1
        plinth = 0.1
        b.box('plinth', 'shadow', x0, xf - 0.05, y0 + 0.02, y1 - 0.02, 0.0, plinth)
        b.box('vanity', wood, x0, xf - HANDLE - FRONT, y0, y1, plinth, zt - 0.04)
        b.box('countertop', 'ceramic', x0, xf - 0.005, y0, y1, zt - 0.04, zt)
        if s == 0:
            n = 1 if W < 0.7 else 2
            for k in range(n):
                door(b, wood, 'chrome', y0 + k * W / n, y0 + (k + 1) * W / n, plinth, zt - 0.045,
                      xf, handle_side=-1 if k % 2 else 1, handle_len=0.12)
            bw = min(W * 0.34, 0.26)
            b.cyl('basin_rim', 'ceramic', 0.02, 0, zt, zt + 0.012, 0.17, bw, n=24)
            b.cyl('basin_recess', 'ceramic_shadow', 0.025, 0, zt + 0.012, zt + 0.014, 0.14,
                  bw - 0.03, n=24)
        else:
            dh = (zt - 0.045 - plinth) / 2
            for k in range(2):
                drawer(b, wood, 'metal', y0, y1, plinth + k * dh, plinth + (k + 1) * dh, xf,
                        'bar')
            rv = min(0.19, D / 2 - 0.04)
            b.lathe('basin', 'ceramic', [(0, zt), (rv * 0.55, zt), (rv * 0.95, zt + 0.08),
                                         (rv, zt + 0.13), (rv * 0.92, zt + 0.13),
                                         (rv * 0.85, zt + 0.08), (rv * 0.45, zt + 0.02),
                                         (0, zt + 0.02)], 0.03, 0, min(1.3, (W / 2 - 0.02) / rv),
                    n=24)
    # tap at the back (-x), the highest point of the model
    tx = x0 + 0.05
    b.cyl('tap', tap, tx, 0, zt, H - 0.012, 0.016, n=12)
    b.seg('tap_spout', tap, (tx, 0, H - 0.03), (tx + 0.13, 0, H - 0.045), 0.011, n=8)
    b.box('tap_lever', tap, tx - 0.05, tx + 0.006, -0.009, 0.009, H - 0.014, H)


@builds('trash can')
def trash_can(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    R = min(W, D) / 2
    ey = W / D if D < W else 1.0
    if s == 0:
        b.cyl('base_ring', 'plastic_black', 0, 0, 0.0, 0.025, R - 0.006, (R - 0.006) * ey, n=24)
        b.cyl('body', 'metal', 0, 0, 0.02, H - 0.03, R - 0.008, (R - 0.008) * ey, n=24)
        b.lathe('lid', 'metal', [(0, H - 0.03), (R - 0.004, H - 0.03), (R - 0.006, H - 0.012),
                                 (R * 0.7, H), (0, H)], 0, 0, ey, n=24)
        b.box('pedal', 'plastic_black', x1 - 0.05, x1, -0.04, 0.04, 0.004, 0.03)
        b.box('hinge', 'plastic_black', x0 + 0.0, x0 + 0.02, -0.03, 0.03, H - 0.05, H - 0.02)
    elif s == 1:
        b.box('body', 'plastic_white', x0 + 0.006, x1 - 0.006, y0 + 0.006, y1 - 0.006, 0.0,
              H - 0.05)
        b.box('rim', 'plastic_grey', x0, x1, y0, y1, H - 0.05, H - 0.03)
        b.box('lid', 'plastic_grey', x0 + 0.01, x1 - 0.01, y0 + 0.01, y1 - 0.01, H - 0.03,
              H - 0.004)
        b.box('swing_flap', 'plastic_white', x0 + 0.03, x1 - 0.03, -W * 0.3, W * 0.3, H - 0.008,
              H)
    else:
        b.lathe('basket', 'plastic_grey', [(0, 0), (R * 0.78, 0), (R, H - 0.02),
                                           (R * 0.95, H - 0.02), (R * 0.74, 0.02), (0, 0.02)],
                0, 0, ey, n=24)
        b.ring('rim', 'plastic_black', 0, 0, H - 0.02, H, R * 0.93, R, ey=ey, n=24)
        b.cyl('bag', 'shadow', 0, 0, 0.02, 0.025, R * 0.7, R * 0.7 * ey, n=16)
