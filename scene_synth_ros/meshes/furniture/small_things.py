"""Builders for small things that stand on surfaces: plants, books, vases, toys, fishbowls,
cups, glasses, bottles and fruit bowls.

Builders sketch in the object frame of ``meshes.builder`` and declare their categories with
``@builds``.
"""
from __future__ import annotations

import math

import numpy as np

from ..builder import Builder, builds, rot_x, rot_y, rot_z
from ..materials import BOOK_COVERS


@builds('plant')
def plant(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    pot = b.pick('terracotta', 'ceramic', 'plastic_black')
    ph = 0.33 * H if s != 1 else 0.28 * H
    pr = 0.62 * R
    b.frustum('pot', pot, 0, 0, 0.0, ph, pr * 0.75, pr, n=20)
    b.ring('pot_rim', pot, 0, 0, ph - 0.02, ph, pr * 0.9, pr * 1.05, n=20)
    b.cyl('soil', 'soil', 0, 0, ph - 0.015, ph - 0.005, pr * 0.92, n=16)
    if s == 0:
        fh = H - ph
        blobs = [(0.0, 0.0, 0.15, 0.62), (0.42, 0.22, 0.3, 0.5), (-0.4, 0.3, 0.35, 0.5),
                 (0.12, -0.45, 0.3, 0.5), (-0.25, -0.2, 0.7, 0.45), (0.25, 0.2, 0.8, 0.42),
                 (0.0, 0.0, 1.0, 0.4)]
        rz = fh * 0.3
        for k, (bx, by, bz, br) in enumerate(blobs):
            rh = br * R
            zc = ph + rz * 0.6 + (fh - rz * 1.6) * bz
            centre = (bx * R * 0.9, by * R * 0.9, zc)
            b.seg('stem', 'leaf_dark', (0, 0, ph - 0.01), centre, 0.006, n=5)
            b.sphere('foliage', ('leaf', 'leaf_dark', 'leaf_light')[k % 3], centre, (rh, rh, rz),
                     subdiv=1)
    elif s == 1:
        n = 9
        for k in range(n):
            a = 2 * math.pi * k / n + 0.3
            lean = 0.18 + 0.08 * (k % 3)
            length = (H - ph) * (0.75 + 0.25 * ((k * 5) % 3) / 2)
            base = np.array([pr * 0.35 * math.cos(a), pr * 0.35 * math.sin(a), ph - 0.01])
            b.obox('leaf', ('leaf', 'leaf_dark', 'leaf_light')[k % 3],
                   base + (0, 0, length / 2), (0.008, 0.035, length), rot_z(a))
            # lean the blade outwards, away from the pot's axis
            b.transform_last(1, rot_z(a) @ rot_y(lean) @ rot_z(-a), pivot=base)
    else:
        b.cyl('trunk', 'bark', 0, 0, ph - 0.01, ph + (H - ph) * 0.5, 0.012, n=8)
        for k, (bx, by, bz, br) in enumerate([(0, 0, 0.7, 0.75), (0.35, 0.2, 0.62, 0.5),
                                              (-0.3, -0.25, 0.66, 0.5)]):
            zc = ph + (H - ph) * bz
            r = br * R
            b.sphere('crown', ('leaf_dark', 'leaf', 'leaf_light')[k], (bx * R, by * R, zc),
                     (r, r, min(r, (H - ph) * 0.3)), subdiv=1)


@builds('book')
def book(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    n = 1 if H < 0.06 else max(2, int(round(H / 0.045)))
    th = H / n
    z = 0.0
    for k in range(n):
        cover = BOOK_COVERS[(k * 3 + s) % len(BOOK_COVERS)]
        if n == 1:
            bw, bd, dx, dy, yaw = W, D, 0.0, 0.0, 0.0
        else:
            bw = W * b.rng.uniform(0.78, 0.95)
            bd = D * b.rng.uniform(0.78, 0.95)
            dx = b.rng.uniform(-1, 1) * (D - bd) / 2
            dy = b.rng.uniform(-1, 1) * (W - bw) / 2
            yaw = b.rng.uniform(-0.08, 0.08)
        c = min(0.004, th * 0.15)
        hx, hy = bd / 2, bw / 2
        b.box('cover', cover, -hx, hx - 0.004, -hy, hy, z, z + c)
        b.box('cover', cover, -hx, hx - 0.004, -hy, hy, z + th - c, z + th)
        b.box('spine', cover, -hx, -hx + 0.006, -hy, hy, z, z + th)
        b.box('pages', 'paper', -hx + 0.006, hx, -hy + 0.004, hy - 0.004, z + c, z + th - c)
        if n > 1:
            b.transform_last(4, rot_z(yaw), shift=(dx, dy, 0.0))
        z += th


@builds('vase')
def vase(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    if s == 0:
        vh = 0.62 * H
        mat = 'blue'
        b.lathe('body', mat, [(0, 0), (R * 0.45, 0), (R * 0.7, vh * 0.35), (R * 0.5, vh * 0.75),
                              (R * 0.3, vh * 0.9), (0, vh * 0.9)], n=20)
        b.ring('lip', mat, 0, 0, vh * 0.88, vh, R * 0.24, R * 0.36, n=16)
        colours = ('red', 'yellow', 'purple', 'orange', 'paper')
        for k in range(5):
            a = 2 * math.pi * k / 5
            tip = np.array([R * 0.8 * math.cos(a), R * 0.8 * math.sin(a),
                            H - 0.03 - 0.03 * (k % 2)])
            b.seg('stem', 'leaf_dark', (0, 0, vh * 0.6), tip, 0.003, n=5)
            b.sphere('flower', colours[k], tip, (0.025, 0.025, 0.02))
    elif s == 1:
        mat = 'ceramic'
        b.frustum('body', mat, 0, 0, 0.0, H - 0.02, R * 0.62, R * 0.9, n=20)
        b.ring('lip', mat, 0, 0, H - 0.03, H, R * 0.8, R, n=20)
        b.ring('foot', 'wood_dark', 0, 0, 0.0, 0.012, R * 0.5, R * 0.66, n=20)
        b.cyl('opening', 'shadow', 0, 0, H - 0.02, H - 0.015, R * 0.8, n=16)
    else:
        mat = 'terracotta'
        b.lathe('body', mat, [(0, 0), (R * 0.35, 0), (R * 0.6, H * 0.12), (R * 0.75, H * 0.45),
                              (R * 0.4, H * 0.75), (0, H * 0.75)], n=20)
        b.frustum('neck', mat, 0, 0, H * 0.72, H, R * 0.28, R * 0.4, n=16)
        for sgn in (-1, 1):
            b.torus('handle', mat, (0, sgn * R * 0.5, H * 0.7), R * 0.22, R * 0.05,
                    rot=rot_y(math.pi / 2), n=12, m=5)


@builds('toy')
def toy(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    kind = ('teddy', 'blocks', 'car')[s]
    if kind == 'teddy' and H < 0.8 * max(W, D):
        kind = 'car'
    elif kind == 'car' and H > 1.2 * min(W, D):
        kind = 'teddy'
    if kind == 'teddy':
        # sitting teddy bear facing +x, in unit proportions scaled to the box at the end
        fur, light = 'fur', 'fur_light'
        b.sphere('body', fur, (0, 0, 0.32), (0.26, 0.3, 0.32), subdiv=2)
        b.sphere('head', fur, (0.04, 0, 0.8), (0.22, 0.24, 0.22), subdiv=2)
        for sgn in (-1, 1):
            b.sphere('ear', fur, (0.0, sgn * 0.18, 0.98), (0.06, 0.08, 0.08))
            b.sphere('arm', fur, (0.12, sgn * 0.3, 0.4), (0.1, 0.1, 0.18))
            b.sphere('leg', fur, (0.22, sgn * 0.16, 0.1), (0.2, 0.11, 0.1))
            b.sphere('eye', 'keys_black', (0.22, sgn * 0.08, 0.86), 0.025, subdiv=0)
            b.sphere('paw', light, (0.41, sgn * 0.16, 0.1), (0.02, 0.07, 0.07))
        b.sphere('muzzle', light, (0.22, 0, 0.76), (0.07, 0.09, 0.07))
        b.sphere('nose', 'keys_black', (0.29, 0, 0.79), 0.025, subdiv=0)
        b.sphere('tummy', light, (0.2, 0, 0.3), (0.08, 0.18, 0.2))
    elif kind == 'blocks':
        # a small pile of toy blocks: a 2 x 2 layer, then two, then one
        colours = ('red', 'blue', 'yellow', 'green', 'orange', 'purple', 'teal')
        layers = int(min(3, max(1, round(H / (min(W, D) / 2.1)))))
        spots = [[(-0.52, -0.52), (-0.52, 0.52), (0.52, -0.52), (0.52, 0.52)],
                 [(0.0, -0.52), (0.0, 0.52)], [(0.0, 0.0)]][:layers]
        k = 0
        for r, layer in enumerate(spots):
            for xc, yc in layer:
                b.box('block', colours[k % len(colours)], xc - 0.5, xc + 0.5, yc - 0.5, yc + 0.5,
                      r, r + 1.0)
                b.transform_last(1, rot_z(0.1 * ((k * 7) % 3 - 1)), pivot=(xc, yc, 0))
                k += 1
    else:
        # toy car facing +x
        b.box('body', 'red', -0.5, 0.5, -0.32, 0.32, 0.15, 0.42)
        b.box('cabin', 'glass_dark', -0.28, 0.15, -0.27, 0.27, 0.42, 0.68)
        b.box('roof', 'red', -0.3, 0.12, -0.28, 0.28, 0.66, 0.72)
        for xc in (-0.32, 0.32):
            for sgn in (-1, 1):
                b.seg('wheel', 'rubber', (xc, sgn * 0.28, 0.15), (xc, sgn * 0.4, 0.15), 0.15,
                      n=14)
        for sgn in (-1, 1):
            b.box('headlight', 'yellow', 0.5, 0.52, sgn * 0.22 - 0.05, sgn * 0.22 + 0.05, 0.3,
                  0.36)


@builds('fishbowl')
def fishbowl(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    R = min(W, D) / 2
    ey = W / D if D < W else 1.0
    if s == 2:
        b.box('tank', 'glass', x0 + 0.002, x1 - 0.002, y0 + 0.002, y1 - 0.002, 0.001, H - 0.001)
        b.box('water', 'water', x0 + 0.006, x1 - 0.006, y0 + 0.006, y1 - 0.006, 0.025, H * 0.85)
        b.box('gravel', 'gravel', x0 + 0.006, x1 - 0.006, y0 + 0.006, y1 - 0.006, 0.006, 0.025)
        for z0, z1 in ((0.0, 0.006), (H - 0.008, H)):
            for ya, yb in ((y0, y0 + 0.008), (y1 - 0.008, y1)):
                b.box('frame', 'plastic_black', x0, x1, ya, yb, z0, z1)
            for xa, xb in ((x0, x0 + 0.008), (x1 - 0.008, x1)):
                b.box('frame', 'plastic_black', xa, xb, y0, y1, z0, z1)
    else:
        prof = [(0, 0), (R * 0.55, 0), (R * 0.9, H * 0.2), (R, H * 0.5), (R * 0.9, H * 0.8),
                (R * 0.62, H), (0, H)]
        b.lathe('bowl', 'glass', prof, 0, 0, ey, n=24)
        b.lathe('water', 'water', [(0, 0.008), (R * 0.52, 0.008), (R * 0.86, H * 0.2),
                                   (R * 0.95, H * 0.5), (R * 0.87, H * 0.75), (0, H * 0.75)],
                0, 0, ey, n=24)
        b.cyl('gravel', 'gravel', 0, 0, 0.008, 0.025, R * 0.55, R * 0.55 * ey, n=16)
        b.ring('rim', 'glass', 0, 0, H - 0.006, H, R * 0.58, R * 0.66, ey=ey, n=24)
    fx, fz = 0.0, H * 0.45
    b.sphere('fish', 'orange', (fx, 0.0, fz), (0.025, 0.011, 0.016))
    b.lathe('fish_tail', 'orange', [(0, 0), (0.014, 0), (0, 0.02)], 0, 0, 0.3, n=6,
            rot=rot_y(-math.pi / 2))
    b.transform_last(1, shift=(fx - 0.02, 0.0, fz))
    for k in range(3):
        b.obox('weed', 'leaf', (R * 0.3 * (k - 1) * 0.8, R * 0.2, 0.025 + H * 0.15),
               (0.004, 0.012, H * 0.3), rot_x(0.15 * (k - 1)))


@builds('cup')
def cup(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    r = min(D / 2, W * 0.39)
    yc = -W / 2 + r
    z0 = 0.0
    if s == 1:
        b.cyl('saucer', 'ceramic', 0, yc, 0.0, 0.008, r * 1.0, n=20)
        z0 = 0.008
        r *= 0.82
    mat = b.pick('ceramic', 'ceramic', 'red')
    top = H
    if s == 2:
        b.lathe('body', mat, [(0, z0), (r, z0), (r, top), (r * 0.88, top), (r * 0.88, z0 + 0.01),
                              (0, z0 + 0.01)], 0, yc, n=20)
    else:
        b.lathe('body', mat, [(0, z0), (r * 0.7, z0), (r, top), (r * 0.9, top),
                              (r * 0.62, z0 + 0.01), (0, z0 + 0.01)], 0, yc, n=20)
    b.cyl('coffee', 'liquid_dark', 0, yc, top - 0.022, top - 0.014, r * (0.86 if s == 2 else 0.8),
          n=16)
    minor = 0.006
    hy = yc + r * 0.85
    major = max(0.006, W / 2 - hy - minor)
    zscale = max(1.0, (top - z0) * 0.3 / major)
    b.torus('handle', mat, (0, hy, z0 + (top - z0) * 0.5), major, minor,
            rot=rot_y(math.pi / 2), n=12, m=6, scale=(1.0, 1.0, zscale))


@builds('glass')
def glass(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    if s == 1:
        # wine glass
        b.cyl('foot', 'glass', 0, 0, 0.0, 0.004, R * 0.8, n=20)
        stem = H * 0.4
        b.cyl('stem', 'glass', 0, 0, 0.004, stem, 0.0045, n=8)
        b.lathe('bowl', 'glass', [(0, stem), (R * 0.7, stem + H * 0.1), (R, stem + H * 0.3),
                                  (R * 0.85, H), (0, H)], n=20)
        b.lathe('wine', 'wine', [(0, stem + 0.005), (R * 0.66, stem + H * 0.1),
                                 (R * 0.92, stem + H * 0.25), (0, stem + H * 0.25)], n=16)
    else:
        b.cyl('base', 'glass', 0, 0, 0.0, 0.012, R * 0.88, n=20)
        b.frustum('wall', 'glass', 0, 0, 0.0, H, R * 0.9, R, n=20)
        b.cyl('liquid', 'water' if s == 0 else 'citrus', 0, 0, 0.012, H * 0.65, R * 0.85, n=16)
        if s == 2:
            for k in range(2):
                c = R * 0.55
                b.box('ice', 'glass', -c / 2, c / 2, -c / 2, c / 2, 0.0, c)
                b.transform_last(1, rot_z(0.4 + k) @ rot_x(0.3),
                                 shift=(R * 0.2 * (k * 2 - 1), R * 0.1, H * 0.58 - c / 2))


@builds('bottle')
def bottle(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    if s == 0:
        # wine bottle: high shoulders, long neck sealed with foil
        sh = 0.6 * H
        b.lathe('body', 'bottle_green', [(0, 0), (R * 0.97, 0), (R, sh), (R * 0.6, sh + 0.07 * H),
                                         (R * 0.3, sh + 0.14 * H), (R * 0.28, H * 0.96),
                                         (0, H * 0.96)], n=20)
        b.cyl('foil', 'red', 0, 0, H * 0.84, H, R * 0.33, n=16)
        b.cyl('label', 'paper', 0, 0, H * 0.18, H * 0.45, R * 1.012, n=20)
    elif s == 1:
        # plastic water bottle with moulded rings and a screw cap
        sh = 0.78 * H
        b.lathe('body', 'water', [(0, 0), (R * 0.95, 0), (R, 0.04 * H), (R, sh),
                                  (R * 0.42, sh + 0.12 * H), (R * 0.35, H * 0.93), (0, H * 0.93)],
                n=20)
        for z in (0.3 * H, 0.55 * H):
            b.ring('ring', 'water', 0, 0, z, z + 0.006, R * 0.9, R, n=20)
        b.cyl('cap', 'blue', 0, 0, H * 0.92, H, R * 0.4, n=16)
        b.cyl('label', 'blue', 0, 0, H * 0.36, H * 0.5, R * 1.012, n=20)
    else:
        # beer bottle: rounded shoulders, crown cap, neck label
        sh = 0.55 * H
        b.lathe('body', 'bottle_brown', [(0, 0), (R * 0.97, 0), (R, sh), (R * 0.8, sh + 0.06 * H),
                                         (R * 0.38, sh + 0.17 * H), (R * 0.32, H * 0.95),
                                         (0, H * 0.95)], n=20)
        b.cyl('cap', 'metal', 0, 0, H * 0.94, H, R * 0.36, n=12)
        b.cyl('label', 'yellow', 0, 0, H * 0.15, H * 0.42, R * 1.012, n=20)
        b.cyl('neck_label', 'yellow', 0, 0, H * 0.8, H * 0.86, R * 0.36, n=16)


@builds('fruit bowl')
def fruit_bowl(b: Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    R = min(W, D) / 2
    ey = W / D if D < W else 1.0
    mat = b.pick('wood', 'ceramic', 'metal')
    bh = 0.5 * H
    b.lathe('bowl', mat, [(0, 0), (R * 0.45, 0), (R * 0.92, bh * 0.7), (R, bh), (R * 0.93, bh),
                          (R * 0.85, bh * 0.72), (R * 0.4, bh * 0.2), (0, bh * 0.2)], 0, 0, ey,
            n=24)
    b.ring('foot', mat, 0, 0, 0.0, 0.006, R * 0.35, R * 0.45, ey=ey, n=16)
    z0 = bh * 0.2
    rf = min(R * 0.3, (H - z0) / 2)
    if s == 0:
        fruits = ('apple', 'citrus', 'apple', 'lemon', 'citrus')
        for k in range(4):
            a = 2 * math.pi * k / 4 + 0.4
            b.sphere('fruit', fruits[k], (R * 0.42 * math.cos(a), R * 0.42 * math.sin(a) * ey,
                                          z0 + rf * 0.95), rf, subdiv=1)
        b.sphere('fruit', fruits[4], (0.0, 0.0, H - rf), rf * 0.95, subdiv=1)
        b.seg('stalk', 'bark', (0, 0, H - 0.01), (0.005, 0.0, H), 0.003, n=5)
    elif s == 1:
        # a bunch of bananas lying across two apples
        for a in (0.5, 2.6):
            b.sphere('fruit', 'apple', (R * 0.4 * math.cos(a), R * 0.4 * math.sin(a) * ey,
                                        z0 + rf * 0.95), rf, subdiv=1)
        rb = min(0.018, (H - z0) / 5)
        for k in range(3):
            yc = (k - 1) * rb * 2.1
            zc = H - rb - (0 if k == 1 else rb * 0.6)
            b.seg('banana', 'lemon', (-R * 0.75, yc - 0.02, zc - rb), (0.0, yc, zc), rb, n=8)
            b.seg('banana', 'lemon', (0.0, yc, zc), (R * 0.75, yc - 0.02, zc - rb), rb, n=8)
        b.seg('banana_stem', 'bark', (R * 0.75, -0.02, H - 2.3 * rb), (R * 0.85, -0.02,
                                                                         H - 1.8 * rb), rb * 0.5,
              n=6)
    else:
        # a cluster of grapes and a pear-shaped lemon
        rg = min(0.012, (H - z0) / 6)
        for layer, (n, rad) in enumerate(((7, R * 0.5), (5, R * 0.32), (1, 0.0))):
            zc = z0 + rg + layer * rg * 1.6
            for i in range(n):
                a = 2 * math.pi * i / n + 0.3 * layer
                b.sphere('grape', 'grape', (rad * math.cos(a) - R * 0.15, rad * math.sin(a) * ey,
                                            zc), rg, subdiv=0)
        b.sphere('fruit', 'lemon', (R * 0.45, -R * 0.2 * ey, H - rf), (rf * 1.1, rf * 0.9, rf),
                 subdiv=1)
