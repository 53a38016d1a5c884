"""Next-category module (paper, section 4.1): what kind of object to add next, or STOP."""
from __future__ import annotations

import torch
from torch import nn

from .blocks import PooledEncoder, mlp
from .config import ModelConfig


class CategoryModel(nn.Module):
    """ResNet-18-style encoder of the top-down image and an MLP over the bag of categories
    already in the room, fused into ``C + 1`` logits; the last one is STOP."""

    def __init__(self, in_channels: int, num_categories: int, cfg: ModelConfig):
        super().__init__()
        self.num_categories = num_categories
        self.encoder = PooledEncoder(in_channels, cfg.category_encoder)
        self.counts = mlp([num_categories, cfg.count_features, cfg.count_features])
        self.head = mlp([self.encoder.out_features + cfg.count_features, cfg.hidden,
                         num_categories + 1], dropout=0.2)

    def forward(self, image: torch.Tensor, counts: torch.Tensor) -> torch.Tensor:
        feats = torch.cat([self.encoder(image), torch.relu(self.counts(counts))], dim=1)
        return self.head(feats)
