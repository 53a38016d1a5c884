"""Component metrics (paper, appendix table): the held-out metrics of each module of the
shipped weights, as stored in their bundles at export, against a randomly initialised
network of the same shape. Nothing is retrained or re-evaluated here."""
from __future__ import annotations

from ..networks import COMPONENT_ROWS
from .paper import COMPONENT_IMPROVEMENT

HIGHER_IS_BETTER = {'top1', 'top5', 'accuracy'}


def improvement(key: str, trained: float, random: float) -> float:
    """The paper's improvement column: an absolute difference for accuracies, a relative
    change in percent for losses."""
    if key in HIGHER_IS_BETTER:
        return trained - random
    return 100.0 * (trained - random) / abs(random) if random else float('nan')


def component_rows(room_type: str, components: dict) -> list[dict]:
    """One row per metric of ``networks.COMPONENT_ROWS``, from a bundle's
    ``metrics['components']``."""
    rows = []
    for label, module, key in COMPONENT_ROWS:
        tr = float(components[module][f'trained_{key}'])
        rn = float(components[module][f'random_{key}'])
        rows.append({'metric': label, 'module': module, 'key': key, 'trained': tr,
                     'random': rn, 'improvement': improvement(key, tr, rn),
                     'relative': key not in HIGHER_IS_BETTER,
                     'paper_improvement': COMPONENT_IMPROVEMENT.get(room_type, {})
                     .get((module, key))})
    return rows
