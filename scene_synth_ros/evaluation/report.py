"""The report: ``index.md`` (tables and figures, summary first), ``results.json`` (every
number), and the short table printed at the end of ``scene-synth evaluate``."""
from __future__ import annotations

import json
import math
import os
from pathlib import Path

from ..corpus import HELDOUT_SEED
from ..synth import MODULES
from . import paper
from .data import CORPUS_SEED, SEED_STRIDE
from .perturb import perturbation_key


def _pct(x) -> str:
    return '–' if x is None or not math.isfinite(x) else f'{100 * x:.1f} %'


def _num(x, fmt: str = '.4f') -> str:
    return '–' if x is None or not math.isfinite(x) else format(x, fmt)


def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    return (['| ' + ' | '.join(header) + ' |', '|' + '---|' * len(header)]
            + ['| ' + ' | '.join(r) + ' |' for r in rows])


def _classifier_keys(cfg: dict) -> list[tuple[str, str]]:
    keys = [('synthesized', 'synthesized (ours)')]
    for p in cfg['perturbations']:
        label = 'held-out corpus (control)' if p == 0 else f'perturbed {100 * p:g} %'
        keys.append((perturbation_key(p), label))
    return keys


def _workers(hw: dict) -> str:
    n = hw['workers']
    return f'{n} worker process{"es" if n != 1 else ""} of one torch thread each'


def _acc(c: dict | None) -> str:
    if not c:
        return '–'
    return f'{100 * c["accuracy"]:.1f} ± {100 * c["stderr"]:.1f} %'


def summary_rows(results: dict) -> list[list[str]]:
    rows = []
    for rt, r in results['room_types'].items():
        d, c, s, sim = r['distribution'], r['classifier'], r['speed'], r['similarity']
        ten = c.get('perturbed_10')
        rows.append([rt, _num(d['kl_model']), _num(d['kl_heldout']), _num(d['kl_uniform']),
                     _acc(c['synthesized']), _acc(ten) if ten else '–',
                     f'{s["median"]:.3f} s', _pct(r['plausibility']['synthesized']['valid']),
                     f'{sim["synthesized"]["median"]:.2f} / {sim["heldout"]["median"]:.2f}'])
    return rows


SUMMARY_HEADER = ['room type', 'KL(synth‖corpus)', 'KL noise floor', 'KL uniform',
                  'classifier accuracy (50 % ideal)', 'perturbed 10 %', 'median time / room',
                  'valid synthesized rooms', 'max similarity, median: synth / held-out']


def markdown(results: dict, figure_dir: str = '') -> str:
    cfg, hw = results['config'], results['hardware']
    rts = results['room_types']
    L: list[str] = ['# Evaluation of synthesized rooms', '']
    cmd = results.get('command') or 'scene-synth evaluate'
    L += [f'`{cmd}`: {cfg["name"]} sizes, seed {cfg["seed"]}, '
          f'{results["seconds"] / 60:.1f} min on {hw["cpu"]} ({hw["cores"]} cores, '
          f'{_workers(hw)}), torch {hw["torch"]}, '
          f'weights: {results["weights_dir"]}.', '',
          f'*Synthesized* rooms are the empty shells of held-out corpus rooms (corpus seed '
          f'{HELDOUT_SEED}, never seen in training) furnished from scratch by the pipeline; '
          f'the *training corpus* is corpus seed {CORPUS_SEED} (the shipped weights were '
          f'trained on its first 3,000 to 5,000 rooms, module by module: see docs/training.md, '
          f'*How the shipped weights were made*); '
          f'*held-out corpus* rooms are the same seed-'
          f'{HELDOUT_SEED} shells as the corpus rules furnished them. Every figure is a '
          f'function of the seed.', '']
    L += ['## Summary', ''] + _table(SUMMARY_HEADER, summary_rows(results)) + ['']
    L += ['The noise floor is the KL of held-out corpus rooms, as many as there are '
          'synthesized rooms: a synthesized KL near it is as close to the corpus as the '
          'corpus is to itself. Paper (SUNCG): KL ' + ', '.join(
              f'{rt} {v}' for rt, v in paper.KL['ours'].items())
          + f'; classifier {paper.CLASSIFIER["ours"]} %; '
          f'{paper.SPEED["ours"][0]} s per room on a {paper.SPEED["ours"][1]}.', '']
    L += _reading(rts)

    # 1. categories
    L += ['## 1. Category distribution (paper, table 1)', '',
          'KL(rooms ‖ training corpus) over the categories of all objects. Lower is better.',
          '']
    rows = []
    for rt, r in rts.items():
        d = r['distribution']
        o = d['objects_per_room']
        rows.append([rt, _num(d['kl_model']), _num(d['kl_heldout']), _num(d['kl_uniform']),
                     _num(paper.KL['ours'].get(rt)), _num(paper.KL['uniform'].get(rt)),
                     f'{o["synthesized"]:.2f}', f'{o["corpus"]:.2f}',
                     f'{d["rooms"]["synthesized"]} / {d["rooms"]["corpus"]} / '
                     f'{d["rooms"]["heldout"]}'])
    L += _table(['room type', 'synthesized', 'held-out corpus (noise floor)', 'uniform',
                 'paper: ours', 'paper: uniform', 'objects / room, synthesized',
                 'corpus', 'rooms (synth / corpus / held-out)'], rows) + ['']
    for rt, r in rts.items():
        fig = _fig(figure_dir, r['figures']['categories'])
        L += [f'![{rt} category frequencies]({fig})', '']

    # 2. classifier
    keys = _classifier_keys(cfg)
    any_rt = next(iter(rts.values()))
    cc = any_rt['classifier_config']
    first = any_rt['classifier']['synthesized']
    L += ['## 2. Real vs synthetic classifier (paper, table 2)', '',
          f'A ResNet-34-style classifier (basic blocks {"-".join(map(str, cc["blocks"]))}, '
          f'widths {"-".join(map(str, cc["widths"]))}, global pooling, one logit) reads the '
          f'pipeline\'s multi-channel top-down image (room frame, at the shipped '
          f'weights\' resolution of {any_rt.get("resolution", 64)} px) and is trained for '
          f'{cc["epochs"]} epoch(s) (batch {cc["batch_size"]}, Adam, lr {cc["lr"]:g} with '
          f'cosine decay, weight decay {cc["weight_decay"]:g}, random 90° turns) on '
          f'{first["train"]} rooms, half training corpus and half "fake", then tested on '
          f'{first["test"]} held-out rooms, balanced. 50 % is ideal (it cannot tell). The '
          f'perturbed baselines are held-out corpus rooms with every object moved by Gaussian '
          f'noise of the given fraction of its bounding box; the control is held-out corpus '
          f'rooms unmoved. Cells: test accuracy ± binomial standard error (training '
          f'accuracy of the last epoch).', '']
    rows = []
    for rt, r in rts.items():
        rows.append([rt] + [f'{_acc(r["classifier"].get(k))} '
                            f'({_pct(r["classifier"][k]["train_accuracy"])})'
                            if k in r['classifier'] else '–' for k, _ in keys])
    pc = paper.CLASSIFIER
    paper_row = {'synthesized': pc['ours'], 'perturbed_1': pc['perturbed_1'],
                 'perturbed_5': pc['perturbed_5'], 'perturbed_10': pc['perturbed_10']}
    rows.append(['paper (SUNCG, all types)'] + [f'{paper_row[k]:.2f} %' if k in paper_row
                                               else '–' for k, _ in keys])
    L += _table(['room type'] + [label for _, label in keys], rows) + ['']

    # 3. speed
    L += ['## 3. Speed (paper, table 3)', '',
          f'Seconds per complete room, furnished from empty, measured on every synthesized '
          f'room: {hw["cpu"]}, {hw["machine"]}, {hw["cores"]} cores, {_workers(hw)}, one '
          f'room at a time per process (each warmed up first). Per module: mean milliseconds '
          f'per room.', '']
    rows = []
    for rt, r in rts.items():
        s = r['speed']
        rows.append([rt, str(s['rooms']), f'{s["mean"]:.3f}', f'{s["median"]:.3f}',
                     f'{s["p90"]:.3f}', f'{s["objects_per_room"]:.2f}']
                    + [f'{1000 * s["modules"][m]:.0f}' for m in MODULES])
    L += _table(['room type', 'rooms', 'mean s', 'median s', 'p90 s', 'objects / room']
                + [f'{m} ms' for m in MODULES], rows) + ['']
    L += _table(['method (paper)', 'seconds per room', 'hardware'],
                [['ours (paper)', f'{paper.SPEED["ours"][0]}', paper.SPEED['ours'][1]],
                 ['Deep Priors', f'~{paper.SPEED["deep_priors"][0]:g}',
                  paper.SPEED['deep_priors'][1]],
                 ['GRAINS', f'{paper.SPEED["grains"][0]}', paper.SPEED['grains'][1]]]) + ['']

    # 4. plausibility
    L += ['## 4. Physical plausibility', '',
          'Mean per room of: the fraction of first-tier object pairs that collide, of objects '
          'off the floor, of doors whose clear zone is entered, of second-tier objects less '
          'than 70 % on their parent; rooms where a 0.4 m robot can drive between all doors; '
          'rooms passing every check (`geometry.check_scene`, the definitions the corpus and '
          'insertion use). Held-out corpus rooms and their perturbed copies for reference.',
          '']
    rows = []
    for rt, r in rts.items():
        for name, p in r['plausibility'].items():
            label = {'synthesized': 'synthesized', 'corpus': 'held-out corpus'}.get(
                name, name.replace('perturbed_', 'perturbed ') + ' %')
            rows.append([rt, label, str(p['rooms'])] + [_pct(p[m]) for m in (
                'colliding_pairs', 'off_floor', 'blocked_doors', 'under_supported',
                'doors_connected', 'valid')])
    L += _table(['room type', 'rooms from', 'n', 'colliding pairs', 'off the floor',
                 'blocked doors', 'under-supported', 'doors connected', 'valid rooms'],
                rows) + ['']
    L += ['Distance of first-tier objects to the nearest wall, mean per room: the training '
          'rooms put wall furniture 0–2 cm from the wall and almost nothing 2–15 cm from it, '
          'a band where a location grid of about 9 cm a pixel drops furniture unless '
          'synthesis pushes it back (`synth.against_walls`).', '']
    rows = [[rt, label, _pct(p.get('against_wall')), _pct(p.get('near_wall'))]
            for rt, r in rts.items()
            for name, p in r['plausibility'].items() if name in ('synthesized', 'corpus')
            for label in [{'synthesized': 'synthesized', 'corpus': 'held-out corpus'}[name]]]
    L += _table(['room type', 'rooms from', '0–2 cm from a wall', '2–15 cm from a wall'],
                rows) + ['']

    # 5. similarity
    L += ['## 5. Generalisation (paper, appendix)', '',
          'For each room, its largest similarity to any of the training-corpus rooms '
          '(1 = an exact copy). Similarity: objects are matched one to one within a '
          'category by optimal assignment, maximising the sum of exp(-d²/σ²) over matches, '
          'where d is the distance between positions normalised to the room\'s bounding box '
          'in the axes of its longest wall (long side first); the sum is divided by the '
          'larger object count, and the best of the room\'s four mirror images is kept '
          f'(`scene_synth_ros/evaluation/similarity.py`). σ = {cfg["similarity_sigma"]:g}.',
          '']
    rows = []
    for rt, r in rts.items():
        sm = r['similarity']
        a, b = sm['synthesized'], sm['heldout']
        rows.append([rt, str(sm['references']), f'{a["n"]} / {b["n"]}',
                     f'{a["median"]:.3f} / {b["median"]:.3f}',
                     f'{a["p10"]:.3f} / {b["p10"]:.3f}', f'{a["p90"]:.3f} / {b["p90"]:.3f}',
                     f'{_pct(a["above_0.9"])} / {_pct(b["above_0.9"])}'])
    L += _table(['room type', 'training rooms', 'rooms (synth / held-out)',
                 'median (synth / held-out)', '10th percentile', '90th percentile',
                 'above 0.9'], rows) + ['']
    for rt, r in rts.items():
        fig = _fig(figure_dir, r['figures']['similarity'])
        L += [f'![{rt} maximal similarity]({fig})', '']

    # 6. components
    L += ['## 6. Component metrics (paper, appendix table)', '',
          'Held-out metrics of each module of the shipped weights, stored in their bundles '
          'at export (512 held-out examples), beside a randomly initialised network of the '
          'same shape. Improvement: absolute for accuracies, relative for losses (as the '
          'paper). The paper\'s losses are on other scales, so only its improvement is '
          'shown.', '']
    rows = []
    for rt, r in rts.items():
        for c in r['components'] or []:
            fmt = (lambda v: f'{v:+.1f} %') if c['relative'] else (lambda v: f'{v:+.3f}')
            pi = c['paper_improvement']
            rows.append([rt, c['metric'], f'{c["trained"]:.3f}', f'{c["random"]:.3f}',
                         fmt(c['improvement']), fmt(pi) if pi is not None else '–'])
    L += _table(['room type', 'metric', 'trained', 'random', 'improvement',
                 'paper improvement'], rows) + ['']

    L += _design_rules(rts, figure_dir)

    # gallery
    L += ['## Gallery', '', 'Top row: held-out shells furnished by the model; bottom row: the '
          'same shells furnished by the corpus rules.', '']
    for rt, r in rts.items():
        L += [f'![{rt} gallery]({_fig(figure_dir, r["figures"]["gallery"])})', '']

    # sizes
    L += ['## Sizes, seeds and time', '',
          f'Synthesized room i uses synthesis seed {SEED_STRIDE:,} x seed + i. Sizes: '
          + ', '.join(f'{k} {_size(v)}' for k, v in cfg.items() if k not in ('name', 'seed'))
          + '.',
          '']
    rows = [[rt] + [f'{v:.1f}' for v in r['stage_seconds'].values()]
            for rt, r in rts.items()]
    stages = list(any_rt['stage_seconds'])
    L += _table(['room type'] + [f'{s} (s)' for s in stages], rows) + ['']
    return '\n'.join(L)


def _size(v) -> str:
    """A configuration value, the same whether it came from the run or from results.json
    (where tuples have become lists)."""
    return f'({", ".join(map(str, v))})' if isinstance(v, (list, tuple)) else str(v)


def _reading(rts: dict) -> list[str]:
    """One plain sentence per room type on what the summary's numbers say, so a reader
    need not work out the comparisons."""
    L = ['### Reading the results', '']
    for rt, r in rts.items():
        d, c, sim = r['distribution'], r['classifier'], r['similarity']
        floor = max(d['kl_heldout'], 1e-9)
        syn = c['synthesized']['accuracy']
        levels = [(k, v['accuracy']) for k, v in c.items()
                  if k.startswith('perturbed_') and k != 'perturbed_0']
        o = d['objects_per_room']
        med_s, med_h = sim['synthesized']['median'], sim['heldout']['median']
        text = (f'- **{rt}**: category KL {d["kl_model"]:.4f}, {d["kl_model"] / floor:.1f}x '
                f'the corpus\' own noise floor and '
                f'{d["kl_uniform"] / max(d["kl_model"], 1e-9):.0f}x '
                f'below a uniform guess; {o["synthesized"]:.2f} objects per room against '
                f'{o["corpus"]:.2f} ({100 * (o["synthesized"] / o["corpus"] - 1):+.1f} %). '
                f'The classifier tells synthesized from corpus rooms {_pct(syn)} of the time')
        if levels:
            # by accuracy, the larger perturbation first among equal accuracies
            ranked = sorted(levels, key=lambda kv: (kv[1], float(kv[0].split('_')[1])))
            def name(kv):
                return f'{kv[0].split("_")[1]} % of their size ({_pct(kv[1])})'
            se = c['synthesized']['stderr']
            moved = 'corpus rooms whose objects were moved by'
            if syn > ranked[-1][1] + 2 * se:
                text += f', more often than {moved} {name(ranked[-1])}'
            elif syn < ranked[0][1] - 2 * se:
                text += f', less often than {moved} {name(ranked[0])}'
            else:
                lo = max((kv for kv in ranked if kv[1] <= syn), key=lambda kv: kv[1],
                         default=ranked[0])
                hi = min((kv for kv in ranked if kv[1] >= syn), key=lambda kv: kv[1],
                         default=ranked[-1])
                text += (f', like {moved} {name(lo)}' if lo == hi
                         else f', between {moved} {name(lo)} and by {name(hi)}')
        text += (f'. Nearest training room: median similarity {med_s:.2f} for synthesized '
                 f'rooms, {med_h:.2f} for held-out corpus rooms (')
        if med_s > med_h + 0.02:
            text += 'synthesized rooms sit closer to training rooms than unseen corpus rooms do).'
        elif med_s < med_h - 0.05:
            text += ('no copying, but further from every training room than unseen corpus '
                     'rooms are: arrangements the corpus rules do not make).')
        else:
            text += 'as close to the training rooms as unseen corpus rooms are: no copying).'
        L.append(text)
    return L + ['']


def _rate(kept_cases) -> str:
    kept, cases = kept_cases
    return f'{_pct(kept / cases)} ({cases})' if cases else '–'


def _design_rules(rts: dict, figure_dir: str) -> list[str]:
    """Section 7: every design rule, corpus beside synthesized, per room type."""
    with_rules = {rt: r['design_rules'] for rt, r in rts.items() if r.get('design_rules')}
    if not with_rules:          # results written before the rules existed
        return []
    L = ['## 7. Design rules', '',
         'What a designer checks, asked of every case a rule applies to (`scene_synth_ros/'
         'rules/`): the share of cases that keep the rule, number of cases '
         'in brackets, in held-out corpus rooms and in the same shells synthesized; the '
         'difference in percentage points, and the p-value of a two-sided test that the '
         'two shares are equal. The rules:', '']
    first = next(iter(with_rules.values()))
    L += [f'- `{name}` ({d["family"]}): {d["question"]}' for name, d in first.items()] + ['']
    rows = []
    for rt, table in with_rules.items():
        for name, d in table.items():
            (ka, na), (kb, nb) = d['corpus'], d['synthesized']
            if not (na or nb):
                continue
            diff = (f'{100 * (kb / nb - ka / na):+.1f}' if na and nb else '–')
            rows.append([rt, name, _rate(d['corpus']), _rate(d['synthesized']), diff,
                         f'{d["p"]:.3f}'])
    L += _table(['room type', 'rule', 'held-out corpus', 'synthesized',
                 'difference (points)', 'p'], rows) + ['']
    L += ['The worst offender of every rule broken somewhere: the room that breaks it in the '
          'most cases (title: rule, cases broken of cases, room).', '']
    for rt, r in rts.items():
        for name in ('synthesized', 'corpus'):
            fig = r['figures'].get(f'rules_{name}')
            if fig:
                L += [f'![{rt} {name}: worst offenders]({_fig(figure_dir, fig)})', '']
            else:
                L += [f'{rt} {name}: no room breaks any rule.', '']
    return L


def _fig(figure_dir: str, name: str) -> str:
    return f'{figure_dir}/{name}' if figure_dir else name


def write(results: dict, out: Path, copy_to: Path | None = None) -> None:
    """``index.md`` and ``results.json`` in ``out``; with ``copy_to``, the same Markdown
    there too, its figure links pointing into ``out``."""
    out = Path(out)
    (out / 'results.json').write_text(json.dumps(results, indent=1, default=str) + '\n')
    (out / 'index.md').write_text(markdown(results) + '\n')
    if copy_to is not None:
        rel = os.path.relpath(out.resolve(), Path(copy_to).resolve().parent)
        Path(copy_to).write_text(markdown(results, Path(rel).as_posix()) + '\n')


def terminal_summary(results: dict) -> str:
    """The short table printed at the end of a run."""
    head = ['room type', 'KL synth', 'KL floor', 'KL unif', 'classifier', 'perturb 10%',
            's/room', 'valid', 'max-sim syn/held']
    rows = summary_rows(results)
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(head)]
    line = lambda cells: '  '.join(c.ljust(w) for c, w in zip(cells, widths, strict=True))  # noqa: E731
    return '\n'.join([line(head)] + [line(r) for r in rows])
