"""Simulation specs: a TOML file describing particles, springs, rods, strings and forces.

The format is documented in ``docs/simulate.md``. In short::

    title = "Example 2"                    # optional
    gravity = [0, -9.81]                   # optional, m/s²
    [parameters]                           # optional named numbers for expressions
    m = 2.0
    [surface]                              # optional: a supporting horizontal surface
    g = 9.81                               #   m/s² pressing the particles onto it
    friction = 0.0                         #   default coefficient of sliding friction
    [solver]                               # optional
    rtol = 1e-10                           #   also: method, stabilization, friction_speed
    [[particle]]                           # one table per particle
    name = "A"
    mass = "m"                             # kg: a number or an expression
    position = [-0.5, 0]                   # m, 2 or 3 components
    velocity = [0, 0]                      # m/s, default rest
    force = [0, 0]                         # N, constant applied force, default none
    friction = 0.4                         # overrides [surface] friction
    [[spring]]
    between = ["A", "B"]
    stiffness = 50                         # N/m
    natural_length = 1.0                   # m, default: the initial distance
    [[rod]]                                # and [[string]]: between, length (default: initial)

Every number may be a TOML number or a string expression (``"sqrt(2)*m"``) over
``pi``, ``e`` and the ``[parameters]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

try:  # Python ≥ 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

from ..bodies.particles import ParticleSystem
from ..errors import DynamicsError, InputFileError, PlumbobError, SpecError
from ..units import STANDARD_GRAVITY
from .motion import Link, MotionModel, Spring

__all__ = ["SimulationSpec", "load_simulation", "parse_simulation"]

_TOP = {"kind", "title", "gravity", "parameters", "surface", "solver", "particle", "spring",
        "rod", "string"}
_PARTICLE = {"name", "mass", "position", "velocity", "force", "friction"}
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


class _Reader:
    def __init__(self, path: str | None) -> None:
        self.path = path
        self.names: dict[str, float] = {}

    def fail(self, message: str, cls: type[PlumbobError] = SpecError) -> PlumbobError:
        return cls(message, path=self.path)

    def keys(self, table: Any, allowed: set[str], where: str) -> dict:
        if not isinstance(table, dict):
            raise self.fail(f"{where} must be a table")
        unknown = sorted(set(table) - allowed)
        if unknown:
            raise self.fail(f"unknown key {unknown[0]!r} in {where}; allowed: "
                            f"{', '.join(sorted(allowed))}")
        return table

    def number(self, value: Any, where: str) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise self.fail(f"{where} must be a number or an expression (got {value!r})")
        if isinstance(value, str):
            from ..spec.expr import evaluate

            try:
                result = evaluate(value, self.names)
            except PlumbobError as error:
                raise self.fail(f"{where}: {error}") from None
        else:
            result = float(value)
        if not math.isfinite(result):
            raise self.fail(f"{where} is not a finite number ({value!r})")
        return result

    def vector(self, value: Any, where: str, dim: int | None) -> np.ndarray:
        if not isinstance(value, list) or not 2 <= len(value) <= 3:
            raise self.fail(f"{where} must be a list of 2 or 3 numbers (got {value!r})")
        if dim is not None and len(value) != dim:
            raise self.fail(f"{where} has {len(value)} components but the positions have {dim}")
        return np.array([self.number(x, f"{where}[{k}]") for k, x in enumerate(value)])


def parse_simulation(data: dict, path: str | None = None) -> SimulationSpec:
    """Build a :class:`SimulationSpec` from parsed TOML ``data`` (``path`` for messages)."""
    rd = _Reader(path)
    rd.keys(data, _TOP, "the spec")
    kind = data.get("kind", "simulation")
    if kind != "simulation":
        raise rd.fail(f"this is a {kind!r} spec, not a simulation; 'plumbob simulate' needs "
                      "[[particle]] tables (see docs/simulate.md)")
    title = data.get("title")
    if title is not None and not isinstance(title, str):
        raise rd.fail("title must be a string")
    params = data.get("parameters", {})
    if not isinstance(params, dict):
        raise rd.fail("[parameters] must be a table of named numbers")
    for key, value in params.items():
        rd.names[key] = rd.number(value, f"parameter {key!r}")

    particles = data.get("particle")
    if not isinstance(particles, list) or not particles:
        raise rd.fail("a simulation needs at least one [[particle]] table")
    names: list[str] = []
    masses, positions, velocities, forces, frictions = [], [], [], [], []
    dim = None
    for k, raw in enumerate(particles, 1):
        where = f"[[particle]] {k}"
        table = rd.keys(raw, _PARTICLE, where)
        name = table.get("name", f"particle {k}")
        if not isinstance(name, str) or not name:
            raise rd.fail(f"{where}: name must be a non-empty string")
        if name in names:
            raise rd.fail(f"two particles are named {name!r}; names must be unique")
        where = f"particle {name!r}"
        names.append(name)
        if "mass" not in table or "position" not in table:
            raise rd.fail(f"{where} needs a mass (kg) and a position (m)")
        mass = rd.number(table["mass"], f"{where} mass")
        if mass <= 0:
            raise rd.fail(f"{where} has mass {mass:g} kg; every mass must be positive",
                          DynamicsError)
        position = rd.vector(table["position"], f"{where} position", dim)
        dim = len(position)
        masses.append(mass)
        positions.append(position)
        velocities.append(rd.vector(table.get("velocity", [0.0] * dim), f"{where} velocity", dim))
        forces.append(rd.vector(table.get("force", [0.0] * dim), f"{where} force", dim))
        frictions.append(table.get("friction"))

    index = {name: k for k, name in enumerate(names)}

    def pair(table: dict, where: str) -> tuple[int, int]:
        between = table.get("between")
        if not (isinstance(between, list) and len(between) == 2
                and all(isinstance(x, str) for x in between)):
            raise rd.fail(f"{where} needs between = [\"NAME\", \"NAME\"] (two particle names)")
        for x in between:
            if x not in index:
                raise rd.fail(f"{where} names particle {x!r}, which is not defined; known: "
                              f"{', '.join(names)}")
        if between[0] == between[1]:
            raise rd.fail(f"{where} joins {between[0]!r} to itself", DynamicsError)
        return index[between[0]], index[between[1]]

    def distance(i: int, j: int) -> float:
        return float(np.linalg.norm(positions[i] - positions[j]))

    springs = []
    for k, raw in enumerate(_tables(rd, data, "spring"), 1):
        where = f"[[spring]] {k}"
        table = rd.keys(raw, _SPRING, where)
        i, j = pair(table, where)
        if "stiffness" not in table:
            raise rd.fail(f"{where} needs a stiffness (N/m)")
        stiffness = rd.number(table["stiffness"], f"{where} stiffness")
        natural = rd.number(table["natural_length"], f"{where} natural_length") \
            if "natural_length" in table else distance(i, j)
        springs.append(Spring(i, j, stiffness, natural))
    links = []
    for kind in ("rod", "string"):
        for k, raw in enumerate(_tables(rd, data, kind), 1):
            where = f"[[{kind}]] {k}"
            table = rd.keys(raw, _LINK, where)
            i, j = pair(table, where)
            length = rd.number(table["length"], f"{where} length") if "length" in table \
                else distance(i, j)
            links.append(Link(i, j, length, kind))

    gravity = rd.vector(data["gravity"], "gravity", dim) if "gravity" in data else None
    surface_g = None
    default_mu = 0.0
    if "surface" in data:
        surface = rd.keys(data["surface"], _SURFACE, "[surface]")
        surface_g = rd.number(surface.get("g", STANDARD_GRAVITY), "[surface] g")
        default_mu = rd.number(surface.get("friction", 0.0), "[surface] friction")
    mu = np.array([default_mu if f is None else rd.number(f, f"particle {names[k]!r} friction")
                   for k, f in enumerate(frictions)])

    options: dict[str, Any] = {}
    if "solver" in data:
        solver = rd.keys(data["solver"], _SOLVER, "[solver]")
        for key in ("rtol", "stabilization", "friction_speed"):
            if key in solver:
                options[key] = rd.number(solver[key], f"[solver] {key}")
        if "method" in solver:
            if solver["method"] not in _METHODS:
                raise rd.fail(f"[solver] method must be one of {', '.join(sorted(_METHODS))}")
            options["method"] = solver["method"]

    try:
        system = ParticleSystem(masses, positions, velocities, names=tuple(names))
        model = MotionModel(system, tuple(springs), tuple(links), gravity=gravity,
                            forces=np.array(forces) if np.any(forces) else None,
                            friction=mu if np.any(mu) else None, surface_gravity=surface_g)
    except PlumbobError as error:
        if error.path or path is None:
            raise
        raise type(error)(error.message, path=path) from None
    return SimulationSpec(model, title, options, path)


def _tables(rd: _Reader, data: dict, key: str) -> list:
    value = data.get(key, [])
    if not isinstance(value, list):
        raise rd.fail(f"write each {key} as a [[{key}]] table")
    return value


def load_simulation(path: str | Path) -> SimulationSpec:
    """Read a simulation spec from a TOML file.

    Raises :class:`InputFileError` when the file is missing or unreadable, and
    :class:`SpecError` / :class:`DynamicsError` for bad contents.
    """
    path = str(path)
    try:
        with open(path, "rb") as handle:
            data = tomllib.load(handle)
    except FileNotFoundError:
        raise InputFileError("no such file; give the path of a simulation spec (.toml)",
                             path=path) from None
    except IsADirectoryError:
        raise InputFileError("is a directory, not a simulation spec", path=path) from None
    except OSError as error:
        raise InputFileError(f"cannot read the file ({error.strerror})", path=path) from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
        raise SpecError(f"not valid TOML: {error}", path=path) from None
    return parse_simulation(data, path)
