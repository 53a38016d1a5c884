"""The paper's four neural modules (next category, location, orientation with snap, dimensions),
their training examples, training loop and weight bundles. Named ``networks`` because "model"
means a catalog 3D model everywhere else in the package."""

# The networks, in the order that seeds their initialisation and their training batches.
NETWORKS = ('category', 'location', 'orientation', 'snap', 'dimensions')

# The paper's appendix table of component metrics: (label, network, held-out metric).
COMPONENT_ROWS = (('category top-1 accuracy', 'category', 'top1'),
                  ('category top-5 accuracy', 'category', 'top5'),
                  ('location cross-entropy', 'location', 'loss'),
                  ('orientation neg. ELBO', 'orientation', 'neg_elbo'),
                  ('snap accuracy', 'snap', 'accuracy'),
                  ('dimensions neg. ELBO', 'dimensions', 'neg_elbo'))
