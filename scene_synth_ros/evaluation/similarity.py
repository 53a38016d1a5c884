"""Scene-to-scene similarity and the generalisation test (paper, appendix): how close each
synthesized room comes to its nearest training room, beside the same for held-out corpus
rooms.

Similarity of two rooms A and B of one type, in [0, 1]:

1. Every object becomes its category and a normalised position: its footprint centre in
   the room's own axes (those of its longest wall, ``render.room_axis_yaw``), relative to the
   room's bounding box in those axes, the longer side first, so that both coordinates lie
   in [-0.5, 0.5] whatever the shell's size and shape.
2. Objects are matched only to objects of the same category, one to one, maximising the
   sum of the kernel ``exp(-d^2 / sigma^2)`` over matched pairs (d: distance between
   normalised positions). The assignment is optimal: per category it is found by
   enumerating the injections of the smaller group into the larger one (corpus rooms hold
   at most two objects of a category, so this is a handful of cases); only when there are
   more than ``MAX_ENUMERATION`` injections does a greedy matching (largest kernel first)
   stand in.
3. The sum is divided by max(|A|, |B|): unmatched objects count as zero, so a room is 1 to
   itself and an empty room is 0 to a furnished one (two empty rooms are 1).
4. The score is the largest over the four mirror images of A's normalised layout (flip
   along either axis, or both): a room and its mirror image are the same arrangement.

Everything is vectorised over the reference rooms with numpy.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from itertools import permutations
from typing import Sequence

import numpy as np

from ..render import Frame, room_frame_box
from ..scene import Scene
from .parallel import pmap

SIGMA = 0.1                    # kernel width, in units of the room's bounding box side
MAX_ENUMERATION = 5040         # injections enumerated per category before going greedy
_CHUNK_ELEMENTS = 2_000_000    # bound on the size of one enumeration array
MIRRORS = np.array([[1.0, 1.0], [-1.0, 1.0], [1.0, -1.0], [-1.0, -1.0]])


@dataclass
class Layout:
    """A room as the similarity sees it: object categories and normalised positions."""

    categories: tuple[str, ...]
    positions: np.ndarray      # (n, 2), each coordinate in [-0.5, 0.5]

    def __len__(self) -> int:
        return len(self.categories)


def layout(scene: Scene) -> Layout:
    """The normalised layout of ``scene`` (see the module docstring, step 1)."""
    box = room_frame_box(scene.room)
    pts = np.array([o.position[:2] for o in scene.objects], dtype=float).reshape(-1, 2)
    uv = Frame(box.centre, box.yaw, box.cap, 1).to_local(pts) / np.array(box.span)
    if box.span[1] > box.span[0]:
        uv = uv[:, ::-1]
    return Layout(tuple(o.category for o in scene.objects), np.ascontiguousarray(uv))


@lru_cache(maxsize=None)
def _injections(m: int, a: int) -> np.ndarray:
    """All ordered choices of ``a`` distinct items out of ``m``: shape (K, a)."""
    return np.array(list(permutations(range(m), a)), dtype=np.intp).reshape(-1, a)


def _greedy(w: np.ndarray) -> np.ndarray:
    """Greedy matching value of (..., a, m) weight matrices: repeatedly take the largest
    weight left and remove its row and column."""
    w = w.copy()
    lead, (a, m) = w.shape[:-2], w.shape[-2:]
    flat = w.reshape(-1, a * m)
    total = np.zeros(flat.shape[0])
    rows = np.arange(flat.shape[0])
    for _ in range(min(a, m)):
        k = flat.argmax(1)
        total += flat[rows, k]
        i, j = np.divmod(k, m)
        grid = flat.reshape(-1, a, m)
        grid[rows, i, :] = -np.inf
        grid[rows, :, j] = -np.inf
    return np.maximum(total, 0.0).reshape(lead)


def best_matching(w: np.ndarray) -> np.ndarray:
    """Maximum total weight of a one-to-one matching between the rows and columns of each
    (a, m) matrix in ``w`` (..., a, m), weights non-negative (unmatched counts zero)."""
    a, m = w.shape[-2:]
    if a == 0 or m == 0:
        return np.zeros(w.shape[:-2])
    if a == 1 or m == 1:
        return w.max(axis=(-2, -1))
    if a > m:
        w, a, m = np.swapaxes(w, -1, -2), m, a
    inj = _injections(m, a) if _count_injections(m, a) <= MAX_ENUMERATION else None
    if inj is None:
        return _greedy(w)
    lead = w.shape[:-2]
    flat = w.reshape(-1, a, m)
    out = np.empty(flat.shape[0])
    step = max(1, _CHUNK_ELEMENTS // (len(inj) * a))
    cols = np.arange(a)
    for start in range(0, flat.shape[0], step):
        part = flat[start:start + step]
        out[start:start + step] = part[:, cols, inj].sum(-1).max(-1)
    return out.reshape(lead)


def _count_injections(m: int, a: int) -> int:
    n = 1
    for k in range(m - a + 1, m + 1):
        n *= k
    return n


class References:
    """The reference rooms, per category a padded array of normalised positions."""

    def __init__(self, layouts: Sequence[Layout]):
        self.size = len(layouts)
        self.counts = np.array([len(lay) for lay in layouts], dtype=float)
        per_cat: dict[str, dict[int, list[np.ndarray]]] = {}
        for r, lay in enumerate(layouts):
            for cat, p in zip(lay.categories, lay.positions, strict=True):
                per_cat.setdefault(cat, {}).setdefault(r, []).append(p)
        self.positions: dict[str, np.ndarray] = {}     # (R, M, 2)
        self.valid: dict[str, np.ndarray] = {}         # (R, M) as 0.0 / 1.0
        for cat, rooms in per_cat.items():
            m = max(len(p) for p in rooms.values())
            pos = np.zeros((self.size, m, 2))
            valid = np.zeros((self.size, m))
            for r, pts in rooms.items():
                pos[r, :len(pts)] = pts
                valid[r, :len(pts)] = 1.0
            self.positions[cat], self.valid[cat] = pos, valid

    @classmethod
    def from_scenes(cls, scenes: Sequence[Scene]) -> 'References':
        return cls([layout(s) for s in scenes])


def similarities(query: Layout, refs: References, sigma: float = SIGMA) -> np.ndarray:
    """Similarity of ``query`` to every reference room: shape (R,)."""
    total = np.zeros((len(MIRRORS), refs.size))
    mirrored = query.positions[None, :, :] * MIRRORS[:, None, :]       # (4, n, 2)
    cats = np.array(query.categories, dtype=object)
    for cat in dict.fromkeys(query.categories):
        if cat not in refs.positions:
            continue
        q = mirrored[:, cats == cat]                                     # (4, a, 2)
        p = refs.positions[cat]                                          # (R, m, 2)
        d2 = ((q[:, None, :, None, :] - p[None, :, None, :, :]) ** 2).sum(-1)
        w = np.exp(-d2 / sigma ** 2) * refs.valid[cat][None, :, None, :]
        total += best_matching(w)
    denom = np.maximum(refs.counts, len(query))
    return np.where(denom > 0, total.max(0) / np.maximum(denom, 1.0), 1.0)


def scene_similarity(a: Scene, b: Scene, sigma: float = SIGMA) -> float:
    """Similarity of two rooms (see the module docstring)."""
    return float(similarities(layout(a), References([layout(b)]), sigma)[0])


_REFS: References | None = None


def _set_refs(refs: References) -> None:
    global _REFS
    _REFS = refs


def _max_chunk(job) -> list[tuple[float, int]]:
    layouts, sigma = job
    out = []
    for lay in layouts:
        s = similarities(lay, _REFS, sigma)
        k = int(s.argmax()) if len(s) else -1
        out.append((float(s[k]) if k >= 0 else 0.0, k))
    return out


def max_similarity(queries: Sequence[Scene], refs: References, sigma: float = SIGMA,
                   workers: int = 1, progress: bool = True, desc: str | None = None
                   ) -> tuple[np.ndarray, np.ndarray]:
    """For every query room, its largest similarity to a reference room and that room's
    index."""
    layouts = [layout(s) for s in queries]
    chunk = max(1, min(25, len(layouts) // max(4 * workers, 1) or 1))
    jobs = [(layouts[k:k + chunk], sigma) for k in range(0, len(layouts), chunk)]
    parts = pmap(_max_chunk, jobs, workers, _set_refs, (refs,), desc=desc, progress=progress)
    pairs = [p for part in parts for p in part]
    return (np.array([p[0] for p in pairs], dtype=float),
            np.array([p[1] for p in pairs], dtype=int))
