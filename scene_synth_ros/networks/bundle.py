"""The shipped weights: one file per room type, loaded without pickle.

A bundle is a plain dict saved with ``torch.save`` and read back with
``torch.load(..., weights_only=True)``: tensors (float16 to halve the size of the package;
cast back to float32 on load), strings (the configuration, metrics and model list as JSON)
and numbers. Nothing in it can execute code on load.

A bundle trained on an imported data set carries its room type's category set
(``RoomTypeSpec.to_dict``, JSON); a weights directory's bundles make the vocabulary its
networks know (``weights_vocabulary``). A bundle without one uses the paper's table.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property, lru_cache
import json
from pathlib import Path
from typing import Any

import torch
from torch import nn

from ..allowance import STRICT, Allowance
from ..categories import PAPER, RoomTypeSpec, Vocabulary
from ..errors import RoomTypeConflict, SceneSynthError
from ..files import writing_together
from ..render import num_channels
from . import NETWORKS
from .category import CategoryModel
from .config import ModelConfig, PipelineConfig
from .dimensions import DimensionsModel
from .location import LocationModel
from .orientation import OrientationModel, SnapModel

FORMAT = 1


class BundleError(SceneSynthError):
    """A weights file that is missing, unreadable or does not match the code."""


def build_networks(room_type: str, cfg: ModelConfig, seed: int | None = None,
                   vocabulary: Vocabulary = PAPER) -> dict[str, nn.Module]:
    """Freshly initialised networks of every module for ``room_type``. With ``seed``, each
    network's initial weights come from its own seed (``seed + k`` for the k-th module), so
    changing one module's architecture leaves the others' initialisation alone."""
    rt = vocabulary.resolve(room_type)
    ch, c = num_channels(rt, vocabulary), len(vocabulary.spec(rt).names)
    kinds = {'category': CategoryModel, 'location': LocationModel,
             'orientation': OrientationModel, 'snap': SnapModel,
             'dimensions': DimensionsModel}
    nets = {}
    for k, name in enumerate(NETWORKS):
        if seed is not None:
            torch.manual_seed(seed + k)
        nets[name] = kinds[name](ch, c, cfg)
    return nets


@dataclass
class Bundle:
    room_type: str
    config: PipelineConfig
    networks: dict[str, nn.Module]
    cooccurrence: torch.Tensor               # (M, M) counts over ``models``
    models: list[str]
    metrics: dict[str, Any] = field(default_factory=dict)
    spec: RoomTypeSpec | None = None         # the data set's category set; None: the paper's
    # what the data set's rooms do that the strict checks refuse (its ``dataset.yaml``'s);
    # insertion lets the rooms these networks furnish do it too
    allowance: Allowance = STRICT

    @cached_property
    def model_index(self) -> dict[str, int]:
        """The index of each of ``models`` (its row and column of ``cooccurrence``)."""
        return {m: k for k, m in enumerate(self.models)}

    @cached_property
    def model_rooms(self) -> torch.Tensor:
        """How many training rooms hold each model (the diagonal of ``cooccurrence``), at
        least 1 so that it can divide."""
        return self.cooccurrence.diagonal().clamp_min(1.0)

    @cached_property
    def vocabulary(self) -> Vocabulary:
        """What these networks know: the paper's table, with the data set's category set
        of their room type when they were trained on one."""
        return PAPER if self.spec is None else PAPER.with_specs([self.spec])


def bundle_path(weights_dir: str | Path, room_type: str,
                vocabulary: Vocabulary = PAPER) -> Path:
    return Path(weights_dir) / f'{vocabulary.resolve(room_type)}.pt'


def save_bundle(bundle: Bundle, path: str | Path) -> None:
    data: dict[str, Any] = {
        'format': FORMAT, 'room_type': bundle.room_type,
        'config': bundle.config.to_json(), 'metrics': json.dumps(bundle.metrics),
        'models': json.dumps(bundle.models),
        'cooccurrence': bundle.cooccurrence.to(torch.int32)}
    if bundle.spec is not None:
        data['room_type_spec'] = json.dumps(bundle.spec.to_dict())
    if bundle.allowance != STRICT:
        data['allowance'] = json.dumps(bundle.allowance.to_dict())
    for name in NETWORKS:
        data[name] = {k: (v.half() if v.is_floating_point() else v).contiguous()
                      for k, v in bundle.networks[name].state_dict().items()}
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with writing_together(path.parent, [path.name]) as tmp:
        torch.save(data, tmp / path.name)


def bundle_specs(weights_dir: str | Path) -> dict[str, RoomTypeSpec | None]:
    """The room types of the bundles in ``weights_dir``, each with the data set's category
    set it carries (None: the paper's), without building any network. A file that is not
    a readable bundle counts by its name, with None: loading it names what is wrong."""
    out: dict[str, RoomTypeSpec | None] = {}
    for path in sorted(Path(weights_dir).glob('*.pt')):
        try:
            st = path.stat()
            room_type, spec = _bundle_spec(str(path), st.st_mtime_ns, st.st_size)
        except (OSError, BundleError):
            room_type, spec = path.stem, None
        out[room_type] = spec
    return out


@lru_cache(maxsize=64)
def _bundle_spec(path: str, mtime: int, size: int) -> tuple[str, RoomTypeSpec | None]:
    try:
        # mmap: the tensors stay on disk, only the small entries are read
        data = torch.load(path, map_location='cpu', weights_only=True, mmap=True)
        return str(data['room_type']), _stored_spec(data)
    except Exception as e:  # any unreadable file: the caller skips it
        raise BundleError(f'{path}: {type(e).__name__}') from None


def _stored_spec(data: dict) -> RoomTypeSpec | None:
    """The data set's category set a bundle's dict carries (None: the paper's);
    ValueError when it is of another room type than the bundle."""
    if 'room_type_spec' not in data:
        return None
    spec = RoomTypeSpec.from_dict(json.loads(data['room_type_spec']))
    if spec.room_type != data['room_type']:
        raise ValueError(f'its category set is of room type {spec.room_type!r}')
    return spec


def weights_vocabulary(weights_dir: str | Path) -> Vocabulary:
    """What the networks in ``weights_dir`` know: the paper's table with the category sets
    of the data sets their bundles were trained on. Reads no network."""
    try:
        return PAPER.with_specs(s for s in bundle_specs(weights_dir).values() if s is not None)
    except RoomTypeConflict as e:
        raise BundleError(f'{weights_dir}: {e}') from None


def load_bundle(path: str | Path, device: str | torch.device = 'cpu') -> Bundle:
    """The networks of one room type, in eval mode on ``device``, with the category set
    they were trained on (``Bundle.vocabulary``). Raises ``BundleError`` naming the file and
    what is wrong with it."""
    path = Path(path)
    if not path.is_file():
        raise BundleError(f'{path}: no such weights file')
    try:
        data = torch.load(path, map_location='cpu', weights_only=True)
    except Exception as e:  # a truncated or foreign file: say so, whatever torch raised
        raise BundleError(f'{path}: not a readable weights file ({type(e).__name__}: '
                          f'{str(e).splitlines()[0] if str(e) else "no detail"})') from None
    if not isinstance(data, dict) or data.get('format') != FORMAT:
        raise BundleError(f'{path}: not a scene_synth_ros weights bundle of format {FORMAT}')
    try:
        cfg = PipelineConfig.from_dict(json.loads(data['config']))
        spec = _stored_spec(data)
        vocabulary = PAPER if spec is None else PAPER.with_specs([spec])
        rt = vocabulary.resolve(data['room_type'])
        nets = build_networks(rt, cfg.model, vocabulary=vocabulary)
        for name in NETWORKS:
            state = {k: (v.float() if v.is_floating_point() else v)
                     for k, v in data[name].items()}
            nets[name].load_state_dict(state)
            nets[name].to(device).eval()
        allowance = (Allowance.from_dict(json.loads(data['allowance']))
                     if 'allowance' in data else STRICT)
        return Bundle(rt, cfg, nets, data['cooccurrence'].float(), json.loads(data['models']),
                      json.loads(data.get('metrics', '{}')), spec, allowance)
    except (KeyError, ValueError, RuntimeError, TypeError) as e:
        raise BundleError(f'{path}: weights do not match the networks of this version '
                          f'({type(e).__name__}: {str(e).splitlines()[0]})') from None
