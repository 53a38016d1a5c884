"""How good synthesized rooms are: the paper's evaluation (section 6 and appendix) on this
package's corpus, weights and machine.

One module per measurement:

* ``distribution`` — KL of the category distribution (table 1) and per-category rates;
* ``classifier`` — a real-vs-synthetic ResNet-34-style classifier (table 2);
* ``speed`` — seconds per room and per module (table 3);
* ``plausibility`` — collisions, floor, doors, support, robot path, per room;
* ``similarity`` — scene-to-scene similarity and the generalisation test (appendix);
* ``components`` — the shipped weights' per-module metrics against random networks;

with ``data`` (the rooms compared), ``perturb`` (the perturbed-corpus baseline),
``figures``, ``report``, ``paper`` (the paper's figures) and ``run`` (``EvalConfig`` and
``run_evaluation``, which ``scene-synth evaluate`` calls). ``dataset`` and ``dataset_report``
are ``scene-synth evaluate --data``: synthesized rooms against the rooms of an imported data
set that training held out.
"""
from .run import EvalConfig, EvaluationError, run_evaluation

__all__ = ['EvalConfig', 'EvaluationError', 'run_evaluation']
