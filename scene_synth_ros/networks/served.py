"""What synthesis needs of a weights bundle besides its network calls, without torch.

A bundle (``bundle.py``) is a torch file: reading it takes torch, a second and a half to
import. A ``Served`` record holds the rest of what synthesis reads of it (its room type,
configuration, category set, allowance, model co-occurrence, the CVAEs' latent sizes and
the dimensions module's learned spread); with the bundle's graphs in the cache
(``runtime.OnnxCalls``), it lets a process furnish rooms without importing torch. Records
are kept beside the graphs, named by a hash of the bundle file's bytes and the code, and
written the first time a process running onnxruntime loads the bundle with torch; like the
graphs they are only ever a saving: one that cannot be read is made again from the bundle.
"""
from __future__ import annotations

from contextlib import suppress
from dataclasses import dataclass, field
from functools import cached_property, lru_cache
import hashlib
import io
import json
from pathlib import Path
from typing import Any

import numpy as np

from ..allowance import STRICT, Allowance
from ..categories import PAPER, RoomTypeSpec, Vocabulary
from ..errors import RoomTypeConflict, SceneSynthError
from .config import PipelineConfig
from .runtime import code_hash, graph_cache_dir, keep

# The most records kept in the cache (a few KB to 2 MB each).
CACHE_RECORDS = 64


class BundleError(SceneSynthError):
    """A weights file that is missing, unreadable or does not match the code."""


def bundle_path(weights_dir: str | Path, room_type: str,
                vocabulary: Vocabulary = PAPER) -> Path:
    return Path(weights_dir) / f'{vocabulary.resolve(room_type)}.pt'


@dataclass
class Served:
    room_type: str
    config: PipelineConfig
    models: list[str]
    cooccurrence: np.ndarray                 # (M, M) counts over ``models``
    spec: RoomTypeSpec | None                # the data set's category set; None: the paper's
    allowance: Allowance
    latents: dict[str, int]                  # the orientation and dimensions CVAEs' z sizes
    log_sigma: np.ndarray | None             # (C, 2) the dimensions' learned spread, or None
    location_multiple: int                   # the location network's image sides' multiple
    channels: int                            # the channels of the images the networks take
    weights: str                             # the bundle file's hash (``file_hash``)
    metrics: dict[str, Any] = field(default_factory=dict)

    @cached_property
    def model_index(self) -> dict[str, int]:
        """The index of each of ``models`` (its row and column of ``cooccurrence``)."""
        return {m: k for k, m in enumerate(self.models)}

    @cached_property
    def model_rooms(self) -> np.ndarray:
        """How many training rooms hold each model (the diagonal of ``cooccurrence``), at
        least 1 so that it can divide."""
        return np.maximum(np.diagonal(self.cooccurrence), 1.0)

    @cached_property
    def vocabulary(self) -> Vocabulary:
        return PAPER if self.spec is None else PAPER.with_specs([self.spec])

    def to_bytes(self) -> bytes:
        meta = {'room_type': self.room_type, 'config': self.config.to_json(),
                'models': self.models, 'metrics': self.metrics,
                'spec': None if self.spec is None else self.spec.to_dict(),
                'allowance': None if self.allowance == STRICT else self.allowance.to_dict(),
                'latents': self.latents, 'location_multiple': self.location_multiple,
                'channels': self.channels, 'weights': self.weights}
        arrays = {'meta': np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8),
                  'cooccurrence': self.cooccurrence.astype(np.float32)}
        if self.log_sigma is not None:
            arrays['log_sigma'] = self.log_sigma.astype(np.float32)
        out = io.BytesIO()
        np.savez(out, **arrays)
        return out.getvalue()

    @classmethod
    def from_bytes(cls, data: bytes) -> Served:
        with np.load(io.BytesIO(data), allow_pickle=False) as z:
            meta = json.loads(z['meta'].tobytes().decode())
            co = z['cooccurrence'].astype(np.float64)
            log_sigma = z['log_sigma'] if 'log_sigma' in z.files else None
        return cls(
            room_type=meta['room_type'],
            config=PipelineConfig.from_dict(json.loads(meta['config'])), models=meta['models'],
            cooccurrence=co,
            spec=None if meta['spec'] is None else RoomTypeSpec.from_dict(meta['spec']),
            allowance=(STRICT if meta['allowance'] is None
                       else Allowance.from_dict(meta['allowance'])),
            latents={k: int(v) for k, v in meta['latents'].items()}, log_sigma=log_sigma,
            location_multiple=int(meta['location_multiple']), channels=int(meta['channels']),
            weights=meta['weights'], metrics=meta['metrics'])


def file_hash(path: Path) -> str:
    """The hash of a bundle file's bytes, which names its weights in the cache; OSError
    where it cannot be read."""
    st = path.stat()
    return _file_hash(str(path.resolve()), st.st_mtime_ns, st.st_size)


@lru_cache(maxsize=64)
def _file_hash(path: str, mtime: int, size: int) -> str:
    h = hashlib.sha256()
    with open(path, 'rb') as f:
        while chunk := f.read(1 << 22):
            h.update(chunk)
    return h.hexdigest()[:32]


def _cached(weights: str, kind: str, suffix: str) -> Path | None:
    """Where the cache keeps the ``kind`` of the bundle whose file hashes to ``weights``;
    None without a cache."""
    cache = graph_cache_dir()
    if cache is None:
        return None
    key = hashlib.sha256(f'{code_hash()}\0{weights}'.encode()).hexdigest()[:32]
    return cache / f'{kind}-{key}{suffix}'


def read_record(path: Path) -> Served | None:
    """The record of the bundle at ``path`` from the cache, or None (no cache, none kept,
    or one that cannot be read)."""
    try:
        where = _cached(file_hash(path), 'bundle', '.npz')
        if where is None:
            return None
        record = Served.from_bytes(where.read_bytes())
    except Exception:   # not there, unreadable, or of a format gone: made again
        return None
    with suppress(OSError):     # used: the last to be pruned (a read-only cache still serves)
        where.touch()
    return record


def keep_record(record: Served) -> None:
    """Keep ``record`` in the cache (nothing where there is none, or it cannot be written)."""
    where = _cached(record.weights, 'bundle', '.npz')
    if where is not None:
        keep(where, record.to_bytes(), CACHE_RECORDS, ('bundle-',))


def _room_type_of(path: Path) -> tuple[str, RoomTypeSpec | None]:
    """The room type of the bundle at ``path`` and the data set's category set it carries:
    from its record, or the cache's note of them, else from the file (torch), noted for
    the next process. OSError or ``BundleError`` where the file is not a readable bundle."""
    record = read_record(path)
    if record is not None:
        return record.room_type, record.spec
    where = _cached(file_hash(path), 'spec', '.json')
    try:
        noted = json.loads(where.read_text())
        return noted['room_type'], (None if noted['spec'] is None
                                    else RoomTypeSpec.from_dict(noted['spec']))
    except Exception:   # no cache, none noted, or a note that cannot be read
        pass
    room_type, spec = _stored_spec(path)
    if where is not None:
        note = {'room_type': room_type, 'spec': None if spec is None else spec.to_dict()}
        keep(where, json.dumps(note).encode(), CACHE_RECORDS, ('spec-',))
    return room_type, spec


def spec_in_bundle(data: dict) -> RoomTypeSpec | None:
    """The data set's category set a bundle's dict carries (None: the paper's);
    ValueError when it is of another room type than the bundle."""
    if 'room_type_spec' not in data:
        return None
    spec = RoomTypeSpec.from_dict(json.loads(data['room_type_spec']))
    if spec.room_type != data['room_type']:
        raise ValueError(f'its category set is of room type {spec.room_type!r}')
    return spec


def _stored_spec(path: Path) -> tuple[str, RoomTypeSpec | None]:
    """The room type of the bundle file at ``path`` and the category set it carries, read
    with torch (``mmap``: the tensors stay on disk) without building any network;
    ``BundleError`` where it is not a readable bundle."""
    import torch  # a bundle not yet noted in the cache
    try:
        data = torch.load(path, map_location='cpu', weights_only=True, mmap=True)
        return str(data['room_type']), spec_in_bundle(data)
    except Exception as e:  # any unreadable file: the caller counts it by its name
        raise BundleError(f'{path}: {type(e).__name__}') from None


def bundle_specs(weights_dir: str | Path) -> dict[str, RoomTypeSpec | None]:
    """The room types of the bundles in ``weights_dir``, each with the data set's category
    set it carries (None: the paper's), from the cache where it has them, else from the
    files without building any network. A file that is not a readable bundle counts by its
    name, with None: loading it names what is wrong."""
    out: dict[str, RoomTypeSpec | None] = {}
    for path in sorted(Path(weights_dir).glob('*.pt')):
        try:
            room_type, spec = _room_type_of(path)
        except (OSError, BundleError):
            room_type, spec = path.stem, None
        out[room_type] = spec
    return out


def weights_vocabulary(weights_dir: str | Path,
                       specs: dict[str, RoomTypeSpec | None] | None = None) -> Vocabulary:
    """What the networks in ``weights_dir`` know: the paper's table with the category sets
    of the data sets their bundles were trained on (``specs``, its ``bundle_specs`` where
    they are known). Reads no network."""
    if specs is None:
        specs = bundle_specs(weights_dir)
    try:
        return PAPER.with_specs(s for s in specs.values() if s is not None)
    except RoomTypeConflict as e:
        raise BundleError(f'{weights_dir}: {e}') from None
