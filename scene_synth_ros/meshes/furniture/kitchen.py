"""Builders for the kitchen: counter runs, sink units, cookers, fridges, dishwashers,
islands, bar stools, and the small appliances that stand on a worktop (microwaves, coffee
machines, toasters).

Kitchen units share one worktop height (``WORKTOP``, clamped into the counter's range) and a
plinth recessed under their doors, so that side by side they read as one run. Builders
sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import math

import numpy as np

from ..builder import Builder, builds, rot_z
from .fittings import FRONT, HANDLE, door, drawer, rounded_rect

PLINTH = 0.1          # toe kick under base units, recessed behind the doors
RECESS = 0.06         # how far the toe kick sits behind the fronts
WORKTOP = (0.86, 0.92)    # the range a sink unit's worktop keeps, as a counter's height
UNIT = 0.6            # width of one base cabinet module


def _modules(width: float, unit: float = UNIT) -> int:
    return max(1, int(round(width / unit)))


def _base_units(b: Builder, front: str, hmat: str, ya: float, yb: float, zt: float, xf: float,
                style: int, n: int):
    """Doors and drawers of ``n`` base modules between ``ya`` and ``yb`` below a worktop
    whose underside is at ``zt``, fronts just behind ``xf``."""
    mw = (yb - ya) / n
    for k in range(n):
        a, c = ya + k * mw, ya + (k + 1) * mw
        if style == 1 and k % 2 == 0:
            # a stack of pan drawers
            dh = (zt - PLINTH) / 3
            for r in range(3):
                drawer(b, front, hmat, a, c, PLINTH + r * dh, PLINTH + (r + 1) * dh, xf, 'bar')
        elif style == 2:
            # handle-less: a finger groove under the worktop instead of handles
            b.box('door', front, xf - HANDLE - FRONT, xf - HANDLE, a + 0.003, c - 0.003,
                  PLINTH + 0.003, zt - 0.04)
        else:
            dh = 0.16
            drawer(b, front, hmat, a, c, zt - dh, zt, xf, 'bar')
            door(b, front, hmat, a, c, PLINTH, zt - dh, xf, handle_side=-1 if k % 2 else 1,
                 handle_len=0.12)
    if style == 2:
        b.box('grip_rail', 'metal', xf - HANDLE - 0.004, xf - HANDLE, ya, yb, zt - 0.037,
              zt - 0.015)


@builds('counter')
def counter(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    front = b.pick('wood_white', 'paint_grey', 'wood_light')
    top = b.pick('stone', 'wood', 'plastic_black')
    hmat = b.pick('chrome', 'metal_dark', 'metal')
    t = 0.035 if s != 1 else 0.04
    xf = x1 - 0.02                      # the worktop overhangs the fronts by 2 cm
    zt = H - t
    b.box('plinth', 'shadow', x0, xf - RECESS, y0, y1, 0.0, PLINTH)
    b.box('carcass', front, x0, xf - HANDLE - FRONT, y0, y1, PLINTH, zt)
    b.box('worktop', top, x0, x1, y0, y1, zt, H)
    b.box('splashback', 'ceramic' if s != 2 else top, x0, x0 + 0.012, y0, y1, zt, H)
    _base_units(b, front, hmat, y0, y1, zt, xf, s, _modules(W))


@builds('kitchen sink')
def kitchen_sink(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    front = b.pick('wood_white', 'paint_grey', 'wood_light')
    top = b.pick('stone', 'wood', 'wood_dark')
    hmat = b.pick('chrome', 'metal_dark', 'metal')
    tap = b.pick('chrome', 'metal_dark', 'chrome')
    zw = min(max(H - 0.28, WORKTOP[0]), WORKTOP[1])     # worktop level with the counters'
    t = 0.035
    xf = x1 - 0.02
    b.box('plinth', 'shadow', x0, xf - RECESS, y0, y1, 0.0, PLINTH)
    b.box('carcass', front, x0, xf - HANDLE - FRONT, y0, y1, PLINTH, zw - t)
    b.box('worktop', top, x0, x1, y0, y1, zw - t, zw)
    # a false drawer front over the doors (the bowl sits behind it), then one or two doors
    b.box('false_front', front, xf - HANDLE - FRONT, xf - HANDLE, y0 + 0.004, y1 - 0.004,
          zw - t - 0.14, zw - t - 0.004)
    n = 1 if W < 0.8 else 2
    for k in range(n):
        door(b, front, hmat, y0 + k * W / n, y0 + (k + 1) * W / n, PLINTH, zw - t - 0.14, xf,
             handle_side=-1 if k % 2 else 1, handle_len=0.12)
    # the bowl: a steel sink with a drainer, a white double bowl, or one undermount bowl
    bx0, bx1 = x0 + 0.12, x1 - 0.07
    if s == 0:
        bw = min(0.42, W * 0.5)
        yb = y0 + 0.05 + bw / 2 if W >= 0.8 else 0.0
        b.box('sink_deck', 'metal', bx0 - 0.02, bx1 + 0.01, y0 + 0.03, y1 - 0.03, zw, zw + 0.004)
        b.box('basin', 'metal_dark', bx0, bx1, yb - bw / 2, yb + bw / 2, zw + 0.004, zw + 0.006)
        if W >= 0.8:
            for yg in np.linspace(yb + bw / 2 + 0.06, y1 - 0.08, 4):
                b.box('drainer_groove', 'metal_dark', bx0 + 0.03, bx1 - 0.03, yg - 0.004,
                      yg + 0.004, zw + 0.004, zw + 0.005)
        yt = yb
    elif s == 1:
        b.box('sink_deck', 'ceramic', bx0 - 0.02, bx1 + 0.01, y0 + 0.04, y1 - 0.04, zw,
              zw + 0.012)
        halves = 2 if W >= 0.9 else 1
        span = (W - 0.14) / halves
        for k in range(halves):
            ya = y0 + 0.07 + k * span
            b.box('basin', 'ceramic_shadow', bx0 + 0.02, bx1 - 0.02, ya + 0.02, ya + span - 0.02,
                  zw + 0.012, zw + 0.014)
        yt = 0.0
    else:
        bw = min(0.5, W * 0.6)
        b.box('basin', 'metal_dark', bx0, bx1, -bw / 2, bw / 2, zw, zw + 0.002)
        b.cyl('drain', 'chrome', (bx0 + bx1) / 2, 0.0, zw + 0.002, zw + 0.003, 0.04, n=12)
        yt = 0.0
    # the tap at the back of the bowl, its column the highest point (a collision piece of
    # its own in the exports), a spout over the bowl and a lever at the side
    tx = x0 + 0.07
    b.cyl('tap', tap, tx, yt, zw, H, 0.02, n=12)
    spout = 0.2 if s != 1 else 0.16
    b.seg('tap_spout', tap, (tx, yt, H - 0.03), (tx + spout, yt, H - 0.03), 0.012, n=8)
    b.seg('tap_spout', tap, (tx + spout, yt, H - 0.03), (tx + spout, yt, H - 0.1), 0.011, n=8)
    b.box('tap_lever', tap, tx - 0.05, tx + 0.008, yt + 0.02, yt + 0.034, H - 0.08, H - 0.06)


@builds('stove')
def stove(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('metal', 'plastic_white', 'metal_dark')
    hob = b.pick('lacquer', 'metal_dark', 'lacquer')
    x_door = x1 - 0.035                  # front of the door and fascia; knobs and bar beyond
    b.box('plinth', 'shadow', x0, x_door - 0.04, y0 + 0.02, y1 - 0.02, 0.0, 0.06)
    b.box('body', body, x0, x_door - 0.02, y0, y1, 0.06, H - 0.012)
    b.box('hob', hob, x0, x_door, y0, y1, H - 0.012, H - 0.006)
    # burners: two rows of two, three in a row on a wide range cooker
    cols = 3 if W >= 0.8 else 2
    xs = (x0 + (x_door - x0) * 0.3, x0 + (x_door - x0) * 0.72)
    ys = np.linspace(y0 + W / (2 * cols), y1 - W / (2 * cols), cols)
    r = min(0.09, W / (2 * cols) - 0.035)
    for i, xc in enumerate(xs):
        for j, yc in enumerate(ys):
            rr = r * (1.0 if (i + j) % 2 == 0 else 0.78)
            if s == 1:
                # gas: a burner cap under a cast-iron pan support
                b.cyl('burner', 'metal', xc, yc, H - 0.006, H - 0.003, rr * 0.6, n=16)
                b.cyl('burner_cap', 'metal_dark', xc, yc, H - 0.003, H, rr * 0.35, n=12)
                b.box('pan_support', 'metal_dark', xc - rr, xc + rr, yc - 0.006, yc + 0.006,
                      H - 0.006, H - 0.001)
                b.box('pan_support', 'metal_dark', xc - 0.006, xc + 0.006, yc - rr, yc + rr,
                      H - 0.006, H - 0.001)
            else:
                # ceramic or induction: rings marked on the glass
                b.ring('hob_ring', 'plastic_grey' if s == 0 else 'red', xc, yc, H - 0.006, H,
                       rr * 0.85, rr, n=24)
    # fascia with knobs, the oven door with its window and bar handle, a drawer below
    zf = H - 0.13
    b.box('fascia', body, x_door - 0.02, x_door, y0 + 0.005, y1 - 0.005, zf, H - 0.014)
    knobs = cols * 2 + (1 if s != 2 else 0)
    for yk in np.linspace(y0 + 0.07, y1 - 0.07, knobs):
        b.xdisc('knob', 'plastic_black' if s != 1 else 'chrome', x_door, x1 - 0.01, yk,
                zf + 0.055, 0.02, n=12)
    zd0, zd1 = 0.2, zf - 0.02
    b.box('oven_door', body if s != 2 else 'lacquer', x_door - 0.02, x_door, y0 + 0.02,
          y1 - 0.02, zd0, zd1)
    b.box('oven_window', 'glass_dark', x_door, x_door + 0.003, y0 + 0.09, y1 - 0.09,
          zd0 + 0.08, zd1 - 0.1)
    for yp in (y0 + 0.07, y1 - 0.07):
        b.box('handle_post', 'chrome', x_door, x1 - 0.015, yp - 0.01, yp + 0.01, zd1 - 0.06,
              zd1 - 0.04)
    b.seg('handle', 'chrome', (x1 - 0.012, y0 + 0.06, zd1 - 0.05),
          (x1 - 0.012, y1 - 0.06, zd1 - 0.05), 0.012, n=10)
    drawer(b, body, 'chrome', y0 + 0.02, y1 - 0.02, 0.07, zd0 - 0.01, x_door + HANDLE, 'top')


@builds('fridge')
def fridge(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_white', 'metal', 'metal_dark')
    hmat = b.pick('metal', 'metal_dark', 'chrome')
    xf = x1 - 0.04                       # the door fronts; handles stand proud to x1
    t = 0.045                            # door thickness
    b.box('plinth', 'shadow', x0 + 0.02, xf - t - 0.03, y0 + 0.02, y1 - 0.02, 0.0, 0.04)
    under_counter = H < 1.0
    b.box('body', body, x0, xf - t, y0, y1, 0.02, H - (0.03 if under_counter else 0.0))
    b.box('vent_grille', 'plastic_black', xf - t, xf, y0 + 0.03, y1 - 0.03, 0.0, 0.04)

    def fridge_door(ya, yb, za, zb, hinge_right: bool, long_handle: bool):
        b.box('door', body, xf - t, xf, ya + 0.004, yb - 0.004, za + 0.004, zb - 0.004)
        yh = ya + 0.05 if hinge_right else yb - 0.05
        hl = min(zb - za - 0.12, 0.9) if long_handle else min(0.3, zb - za - 0.08)
        zc = za + (zb - za) * (0.5 if long_handle else 0.25)
        if not long_handle and zb < H - 0.01:
            zc = zb - hl / 2 - 0.06          # a freezer's handle at the top of its door
        for zp in (zc - hl / 2 + 0.02, zc + hl / 2 - 0.02):
            b.box('handle_post', hmat, xf, x1 - 0.015, yh - 0.01, yh + 0.01, zp - 0.015,
                  zp + 0.015)
        b.box('handle', hmat, x1 - 0.018, x1, yh - 0.013, yh + 0.013, zc - hl / 2, zc + hl / 2)

    z0 = 0.04
    if under_counter:
        # one door under a worktop of its own
        fridge_door(y0, y1, z0, H - 0.03, True, False)
        b.box('top', 'plastic_grey', x0, xf, y0, y1, H - 0.03, H)
    elif H < 1.5:
        # a larder fridge: one tall door
        fridge_door(y0, y1, z0, H, s != 1, True)
    elif W >= 0.8:
        if s == 2:
            # French doors over a freezer drawer
            zm = z0 + (H - z0) * 0.3
            fridge_door(y0, 0.0, zm, H, False, True)
            fridge_door(0.0, y1, zm, H, True, True)
            b.box('door', body, xf - t, xf, y0 + 0.004, y1 - 0.004, z0 + 0.004, zm - 0.004)
            b.box('handle', hmat, x1 - 0.018, x1, y0 + 0.15, y1 - 0.15, zm - 0.08, zm - 0.055)
            b.box('handle_post', hmat, xf, x1 - 0.015, y0 + 0.16, y0 + 0.18, zm - 0.08, zm - 0.055)
            b.box('handle_post', hmat, xf, x1 - 0.015, y1 - 0.18, y1 - 0.16, zm - 0.08, zm - 0.055)
        else:
            # side by side: freezer on the left, fridge on the right (seen from the front)
            ym = y0 + W * 0.42
            fridge_door(y0, ym, z0, H, False, True)
            fridge_door(ym, y1, z0, H, True, True)
        b.box('dispenser', 'screen', xf, xf + 0.004, y0 + 0.08, y0 + 0.26, H * 0.5, H * 0.68)
    else:
        # fridge-freezer: the fridge above, the freezer below (the other way round in style 1)
        split = 0.62 if s != 1 else 0.32
        zm = z0 + (H - z0) * (1.0 - split)
        top_is_freezer = s == 1
        fridge_door(y0, y1, zm, H, True, not top_is_freezer)
        fridge_door(y0, y1, z0, zm, True, top_is_freezer)
        if s == 0:
            b.box('display', 'screen_on', xf, xf + 0.003, -0.06, 0.06, zm + 0.25, zm + 0.31)


@builds('dishwasher')
def dishwasher(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_white', 'metal', 'metal_dark')
    xf = x1 - HANDLE
    b.box('plinth', 'shadow', x0, xf - RECESS, y0 + 0.01, y1 - 0.01, 0.0, PLINTH)
    b.box('body', body, x0, xf - FRONT, y0, y1, PLINTH, H - 0.02)
    b.box('top', 'plastic_grey' if s != 2 else 'wood', x0, xf, y0, y1, H - 0.02, H)
    zc = H - 0.12                        # top of the door, under the control strip
    b.box('door', body, xf - FRONT, xf, y0 + 0.004, y1 - 0.004, PLINTH, zc - 0.004)
    b.box('control_panel', 'plastic_black' if s != 1 else 'plastic_grey', xf - FRONT, xf,
          y0 + 0.004, y1 - 0.004, zc, H - 0.024)
    b.box('display', 'screen_on', xf, xf + 0.003, y1 - 0.16, y1 - 0.06, zc + 0.03, zc + 0.06)
    for k in range(4 if s != 2 else 2):
        yk = y0 + 0.06 + 0.045 * k
        b.box('button', 'plastic_white', xf, xf + 0.004, yk - 0.012, yk + 0.012, zc + 0.03,
              zc + 0.05)
    if s == 1:
        b.box('handle', 'chrome', xf, x1, -W * 0.3, W * 0.3, zc - 0.06, zc - 0.04)
    else:
        b.box('handle', 'chrome' if s == 0 else 'plastic_black', xf, x1, -W * 0.18, W * 0.18,
              zc - 0.05, zc - 0.025)
    b.box('kick_logo', 'metal', xf, xf + 0.003, -0.05, 0.05, PLINTH + 0.03, PLINTH + 0.05)


@builds('kitchen island')
def kitchen_island(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    front = b.pick('paint_grey', 'wood_white', 'wood_dark')
    top = b.pick('stone', 'wood_light', 'stone')
    hmat = b.pick('chrome', 'metal_dark', 'brass')
    t = 0.04
    zt = H - t
    overhang = min(0.3, D * 0.35)        # knee space for bar stools at the front (+x)
    xc = x1 - overhang                   # the cabinets' face towards the stools
    end = 0.05 if s == 1 else 0.0        # waterfall end panels
    if s == 0:
        # a hob flush in the worktop on the cook's side
        b.box('worktop', top, x0, x1, y0, y1, zt, H - 0.002)
        hw = min(0.6, W * 0.4)
        b.box('hob', 'lacquer', x0 + 0.06, x0 + 0.56, -hw / 2, hw / 2, H - 0.004, H)
        for xc in (x0 + 0.18, x0 + 0.44):
            for yc in (-hw / 4, hw / 4):
                b.ring('hob_ring', 'plastic_grey', xc, yc, H - 0.004, H, 0.06, 0.075, n=20)
    else:
        b.box('worktop', top, x0, x1, y0, y1, zt, H)
    if s == 1:
        for ya in (y0, y1 - end):
            b.box('waterfall', top, x0, x1, ya, ya + end, 0.0, zt)
    elif s == 2:
        for ya in (y0 + 0.02, y1 - 0.08):
            b.box('leg', front, x1 - 0.08, x1 - 0.02, ya, ya + 0.06, 0.0, zt)
    xb = x0 + HANDLE + FRONT             # the cabinets' back, behind the doors
    b.box('plinth', 'shadow', xb + RECESS - HANDLE - FRONT, xc - 0.02, y0 + end, y1 - end, 0.0,
          PLINTH)
    b.box('carcass', front, xb, xc, y0 + end, y1 - end, PLINTH, zt)
    b.box('seating_panel', front if s != 0 else 'wood', xc, xc + 0.02, y0 + end + 0.02,
          y1 - end - 0.02, PLINTH, zt)
    # doors and drawers face the cook at the back: drawn at the front, then turned round
    n = _modules(W - 2 * end)
    before = len(b.parts)
    _base_units(b, front, hmat, -(y1 - end), -(y0 + end), zt, -x0, 0 if s != 1 else 1, n)
    b.transform_last(len(b.parts) - before, rot_z(math.pi))


@builds('bar stool')
def bar_stool(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    backed = H > 0.85
    hs = H - 0.3 if backed else H           # seat height
    hs = max(hs, 0.6)
    seat = b.pick('wood', 'leather_black', 'fabric_grey')
    frame = b.pick('wood_dark', 'chrome', 'metal_dark')
    zf = hs * 0.38                          # footrest height
    if s == 1:
        # one gas-lift column on a round base
        b.cyl('base', frame, 0, 0, 0.0, 0.03, R * 0.9, n=24)
        b.cyl('column', frame, 0, 0, 0.03, hs - 0.06, 0.03, n=12)
        b.torus('footrest', frame, (0, 0, zf), R * 0.62, 0.012, n=20, m=6)
        for k in range(3):
            a = math.radians(120 * k)
            b.seg('footrest_spoke', frame, (0, 0, zf), (R * 0.62 * math.cos(a),
                                                        R * 0.62 * math.sin(a), zf), 0.008, n=6)
    else:
        n = 4
        for k in range(n):
            a = math.radians(45 + 90 * k)
            ca, sa = math.cos(a), math.sin(a)
            rb, rt = R - 0.02, R * 0.6
            b.seg('leg', frame, (rb * ca, rb * sa, 0.0), (rt * ca, rt * sa, hs - 0.04),
                  0.018 if s == 0 else 0.012, n=8)
        rf = R - 0.02 - (R - 0.02 - R * 0.6) * (zf / (hs - 0.04))
        if s == 0:
            b.torus('footrest', 'metal', (0, 0, zf), rf, 0.01, n=20, m=6)
        else:
            for k in range(n):
                a0, a1 = math.radians(45 + 90 * k), math.radians(135 + 90 * k)
                b.seg('footrest', frame, (rf * math.cos(a0), rf * math.sin(a0), zf),
                      (rf * math.cos(a1), rf * math.sin(a1), zf), 0.01, n=6)
    if s == 2:
        b.box('seat', seat, -R * 0.95, R * 0.95, -R * 0.95, R * 0.95, hs - 0.05, hs)
    else:
        b.cyl('seat', seat, 0, 0, hs - 0.05, hs, R, n=24)
    if backed:
        # a low back at -x
        bx = -R + 0.02
        for yc in (-R * 0.55, R * 0.55):
            b.seg('back_post', frame, (bx + 0.03, yc, hs - 0.02), (bx, yc, H - 0.06), 0.012, n=8)
        b.box('backrest', seat, bx - 0.02, bx + 0.02, -R * 0.75, R * 0.75, H - 0.12, H)


@builds('microwave')
def microwave(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_white', 'metal', 'plastic_black')
    xf = x1 - 0.012
    for xa in (x0 + 0.04, xf - 0.05):
        for ya in (y0 + 0.04, y1 - 0.04):
            b.cyl('foot', 'rubber', xa, ya, 0.0, 0.012, 0.012, n=8)
    b.box('body', body, x0, xf, y0, y1, 0.012, H)
    panel = min(0.13, W * 0.26)                # controls on the right seen from the front
    b.box('door', 'plastic_black' if s != 2 else 'metal_dark', xf, xf + 0.006, y0 + 0.01,
          y1 - panel - 0.005, 0.03, H - 0.02)
    b.box('window', 'glass_dark', xf + 0.006, xf + 0.008, y0 + 0.05, y1 - panel - 0.09, 0.07,
          H - 0.06)
    b.box('control_panel', 'plastic_grey' if s != 2 else 'plastic_black', xf, xf + 0.004,
          y1 - panel, y1 - 0.01, 0.03, H - 0.02)
    b.box('display', 'screen_on', xf + 0.004, xf + 0.006, y1 - panel + 0.02, y1 - 0.03,
          H - 0.07, H - 0.045)
    if s == 0:
        b.xdisc('dial', 'plastic_grey', xf + 0.004, x1, y1 - panel / 2 - 0.005, H * 0.45, 0.025,
                n=14)
        b.box('handle', 'plastic_grey', xf + 0.006, x1, y1 - panel - 0.045, y1 - panel - 0.025,
              0.08, H - 0.08)
    else:
        for k in range(3):
            for j in range(2):
                yb = y1 - panel + 0.03 + j * (panel - 0.05) / 2
                zb = H * 0.55 - k * 0.03
                b.box('button', 'plastic_white', xf + 0.004, xf + 0.007, yb - 0.008, yb + 0.008,
                      zb - 0.01, zb + 0.01)
        b.box('door_release', 'metal', xf + 0.004, x1, y1 - panel + 0.02, y1 - 0.03, 0.04,
              0.06)


@builds('coffee machine')
def coffee_machine(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('metal', 'plastic_black', 'red')
    xb = x0 + D * 0.55                    # the tower's front; the drip tray reaches x1
    b.box('base', 'plastic_black', x0, x1 - 0.02, y0, y1, 0.0, 0.03)
    b.box('drip_tray', 'metal', xb, x1, y0 + 0.02, y1 - 0.02, 0.03, 0.05)
    b.box('tower', body, x0, xb, y0, y1, 0.03, H - 0.02)
    b.box('head', body, xb, x1 - 0.03, y0 + 0.01, y1 - 0.01, H - 0.11, H - 0.03)
    b.box('lid', 'plastic_black', x0, x1 - 0.03, y0, y1, H - 0.03 if s != 1 else H - 0.02,
          H if s != 1 else H - 0.005)
    if s == 1:
        # a bean hopper on top (bean-to-cup)
        b.frustum('bean_hopper', 'glass_dark', (x0 + xb) / 2, 0.0, H - 0.02, H, W * 0.25,
                  W * 0.32, n=16)
    b.cyl('spout', 'chrome', (xb + x1) / 2 - 0.01, 0.0, H - 0.15, H - 0.11, 0.022, n=12)
    b.lathe('cup', 'ceramic', [(0.0, 0.05), (0.028, 0.05), (0.034, 0.12), (0.0, 0.12)],
            (xb + x1) / 2 - 0.01, 0.0, n=14)
    b.box('water_tank', 'glass', x0 - 0.0, x0 + 0.012, y0 + 0.02, y1 - 0.02, 0.08, H - 0.08)
    if s == 0:
        b.seg('steam_wand', 'chrome', (xb, y1 - 0.02, H - 0.13), (xb + 0.06, y1 - 0.02, 0.1),
              0.006, n=6)
        b.xdisc('gauge', 'plastic_white', xb, xb + 0.004, 0.0, H * 0.62, min(0.035, W * 0.15),
                n=14)
    else:
        b.box('display', 'screen_on', xb, xb + 0.003, y0 + 0.03, y1 - 0.03, H - 0.2, H - 0.14)


@builds('toaster')
def toaster(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1 = b.x0, b.x1
    body = b.pick('metal', 'plastic_white', 'red')
    r = D / 2 - 0.01 if s == 1 else min(0.03, D / 2 - 0.015)
    b.prism('body', body, rounded_rect(D / 2 - 0.006, W / 2, r, 6), 0.015, H - 0.002, cx=-0.006)
    for ya in (-W / 2 + 0.05, W / 2 - 0.05):
        for xa in (x0 + 0.03, x1 - 0.042):
            b.cyl('foot', 'plastic_black', xa, ya, 0.0, 0.015, 0.01, n=8)
    slots = 4 if W >= 0.34 else 2
    rows = 2 if slots == 4 and s == 2 else 1
    per_row = slots // rows
    xs = (-0.025, 0.025) if rows == 2 else (0.0,)
    length = (W - 0.09) / per_row - 0.02
    for xc in xs:
        for k in range(per_row):
            yc = -W / 2 + 0.045 + (k + 0.5) * (W - 0.09) / per_row
            b.box('slot', 'shadow', xc - 0.008, xc + 0.008, yc - length / 2, yc + length / 2,
                  H - 0.004, H)
    # the lever and the browning dial on the front face
    b.box('lever', 'plastic_black', x1 - 0.012, x1, W / 2 - 0.09, W / 2 - 0.05, H * 0.55,
          H * 0.62)
    b.xdisc('dial', 'plastic_black', x1 - 0.012, x1 - 0.002, -W / 2 + 0.08, H * 0.35, 0.014,
            n=12)
    if s == 1:
        b.box('crumb_tray', 'chrome', x1 - 0.014, x1 - 0.004, -W / 4, W / 4, 0.02, 0.035)
    elif s == 2:
        for k, mat in enumerate(('plastic_white', 'orange')):
            zc = H * 0.62 - 0.03 * k
            b.box('button', mat, x1 - 0.012, x1 - 0.004, -W / 2 + 0.12, -W / 2 + 0.15, zc - 0.008,
                  zc + 0.008)
