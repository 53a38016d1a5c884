"""The networks of one weights directory as synthesis runs them.

Each room type is made ready once, on first use: what synthesis reads of its bundle
(``served.Served``) and its four calls (``runtime.MODULE_CALLS``), run by onnxruntime
(``runtime.OnnxCalls``) or torch (``graphs.TorchCalls``). Under onnxruntime, a bundle whose
record and graphs are in the cache is served from there, and torch is not imported; else the
bundle is loaded with torch, on ``device``, with its batch norms folded into the
convolutions (``blocks.fold_batch_norms``) and, on the CPU, its weights laid out
channels-last: oneDNN convolves images of some 40 channels so laid out faster
(docs/design/investigations.md), and images drawn that way need no copy to get there
(``image``). ``prepare`` readies a room type's calls before any room.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..categories import Vocabulary
from ..errors import sentence
from ..render import FIRST_CATEGORY, num_channels
from . import runtime
from .runtime import OnnxCalls
from .served import BundleError, Served, bundle_path, file_hash, keep_record, read_record


class LoadedNetworks:
    """The bundles of ``weights_dir``'s room types on ``device`` (``cpu`` or ``cuda``), run by
    ``runtime`` (torch or onnxruntime); room types are resolved in ``vocabulary``."""

    def __init__(self, weights_dir: Path, device: str, runtime: str, vocabulary: Vocabulary):
        self.weights_dir, self.device, self.runtime = weights_dir, device, runtime
        self.vocabulary = vocabulary
        self.channels_last = device == 'cpu'
        self._bundles: dict = {}                    # torch ``Bundle``s, by room type
        self._served: dict[str, Served] = {}
        self._calls: dict = {}                      # what ``lockstep.ask`` gets

    def bundle(self, room_type: str):
        """The torch networks of ``room_type`` (a ``bundle.Bundle``), ready for inference;
        ``BundleError`` names a bad file."""
        rt = self.vocabulary.resolve(room_type)
        if rt not in self._bundles:
            import torch  # a bundle read with torch: the cache misses it, or runtime torch

            from .blocks import fold_batch_norms  # torch, as above
            from .bundle import load_bundle  # torch, as above
            runtime.torch_loaded()      # the threads asked for before torch was loaded
            bundle = load_bundle(self._path(rt), self.device)
            for net in bundle.networks.values():
                fold_batch_norms(net)
                if self.channels_last:
                    net.to(memory_format=torch.channels_last)
            self._bundles[rt] = bundle
        return self._bundles[rt]

    def _path(self, rt: str) -> Path:
        path = bundle_path(self.weights_dir, rt, self.vocabulary)
        if not path.is_file():
            raise BundleError(f'{path}: no such weights file')
        return path

    def served(self, room_type: str) -> Served:
        """What synthesis reads of ``room_type``'s bundle, from the cache where it can be
        (onnxruntime), else from the bundle (kept in the cache for the next process)."""
        rt = self.vocabulary.resolve(room_type)
        if rt in self._served:
            return self._served[rt]
        path = self._path(rt)
        record = read_record(path) if self.runtime == 'onnxruntime' else None
        if record is None:
            from .bundle import served_record  # torch: the record is made from the bundle
            weights = self._hash(path)
            bundle = self.bundle(rt)
            self._unchanged(path, weights)      # what was loaded is what was hashed
            record = served_record(bundle, weights)
            if self.runtime == 'onnxruntime':
                keep_record(record)
        want = num_channels(rt, self.vocabulary)
        if record.channels != want:
            raise BundleError(f'{path}: weights do not match the networks of this version (they '
                              f'take images of {record.channels} channels, this code draws '
                              f'{want})')
        if self.runtime == 'onnxruntime':
            calls = OnnxCalls(lambda: self._networks_of(rt, path, record.weights),
                              record.weights, record.channels)
        else:
            from .graphs import TorchCalls  # torch: runtime torch
            calls = TorchCalls(self.bundle(rt).networks, self.device, record.channels)
        self._served[rt], self._calls[rt] = record, calls
        return record

    def _networks_of(self, rt: str, path: Path, weights: str) -> dict:
        """The torch networks of ``rt`` for its calls, whose graphs and record name the file's
        ``weights``: a file replaced since is refused, not exported under the old name."""
        networks = self.bundle(rt).networks
        self._unchanged(path, weights)
        return networks

    @staticmethod
    def _hash(path: Path) -> str:
        try:
            return file_hash(path)
        except OSError as e:
            raise BundleError(f'{path}: cannot be read ({e.strerror})') from None

    def _unchanged(self, path: Path, weights: str) -> None:
        if self._hash(path) != weights:
            raise BundleError(f'{path}: the file changed while it was in use; start again to '
                              f'use the new weights')

    def calls(self, room_type: str):
        """The networks of ``room_type`` as synthesis calls them (``runtime``): an
        ``OnnxCalls`` or a ``graphs.TorchCalls``."""
        self.served(room_type)
        return self._calls[self.vocabulary.resolve(room_type)]

    def prepare(self, room_type: str, fall_back: bool) -> str | None:
        """Ready ``room_type``'s record and calls and, in onnxruntime, have each call's graph
        read from the cache, or exported, and in a session: one pass of each on an empty
        image, which draws nothing from any seed. None when every call runs; else the
        sentence saying which call onnxruntime cannot run, and with ``fall_back`` the room
        type's calls are torch's from then on."""
        record = self.served(room_type)
        calls = self.calls(room_type)
        if not isinstance(calls, OnnxCalls):
            return None
        n = record.config.model.resolution
        c = FIRST_CATEGORY + len(self.vocabulary.spec(record.room_type).names)
        drawn = self.image(n, c, calls=calls)
        drawn[:c] = 0.0
        image = drawn[None]
        cats = np.zeros(1, dtype=np.int64)
        module = 'category'
        try:
            calls(module, image, np.zeros((1, c - FIRST_CATEGORY), dtype=np.float32))
            module = 'location'
            calls(module, image)
            for module in ('orientation', 'dimensions'):
                calls(module, image, cats,
                      np.zeros((1, record.latents[module]), dtype=np.float32))
        except BundleError:
            raise                # the weights, not onnxruntime: no runtime can run them
        except Exception as e:   # whatever the exporter or onnxruntime raised
            if fall_back:
                from .graphs import TorchCalls  # torch: onnxruntime cannot run them
                self._calls[record.room_type] = TorchCalls(
                    self.bundle(record.room_type).networks, self.device, record.channels)
            return sentence(f'onnxruntime cannot run the {record.room_type} networks\' '
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
