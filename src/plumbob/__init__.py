"""plumbob: mass properties, stability and energy from geometry alone.

The public API, imported lazily so ``plumbob mass part.stl`` pays only for numpy::

    import plumbob
    body = plumbob.load("shapes/l_shape.toml")
    props = plumbob.mass_properties(body)
    props.center_of_mass            # array([0.8333..., 0.8333...])
"""

from __future__ import annotations

from importlib import import_module
from typing import Any

__all__ = [
    "load",
    "read",
    "mass_properties",
    "MassProperties",
    "PlumbobError",
    "primitives",
    "union",
    "difference",
    "intersection",
    "Assembly",
    "ParticleSystem",
    "Lamina",
    "MeshSolid",
    "material",
    "collide",
]

_LAZY = {
    "read": ("plumbob.io", "read"),
    "MassProperties": ("plumbob.massprops", "MassProperties"),
    "PlumbobError": ("plumbob.errors", "PlumbobError"),
    "primitives": ("plumbob.bodies.primitives", None),
    "union": ("plumbob.bodies.csg", "union"),
    "difference": ("plumbob.bodies.csg", "difference"),
    "intersection": ("plumbob.bodies.csg", "intersection"),
    "Assembly": ("plumbob.bodies.csg", "Assembly"),
    "ParticleSystem": ("plumbob.bodies.particles", "ParticleSystem"),
    "Lamina": ("plumbob.bodies.lamina", "Lamina"),
    "MeshSolid": ("plumbob.bodies.solid", "MeshSolid"),
    "material": ("plumbob.materials", "material"),
    "collide": ("plumbob.dynamics.collisions", "collide"),
    "check": ("plumbob.stability", "check"),
    "poses": ("plumbob.stability", "resting_poses"),
    "lift": ("plumbob.energy", "lift_energy"),
    "batch": ("plumbob.batch", None),
}


def load(path: str, **options: Any):
    """The body described by the file at ``path`` (spec, mesh or outline)."""
    from .io import read

    return read(path, **options).body


def mass_properties(body):
    """The :class:`MassProperties` of ``body`` (a body, or a path to load)."""
    if isinstance(body, str):
        body = load(body)
    return body.mass_properties()


def __getattr__(name: str):
    if name not in _LAZY:
        raise AttributeError(f"module 'plumbob' has no attribute {name!r}")
    module, attribute = _LAZY[name]
    value = import_module(module)
    return value if attribute is None else getattr(value, attribute)
