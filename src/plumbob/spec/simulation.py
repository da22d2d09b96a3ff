"""Simulation specs: particles joined by springs, rods and strings, under gravity,
applied forces and friction — the :class:`~plumbob.dynamics.motion.MotionModel` and
the solver's options. The format is documented in ``docs/simulate.md``; in short::

    kind = "simulation"                    # optional when the content says so
    title = "Example 2"                    # optional
    gravity = [0, -9.81]                   # optional, m/s²
    [parameters]                           # optional named numbers for expressions
    m = 2.0
    [surface]                              # optional: a supporting horizontal surface
    g = 9.81                               #   m/s² pressing the particles onto it
    friction = 0.0                         #   default coefficient of sliding friction
    [solver]                               # optional
    rtol = 1e-10                           #   also: method, stabilization, friction_speed
    [[particle]]                           # one table per particle (spec/particles.py)
    name = "A"
    mass = "m"
    position = [-0.5, 0]
    force = [0, 0]
    [[spring]]
    between = ["A", "B"]
    stiffness = 50                         # N/m
    natural_length = 1.0                   # m, default: the initial distance
    [[rod]]                                # and [[string]]: between, length (default: initial)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..dynamics.motion import MIN_RTOL, Link, MotionModel, Spring
from ..errors import DynamicsError, PlumbobError
from ..units import SEED_GRAVITY
from .particles import read_particles
from .values import SpecContext

__all__ = ["SimulationSpec", "build_simulation", "SIMULATION_KEYS"]

#: the top-level keys of a simulation spec
SIMULATION_KEYS = {"kind", "title", "gravity", "parameters", "surface", "solver", "particle",
                   "spring", "rod", "string"}
_SPRING = {"between", "stiffness", "natural_length"}
_LINK = {"between", "length"}
_SURFACE = {"g", "friction"}
_SOLVER = {"rtol", "method", "stabilization", "friction_speed"}
_METHODS = {"RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA"}


@dataclass(frozen=True, eq=False)
class SimulationSpec:
    """A loaded simulation: the model plus solver options (``solve_ivp`` keywords)."""

    model: MotionModel
    title: str | None
    options: dict[str, Any]
    path: str | None = None


def build_simulation(spec: SpecContext, data: dict) -> SimulationSpec:
    """The simulation the parsed TOML ``data`` describes (its ``[parameters]`` already
    in ``spec``)."""
    spec.table(data, SIMULATION_KEYS, None)
    title = spec.text(data["title"], "title") if "title" in data else None
    particles = read_particles(spec, data.get("particle"), simulation=True)
    system = particles.system
    names = list(system.names or ())
    index = {name: k for k, name in enumerate(names)}
    dim = (system.dim,)

    def pair(table: dict, where: str) -> tuple[int, int]:
        between = table.get("between")
        if not (isinstance(between, list) and len(between) == 2
                and all(isinstance(x, str) for x in between)):
            raise spec.error(where, 'needs between = ["NAME", "NAME"] (two particle names)')
        for x in between:
            if x not in index:
                raise spec.error(f"{where}.between", f"names particle {x!r}, which is not "
                                 f"defined; known: {', '.join(names)}")
        if between[0] == between[1]:
            raise spec.error(f"{where}.between", f"joins {between[0]!r} to itself",
                             DynamicsError)
        return index[between[0]], index[between[1]]

    def distance(i: int, j: int) -> float:
        return float(np.linalg.norm(system.positions[i] - system.positions[j]))

    springs = []
    for k, raw in enumerate(_tables(spec, data, "spring"), 1):
        where = f"spring {k}"
        table = spec.table(raw, _SPRING, where)
        i, j = pair(table, where)
        if "stiffness" not in table:
            raise spec.error(where, "needs a stiffness (N/m)")
        stiffness = spec.number(table["stiffness"], f"{where}.stiffness")
        natural = spec.number(table["natural_length"], f"{where}.natural_length") \
            if "natural_length" in table else distance(i, j)
        springs.append(Spring(i, j, stiffness, natural))
    links = []
    for kind in ("rod", "string"):
        for k, raw in enumerate(_tables(spec, data, kind), 1):
            where = f"{kind} {k}"
            table = spec.table(raw, _LINK, where)
            i, j = pair(table, where)
            length = spec.number(table["length"], f"{where}.length") if "length" in table \
                else distance(i, j)
            links.append(Link(i, j, length, kind))

    gravity = spec.vector(data["gravity"], "gravity", dim, like="the positions") \
        if "gravity" in data else None
    surface_g = None
    default_mu = 0.0
    if "surface" in data:
        surface = spec.table(data["surface"], _SURFACE, "surface")
        surface_g = spec.number(surface.get("g", SEED_GRAVITY), "surface.g")
        default_mu = spec.number(surface.get("friction", 0.0), "surface.friction")
    mu = np.array([default_mu if f is None else f for f in particles.frictions])
    options = _solver_options(spec, data)
    try:
        model = MotionModel(system, tuple(springs), tuple(links), gravity=gravity,
                            forces=particles.forces, friction=mu if np.any(mu) else None,
                            surface_gravity=surface_g)
    except PlumbobError as error:
        raise error.within(path=spec.path) from None
    return SimulationSpec(model, title, options, spec.path)


def _solver_options(spec: SpecContext, data: dict) -> dict[str, Any]:
    """``[solver]`` as keywords of :func:`~plumbob.dynamics.motion.simulate`."""
    options: dict[str, Any] = {}
    if "solver" in data:
        solver = spec.table(data["solver"], _SOLVER, "solver")
        for key in ("rtol", "stabilization", "friction_speed"):
            if key in solver:
                options[key] = spec.number(solver[key], f"solver.{key}")
        if "rtol" in options and not MIN_RTOL <= options["rtol"] < 1:
            raise spec.error("solver.rtol", f"{options['rtol']!r} is not a tolerance double "
                             f"precision can keep: give one from {MIN_RTOL:g} up to 1 "
                             "(1e-10 by default)", DynamicsError)
        if "method" in solver:
            options["method"] = spec.text(solver["method"], "solver.method", sorted(_METHODS),
                                          what="method")
    return options


def _tables(spec: SpecContext, data: dict, key: str) -> list:
    value = data.get(key, [])
    if not isinstance(value, list):
        raise spec.error(key, f"write each {key} as a [[{key}]] table")
    return value
