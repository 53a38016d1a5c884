"""The report's pictures: category frequencies, the similarity histogram, a gallery, the
worst offender of every design rule.

Figures are drawn with ``matplotlib.figure.Figure`` (no pyplot, no global state) and hold
nothing that varies between runs of one seed (no timings, no dates)."""
from __future__ import annotations

import os
from typing import Sequence

from matplotlib.figure import Figure
import numpy as np

from ..plot import save_grid
from ..scene import Scene

SYNTH_COLOR = '#d1603d'
CORPUS_COLOR = '#3d7dd1'
DPI = 100


def category_bars(frequencies: dict[str, dict[str, float]], path: str | os.PathLike,
                  title: str) -> str:
    """Horizontal bars of objects per room for every category, synthesized beside corpus,
    most frequent (in the corpus) at the top; categories neither set has are left out."""
    synth, corpus = frequencies['synthesized'], frequencies['corpus']
    names = [c for c in sorted(corpus, key=lambda c: (-corpus[c], c))
             if corpus[c] > 0 or synth.get(c, 0) > 0]
    n = max(len(names), 1)
    fig = Figure(figsize=(7.0, 1.2 + 0.28 * n), dpi=DPI)
    ax = fig.add_axes((0.25, 0.6 / (1.2 + 0.28 * n), 0.7, 1 - 1.0 / (1.2 + 0.28 * n)))
    y = np.arange(len(names))
    h = 0.4
    ax.barh(y - h / 2, [synth.get(c, 0.0) for c in names], h, color=SYNTH_COLOR,
            label='synthesized')
    ax.barh(y + h / 2, [corpus[c] for c in names], h, color=CORPUS_COLOR,
            label='training corpus')
    ax.set_yticks(y, names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel('objects per room', fontsize=9)
    ax.tick_params(axis='x', labelsize=8)
    ax.grid(axis='x', alpha=0.3)
    ax.set_axisbelow(True)
    ax.legend(fontsize=8, loc='lower right', frameon=False)
    ax.set_title(title, fontsize=10)
    fig.savefig(path, dpi=DPI, format='png')
    return os.fspath(path)


def similarity_histogram(synthesized: np.ndarray, heldout: np.ndarray,
                         path: str | os.PathLike, title: str, bins: int = 20) -> str:
    """Overlaid histograms of the maximal similarity to the training rooms, as fractions of
    rooms, with each set's median marked."""
    edges = np.linspace(0.0, 1.0, bins + 1)
    fig = Figure(figsize=(7.0, 4.0), dpi=DPI)
    ax = fig.add_axes((0.1, 0.13, 0.86, 0.77))
    for values, color, label in ((heldout, CORPUS_COLOR, 'held-out corpus rooms'),
                                 (synthesized, SYNTH_COLOR, 'synthesized rooms')):
        values = np.clip(np.asarray(values, dtype=float), 0.0, 1.0)
        if not len(values):
            continue
        weights = np.full(len(values), 1.0 / len(values))
        ax.hist(values, edges, weights=weights, color=color, alpha=0.45,
                label=f'{label} (n = {len(values)}, median {np.median(values):.2f})')
        ax.hist(values, edges, weights=weights, color=color, histtype='step', lw=1.4)
        ax.axvline(float(np.median(values)), color=color, ls='--', lw=1.2)
    ax.set_xlim(0, 1)
    ax.set_xlabel('maximal similarity to a training-corpus room', fontsize=9)
    ax.set_ylabel('fraction of rooms', fontsize=9)
    ax.tick_params(labelsize=8)
    ax.legend(fontsize=8, loc='upper right', frameon=False)
    ax.set_title(title, fontsize=10)
    fig.savefig(path, dpi=DPI, format='png')
    return os.fspath(path)


def gallery(synthesized: Sequence[Scene], corpus: Sequence[Scene], path: str | os.PathLike,
            room_type: str) -> str:
    """Top row: shells furnished by the model; bottom row: the same shells as the corpus
    rules furnished them."""
    k = min(len(synthesized), len(corpus))
    scenes = list(synthesized[:k]) + list(corpus[:k])
    titles = ([f'model, {room_type} shell #{i}' for i in range(k)]
              + [f'corpus rules, shell #{i}' for i in range(k)])
    return save_grid(scenes, path, ncols=k, titles=titles, cell=3.2)


def rule_offenders(scenes: Sequence[Scene], outcomes: Sequence[dict[str, tuple[int, int]]],
                   path: str | os.PathLike, title: str) -> str | None:
    """For every design rule some room breaks, the room that breaks it in the most cases
    (the first such room on ties), titled with the rule and the count; None when no rule is
    broken anywhere. ``outcomes[i]`` is ``design_rules.measure(scenes[i])``."""
    picked, titles = [], []
    for name in outcomes[0] if outcomes else ():
        broken = [n - k for k, n in (row[name] for row in outcomes)]
        worst = int(np.argmax(broken))
        if broken[worst] > 0:
            kept, cases = outcomes[worst][name]
            picked.append(scenes[worst])
            titles.append(f'{name}\n{cases - kept} of {cases} broken ({title} #{worst})')
    if not picked:
        return None
    return save_grid(picked, path, ncols=4, titles=titles, cell=3.4)
