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
from functools import cached_property
import json
from pathlib import Path
from typing import Any

import torch
from torch import nn

from ..allowance import STRICT, Allowance
from ..categories import PAPER, RoomTypeSpec, Vocabulary
from ..files import writing_together
from ..render import num_channels
from . import NETWORKS
from .category import CategoryModel
from .config import ModelConfig, PipelineConfig
from .dimensions import DimensionsModel
from .graphs import image_channels
from .location import LocationModel
from .orientation import OrientationModel, SnapModel
from .served import (  # noqa: F401  (where they were defined once: imported from here)
    BundleError,
    Served,
    bundle_path,
    bundle_specs,
    spec_in_bundle,
    weights_vocabulary,
)

FORMAT = 1


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
    def vocabulary(self) -> Vocabulary:
        """What these networks know: the paper's table, with the data set's category set
        of their room type when they were trained on one."""
        return PAPER if self.spec is None else PAPER.with_specs([self.spec])


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
        spec = spec_in_bundle(data)
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


def served_record(bundle: Bundle, weights: str) -> Served:
    """What synthesis reads of ``bundle`` besides its calls (``served.Served``); ``weights``
    names the file it came from (``served.file_hash``)."""
    dims = bundle.networks['dimensions']
    return Served(
        room_type=bundle.room_type, config=bundle.config, models=list(bundle.models),
        cooccurrence=bundle.cooccurrence.double().cpu().numpy(), spec=bundle.spec,
        allowance=bundle.allowance,
        latents={name: int(bundle.networks[name].latent)
                 for name in ('orientation', 'dimensions')},
        log_sigma=(None if dims.log_sigma is None
                   else dims.log_sigma.detach().float().cpu().numpy()),
        location_multiple=int(bundle.networks['location'].multiple),
        channels=image_channels(bundle.networks), weights=weights, metrics=bundle.metrics)
