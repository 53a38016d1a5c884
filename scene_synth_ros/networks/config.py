"""Configuration of the four networks and of their training, read from YAML.

Shipped configurations live in ``config/``: ``compact.yaml`` (the default: 64 px images,
quarter-width ResNets, sized so that the paper's four room types train on a 2-core CPU
within four hours), ``paper.yaml`` (the paper's 256 px input and full ResNet-18/34 widths) and
``shipped.yaml`` (the compact networks with the schedules of the shipped weights: some
modules, and one module of one room type, train apart from the ``train`` section, stated in
its ``modules`` and ``room_types`` sections).
"""
from __future__ import annotations

from dataclasses import asdict, dataclass, field, fields, is_dataclass, replace
from importlib import metadata
import json
import math
from pathlib import Path
from typing import Any

import yaml

from ..errors import quoted
from . import NETWORKS


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
    # Corpus rooms sized as real rooms of their type are (``corpus.shell.sample_shell``),
    # up to 16 m, instead of within the type's square as the paper's (and the shipped
    # bundles', until they are trained again: docs/training.md).
    real_sizes: bool = False
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
    # Category and location batches of rooms of like size (``examples.SizeBuckets``): at
    # least this many training rooms a bucket, 0 for batches of any rooms. A batch is padded
    # to its largest room, so with rooms up to 16 m nearly every batch of any rooms is the
    # size of the largest; a room's chance to be drawn is the same either way.
    size_buckets: int = 0
    category: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(4000))
    location: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(1200, 32))
    orientation: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(2400))
    snap: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(400))
    dimensions: ModuleSchedule = field(default_factory=lambda: ModuleSchedule(600))
    empty_weight: float = 0.1              # location: weight of empty pixels vs centroids
    location_target_radius: int = 1        # location: centroid marked on (2r+1)^2 pixels
    kl_weight: float = 1.0                 # CVAE: weight of the KL term
    adversarial_weight: float = 0.05       # dimensions: weight of the discriminator's loss


# The settings of ``TrainConfig`` that one module's training may take apart from the other
# modules' (``ModuleOverride``): the others (seed, held-out rooms, loss weights...) are one
# for the whole room type, or read by one module alone already.
MODULE_RUN_SETTINGS = ('train_rooms', 'val_every', 'checkpoint_every')


@dataclass
class ModuleOverride:
    """Where one module's training departs from the ``train`` section: its schedule
    (``ModuleSchedule``'s settings) and ``MODULE_RUN_SETTINGS``; None keeps the section's."""

    steps: int | None = None
    batch_size: int | None = None
    lr: float | None = None
    weight_decay: float | None = None
    train_rooms: int | None = None
    val_every: int | None = None
    checkpoint_every: int | None = None

    def set(self) -> dict[str, int | float]:
        """The settings it gives, by name."""
        return {k: v for k, v in asdict(self).items() if v is not None}


@dataclass
class PipelineConfig:
    """Everything a training run or a synthesizer needs to know about the networks.

    ``modules`` (module name -> ``ModuleOverride``) and ``room_types`` (room type -> module
    name -> ``ModuleOverride``) let single modules train apart from ``train``: the settings
    of ``module`` of a room type are ``train``'s, then ``modules``', then ``room_types``'
    (``module_train``)."""

    name: str = 'compact'
    device: str = 'auto'                    # cpu | cuda | auto
    model: ModelConfig = field(default_factory=ModelConfig)
    train: TrainConfig = field(default_factory=TrainConfig)
    modules: dict[str, ModuleOverride] = field(default_factory=dict)
    room_types: dict[str, dict[str, ModuleOverride]] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        # Without overrides a configuration writes what it wrote before they existed.
        for key in ('modules', 'room_types'):
            d.pop(key)
        if self.modules:
            d['modules'] = {m: o.set() for m, o in self.modules.items()}
        if self.room_types:
            d['room_types'] = {rt: {m: o.set() for m, o in mods.items()}
                               for rt, mods in self.room_types.items()}
        return d

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> 'PipelineConfig':
        if not isinstance(d, dict):
            raise ValueError(f'config: expected a mapping, got {type(d).__name__}')
        rest = {k: v for k, v in d.items() if k not in ('modules', 'room_types')}
        cfg = _build(cls, rest, 'config')
        cfg.modules = _overrides(d.get('modules', {}), 'config.modules')
        rts = d.get('room_types', {})
        if not isinstance(rts, dict):
            raise ValueError(f'config.room_types: expected a mapping of room types, got '
                             f'{type(rts).__name__}')
        cfg.room_types = {str(rt): _overrides(mods, f'config.room_types.{str(rt)[:40]}')
                          for rt, mods in rts.items()}
        cfg.check_overrides()
        return cfg

    def module_train(self, module: str, room_type: str | None = None) -> TrainConfig:
        """The training settings ``module`` of ``room_type`` runs with: ``train`` with the
        departures of ``modules``, then of ``room_types``, applied."""
        if module not in NETWORKS:
            raise ValueError(f'unknown module {quoted(module)}; expected one of '
                             f'{", ".join(NETWORKS)}')
        t = self.train
        for o in (self.modules.get(module),
                  self.room_types.get(room_type, {}).get(module) if room_type else None):
            if o is None:
                continue
            given = o.set()
            run = {k: v for k, v in given.items() if k in MODULE_RUN_SETTINGS}
            sched = {k: v for k, v in given.items() if k not in MODULE_RUN_SETTINGS}
            t = replace(t, **run, **{module: replace(getattr(t, module), **sched)})
        return t

    def for_module(self, module: str, room_type: str | None = None) -> 'PipelineConfig':
        """This configuration as ``module`` of ``room_type`` trains with it: its settings
        (``module_train``) in ``train``, no overrides left."""
        return replace(self, train=self.module_train(module, room_type), modules={},
                       room_types={})

    def check_overrides(self) -> None:
        """ValueError, one sentence, where an override would train a module on rooms that
        the component table holds out (those after ``train.train_rooms``)."""
        sections = [(f'modules.{m}', o) for m, o in self.modules.items()] + \
            [(f'room_types.{rt}.{m}', o) for rt, mods in self.room_types.items()
             for m, o in mods.items()]
        for where, o in sections:
            if o.train_rooms is not None and o.train_rooms > self.train.train_rooms:
                raise ValueError(f'config.{where}.train_rooms: {o.train_rooms} is more than '
                                 f'train.train_rooms ({self.train.train_rooms}), past which '
                                 'the rooms are held out')

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


def _overrides(data: Any, where: str) -> dict[str, ModuleOverride]:
    """Module name -> ``ModuleOverride`` from a mapping; ValueError, one sentence, on an
    unknown module or setting or a value that is not a positive number."""
    if not isinstance(data, dict):
        raise ValueError(f'{where}: expected a mapping of modules, got {type(data).__name__}')
    out = {}
    known = [f.name for f in fields(ModuleOverride)]
    for module, settings in data.items():
        if module not in NETWORKS:
            raise ValueError(f'{where}: unknown module {quoted(module)}; expected one of '
                             f'{", ".join(NETWORKS)}')
        if not isinstance(settings, dict):
            raise ValueError(f'{where}.{module}: expected a mapping of settings, got '
                             f'{type(settings).__name__}')
        kwargs = {}
        for name, value in settings.items():
            if name not in known:
                raise ValueError(f'{where}.{module}: unknown setting {quoted(name)}; expected '
                                 f'one of {", ".join(known)}')
            integral = name not in ('lr', 'weight_decay')
            least = 0 if name == 'weight_decay' else 1 if integral else math.ulp(0)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                    not math.isfinite(value) or value < least or \
                    (integral and value != int(value)):
                kind = 'a positive whole number' if integral else \
                    'a number of 0 or more' if name == 'weight_decay' else 'a positive number'
                raise ValueError(f'{where}.{module}.{name}: expected {kind}, got '
                                 f'{quoted(value)}')
            kwargs[name] = int(value) if integral else float(value)
        out[module] = ModuleOverride(**kwargs)
    return out


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


def device_name(name: str) -> str:
    """``cpu`` or ``cuda`` for ``cpu | cuda | auto`` (``resolve_device``). ``cpu``, and
    ``auto`` where the installed torch is a CPU-only build (which sees no CUDA device), are
    named without importing torch (a second and a half)."""
    if name == 'cpu' or (name == 'auto' and _cpu_only_torch()):
        return 'cpu'
    return resolve_device(name).type


def _cpu_only_torch() -> bool:
    """Whether the installed torch is a CPU-only build (its version says ``+cpu``), read
    from its metadata."""
    try:
        return metadata.version('torch').endswith('+cpu')
    except metadata.PackageNotFoundError:
        return False


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
    torch device or its name), as ``runtime.py`` says; ValueError, one sentence, where that
    cannot be."""
    device_type = getattr(device, 'type', device)
    if runtime not in RUNTIMES:
        raise ValueError(f'no runtime {quoted(runtime)}; the runtimes are {", ".join(RUNTIMES)}')
    if runtime == 'torch':
        return runtime
    if runtime == 'auto':
        return 'onnxruntime' if device_type == 'cpu' and onnxruntime_available() else 'torch'
    if device_type != 'cpu':
        raise ValueError(f'the onnxruntime runtime runs on the CPU, not on {device_type}; '
                         'use the torch runtime there')
    if not onnxruntime_available():
        raise ValueError('the onnxruntime runtime needs the onnxruntime package '
                         '(pip install -r requirements.txt)')
    return runtime
