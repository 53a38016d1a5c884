"""Dimensions module (paper, section 4.4): the footprint of an object at a location and
orientation. The CVAE sees the scene rotated into the object's frame and predicts the
footprint's extent along the object's x (depth) and y (width) axes; an extra adversarial
loss comes from a discriminator that sees the scene with the signed distance field of the
predicted box."""
from __future__ import annotations

import math

import torch
from torch import nn

from .blocks import mlp
from .config import ModelConfig
from .cvae import ConditionalVAE, kl_to_prior

# The decoder works in log metres; a Gaussian likelihood with sigma = 0.1 (about 10 %), or
# with a sigma learned per category and axis, starting there (``ModelConfig.dimensions_noise``).
SIGMA = 0.1
LOG_PRECISION = 1.0 / (2 * SIGMA ** 2)
SDF_SCALE = 0.25   # metres: the SDF channel holds tanh(distance / SDF_SCALE)


class DimensionsModel(ConditionalVAE):
    """Targets and outputs are log(depth), log(width) in metres."""

    def __init__(self, in_channels: int, num_categories: int, cfg: ModelConfig):
        super().__init__(in_channels, num_categories, 2, 2, cfg)
        # log sigma of the likelihood per category, (depth, width); None: fixed at SIGMA
        # and not drawn from.
        self.log_sigma = (nn.Parameter(torch.full((num_categories, 2), math.log(SIGMA)))
                          if cfg.dimensions_noise else None)

    def spread(self, category: torch.Tensor) -> torch.Tensor | None:
        """The likelihood's sigma for each of ``category`` (B x 2, log metres), or None
        when it is fixed."""
        if self.log_sigma is None:
            return None
        return torch.exp(self.log_sigma[category])


def dimensions_elbo(out: torch.Tensor, target: torch.Tensor, mu, logvar,
                    kl_weight: float = 1.0, log_sigma: torch.Tensor | None = None
                    ) -> tuple[torch.Tensor, torch.Tensor]:
    """The loss (weighted negative ELBO, batch mean) and the negative ELBO per example, up
    to the likelihood's constant. ``log_sigma`` (B x 2): the learned sigmas of the examples'
    categories; None: sigma fixed at SIGMA."""
    if log_sigma is None:
        recon = LOG_PRECISION * (out - target).pow(2).sum(dim=1)
    else:
        recon = (0.5 * (out - target).pow(2) * torch.exp(-2 * log_sigma) + log_sigma).sum(dim=1)
    kl = kl_to_prior(mu, logvar)
    return (recon + kl_weight * kl).mean(), recon + kl


def box_sdf(log_dims: torch.Tensor, resolution: int, extent: float) -> torch.Tensor:
    """(B, 1, N, N) signed distance (squashed by tanh) to boxes centred in a local image of
    side ``extent`` metres, of depth ``exp(log_dims[:, 0])`` along the columns and width
    ``exp(log_dims[:, 1])`` along the rows; differentiable in the dimensions."""
    m = extent / resolution
    axis = (torch.arange(resolution, device=log_dims.device) + 0.5 - resolution / 2) * m
    v, u = torch.meshgrid(axis, axis, indexing='ij')
    half = torch.exp(log_dims) / 2
    qx = u.abs()[None] - half[:, 0, None, None]
    qy = v.abs()[None] - half[:, 1, None, None]
    outside = torch.sqrt(qx.clamp_min(0) ** 2 + qy.clamp_min(0) ** 2 + 1e-12)
    inside = torch.maximum(qx, qy).clamp_max(0)
    return torch.tanh((outside + inside) / SDF_SCALE).unsqueeze(1)


class Discriminator(nn.Module):
    """Real or predicted footprint? Strided convolutions over the local image and the box's
    SDF, pooled, joined with the category, to one logit."""

    def __init__(self, in_channels: int, num_categories: int, cfg: ModelConfig):
        super().__init__()
        layers, cin = [], in_channels + 1
        for w in cfg.discriminator_widths:
            layers += [nn.Conv2d(cin, w, 4, 2, 1), nn.LeakyReLU(0.2, inplace=True)]
            cin = w
        self.conv = nn.Sequential(*layers)
        self.embed = nn.Embedding(num_categories, 16)
        self.head = mlp([cin + 16, cfg.hidden, 1])

    def forward(self, image, sdf, category):
        h = self.conv(torch.cat([image, sdf], dim=1)).mean(dim=(2, 3))
        return self.head(torch.cat([h, self.embed(category)], dim=1)).squeeze(1)
