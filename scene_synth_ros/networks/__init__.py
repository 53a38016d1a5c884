"""The paper's four neural modules (next category, location, orientation with snap, dimensions),
their training examples, training loop and weight bundles. Named ``networks`` because "model"
means a catalog 3D model everywhere else in the package."""
