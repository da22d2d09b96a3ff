"""The one reader of TOML specs: a **shape** (a body, ``docs/shapes.md``) or a
**simulation** (particles in motion, ``docs/simulate.md``), chosen by the top-level
``kind = "shape" | "simulation"``.

When ``kind`` is absent the content decides: a ``[shape]`` table or
``[[part]]`` tables make a shape; a ``title``, ``gravity``, ``[surface]``,
``[solver]``, ``[[spring]]``, ``[[rod]]``, ``[[string]]`` or a particle's ``force``
or ``friction`` make a simulation; bare ``[[particle]]`` tables, which both kinds
read alike, are what the caller asks for. Both kinds share ``[parameters]`` and one
``[[particle]]`` schema (:mod:`.particles`).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..bodies.base import Body
from ..errors import InputFileError, SpecError
from ..io import read_checked
from ..reading import Reading
from ..units import LENGTH_UNITS, length_scale
from .particles import MOTION_KEYS, read_particles
from .parts import MATERIAL_KEYS, build_parts, named
from .simulation import SIMULATION_KEYS, SimulationSpec, build_simulation
from .values import SpecContext, read_parameters

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["load_spec", "build_spec", "load_simulation", "parse_simulation", "spec_kind", "KINDS"]

MAX_SPEC_BYTES = 4 << 20
#: the values of a spec's top-level ``kind``
KINDS = ("shape", "simulation")
#: the top-level keys of a shape spec
TOP_KEYS = {"kind", "shape", "parameters", "part", "particle"}
#: the keys of [shape] in a spec of particles
SHAPE_KEYS = {"name", "description", "kind", "units", "source", "figure"}
#: the keys of [shape] in a spec of parts ("segments" is accepted and, today, unused)
PARTS_SHAPE_KEYS = SHAPE_KEYS | MATERIAL_KEYS | {"segments"}
_SIMULATION_ONLY = SIMULATION_KEYS - TOP_KEYS


def spec_kind(data: dict, default: str) -> Any:
    """The kind ``data`` declares, else the one its content shows, else ``default``.

    The default decides only bare ``[[particle]]`` tables (no ``[shape]``, no
    simulation key, no force or friction), which both kinds read alike.

    >>> spec_kind({"part": []}, "simulation"), spec_kind({"spring": []}, "shape")
    ('shape', 'simulation')
    >>> spec_kind({"particle": [{"mass": 1, "position": [0, 0], "force": [1, 0]}]}, "shape")
    'simulation'
    """
    if "kind" in data:
        return data["kind"]
    if "shape" in data or "part" in data:
        return "shape"
    particles = data.get("particle")
    moving = isinstance(particles, list) and any(
        isinstance(p, dict) and MOTION_KEYS & set(p) for p in particles)
    if moving or _SIMULATION_ONLY & set(data):
        return "simulation"
    return default


def build_spec(data: dict, path: str = "<spec>", *,
               parameters: Mapping[str, float | str] | None = None) -> Reading:
    """The body a parsed spec describes: a shape's body, or a simulation's particles
    at t = 0. ``parameters`` override ``[parameters]`` entries by name
    (:func:`~.values.read_parameters`)."""
    _check_table(data, path)
    kind = spec_kind(data, "shape")
    if kind == "simulation":
        return Reading(_simulation(data, path, parameters).model.system, (), path)
    if kind != "shape":
        raise SpecError(
            f'kind: a spec is a "shape" or a "simulation", not {kind!r} (the kind of body '
            "a shape makes, such as lamina or solid, goes in [shape] kind)",
            path=path,
        )
    return Reading(_shape(data, path, parameters), (), path)


def parse_simulation(data: dict, path: str | None = None, *,
                     parameters: Mapping[str, float | str] | None = None) -> SimulationSpec:
    """The :class:`SimulationSpec` of parsed TOML ``data`` (``path`` for messages;
    ``parameters`` override ``[parameters]`` entries by name)."""
    _check_table(data, path)
    kind = spec_kind(data, "simulation")
    if kind != "simulation":
        raise SpecError(
            f"this is a {kind!r} spec, not a simulation; 'plumbob simulate' needs a "
            'simulation spec (kind = "simulation", see docs/simulate.md)',
            path=path,
        )
    return _simulation(data, path, parameters)


def load_spec(path: str, *, parameters: Mapping[str, float | str] | None = None) -> Reading:
    """Read and build the TOML spec at ``path``; ``parameters`` override its
    ``[parameters]`` entries by name (a number, an expression, or a number with a
    length unit such as ``"30 cm"``)."""
    path = os.fspath(path)
    return read_checked(path, lambda: build_spec(_read_toml(path), path, parameters=parameters))


def load_simulation(path: str | Path, *,
                    parameters: Mapping[str, float | str] | None = None) -> SimulationSpec:
    """Read the simulation spec at ``path`` (``parameters`` as for :func:`load_spec`).

    Raises :class:`InputFileError` when the file is missing or unreadable, and
    :class:`SpecError` / :class:`DynamicsError` for bad contents.
    """
    path = os.fspath(path)
    return read_checked(
        path, lambda: parse_simulation(_read_toml(path), path, parameters=parameters))


def _check_table(data: Any, path: str | None) -> None:
    if not isinstance(data, dict):
        raise SpecError("a spec must be a TOML table", path=path)


def _simulation(data: dict, path: str | None,
                parameters: Mapping[str, float | str] | None) -> SimulationSpec:
    names = read_parameters(path, data.get("parameters", {}), parameters)
    return build_simulation(SpecContext(path, names), data)


def _shape(data: dict, path: str, parameters: Mapping[str, float | str] | None) -> Body:
    """The body of a shape spec: ``[shape]``, ``[parameters]``, then ``[[part]]`` or
    ``[[particle]]`` tables."""
    spec = SpecContext(path, {})
    spec.table(data, TOP_KEYS, None, what="top-level key")
    shape = data.get("shape", {})
    if not isinstance(shape, dict):
        raise spec.error(None, "[shape] must be a table")
    has_parts, has_particles = "part" in data, "particle" in data
    spec.table(shape, SHAPE_KEYS if has_particles else PARTS_SHAPE_KEYS, "shape")
    unit = shape.get("units", "m")
    if unit not in LENGTH_UNITS:
        raise spec.error(
            "shape.units", f"unknown unit {unit!r}; use one of {', '.join(LENGTH_UNITS)}"
        )
    scale = length_scale(unit)
    spec = SpecContext(path, read_parameters(path, data.get("parameters", {}), parameters, scale),
                       scale)
    if has_parts == has_particles:
        raise spec.error(
            None, "a spec needs [[part]] tables or [[particle]] tables (one kind, not both)"
        )
    if has_particles:
        body: Body = read_particles(spec, data["particle"], simulation=False).system
    else:
        body = build_parts(spec, shape, data["part"])
    expected = shape.get("kind")
    if expected is not None and expected != body.kind:
        raise spec.error("shape.kind", f"the parts make a {body.kind}, not a {expected}")
    return named(body, shape.get("name"))


def _read_toml(path: str) -> dict:
    """The parsed TOML of a spec file (the caller has checked it exists and holds bytes)."""
    size = os.path.getsize(path)
    if size > MAX_SPEC_BYTES:
        raise InputFileError(
            f"a spec is limited to {MAX_SPEC_BYTES >> 20} MiB; this one is {size} bytes",
            path=path,
        )
    with open(path, "rb") as handle:
        raw = handle.read()
    if not raw.strip():
        raise InputFileError(
            "the file is empty; a spec needs [[part]] or [[particle]] tables", path=path
        )
    try:
        return tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise InputFileError("not a text file (a TOML spec must be UTF-8)", path=path) from None
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(f"not valid TOML: {exc}", path=path) from None
