"""The networks of one weights directory as synthesis runs them.

Each room type's bundle is loaded on the device once, on first use, with its batch norms
folded into the convolutions (``blocks.fold_batch_norms``) and, on the CPU, its weights laid
out channels-last: oneDNN convolves images of some 40 channels so laid out faster
(docs/design/investigations.md), and images drawn that way need no copy to get there
(``image``). The four calls of a room type run in torch or, with runtime ``onnxruntime``, in
onnxruntime sessions (``runtime.OnnxCalls``); ``prepare`` readies them before any room.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import torch

from ..categories import Vocabulary
from ..errors import sentence
from ..render import FIRST_CATEGORY
from .blocks import fold_batch_norms
from .bundle import Bundle, bundle_path, load_bundle
from .runtime import OnnxCalls


class LoadedNetworks:
    """The bundles of ``weights_dir``'s room types on ``device``, run by ``runtime`` (torch or
    onnxruntime); room types are resolved in ``vocabulary``."""

    def __init__(self, weights_dir: Path, device: torch.device, runtime: str,
                 vocabulary: Vocabulary):
        self.weights_dir, self.device, self.runtime = weights_dir, device, runtime
        self.vocabulary = vocabulary
        self.channels_last = device.type == 'cpu'
        self._bundles: dict[str, Bundle] = {}
        self._calls: dict[str, dict | OnnxCalls] = {}   # what ``lockstep.ask`` gets

    def bundle(self, room_type: str) -> Bundle:
        """The networks of ``room_type``, ready for inference; ``BundleError`` names a bad
        file."""
        rt = self.vocabulary.resolve(room_type)
        if rt not in self._bundles:
            bundle = load_bundle(bundle_path(self.weights_dir, rt, self.vocabulary), self.device)
            for net in bundle.networks.values():
                fold_batch_norms(net)
                if self.channels_last:
                    net.to(memory_format=torch.channels_last)
            self._bundles[rt] = bundle
            self._calls[rt] = (OnnxCalls(bundle.networks) if self.runtime == 'onnxruntime'
                               else bundle.networks)
        return self._bundles[rt]

    def calls(self, room_type: str) -> dict | OnnxCalls:
        """The networks of ``room_type`` as synthesis calls them (``runtime``): the bundle's
        torch networks, or their ``OnnxCalls``."""
        self.bundle(room_type)
        return self._calls[self.vocabulary.resolve(room_type)]

    def prepare(self, room_type: str, fall_back: bool) -> str | None:
        """Load ``room_type``'s bundle and, in onnxruntime, have each of its calls exported,
        or read from the cache, and in a session: one pass of each on an empty image, which
        draws nothing from any seed. None when every call runs; else the sentence saying which
        call onnxruntime cannot run, and with ``fall_back`` the room type's calls are torch's
        from then on."""
        bundle = self.bundle(room_type)
        calls = self.calls(room_type)
        if not isinstance(calls, OnnxCalls):
            return None
        n = bundle.config.model.resolution
        c = FIRST_CATEGORY + len(self.vocabulary.spec(bundle.room_type).names)
        drawn = self.image(n, c, calls=calls)
        drawn[:c] = 0.0
        image = torch.from_numpy(drawn)[None]
        cats = torch.zeros(1, dtype=torch.long)
        nets = bundle.networks
        module = 'category'
        try:
            with torch.inference_mode():
                calls(module, image, torch.zeros(1, c - FIRST_CATEGORY))
                module = 'location'
                calls(module, image)
                for module in ('orientation', 'dimensions'):
                    calls(module, image, cats, torch.zeros(1, nets[module].latent))
        except Exception as e:   # whatever the exporter or onnxruntime raised
            if fall_back:
                self._calls[bundle.room_type] = nets
            return sentence(f'onnxruntime cannot run the {bundle.room_type} networks\' '
                            f'{module} call ({type(e).__name__}: {sentence(e, 160)}); runtime '
                            f'torch runs them')
        return None

    def image(self, n: int, c: int, batch: int | None = None, calls=None) -> np.ndarray:
        """An image of ``c`` channels, ``n`` x ``n`` (a batch of them), shaped channels-first
        for the renderer, laid out as the networks take it: the renderer draws the first
        ``c`` channels; for ``calls`` run by onnxruntime zero channels follow, up to the
        graphs' count (``OnnxCalls.image_channels``), so that the graphs take it as it is."""
        lead = () if batch is None else (batch,)
        if not self.channels_last:
            return np.empty(lead + (c, n, n), dtype=np.float32)
        p = calls.image_channels if isinstance(calls, OnnxCalls) else c
        image = np.empty(lead + (n, n, p), dtype=np.float32)
        image[..., c:] = 0.0
        return np.moveaxis(image, -1, -3)
