"""The shipped weights: one file per room type, loaded without pickle.

A bundle is a plain dict saved with ``torch.save`` and read back with
``torch.load(..., weights_only=True)``: tensors (float16 to halve the size of the package;
cast back to float32 on load), strings (the configuration, metrics and model list as JSON)
and numbers. Nothing in it can execute code on load.
"""
from __future__ import annotations

from dataclasses import dataclass, field
import json
from pathlib import Path
from typing import Any

import torch
from torch import nn

from ..categories import resolve_room_type, room_spec
from ..errors import SceneSynthError
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


def build_networks(room_type: str, cfg: ModelConfig, seed: int | None = None
                   ) -> dict[str, nn.Module]:
    """Freshly initialised networks of every module for ``room_type``. With ``seed``, each
    network's initial weights come from its own seed (``seed + k`` for the k-th module), so
    changing one module's architecture leaves the others' initialisation alone."""
    rt = resolve_room_type(room_type)
    ch, c = num_channels(rt), len(room_spec(rt).names)
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


def bundle_path(weights_dir: str | Path, room_type: str) -> Path:
    return Path(weights_dir) / f'{resolve_room_type(room_type)}.pt'


def save_bundle(bundle: Bundle, path: str | Path) -> None:
    data: dict[str, Any] = {
        'format': FORMAT, 'room_type': bundle.room_type,
        'config': bundle.config.to_json(), 'metrics': json.dumps(bundle.metrics),
        'models': json.dumps(bundle.models),
        'cooccurrence': bundle.cooccurrence.to(torch.int32)}
    for name in NETWORKS:
        data[name] = {k: (v.half() if v.is_floating_point() else v).contiguous()
                      for k, v in bundle.networks[name].state_dict().items()}
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with writing_together(path.parent, [path.name]) as tmp:
        torch.save(data, tmp / path.name)


def load_bundle(path: str | Path, device: str | torch.device = 'cpu') -> Bundle:
    """The networks of one room type, in eval mode on ``device``. Raises ``BundleError``
    naming the file and what is wrong with it."""
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
        rt = resolve_room_type(data['room_type'])
        nets = build_networks(rt, cfg.model)
        for name in NETWORKS:
            state = {k: (v.float() if v.is_floating_point() else v)
                     for k, v in data[name].items()}
            nets[name].load_state_dict(state)
            nets[name].to(device).eval()
        return Bundle(rt, cfg, nets, data['cooccurrence'].float(), json.loads(data['models']),
                      json.loads(data.get('metrics', '{}')))
    except (KeyError, ValueError, RuntimeError, TypeError) as e:
        raise BundleError(f'{path}: weights do not match the networks of this version '
                          f'({type(e).__name__}: {str(e).splitlines()[0]})') from None
