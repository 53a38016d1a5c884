"""Real vs synthetic classifier (paper, table 2).

A ResNet-34-style network (stages of 3, 4, 6 and 3 ``BasicBlock``s, narrow widths for a
CPU) reads the same multi-channel top-down image the pipeline's networks see (the room's
global view, ``Frame.for_room``, at the shipped weights' resolution) and says whether a room
came from the training corpus ("real") or from elsewhere ("fake": synthesized, or a
perturbed held-out corpus room). It is trained on a balanced set and scored on a balanced
held-out set; 50 % accuracy means it cannot tell the two apart.

Training: binary cross-entropy, Adam with cosine learning-rate decay, every training image
drawn from the room turned by a random multiple of 90 degrees (the room's images turn
exactly with it), test images unturned. Initial weights, batch order and turns come from
the seed, so a run is reproducible on one torch thread.
"""
from __future__ import annotations

from dataclasses import dataclass
import math
import time
from typing import Protocol, Sequence

import numpy as np
import torch
from torch import nn
from tqdm import tqdm

from ..networks.blocks import ResNetEncoder
from ..networks.config import EncoderConfig
from ..networks.examples import padded_batch, rotate_scene
from ..render import Frame, TopDownRenderer
from ..scene import Scene


@dataclass
class ClassifierConfig:
    blocks: tuple[int, ...] = (3, 4, 6, 3)         # ResNet-34's stages
    widths: tuple[int, ...] = (16, 32, 64, 128)    # a quarter of ResNet-34's
    epochs: int = 12
    batch_size: int = 32
    lr: float = 1e-3
    weight_decay: float = 1e-4
    augment: bool = True                           # random 90-degree turns while training


class RealFakeNet(nn.Module):
    """ResNet encoder, global average pooling, one logit (positive: fake)."""

    def __init__(self, in_channels: int, cfg: ClassifierConfig):
        super().__init__()
        self.encoder = ResNetEncoder(in_channels, EncoderConfig(tuple(cfg.blocks),
                                                                tuple(cfg.widths)))
        self.head = nn.Linear(self.encoder.out_channels, 1)

    def forward(self, x):
        return self.head(self.encoder(x).mean(dim=(2, 3)))[:, 0]


class Images(Protocol):
    """Where a classifier's inputs come from: ``len``, per-item ``labels`` (1 = fake) and
    ``batch(indices, turns)`` giving a float tensor (B, C, N, N)."""

    labels: np.ndarray

    def __len__(self) -> int: ...

    def batch(self, indices: np.ndarray, turns: np.ndarray | None) -> torch.Tensor: ...


class SceneImages:
    """Rooms rendered on demand (a whole set of 46-channel images would not fit in memory
    comfortably), each turned by ``turns[i]`` quarter turns first."""

    def __init__(self, scenes: Sequence[Scene], labels: Sequence[int], resolution: int):
        if len(scenes) != len(labels):
            raise ValueError(f'{len(scenes)} scenes given with {len(labels)} labels')
        self.scenes = list(scenes)
        self.labels = np.asarray(labels, dtype=np.float32)
        self.renderer = TopDownRenderer(resolution, cache_size=64)
        self._renderers = {resolution: self.renderer}
        self.resolution = resolution

    def __len__(self) -> int:
        return len(self.scenes)

    def channels(self) -> int:
        return self.renderer.num_channels(self.scenes[0].room.room_type)

    def batch(self, indices, turns=None) -> torch.Tensor:
        out = []
        for k, i in enumerate(indices):
            s = self.scenes[int(i)]
            if turns is not None and turns[k]:
                s = rotate_scene(s, int(turns[k]))
            # A room larger than its type's square is seen larger, at the same pixel size,
            # as the synthesizer sees it; the classifier pools globally over any size.
            frame = Frame.for_room(s.room, self.resolution, multiple=2)
            if frame.resolution not in self._renderers:
                self._renderers[frame.resolution] = TopDownRenderer(frame.resolution,
                                                                    cache_size=64)
            out.append(self._renderers[frame.resolution].render(s, frame))
        return padded_batch(out)


class TensorImages:
    """Images already in memory. Turns rotate the pixels only, leaving the orientation
    channels' values alone: fine for synthetic inputs, not for rendered rooms."""

    def __init__(self, images: torch.Tensor, labels: Sequence[int]):
        self.images = images
        self.labels = np.asarray(labels, dtype=np.float32)

    def __len__(self) -> int:
        return len(self.images)

    def channels(self) -> int:
        return int(self.images.shape[1])

    def batch(self, indices, turns=None) -> torch.Tensor:
        x = self.images[torch.as_tensor(np.asarray(indices, dtype=np.int64))]
        if turns is not None:
            x = torch.stack([torch.rot90(im, int(t), (1, 2))
                             for im, t in zip(x, turns, strict=True)])
        return x


def train_classifier(train: Images, cfg: ClassifierConfig, seed: int,
                     progress: bool = False, desc: str | None = None
                     ) -> tuple[RealFakeNet, float]:
    """A classifier fitted to ``train``, and its accuracy on the last epoch's batches."""
    rng = np.random.default_rng(seed)
    torch.manual_seed(int(rng.integers(2 ** 31)))
    net = RealFakeNet(train.channels(), cfg)
    opt = torch.optim.Adam(net.parameters(), cfg.lr, weight_decay=cfg.weight_decay)
    steps_per_epoch = math.ceil(len(train) / cfg.batch_size)
    total = max(1, cfg.epochs * steps_per_epoch)
    sched = torch.optim.lr_scheduler.LambdaLR(
        opt, lambda step: 0.5 * (1 + math.cos(math.pi * min(step, total) / total)))
    labels = torch.from_numpy(train.labels)
    correct = seen = 0
    net.train()
    bar = tqdm(total=total, desc=desc, disable=not progress, leave=False, unit='step')
    for _ in range(cfg.epochs):
        order = rng.permutation(len(train))
        correct = seen = 0
        for start in range(0, len(order), cfg.batch_size):
            idx = order[start:start + cfg.batch_size]
            turns = rng.integers(0, 4, len(idx)) if cfg.augment else None
            x, y = train.batch(idx, turns), labels[idx]
            logits = net(x)
            loss = nn.functional.binary_cross_entropy_with_logits(logits, y)
            opt.zero_grad()
            loss.backward()
            opt.step()
            sched.step()
            correct += int(((logits.detach() > 0).float() == y).sum())
            seen += len(idx)
            bar.update()
    bar.close()
    net.eval()
    return net, correct / max(seen, 1)


@torch.inference_mode()
def accuracy(net: nn.Module, data: Images, batch_size: int = 64) -> float:
    """Fraction of ``data`` classified correctly (logit > 0 means fake)."""
    net.eval()
    correct = 0
    for start in range(0, len(data), batch_size):
        idx = np.arange(start, min(start + batch_size, len(data)))
        pred = (net(data.batch(idx, None)) > 0).float().numpy()
        correct += int((pred == data.labels[idx]).sum())
    return correct / max(len(data), 1)


def split(real: Sequence[Scene], fake: Sequence[Scene], n_train: int, n_test: int
          ) -> tuple[list[Scene], list[int], list[Scene], list[int]]:
    """Balanced train and test sets: the first n_train/2 of each side train, the next
    n_test/2 test."""
    ht, hs = n_train // 2, n_test // 2
    if min(len(real), len(fake)) < ht + hs:
        raise ValueError(f'the classifier needs {ht + hs} rooms of each side, got '
                         f'{len(real)} real and {len(fake)} fake')
    train = list(real[:ht]) + list(fake[:ht])
    test = list(real[ht:ht + hs]) + list(fake[ht:ht + hs])
    return train, [0] * ht + [1] * ht, test, [0] * hs + [1] * hs


def real_vs_fake(real: Sequence[Scene], fake: Sequence[Scene], n_train: int, n_test: int,
                 resolution: int, cfg: ClassifierConfig, seed: int, progress: bool = False,
                 desc: str | None = None) -> dict:
    """Train on a balanced split of ``real`` and ``fake`` and score on the held-out rest."""
    t0 = time.perf_counter()
    tr, ytr, te, yte = split(real, fake, n_train, n_test)
    net, train_acc = train_classifier(SceneImages(tr, ytr, resolution), cfg, seed, progress,
                                      desc)
    acc = accuracy(net, SceneImages(te, yte, resolution))
    n = len(te)
    return {'accuracy': acc, 'stderr': math.sqrt(acc * (1 - acc) / n) if n else math.nan,
            'train_accuracy': train_acc, 'train': len(tr), 'test': n,
            'seconds': time.perf_counter() - t0}


def run_job(job) -> tuple[str, dict]:
    """One entry of a parallel map: (name, real, fake, n_train, n_test, resolution,
    config, seed) -> (name, scores)."""
    name, real, fake, n_train, n_test, resolution, cfg, seed = job
    return name, real_vs_fake(real, fake, n_train, n_test, resolution, cfg, seed)
