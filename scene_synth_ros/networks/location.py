"""Location module (paper, section 4.2): where in the room an object of each category goes."""
from __future__ import annotations

import math

import numpy as np
import torch
from torch import nn

from .blocks import ResNetEncoder, UpBlock
from .config import ModelConfig

MAX_OFFSET = 2.0     # pixels: a target block's radius (1 in compact.yaml) and a half


class LocationModel(nn.Module):
    """ResNet-34-style encoder and a decoder of nearest-neighbour upsampling + 3x3
    convolutions to ``(C + 1) x L x L`` logits (L = ``location_resolution``). Channel 0 is
    "no object centred here", channel ``1 + c`` category ``c``. Dropout before and after the
    encoder and before the last 1x1 convolution, as in the paper. With
    ``location_offsets`` a second 1x1 convolution gives ``2 x L x L`` offsets: from each
    pixel's centre to the centroid of the object marked there, in pixels (row, col)."""

    def __init__(self, in_channels: int, num_categories: int, cfg: ModelConfig):
        super().__init__()
        self.num_categories = num_categories
        self.encoder = ResNetEncoder(in_channels, cfg.location_encoder)
        # The sides of the images it takes are multiples of this, so that every skip meets
        # a decoder map of its own size (a room larger than its type's square is seen so).
        self.multiple = self.encoder.downsampling
        bottleneck = cfg.resolution // self.encoder.downsampling
        if bottleneck < 1 or cfg.location_resolution % bottleneck:
            raise ValueError(f'a {cfg.resolution} px input reduced {self.encoder.downsampling}x '
                             f'cannot be decoded to {cfg.location_resolution} px')
        ups = int(round(math.log2(cfg.location_resolution // bottleneck)))
        if 2 ** ups * bottleneck != cfg.location_resolution:
            raise ValueError('location_resolution must be a power-of-two multiple of the '
                             'encoder output size')
        widths = list(cfg.location_decoder_widths[:ups])
        widths += [widths[-1] if widths else self.encoder.out_channels] * (ups - len(widths))
        # Skip features by resolution (finest first); the bottleneck itself is not a skip.
        self.skips = cfg.location_skips
        sizes = self._feature_sizes(cfg.resolution)
        self.skip_at: list[int | None] = []
        layers, cin, size = [], self.encoder.out_channels, bottleneck
        for w in widths:
            size *= 2
            k = sizes.index(size) if self.skips and size in sizes[:-1] else None
            self.skip_at.append(k)
            layers.append(UpBlock(cin, w, self.encoder.skip_channels[k] if k is not None else 0))
            cin = w
        self.decoder = nn.ModuleList(layers)
        p = cfg.location_dropout
        self.drop_in, self.drop_mid, self.drop_out = nn.Dropout(p), nn.Dropout(p), nn.Dropout(p)
        self.final = nn.Conv2d(cin, num_categories + 1, 1)
        # Made after ``final`` so that the other layers start from the same weights either way.
        self.offset = nn.Conv2d(cin, 2, 1) if cfg.location_offsets else None

    def _feature_sizes(self, resolution: int) -> list[int]:
        with torch.no_grad():
            was = self.encoder.training
            self.encoder.eval()
            feats = self.encoder.features(torch.zeros(1, self.encoder.stem[0].in_channels,
                                                      resolution, resolution))
            self.encoder.train(was)
        return [f.shape[-1] for f in feats]

    def forward(self, image: torch.Tensor) -> torch.Tensor:
        return self.predict(image)[0]

    def predict(self, image: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor | None]:
        """The logits and, with ``location_offsets``, the offsets (else None)."""
        image = self.drop_in(image)
        if self.skips:
            feats = self.encoder.features(image)
            x = self.drop_mid(feats[-1])
        else:
            feats, x = [], self.drop_mid(self.encoder(image))
        for layer, k in zip(self.decoder, self.skip_at, strict=True):
            x = layer(x, feats[k] if k is not None else None)
        x = self.drop_out(x)
        return self.final(x), (self.offset(x) if self.offset is not None else None)


def location_loss(logits: torch.Tensor, target: torch.Tensor, empty_weight: float
                  ) -> torch.Tensor:
    """Pixel-wise cross-entropy where "empty" pixels weigh ``empty_weight`` and object
    centroids 1 (the targets are sparse: a handful of centroids among thousands of pixels)."""
    weight = torch.ones(logits.shape[1], device=logits.device)
    weight[0] = empty_weight
    return nn.functional.cross_entropy(logits, target, weight=weight)


def offset_loss(offsets: torch.Tensor, target: torch.Tensor, marked: torch.Tensor
                ) -> torch.Tensor:
    """Mean absolute error of the offsets (B x 2 x L x L, pixels) on the ``marked`` pixels
    (B x L x L, those of an object's target); 0 when none is marked."""
    mask = marked.unsqueeze(1).expand_as(offsets)
    if not bool(mask.any()):
        return offsets.sum() * 0.0
    return (offsets - target).abs()[mask].mean()


def location_distribution(logits: torch.Tensor, category: int, mask: np.ndarray,
                          temperature: float = 0.8) -> np.ndarray | None:
    """The sampling distribution over the ``L x L`` grid for ``category`` (index into the
    room type's categories): the category's channel of the per-pixel softmax, zero outside
    ``mask`` (the floor, or the surfaces that can support a second-tier category), then
    tempered as ``p ** (1 / temperature)``. ``None`` when the mask leaves nothing."""
    if temperature <= 0:
        raise ValueError('the location temperature must be positive')
    with torch.no_grad():
        logp = torch.log_softmax(logits.float(), dim=0)[1 + category].cpu().numpy()
    logp = logp.astype(np.float64) / temperature
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
