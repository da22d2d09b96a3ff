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
import re
import sys
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from ..bodies.base import Body
from ..bodies.csg import DEFAULT_SEGMENTS
from ..errors import InputFileError, LimitError, SpecError
from ..files import read_bytes
from ..formats import read_checked
from ..limits import MAX_SEGMENTS, MAX_SPEC_NESTING, check_count
from ..reading import Reading
from ..units import length_scale
from .loads import read_extendables, read_loads
from .particles import MOTION_KEYS, read_particles
from .parts import MATERIAL_KEYS, build_parts, named
from .parts import MESH_NOTICE as _MESH_NOTICE
from .simulation import SIMULATION_KEYS, SimulationSpec, build_simulation
from .values import LoadOptions, SpecContext, read_parameters, shown

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["load_spec", "build_spec", "spec_parameters", "load_simulation", "parse_simulation",
           "spec_kind"]

MAX_SPEC_BYTES = 8 << 20
#: the top-level keys of a shape spec
TOP_KEYS = {"kind", "shape", "parameters", "part", "particle", "load", "extendable"}
#: the keys of [shape] in a spec of particles
SHAPE_KEYS = {"name", "description", "kind", "units", "source", "figure"}
#: the keys of [shape] in a spec of parts ("segments": per turn, for faceted booleans)
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
               parameters: Mapping[str, float | str] | None = None, units: str | None = None,
               repair: bool = False, allow_outside_files: bool = False,
               units_override: bool = False) -> Reading:
    """The body a parsed spec describes: a shape's body, or a simulation's particles
    at t = 0, with the notices a user should see.

    ``parameters`` override ``[parameters]`` entries by name
    (:func:`~.values.read_parameters`); ``units``, ``repair`` and
    ``allow_outside_files`` are the caller's load options (:class:`~.values.LoadOptions`,
    the rules in ``docs/shapes.md``): an option that cannot apply is an error or a
    notice, never ignored."""
    options = LoadOptions(parameters, units, repair, allow_outside_files, units_override)
    _check_table(data, path)
    kind = spec_kind(data, "shape")
    if kind == "simulation":
        if units is not None:
            raise SpecError(f"units {units!r} (--units) do not apply: a simulation spec is in "
                            "metres, kilograms and seconds", path=path)
        notices = ("repair: a simulation spec has no mesh files to repair",) if repair else ()
        return Reading(_simulation(data, path, options).model.system, notices, path)
    if kind != "shape":
        raise SpecError(
            f'kind: a spec is a "shape" or a "simulation", not {kind!r} (the kind of body '
            "a shape makes, such as lamina or solid, goes in [shape] kind)",
            path=path,
        )
    spec = _shape_context(data, path, options)
    body = _shape(data, spec)
    if repair and not any(n.startswith(_MESH_NOTICE) for n in spec.notices):
        spec.notices.append("repair: the spec reads no mesh files; nothing to repair")
    loads = read_loads(spec, data["load"], body.dim) if "load" in data else ()
    extendables = (read_extendables(spec, data["extendable"], body.dim)
                   if "extendable" in data else ())
    return Reading(body, tuple(dict.fromkeys(spec.notices)), path, spec.unit, loads,
                   extendables)


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
    return _simulation(data, path, LoadOptions(parameters))


def load_spec(path: str, *, parameters: Mapping[str, float | str] | None = None,
              units: str | None = None, repair: bool = False,
              allow_outside_files: bool = False, units_override: bool = False) -> Reading:
    """Read and build the TOML spec at ``path`` (the options as for :func:`build_spec`);
    ``parameters`` override its ``[parameters]`` entries by name (a number, an
    expression, or a number with a length unit such as ``"30 cm"``)."""
    path = os.fspath(path)
    return read_checked(path, lambda: build_spec(
        _read_toml(path), path, parameters=parameters, units=units, repair=repair,
        allow_outside_files=allow_outside_files, units_override=units_override))


def spec_parameters(path: str) -> dict[str, float]:
    """The values of the spec's ``[parameters]``, in order (empty when it has none)."""
    path = os.fspath(path)
    return read_checked(path, lambda: read_parameters(
        path, _read_toml(path).get("parameters", {})))


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
    """A parsed spec is a table nested no deeper than plumbob's limit (a dict built by
    a caller is checked as a file is)."""
    if not isinstance(data, dict):
        raise SpecError("a spec must be a TOML table", path=path)
    if nesting_depth(data) > MAX_SPEC_NESTING:
        raise _too_deep(path)


def _simulation(data: dict, path: str | None, options: LoadOptions) -> SimulationSpec:
    names = read_parameters(path, data.get("parameters", {}), options.parameters)
    return build_simulation(SpecContext(path, names, options=options), data)


def _shape_context(data: dict, path: str, options: LoadOptions) -> SpecContext:
    """The context of a shape spec: its unit (from ``[shape] units``, else the
    caller's, else metres) and its parameters."""
    spec = SpecContext(path, {})
    spec.table(data, TOP_KEYS, None, what="top-level key")
    shape = data.get("shape", {})
    if not isinstance(shape, dict):
        raise spec.error(None, f"[shape] must be a table, not {shown(shape)}")
    spec.table(shape, SHAPE_KEYS if "particle" in data else PARTS_SHAPE_KEYS, "shape")
    unit = spec.unit_name(shape["units"], "shape.units") if "units" in shape else None
    notices: list[str] = []
    if options.units is not None:
        asked = spec.unit_name(options.units, "units (--units)")
        if unit is None:
            unit = asked
            notices.append(f"units: {asked} (as asked; the spec sets none)")
        elif asked == unit:
            notices.append(f'units: the spec already says units = "{unit}"; --units {asked} '
                           "changes nothing")
        elif options.units_override:
            notices.append(f'units: the spec says units = "{unit}"; {asked} used as '
                           "--units-override asks")
            unit = asked
        else:
            raise spec.error("shape.units", f'the spec says units = "{unit}", so the units '
                             f"asked for ({asked}, --units) do not apply: remove the option, "
                             "pass --units-override to use them anyway, or change the spec")
    scale = length_scale(unit)
    names = read_parameters(path, data.get("parameters", {}), options.parameters, scale)
    segments = DEFAULT_SEGMENTS
    if "segments" in shape:
        segments = spec.number(shape["segments"], "shape.segments")
        if not segments >= 8:
            raise spec.error("shape.segments", f"at least 8 segments per turn, not {segments:g}")
        segments = check_count("shape.segments", segments, MAX_SEGMENTS, path=path,
                               hint="plumbob.limits.MAX_SEGMENTS")
    return SpecContext(path, names, scale, unit, options, notices, segments)


def _shape(data: dict, spec: SpecContext) -> Body:
    """The body of a shape spec: ``[[part]]`` or ``[[particle]]`` tables, with the
    material, kind and name ``[shape]`` gives them."""
    shape = data.get("shape", {})
    has_parts, has_particles = "part" in data, "particle" in data
    if has_parts == has_particles:
        raise spec.error(
            None, "a spec needs [[part]] tables or [[particle]] tables (one kind, not both)"
        )
    if has_particles:
        body: Body = read_particles(spec, data["particle"], simulation=False).system
    else:
        body = build_parts(spec, shape, data["part"])
    if "kind" in shape:
        expected = spec.text(shape["kind"], "shape.kind", ("lamina", "solid", "assembly",
                                                            "particles"), what="kind of body")
        if expected != body.kind:
            raise spec.error("shape.kind", f"the parts make a {body.kind}, not a {expected}")
    for key in ("name", "description", "source", "figure"):
        if key in shape:
            spec.text(shape[key], f"shape.{key}")
    return named(body, shape.get("name"))


def count_parts(parts: Any) -> int:
    """How many ``[[part]]`` tables ``parts`` holds, groups' parts included, counted
    with a list of what is left to visit (no recursion, nothing built).

    >>> count_parts([{"type": "disc"}, {"part": [{"type": "disc"}, {"type": "box"}]}])
    4
    """
    count, stack = 0, [parts]
    while stack:
        value = stack.pop()
        if isinstance(value, list):
            stack.extend(value)
        elif isinstance(value, dict):
            count += 1
            if "part" in value:
                stack.append(value["part"])
    return count


def _read_toml(path: str) -> dict:
    """The parsed TOML of a spec file: a regular file of at most
    :data:`MAX_SPEC_BYTES`, nested at most :data:`~plumbob.limits.MAX_SPEC_NESTING` deep."""
    raw = read_bytes(path, MAX_SPEC_BYTES)
    if not raw.strip():
        raise InputFileError(
            "the file is empty; a spec needs [[part]] or [[particle]] tables", path=path
        )
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        raise InputFileError("not a text file (a TOML spec must be UTF-8)", path=path) from None
    # Parts and particles are not counted: each is written out, so MAX_SPEC_BYTES bounds
    # their number and the work of parsing and building them (90,000 cubes are ~6 MB).
    # a table header naming a path deeper than the limit ([[part.part.part…]]) is
    # refused before parsing, as the parsed nesting would be
    if any(header.count(".") >= MAX_SPEC_NESTING for header in _HEADER.findall(text)):
        raise _too_deep(path)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(f"not valid TOML: {exc}", path=path) from None
    except RecursionError:  # tomllib recurses into nested arrays and inline tables
        raise _too_deep(path) from None
    except ValueError as exc:  # an integer of over 4,300 digits (Python's int-string limit)
        raise SpecError(f"not a usable TOML value: {str(exc).split(';')[0]}", path=path) from None
    return data


#: a table header's dotted path: ``[a.b]`` or ``[[part.part]]`` at the start of a line
_HEADER = re.compile(r"^[ \t]*\[\[?([^\]\n]*)", re.MULTILINE)


def _too_deep(path: str | None) -> LimitError:
    return LimitError(f"the spec nests tables and arrays over {MAX_SPEC_NESTING} deep, plumbob's "
                      "limit (plumbob.limits.MAX_SPEC_NESTING)", path=path)


def nesting_depth(data: Any) -> int:
    """How deep tables and arrays nest in ``data`` (a scalar is 0), found with a list
    of what is left to visit, not by recursion; it stops counting once past
    :data:`~plumbob.limits.MAX_SPEC_NESTING`.

    >>> nesting_depth({"part": [{"vertices": [[0, 0], [1, 0]]}]}), nesting_depth(3)
    (5, 0)
    """
    deepest = 0
    stack = [(data, 1)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, dict):
            value = list(value.values())
        elif not isinstance(value, list):
            continue
        deepest = max(deepest, depth)
        if depth > MAX_SPEC_NESTING:
            break
        stack.extend((item, depth + 1) for item in value if isinstance(item, (dict, list)))
    return deepest
