"""The torch side of the network calls (``runtime.MODULE_CALLS``): ``forward``, the one
definition of what each call computes; ``TorchCalls``, the calls run by torch; and the
export of a call to the ONNX graph that ``runtime.OnnxCalls`` runs."""
from __future__ import annotations

import copy
import hashlib
import io
import warnings

import numpy as np
import torch
from torch import nn

from .blocks import ResNetEncoder
from .calls import CALL_NETWORKS, MODULE_CALLS


def forward(networks: dict, module: str, *args: torch.Tensor
            ) -> tuple[torch.Tensor | None, ...]:
    """``module``'s forward pass over a batch (see ``MODULE_CALLS``), in torch."""
    if module == 'category':
        return (networks['category'](*args),)
    if module == 'location':
        return networks['location'].predict(*args)
    if module in ('orientation', 'dimensions'):
        crops, cats, z = args
        net = networks[module]
        out = net.decode(net.condition(crops, cats), cats, z)
        if module == 'dimensions':
            return (out,)
        return out, networks['snap'](crops, cats)
    raise ValueError(f'no network call {module!r}; the calls are {", ".join(MODULE_CALLS)}')


class TorchCalls:
    """A bundle's network calls run by torch on ``device``, called as ``OnnxCalls`` is: numpy
    arrays in, numpy arrays out (on the CPU the arrays are shared with torch, not copied).
    Images of more channels than the networks' ``channels`` (drawn for onnxruntime) are
    taken without the extra ones."""

    def __init__(self, networks: dict, device: str | torch.device = 'cpu',
                 channels: int | None = None):
        self.networks = networks
        self.device = torch.device(device)
        self.channels = channels
        # On the CPU the networks are laid out channels-last (``LoadedNetworks``), and so
        # are the images they are fed, for oneDNN's fast path.
        self.channels_last = self.device.type == 'cpu'

    def _tensor(self, a: np.ndarray) -> torch.Tensor:
        t = torch.from_numpy(np.asarray(a))
        if t.dim() == 4:
            if self.channels is not None and t.shape[1] != self.channels:
                t = t[:, :self.channels]
            if self.channels_last and not t.is_contiguous(memory_format=torch.channels_last):
                t = t.contiguous(memory_format=torch.channels_last)
        return t.to(self.device)

    def __call__(self, module: str, *args: np.ndarray) -> tuple[np.ndarray | None, ...]:
        with torch.inference_mode():
            outs = forward(self.networks, module, *(self._tensor(a) for a in args))
            return tuple(None if o is None else o.float().cpu().numpy() for o in outs)


def image_channels(networks: dict) -> int:
    """The channels of the images the networks take: their encoders' stems'."""
    found = {m.stem[0].in_channels for net in networks.values() for m in net.modules()
             if isinstance(m, ResNetEncoder)}
    if len(found) != 1:
        raise ValueError(f'networks whose encoders take images of {len(found)} different '
                         'channel counts')
    return found.pop()


def weights_hash(networks: dict, module: str) -> str:
    """A name for the weights of the networks ``module``'s call runs (``CALL_NETWORKS``),
    for networks that come from no bundle file: a hash of their structure and weights."""
    h = hashlib.sha256()
    for name in CALL_NETWORKS[module]:
        net = networks[name]
        h.update(repr(net).encode())
        for key, value in net.state_dict().items():
            value = value.detach().cpu().contiguous()
            h.update(f'{key} {value.dtype} {tuple(value.shape)}'.encode())
            h.update(value.view(-1).view(torch.uint8).numpy().tobytes())
    return h.hexdigest()


class _Call(nn.Module):
    """One call of ``forward`` giving only the outputs that exist (an ONNX graph has no
    None)."""

    def __init__(self, networks: dict, module: str):
        super().__init__()
        self.networks = nn.ModuleDict(networks)
        self.module = module

    def forward(self, *args: torch.Tensor) -> tuple[torch.Tensor, ...]:
        return tuple(o for o in forward(self.networks, self.module, *args) if o is not None)


class _Stem(nn.Module):
    """An encoder's first convolution taking its image channels-last (N, H, W, C), with
    ``channels`` channels, the weights of those it did not take zero: the same function of
    the image, zero channels appended.

    The turn to channels-first is each stem's own, so that in a graph where two encoders
    see one image (orientation and snap) each turn is fused into the reordering that
    onnxruntime's blocked convolutions start with; one turn shared by both took longer than
    the two convolutions."""

    def __init__(self, conv: nn.Conv2d, channels: int):
        super().__init__()
        self.conv = nn.Conv2d(channels, conv.out_channels, conv.kernel_size, conv.stride,
                              conv.padding, bias=conv.bias is not None)
        with torch.no_grad():
            self.conv.weight.zero_()
            self.conv.weight[:, :conv.in_channels] = conv.weight
            if conv.bias is not None:
                self.conv.bias.copy_(conv.bias)
        self.conv.to(conv.weight.device)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.conv(x.permute(0, 3, 1, 2))


def export_graph(networks: dict, module: str, feed: list[np.ndarray], names: list[str],
                 channels: int) -> bytes:
    """``module``'s call exported to an ONNX graph, for a batch of any size, taking its
    images channels-last (as ``feed`` holds them) with ``channels`` channels."""
    graph_nets = {}
    for name in CALL_NETWORKS[module]:
        net = copy.deepcopy(networks[name])
        for m in net.modules():
            if isinstance(m, ResNetEncoder):
                m.stem[0] = _Stem(m.stem[0], channels)
        graph_nets[name] = net
    call = _Call(graph_nets, module).eval()
    graph = io.BytesIO()
    # The TorchScript-based exporter: torch (pinned) still has it, and it exports a call
    # in about 0.1 s, where the torch.export-based one takes 4 s and another package.
    with warnings.catch_warnings(), torch.inference_mode(False), torch.no_grad():
        warnings.simplefilter('ignore')
        example = tuple(torch.from_numpy(np.array(a)) for a in feed)
        torch.onnx.export(call, example, graph, dynamo=False, input_names=names,
                          dynamic_axes={name: {0: 'batch'} for name in names})
    return _turn_per_stem(graph.getvalue())


def _turn_per_stem(graph: bytes) -> bytes:
    """``graph`` with a Transpose read by several nodes repeated for each of them: the
    exporter merges the stems' identical turns of one image (``_Stem``) into one, which
    onnxruntime can then fuse into none of the stems' reorderings."""
    import onnx  # optional: only exporting a graph for onnxruntime needs it
    model = onnx.load_from_string(graph)
    readers: dict[str, list] = {}
    for node in model.graph.node:
        for k, name in enumerate(node.input):
            readers.setdefault(name, []).append((node, k))
    nodes = []
    for node in model.graph.node:
        nodes.append(node)
        if node.op_type != 'Transpose':
            continue
        for j, (reader, k) in enumerate(readers.get(node.output[0], [])[1:], 1):
            turn = copy.deepcopy(node)
            turn.name, turn.output[0] = f'{node.name}_{j}', f'{node.output[0]}_{j}'
            reader.input[k] = turn.output[0]
            nodes.append(turn)
    del model.graph.node[:]
    model.graph.node.extend(nodes)
    return model.SerializeToString()
