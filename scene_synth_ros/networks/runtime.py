"""What runs the networks' forward passes in synthesis: torch, or onnxruntime on the CPU.

Synthesis makes four network calls (``MODULE_CALLS``); ``forward`` is each call as torch
runs it, the one definition of what a call computes. On the CPU a call of one room at a
time is a batch of one through networks of 16-128 channels, which torch runs at the speed of
its per-layer overhead, not of the arithmetic. ``OnnxCalls`` exports each call once, from
``forward`` and the bundle's folded networks, to an ONNX graph and runs it in an onnxruntime
session: at a batch of one a bedroom's calls take 2.3-2.9x less time there (the location
call 1.21 against 3.32 ms), and a whole bedroom 37 % less (``docs/design/investigations.md``).

The graphs take the images as synthesis draws them on the CPU, channels-last, with zero
channels after the drawn ones up to a multiple of ``CHANNEL_BLOCK`` (``padded_channels``),
so no image is copied on the way in. Each encoder's first convolution takes the extra
channels with zero weights (``_Stem``): a 46-channel convolution is one onnxruntime runs
plainly, a 48-channel one in its blocked layout, where the stems, a third of a bedroom's
network time, took half as long or less.

The two runtimes sum in different orders, so their outputs differ in the last digits (about
1e-6 of the largest output); a draw that falls that close to a boundary can go another way,
and the room goes on differently from there. The rooms of one runtime are therefore equal
in distribution to the other's, nearly all the very same rooms (``tests/test_runtime.py``
checks both), and the same seed gives the same room in either.

onnxruntime's lead is overhead saved, so it shrinks as the batch grows, and beyond
``ONNX_MAX_BATCH`` examples a call is run by torch (``docs/design/investigations.md``, on
this CPU: onnxruntime 1.07-1.16x ahead at 24; at 32 the location call 0.71x, from 48 every
call but the category call behind). So batches of rooms in lockstep (8 by default,
``batch``) run onnxruntime too.

``config.resolve_runtime`` chooses: ``auto`` is onnxruntime on the CPU where it is installed
(it is in ``requirements.txt``), torch elsewhere (CUDA, or no onnxruntime).

Exporting the four calls of a room type takes about 0.7 s, more than five rooms; a process
that furnishes one room (``scene-synth generate``) would pay it every time. So each graph
is kept on disk (``graph_cache_dir``), named by a hash of all that made it: the networks'
weights, the code of this package's networks, torch's version and the inputs' shapes.
Another process, or the same weights again, reads it back in milliseconds. The cache is
only ever a saving: a file that cannot be written, read or run is exported again.
"""
from __future__ import annotations

from contextlib import suppress
import copy
from functools import lru_cache
import hashlib
import io
import os
from pathlib import Path
import warnings

import numpy as np
import torch
from torch import nn

from .. import __version__
from ..files import write_atomic
from .blocks import ResNetEncoder

# The network calls of synthesis: what each takes and gives, batch first.
#   category     (image, counts)    -> (logits,)            next category or STOP
#   location     (image,)           -> (logits, offsets)    offsets None without them
#   orientation  (crops, cats, z)   -> (outputs, snap logits)
#   dimensions   (crops, cats, z)   -> (log footprints,)
MODULE_CALLS = ('category', 'location', 'orientation', 'dimensions')


# The largest batch of a call that onnxruntime runs; larger ones go to torch (see above).
ONNX_MAX_BATCH = 24

# Images reach the graphs with their channels padded with zeros to a multiple of this:
# onnxruntime runs a convolution over a multiple of 16 channels in its blocked layout,
# and the encoders' stems, over 46 channels, were a third of a bedroom's network time.
CHANNEL_BLOCK = 16

# The networks each call runs: their weights name its graph in the cache.
CALL_NETWORKS = {'category': ('category',), 'location': ('location',),
                 'orientation': ('orientation', 'snap'), 'dimensions': ('dimensions',)}

# The environment variable naming the directory of exported graphs; ``off`` keeps none.
CACHE_ENV = 'SCENE_SYNTH_ROS_CACHE'
# The most graphs kept there: four calls of four room types, four times over (about 200 MB).
CACHE_GRAPHS = 64


def graph_cache_dir() -> Path | None:
    """Where exported graphs are kept: ``$SCENE_SYNTH_ROS_CACHE``, else
    ``$XDG_CACHE_HOME/scene_synth_ros/onnx``, else ``~/.cache/scene_synth_ros/onnx``;
    None when ``$SCENE_SYNTH_ROS_CACHE`` is ``off`` (or the home directory is unknown)."""
    chosen = os.environ.get(CACHE_ENV, '').strip()
    if chosen.lower() == 'off':
        return None
    if chosen:
        return Path(chosen).expanduser()
    base = os.environ.get('XDG_CACHE_HOME', '').strip()
    try:
        root = Path(base) if base else Path.home() / '.cache'
    except RuntimeError:         # no home directory to be found
        return None
    return root / 'scene_synth_ros' / 'onnx'


@lru_cache(maxsize=1)
def _networks_code_hash() -> str:
    """A hash of this package's version and network code (the directory of this module,
    sources or, where an install kept only those, compiled files): a graph exported by
    other code is not this code's graph, whatever the weights."""
    h = hashlib.sha256(__version__.encode() + b'\0')
    here = Path(__file__).resolve().parent
    for path in sorted(here.glob('*.py')) or sorted(here.glob('*.pyc')):
        h.update(path.name.encode() + b'\0' + path.read_bytes() + b'\0')
    return h.hexdigest()


def graph_key(networks: dict, module: str, args: tuple[torch.Tensor, ...]) -> str:
    """The name of ``module``'s exported graph for these networks and inputs: a hash of the
    weights of the networks it runs, the network code, torch's version and each input's
    dtype and shape past the batch."""
    h = hashlib.sha256()
    for part in (_networks_code_hash(), torch.__version__, module,
                 repr([(str(a.dtype), tuple(a.shape[1:])) for a in args])):
        h.update(part.encode() + b'\0')
    for name in CALL_NETWORKS[module]:
        net = networks[name]
        h.update(repr(net).encode())
        for key, value in net.state_dict().items():
            value = value.detach().cpu().contiguous()
            h.update(f'{key} {value.dtype} {tuple(value.shape)}'.encode())
            h.update(value.view(-1).view(torch.uint8).numpy().tobytes())
    return h.hexdigest()[:32]


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


class OnnxCalls:
    """A bundle's network calls run by onnxruntime: each exported from ``forward`` on its
    first call, for a batch of any size, and run in a session of as many threads as torch
    has then (one in a batch worker); a batch larger than ``ONNX_MAX_BATCH`` says is run by
    torch. Called like ``forward`` with the networks bound: ``calls(module, *args)``;
    answers are torch tensors on the CPU."""

    def __init__(self, networks: dict, cache_dir: Path | None | str = 'default'):
        self.networks = networks
        # where graphs are kept (``graph_cache_dir``); None keeps none
        self.cache_dir = graph_cache_dir() if cache_dir == 'default' else cache_dir
        self._sessions: dict[tuple, tuple] = {}   # by call and image size
        self.loaded: list[str] = []     # the calls whose graphs came from the cache
        # the channels of the images the networks take, and of those the graphs take
        self.channels = _image_channels(networks)
        self.image_channels = padded_channels(self.channels)

    @property
    def exported(self) -> tuple[str, ...]:
        """The calls exported so far (those onnxruntime has run)."""
        return tuple(sorted({module for module, _ in self._sessions}))

    def __call__(self, module: str, *args: torch.Tensor) -> tuple[torch.Tensor | None, ...]:
        if module not in MODULE_CALLS:
            raise ValueError(f'no network call {module!r}; the calls are '
                             f'{", ".join(MODULE_CALLS)}')
        if args[0].shape[0] > ONNX_MAX_BATCH:
            return forward(self.networks, module, *(self._drawn(a) if a.dim() == 4 else a
                                                    for a in args))
        feed = [self._image(a) if a.dim() == 4 else a.detach().cpu().numpy() for a in args]
        # A graph per image size: a room larger than its type's square is seen larger, and
        # graphs of fixed sizes keep the rooms of the paper's sizes on their fastest path.
        key = (module, tuple(args[0].shape[2:]))
        if key not in self._sessions:
            self._sessions[key] = self._export(module, feed)
        session, names, offsets = self._sessions[key]
        outs = tuple(torch.from_numpy(o) for o in
                     session.run(None, dict(zip(names, feed, strict=True))))
        if module == 'location' and not offsets:
            return outs + (None,)
        return outs

    def _drawn(self, image: torch.Tensor) -> torch.Tensor:
        """``image`` without the zero channels, for torch: laid out channels-last again, so
        that its convolutions take their fast path (a channel slice is laid out neither
        way)."""
        if image.shape[1] == self.channels:
            return image
        return image[:, :self.channels].contiguous(memory_format=torch.channels_last)

    def _image(self, image: torch.Tensor) -> np.ndarray:
        """``image`` (N, C, H, W) as the graphs take it: channels-last, with
        ``image_channels``; one drawn so (``padded_channels``) is not copied."""
        pixels = image.detach().cpu().permute(0, 2, 3, 1).numpy()
        if pixels.shape[-1] == self.image_channels:
            return np.ascontiguousarray(pixels)
        if pixels.shape[-1] != self.channels:
            raise ValueError(f'an image of {pixels.shape[-1]} channels for networks that '
                             f'take {self.channels}')
        out = np.zeros(pixels.shape[:-1] + (self.image_channels,), dtype=np.float32)
        out[..., :self.channels] = pixels
        return out

    def _export(self, module: str, feed: list[np.ndarray]) -> tuple:
        args = tuple(torch.from_numpy(a) for a in feed)
        names = [f'input{k}' for k in range(len(args))]
        offsets = module == 'location' and self.networks['location'].offset is not None
        path = None
        if self.cache_dir is not None:
            key = graph_key(self.networks, module, args)
            path = Path(self.cache_dir) / f'{module}-{key}.onnx'
            try:
                session = _session(path.read_bytes(), module)
            except Exception:   # not there, unreadable or not a graph: export it again
                pass
            else:
                self.loaded.append(module)
                with suppress(OSError):   # used: the last to be pruned (``_keep``)
                    path.touch()
                return session, names, offsets
        graph = self._graph(module, args, names)
        session = _session(graph, module)
        if path is not None:
            _keep(path, graph)
        return session, names, offsets

    def _graph(self, module: str, args: tuple[torch.Tensor, ...], names: list[str]) -> bytes:
        """``module``'s call exported to an ONNX graph, for a batch of any size, taking its
        images channels-last with ``image_channels``."""
        networks = _graph_networks(self.networks, module, self.image_channels)
        call = _Call(networks, module).eval()
        graph = io.BytesIO()
        # The TorchScript-based exporter: torch (pinned) still has it, and it exports a call
        # in about 0.1 s, where the torch.export-based one takes 4 s and another package.
        # Synthesis calls inside inference mode, whose tensors a trace cannot record.
        with warnings.catch_warnings(), torch.inference_mode(False), torch.no_grad():
            warnings.simplefilter('ignore')
            example = tuple(a.clone() for a in args)
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


def padded_channels(channels: int) -> int:
    """The channels of the images that the graphs take: ``channels`` rounded up to a whole
    number of ``CHANNEL_BLOCK``, the extra ones zero."""
    return -(-channels // CHANNEL_BLOCK) * CHANNEL_BLOCK


def _image_channels(networks: dict) -> int:
    """The channels of the images the networks take: their encoders' stems'."""
    found = {m.stem[0].in_channels for net in networks.values() for m in net.modules()
             if isinstance(m, ResNetEncoder)}
    if len(found) != 1:
        raise ValueError(f'networks whose encoders take images of {len(found)} different '
                         'channel counts')
    return found.pop()


def _graph_networks(networks: dict, module: str, channels: int) -> dict:
    """Copies of the networks ``module`` runs whose encoders take their images as the
    graphs do: channels-last, with ``channels`` channels (``_Stem``)."""
    out = {}
    for name in CALL_NETWORKS[module]:
        net = copy.deepcopy(networks[name])
        for m in net.modules():
            if isinstance(m, ResNetEncoder):
                m.stem[0] = _Stem(m.stem[0], channels)
        out[name] = net
    return out


def _session(graph: bytes, module: str):
    """An onnxruntime session running ``graph``, ``module``'s call, with as many threads as
    torch has."""
    import onnxruntime  # optional: the torch runtime runs without it
    options = onnxruntime.SessionOptions()
    options.intra_op_num_threads = torch.get_num_threads()
    options.inter_op_num_threads = 1
    options.execution_mode = onnxruntime.ExecutionMode.ORT_SEQUENTIAL
    options.log_severity_level = 4          # none: a damaged cached graph is exported again
    # No arena: it kept the largest batch's buffers, 50 MB more a lockstep worker. No
    # spinning: threads that spin between passes starve the process beside them (two
    # threads and one busy core took a bedroom from 0.12 to 0.35 s).
    options.enable_cpu_mem_arena = False
    options.add_session_config_entry('session.intra_op.allow_spinning', '0')
    # Where several networks see one image, common subexpression elimination would merge
    # their stems' turns again (``_turn_per_stem``); elsewhere onnxruntime's default stays.
    disabled = ['CommonSubexpressionElimination'] if len(CALL_NETWORKS[module]) > 1 else []
    return onnxruntime.InferenceSession(graph, options, providers=['CPUExecutionProvider'],
                                        disabled_optimizers=disabled)


def _keep(path: Path, graph: bytes) -> None:
    """Write ``graph`` to the cache whole or not at all; a cache that cannot be written
    (read-only, full) only costs the next process an export."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(path, graph)     # processes writing the same graph: the last one stays
        # The least recently used graphs beyond CACHE_GRAPHS go (those of weights or code
        # replaced since): reading a graph back marks it used.
        kept = sorted(path.parent.glob('*.onnx'), key=lambda p: p.stat().st_mtime,
                      reverse=True)
        for old in kept[CACHE_GRAPHS:]:
            old.unlink(missing_ok=True)
    except OSError:
        pass
