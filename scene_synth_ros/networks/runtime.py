"""What runs the networks' forward passes in synthesis: torch, or onnxruntime on the CPU.

Synthesis makes four network calls (``calls.MODULE_CALLS``); ``graphs.forward`` is each call
as torch runs it, the one definition of what a call computes. On the CPU a call of one room at a
time is a batch of one through networks of 16-128 channels, which torch runs at the speed of
its per-layer overhead, not of the arithmetic. ``OnnxCalls`` exports each call once, from
``forward`` and the bundle's folded networks, to an ONNX graph and runs it in an onnxruntime
session: at a batch of one a bedroom's calls take 2.3-2.9x less time there (the location
call 1.21 against 3.32 ms), and a whole bedroom 37 % less (``docs/design/investigations.md``).

Synthesis hands every call numpy arrays and gets numpy arrays back, whichever runtime
answers (``TorchCalls`` in ``graphs.py`` converts at its edge). Nothing here imports torch: a
process whose graphs and bundle records (``served.py``) are in the cache (below) furnishes
rooms without it (``docs/design/speed.md``).

The graphs take the images as synthesis draws them on the CPU, channels-last, with zero
channels after the drawn ones up to a multiple of ``CHANNEL_BLOCK`` (``padded_channels``),
so no image is copied on the way in. Each encoder's first convolution takes the extra
channels with zero weights (``graphs._Stem``): a 46-channel convolution is one onnxruntime runs
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
weights (a bundle file's hash, or the weights themselves), the code of this package's
networks, torch's version and the inputs' shapes.
Another process, or the same weights again, reads it back in milliseconds. The cache is
only ever a saving: a file that cannot be written, read or run is exported again.
"""
from __future__ import annotations

from contextlib import suppress
from functools import lru_cache
import hashlib
from importlib import metadata
import os
from pathlib import Path
import sys
from typing import Callable, Sequence

import numpy as np

from .. import __version__
from ..files import write_atomic
from .calls import CALL_NETWORKS, MODULE_CALLS  # noqa: F401  (the calls' API here too)

# The largest batch of a call that onnxruntime runs; larger ones go to torch (see above).
ONNX_MAX_BATCH = 24

# Images reach the graphs with their channels padded with zeros to a multiple of this:
# onnxruntime runs a convolution over a multiple of 16 channels in its blocked layout,
# and the encoders' stems, over 46 channels, were a third of a bedroom's network time.
CHANNEL_BLOCK = 16

# The environment variable naming the directory of exported graphs; ``off`` keeps none.
CACHE_ENV = 'SCENE_SYNTH_ROS_CACHE'
# The most graphs kept there: four calls of seven room types, and the category and location
# calls at four larger sizes of room each, twice over (about 400 MB).
CACHE_GRAPHS = 128

# The CPU threads the networks may use (``set_threads``); None: as ``threads`` says.
_threads: int | None = None


def set_threads(n: int | None) -> None:
    """Let the networks use ``n`` CPU threads: onnxruntime sessions made from now on, and
    torch, now if it is loaded, else when ``LoadedNetworks`` loads it (``torch_loaded``).
    None: as ``threads`` says when nothing was set."""
    global _threads
    _threads = None if n is None else int(n)
    torch_loaded()


def torch_loaded() -> None:
    """Give torch, if it is loaded, the threads ``set_threads`` asked for (if it did)."""
    torch = sys.modules.get('torch')
    if torch is not None and _threads is not None:
        torch.set_num_threads(_threads)


def threads() -> int:
    """The CPU threads the networks may use: those ``set_threads`` asked for; else torch's
    count where torch is loaded; else ``OMP_NUM_THREADS`` where it is set, else the CPUs
    this process may run on (as torch would have counted them)."""
    if _threads is not None:
        return _threads
    torch = sys.modules.get('torch')
    if torch is not None:
        return torch.get_num_threads()
    with suppress(ValueError):
        if int(os.environ.get('OMP_NUM_THREADS', '')) > 0:
            return int(os.environ['OMP_NUM_THREADS'])
    try:
        return len(os.sched_getaffinity(0)) or 1
    except AttributeError:          # not on Linux
        return os.cpu_count() or 1


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
def code_hash() -> str:
    """A hash of this package's version, its network code (the directory of this module,
    sources or, where an install kept only those, compiled files) and torch's version: a
    graph exported by other code is not this code's graph, whatever the weights."""
    h = hashlib.sha256(__version__.encode() + b'\0' + _torch_version().encode() + b'\0')
    here = Path(__file__).resolve().parent
    for path in sorted(here.glob('*.py')) or sorted(here.glob('*.pyc')):
        h.update(path.name.encode() + b'\0' + path.read_bytes() + b'\0')
    return h.hexdigest()


def _torch_version() -> str:
    """torch's version as installed, read without importing it (a second)."""
    try:
        return metadata.version('torch')
    except metadata.PackageNotFoundError:   # no graph can be exported then
        return 'none'


def graph_key(weights: str, module: str, feed: Sequence[np.ndarray]) -> str:
    """The name of ``module``'s exported graph for the weights named ``weights`` (a bundle
    file's hash, or ``graphs.weights_hash``) and these inputs: a hash of that, the code
    (``code_hash``) and each input's dtype and shape past the batch."""
    h = hashlib.sha256()
    for part in (code_hash(), module, weights,
                 repr([(str(a.dtype), tuple(a.shape[1:])) for a in feed])):
        h.update(part.encode() + b'\0')
    return h.hexdigest()[:32]


class OnnxCalls:
    """A bundle's network calls run by onnxruntime: each call's graph read from the cache or
    exported from torch on its first call, for a batch of any size, and run in a session of
    ``threads()`` threads; a batch larger than ``ONNX_MAX_BATCH`` is run by torch. Called
    with numpy arrays: ``calls(module, *args)`` gives numpy arrays (None for location
    offsets the networks do not make).

    ``networks``: the bundle's torch networks, or a function that loads them, called only
    when a graph must be exported or torch must run a call: with every graph in the cache,
    torch is never imported. ``weights`` names them in the graph keys (a bundle file's
    hash); None: a hash of the networks' weights. ``channels``: the channels of the images
    the networks take (None: read from the networks)."""

    def __init__(self, networks: dict | Callable[[], dict], weights: str | None = None,
                 channels: int | None = None, cache_dir: Path | None | str = 'default'):
        self._networks = networks if isinstance(networks, dict) else None
        self._load = None if isinstance(networks, dict) else networks
        self.weights = weights
        # where graphs are kept (``graph_cache_dir``); None keeps none
        self.cache_dir = graph_cache_dir() if cache_dir == 'default' else cache_dir
        self._sessions: dict[tuple, tuple] = {}   # by call and image size
        self._torch = None                          # ``TorchCalls`` for large batches
        self.loaded: list[str] = []     # the calls whose graphs came from the cache
        if channels is None:
            from .graphs import image_channels  # torch: read from the networks
            channels = image_channels(self.networks)
        # the channels of the images the networks take, and of those the graphs take
        self.channels = channels
        self.image_channels = padded_channels(self.channels)

    @property
    def networks(self) -> dict:
        """The torch networks (loaded now if they were not)."""
        if self._networks is None:
            self._networks = self._load()
        return self._networks

    @property
    def exported(self) -> tuple[str, ...]:
        """The calls exported so far (those onnxruntime has run)."""
        return tuple(sorted({module for module, _ in self._sessions}))

    def __call__(self, module: str, *args: np.ndarray) -> tuple[np.ndarray | None, ...]:
        if module not in MODULE_CALLS:
            raise ValueError(f'no network call {module!r}; the calls are '
                             f'{", ".join(MODULE_CALLS)}')
        if args[0].shape[0] > ONNX_MAX_BATCH:
            if self._torch is None:
                from .graphs import TorchCalls  # torch: a batch too large
                self._torch = TorchCalls(self.networks, 'cpu', self.channels)
            return self._torch(module, *args)
        feed = [self._image(a) if a.ndim == 4 else np.asarray(a) for a in args]
        # A graph per image size: a room larger than its type's square is seen larger, and
        # graphs of fixed sizes keep the rooms of the paper's sizes on their fastest path.
        key = (module, tuple(args[0].shape[2:]))
        if key not in self._sessions:
            self._sessions[key] = self._open(module, feed)
        session, names = self._sessions[key]
        outs = tuple(session.run(None, dict(zip(names, feed, strict=True))))
        if module == 'location' and len(outs) == 1:
            return outs + (None,)
        return outs

    def _image(self, image: np.ndarray) -> np.ndarray:
        """``image`` (N, C, H, W) as the graphs take it: channels-last, with
        ``image_channels``; one drawn so (``padded_channels``) is not copied."""
        pixels = np.moveaxis(image, 1, -1)
        if pixels.shape[-1] == self.image_channels:
            return np.ascontiguousarray(pixels, dtype=np.float32)
        if pixels.shape[-1] != self.channels:
            raise ValueError(f'an image of {pixels.shape[-1]} channels for networks that '
                             f'take {self.channels}')
        out = np.zeros(pixels.shape[:-1] + (self.image_channels,), dtype=np.float32)
        out[..., :self.channels] = pixels
        return out

    def _open(self, module: str, feed: list[np.ndarray]) -> tuple:
        """A session running ``module``'s graph for inputs shaped as ``feed``: the cached
        graph, else one exported now (and kept)."""
        names = [f'input{k}' for k in range(len(feed))]
        path = None
        if self.cache_dir is not None:
            if self.weights is not None:
                weights = self.weights
            else:
                from .graphs import weights_hash  # torch: networks of no file
                weights = weights_hash(self.networks, module)
            path = Path(self.cache_dir) / f'{module}-{graph_key(weights, module, feed)}.onnx'
            try:
                session = _session(path.read_bytes(), module)
            except Exception:   # not there, unreadable or not a graph: export it again
                pass
            else:
                self.loaded.append(module)
                with suppress(OSError):   # used: the last to be pruned (``keep``)
                    path.touch()
                return session, names
        from .graphs import export_graph  # torch: a graph not in the cache
        graph = export_graph(self.networks, module, feed, names, self.image_channels)
        session = _session(graph, module)
        if path is not None:
            keep(path, graph, CACHE_GRAPHS, tuple(f'{m}-' for m in MODULE_CALLS))
        return session, names


def padded_channels(channels: int) -> int:
    """The channels of the images that the graphs take: ``channels`` rounded up to a whole
    number of ``CHANNEL_BLOCK``, the extra ones zero."""
    return -(-channels // CHANNEL_BLOCK) * CHANNEL_BLOCK


def _session(graph: bytes, module: str):
    """An onnxruntime session running ``graph``, ``module``'s call, with ``threads()``
    threads."""
    import onnxruntime  # optional: the torch runtime runs without it
    options = onnxruntime.SessionOptions()
    options.intra_op_num_threads = threads()
    options.inter_op_num_threads = 1
    options.execution_mode = onnxruntime.ExecutionMode.ORT_SEQUENTIAL
    options.log_severity_level = 4          # none: a damaged cached graph is exported again
    # No arena: it kept the largest batch's buffers, 50 MB more a lockstep worker. No
    # spinning: threads that spin between passes starve the process beside them (two
    # threads and one busy core took a bedroom from 0.12 to 0.35 s).
    options.enable_cpu_mem_arena = False
    options.add_session_config_entry('session.intra_op.allow_spinning', '0')
    # Where several networks see one image, common subexpression elimination would merge
    # their stems' turns again (``graphs.export_graph``); elsewhere onnxruntime's default
    # stays.
    disabled = ['CommonSubexpressionElimination'] if len(CALL_NETWORKS[module]) > 1 else []
    return onnxruntime.InferenceSession(graph, options, providers=['CPUExecutionProvider'],
                                        disabled_optimizers=disabled)


def keep(path: Path, data: bytes, limit: int, kinds: tuple[str, ...]) -> None:
    """Write ``data`` to the cache whole or not at all; a cache that cannot be written
    (read-only, full) only costs the next process an export. Of the files there of ``path``'s
    suffix whose names start with one of ``kinds`` (this package's: other files in a shared
    directory stay), the least recently used beyond ``limit`` go."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(path, data)     # processes writing the same file: the last one stays
        # Those of weights or code replaced since go first: reading one back marks it used.
        ours = [p for p in path.parent.glob(f'*{path.suffix}') if p.name.startswith(kinds)]
        for old in sorted(ours, key=lambda p: p.stat().st_mtime, reverse=True)[limit:]:
            old.unlink(missing_ok=True)
    except OSError:
        pass
