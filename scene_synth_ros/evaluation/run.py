"""One evaluation run: every measurement of every room type asked for, then the report.

``run_evaluation(['bedroom'], EvalConfig(), 'report/')`` is what ``scene-synth evaluate``
calls; ``EvalConfig.quick()`` is the smoke-test size.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass
import math
from pathlib import Path
import time
from typing import Callable, Sequence

import numpy as np
import torch

from .. import rules as design_rules
from ..categories import ROOM_TYPES, resolve_room_type
from ..corpus import HELDOUT_SEED
from ..errors import SceneSynthError
from ..networks.bundle import BundleError, bundle_path, load_bundle
from ..paths import weights_dir as default_weights
from . import (
    classifier,
    components,
    data,
    distribution,
    figures,
    plausibility,
    report,
    similarity,
    speed,
)
from .parallel import pmap
from .perturb import perturb_all, perturbation_key

EvalEcho = Callable[[str], None]


class EvaluationError(SceneSynthError):
    """A problem with the evaluation's input, said in one sentence."""


@dataclass
class EvalConfig:
    """Sizes of an evaluation run; the defaults are the paper's."""

    name: str = 'full'
    seed: int = 0
    synth_rooms: int = 1000          # synthesized rooms per room type (held-out shells)
    corpus_rooms: int = 5000         # training-corpus rooms: KL and similarity reference,
                                     # the classifier's real side
    heldout_rooms: int = 1000        # held-out corpus rooms: noise floors, perturbed side
    classifier_train: int = 1600     # half real, half fake
    classifier_test: int = 320       # held out, balanced
    classifier_epochs: int = 12
    classifier_widths: tuple[int, ...] = (16, 32, 64, 128)
    classifier_batch: int = 32
    perturbations: tuple[float, ...] = (0.0, 0.01, 0.05, 0.10)   # 0.0: unperturbed control
    similarity_queries: int = 1000   # synthesized and held-out rooms compared...
    similarity_sigma: float = 0.1    # ...with the kernel width of similarity.SIGMA
    histogram_bins: int = 20
    gallery_rooms: int = 4

    @classmethod
    def quick(cls, seed: int = 0) -> 'EvalConfig':
        """Tiny sizes that check the whole run end to end in seconds, not its values."""
        return cls(name='quick', seed=seed, synth_rooms=24, corpus_rooms=32,
                   heldout_rooms=24, classifier_train=32, classifier_test=16,
                   classifier_epochs=1, classifier_widths=(8, 16, 32, 64),
                   similarity_queries=16, histogram_bins=10, gallery_rooms=2)

    def validate(self) -> None:
        """Raise ValueError naming the first inconsistent size."""
        for k in ('synth_rooms', 'corpus_rooms', 'heldout_rooms', 'classifier_train',
                  'classifier_test', 'classifier_epochs', 'classifier_batch',
                  'similarity_queries', 'histogram_bins', 'gallery_rooms'):
            if getattr(self, k) < 1:
                raise ValueError(f'{k} must be at least 1, got {getattr(self, k)}')
        if self.classifier_train % 2 or self.classifier_test % 2:
            raise ValueError('the classifier sets are balanced: classifier_train and '
                             'classifier_test must be even')
        side = (self.classifier_train + self.classifier_test) // 2
        for k in ('synth_rooms', 'corpus_rooms', 'heldout_rooms'):
            if getattr(self, k) < side:
                raise ValueError(f'{k} ({getattr(self, k)}) must be at least the {side} '
                                 f'rooms a side of the classifier needs')
        if self.similarity_queries > min(self.synth_rooms, self.heldout_rooms):
            raise ValueError('similarity_queries cannot exceed synth_rooms or heldout_rooms')
        if self.gallery_rooms > min(self.synth_rooms, self.heldout_rooms):
            raise ValueError('gallery_rooms cannot exceed synth_rooms or heldout_rooms')
        if not self.similarity_sigma > 0:
            raise ValueError('similarity_sigma must be positive')
        if any(not 0 <= p < 1 for p in self.perturbations):
            raise ValueError('perturbations are fractions of a bounding box in [0, 1)')


def prepare_out_dir(out: str | Path) -> Path:
    """Create ``out`` and check a file can be written in it."""
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        probe = out / '.write_test'
        probe.write_text('')
        probe.unlink()
    except OSError as e:
        raise EvaluationError(f'{out}: cannot write the report there '
                              f'({e.strerror or type(e).__name__})') from None
    return out


def _load_bundles(room_types: Sequence[str], weights_dir) -> dict:
    """Per room type, the shipped bundle's input resolution and component metrics; bad or
    missing weights are found here, before any long computation."""
    root = Path(weights_dir) if weights_dir else default_weights()
    out = {}
    for rt in room_types:
        try:
            b = load_bundle(bundle_path(root, rt))
        except BundleError as e:
            raise EvaluationError(str(e)) from None
        out[rt] = {'resolution': b.config.model.resolution,
                   'components': b.metrics.get('components')}
    return out


def _seed(*parts: int) -> int:
    return int(np.random.SeedSequence([int(p) for p in parts]).generate_state(1)[0])


def _summary(values: np.ndarray) -> dict:
    v = np.asarray(values, dtype=float)
    return {'n': int(len(v)), 'mean': float(v.mean()), 'median': float(np.median(v)),
            'p10': float(np.quantile(v, 0.1)), 'p90': float(np.quantile(v, 0.9)),
            'above_0.9': float((v > 0.9).mean()), 'values': [round(float(x), 5) for x in v]}


def evaluate_room_type(room_type: str, cfg: EvalConfig, out: Path, bundle: dict,
                       workers: int = 1, weights_dir=None, progress: bool = True,
                       echo: EvalEcho = print) -> dict:
    """Every measurement of one room type; writes its figures into ``out``."""
    rt = resolve_room_type(room_type)
    k_rt = ROOM_TYPES.index(rt)
    stages: dict[str, float] = {}
    res: dict = {'resolution': bundle['resolution'], 'stage_seconds': stages}
    clock = time.perf_counter()

    def stage(name: str) -> None:
        nonlocal clock
        now = time.perf_counter()
        stages[name] = now - clock
        clock = now
        echo(f'  {rt}: {name} done in {stages[name]:.1f} s')

    corpus = data.corpus_rooms(rt, cfg.corpus_rooms, data.CORPUS_SEED, workers, progress)
    heldout = data.corpus_rooms(rt, cfg.heldout_rooms, HELDOUT_SEED, workers, progress)
    stage('corpus rooms')
    records = data.synthesize(rt, cfg.synth_rooms, cfg.seed, workers, weights_dir, progress)
    synth = [r.scene for r in records]
    stage('synthesis')

    res['distribution'] = distribution.compare(rt, synth, corpus, heldout)
    res['speed'] = speed.summarize(records)
    perturbed = {p: perturb_all(heldout, p, [cfg.seed, k_rt, 7, j])
                 for j, p in enumerate(cfg.perturbations) if p > 0}
    groups = {'synthesized': synth, 'corpus': heldout}
    groups.update({perturbation_key(p): s for p, s in perturbed.items()})
    res['plausibility'] = {}
    for name, scenes in groups.items():
        rows = pmap(plausibility.room_metrics, scenes, workers, desc=f'{rt} checks {name}',
                    progress=progress, chunksize=16)
        res['plausibility'][name] = plausibility.summarize(rows)
    stage('distribution, speed, plausibility')

    rule_rows = {name: pmap(design_rules.measure, scenes, workers, desc=f'{rt} rules {name}',
                            progress=progress, chunksize=16)
                 for name, scenes in (('corpus', heldout), ('synthesized', synth))}
    res['design_rules'] = design_rules.summarize(rule_rows['corpus'], rule_rows['synthesized'])
    stage('design rules')

    side = (cfg.classifier_train + cfg.classifier_test) // 2
    ccfg = classifier.ClassifierConfig(widths=tuple(cfg.classifier_widths),
                                       epochs=cfg.classifier_epochs,
                                       batch_size=cfg.classifier_batch)
    fakes = {'synthesized': synth}
    for p in cfg.perturbations:
        fakes[perturbation_key(p)] = perturbed[p] if p > 0 else heldout
    jobs = [(name, corpus[:side], fake[:side], cfg.classifier_train, cfg.classifier_test,
             bundle['resolution'], ccfg, _seed(cfg.seed, k_rt, 11, k))
            for k, (name, fake) in enumerate(fakes.items())]
    res['classifier'] = dict(pmap(classifier.run_job, jobs, workers,
                                  desc=f'{rt} classifiers', progress=progress))
    res['classifier_config'] = asdict(ccfg)
    stage('classifiers')

    refs = similarity.References.from_scenes(corpus)
    sims = {}
    for name, scenes in (('synthesized', synth), ('heldout', heldout)):
        best, _ = similarity.max_similarity(scenes[:cfg.similarity_queries], refs,
                                            cfg.similarity_sigma, workers, progress,
                                            desc=f'{rt} similarity {name}')
        sims[name] = best
    res['similarity'] = {'references': refs.size, 'sigma': cfg.similarity_sigma,
                         **{k: _summary(v) for k, v in sims.items()}}
    stage('similarity')

    comp = bundle.get('components')
    res['components'] = components.component_rows(rt, comp) if comp else None
    res['figures'] = {
        'categories': Path(figures.category_bars(
            res['distribution']['frequencies'], out / f'categories_{rt}.png',
            f'{rt}: objects per room, {len(synth)} synthesized vs {len(corpus)} corpus '
            f'rooms')).name,
        'similarity': Path(figures.similarity_histogram(
            sims['synthesized'], sims['heldout'], out / f'similarity_{rt}.png',
            f'{rt}: nearest of {refs.size} training rooms (sigma = {cfg.similarity_sigma:g})',
            cfg.histogram_bins)).name,
        'gallery': Path(figures.gallery(synth[:cfg.gallery_rooms],
                                        heldout[:cfg.gallery_rooms],
                                        out / f'gallery_{rt}.png', rt)).name,
    }
    for name, scenes in (('synthesized', synth), ('corpus', heldout)):
        drawn = figures.rule_offenders(scenes, rule_rows[name], out / f'rules_{name}_{rt}.png',
                                       f'{rt} {name}')
        if drawn:
            res['figures'][f'rules_{name}'] = Path(drawn).name
    stage('components and figures')
    return res


def run_evaluation(room_types: Sequence[str], cfg: EvalConfig, out: str | Path,
                   workers: int = 1, weights_dir=None, progress: bool = True,
                   echo: EvalEcho = print, command: str | None = None,
                   markdown_copy: str | Path | None = None) -> dict:
    """Evaluate ``room_types`` and write ``out/index.md``, ``out/results.json`` and the
    figures (and the Markdown also to ``markdown_copy``, linking to the figures in ``out``).
    Raises ``EvaluationError`` for bad input before any long computation."""
    rts = [resolve_room_type(rt) for rt in room_types]
    try:
        cfg.validate()
    except ValueError as e:
        raise EvaluationError(str(e)) from None
    workers = max(1, int(workers))
    out = prepare_out_dir(out)
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    try:
        bundles = _load_bundles(rts, weights_dir)
        results = {'command': command, 'config': asdict(cfg),
                   'hardware': speed.hardware(workers),
                   'weights_dir': str(weights_dir) if weights_dir else 'shipped',
                   'room_types': {}, 'seconds': 0.0}
        t0 = time.perf_counter()
        for rt in rts:
            echo(f'{rt}: evaluating ({cfg.name} sizes, seed {cfg.seed}, {workers} workers)')
            results['room_types'][rt] = evaluate_room_type(
                rt, cfg, out, bundles[rt], workers, weights_dir, progress, echo)
            results['seconds'] = time.perf_counter() - t0
            report.write(results, out, Path(markdown_copy) if markdown_copy else None)
    finally:
        torch.set_num_threads(threads)
    return results


def finite_numbers(obj) -> list[str]:
    """Paths of every number in ``obj`` that is not finite (for the smoke test)."""
    bad = []

    def walk(x, path):
        if isinstance(x, dict):
            for k, v in x.items():
                walk(v, f'{path}.{k}')
        elif isinstance(x, (list, tuple)):
            for k, v in enumerate(x):
                walk(v, f'{path}[{k}]')
        elif isinstance(x, float) and not math.isfinite(x):
            bad.append(path)
    walk(obj, '')
    return bad


__all__ = ['EvalConfig', 'EvaluationError', 'finite_numbers', 'prepare_out_dir',
           'run_evaluation']
