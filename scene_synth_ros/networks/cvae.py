"""The conditional variational autoencoder shared by the orientation and dimension modules."""
from __future__ import annotations

import torch
from torch import nn

from .blocks import PerCategoryLinear, PooledEncoder, mlp
from .config import ModelConfig


class ConditionalVAE(nn.Module):
    """p(y | image, category) with a latent z: an image encoder gives the condition; the
    recognition network q(z | condition, y) is used in training only; the decoder maps
    (condition, z) through a trunk to a per-category output layer."""

    def __init__(self, in_channels: int, num_categories: int, target_dim: int, out_dim: int,
                 cfg: ModelConfig):
        super().__init__()
        self.latent = cfg.latent
        self.encoder = PooledEncoder(in_channels, cfg.local_encoder)
        self.embed = nn.Embedding(num_categories, 16)
        cond = self.encoder.out_features + 16
        self.recognition = mlp([cond + target_dim, cfg.hidden, 2 * cfg.latent])
        self.trunk = nn.Sequential(mlp([cond + cfg.latent, cfg.hidden]), nn.ReLU(inplace=True))
        self.head = PerCategoryLinear(num_categories, cfg.hidden, out_dim)

    def condition(self, image: torch.Tensor, category: torch.Tensor) -> torch.Tensor:
        return torch.cat([self.encoder(image), self.embed(category)], dim=1)

    def decode(self, cond: torch.Tensor, category: torch.Tensor, z: torch.Tensor):
        return self.head(self.trunk(torch.cat([cond, z], dim=1)), category)

    def forward(self, image, category, target):
        """Training pass: (decoded output, mu, logvar) with z drawn from q."""
        cond = self.condition(image, category)
        mu, logvar = self.recognition(torch.cat([cond, target], dim=1)).chunk(2, dim=1)
        logvar = logvar.clamp(-10, 10)
        z = mu + torch.randn_like(mu) * torch.exp(0.5 * logvar)
        return self.decode(cond, category, z), mu, logvar

    def sample(self, image, category, generator: torch.Generator | None = None):
        """Decoded outputs for z drawn from the prior N(0, I)."""
        cond = self.condition(image, category)
        return self.decode(cond, category, self.noise(cond.shape[0], generator, cond.device))

    def noise(self, n: int, generator: torch.Generator | None, device: torch.device
              ) -> torch.Tensor:
        """``n`` draws of z from the prior, on ``device``. Drawn where the generator lives
        (synthesis seeds a CPU one), then moved: the same seed gives the same noise on every
        device."""
        gen_device = generator.device if generator is not None else device
        return torch.randn(n, self.latent, generator=generator, device=gen_device).to(device)


def kl_to_prior(mu: torch.Tensor, logvar: torch.Tensor) -> torch.Tensor:
    """KL(q(z) || N(0, I)) per example."""
    return -0.5 * torch.sum(1 + logvar - mu.pow(2) - logvar.exp(), dim=1)
