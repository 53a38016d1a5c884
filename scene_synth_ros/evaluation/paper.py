"""The figures reported by Ritchie, Wang and Lin (CVPR 2019), printed beside ours.

They were measured on SUNCG with the paper's networks and hardware, so they are a point of
reference, not a target our procedural corpus can be held to number for number.
"""
from ..networks import COMPONENT_ROWS

# Table 1: KL(synthesized || training set) of the category distribution.
KL = {
    'ours': {'bedroom': 0.0095, 'living': 0.0179, 'bathroom': 0.0240, 'office': 0.0436},
    'uniform': {'bedroom': 0.6202, 'living': 0.8858, 'bathroom': 1.3675, 'office': 0.7219},
    'deep_priors': {'bedroom': 0.2017, 'living': 0.4874, 'bathroom': 0.2479,
                    'office': 0.2138},
}

# Table 2: real-vs-synthetic classifier accuracy in percent (all room types together).
CLASSIFIER = {'deep_priors': 84.69, 'human_centric': 76.18, 'ours': 58.75,
              'perturbed_1': 50.00, 'perturbed_5': 54.69, 'perturbed_10': 64.38}

# Table 3: average seconds to synthesize a complete scene.
SPEED = {'ours': (1.858, 'NVIDIA GeForce GTX 1080 Ti'),
         'deep_priors': (240.0, 'GPU, approximate'),
         'grains': (0.1027, 'GPU')}

# Appendix table: improvement of each module over a randomly initialised network on
# held-out data, keyed by (module, metric), one value per row of ``networks.COMPONENT_ROWS``
# (accuracies: absolute difference; losses: relative change in percent).
COMPONENT_IMPROVEMENT = {
    rt: dict(zip(((module, key) for _, module, key in COMPONENT_ROWS), values, strict=True))
    for rt, values in {
        'bedroom': (0.4225, 0.7600, -98.61, -54.20, 0.3821, -97.74),
        'living': (0.5312, 0.8001, -98.56, -44.99, 0.3902, -97.79),
        'office': (0.5525, 0.7629, -98.25, -68.03, 0.4482, -98.14),
        'bathroom': (0.5873, 0.8597, -85.00, -53.23, 0.4419, -97.64),
    }.items()}
