"""The ``[[particle]]`` tables: one schema for shape and simulation specs.

Each table gives a particle's ``mass`` (kg, > 0) and ``position`` (2 or 3 numbers in the
spec's length unit), and optionally a unique ``name``, a ``velocity`` (length unit per
second, default at rest), and — acting only in a simulation — a constant ``force`` (N)
and a sliding ``friction`` coefficient. Documented in ``docs/shapes.md`` and
``docs/simulate.md``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..bodies.particles import ParticleSystem
from ..errors import DynamicsError, SpecError
from .values import SpecContext

__all__ = ["Particles", "read_particles", "PARTICLE_KEYS", "MOTION_KEYS"]

#: the keys of a [[particle]] table
PARTICLE_KEYS = {"name", "mass", "position", "velocity", "force", "friction"}
#: the keys that act only in a simulation
MOTION_KEYS = {"force", "friction"}


@dataclass(frozen=True, eq=False)
class Particles:
    """The particles a spec describes, with what only a simulation uses."""

    system: ParticleSystem
    #: (n, d) N, constant applied forces; None when no particle has one
    forces: np.ndarray | None
    #: each particle's own coefficient of friction; None: the surface's
    frictions: tuple[float | None, ...]


def read_particles(spec: SpecContext, tables: Any, simulation: bool) -> Particles:
    """The particles of the ``[[particle]]`` ``tables``. ``simulation``: the spec is a
    simulation, where a mass that is not positive is a :class:`DynamicsError` (a bad
    physical input) and ``force`` and ``friction`` act; a shape spec refuses them."""
    if not isinstance(tables, list) or not tables:
        raise spec.error("particle", "give at least one [[particle]] table")
    names: list[str] = []
    masses, positions, velocities, forces, frictions = [], [], [], [], []
    moving = False
    dim: tuple[int, ...] = (2, 3)
    for k, raw in enumerate(tables, 1):
        where = f"particle {k}"
        table = spec.table(raw, PARTICLE_KEYS, where)
        name = spec.text(table["name"], f"{where}.name", what="a name") if "name" in table \
            else where
        if name in names:
            raise spec.error(f"{where}.name", f"two particles are named {name!r}; names must "
                             "be unique")
        if "name" in table:
            where = f"{where} ({name})"
        if not simulation and MOTION_KEYS & set(table):
            raise spec.error(where, "force and friction act only in a simulation spec "
                             '(kind = "simulation", see docs/simulate.md)')
        if "mass" not in table or "position" not in table:
            raise spec.error(where, "a particle needs a mass (kg) and a position (m)")
        mass = spec.number(table["mass"], f"{where}.mass")
        if not mass > 0:
            raise spec.error(f"{where}.mass", f"every mass must be positive, not {mass:g} kg",
                             DynamicsError if simulation else SpecError)
        like = None if k == 1 else "the first particle's position"
        position = spec.vector(table["position"], f"{where}.position", dim, like=like)
        dim = (len(position),)
        like = "the position"
        rest = [0.0] * dim[0]
        moving = moving or "velocity" in table
        names.append(name)
        masses.append(mass)
        positions.append(position)
        velocities.append(spec.vector(table.get("velocity", rest), f"{where}.velocity", dim,
                                      like=like))
        forces.append(spec.vector(table.get("force", rest), f"{where}.force", dim,
                                  length=False, like=like))
        frictions.append(spec.number(table["friction"], f"{where}.friction")
                         if "friction" in table else None)
    system = ParticleSystem(np.array(masses), np.array(positions),
                            np.array(velocities) if moving else None, tuple(names))
    return Particles(system, np.array(forces) if np.any(forces) else None, tuple(frictions))
