"""What runs the networks' forward passes in synthesis: torch, or onnxruntime on the CPU.

Synthesis makes four network calls (``MODULE_CALLS``); ``forward`` is each call as torch
runs it, the one definition of what a call computes. On the CPU a call of one room at a
time is a batch of one through networks of 16-128 channels, which torch runs at the speed of
its per-layer overhead, not of the arithmetic. ``OnnxCalls`` exports each call once, from
``forward`` and the bundle's folded networks, to an ONNX graph and runs it in an onnxruntime
session: at a batch of one a bedroom's calls take 1.3-2.4x less time there (the location
call 2.1 against 4.8 ms on a slow day), and a whole bedroom 27-30 % less
(``benchmarks/runtime_gain.py``). The graphs take
images laid out channels-last, as synthesis draws them on the CPU, so no image is copied on
the way in.

The two runtimes sum in different orders, so their outputs differ in the last digits (about
1e-6 of the largest output); a draw that falls that close to a boundary can go another way,
and the room goes on differently from there. The rooms of one runtime are therefore equal
in distribution to the other's, nearly all the very same rooms (``tests/test_runtime.py``
checks both), and the same seed gives the same room in either.

onnxruntime's lead is overhead saved, so it shrinks as the batch grows: torch's oneDNN
convolutions gain from a batch of four or more, onnxruntime's pass costs about the batch
times one example's. So a call of more examples than ``ONNX_MAX_BATCH`` says is run by torch
(on this CPU, ``benchmarks/runtime_gain.py --sizes 1,2,3,4,6,8,16``, onnxruntime is ahead up
to those sizes and level or behind beyond), and a batch of rooms in lockstep, whose calls
are mostly larger, runs torch under ``auto`` (``batch._runtime_chosen``).

``config.resolve_runtime`` chooses: ``auto`` is onnxruntime on the CPU where it is installed
(it is in ``requirements.txt``), torch elsewhere (CUDA, or no onnxruntime).
"""
from __future__ import annotations

import io
import warnings

import numpy as np
import torch
from torch import nn

# The network calls of synthesis: what each takes and gives, batch first.
#   category     (image, counts)    -> (logits,)            next category or STOP
#   location     (image,)           -> (logits, offsets)    offsets None without them
#   orientation  (crops, cats, z)   -> (outputs, snap logits)
#   dimensions   (crops, cats, z)   -> (log footprints,)
MODULE_CALLS = ('category', 'location', 'orientation', 'dimensions')


# The largest batch of each call that onnxruntime runs; larger ones go to torch (see above).
ONNX_MAX_BATCH = {'category': 4, 'location': 8, 'orientation': 3, 'dimensions': 3}


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
    """One call of ``forward`` with its images taken channels-last (N, H, W, C), and only
    the outputs that exist (an ONNX graph has no None)."""

    def __init__(self, networks: dict, module: str, images: tuple[bool, ...]):
        super().__init__()
        self.networks = nn.ModuleDict(networks)
        self.module = module
        self.images = images

    def forward(self, *args: torch.Tensor) -> tuple[torch.Tensor, ...]:
        args = tuple(a.permute(0, 3, 1, 2) if image else a
                     for a, image in zip(args, self.images, strict=True))
        return tuple(o for o in forward(self.networks, self.module, *args) if o is not None)


class OnnxCalls:
    """A bundle's network calls run by onnxruntime: each exported from ``forward`` on its
    first call, for a batch of any size, and run in a session of as many threads as torch
    has then (one in a batch worker); a batch larger than ``ONNX_MAX_BATCH`` says is run by
    torch. Called like ``forward`` with the networks bound: ``calls(module, *args)``;
    answers are torch tensors on the CPU."""

    def __init__(self, networks: dict):
        self.networks = networks
        self._sessions: dict[str, tuple] = {}

    @property
    def exported(self) -> tuple[str, ...]:
        """The calls exported so far (those onnxruntime has run)."""
        return tuple(sorted(self._sessions))

    def __call__(self, module: str, *args: torch.Tensor) -> tuple[torch.Tensor | None, ...]:
        if module not in MODULE_CALLS:
            raise ValueError(f'no network call {module!r}; the calls are '
                             f'{", ".join(MODULE_CALLS)}')
        if args[0].shape[0] > ONNX_MAX_BATCH[module]:
            return forward(self.networks, module, *args)
        if module not in self._sessions:
            self._sessions[module] = self._export(module, args)
        session, names, offsets = self._sessions[module]
        feed = {name: np.ascontiguousarray((a.permute(0, 2, 3, 1) if a.dim() == 4 else a)
                                           .detach().cpu().numpy())
                for name, a in zip(names, args, strict=True)}
        outs = tuple(torch.from_numpy(o) for o in session.run(None, feed))
        if module == 'location' and not offsets:
            return outs + (None,)
        return outs

    def _export(self, module: str, args: tuple[torch.Tensor, ...]) -> tuple:
        import onnxruntime
        images = tuple(a.dim() == 4 for a in args)
        names = [f'input{k}' for k in range(len(args))]
        call = _Call(self.networks, module, images).eval()
        graph = io.BytesIO()
        # The TorchScript-based exporter: torch (pinned) still has it, and it exports a call
        # in about 0.1 s, where the torch.export-based one takes 4 s and another package.
        # Synthesis calls inside inference mode, whose tensors a trace cannot record.
        with warnings.catch_warnings(), torch.inference_mode(False), torch.no_grad():
            warnings.simplefilter('ignore')
            example = tuple((a.permute(0, 2, 3, 1) if image else a).detach().cpu().clone()
                            for a, image in zip(args, images, strict=True))
            torch.onnx.export(call, example, graph, dynamo=False, input_names=names,
                              dynamic_axes={name: {0: 'batch'} for name in names})
        options = onnxruntime.SessionOptions()
        options.intra_op_num_threads = torch.get_num_threads()
        options.inter_op_num_threads = 1
        options.execution_mode = onnxruntime.ExecutionMode.ORT_SEQUENTIAL
        options.log_severity_level = 3          # errors only: its warnings are about graphs
        # No arena: it kept the largest batch's buffers, 50 MB more a lockstep worker. No
        # spinning: threads that spin between passes starve the process beside them (two
        # threads and one busy core took a bedroom from 0.12 to 0.35 s).
        options.enable_cpu_mem_arena = False
        options.add_session_config_entry('session.intra_op.allow_spinning', '0')
        session = onnxruntime.InferenceSession(graph.getvalue(), options,
                                               providers=['CPUExecutionProvider'])
        offsets = module == 'location' and self.networks['location'].offset is not None
        return session, names, offsets
