"""The furniture builders, one module per family of categories.

Each builder function declares its categories with ``meshes.builder.builds``;
``meshes.registry`` imports every module here by name and collects the declarations. This
``__init__`` imports none of them, so the registry stays the one place that lists them.
"""
