"""Training of the four modules of one room type, resumable, with a fixed seed.

Every batch and every draw of dropout / CVAE noise is a pure function of (seed, module,
step), so a run stopped and resumed from its last checkpoint continues exactly as if it had
never stopped. Progress goes to a tqdm bar and, as JSON lines, to ``<run>/<room>/log.jsonl``.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
import json
import math
from pathlib import Path
import time
from typing import Callable

import numpy as np
import torch
from torch import nn
from tqdm import tqdm

from ..allowance import STRICT
from ..catalog import variants
from ..categories import CORPUS, PAPER, Vocabulary
from ..corpus.generate import generate_corpus
from ..datasets.training import describe_dir, room_type_specs, split_rooms
from ..files import writing_together
from ..scene import Scene
from . import COMPONENT_ROWS, NETWORKS
from .bundle import Bundle, build_networks, bundle_path, load_bundle, save_bundle
from .config import (
    OWN_SETTINGS,
    ModelConfig,
    ModuleSchedule,
    PipelineConfig,
    resolve_device,
    settings_differing,
)
from .dimensions import Discriminator, box_sdf, dimensions_elbo
from .examples import ExampleSource
from .location import location_loss, offset_loss
from .orientation import orientation_elbo, orientation_target

VAL_BATCH = 64


@dataclass
class RoomCorpus:
    train: list[Scene]
    val: list[Scene]


def data_vocabulary(data_dir: Path | None) -> Vocabulary:
    """What the rooms of ``data_dir``, an imported data set, know: the paper's table with the
    data set's category sets; without one, the corpus's (``CORPUS``)."""
    if data_dir is None:
        return CORPUS
    return PAPER.with_specs(room_type_specs(describe_dir(data_dir)).values())


def load_corpus(room_type: str, cfg: PipelineConfig, workers: int | None = None,
                data_dir: Path | None = None) -> RoomCorpus:
    """Training rooms 0..N-1 and held-out rooms N..N+V-1 of the corpus seed; with
    ``data_dir``, an imported data set's rooms split by ``datasets.training.split`` (the
    corpus seed shuffles; at most N training and V held-out rooms)."""
    t = cfg.train
    if data_dir is not None:
        data = split_rooms(data_dir, data_vocabulary(data_dir).spec(room_type), t.corpus_seed,
                           t.train_rooms, t.val_rooms)
        return RoomCorpus(data.train, data.held_out)
    rooms = list(generate_corpus(room_type, t.train_rooms + t.val_rooms, seed=t.corpus_seed,
                                 workers=workers, real_sizes=t.real_sizes))
    return RoomCorpus(rooms[:t.train_rooms], rooms[t.train_rooms:])


def load_corpora(room_type: str, cfg: PipelineConfig, sizes: set[int],
                 workers: int | None = None, data_dir: Path | None = None,
                 cache: dict | None = None, echo: Callable[[str], None] = print
                 ) -> dict[int, RoomCorpus]:
    """``load_corpus`` for each number of training rooms in ``sizes`` (modules of one room
    type may train on different numbers: ``PipelineConfig.module_train``), all cut from the
    rooms of the largest: a corpus room is a function of its seed and index, and a data
    set's split does not depend on how many of its training rooms are taken. ``cache``, a
    dict kept by the caller, keeps the rooms made for the next call (in this process or,
    handed over, in another). ``echo`` says what is made or read."""
    t = cfg.train
    key = (room_type, t.corpus_seed, t.real_sizes, t.val_rooms, str(data_dir))
    most = max(sizes)
    have = (cache or {}).get(key)
    if have is None or len(have.train) < most:
        if data_dir is None:
            echo(f'{room_type}: making {most} training and {t.val_rooms} held-out corpus '
                 f'rooms (corpus seed {t.corpus_seed})')
        have = load_corpus(room_type, replace(cfg, train=replace(t, train_rooms=most)),
                           workers, data_dir)
        if data_dir is not None:
            echo(f'{room_type}: {len(have.train)} training and {len(have.val)} held-out '
                 f'rooms of {data_dir}')
        if cache is not None:
            cache[key] = have
    if data_dir is not None:
        return {n: RoomCorpus(have.train[:n], have.val) for n in sizes}
    rooms = have.train + have.val
    return {n: RoomCorpus(rooms[:n], rooms[n:n + t.val_rooms]) for n in sizes}


def model_cooccurrence(room_type: str, scenes: list[Scene], vocabulary: Vocabulary = PAPER
                       ) -> tuple[list[str], torch.Tensor]:
    """How often each pair of catalog models appears in the same training room."""
    models = [v.model_id for c in vocabulary.spec(room_type).names
              for v in variants(c, room_type, vocabulary)]
    index = {m: k for k, m in enumerate(models)}
    counts = torch.zeros(len(models), len(models))
    for s in scenes:
        ids = sorted({index[o.model_id] for o in s.objects if o.model_id in index})
        if ids:
            t = torch.tensor(ids)
            counts[t[:, None], t[None, :]] += 1
    return models, counts


def _step_seed(seed: int, module: str, step: int) -> list[int]:
    return [seed, NETWORKS.index(module), step]


class _Batches(torch.utils.data.Dataset):
    """The batches of one module's schedule, step by step, for a DataLoader: each is the
    pure function of (seed, module, step) that training would have made itself."""

    def __init__(self, source: ExampleSource, module: str, seed: int, size: int):
        self.source, self.module, self.seed, self.size = source, module, seed, size

    def __getitem__(self, step: int) -> dict:
        return self.source.batch(self.module, _step_seed(self.seed, self.module, step),
                                 self.size)


def _worker_threads(_worker: int) -> None:
    torch.set_num_threads(1)      # rendering is numpy; one core per loader process


def batches(source: ExampleSource, module: str, seed: int, size: int, start: int, stop: int,
            workers: int = 0, pin: bool = False):
    """The training batches of steps ``start``..``stop - 1`` in order, made by ``workers``
    processes ahead of the step (none: made here, one at a time)."""
    data = _Batches(source, module, seed, size)
    if workers <= 0:
        return (data[step] for step in range(start, stop))
    return iter(torch.utils.data.DataLoader(
        data, batch_size=None, sampler=range(start, stop), num_workers=workers,
        pin_memory=pin, prefetch_factor=4, worker_init_fn=_worker_threads,
        persistent_workers=False))


# Training examples whose targets start the learned spread of the dimensions' likelihood.
SPREAD_BATCHES = 16


def _initial_spread(net: nn.Module, data) -> None:
    """Start each category's learned sigma at the spread of its targets in the first
    training batches (the likelihood's maximum for a decoder that answers the category's
    mean), where at least 8 examples show it; a few hundred steps at the schedule's rate move
    a log sigma by only tenths, and the bedrooms' learned sigmas run from 4 to 26 %."""
    targets = [data[step] for step in range(SPREAD_BATCHES)]
    y = torch.cat([b['target'] for b in targets]).double()
    cats = torch.cat([b['category'] for b in targets])
    with torch.no_grad():
        for c in cats.unique().tolist():
            mine = y[cats == c]
            if len(mine) >= 8:
                std = mine.std(dim=0).clamp_min(0.01)
                net.log_sigma[c] = torch.log(std).to(net.log_sigma)


def _lr(sched: ModuleSchedule, step: int) -> float:
    # Cosine decay to a tenth of the base rate: short CPU budgets still end on a small step.
    return sched.lr * (0.1 + 0.45 * (1 + math.cos(math.pi * step / max(sched.steps, 1))))


# ---- losses and metrics ---------------------------------------------------------------------
def batch_loss(module: str, net: nn.Module, batch: dict, cfg: PipelineConfig, device,
               disc: nn.Module | None = None, extent: float = 0.0
               ) -> tuple[torch.Tensor, dict[str, float]]:
    """The loss a module is trained on, and the metrics of that batch (``extent``: metres
    an image covers, for the discriminator's SDF)."""
    b = {k: v.to(device) for k, v in batch.items()}
    t = cfg.train
    if module == 'category':
        logits = net(b['image'], b['counts'])
        loss = nn.functional.cross_entropy(logits, b['target'])
        # a room type of fewer than five categories (with STOP) has every one in its top 5
        top5 = logits.topk(min(5, logits.shape[1]), dim=1).indices
        return loss, {'loss': loss.item(),
                      'top1': (top5[:, 0] == b['target']).float().mean().item(),
                      'top5': (top5 == b['target'][:, None]).any(1).float().mean().item()}
    if module == 'location':
        logits, offsets = net.predict(b['image'])
        loss = location_loss(logits, b['target'], t.empty_weight)
        metrics = {'loss': loss.item()}        # the cross-entropy of the component table
        if offsets is not None:
            err = offset_loss(offsets, b['offset'], b['target'] > 0)
            metrics['offset_error'] = err.item()
            loss = loss + err
        return loss, metrics
    if module == 'orientation':
        target = orientation_target(b['theta'])
        out, mu, logvar = net(b['image'], b['category'], target)
        loss, nelbo = orientation_elbo(out, target, mu, logvar, t.kl_weight)
        return loss, {'loss': loss.item(), 'neg_elbo': nelbo.mean().item()}
    if module == 'snap':
        logits = net(b['image'], b['category'])
        loss = nn.functional.binary_cross_entropy_with_logits(logits, b['snapped'])
        acc = ((logits > 0).float() == b['snapped']).float().mean().item()
        return loss, {'loss': loss.item(), 'accuracy': acc}
    if module == 'dimensions':
        out, mu, logvar = net(b['image'], b['category'], b['target'])
        log_sigma = None if net.log_sigma is None else net.log_sigma[b['category']]
        loss, nelbo = dimensions_elbo(out, b['target'], mu, logvar, t.kl_weight, log_sigma)
        metrics = {'loss': loss.item(), 'neg_elbo': nelbo.mean().item()}
        if disc is not None and t.adversarial_weight > 0:
            fake = disc(b['image'], box_sdf(out, b['image'].shape[-1], extent), b['category'])
            adv = nn.functional.binary_cross_entropy_with_logits(fake, torch.ones_like(fake))
            loss = loss + t.adversarial_weight * adv
            metrics['adversarial'] = adv.item()
        return loss, metrics
    raise ValueError(f'unknown module {module!r}')


def evaluate(module: str, net: nn.Module, source: ExampleSource, cfg: PipelineConfig, device,
             seed: int, examples: int) -> dict[str, float]:
    """Held-out metrics of one module: the mean over ``examples`` fixed examples."""
    net.eval()
    totals: dict[str, float] = {}
    n = 0
    with torch.no_grad():
        for k in range(0, examples, VAL_BATCH):
            size = min(VAL_BATCH, examples - k)
            # held-out examples of rooms of any size, as they always were: metrics along one
            # run compare with another's whatever its size buckets
            batch = source.batch(module, [seed, 10_000 + NETWORKS.index(module), k], size,
                                 by_size=False)
            torch.manual_seed(seed + k)
            _, m = batch_loss(module, net, batch, cfg, device)
            for key, v in m.items():
                totals[key] = totals.get(key, 0.0) + v * size
            n += size
    net.train()
    return {k: v / n for k, v in totals.items()}


# ---- one module ------------------------------------------------------------------------------
def _resume(ckpt: Path, device, net: nn.Module, opt, disc: nn.Module | None, disc_opt) -> int:
    """The step a module's training goes on from: that of its checkpoint ``ckpt``, whose
    states are loaded into the networks and optimisers, or 0 without one."""
    if not ckpt.is_file():
        return 0
    state = torch.load(ckpt, map_location=device, weights_only=True)
    net.load_state_dict(state['net'])
    opt.load_state_dict(state['opt'])
    if disc is not None:
        disc.load_state_dict(state['disc'])
        disc_opt.load_state_dict(state['disc_opt'])
    return int(state['step'])


def train_module(module: str, net: nn.Module, source: ExampleSource, val: ExampleSource,
                 cfg: PipelineConfig, device, run_dir: Path, log: Callable[[dict], None],
                 progress: bool = True, until: int | None = None) -> dict[str, float] | None:
    """Train ``module`` from its last checkpoint in ``run_dir`` (if any) to the end of its
    schedule and return its held-out metrics; with ``until``, stop after that step (saving a
    checkpoint) and return None, as an interrupted run would."""
    t = cfg.train
    sched: ModuleSchedule = getattr(t, module)
    net.to(device).train()
    opt = torch.optim.Adam(net.parameters(), lr=sched.lr, weight_decay=sched.weight_decay)
    disc = disc_opt = None
    if module == 'dimensions' and t.adversarial_weight > 0:
        # Its own seed after the networks' (bundle.build_networks): unseeded, its initial
        # weights were those of whatever had drawn before in the process, so the dimensions
        # module trained alone (train --modules, --jobs) and after the others came out apart.
        torch.manual_seed(t.seed + len(NETWORKS))
        disc = Discriminator(source.renderer.num_channels(source.room_type),
                             source.num_categories, cfg.model).to(device)
        disc_opt = torch.optim.Adam(disc.parameters(), lr=sched.lr, betas=(0.5, 0.999))
    ckpt = run_dir / f'{module}.ckpt'
    start = _resume(ckpt, device, net, opt, disc, disc_opt)
    if start == 0 and getattr(net, 'log_sigma', None) is not None:
        _initial_spread(net, _Batches(source, module, t.seed, sched.batch_size))

    def save(step: int) -> None:
        state = {'net': net.state_dict(), 'opt': opt.state_dict(), 'step': step}
        if disc is not None:
            state.update(disc=disc.state_dict(), disc_opt=disc_opt.state_dict())
        with writing_together(run_dir, [ckpt.name]) as tmp:
            torch.save(state, tmp / ckpt.name)

    bar = tqdm(range(start, sched.steps), initial=start, total=sched.steps,
               desc=f'{source.room_type}/{module}', unit='step', disable=not progress,
               mininterval=5.0)
    running: dict[str, float] = {}
    last_val: dict[str, float] | None = None
    t0 = time.perf_counter()
    made = batches(source, module, t.seed, sched.batch_size, start, sched.steps,
                   t.loader_workers, pin=torch.device(device).type == 'cuda')
    for step, batch in zip(bar, made, strict=True):
        for g in opt.param_groups:
            g['lr'] = _lr(sched, step)
        torch.manual_seed(int(np.random.SeedSequence(_step_seed(t.seed, module, step))
                              .generate_state(1)[0]))
        if disc is not None:
            _discriminator_step(disc, disc_opt, net, batch, device, source.extent)
        loss, metrics = batch_loss(module, net, batch, cfg, device, disc, source.extent)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        for k, v in metrics.items():
            running[k] = 0.95 * running.get(k, v) + 0.05 * v
        done = step + 1
        if done % 25 == 0:
            bar.set_postfix({k: f'{v:.3f}' for k, v in running.items()}, refresh=False)
            log({'module': module, 'step': done, 'lr': _lr(sched, step),
                 'seconds': round(time.perf_counter() - t0, 1),
                 **{f'train_{k}': round(v, 5) for k, v in running.items()}})
        if done % t.val_every == 0 or done == sched.steps:
            last_val = evaluate(module, net, val, cfg, device, t.seed, t.val_examples)
            log({'module': module, 'step': done, **{f'val_{k}': round(v, 5)
                                                       for k, v in last_val.items()}})
        if done % t.checkpoint_every == 0 or done == sched.steps or done == until:
            save(done)
        if done == until:
            bar.close()
            return None
    bar.close()
    if last_val is None:      # resumed at the end of the schedule: nothing was validated
        last_val = evaluate(module, net, val, cfg, device, t.seed, t.val_examples)
    net.eval()
    return last_val


def _discriminator_step(disc, disc_opt, net, batch, device, extent: float) -> None:
    image = batch['image'].to(device)
    category = batch['category'].to(device)
    target = batch['target'].to(device)
    with torch.no_grad():
        fake_dims = net.sample(image, category)
    n = image.shape[-1]
    real = disc(image, box_sdf(target, n, extent), category)
    fake = disc(image, box_sdf(fake_dims, n, extent), category)
    loss = nn.functional.binary_cross_entropy_with_logits(real, torch.ones_like(real)) + \
        nn.functional.binary_cross_entropy_with_logits(fake, torch.zeros_like(fake))
    disc_opt.zero_grad(set_to_none=True)
    loss.backward()
    disc_opt.step()


# ---- a room type -------------------------------------------------------------------------------
def component_table(nets: dict[str, nn.Module], val: ExampleSource, cfg: PipelineConfig, device,
                    room_type: str) -> dict[str, dict[str, float]]:
    """The paper's component metrics on held-out rooms, for the given networks and for
    freshly initialised ones of the same shape (seeded)."""
    fresh = build_networks(room_type, cfg.model, seed=cfg.train.seed + 1000,
                           vocabulary=val.vocabulary)
    out: dict[str, dict[str, float]] = {}
    for name in NETWORKS:
        for label, net in (('trained', nets[name]), ('random', fresh[name])):
            net.to(device)
            m = evaluate(name, net, val, cfg, device, cfg.train.seed + 1, cfg.train.val_examples)
            out.setdefault(name, {}).update({f'{label}_{k}': v for k, v in m.items()
                                             if k != 'adversarial'})
    return out


def train_room_type(room_type: str, cfg: PipelineConfig, run_root: Path, weights_dir: Path,
                    progress: bool = True, echo: Callable[[str], None] = print,
                    modules: tuple[str, ...] = NETWORKS,
                    others_from: Path | None = None,
                    data_dir: Path | None = None,
                    corpus_cache: dict | None = None) -> Bundle | None:
    """Train (or resume) the modules of ``room_type`` and export the bundle. With a subset
    of ``modules`` only those are trained and nothing is exported: several processes can
    then train different modules of one room type at once in the same run directory, and a
    final run over all modules (each resuming at its end) exports the bundle. With
    ``others_from``, a directory of bundles made with the same model configuration, the
    modules not trained are taken from its bundle and the result is exported: one module
    retrained, the others kept. With ``data_dir`` (an imported data set, see ``train``) the
    rooms and category sets are the data set's and the bundle carries its room type's.
    Each module trains with its own settings (``PipelineConfig.for_module``); the bundle's
    co-occurrence counts and component table read the rooms of ``cfg.train``.
    ``corpus_cache``: see ``load_corpora``."""
    vocabulary = data_vocabulary(data_dir)
    rt = vocabulary.resolve(room_type)
    device = resolve_device(cfg.device)
    t = cfg.train
    if t.threads:
        torch.set_num_threads(t.threads)
    run_dir = Path(run_root) / rt
    run_dir.mkdir(parents=True, exist_ok=True)
    (run_dir / 'config.json').write_text(cfg.to_json() + '\n')
    log_file = open(run_dir / 'log.jsonl', 'a', encoding='utf-8')

    def log(entry: dict) -> None:
        log_file.write(json.dumps({'room_type': rt, **entry}) + '\n')
        log_file.flush()

    exporting = set(modules) == set(NETWORKS) or others_from is not None
    runs = {name: cfg.for_module(name, rt) for name in NETWORKS if name in modules}
    sizes = {r.train.train_rooms for r in runs.values()} | \
        ({t.train_rooms} if exporting else set())
    corpora = load_corpora(rt, cfg, sizes, workers=t.threads or None, data_dir=data_dir,
                           cache=corpus_cache, echo=echo)
    m = cfg.model
    nets = build_networks(rt, m, seed=t.seed, vocabulary=vocabulary)
    multiple = nets['location'].multiple
    sources: dict[int, tuple[ExampleSource, ExampleSource]] = {
        n: tuple(ExampleSource(rt, rooms, m.resolution, m.location_resolution,
                               target_radius=t.location_target_radius, vocabulary=vocabulary,
                               multiple=multiple, size_buckets=t.size_buckets)
                 for rooms in (c.train, c.val))
        for n, c in corpora.items()}
    if others_from is not None:
        _take_networks(nets, bundle_path(others_from, rt, vocabulary), m,
                       [n for n in NETWORKS if n not in modules])
    final: dict[str, dict[str, float]] = {}
    for name, run in runs.items():
        source, val = sources[run.train.train_rooms]
        final[name] = train_module(name, nets[name], source, val, run, device, run_dir, log,
                                   progress)
        echo(f'{rt}/{name}: ' + ', '.join(f'{k} {v:.4f}' for k, v in final[name].items()))
    if not exporting:
        log_file.close()
        echo(f'{rt}: trained {", ".join(modules)}; run again over all modules to export')
        return None
    corpus = corpora[t.train_rooms]
    val = sources[t.train_rooms][1]
    table = component_table(nets, val, cfg, device, rt)
    models, co = model_cooccurrence(rt, corpus.train, vocabulary)
    bundle = Bundle(rt, cfg, nets, co, models, {'components': table},
                    vocabulary.spec(rt) if vocabulary.defines(rt) else None,
                    describe_dir(data_dir).allowance if data_dir is not None else STRICT)
    for net in nets.values():
        net.to('cpu')
    out = Path(weights_dir) / f'{rt}.pt'
    save_bundle(bundle, out)
    log({'event': 'exported', 'path': str(out), 'components': table})
    log_file.close()
    echo(format_components({rt: table}))
    echo(f'{rt}: weights written to {out}')
    return bundle


def _take_networks(nets: dict[str, nn.Module], path: Path, model: ModelConfig,
                   names: list[str]) -> None:
    """Replace ``names`` in ``nets`` by the trained networks of the bundle at ``path``."""
    base = load_bundle(path)
    trained = [n for n in NETWORKS if n not in names]
    own = {s for n in trained for s in OWN_SETTINGS.get(n, ())}
    differing = sorted(settings_differing(base.config.model, model) - own)
    if differing:
        raise ValueError(f'{path}: its networks were made with another model configuration '
                         f'({base.config.name}: {differing[0]} differs); train all modules '
                         'instead')
    for name in names:
        nets[name].load_state_dict(base.networks[name].state_dict())


def format_components(tables: dict[str, dict[str, dict[str, float]]],
                      markdown: bool = False) -> str:
    """The paper's component table, trained beside random initialisation."""
    if markdown:
        rts = list(tables)
        lines = ['| metric | ' + ' | '.join(f'{rt} trained / random' for rt in rts) + ' |',
                 '|---|' + '---|' * len(rts)]
        for label, module, key in COMPONENT_ROWS:
            cells = [f'{tables[rt][module][f"trained_{key}"]:.3f} / '
                     f'{tables[rt][module][f"random_{key}"]:.3f}' for rt in rts]
            lines.append(f'| {label} | ' + ' | '.join(cells) + ' |')
        return '\n'.join(lines)
    lines = [f'{"room type":10s} {"metric":26s} {"trained":>10s} {"random":>10s}']
    for rt, table in tables.items():
        for label, module, key in COMPONENT_ROWS:
            tr = table[module][f'trained_{key}']
            rn = table[module][f'random_{key}']
            lines.append(f'{rt:10s} {label:26s} {tr:10.4f} {rn:10.4f}')
    return '\n'.join(lines)


def check_room_types(cfg: PipelineConfig, known) -> None:
    """ValueError, one sentence, where ``cfg.room_types`` names a room type not ``known``."""
    for rt in cfg.room_types:
        if rt not in known:
            raise ValueError(f'the configuration {cfg.name[:40]!r} has settings for room type '
                             f'{rt[:40]!r}, which is none of {", ".join(known)}')


def train(types: list[str] | None, cfg: PipelineConfig, run_root: Path, weights_dir: Path,
          progress: bool = True, echo: Callable[[str], None] = print,
          modules: tuple[str, ...] = NETWORKS,
          others_from: Path | None = None,
          data_dir: Path | None = None) -> dict[str, Bundle | None]:
    """Train each of ``types`` (None: the package's room types, or with ``data_dir`` every room type
    of the imported data set there, on the category sets it describes)."""
    unknown = sorted(set(modules) - set(NETWORKS))
    if unknown:
        raise ValueError(f'unknown module {unknown[0]!r}; expected some of {", ".join(NETWORKS)}')
    if data_dir is not None:
        specs = room_type_specs(describe_dir(data_dir))
        if types is None:
            types = list(specs)
        missing = [rt for rt in types if rt not in specs]
        if missing:
            raise ValueError(f'{data_dir} holds no {missing[0]} rooms; its room types are '
                             f'{", ".join(specs)}')
    known = data_vocabulary(data_dir).room_types
    check_room_types(cfg, known)
    out = {}
    for rt in types if types is not None else list(known):
        if rt not in known:
            raise ValueError(f'unknown room type {rt!r}')
        out[rt] = train_room_type(rt, cfg, run_root, weights_dir, progress, echo, modules,
                                  others_from, data_dir)
    return out
