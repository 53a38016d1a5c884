"""Builders for living-room and office pieces: coat hangers, whiteboards, pianos and
fireplaces.

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import math

import numpy as np

from ..builder import Builder, builds
from ..materials import BOOK_COVERS


@builds('hanger')
def hanger(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    if s == 1:
        mat = 'metal'
        for yc in (y0 + 0.02, y1 - 0.02):
            b.box('foot', mat, x0, x1, yc - 0.02, yc + 0.02, 0.0, 0.03)
            b.cyl('upright', mat, 0, yc, 0.03, H - 0.02, 0.014, n=10)
        b.seg('rail', mat, (0, y0 + 0.02, H - 0.02), (0, y1 - 0.02, H - 0.02), 0.014, n=10)
        b.seg('base_bar', mat, (0, y0 + 0.02, 0.15), (0, y1 - 0.02, 0.15), 0.01, n=8)
        n = max(2, int((W - 0.1) / 0.12))
        colours = ('blue', 'fabric_beige', 'red', 'fabric_grey', 'green', 'purple')
        for k, yc in enumerate(np.linspace(y0 + 0.08, y1 - 0.08, n)):
            gl = 0.6 + 0.25 * ((k * 7) % 3) / 2
            gw = min(D * 0.85, 0.42)
            b.seg('hook', 'metal', (0, yc, H - 0.04), (0, yc, H - 0.08), 0.004, n=6)
            b.box('garment', colours[k % len(colours)], -gw / 2, gw / 2, yc - 0.015, yc + 0.015,
                  H - 0.08 - gl, H - 0.08)
            b.obox('shoulder', colours[k % len(colours)], (0, yc, H - 0.1), (gw * 1.0, 0.03, 0.05),
                   np.eye(3))
        return
    mat = b.pick('wood', '', 'wood_dark')
    R = min(W, D) / 2
    if s == 0:
        b.cyl('base', mat, 0, 0, 0.0, 0.03, R * 0.8, n=24)
    else:
        for k in range(3):
            a = math.radians(90 + 120 * k)
            b.seg('foot', mat, (R * 0.95 * math.cos(a), R * 0.95 * math.sin(a), 0.0),
                  (0, 0, 0.35), 0.018, n=8)
    b.cyl('pole', mat, 0, 0, 0.0, H - 0.04, 0.022, n=12)
    b.sphere('finial', mat, (0, 0, H - 0.04), 0.04)
    for tier, zt in enumerate((H - 0.22, H - 0.4)):
        for k in range(4):
            a = math.radians(45 * tier + 90 * k)
            reach = R * (0.95 if tier == 0 else 0.7)
            b.seg('hook', 'metal_dark' if s == 0 else 'brass', (0, 0, zt),
                  (reach * math.cos(a), reach * math.sin(a), zt + 0.12), 0.009, n=6)
            b.sphere('hook_tip', 'metal_dark' if s == 0 else 'brass',
                     (reach * math.cos(a), reach * math.sin(a), zt + 0.12), 0.014)
    if W > 0.55:
        b.box('coat', 'fabric_beige', -0.05, 0.05, R * 0.2, W / 2, H - 1.05, H - 0.18)


@builds('whiteboard')
def whiteboard(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    frame = b.pick('metal', 'metal', 'blue')
    u = 0.04
    for yc in (y0 + u / 2, y1 - u / 2):
        b.box('upright', frame, -u / 2, u / 2, yc - u / 2, yc + u / 2, 0.06, H)
        b.box('foot', frame, x0 + 0.02, x1 - 0.02, yc - 0.02, yc + 0.02, 0.03, 0.06)
        for xc in (x0 + 0.03, x1 - 0.03):
            b.sphere('caster', 'rubber', (xc, yc, 0.03), 0.03)
    zb0, zb1 = 0.82, H - 0.04
    b.box('board', 'whiteboard', -0.01, 0.012, y0 + u, y1 - u, zb0, zb1)
    for z0, z1 in ((zb0 - 0.02, zb0), (zb1, zb1 + 0.02)):
        b.box('board_frame', 'metal', -0.014, 0.016, y0 + u, y1 - u, z0, z1)
    b.box('marker_tray', 'metal', 0.012, 0.08, y0 + 0.2, y1 - 0.2, zb0 - 0.02, zb0)
    for k, col in enumerate(('red', 'blue', 'green')):
        yc = -0.1 + 0.08 * k
        b.seg('marker', col, (0.04, yc - 0.06, zb0 + 0.008), (0.04, yc + 0.06, zb0 + 0.008),
              0.008, n=8)
    if s != 0:
        b.box('crossbar', frame, -0.015, 0.015, y0 + u, y1 - u, 0.3, 0.33)
    if s == 2:
        # a few strokes of writing on the board
        for k in range(3):
            length = (W - 0.5) * (0.7 - 0.15 * k)
            b.box('writing', BOOK_COVERS[k], 0.012, 0.013, y0 + 0.2, y0 + 0.2 + length,
                  zb1 - 0.15 - 0.12 * k, zb1 - 0.13 - 0.12 * k)


@builds('piano')
def piano(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('lacquer', 'wood_dark', 'lacquer_white')
    body_d = 0.34
    b.box('case', mat, x0, x0 + body_d, y0, y1, 0.0, H - 0.02)
    b.box('lid', mat, x0, x0 + body_d + 0.015, y0, y1, H - 0.02, H)
    ch = 0.05
    kz = 0.72
    b.box('cheek', mat, x0 + body_d, x1, y0, y0 + ch, 0.62, kz + 0.06)
    b.box('cheek', mat, x0 + body_d, x1, y1 - ch, y1, 0.62, kz + 0.06)
    b.box('keybed', mat, x0 + body_d, x1 - 0.02, y0 + ch, y1 - ch, 0.62, kz - 0.02)
    b.box('key_slip', mat, x1 - 0.02, x1, y0 + ch, y1 - ch, 0.6, kz)
    kx0, kx1 = x1 - 0.17, x1 - 0.02
    b.box('keys_white', 'keys_white', kx0, kx1, y0 + ch, y1 - ch, kz - 0.02, kz)
    b.box('fallboard', mat, x0 + body_d, kx0, y0 + ch, y1 - ch, kz - 0.02, kz + 0.05)
    b.box('music_desk', mat, x0 + body_d, x0 + body_d + 0.05, y0 + 0.25, y1 - 0.25, kz + 0.26,
          kz + 0.28)
    nwhite = 52
    kw = (W - 2 * ch) / nwhite
    names = 'ABCDEFG'
    for i in range(nwhite - 1):
        if names[i % 7] in 'ACDFG':
            yc = y0 + ch + kw * (i + 1)
            b.box('key_black', 'keys_black', kx0 + 0.01, kx0 + 0.1, yc - kw * 0.3, yc + kw * 0.3,
                  kz, kz + 0.012)
    if s != 2:
        for ya in (y0 + 0.07, y1 - 0.07):
            b.cyl('leg', mat, x1 - 0.05, ya, 0.04, 0.62, 0.025, n=12)
            b.box('toe_block', mat, x0 + body_d, x1 - 0.02, ya - 0.025, ya + 0.025, 0.0, 0.05)
    else:
        b.box('lower_panel', mat, x0 + body_d, x0 + body_d + 0.05, y0 + ch, y1 - ch, 0.0, 0.62)
    for k in (-1, 0, 1):
        b.box('pedal', 'brass', x0 + body_d, x0 + body_d + 0.1, k * 0.06 - 0.012, k * 0.06 + 0.012,
              0.04, 0.055)


@builds('fireplace')
def fireplace(b: Builder):
    W, H, s = b.W, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    surround = b.pick('stone', 'wood_white', 'brick')
    hearth_d = 0.12
    xs = x1 - hearth_d
    b.box('hearth', b.pick('stone', 'stone', 'firebox'), x0, x1, y0 + 0.05, y1 - 0.05, 0.0, 0.05)
    ow = 0.55 * W
    oh = 0.55 * H
    z0 = 0.05
    b.box('jamb', surround, x0, xs, y0 + 0.03, -ow / 2, z0, H - 0.05)
    b.box('jamb', surround, x0, xs, ow / 2, y1 - 0.03, z0, H - 0.05)
    b.box('lintel', surround, x0, xs, -ow / 2, ow / 2, z0 + oh, H - 0.05)
    b.box('mantel', b.pick('wood_dark', 'wood_white', 'wood_dark'), x0, xs + 0.05, y0, y1,
          H - 0.05, H)
    # the opening is a dark recess: back wall, side and top liners, sooty floor
    lt = 0.012
    b.box('firebox', 'firebox', x0, x0 + 0.03, -ow / 2, ow / 2, z0, z0 + oh)
    for ya, yb in ((-ow / 2, -ow / 2 + lt), (ow / 2 - lt, ow / 2)):
        b.box('firebox_side', 'firebox', x0 + 0.03, xs - 0.005, ya, yb, z0, z0 + oh)
    b.box('firebox_top', 'firebox', x0 + 0.03, xs - 0.005, -ow / 2 + lt, ow / 2 - lt,
          z0 + oh - lt, z0 + oh)
    b.box('firebox_floor', 'firebox', x0 + 0.03, xs - 0.005, -ow / 2 + lt, ow / 2 - lt, z0,
          z0 + 0.004)
    if s == 1:
        for yc in (-ow / 2 - 0.08, ow / 2 + 0.08):
            b.box('pilaster', 'wood_white', xs, xs + 0.025, yc - 0.06, yc + 0.06, z0, H - 0.05)
    fx = (x0 + 0.03 + xs) / 2 - 0.01
    fr = max(0.025, min(0.08, (xs - x0 - 0.06) / 2 - 0.015))
    for dz in (0.0, 0.05):
        b.seg('log', 'bark', (fx - 0.02, -ow * 0.3, z0 + 0.04 + dz),
              (fx + 0.02, ow * 0.3, z0 + 0.05 + dz), min(0.035, fr * 0.7), n=10)
    if s != 1:
        b.lathe('fire', 'fire', [(0, z0 + 0.08), (fr, z0 + 0.08), (0, z0 + 0.08 + oh * 0.45)],
                fx, 0.0, ey=min(2.5, ow * 0.3 / fr), n=12)
    b.box('fender', 'metal_dark', xs - 0.025, xs - 0.012, -ow / 2 + lt, ow / 2 - lt, z0 + 0.004,
          z0 + 0.12)
