"""Location module (paper, section 4.2): where in the room an object of each category goes."""
from __future__ import annotations

import math

import torch
from torch import nn

from .blocks import ResNetEncoder, UpBlock
from .config import ModelConfig


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
