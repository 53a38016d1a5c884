"""Evaluation against an imported data set's held-out rooms (``scene-synth evaluate --data``).

For each room type of the weights' bundles that the data set holds:

* *held-out* rooms: the rooms training held out, found again by the code training found them
  with (``datasets.training.split_rooms``): the data set's rooms of that type, reduced to
  what the bundle's category set can place, split by a shuffle of their file names with the
  bundle's ``corpus_seed``, the first ``val_rooms`` of the held-out part;
* *training* rooms: the first ``train_rooms`` of the other part, the rooms the bundle
  learned from. Their category KL from the held-out rooms is how much two samples of real
  rooms differ, the line the synthesized rooms' KL is read against;
* *synthesized* rooms: the empty shell of every held-out room furnished from scratch
  ``rooms_per_shell`` times, copy ``k`` of shell ``i`` with synthesis seed
  ``seed * SEED_STRIDE + i * rooms_per_shell + k``.

Measured per room type, synthesized against held-out: the category KL
(``categories.kl_divergence``), objects per room, validity (``plausibility``, the checks of
the paper-corpus evaluation) and the design rules (``design_rules``; a rule none of whose
categories the data set has has no case on either side and reads as not applicable).
"""
from __future__ import annotations

from contextlib import ExitStack
from dataclasses import asdict, dataclass
from pathlib import Path
import time
from typing import Sequence

import torch

from .. import rules as design_rules
from ..allowance import STRICT, Allowance
from ..categories import PAPER, ROOM_TYPE_ALIASES, RoomTypeSpec, Vocabulary, kl_divergence
from ..datasets.training import describe_dir, room_type_spec, split_rooms
from ..errors import DatasetError, RoomTypeConflict
from ..geometry import check_scene
from ..networks.bundle import BundleError, bundle_path, bundle_specs, load_bundle
from ..scene import Scene
from ..synth import SynthConfig, SynthesisError, Synthesizer
from . import dataset_report, plausibility, speed
from .data import SynthRecord
from .distribution import distribution, frequencies
from .parallel import pmap
from .run import EvalEcho, EvaluationError, prepare_out_dir

SEED_STRIDE = 100_000


@dataclass
class DataEvalConfig:
    """Sizes and seeds of a data-set evaluation."""

    rooms_per_shell: int = 4                 # synthesized rooms per held-out shell
    seed: int = 0
    synth: SynthConfig | None = None         # None: the synthesizer's defaults

    def validate(self) -> None:
        if self.rooms_per_shell < 1:
            raise EvaluationError(f'--rooms-per-shell must be at least 1, got '
                                  f'{self.rooms_per_shell}')

    def seed_of(self, shell: int, copy: int) -> int:
        return self.seed * SEED_STRIDE + shell * self.rooms_per_shell + copy

    def to_dict(self) -> dict:
        return {'rooms_per_shell': self.rooms_per_shell, 'seed': self.seed,
                'seed_stride': SEED_STRIDE,
                'synth': asdict(self.synth) if self.synth is not None else None}


@dataclass
class Split:
    """One room type's rooms of the data set as the bundle's training split them."""

    room_type: str
    corpus_seed: int
    rooms: int                        # rooms of the type in the data set
    training: list[Scene]
    heldout: list[Scene]
    heldout_names: list[str]
    removed: dict[str, int]           # objects the category set cannot place, by reason


# ---- input -------------------------------------------------------------------------------
def _describe(data_dir: Path):
    try:
        return describe_dir(data_dir)
    except DatasetError as e:
        raise EvaluationError(str(e)) from None


def _room_type_name(value: str) -> str:
    # The names ``scene-synth train --data`` accepts, and the aliases of the paper's types.
    key = value.strip().lower().replace('_', ' ')
    return ROOM_TYPE_ALIASES.get(key, key)


def choose_room_types(value: str, held: Sequence[str], bundles: dict, data_dir: Path,
                      weights_dir: Path) -> list[str]:
    """The room types a ``--room-type`` value names among those the data set holds, each
    with a bundle in the weights directory (``all``: every such one)."""
    train = f'scene-synth train --data {data_dir} --weights-dir {weights_dir}'
    if value == 'all':
        rts = [rt for rt in held if rt in bundles]
        if not rts:
            raise EvaluationError(f'{weights_dir} holds no bundle for any room type of '
                                  f'{data_dir} ({", ".join(held)}); train them with {train}')
    else:
        rt = _room_type_name(value)
        if rt not in held:
            raise EvaluationError(f'unknown room type {value[:80]!r}: {data_dir} holds '
                                  f'{", ".join(held)}')
        if rt not in bundles:
            raise EvaluationError(f'{weights_dir} holds no bundle for room type {rt!r} of '
                                  f'{data_dir}; train it with {train} --room-type {rt}')
        rts = [rt]
    for rt in rts:
        if bundles[rt] is None:
            raise EvaluationError(f'the bundle for {rt!r} in {weights_dir} was trained on the '
                                  f'procedural corpus, not on a data set: --data needs '
                                  f'weights trained on {data_dir} (scene-synth train --data '
                                  f'{data_dir} --weights-dir NEW_DIR)')
    return rts


def _train_config(weights_dir: Path, room_type: str, vocabulary: Vocabulary):
    """The training configuration of a bundle: how it split the data set's rooms."""
    try:
        return load_bundle(bundle_path(weights_dir, room_type, vocabulary)).config.train
    except BundleError as e:
        raise EvaluationError(str(e)) from None


def load_split(data_dir: Path, spec: RoomTypeSpec, train_cfg, rooms: int) -> Split:
    """The training and held-out rooms of ``spec``'s room type, divided by the code that
    divides them for training (``datasets.training.split_rooms``) with the bundle's corpus
    seed and sizes; ``rooms``: how many the data set holds (its description says)."""
    d = split_rooms(data_dir, spec, train_cfg.corpus_seed, train_cfg.train_rooms,
                    train_cfg.val_rooms)
    if not d.held_out:
        raise EvaluationError(f'{data_dir} holds {len(d.train)} readable {spec.room_type} '
                              f'room(s), too few for training to have held any out')
    return Split(spec.room_type, train_cfg.corpus_seed, rooms, d.train, d.held_out,
                 d.held_out_names, dict(d.removed))


def _data_spec(desc, room_type: str) -> RoomTypeSpec | None:
    try:
        return room_type_spec(desc.room_types[room_type], desc.format)
    except DatasetError:
        return None


# ---- synthesis ---------------------------------------------------------------------------
_SYNTH = None


def _init_synthesizer(weights_dir, synth_cfg) -> None:
    global _SYNTH
    # One per process (a worker too); it knows the weights' room types (its vocabulary).
    _SYNTH = Synthesizer(weights_dir, synth_cfg)
    _SYNTH.load_all()           # so that no room's seconds include loading its bundle


def _furnish(job) -> SynthRecord | str:
    """One shell furnished, or why it could not be (the room is then left out)."""
    index, room, seed = job
    try:
        r = _SYNTH.generate(room, seed=seed)
    except SynthesisError as e:
        return str(e)
    return SynthRecord(index, r.scene, r.seconds, dict(r.timings), r.stopped)


def synthesize_shells(split: Split, cfg: DataEvalConfig, weights_dir: Path, workers: int = 1,
                      progress: bool = True) -> tuple[list[dict], list[SynthRecord], list[dict]]:
    """The held-out shells furnished ``cfg.rooms_per_shell`` times each: a row per
    synthesized room, the rooms, and a row per shell copy that failed."""
    k = cfg.rooms_per_shell
    jobs = [(i * k + c, split.heldout[i].room, cfg.seed_of(i, c))
            for i in range(len(split.heldout)) for c in range(k)]
    outcomes = pmap(_furnish, jobs, workers, _init_synthesizer, (str(weights_dir), cfg.synth),
                    desc=f'{split.room_type} synthesis', progress=progress)
    rows, records, failed = [], [], []
    for (index, _, seed), got in zip(jobs, outcomes, strict=True):
        shell = split.heldout_names[index // k]
        if isinstance(got, str):
            failed.append({'shell': shell, 'seed': seed, 'error': got})
            continue
        records.append(got)
        rows.append({'shell': shell, 'seed': seed, 'objects': len(got.scene),
                     'stopped': got.stopped, 'seconds': round(got.seconds, 4)})
    return rows, records, failed


# ---- measurements ------------------------------------------------------------------------
def _mean_objects(scenes: Sequence[Scene]) -> float | None:
    return sum(len(s) for s in scenes) / len(scenes) if scenes else None


def compare_categories(spec: RoomTypeSpec, synth: Sequence[Scene], heldout: Sequence[Scene],
                       training: Sequence[Scene]) -> dict:
    """KL(group || held-out) of the synthesized and the training rooms (and of a uniform
    guess over the category set), objects per room, and per-category frequencies."""
    ref = distribution(heldout)

    def kl(p: dict) -> float | None:
        # None where undefined: a side without objects has no category distribution.
        return kl_divergence(p, ref) if p and ref else None
    names = list(spec.names)
    names += sorted({o.category for g in (synth, heldout, training) for s in g
                     for o in s.objects} - set(names))
    per_room = {name: _mean_objects(g) for name, g in
                (('synthesized', synth), ('heldout', heldout), ('training', training))}
    held = per_room['heldout']
    return {
        'kl_synthesized': kl(distribution(synth)),
        'kl_training': kl(distribution(training)),
        'kl_uniform': kl({c: 1.0 / len(spec.names) for c in spec.names}),
        'objects_per_room': per_room,
        'objects_relative_difference': (per_room['synthesized'] / held - 1
                                        if held and per_room['synthesized'] is not None
                                        else None),
        'frequencies': {name: frequencies(g, names) for name, g in
                        (('synthesized', synth), ('heldout', heldout), ('training', training))},
    }


def validity(groups: dict[str, Sequence[Scene]], allowance: Allowance = STRICT) -> dict:
    """The paper-corpus evaluation's validity checks (``plausibility``) of each group, with
    what the data set's ``allowance`` lets its rooms do; ``valid_strict``: the share of
    rooms valid without it."""
    out = {}
    for name, scenes in groups.items():
        out[name] = plausibility.evaluate(scenes, allowance)
        out[name]['valid_strict'] = (sum(check_scene(s).ok for s in scenes) / len(scenes)
                                     if scenes else 0.0)
    return out


def rule_report(heldout: Sequence[Scene], synth: Sequence[Scene],
                vocabulary: Vocabulary = PAPER) -> dict:
    """Every design rule in the held-out rooms (the ``corpus`` side of the record) and in
    the synthesized ones, whose categories are those of ``vocabulary``."""
    return design_rules.summarize(
        [design_rules.measure(s, vocabulary=vocabulary) for s in heldout],
        [design_rules.measure(s, vocabulary=vocabulary) for s in synth])


def evaluate_data_room_type(split: Split, spec: RoomTypeSpec, cfg: DataEvalConfig,
                            weights_dir: Path, workers: int = 1, progress: bool = True,
                            echo: EvalEcho = print, allowance: Allowance = STRICT) -> dict:
    """Every measurement of one room type against its held-out rooms."""
    stages: dict[str, float] = {}
    clock = time.perf_counter()

    def stage(name: str) -> None:
        nonlocal clock
        now = time.perf_counter()
        stages[name], clock = now - clock, now
        echo(f'  {split.room_type}: {name} done in {stages[name]:.1f} s')

    rows, records, failed = synthesize_shells(split, cfg, weights_dir, workers, progress)
    synth = [r.scene for r in records]
    stage('synthesis')
    res = {
        'split': {'corpus_seed': split.corpus_seed, 'rooms': split.rooms,
                  'training': len(split.training), 'heldout': len(split.heldout),
                  'objects_removed': split.removed},
        'heldout_names': split.heldout_names,
        'rooms': {'shells': len(split.heldout), 'synthesized': len(synth),
                  'failed': len(failed)},
        'synthesized': rows, 'failed': failed,
        'distribution': compare_categories(spec, synth, split.heldout, split.training),
        'validity': validity({'synthesized': synth, 'heldout': split.heldout}, allowance),
        'speed': speed.summarize(records),
        'stage_seconds': stages,
    }
    stage('categories and validity')
    res['design_rules'] = rule_report(split.heldout, synth, PAPER.with_specs([spec]))
    stage('design rules')
    return res


# ---- the run -----------------------------------------------------------------------------
def _bundle_specs(weights_dir: Path) -> dict[str, RoomTypeSpec | None]:
    if not weights_dir.is_dir():
        raise EvaluationError(f'{weights_dir}: no such weights directory')
    return bundle_specs(weights_dir)


def run_data_evaluation(data_dir: str | Path, weights_dir: str | Path, room_type: str = 'all',
                        cfg: DataEvalConfig | None = None, out: str | Path = 'report',
                        workers: int = 1, progress: bool = True, echo: EvalEcho = print,
                        command: str | None = None,
                        markdown_copy: str | Path | None = None) -> dict:
    """Evaluate the weights of ``weights_dir`` against the held-out rooms of the imported
    data set ``data_dir`` and write ``out/index.md`` and ``out/results.json`` (and the
    Markdown to ``markdown_copy`` too). Raises ``EvaluationError`` for bad input before any
    long computation. The room types and categories are those the weights were trained on."""
    cfg = cfg or DataEvalConfig()
    cfg.validate()
    data_dir, weights_dir = Path(data_dir), Path(weights_dir)
    desc = _describe(data_dir)
    specs = _bundle_specs(weights_dir)
    rts = choose_room_types(room_type, list(desc.room_types), specs, data_dir, weights_dir)
    workers = max(1, int(workers))
    out = prepare_out_dir(out)
    threads = torch.get_num_threads()
    try:
        vocabulary = PAPER.with_specs(s for s in specs.values() if s is not None)
    except RoomTypeConflict as e:
        raise EvaluationError(f'{weights_dir}: {e}') from None
    with ExitStack() as stack:
        stack.callback(torch.set_num_threads, threads)
        splits = {rt: load_split(data_dir, specs[rt],
                                 _train_config(weights_dir, rt, vocabulary),
                                 desc.room_types[rt].rooms) for rt in rts}
        results = {'mode': 'dataset', 'command': command, 'data_dir': str(data_dir),
                   'format': desc.format, 'weights_dir': str(weights_dir),
                   'config': cfg.to_dict(), 'hardware': speed.hardware(workers),
                   'allowance': desc.allowance.to_dict(),
                   'without_bundle': [rt for rt in desc.room_types if rt not in specs],
                   'room_types': {}, 'seconds': 0.0}
        if room_type == 'all' and results['without_bundle']:
            echo(f'{weights_dir} holds no bundle for {", ".join(results["without_bundle"])} '
                 f'of {data_dir}: not evaluated')
        t0 = time.perf_counter()
        for rt in rts:
            split = splits[rt]
            echo(f'{rt}: {len(split.heldout)} held-out rooms of {split.rooms}, '
                 f'{cfg.rooms_per_shell} synthesized per shell (seed {cfg.seed}, '
                 f'{workers} workers)')
            res = evaluate_data_room_type(split, specs[rt], cfg, weights_dir, workers,
                                          progress, echo, desc.allowance)
            # A description edited after training no longer says what the weights learned.
            res['spec_matches_data'] = _data_spec(desc, rt) == specs[rt]
            results['room_types'][rt] = res
            results['seconds'] = time.perf_counter() - t0
            dataset_report.write(results, out, Path(markdown_copy) if markdown_copy else None)
    return results


__all__ = ['DataEvalConfig', 'Split', 'choose_room_types', 'load_split',
           'run_data_evaluation']
