"""ResNet building blocks, written here (no torchvision): the encoders of all four modules."""
from __future__ import annotations

import itertools

import torch
from torch import nn

from .config import EncoderConfig


class BasicBlock(nn.Module):
    """Two 3x3 convolutions with batch norm and an identity (or 1x1 projection) shortcut."""

    FOLDS = (('conv1', 'bn1'), ('conv2', 'bn2'))     # (convolution, its batch norm)

    def __init__(self, cin: int, cout: int, stride: int = 1):
        super().__init__()
        self.conv1 = nn.Conv2d(cin, cout, 3, stride, 1, bias=False)
        self.bn1 = nn.BatchNorm2d(cout)
        self.conv2 = nn.Conv2d(cout, cout, 3, 1, 1, bias=False)
        self.bn2 = nn.BatchNorm2d(cout)
        self.shortcut = nn.Identity()
        if stride != 1 or cin != cout:
            self.shortcut = nn.Sequential(nn.Conv2d(cin, cout, 1, stride, bias=False),
                                          nn.BatchNorm2d(cout))

    def forward(self, x):
        y = torch.relu(self.bn1(self.conv1(x)))
        y = self.bn2(self.conv2(y))
        return torch.relu(y + self.shortcut(x))


class ResNetEncoder(nn.Module):
    """Stem, then one stage per entry of ``cfg.blocks`` (each stage after the first halves
    the resolution). ``forward`` returns the last feature map; ``out_channels`` its depth and
    ``downsampling`` the total reduction of the image side."""

    def __init__(self, in_channels: int, cfg: EncoderConfig):
        super().__init__()
        w0 = cfg.widths[0]
        stem = [nn.Conv2d(in_channels, w0, 3, cfg.stem_stride, 1, bias=False),
                nn.BatchNorm2d(w0), nn.ReLU(inplace=True)]
        self.downsampling = cfg.stem_stride
        if cfg.stem_pool:
            stem.append(nn.MaxPool2d(3, 2, 1))
            self.downsampling *= 2
        self.stem = nn.Sequential(*stem)
        stages, cin = [], w0
        # A configuration may list more widths than stages (one width list serves encoders
        # of several depths); the stages take the first ones.
        for k, (n, w) in enumerate(zip(cfg.blocks, cfg.widths, strict=False)):
            stride = 1 if k == 0 else 2
            if k:
                self.downsampling *= 2
            blocks = [BasicBlock(cin, w, stride)] + [BasicBlock(w, w) for _ in range(n - 1)]
            stages.append(nn.Sequential(*blocks))
            cin = w
        self.stages = nn.Sequential(*stages)
        self.out_channels = cin
        self.skip_channels = [cfg.widths[0]] + [w for w in cfg.widths[:len(cfg.blocks)]]

    def forward(self, x):
        return self.stages(self.stem(x))

    def features(self, x) -> list:
        """The stem's output before pooling and every stage's output, finest first (for
        skip connections); the last one is what ``forward`` returns."""
        stem = list(self.stem)
        pool = stem.pop() if isinstance(stem[-1], nn.MaxPool2d) else None
        for layer in stem:
            x = layer(x)
        out = [x]
        if pool is not None:
            x = pool(x)
        for stage in self.stages:
            x = stage(x)
            out.append(x)
        return out


class PooledEncoder(nn.Module):
    """A ``ResNetEncoder`` followed by global average pooling: image -> feature vector."""

    def __init__(self, in_channels: int, cfg: EncoderConfig):
        super().__init__()
        self.body = ResNetEncoder(in_channels, cfg)
        self.out_features = self.body.out_channels

    def forward(self, x):
        return self.body(x).mean(dim=(2, 3))


class UpBlock(nn.Module):
    """Nearest-neighbour 2x upsampling and a 3x3 convolution (the paper's up-convolution,
    which avoids the checkerboard artefacts of transposed convolutions), optionally over the
    upsampled map joined with a skip feature map of the new resolution."""

    FOLDS = (('conv', 'bn'),)

    def __init__(self, cin: int, cout: int, skip: int = 0):
        super().__init__()
        self.conv = nn.Conv2d(cin + skip, cout, 3, 1, 1, bias=False)
        self.bn = nn.BatchNorm2d(cout)

    def forward(self, x, skip=None):
        x = nn.functional.interpolate(x, scale_factor=2, mode='nearest')
        if skip is not None:
            x = torch.cat([x, skip], dim=1)
        return torch.relu(self.bn(self.conv(x)))


def fold_batch_norm(conv: nn.Conv2d, bn: nn.BatchNorm2d) -> nn.Conv2d:
    """One convolution that computes ``bn(conv(x))`` as ``bn`` does in evaluation (with its
    running statistics): the batch norm's scale goes into the weights, its shift into a
    bias."""
    if bn.running_var is None or bn.running_mean is None:
        raise ValueError('a batch norm without running statistics cannot be folded')
    scale = torch.rsqrt(bn.running_var + bn.eps)
    shift = -bn.running_mean * scale
    if bn.affine:
        scale, shift = scale * bn.weight, shift * bn.weight + bn.bias
    fused = nn.Conv2d(conv.in_channels, conv.out_channels, conv.kernel_size, conv.stride,
                      conv.padding, conv.dilation, conv.groups, bias=True,
                      padding_mode=conv.padding_mode, device=conv.weight.device)
    with torch.no_grad():
        fused.weight.copy_(conv.weight * scale.reshape(-1, 1, 1, 1))
        bias = shift if conv.bias is None else conv.bias * scale + shift
        fused.bias.copy_(bias)
    return fused.requires_grad_(False).eval()


def fold_batch_norms(net: nn.Module) -> nn.Module:
    """``net``, in evaluation mode, with every batch norm folded into the convolution before
    it (``fold_batch_norm``), in place: a layer fewer per convolution, 1.15-1.24x faster a pass
    alone and up to 1.11x in a batch of 10 (``docs/design/investigations.md``). Outputs
    agree with the unfolded network's to float32 rounding (within 1e-6 of the largest), not
    bit for bit; inference only, as a folded network cannot be trained or saved as a
    bundle."""
    if net.training:
        raise ValueError('batch norms fold only in evaluation mode, where they are constant')
    for module in list(net.modules()):
        for conv, bn in getattr(module, 'FOLDS', ()):
            if isinstance(getattr(module, bn), nn.BatchNorm2d):
                setattr(module, conv, fold_batch_norm(getattr(module, conv), getattr(module, bn)))
                setattr(module, bn, nn.Identity())
        if isinstance(module, nn.Sequential):
            for k in range(len(module) - 1):
                if isinstance(module[k], nn.Conv2d) and isinstance(module[k + 1], nn.BatchNorm2d):
                    module[k] = fold_batch_norm(module[k], module[k + 1])
                    module[k + 1] = nn.Identity()
    return net


def mlp(sizes: list[int], dropout: float = 0.0) -> nn.Sequential:
    """Linear layers with ReLU between them (none after the last)."""
    layers: list[nn.Module] = []
    for k, (a, b) in enumerate(itertools.pairwise(sizes)):
        layers.append(nn.Linear(a, b))
        if k < len(sizes) - 2:
            layers.append(nn.ReLU(inplace=True))
            if dropout:
                layers.append(nn.Dropout(dropout))
    return nn.Sequential(*layers)


class PerCategoryLinear(nn.Module):
    """A separate linear output layer for every category, applied to each example with the
    weights of its own category: the per-category heads of the orientation, snap and
    dimension modules share a trunk but never each other's outputs."""

    def __init__(self, num_categories: int, cin: int, cout: int):
        super().__init__()
        self.weight = nn.Parameter(torch.empty(num_categories, cin, cout))
        self.bias = nn.Parameter(torch.zeros(num_categories, cout))
        bound = cin ** -0.5          # nn.Linear's default initialisation, per category
        nn.init.uniform_(self.weight, -bound, bound)

    def forward(self, x, category):
        return torch.bmm(x.unsqueeze(1), self.weight[category]).squeeze(1) + self.bias[category]
