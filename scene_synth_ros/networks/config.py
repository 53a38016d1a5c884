"""Configuration of the four networks and of their training, read from YAML.

Two shipped configurations live in ``config/``: ``compact.yaml`` (the default: 64 px images,
quarter-width ResNets, sized so that all four room types train on a 2-core CPU within four
hours) and ``paper.yaml`` (the paper's 256 px input and full ResNet-18/34 widths).
"""
from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields, is_dataclass, replace
import json
from pathlib import Path
from typing import Any

import yaml

from ..errors import quoted


@dataclass
class EncoderConfig:
    """A ResNet-style encoder: ``blocks`` basic blocks per stage, ``widths`` channels."""

    blocks: tuple[int, ...] = (2, 2, 2, 2)
    widths: tuple[int, ...] = (16, 32, 64, 128)
    stem_stride: int = 2       # the stem convolution's stride
    stem_pool: bool = True     # a 2x max-pool after the stem, as in ResNet


@dataclass
class ModelConfig:
    """Sizes of the networks. ``resolution`` is the input image side; the location module
    always answers on a ``location_resolution`` grid (64 in the paper)."""

    resolution: int = 64
    location_resolution: int = 64
    category_encoder: EncoderConfig = field(default_factory=EncoderConfig)
    location_encoder: EncoderConfig = field(
        default_factory=lambda: EncoderConfig(blocks=(3, 4, 6, 3)))
    location_decoder_widths: tuple[int, ...] = (64, 32, 32, 16, 16)
    location_dropout: float = 0.1
    # U-Net-style skips from the encoder into the decoder. The paper decodes from the 8 x 8
    # bottleneck of a 256 px input; a compact 64 px encoder ends at 2 x 2, from which alone
    # the decoder cannot place anything finer than a quarter of the room.
    location_skips: bool = True
    # A per-pixel offset to the centroid, regressed beside the heat map (as CenterNet does),
    # so that a drawn location is put where the object's centre is, not anywhere in its pixel
    # or the target's block (``docs/design/investigations.md``). Off in the shipped
    # configuration: in 1,200 compact steps the offsets stayed near their zero baseline (0.60
    # pixels of error against 0.75) and cost the heat maps (held-out cross-entropy 0.328
    # against 0.280 in bedrooms), where ``SynthConfig.location_mode`` gets the precision.
    location_offsets: bool = False
    local_encoder: EncoderConfig = field(
        default_factory=lambda: EncoderConfig(blocks=(1, 1, 1, 1)))
    count_features: int = 64       # width of the bag-of-categories MLP
    hidden: int = 128              # width of the MLP heads
    latent: int = 8                # CVAE latent dimension (orientation and dimensions)
    # The dimensions module's likelihood with a spread learned per category and axis
    # (``DimensionsModel.log_sigma``), drawn from at synthesis: footprint = decoded mean times
    # exp(sigma * noise). On in every configuration of config/ and in the shipped weights;
    # off (bundles made before it), the likelihood's sigma is fixed at 0.1 and synthesis takes
    # the mean, whose draws spread over a third of the corpus's sizes
    # (``docs/design/investigations.md``).
    dimensions_noise: bool = False
    discriminator_widths: tuple[int, ...] = (16, 32, 64, 64)


# The model settings that one module's network alone reads: a bundle may take its other
# modules from bundles made with other values of these (``train --others-from``).
OWN_SETTINGS: dict[str, tuple[str, ...]] = {
    'category': ('category_encoder', 'count_features'),
    'location': ('location_resolution', 'location_encoder', 'location_decoder_widths',
                 'location_dropout', 'location_skips', 'location_offsets'),
    'dimensions': ('discriminator_widths', 'dimensions_noise'),
}


def settings_differing(a: ModelConfig, b: ModelConfig) -> set[str]:
    """The names of the model settings whose values differ between ``a`` and ``b``."""
    return {f.name for f in fields(ModelConfig) if getattr(a, f.name) != getattr(b, f.name)}


@dataclass
class ModuleSchedule:
    steps: int
    batch_size: int = 64
    lr: float = 1e-3
    weight_decay: float = 1e-5


@dataclass
class TrainConfig:
    """How the networks are trained. Steps are per module and per room type. The defaults
    are the compact configuration's (``config/compact.yaml``)."""

    seed: int = 0
    corpus_seed: int = 0
    train_rooms: int = 3000
    val_rooms: int = 200
    val_examples: int = 512
    val_every: int = 250
    checkpoint_every: int = 100
    threads: int = 0                       # torch threads; 0 = all cores
    # Processes that make the batches ahead of the training step (torch's DataLoader); 0:
    # the training process makes each batch itself. Batches are pure functions of their
    # seed, so the weights do not depend on it; on a GPU, rendering is the bottleneck.
    loader_workers: int = 0
    category: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(4000))
    location: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(1200, 32))
    orientation: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(2400))
    snap: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(400))
    dimensions: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(600))
    empty_weight: float = 0.1              # location: weight of empty pixels vs centroids
    location_target_radius: int = 1        # location: centroid marked on (2r+1)^2 pixels
    kl_weight: float = 1.0                 # CVAE: weight of the KL term
    adversarial_weight: float = 0.05       # dimensions: weight of the discriminator's loss


@dataclass
class PipelineConfig:
    """Everything a training run or a synthesizer needs to know about the networks."""

    name: str = 'compact'
    device: str = 'auto'                    # cpu | cuda | auto
    model: ModelConfig = field(default_factory=ModelConfig)
    train: TrainConfig = field(default_factory=TrainConfig)

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> 'PipelineConfig':
        return _build(cls, d, 'config')

    @classmethod
    def from_yaml(cls, path: str | Path) -> 'PipelineConfig':
        with open(path, encoding='utf-8') as f:
            data = yaml.safe_load(f)
        if not isinstance(data, dict):
            raise ValueError(f'{path}: a configuration must be a YAML mapping')
        return cls.from_dict(data)


def _build(cls, data: Any, where: str, base=None):
    """A dataclass from a nested mapping over the defaults in ``base``, refusing unknown
    keys so that a typo in a YAML file is an error instead of a silently ignored setting."""
    if not isinstance(data, dict):
        raise ValueError(f'{where}: expected a mapping, got {type(data).__name__}')
    known = {f.name: f for f in fields(cls)}
    unknown = sorted(set(data) - set(known))
    if unknown:
        raise ValueError(f'{where}: unknown setting {unknown[0]!r}; expected one of '
                         f'{", ".join(known)}')
    kwargs = {}
    defaults = base if base is not None else cls()
    for name, value in data.items():
        current = getattr(defaults, name)
        if is_dataclass(current):
            kwargs[name] = _build(type(current), value, f'{where}.{name}', current)
        elif isinstance(current, tuple):
            if not isinstance(value, (list, tuple)):
                raise ValueError(f'{where}.{name}: expected a list')
            kwargs[name] = tuple(value)
        elif isinstance(current, bool):
            if not isinstance(value, bool):
                raise ValueError(f'{where}.{name}: expected true or false')
            kwargs[name] = value
        elif isinstance(current, (int, float)):
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise ValueError(f'{where}.{name}: expected a number')
            kwargs[name] = type(current)(value)
        else:
            kwargs[name] = value
    return replace(defaults, **kwargs)


def resolve_device(name: str):
    """A torch device for ``cpu | cuda | auto`` (auto: cuda when available)."""
    import torch  # heavy: scene-synth --help reads this module, only a device needs torch
    if name == 'auto':
        return torch.device('cuda' if torch.cuda.is_available() else 'cpu')
    if name == 'cuda' and not torch.cuda.is_available():
        raise ValueError('device cuda was asked for, but torch sees no CUDA device')
    if name not in ('cpu', 'cuda'):
        raise ValueError(f'unknown device {name!r}; expected cpu, cuda or auto')
    return torch.device(name)


# What runs synthesis's forward passes (``networks/runtime.py``).
RUNTIMES = ('auto', 'torch', 'onnxruntime')


def onnxruntime_available() -> bool:
    try:
        import onnxruntime  # noqa: F401  optional: probed, not used
    except ImportError:
        return False
    return True


def resolve_runtime(runtime: str, device) -> str:
    """``torch`` or ``onnxruntime`` for ``runtime`` (one of ``RUNTIMES``) on ``device`` (a
    torch device), as ``runtime.py`` says; ValueError, one sentence, where that cannot be."""
    if runtime not in RUNTIMES:
        raise ValueError(f'no runtime {quoted(runtime)}; the runtimes are {", ".join(RUNTIMES)}')
    if runtime == 'torch':
        return runtime
    if runtime == 'auto':
        return 'onnxruntime' if device.type == 'cpu' and onnxruntime_available() else 'torch'
    if device.type != 'cpu':
        raise ValueError(f'the onnxruntime runtime runs on the CPU, not on {device.type}; '
                         'use the torch runtime there')
    if not onnxruntime_available():
        raise ValueError('the onnxruntime runtime needs the onnxruntime package '
                         '(pip install -r requirements.txt)')
    return runtime
