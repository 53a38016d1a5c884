"""Pictures of catalog models for people: a rendered image, a labelled PNG per model and a
contact sheet of many.

matplotlib's 3D axes sort whole polygons back to front, which goes wrong for layered
furniture (a door 2 cm in front of a carcass). ``render_image`` therefore rasterises the
mesh itself with a small z-buffer (orthographic, flat shading, part outlines, alpha-blended
glass), and matplotlib only lays out and saves the images; it is imported inside the
functions that need it, so importing the meshes package stays cheap.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import Sequence

import numpy as np

from .. import catalog
from ..catalog import ModelVariant
from ..categories import CATEGORIES
from .materials import MATERIALS
from .registry import build_parts


def _view_basis(elev: float, azim: float):
    e, a = math.radians(elev), math.radians(azim)
    eye = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
    right = np.cross([0.0, 0.0, 1.0], eye)
    right /= np.linalg.norm(right)
    up = np.cross(eye, right)
    return eye, right, up


def render_image(variant: ModelVariant, px: int = 320, elev: float = 22.0,
                 azim: float = 32.0) -> np.ndarray:
    """An RGB float image (px x px, row 0 at the top) of ``variant`` seen from the front
    three-quarter direction (camera on the +x, +y side, ``elev`` degrees up)."""
    eye, right, up = _view_basis(elev, azim)
    light = eye + np.array([0.3, -0.2, 0.8])
    light /= np.linalg.norm(light)
    parts = build_parts(variant)
    allv = np.vstack([p.vertices for p in parts])
    uv_all = np.column_stack((allv @ right, allv @ up))
    lo, hi = uv_all.min(axis=0), uv_all.max(axis=0)
    scale = 0.9 * px / max(hi[0] - lo[0], hi[1] - lo[1])
    offset = px / 2.0 - scale * (lo + hi) / 2.0
    img = np.ones((px, px, 3))
    zbuf = np.full((px, px), -np.inf)
    ids = np.full((px, px), -1)
    glass = []

    def raster(tri_uv, z, on_pixels):
        (x0, y0), (x1, y1), (x2, y2) = tri_uv
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if abs(area) < 1e-9:
            return
        cmin = max(int(math.floor(min(x0, x1, x2))), 0)
        cmax = min(int(math.ceil(max(x0, x1, x2))), px - 1)
        rmin = max(int(math.floor(min(y0, y1, y2))), 0)
        rmax = min(int(math.ceil(max(y0, y1, y2))), px - 1)
        if cmin > cmax or rmin > rmax:
            return
        xs = np.arange(cmin, cmax + 1) + 0.5
        ys = np.arange(rmin, rmax + 1) + 0.5
        gx, gy = np.meshgrid(xs, ys)
        w0 = ((x1 - gx) * (y2 - gy) - (x2 - gx) * (y1 - gy)) / area
        w1 = ((x2 - gx) * (y0 - gy) - (x0 - gx) * (y2 - gy)) / area
        w2 = 1.0 - w0 - w1
        inside = (w0 >= -1e-6) & (w1 >= -1e-6) & (w2 >= -1e-6)
        if not inside.any():
            return
        depth = w0 * z[0] + w1 * z[1] + w2 * z[2]
        on_pixels(slice(rmin, rmax + 1), slice(cmin, cmax + 1), inside, depth)

    for pid, p in enumerate(parts):
        mat = MATERIALS[p.material]
        rgba = np.array(mat.rgba, float) / 255.0
        tri = p.vertices[p.faces]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1), 1e-12)[:, None]
        shade = 0.42 + 0.58 * np.clip(n @ light, 0.0, 1.0)
        uv = np.stack((tri @ right, tri @ up), axis=-1) * scale + offset
        z = tri @ eye
        for k in range(len(tri)):
            if mat.transparent:
                glass.append((float(z[k].mean()), uv[k], z[k], rgba, shade[k]))
                continue
            if n[k] @ eye <= 0.0:
                continue
            colour = rgba[:3] * shade[k]

            def write(rs, cs, inside, depth, colour=colour, pid=pid):
                closer = inside & (depth > zbuf[rs, cs])
                zbuf[rs, cs][closer] = depth[closer]
                img[rs, cs][closer] = colour
                ids[rs, cs][closer] = pid
            raster(uv[k], z[k], write)
    # outlines where the visible part changes or the depth jumps
    edge = np.zeros((px, px), bool)
    size = max(variant.size)
    zfin = np.where(np.isfinite(zbuf), zbuf, -1e3 * size)
    for axis in (0, 1):
        dz = np.abs(zfin - np.roll(zfin, 1, axis=axis))
        other = ids != np.roll(ids, 1, axis=axis)
        edge |= (other & (dz > 2e-3 * size)) | (dz > 0.03 * size)
    edge &= (ids >= 0) | np.roll(ids >= 0, 1, 0) | np.roll(ids >= 0, 1, 1)
    img[edge] *= 0.55
    for _, tri_uv, z, rgba, sh in sorted(glass, key=lambda g: g[0]):
        colour = rgba[:3] * (0.75 + 0.25 * sh)
        alpha = max(0.25, rgba[3] * 0.7)

        def blend(rs, cs, inside, depth, colour=colour, alpha=alpha):
            front = inside & (depth > zbuf[rs, cs])
            img[rs, cs][front] = img[rs, cs][front] * (1 - alpha) + colour * alpha
        raster(tri_uv, z, blend)
    return np.clip(img[::-1], 0.0, 1.0)


def render_preview(variant: ModelVariant, path: str | Path, size_px: int = 400) -> Path:
    """Draw ``variant`` from a front three-quarter view (camera on the +x, +y side, a
    little above) into a labelled PNG, using matplotlib's Agg backend."""
    import matplotlib  # heavy: every export loads meshes/, only previews draw
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt  # after use('Agg'): no display needed

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig = plt.figure(figsize=(size_px / 100, size_px / 100 + 0.3), dpi=100)
    ax = fig.add_axes((0.0, 0.0, 1.0, size_px / (size_px + 30.0)))
    ax.imshow(render_image(variant, px=size_px * 2), interpolation='antialiased')
    ax.set_axis_off()
    fig.suptitle(f'{variant.category} ({variant.model_id})', fontsize=9, y=0.99)
    fig.savefig(path)
    plt.close(fig)
    return path


def save_contact_sheet(path: str | Path, variants: Sequence[ModelVariant] | None = None,
                       columns: int = 8, panel_px: int = 200) -> Path:
    """A labelled grid of previews, by default one variant per category (styles mixed)."""
    import matplotlib  # heavy: every export loads meshes/, only previews draw
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt  # after use('Agg'): no display needed

    if variants is None:
        variants = [catalog.variants(c)[3 + i % 3] for i, c in enumerate(CATEGORIES)]
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    rows = math.ceil(len(variants) / columns)
    dpi = 100
    fig = plt.figure(figsize=(columns * panel_px / dpi, rows * (panel_px + 26) / dpi), dpi=dpi)
    for i, v in enumerate(variants):
        ax = fig.add_subplot(rows, columns, i + 1)
        ax.imshow(render_image(v, px=panel_px * 2), interpolation='antialiased')
        ax.set_axis_off()
        ax.set_title(f'{v.category}\n{v.model_id}', fontsize=7, pad=1)
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=0.97, wspace=0.02, hspace=0.18)
    fig.savefig(path)
    plt.close(fig)
    return path
