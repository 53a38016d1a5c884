"""The draws synthesis makes from the networks' outputs, in numpy and from the room's own
generator (``numpy.random.Generator``): the next category (paper: Next Object Category), a
location on the grid (Object Location), the prior noise of the two CVAEs and the angle the
orientation decoder gives (Object Orientation).

Nothing here imports torch: a process that runs its networks in onnxruntime sessions read
from the graph cache furnishes rooms without it (``networks/runtime.py``)."""
from __future__ import annotations

import math

import numpy as np

MAX_OFFSET = 2.0     # pixels: a target block's radius (1 in compact.yaml) and a half


def _log_softmax(x: np.ndarray, axis: int) -> np.ndarray:
    top = np.max(x, axis=axis, keepdims=True)
    top = np.where(np.isfinite(top), top, 0.0)
    shifted = x - top
    with np.errstate(divide='ignore'):
        return shifted - np.log(np.sum(np.exp(shifted), axis=axis, keepdims=True))


def category_probabilities(logits: np.ndarray, allowed: np.ndarray | None = None
                           ) -> np.ndarray:
    """Softmax of one example's logits (float64) with the categories not ``allowed`` (bool,
    C + 1) given zero probability; STOP stays allowed unless the mask says otherwise."""
    logits = np.asarray(logits, dtype=np.float64)
    if allowed is not None:
        logits = np.where(allowed, logits, -np.inf)
    return np.exp(_log_softmax(logits, axis=-1))


def prior_noise(rng: np.random.Generator, n: int, latent: int) -> np.ndarray:
    """``n`` draws of a CVAE's z from its prior, N(0, I), as the graphs take them."""
    return rng.standard_normal((n, latent), dtype=np.float32)


def decode_angle(out: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Angles from the orientation decoder's outputs (B x 2): cos from the first, the sign
    of sin drawn from the second's probability."""
    out = np.asarray(out, dtype=np.float64)
    c = np.clip(np.tanh(out[:, 0]), -1.0, 1.0)
    positive = rng.random(out.shape[0]) < sigmoid(out[:, 1])
    sign = np.where(positive, 1.0, -1.0)
    return np.arctan2(sign * np.sqrt(np.clip(1 - c * c, 0.0, None)), c)


def sigmoid(x: np.ndarray) -> np.ndarray:
    return 0.5 * (1.0 + np.tanh(0.5 * np.asarray(x, dtype=np.float64)))


def snap_angle(theta: float) -> float:
    """The nearest multiple of 90 degrees."""
    return round(theta / (math.pi / 2)) * (math.pi / 2)


def log_normaliser(logits: np.ndarray) -> np.ndarray:
    """The log of the per-pixel softmax's normaliser of the location module's logits
    (C + 1, L, L), in float32 as the network gives them: made once for an insertion's
    logits, shared by its categories' draws."""
    x = np.asarray(logits, dtype=np.float32)
    top = x.max(axis=0)
    return top + np.log(np.exp(x - top).sum(axis=0))


def location_distribution(logits: np.ndarray, category: int, mask: np.ndarray,
                          temperature: float = 0.8, log_norm: np.ndarray | None = None
                          ) -> np.ndarray | None:
    """The sampling distribution over the ``L x L`` grid for ``category`` (index into the
    room type's categories): the category's channel of the per-pixel softmax, zero outside
    ``mask`` (the floor, or the surfaces that can support a second-tier category), then
    tempered as ``p ** (1 / temperature)``. ``None`` when the mask leaves nothing.
    ``log_norm``: the logits' ``log_normaliser``, where it is known."""
    if temperature <= 0:
        raise ValueError('the location temperature must be positive')
    if log_norm is None:
        log_norm = log_normaliser(logits)
    logp = (logits[1 + category] - log_norm).astype(np.float64) / temperature
    logp[~mask] = -np.inf
    top = logp.max()
    if not np.isfinite(top):
        return None
    p = np.exp(logp - top)
    return p / p.sum()


class LocationDraws:
    """Draws from one grid distribution ``p`` (``location_distribution``): a category's
    retries draw up to ``location_samples`` times from the same distribution, so its
    cumulative sum and its 3 x 3 block sums (``blob_centre``) are made once, at the first
    draw that needs them."""

    def __init__(self, p: np.ndarray):
        self.p = p
        self._cdf: np.ndarray | None = None
        self._blocks: np.ndarray | None = None

    def pixels(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """``n`` flat pixel indices drawn from ``p`` with replacement: the draws, and the
        random numbers they use, of ``rng.choice(p.size, size=n, p=p.ravel())`` (which
        checks ``p`` again at every call)."""
        if self._cdf is None:
            self._cdf = self.p.ravel().astype(np.float64).cumsum()
            self._cdf /= self._cdf[-1]
        return self._cdf.searchsorted(rng.random(n), side='right')

    @property
    def blocks(self) -> np.ndarray:
        """The probability in each pixel's 3 x 3 neighbourhood, padded with -1 outside."""
        if self._blocks is None:
            n, pad = self.p.shape[0], np.pad(self.p, 1)
            box = sum(pad[1 + i:1 + i + n, 1 + j:1 + j + n]
                      for i, j in zip(_DI, _DJ, strict=True))
            self._blocks = np.pad(box, 1, constant_values=-1.0)
        return self._blocks

    def sample(self, rng: np.random.Generator, n: int = 1, offsets: np.ndarray | None = None,
               mode: bool = False) -> np.ndarray:
        """``n`` (row, col) pixels drawn from ``p`` (with replacement), as continuous
        coordinates. With ``mode`` each draw is first moved to the centre of the blob it
        fell in (``blob_centre``). With the network's ``offsets`` (2 x L x L) the pixel
        reached is then moved by the offset predicted there; without them, a draw that was
        not moved to a blob centre is put anywhere inside its pixel, uniformly."""
        p = self.p
        rows, cols = np.divmod(self.pixels(rng, n), p.shape[1])
        points = np.stack([rows, cols], -1).astype(np.float64)
        if mode:
            points = blob_centre(p, points, self.blocks)
        if offsets is not None:
            at = np.clip(np.floor(points + 0.5), 0, p.shape[0] - 1).astype(int)
            # At most the target's reach from the pixel: a wild offset must not leave the
            # block.
            shift = np.clip(offsets[:, at[:, 0], at[:, 1]].T, -MAX_OFFSET, MAX_OFFSET)
            return at + shift
        if mode:
            return points
        return points + rng.uniform(-0.5, 0.5, size=(n, 2))


def sample_pixel(p: np.ndarray, rng: np.random.Generator, n: int = 1,
                 offsets: np.ndarray | None = None, mode: bool = False) -> np.ndarray:
    """``n`` (row, col) pixels drawn from the grid distribution ``p``: one
    ``LocationDraws.sample``."""
    return LocationDraws(p).sample(rng, n, offsets, mode)


# The 3 x 3 neighbourhood of a pixel, row and column steps, the pixel itself fifth.
_DI, _DJ = (a.ravel() for a in np.meshgrid(np.arange(-1, 2), np.arange(-1, 2), indexing='ij'))


def blob_centre(p: np.ndarray, points: np.ndarray, blocks: np.ndarray | None = None
                ) -> np.ndarray:
    """Each point moved to the centre of the blob of ``p`` it lies in: uphill to the pixel
    whose 3 x 3 neighbourhood holds the most probability (the best match of a 3 x 3 block),
    then to the probability-weighted mean of that neighbourhood (``blocks``: those block
    sums, ``LocationDraws.blocks``, when they are known).

    A location module trained on a 3 x 3 target answers an object's centroid with a blob
    about that wide, every pixel of it likely; a draw from the blob is up to a pixel off the
    centroid (``docs/design/investigations.md``), the blob's centre is not."""
    if blocks is None:
        blocks = LocationDraws(p).blocks
    n, di, dj = p.shape[0], _DI, _DJ
    at = np.clip(np.floor(points + 0.5), 0, n - 1).astype(int)
    k = np.arange(len(at))
    for _ in range(2 * n):
        values = blocks[at[:, :1] + di + 1, at[:, 1:] + dj + 1]       # (points, 9)
        best = values.argmax(1)
        climb = values[k, best] > values[:, 4]                        # 4: the pixel itself
        if not climb.any():
            break
        at[climb] += np.stack([di[best], dj[best]], -1)[climb]
    rows, cols = at[:, :1] + di, at[:, 1:] + dj
    w = np.pad(p, 1)[rows + 1, cols + 1]
    total = w.sum(1)
    out = at.astype(np.float64)
    some = total > 0
    out[some, 0] = (w * rows).sum(1)[some] / total[some]
    out[some, 1] = (w * cols).sum(1)[some] / total[some]
    return out
