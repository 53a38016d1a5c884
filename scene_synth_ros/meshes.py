"""Low-poly meshes for the catalog models, their export, and whole scenes as trimesh scenes.

Every model is put together from primitives (boxes, cylinders, spheres, surfaces of
revolution) in the package's object frame: front towards +x, width along y, depth along x,
origin at the centre of the footprint on the floor. After assembly the parts are mapped onto
the variant's box, so the axis-aligned bounds of every mesh are exactly
``x in [-depth/2, depth/2]``, ``y in [-width/2, width/2]``, ``z in [0, height]``.

Each part carries a material name (see ``MATERIALS``). ``build_mesh`` returns one mesh with
per-vertex colours; the exporters write one primitive per material instead (glTF PBR
materials for ``.glb``, an ``.mtl`` file for ``.obj``), which is what simulators and viewers
read most reliably.

Coordinates are the package's (REP-103): metres, z up. Exported files keep that frame; a
glTF consumer that insists on glTF's y-up convention must add its own root rotation.

Public API: ``build_parts`` (named single-material parts), ``build_mesh`` (one vertex-coloured
mesh), ``model_scene`` / ``export_model`` / ``export_catalog`` / ``mesh_path`` (files),
``scene_mesh`` / ``object_transform`` / ``variant_for`` (whole scenes), ``render_image`` /
``render_preview`` / ``save_contact_sheet`` (pictures for people), ``MATERIALS``.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
import math
from pathlib import Path
from typing import Callable, Iterable, Sequence
import zlib

import numpy as np
import trimesh
from trimesh import creation

from . import catalog
from .catalog import ModelVariant
from .categories import CATEGORIES

# ---------------------------------------------------------------------------------------
# materials


@dataclass(frozen=True)
class Material:
    """A plain PBR material: base colour (RGBA, 0-255), metallic and roughness factors."""

    name: str
    rgba: tuple[int, int, int, int]
    metallic: float = 0.0
    roughness: float = 0.7

    @property
    def transparent(self) -> bool:
        return self.rgba[3] < 255


def _m(name, r, g, b, a=255, metallic=0.0, roughness=0.7):
    return Material(name, (r, g, b, a), metallic, roughness)


MATERIALS: dict[str, Material] = {m.name: m for m in (
    _m('wood', 150, 105, 65), _m('wood_light', 206, 170, 122), _m('wood_dark', 92, 60, 38),
    _m('wood_white', 236, 233, 226, roughness=0.5), _m('paint_grey', 118, 122, 128),
    _m('paint_cream', 228, 218, 196, roughness=0.5), _m('shadow', 42, 36, 32, roughness=0.9),
    _m('fabric_grey', 122, 126, 134, roughness=0.95),
    _m('fabric_grey_light', 178, 180, 184, roughness=0.95),
    _m('fabric_dark', 48, 50, 56, roughness=0.95), _m('fabric_blue', 64, 92, 140, roughness=0.95),
    _m('fabric_beige', 204, 188, 158, roughness=0.95),
    _m('fabric_green', 86, 124, 94, roughness=0.95), _m('fabric_red', 152, 58, 52, roughness=0.95),
    _m('fabric_mustard', 214, 160, 52, roughness=0.95),
    _m('leather', 112, 68, 42, roughness=0.5), _m('leather_black', 30, 30, 32, roughness=0.45),
    _m('mattress', 242, 240, 232, roughness=0.95), _m('linen', 252, 252, 250, roughness=0.95),
    _m('blanket_blue', 150, 178, 212, roughness=0.95),
    _m('blanket_rose', 214, 170, 160, roughness=0.95),
    _m('blanket_green', 160, 190, 150, roughness=0.95),
    _m('metal', 172, 175, 180, metallic=0.8, roughness=0.35),
    _m('chrome', 214, 216, 220, metallic=1.0, roughness=0.15),
    _m('metal_dark', 58, 60, 66, metallic=0.6, roughness=0.45),
    _m('brass', 200, 160, 70, metallic=0.9, roughness=0.3),
    _m('plastic_black', 34, 34, 38, roughness=0.5),
    _m('plastic_white', 240, 240, 236, roughness=0.4),
    _m('plastic_grey', 150, 152, 156, roughness=0.5), _m('rubber', 28, 28, 28, roughness=0.9),
    _m('ceramic', 246, 246, 244, roughness=0.15),
    _m('ceramic_shadow', 200, 208, 214, roughness=0.15),
    _m('screen', 14, 16, 24, roughness=0.1), _m('screen_on', 40, 70, 110, roughness=0.1),
    _m('glass', 196, 222, 234, 90, roughness=0.05),
    _m('glass_dark', 40, 52, 64, 200, roughness=0.05),
    _m('mirror', 206, 220, 230, metallic=0.9, roughness=0.05),
    _m('water', 78, 150, 214, 140, roughness=0.05), _m('whiteboard', 252, 252, 252, roughness=0.2),
    _m('lacquer', 20, 20, 22, roughness=0.15), _m('lacquer_white', 244, 242, 238, roughness=0.15),
    _m('keys_white', 250, 250, 246, roughness=0.3), _m('keys_black', 16, 16, 16, roughness=0.3),
    _m('stone', 204, 198, 186, roughness=0.85), _m('brick', 150, 76, 56, roughness=0.9),
    _m('firebox', 26, 24, 24, roughness=0.9), _m('fire', 250, 130, 30, roughness=0.9),
    _m('leaf', 66, 132, 58, roughness=0.8), _m('leaf_dark', 38, 94, 44, roughness=0.8),
    _m('leaf_light', 112, 164, 70, roughness=0.8), _m('soil', 72, 52, 36, roughness=1.0),
    _m('terracotta', 182, 96, 60, roughness=0.9), _m('bark', 100, 70, 46, roughness=0.9),
    _m('shade', 246, 236, 212, roughness=0.9), _m('bulb', 255, 246, 214, roughness=0.3),
    _m('paper', 246, 242, 228, roughness=0.9),
    _m('red', 184, 46, 44, roughness=0.5), _m('blue', 46, 82, 160, roughness=0.5),
    _m('green', 52, 128, 72, roughness=0.5), _m('yellow', 230, 190, 60, roughness=0.5),
    _m('orange', 232, 124, 40, roughness=0.5), _m('purple', 112, 72, 144, roughness=0.5),
    _m('teal', 40, 140, 140, roughness=0.5),
    _m('fur', 168, 116, 70, roughness=1.0), _m('fur_light', 220, 186, 140, roughness=1.0),
    _m('apple', 192, 36, 36, roughness=0.4), _m('citrus', 244, 146, 28, roughness=0.6),
    _m('lemon', 240, 214, 60, roughness=0.6), _m('grape', 96, 40, 90, roughness=0.4),
    _m('bottle_green', 40, 96, 52, 220, roughness=0.1), _m('bottle_brown', 110, 60, 24, 230,
                                                              roughness=0.1),
    _m('liquid_dark', 70, 40, 20, roughness=0.2), _m('wine', 110, 18, 36, 220, roughness=0.1),
    _m('gravel', 176, 156, 124, roughness=1.0),
)}

BOOK_COVERS = ('red', 'blue', 'green', 'yellow', 'orange', 'purple', 'teal', 'wood_dark')

# ---------------------------------------------------------------------------------------
# primitives as (vertices, faces) arrays


@lru_cache(maxsize=None)
def _unit_box():
    m = creation.box(extents=(1.0, 1.0, 1.0))
    return np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)


@lru_cache(maxsize=None)
def _unit_cylinder(sections: int):
    """Radius 1, z from 0 to 1."""
    m = creation.cylinder(radius=1.0, height=1.0, sections=sections)
    v = np.asarray(m.vertices, float) + (0.0, 0.0, 0.5)
    return v, np.asarray(m.faces, np.int64)


@lru_cache(maxsize=None)
def _unit_sphere(subdivisions: int):
    m = creation.icosphere(subdivisions=subdivisions, radius=1.0)
    return np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)


@lru_cache(maxsize=None)
def _revolved(profile: tuple[tuple[float, float], ...], sections: int):
    m = creation.revolve(np.asarray(profile, float), sections=sections)
    v, f = np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)
    if _signed_volume(v, f) < 0:
        f = f[:, ::-1]
    return v, f


@lru_cache(maxsize=None)
def _unit_torus(minor_ratio: float, major_sections: int, minor_sections: int):
    m = creation.torus(1.0, minor_ratio, major_sections=major_sections,
                       minor_sections=minor_sections)
    return np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)


def _signed_volume(v: np.ndarray, f: np.ndarray) -> float:
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return float(np.einsum('ij,ij->i', a, np.cross(b, c)).sum() / 6.0)


def _rot_x(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def _rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def _rot_z(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def _align_z(d: np.ndarray) -> np.ndarray:
    """A rotation taking +z onto the unit vector ``d``."""
    z = np.array([0.0, 0.0, 1.0])
    d = d / np.linalg.norm(d)
    v = np.cross(z, d)
    c = float(np.dot(z, d))
    if np.linalg.norm(v) < 1e-12:
        return np.eye(3) if c > 0 else np.diag([1.0, -1.0, -1.0])
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])
    return np.eye(3) + k + k @ k * (1.0 / (1.0 + c))


# ---------------------------------------------------------------------------------------
# parts and the builder


@dataclass(frozen=True, eq=False)
class Part:
    """One named, single-material piece of a model (in the model's frame, metres)."""

    name: str
    material: str
    vertices: np.ndarray
    faces: np.ndarray

    def mesh(self) -> trimesh.Trimesh:
        m = trimesh.Trimesh(self.vertices.copy(), self.faces.copy(), process=False)
        m.visual.vertex_colors = MATERIALS[self.material].rgba
        return m

    @property
    def bounds(self) -> np.ndarray:
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    @property
    def centre(self) -> np.ndarray:
        return self.bounds.mean(axis=0)


class _Builder:
    """Collects parts in the model frame; ``finish`` maps them onto the variant's box."""

    def __init__(self, variant: ModelVariant):
        self.W, self.D, self.H = (float(s) for s in variant.size)
        self.s = int(variant.style) % 3
        self.x0, self.x1 = -self.D / 2.0, self.D / 2.0
        self.y0, self.y1 = -self.W / 2.0, self.W / 2.0
        self.rng = np.random.default_rng(zlib.crc32(variant.model_id.encode()))
        self.parts: list[list] = []

    def pick(self, *options):
        return options[self.s % len(options)]

    # -- adding geometry -----------------------------------------------------------------
    def add(self, name: str, mat: str, v: np.ndarray, f: np.ndarray) -> list:
        if mat not in MATERIALS:
            raise KeyError(f'unknown material {mat!r}')
        part = [name, mat, np.asarray(v, float), np.asarray(f, np.int64)]
        self.parts.append(part)
        return part

    def box(self, name, mat, x0, x1, y0, y1, z0, z1):
        lo = np.minimum((x0, y0, z0), (x1, y1, z1))
        hi = np.maximum((x0, y0, z0), (x1, y1, z1))
        ext = np.maximum(hi - lo, 1e-4)
        v, f = _unit_box()
        return self.add(name, mat, v * ext + (lo + hi) / 2.0, f)

    def obox(self, name, mat, centre, extents, rot):
        v, f = _unit_box()
        return self.add(name, mat, (v * np.asarray(extents, float)) @ np.asarray(rot).T
                        + np.asarray(centre, float), f)

    def cyl(self, name, mat, cx, cy, z0, z1, rx, ry=None, n=20):
        """Vertical (elliptic) cylinder."""
        v, f = _unit_cylinder(n)
        ry = rx if ry is None else ry
        return self.add(name, mat, v * (rx, ry, z1 - z0) + (cx, cy, z0), f)

    def seg(self, name, mat, p0, p1, r, n=12, r2=None):
        """Cylinder of radius ``r`` from ``p0`` to ``p1`` (elliptic if ``r2`` is given: ``r``
        then applies to the first axis perpendicular to the segment)."""
        p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
        d = p1 - p0
        length = float(np.linalg.norm(d))
        v, f = _unit_cylinder(n)
        local = v * (r, r if r2 is None else r2, length)
        return self.add(name, mat, local @ _align_z(d).T + p0, f)

    def xdisc(self, name, mat, x0, x1, cy, cz, r, rz=None, n=20):
        """Cylinder whose axis is along x (a disc facing +x), optionally elliptic."""
        v, f = _unit_cylinder(n)
        rz = r if rz is None else rz
        local = v * (rz, r, x1 - x0)            # local x -> world z, local z -> world x
        world = np.column_stack((local[:, 2] + x0, local[:, 1] + cy, -local[:, 0] + cz))
        return self.add(name, mat, world, f)

    def sphere(self, name, mat, c, radii, subdiv=1):
        v, f = _unit_sphere(subdiv)
        return self.add(name, mat, v * np.broadcast_to(np.asarray(radii, float), 3)
                        + np.asarray(c, float), f)

    def lathe(self, name, mat, profile, cx=0.0, cy=0.0, ey=1.0, n=20, rot=None):
        """Surface of revolution of ``profile`` [(r, z), ...] about a vertical axis through
        (cx, cy); ``ey`` scales the radius along y (elliptic section)."""
        v, f = _revolved(tuple((float(r), float(z)) for r, z in profile), n)
        v = v * (1.0, ey, 1.0)
        if rot is not None:
            v = v @ np.asarray(rot).T
        return self.add(name, mat, v + (cx, cy, 0.0), f)

    def frustum(self, name, mat, cx, cy, z0, z1, r0, r1, ey=1.0, n=20):
        return self.lathe(name, mat, [(0, z0), (r0, z0), (r1, z1), (0, z1)], cx, cy, ey, n)

    def ring(self, name, mat, cx, cy, z0, z1, r_in, r_out, ey=1.0, n=24):
        prof = [(r_in, z1), (r_in, z0), (r_out, z0), (r_out, z1), (r_in, z1)]
        return self.lathe(name, mat, prof, cx, cy, ey, n)

    def torus(self, name, mat, c, major, minor, rot=None, n=16, m=6, scale=(1.0, 1.0, 1.0)):
        v, f = _unit_torus(round(minor / major, 4), n, m)
        v = v * major
        if rot is not None:
            v = v @ np.asarray(rot).T
        return self.add(name, mat, v * np.asarray(scale, float) + np.asarray(c, float), f)

    def prism(self, name, mat, outline, z0, z1, cx=0.0, cy=0.0):
        """Vertical prism over a convex outline [(x, y), ...] given counter-clockwise."""
        pts = np.asarray(outline, float) + (cx, cy)
        k = len(pts)
        c = pts.mean(axis=0)
        v = np.vstack([np.column_stack((pts, np.full(k, z0))),
                       np.column_stack((pts, np.full(k, z1))),
                       [[c[0], c[1], z0], [c[0], c[1], z1]]])
        i = np.arange(k)
        j = (i + 1) % k
        cb, ct = 2 * k, 2 * k + 1
        f = np.vstack([np.column_stack((i, j, j + k)), np.column_stack((i, j + k, i + k)),
                       np.column_stack((np.full(k, ct), i + k, j + k)),
                       np.column_stack((np.full(k, cb), j, i))])
        if _signed_volume(v, f) < 0:
            f = f[:, ::-1]
        return self.add(name, mat, v, f)

    # -- editing -------------------------------------------------------------------------
    def transform_last(self, count: int, rot=None, pivot=(0, 0, 0), shift=(0, 0, 0)):
        """Rotate the last ``count`` parts about ``pivot`` then shift them."""
        pivot = np.asarray(pivot, float)
        for part in self.parts[-count:]:
            v = part[2] - pivot
            if rot is not None:
                v = v @ np.asarray(rot).T
            part[2] = v + pivot + np.asarray(shift, float)

    def finish(self) -> tuple[Part, ...]:
        allv = np.vstack([p[2] for p in self.parts])
        lo, hi = allv.min(axis=0), allv.max(axis=0)
        t_lo = np.array([self.x0, self.y0, 0.0])
        t_hi = np.array([self.x1, self.y1, self.H])
        scale = (t_hi - t_lo) / np.maximum(hi - lo, 1e-9)
        out = []
        for name, mat, v, f in self.parts:
            v = (v - lo) * scale + t_lo
            v = np.clip(v, t_lo, t_hi)
            v.setflags(write=False)
            f = f.copy()
            f.setflags(write=False)
            out.append(Part(name, mat, v, f))
        return tuple(out)


def _rounded_rect(hx: float, hy: float, r: float, per_corner: int = 6) -> np.ndarray:
    """Counter-clockwise outline of a rectangle (half sizes hx, hy) with corner radius r;
    r = min(hx, hy) gives a stadium."""
    r = min(r, hx, hy)
    pts = []
    for (cx, cy, a0) in ((hx - r, hy - r, 0.0), (-hx + r, hy - r, 90.0),
                         (-hx + r, -hy + r, 180.0), (hx - r, -hy + r, 270.0)):
        for t in np.linspace(a0, a0 + 90.0, per_corner + 1):
            pts.append((cx + r * math.cos(math.radians(t)), cy + r * math.sin(math.radians(t))))
    out = [pts[0]]
    for p in pts[1:]:
        if math.dist(p, out[-1]) > 1e-9:
            out.append(p)
    if math.dist(out[0], out[-1]) < 1e-9:
        out.pop()
    return np.asarray(out)


HANDLE = 0.014     # how far handles and knobs stand proud of a front
FRONT = 0.018      # thickness of door and drawer fronts


def _drawer(b: _Builder, mat, hmat, y0, y1, z0, z1, xf, handle='bar', gap=0.004):
    """A drawer front in the plane just behind ``xf`` with its handle reaching ``xf``."""
    b.box('drawer', mat, xf - HANDLE - FRONT, xf - HANDLE, y0 + gap, y1 - gap, z0 + gap, z1 - gap)
    yc, zc = (y0 + y1) / 2.0, (z0 + z1) / 2.0
    if handle == 'bar':
        hw = min(0.16, 0.4 * (y1 - y0))
        b.box('handle', hmat, xf - HANDLE, xf, yc - hw / 2, yc + hw / 2, zc - 0.008, zc + 0.008)
    elif handle == 'knob':
        b.seg('handle', hmat, (xf - HANDLE, yc, zc), (xf, yc, zc), 0.013, n=10)
    elif handle == 'knobs':
        for yk in (y0 + (y1 - y0) * 0.25, y0 + (y1 - y0) * 0.75):
            b.seg('handle', hmat, (xf - HANDLE, yk, zc), (xf, yk, zc), 0.012, n=10)
    elif handle == 'top':
        hw = min(0.2, 0.6 * (y1 - y0))
        b.box('handle', hmat, xf - HANDLE, xf, yc - hw / 2, yc + hw / 2, z1 - gap - 0.03,
              z1 - gap - 0.015)


def _door(b: _Builder, mat, hmat, y0, y1, z0, z1, xf, handle_side=+1, handle_z=None,
          gap=0.004, handle_len=None):
    """A door panel; a vertical bar handle near the y1 edge (``handle_side`` +1) or the y0
    edge (-1)."""
    b.box('door', mat, xf - HANDLE - FRONT, xf - HANDLE, y0 + gap, y1 - gap, z0 + gap, z1 - gap)
    hl = handle_len if handle_len is not None else min(0.28, 0.35 * (z1 - z0))
    if handle_z is None:
        handle_z = min(max(1.0, z0 + hl), z1 - hl * 0.6 - 0.05) if z1 - z0 > 0.9 \
            else z1 - 0.06 - hl / 2
    handle_z = min(max(handle_z, z0 + hl / 2 + 0.02), z1 - hl / 2 - 0.02)
    yh = y1 - 0.045 if handle_side > 0 else y0 + 0.045
    b.box('handle', hmat, xf - HANDLE, xf, yh - 0.009, yh + 0.009, handle_z - hl / 2,
          handle_z + hl / 2)


def _legs_box(b: _Builder, mat, x0, x1, y0, y1, z0, z1, t=0.045, inset=0.0, name='leg'):
    for xa in (x0 + inset, x1 - inset - t):
        for ya in (y0 + inset, y1 - inset - t):
            b.box(name, mat, xa, xa + t, ya, ya + t, z0, z1)


def _legs_round(b: _Builder, mat, x0, x1, y0, y1, z0, z1, r=0.02, inset=0.0, taper=1.0, n=10):
    for xa in (x0 + inset + r, x1 - inset - r):
        for ya in (y0 + inset + r, y1 - inset - r):
            if taper == 1.0:
                b.cyl('leg', mat, xa, ya, z0, z1, r, n=n)
            else:
                b.frustum('leg', mat, xa, ya, z0, z1, r * taper, r, n=n)


# ---------------------------------------------------------------------------------------
# beds


def _bed(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


def _bunker_bed(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'metal_dark')
    p = 0.07
    _legs_box(b, mat, x0, x1, y0, y1, 0.0, H, t=p, name='post')
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


def _baby_bed(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood_light', 'wood')
    p = 0.045
    _legs_box(b, mat, x0, x1, y0, y1, 0.0, H, t=p, name='post')
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


def _daybed(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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
        _legs_box(b, 'wood_dark', x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, 0.06, t=0.05)
    b.box('mattress', b.pick('mattress', 'mattress', soft), x0 + t, x1 - 0.01, y0 + t, y1 - t,
          0.3, 0.46)
    inner = W - 2 * t
    zc = min(0.62, H - 0.2)
    for i in range(3):
        yc = y0 + t + inner * (i + 0.5) / 3
        b.sphere('cushion', b.pick('fabric_blue', 'fabric_mustard', 'fabric_green'),
                 (x0 + t + 0.1, yc, zc), (0.09, inner / 6 - 0.02, 0.16), subdiv=2)


# ---------------------------------------------------------------------------------------
# case furniture


def _wardrobe(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'wood_dark')
    front = b.pick('wood_light', 'wood_white', 'wood_dark')
    hmat = b.pick('metal', 'chrome', 'brass')
    xf = x1
    plinth = 0.08
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, plinth, H - 0.04)
    b.box('cornice', mat, x0, xf - HANDLE, y0, y1, H - 0.04, H)
    if s == 1:
        _legs_round(b, 'metal', x0 + 0.03, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, plinth, r=0.02)
        b.box('bottom', mat, x0, xf - HANDLE - FRONT, y0, y1, plinth, plinth + 0.03)
    else:
        b.box('plinth', 'wood_dark' if s == 0 else 'shadow', x0, xf - 0.05, y0 + 0.02, y1 - 0.02,
              0.0, plinth)
    n = 2 if W < 1.2 else (3 if W < 1.8 else 4)
    z_doors = plinth + 0.005
    if s == 0 and H > 2.0:
        z_doors = plinth + 0.28
        for k in range(2):
            _drawer(b, front, hmat, y0 + k * W / 2, y0 + (k + 1) * W / 2, plinth, z_doors, xf)
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
        _door(b, door_mat, hmat, ya, yb, z_doors, H - 0.045, xf, handle_side=side,
              handle_len=0.35)


def _stand(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_light', 'wood_white', 'wood_dark')
    hmat = b.pick('brass', 'chrome', 'metal')
    xf = x1
    base = 0.14 if s == 0 else 0.04
    top = 0.025
    if s == 0:
        _legs_round(b, mat, x0 + 0.02, xf - HANDLE - 0.02, y0 + 0.02, y1 - 0.02, 0.0, base + 0.01,
                    r=0.018, taper=0.6, n=8)
    else:
        b.box('plinth', 'shadow', x0 + 0.02, xf - 0.05, y0 + 0.02, y1 - 0.02, 0.0, base)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, base, H - top)
    b.box('top', mat, x0, xf - HANDLE + 0.002, y0, y1, H - top, H)
    zs = H - top
    if s == 1:
        dh = min(0.16, (zs - base) * 0.4)
        _drawer(b, mat, hmat, y0, y1, zs - dh, zs, xf, handle='knob')
        b.box('niche', 'shadow', xf - HANDLE - FRONT - 0.003, xf - HANDLE - FRONT + 0.002,
              y0 + 0.025, y1 - 0.025, base + 0.025, zs - dh - 0.02)
    else:
        n = 2 if s == 0 else 3
        dh = (zs - base) / n
        for k in range(n):
            _drawer(b, mat, hmat, y0, y1, base + k * dh, base + (k + 1) * dh, xf,
                    handle='knob' if s == 0 else 'bar')


def _dresser(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood', 'wood_white', 'wood_dark')
    front = b.pick('wood_light', 'paint_cream', 'wood')
    hmat = b.pick('metal', 'brass', 'brass')
    xf = x1
    base = 0.09 if s != 1 else 0.13
    if s == 1:
        _legs_round(b, 'wood_dark', x0 + 0.03, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, base + 0.01,
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
            _drawer(b, front, hmat, y0 + k * W / c, y0 + (k + 1) * W / c, za, zb, xf,
                    handle='knobs' if (s == 1 and c == 1) else ('knob' if s == 1 else 'bar'))


def _dressing_table(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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
                _drawer(b, mat, hmat, ya, yb, 0.02 + k * dh, 0.02 + (k + 1) * dh, xf, 'knob')
    else:
        if s == 0:
            _legs_round(b, mat, x0 + 0.02, xf - HANDLE - 0.02, y0 + 0.02, y1 - 0.02, 0.0,
                        th - 0.03, r=0.022, taper=0.55, n=10)
        else:
            _legs_box(b, mat, x0 + 0.01, xf - HANDLE - 0.01, y0 + 0.01, y1 - 0.01, 0.0, th - 0.03,
                      t=0.04)
        b.box('apron', mat, x0 + 0.02, xf - HANDLE - FRONT, y0 + 0.03, y1 - 0.03, th - 0.15,
              th - 0.03)
        _drawer(b, mat, hmat, -W * 0.3, W * 0.3, th - 0.15, th - 0.03, xf, 'knob')
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
            b.obox('mirror_wing', mat, (xc, yc, zc), (0.025, sw, zm1 - zm0 - 0.1), _rot_z(-ang))
            b.obox('mirror', 'mirror', (xc + 0.014 * math.cos(ang), yc - 0.014 * math.sin(ang),
                                        zc), (0.006, sw - 0.05, zm1 - zm0 - 0.16), _rot_z(-ang))


def _tv_stand(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood', 'wood_dark')
    front = b.pick('wood_light', 'wood', 'paint_grey')
    hmat = b.pick('metal', 'metal_dark', 'chrome')
    xf = x1
    base = b.pick(0.12, 0.04, 0.16)
    if s == 1:
        b.box('plinth', 'shadow', x0 + 0.02, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, base)
    else:
        _legs_round(b, b.pick('metal', '', 'wood_dark'), x0 + 0.03, xf - 0.05, y0 + 0.04,
                    y1 - 0.04, 0.0, base + 0.01, r=0.018, taper=0.6 if s == 2 else 1.0, n=8)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, base, H - 0.025)
    b.box('top', mat, x0, xf - HANDLE + 0.002, y0, y1, H - 0.025, H)
    zs = H - 0.025
    if s == 0:
        dw = W * 0.3
        _drawer(b, front, hmat, y0, y0 + dw, base, zs, xf, 'top')
        _drawer(b, front, hmat, y1 - dw, y1, base, zs, xf, 'top')
        b.box('niche', 'shadow', xf - HANDLE - FRONT - 0.003, xf - HANDLE - FRONT + 0.002,
              y0 + dw + 0.02, y1 - dw - 0.02, base + 0.02, zs - 0.02)
    elif s == 1:
        n = 3 if W > 1.3 else 2
        for k in range(n):
            _door(b, front, hmat, y0 + k * W / n, y0 + (k + 1) * W / n, base, zs, xf,
                  handle_side=-1 if k % 2 else 1, handle_len=0.12)
    else:
        dh = (zs - base) * 0.35
        for k in range(2):
            _drawer(b, front, hmat, y0 + k * W / 2, y0 + (k + 1) * W / 2, zs - dh, zs, xf, 'bar')
        for k in range(2):
            b.box('niche', 'shadow', xf - HANDLE - FRONT - 0.003, xf - HANDLE - FRONT + 0.002,
                  y0 + k * W / 2 + 0.025, y0 + (k + 1) * W / 2 - 0.025, base + 0.02,
                  zs - dh - 0.015)


def _shelving(b: _Builder):
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


def _shoes_cabinet(b: _Builder):
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
        _legs_round(b, 'metal_dark', x0 + 0.02, xf - 0.04, y0 + 0.02, y1 - 0.02, 0.0, leg + 0.01,
                    r=0.012, n=8)
    b.box('carcass', mat, x0, xf - HANDLE - FRONT, y0, y1, leg, H - 0.02)
    b.box('top', mat, x0, xf - HANDLE + 0.002, y0, y1, H - 0.02, H)
    rows = 2 if H < 1.0 else 3
    cols = 2 if (s == 1 and W > 0.8) else 1
    zs = H - 0.02
    dh = (zs - leg) / rows
    for r in range(rows):
        for c in range(cols):
            _drawer(b, mat, hmat, y0 + c * W / cols, y0 + (c + 1) * W / cols, leg + r * dh,
                    leg + (r + 1) * dh, xf, 'top')


def _cabinet(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    mat = b.pick('wood_white', 'wood_light', 'paint_grey')
    hmat = b.pick('chrome', 'metal_dark', 'chrome')
    xf = x1
    base = 0.08
    if s == 1:
        _legs_round(b, 'metal', x0 + 0.02, xf - 0.04, y0 + 0.02, y1 - 0.02, 0.0, base + 0.01,
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
            _door(b, 'glass' if glass else mat, hmat, ya, yb, za, zb, xf,
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


# ---------------------------------------------------------------------------------------
# tables and desks


def _desk(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    top = b.pick('wood_light', 'wood_white', 'wood')
    t = 0.03
    b.box('top', top, x0, x1, y0, y1, H - t, H)
    zt = H - t
    if s == 0:
        _legs_box(b, 'metal_dark', x0 + 0.03, x1 - 0.03, y0 + 0.03, y1 - 0.03, 0.0, zt, t=0.04)
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
            _drawer(b, top, hmat, y1 - pw, y1 - 0.01, 0.03 + k * dh, 0.03 + (k + 1) * dh, xf,
                    'bar')


def _coffee_table(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    if s == 0:
        mat = 'wood'
        b.box('top', mat, x0, x1, y0, y1, H - 0.04, H)
        _legs_box(b, mat, x0 + 0.03, x1 - 0.03, y0 + 0.03, y1 - 0.03, 0.0, H - 0.04, t=0.05)
        b.box('apron', mat, x0 + 0.05, x1 - 0.05, y0 + 0.05, y1 - 0.05, H - 0.1, H - 0.04)
    elif s == 1:
        # rounded-end (stadium) glass top on a metal frame with a wooden lower shelf
        r = D / 2
        core = max(W - 2 * r, 0.0)

        def stadium(name, mat, z0, z1, shrink):
            b.prism(name, mat, _rounded_rect(D / 2 - shrink, W / 2 - shrink, r - shrink, 8),
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


# ---------------------------------------------------------------------------------------
# seating


def _office_chair(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
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
    b.transform_last(1, _rot_y(-tilt), pivot=(bx, 0, zb0))
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


def _straight_chair(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


def _chair(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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
               _rot_y(-math.radians(10)))
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


def _stool(b: _Builder):
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
        _legs_box(b, mat, x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, zt, t=0.035)
        for z in (0.18 * H,):
            b.box('stretcher', mat, x0 + 0.03, x1 - 0.03, y0 + 0.03, y0 + 0.045, z, z + 0.02)
            b.box('stretcher', mat, x0 + 0.03, x1 - 0.03, y1 - 0.045, y1 - 0.03, z, z + 0.02)
            b.box('stretcher', mat, x0 + 0.03, x0 + 0.045, y0 + 0.03, y1 - 0.03, z + 0.04,
                  z + 0.06)
            b.box('stretcher', mat, x1 - 0.045, x1 - 0.03, y0 + 0.03, y1 - 0.03, z + 0.04,
                  z + 0.06)


def _bench_chair(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    if s == 0:
        mat = 'wood'
        b.box('seat', mat, x0, x1, y0, y1, H - 0.05, H)
        _legs_box(b, mat, x0 + 0.03, x1 - 0.03, y0 + 0.05, y1 - 0.05, 0.0, H - 0.05, t=0.05)
        b.box('stretcher', mat, -0.015, 0.015, y0 + 0.1, y1 - 0.1, 0.12, 0.16)
    elif s == 1:
        b.box('frame', 'wood_dark', x0, x1, y0, y1, H - 0.13, H - 0.08)
        b.box('cushion', 'fabric_mustard', x0 + 0.005, x1 - 0.005, y0 + 0.005, y1 - 0.005,
              H - 0.08, H)
        _legs_round(b, 'metal_dark', x0 + 0.02, x1 - 0.02, y0 + 0.03, y1 - 0.03, 0.0, H - 0.13,
                    r=0.015, n=8)
    else:
        mat = 'wood_light'
        for ya in (y0, y1 - 0.05):
            b.box('panel_leg', 'metal_dark', x0 + 0.02, x1 - 0.02, ya, ya + 0.05, 0.0, H - 0.04)
        n = 4
        sw = D / n
        for k in range(n):
            b.box('slat', mat, x0 + k * sw + 0.006, x0 + (k + 1) * sw - 0.006, y0, y1, H - 0.04, H)


def _ottoman(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    fab = b.pick('fabric_blue', 'fabric_mustard', 'leather')
    if s == 0:
        _legs_round(b, 'wood_dark', x0 + 0.03, x1 - 0.03, y0 + 0.03, y1 - 0.03, 0.0, 0.07,
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


def _upholstered(b: _Builder, kind: str):
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
    for ya, yb, sgn in ((y0, y0 + arm_w, -1), (y1 - arm_w, y1, 1)):
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
            b.transform_last(1, _rot_y(-0.3) @ _rot_x(-0.2 * sgn),
                             shift=(x0 + back_t + 0.14, yc, sc + 0.2))


# ---------------------------------------------------------------------------------------
# lamps, electronics, appliances


def _floor_lamp(b: _Builder):
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


def _table_lamp(b: _Builder):
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


def _loudspeaker(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


def _pedestal_fan(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
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
               (0.006, R * 0.32, R * 0.78), _rot_x(a - math.pi / 2) @ _rot_z(0.25))
    b.ring('guard', 'plastic_grey', 0.0, 0.0, 0.0, 0.016, R - 0.016, R, n=28)
    b.transform_last(1, _rot_y(math.pi / 2), shift=(0.03, 0.0, zc))
    b.xdisc('grille', 'glass', 0.07, 0.074, 0.0, zc, R - 0.02, n=28)
    b.xdisc('badge', body, 0.074, 0.08, 0.0, zc, 0.04, n=12)
    for k in range(2):
        a = math.radians(45 + 90 * k)
        b.seg('guard_wire', 'plastic_grey', (0.074, (R - 0.02) * math.cos(a),
                                            zc + (R - 0.02) * math.sin(a)),
              (0.074, -(R - 0.02) * math.cos(a), zc - (R - 0.02) * math.sin(a)), 0.004, n=6)


def _television(b: _Builder):
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


def _laptop(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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
    b.transform_last(n, _rot_y(-tilt), shift=(xh, 0.0, tb * 0.6))
    if s == 1:
        b.seg('hinge', 'plastic_black', (xh + 0.004, y0 + 0.03, tb * 0.6),
              (xh + 0.004, y1 - 0.03, tb * 0.6), 0.006, n=10)



def _console(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_black', 'plastic_white', 'plastic_grey')
    feet = 0.008
    _legs_box(b, 'rubber', x0 + 0.02, x1 - 0.02, y0 + 0.02, y1 - 0.02, 0.0, feet, t=0.02)
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


def _washer(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
    body = b.pick('plastic_white', 'plastic_white', 'metal')
    xf = x1 - 0.012
    _legs_box(b, 'plastic_grey', x0 + 0.03, xf - 0.05, y0 + 0.03, y1 - 0.03, 0.0, 0.02, t=0.04)
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
    b.transform_last(1, _rot_y(math.pi / 2), shift=(xf - 0.006, 0.0, zc))
    b.xdisc('door_glass', 'glass_dark', xf - 0.004, xf + 0.004, 0.0, zc, R * 0.74, n=28)
    b.box('door_handle', 'plastic_grey', xf + 0.004, x1 - 0.004, R - 0.01, R + 0.03, zc - 0.05,
          zc + 0.05)


def _water_machine(b: _Builder):
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


# ---------------------------------------------------------------------------------------
# bathroom


def _toilet(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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
        b.transform_last(1, _rot_y(-math.radians(80)), shift=(x0 + tank_d + 0.03, 0.0,
                                                               zr + rx * 0.96 + 0.01))
    for sgn in (-1, 1):
        b.box('hinge', 'chrome', bx0 + 0.02, bx0 + 0.05, sgn * 0.08 - 0.015, sgn * 0.08 + 0.015,
              zr, zr + 0.03)


def _bidet(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


def _bathtub(b: _Builder):
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


def _shower(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


def _sink(b: _Builder):
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
                _door(b, wood, 'chrome', y0 + k * W / n, y0 + (k + 1) * W / n, plinth, zt - 0.045,
                      xf, handle_side=-1 if k % 2 else 1, handle_len=0.12)
            bw = min(W * 0.34, 0.26)
            b.cyl('basin_rim', 'ceramic', 0.02, 0, zt, zt + 0.012, 0.17, bw, n=24)
            b.cyl('basin_recess', 'ceramic_shadow', 0.025, 0, zt + 0.012, zt + 0.014, 0.14,
                  bw - 0.03, n=24)
        else:
            dh = (zt - 0.045 - plinth) / 2
            for k in range(2):
                _drawer(b, wood, 'metal', y0, y1, plinth + k * dh, plinth + (k + 1) * dh, xf,
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


def _trash_can(b: _Builder):
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


# ---------------------------------------------------------------------------------------
# living room and office pieces


def _hanger(b: _Builder):
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


def _whiteboard(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


def _piano(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


def _fireplace(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
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


# ---------------------------------------------------------------------------------------
# small things on surfaces


def _plant(b: _Builder):
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
                   base + (0, 0, length / 2), (0.008, 0.035, length), _rot_z(a))
            # lean the blade outwards, away from the pot's axis
            b.transform_last(1, _rot_z(a) @ _rot_y(lean) @ _rot_z(-a), pivot=base)
    else:
        b.cyl('trunk', 'bark', 0, 0, ph - 0.01, ph + (H - ph) * 0.5, 0.012, n=8)
        for k, (bx, by, bz, br) in enumerate([(0, 0, 0.7, 0.75), (0.35, 0.2, 0.62, 0.5),
                                              (-0.3, -0.25, 0.66, 0.5)]):
            zc = ph + (H - ph) * bz
            r = br * R
            b.sphere('crown', ('leaf_dark', 'leaf', 'leaf_light')[k], (bx * R, by * R, zc),
                     (r, r, min(r, (H - ph) * 0.3)), subdiv=1)


def _book(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
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
            b.transform_last(4, _rot_z(yaw), shift=(dx, dy, 0.0))
        z += th


def _vase(b: _Builder):
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
                    rot=_rot_y(math.pi / 2), n=12, m=5)


def _toy(b: _Builder):
    W, D, H, s = b.W, b.D, b.H, b.s
    x0, x1, y0, y1 = b.x0, b.x1, b.y0, b.y1
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
                b.transform_last(1, _rot_z(0.1 * ((k * 7) % 3 - 1)), pivot=(xc, yc, 0))
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


def _fishbowl(b: _Builder):
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
            rot=_rot_y(-math.pi / 2))
    b.transform_last(1, shift=(fx - 0.02, 0.0, fz))
    for k in range(3):
        b.obox('weed', 'leaf', (R * 0.3 * (k - 1) * 0.8, R * 0.2, 0.025 + H * 0.15),
               (0.004, 0.012, H * 0.3), _rot_x(0.15 * (k - 1)))


def _cup(b: _Builder):
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
            rot=_rot_y(math.pi / 2), n=12, m=6, scale=(1.0, 1.0, zscale))


def _glass(b: _Builder):
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
                b.transform_last(1, _rot_z(0.4 + k) @ _rot_x(0.3),
                                 shift=(R * 0.2 * (k * 2 - 1), R * 0.1, H * 0.58 - c / 2))


def _bottle(b: _Builder):
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


def _fruit_bowl(b: _Builder):
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
        for k, a in enumerate((0.5, 2.6)):
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
        k = 0
        for layer, (n, rad) in enumerate(((7, R * 0.5), (5, R * 0.32), (1, 0.0))):
            zc = z0 + rg + layer * rg * 1.6
            for i in range(n):
                a = 2 * math.pi * i / n + 0.3 * layer
                b.sphere('grape', 'grape', (rad * math.cos(a) - R * 0.15, rad * math.sin(a) * ey,
                                            zc), rg, subdiv=0)
                k += 1
        b.sphere('fruit', 'lemon', (R * 0.45, -R * 0.2 * ey, H - rf), (rf * 1.1, rf * 0.9, rf),
                 subdiv=1)


# ---------------------------------------------------------------------------------------
# registry and public functions

_BUILDERS: dict[str, Callable[[_Builder], None]] = {
    'wardrobe': _wardrobe, 'stand': _stand, 'double bed': _bed, 'single bed': _bed,
    'bunker bed': _bunker_bed, 'baby bed': _baby_bed, 'daybed': _daybed, 'desk': _desk,
    'dresser': _dresser, 'dressing table': _dressing_table, 'tv stand': _tv_stand,
    'shelving': _shelving, 'shoes cabinet': _shoes_cabinet, 'office chair': _office_chair,
    'straight chair': _straight_chair, 'chair': _chair, 'stool': _stool,
    'bench chair': _bench_chair, 'ottoman': _ottoman,
    'sofa': lambda b: _upholstered(b, 'sofa'),
    'sofa chair': lambda b: _upholstered(b, 'sofa chair'),
    'armchair': lambda b: _upholstered(b, 'armchair'),
    'coffee table': _coffee_table, 'floor lamp': _floor_lamp, 'loudspeaker': _loudspeaker,
    'pedestal fan': _pedestal_fan, 'hanger': _hanger, 'whiteboard': _whiteboard,
    'piano': _piano, 'fireplace': _fireplace, 'water machine': _water_machine,
    'toilet': _toilet, 'bidet': _bidet, 'bathtub': _bathtub, 'shower': _shower, 'sink': _sink,
    'washer': _washer, 'trash can': _trash_can, 'cabinet': _cabinet,
    'table lamp': _table_lamp, 'plant': _plant, 'television': _television, 'laptop': _laptop,
    'book': _book, 'vase': _vase, 'console': _console, 'toy': _toy, 'fishbowl': _fishbowl,
    'cup': _cup, 'glass': _glass, 'bottle': _bottle, 'fruit bowl': _fruit_bowl,
}


def _plain_box(b: _Builder):
    """Fallback for a category without a builder: a grey block with a darker top."""
    b.box('body', 'paint_grey', b.x0, b.x1, b.y0, b.y1, 0.0, b.H * 0.9)
    b.box('top', 'plastic_black', b.x0, b.x1, b.y0, b.y1, b.H * 0.9, b.H)
    b.box('front_mark', 'plastic_white', b.x1 - 0.01, b.x1, -b.W * 0.1, b.W * 0.1, b.H * 0.4,
          b.H * 0.6)


@lru_cache(maxsize=1024)
def build_parts(variant: ModelVariant) -> tuple[Part, ...]:
    """The named parts of ``variant``'s mesh, already fitted to its box (read-only arrays)."""
    if min(variant.size) <= 0:
        raise ValueError(f'{variant.model_id}: sizes must be positive, got {variant.size}')
    b = _Builder(variant)
    _BUILDERS.get(variant.category, _plain_box)(b)
    return b.finish()


def build_mesh(variant: ModelVariant) -> trimesh.Trimesh:
    """One mesh for ``variant`` with per-vertex colours; bounds are exactly its box
    (x: depth, y: width, z: 0..height). ``metadata['parts']`` lists the part names, one per
    connected body, in order."""
    parts = build_parts(variant)
    verts, faces, colours = [], [], []
    offset = 0
    for p in parts:
        verts.append(p.vertices)
        faces.append(p.faces + offset)
        colours.append(np.tile(MATERIALS[p.material].rgba, (len(p.vertices), 1)))
        offset += len(p.vertices)
    mesh = trimesh.Trimesh(np.vstack(verts), np.vstack(faces), process=False,
                           vertex_colors=np.vstack(colours).astype(np.uint8))
    mesh.metadata['model_id'] = variant.model_id
    mesh.metadata['category'] = variant.category
    mesh.metadata['parts'] = [p.name for p in parts]
    return mesh


def _material_meshes(variant: ModelVariant) -> dict[str, trimesh.Trimesh]:
    """The model's faces grouped by material, each group a mesh with a glTF PBR material."""
    groups: dict[str, list[Part]] = {}
    for p in build_parts(variant):
        groups.setdefault(p.material, []).append(p)
    out = {}
    for mat_name, parts in groups.items():
        mat = MATERIALS[mat_name]
        verts, faces, offset = [], [], 0
        for p in parts:
            verts.append(p.vertices)
            faces.append(p.faces + offset)
            offset += len(p.vertices)
        m = trimesh.Trimesh(np.vstack(verts), np.vstack(faces), process=False)
        m.visual = trimesh.visual.TextureVisuals(material=_pbr(mat))
        out[mat_name] = m
    return out


def _pbr(mat: Material):
    return trimesh.visual.material.PBRMaterial(
        name=mat.name, baseColorFactor=list(mat.rgba), metallicFactor=mat.metallic,
        roughnessFactor=mat.roughness, alphaMode='BLEND' if mat.transparent else 'OPAQUE',
        doubleSided=mat.transparent)


def model_scene(variant: ModelVariant) -> trimesh.Scene:
    """A trimesh scene for one model: a root node named after the model id, with one child
    node (and one geometry) per material."""
    scene = trimesh.Scene()
    root = variant.model_id
    scene.graph.update(frame_to=root, frame_from=scene.graph.base_frame, matrix=np.eye(4))
    for mat_name, mesh in _material_meshes(variant).items():
        scene.add_geometry(mesh, node_name=f'{root}/{mat_name}',
                           geom_name=f'{root}/{mat_name}', parent_node_name=root)
    return scene


def _write_obj(variant: ModelVariant, path: Path) -> None:
    """Wavefront OBJ with an MTL file next to it (``<stem>.mtl``), one group per material."""
    mtl_path = path.with_suffix('.mtl')
    lines = [f'# {variant.model_id} ({variant.category}), metres, z up, front +x',
             f'mtllib {mtl_path.name}']
    mtl = []
    groups: dict[str, list[Part]] = {}
    for p in build_parts(variant):
        groups.setdefault(p.material, []).append(p)
    offset = 1
    for mat_name, parts in groups.items():
        mat = MATERIALS[mat_name]
        r, g, bl, a = (c / 255.0 for c in mat.rgba)
        mtl += [f'newmtl {mat_name}', f'Kd {r:.4f} {g:.4f} {bl:.4f}', 'Ka 0 0 0',
                f'Ks {0.5 * mat.metallic + 0.04:.3f} {0.5 * mat.metallic + 0.04:.3f} '
                f'{0.5 * mat.metallic + 0.04:.3f}',
                f'Ns {max(1.0, (1.0 - mat.roughness) * 200):.1f}', f'd {a:.3f}', 'illum 2', '']
        lines += [f'o {mat_name}', f'usemtl {mat_name}']
        for p in parts:
            lines += [f'v {x:.6f} {y:.6f} {z:.6f}' for x, y, z in p.vertices]
            lines += [f'f {i + offset} {j + offset} {k + offset}' for i, j, k in p.faces]
            offset += len(p.vertices)
    path.write_text('\n'.join(lines) + '\n')
    mtl_path.write_text('\n'.join(mtl))


def export_model(variant: ModelVariant, path: str | Path) -> Path:
    """Write ``variant``'s mesh to ``path``: binary glTF for ``.glb`` (PBR material per
    colour, flat normals), Wavefront for ``.obj`` (plus ``.mtl``)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    suffix = path.suffix.lower()
    if suffix == '.glb':
        data = trimesh.exchange.gltf.export_glb(model_scene(variant), include_normals=False)
        path.write_bytes(data)
    elif suffix == '.obj':
        _write_obj(variant, path)
    else:
        raise ValueError(f'unsupported mesh format {path.suffix!r}; use .glb or .obj')
    return path


def mesh_path(model_id: str, out_dir: str | Path, fmt: str = 'glb') -> Path:
    """Where ``export_catalog`` puts ``model_id``: ``<out_dir>/<model_id>.<fmt>``."""
    fmt = fmt.lower().lstrip('.')
    if fmt not in ('glb', 'obj'):
        raise ValueError(f'unsupported mesh format {fmt!r}; use glb or obj')
    return Path(out_dir) / f'{model_id}.{fmt}'


def export_catalog(out_dir: str | Path, fmt: str = 'glb',
                   categories: Iterable[str] | None = None) -> list[Path]:
    """Write one file per catalog variant (all categories unless ``categories`` is given)."""
    cats = list(CATEGORIES) if categories is None else list(categories)
    for c in cats:
        if c not in CATEGORIES:
            raise KeyError(f'unknown category {c!r}')
    out = []
    for c in cats:
        for v in catalog.variants(c):
            out.append(export_model(v, mesh_path(v.model_id, out_dir, fmt)))
    return out


# ---------------------------------------------------------------------------------------
# whole scenes


def object_transform(position: Sequence[float], yaw: float) -> np.ndarray:
    """World transform of a placed object: translate(position) . rotate_z(yaw)."""
    t = np.eye(4)
    t[:3, :3] = _rot_z(float(yaw))
    t[:3, 3] = [float(v) for v in position]
    return t


def variant_for(obj) -> ModelVariant:
    """The model a placed object shows: its catalog variant, re-sized to ``obj.size`` when
    the object's size differs from the catalog's (style kept); for an unknown model id, the
    style of the category's nearest variant."""
    size = tuple(float(v) for v in obj.size)
    try:
        v = catalog.get(obj.model_id)
    except KeyError:
        v = None
    if v is not None and v.category == obj.category:
        if np.allclose(v.size, size, atol=1e-6):
            return v
        return ModelVariant(f'{v.model_id}@{size[0]:.3f}x{size[1]:.3f}x{size[2]:.3f}',
                            v.category, size, v.style)
    style = 0
    if obj.category in CATEGORIES:
        style = catalog.nearest(obj.category, size[0], size[1]).style
    return ModelVariant(f'{obj.model_id or obj.category}@{size[0]:.3f}x{size[1]:.3f}x'
                        f'{size[2]:.3f}', obj.category, size, style)


def scene_mesh(scene) -> trimesh.Scene:
    """A trimesh scene with every object of a ``scene_synth_ros.scene.Scene``.

    Each object is a node named after its id whose transform is
    ``translate(position) . rotate_z(yaw)``; its children are one node per material
    (``<object id>/<material>``) with identity transforms. Geometry is shared between
    objects showing the same model at the same size. The room itself is not included."""
    out = trimesh.Scene()
    base = out.graph.base_frame
    cache: dict[str, dict[str, trimesh.Trimesh]] = {}
    for obj in scene.objects:
        v = variant_for(obj)
        if v.model_id not in cache:
            cache[v.model_id] = _material_meshes(v)
        out.graph.update(frame_to=obj.id, frame_from=base,
                         matrix=object_transform(obj.position, obj.yaw))
        for mat_name, mesh in cache[v.model_id].items():
            geom = f'{v.model_id}/{mat_name}'
            if geom not in out.geometry:
                out.add_geometry(mesh, geom_name=geom, node_name=f'{obj.id}/{mat_name}',
                                 parent_node_name=obj.id)
            else:
                out.graph.update(frame_to=f'{obj.id}/{mat_name}', frame_from=obj.id,
                                 matrix=np.eye(4), geometry=geom)
    return out


# ---------------------------------------------------------------------------------------
# previews
#
# matplotlib's 3D axes sort whole polygons back to front, which goes wrong for layered
# furniture (a door 2 cm in front of a carcass). The preview therefore rasterises the mesh
# itself with a small z-buffer (orthographic, flat shading, part outlines, alpha-blended glass)
# and shows the image with matplotlib.


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
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

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
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

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
