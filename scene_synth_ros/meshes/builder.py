"""The toolkit every furniture builder draws with.

A builder function receives a ``Builder`` for one catalog variant and adds named,
single-material parts made from primitives (boxes, cylinders, spheres, surfaces of
revolution, prisms) in the package's object frame: front towards +x, width along y, depth
along x, origin at the centre of the footprint on the floor. ``Builder.finish`` then maps the
parts onto the variant's box, so whatever proportions a builder sketches, the result spans
exactly ``x in [-depth/2, depth/2]``, ``y in [-width/2, width/2]``, ``z in [0, height]``.
``builds`` declares which categories a builder function draws; the registry collects those
declarations.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
import math
from typing import Callable
import zlib

import numpy as np
import trimesh
from trimesh import creation

from ..catalog import ModelVariant
from .materials import MATERIALS

# primitives as (vertices, faces) arrays, cached because every model reuses a handful


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


def rot_x(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_z(a: float) -> np.ndarray:
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


class Builder:
    """Collects parts in the model frame; ``finish`` maps them onto the variant's box."""

    def __init__(self, variant: ModelVariant):
        self.category = variant.category
        self.W, self.D, self.H = (float(s) for s in variant.size)
        # the catalog's styles cycle through three looks per category
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


BuildFn = Callable[[Builder], None]


def builds(*categories: str) -> Callable[[BuildFn], BuildFn]:
    """Decorator declaring the catalog categories the decorated builder function draws.

    It only records them on the function (as ``builds_categories``): the registry, which imports
    every furniture module, turns the declarations into its lookup table. Keeping the
    decorator here rather than in the registry is what lets the registry import the furniture
    modules without an import cycle."""
    if not categories:
        raise ValueError('builds() needs at least one category')

    def declare(fn: BuildFn) -> BuildFn:
        fn.builds_categories = tuple(categories)
        return fn
    return declare
