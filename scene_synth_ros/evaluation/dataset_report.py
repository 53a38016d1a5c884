"""The report of a data-set evaluation (``dataset.run_data_evaluation``): ``index.md``,
``results.json`` and the short table printed at the end, in the style of ``report``."""
from __future__ import annotations

import json
import os
from pathlib import Path

from .report import _num, _pct, _rate, _table, _workers

# The validity columns, in the order of the paper-corpus report's plausibility table.
VALIDITY = ('colliding_pairs', 'off_floor', 'blocked_doors', 'under_supported',
            'doors_connected', 'valid')


def _diff(x) -> str:
    return '–' if x is None else f'{100 * x:+.1f} %'


def _per_room(d: dict) -> str:
    o = d['objects_per_room']
    return f'{_num(o["synthesized"], ".2f")} / {_num(o["heldout"], ".2f")}'


def summary_rows(results: dict) -> list[list[str]]:
    rows = []
    for rt, r in results['room_types'].items():
        d, v = r['distribution'], r['validity']
        rows.append([rt, str(r['split']['heldout']), str(r['rooms']['synthesized']),
                     _num(d['kl_synthesized']), _num(d['kl_training']),
                     _num(d['kl_uniform']), _per_room(d),
                     _diff(d['objects_relative_difference']),
                     f'{_pct(v["synthesized"]["valid"])} / {_pct(v["heldout"]["valid"])}'])
    return rows


SUMMARY_HEADER = ['room type', 'held-out rooms', 'synthesized rooms', 'KL(synth‖held-out)',
                  'KL(training‖held-out)', 'KL(uniform‖held-out)',
                  'objects / room: synth / held-out', 'difference',
                  'valid rooms: synth / held-out']


def markdown(results: dict) -> str:
    cfg, hw, rts = results['config'], results['hardware'], results['room_types']
    k = cfg['rooms_per_shell']
    cmd = results.get('command') or 'scene-synth evaluate --data'
    L = ['# Evaluation against held-out rooms of a data set', '',
         f'`{cmd}`: data set {results["data_dir"]} ({results["format"]}), weights '
         f'{results["weights_dir"]}, {k} synthesized room(s) per shell, seed {cfg["seed"]}, '
         f'{results["seconds"] / 60:.1f} min on {hw["cpu"]} ({hw["cores"]} cores, '
         f'{_workers(hw)}), torch {hw["torch"]}.', '',
         '*Held-out* rooms are the data set\'s rooms that training held out: the same seeded '
         'split of the file names (`datasets.training.split_rooms`, the bundle\'s corpus seed) '
         'and the same cap (the bundle\'s `val_rooms`), each reduced, as training reduced it, '
         'to the categories the model can place. *Synthesized* rooms are the empty shells of '
         f'those rooms furnished from scratch, {k} per shell (copy c of shell i: synthesis '
         f'seed {cfg["seed_stride"]:,} x seed + {k} x i + c). *Training* rooms are the rooms '
         'the bundle learned from: their KL from the held-out rooms is how far two samples '
         'of real rooms are apart, the line to read the synthesized KL against.', '']
    if results.get('without_bundle'):
        L += [f'Room types of the data set without a bundle, not evaluated: '
              f'{", ".join(results["without_bundle"])}.', '']
    L += ['## Summary', ''] + _table(SUMMARY_HEADER, summary_rows(results)) + ['']
    L += _reading(rts)
    L += _categories(rts) + _validity(rts, results.get('allowance')) + _rules(rts) \
        + _split(rts)
    return '\n'.join(L)


def _reading(rts: dict) -> list[str]:
    """One plain sentence per room type on what the summary says."""
    L = ['### Reading the results', '']
    for rt, r in rts.items():
        d = r['distribution']
        ks, kt = d['kl_synthesized'], d['kl_training']
        text = f'- **{rt}**: category KL {_num(ks)}'
        if ks is not None and kt:
            text += f', {ks / kt:.1f}x that of the training rooms ({_num(kt)})'
        o = d['objects_per_room']
        diff = _diff(d['objects_relative_difference'])
        text += (f'; {_num(o["synthesized"], ".2f")} objects per room against '
                 f'{_num(o["heldout"], ".2f")} held out ({diff})'
                 f'; {_pct(r["validity"]["synthesized"]["valid"])} of the synthesized rooms '
                 f'and {_pct(r["validity"]["heldout"]["valid"])} of the held-out ones pass '
                 f'every validity check.')
        if not r.get('spec_matches_data', True):
            text += (' The data set\'s description no longer gives the category set the '
                     'weights were trained with: it was edited, or the weights come from '
                     'another data set.')
        L.append(text)
    return L + ['']


def _categories(rts: dict) -> list[str]:
    L = ['## 1. Categories', '', 'Objects per room of every category present on any side, '
         'most frequent in the held-out rooms first.', '']
    for rt, r in rts.items():
        f = r['distribution']['frequencies']
        names = [c for c in f['heldout'] if any(f[g][c] for g in f)]
        names.sort(key=lambda c: (-f['heldout'][c], -f['synthesized'][c], c))
        L += [f'### {rt}', '']
        L += _table(['category', 'synthesized', 'held-out', 'training'],
                    [[c] + [f'{f[g][c]:.2f}' for g in ('synthesized', 'heldout', 'training')]
                     for c in names]) + ['']
    return L


def _validity(rts: dict, allowance: dict | None = None) -> list[str]:
    L = ['## 2. Validity', '',
         'The checks of the paper-corpus evaluation (`evaluation/plausibility.py`, '
         '`geometry.check_scene`): mean per room of the fraction of first-tier pairs that '
         'collide, of objects off the floor, of doors whose clear zone is entered, of '
         'second-tier objects less than 70 % on their parent; rooms where a 0.4 m robot '
         'drives between all doors; rooms passing every check. The held-out rooms are held '
         'to the same checks as the synthesized ones, with what the data set\'s rooms do '
         '(its allowance, derived at import: `dataset.yaml`, `datasets/allowance.py`); the '
         'last column holds them to the strict checks, without it.', '']
    if allowance:
        L += ['Allowance: ' + _allowance_text(allowance), '']
    rows = [[rt, label, str(r['validity'][name]['rooms'])]
            + [_pct(r['validity'][name][m]) for m in VALIDITY]
            + [_pct(r['validity'][name].get('valid_strict', float('nan')))]
            for rt, r in rts.items()
            for name, label in (('synthesized', 'synthesized'), ('heldout', 'held-out'))]
    return L + _table(['room type', 'rooms from', 'n', 'colliding pairs', 'off the floor',
                       'blocked doors', 'under-supported', 'doors connected', 'valid rooms',
                       'valid rooms, strict'], rows) + ['']


def _allowance_text(a: dict) -> str:
    tucks = ', '.join(f'{t["tucked"]} under {t["host"]} up to {t["depth"]:.2f} m'
                      for t in a.get('tucks') or []) or 'no tucks'
    inside = ', '.join(f'{p} (from {v:.0%} of its height)'
                       for p, v in (a.get('inside') or {}).items())
    door = a.get('door_depth')
    return (f'{tucks}; things rest inside {inside or "nothing"}; '
            f'{a.get("settle", 0):.2f} m above a support surface; door zones '
            + ('as strict' if door is None else f'at most {door:.2f} m deep') + '.')


def _rules(rts: dict) -> list[str]:
    L = ['## 3. Design rules', '',
         'Share of the cases that keep each rule (`rules/`), number of '
         'cases in brackets, in the held-out rooms and in the synthesized ones; the '
         'difference in percentage points and the p-value of a two-sided test that the '
         'shares are equal. A rule with no case on either side does not apply to the data '
         'set\'s categories and is listed below the table.', '']
    rows, absent = [], {}
    for rt, r in rts.items():
        for name, d in r['design_rules'].items():
            (ka, na), (kb, nb) = d['corpus'], d['synthesized']
            if not (na or nb):
                absent.setdefault(rt, []).append(name)
                continue
            diff = f'{100 * (kb / nb - ka / na):+.1f}' if na and nb else '–'
            rows.append([rt, name, _rate(d['corpus']), _rate(d['synthesized']), diff,
                         f'{d["p"]:.3f}'])
    L += _table(['room type', 'rule', 'held-out', 'synthesized', 'difference (points)', 'p'],
                rows) + ['']
    L += [f'Not applicable in {rt}: {", ".join(names)}.' for rt, names in absent.items()]
    return L + ['']


def _split(rts: dict) -> list[str]:
    L = ['## 4. Rooms and synthesis', '']
    rows = []
    for rt, r in rts.items():
        s, n, sp = r['split'], r['rooms'], r['speed']
        rows.append([rt, str(s['rooms']), str(s['corpus_seed']), str(s['training']),
                     str(s['heldout']), str(n['synthesized']), str(n['failed']),
                     f'{sp["median"]:.2f}' if sp.get('rooms') else '–',
                     ', '.join(f'{k} {v}' for k, v in sp.get('stopped', {}).items()) or '–'])
    L += _table(['room type', 'rooms in the data set', 'corpus seed', 'training',
                 'held out', 'synthesized', 'failed', 'median s / room', 'stopped by'],
                rows) + ['']
    for rt, r in rts.items():
        removed = r['split']['objects_removed']
        if removed:
            L.append(f'{rt}: objects the category set cannot place, left out of the data '
                     f'set\'s {rt} rooms as training left them out (counted over all of '
                     'them): ' + ', '.join(f'{k} {v}' for k, v in removed.items()) + '.')
        L += [f'{rt}: shell {f["shell"]} (seed {f["seed"]}) not furnished: {f["error"]}'
              for f in r['failed']]
    return L + ['']


def write(results: dict, out: Path, copy_to: Path | None = None) -> None:
    """``index.md`` and ``results.json`` in ``out``; with ``copy_to``, the Markdown there
    too (it has no figures, so no link needs rewriting)."""
    out = Path(out)
    (out / 'results.json').write_text(json.dumps(results, indent=1, default=str) + '\n')
    text = markdown(results) + '\n'
    (out / 'index.md').write_text(text)
    if copy_to is not None:
        os.makedirs(Path(copy_to).resolve().parent, exist_ok=True)
        Path(copy_to).write_text(text)


def terminal_summary(results: dict) -> str:
    """The short table printed at the end of a run."""
    head = ['room type', 'held out', 'synth', 'KL synth', 'KL training', 'KL unif',
            'objects syn/held', 'diff', 'valid syn/held']
    rows = summary_rows(results)
    widths = [max(len(h), *(len(r[k]) for r in rows)) for k, h in enumerate(head)]
    return '\n'.join('  '.join(c.ljust(w) for c, w in zip(cells, widths, strict=True))
                     for cells in [head] + rows)
