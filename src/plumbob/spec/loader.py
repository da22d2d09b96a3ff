"""TOML shape specs → bodies. The format is documented in ``docs/shapes.md``.

A spec has a ``[shape]`` table (name, units, density or material, thickness),
``[parameters]`` (numbers or whitelisted expressions, evaluated in order, each
may use the ones before), and either ``[[part]]`` tables — primitives placed
and combined with ``op = "add" | "subtract" | "intersect"`` — or
``[[particle]]`` tables (mass and position).
"""

from __future__ import annotations

import difflib
import os
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..bodies import primitives as prim
from ..bodies.base import Body, check_density
from ..bodies.csg import Assembly, Composite, difference, intersection, leaf_densities, union
from ..bodies.lamina import Lamina
from ..bodies.particles import ParticleSystem
from ..bodies.region import Region, Ring
from ..errors import InputFileError, PlumbobError, SpecError
from ..io import Reading
from ..massprops import rotation_matrix
from ..materials import material as lookup_material
from ..units import LENGTH_UNITS, length_scale
from .expr import Expression, parse

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["load_spec", "build_spec", "PRIMITIVES"]

MAX_SPEC_BYTES = 4 << 20
SHAPE_KEYS = {
    "name",
    "description",
    "kind",
    "units",
    "density",
    "material",
    "thickness",
    "source",
    "figure",
    "segments",
}
PLACEMENT_KEYS = {"at", "rotate", "mirror"}
PART_KEYS = {"type", "name", "op", "density", "material", "thickness"} | PLACEMENT_KEYS
PARTICLE_KEYS = {"name", "mass", "position", "velocity"}
TOP_KEYS = {"shape", "parameters", "part", "particle"}


@dataclass(frozen=True)
class _Spec:
    """Context for building one spec: names for expressions and the length scale."""

    path: str
    names: Mapping[str, float]
    scale: float

    def error(self, where: str, message: str) -> SpecError:
        return SpecError(f"{where}: {message}", path=self.path)

    def number(self, value: Any, where: str, length: bool = False) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise self.error(where, f"expected a number or an expression, not {value!r}")
        try:
            if isinstance(value, str):
                result = parse(value).evaluate(self.names)
                if np.ndim(result) != 0:
                    raise self.error(where, f"{value!r} must give a single number")
                result = float(result)
            else:
                result = float(value)
        except PlumbobError as exc:
            raise self.error(where, exc.message) from None
        if not np.isfinite(result):
            raise self.error(where, f"{value!r} is not a finite number")
        return result * (self.scale if length else 1.0)

    def points(
        self, value: Any, where: str, dims: tuple[int, ...] = (2,), length: bool = True
    ) -> np.ndarray:
        if not isinstance(value, list) or not value:
            raise self.error(where, "expected a list of points like [[0, 0], [1, 0], [0, 1]]")
        rows = []
        for i, row in enumerate(value):
            if not isinstance(row, list) or len(row) not in dims:
                raise self.error(
                    where, f"point {i + 1} must be a list of {' or '.join(map(str, dims))} numbers"
                )
            rows.append([self.number(v, f"{where}[{i + 1}]", length) for v in row])
        if len({len(r) for r in rows}) != 1:
            raise self.error(where, "all points must have the same number of coordinates")
        return np.array(rows)

    def vector(
        self, value: Any, where: str, dims: tuple[int, ...], length: bool = True
    ) -> np.ndarray:
        if not isinstance(value, list) or len(value) not in dims:
            raise self.error(where, f"expected a list of {' or '.join(map(str, dims))} numbers")
        return np.array([self.number(v, f"{where}[{i + 1}]", length) for i, v in enumerate(value)])


# ----------------------------------------------------------------- primitives
def _n(spec: _Spec, t: dict, key: str, where: str, length: bool = True) -> float:
    return spec.number(t[key], f"{where}.{key}", length)


def _angle(spec: _Spec, t: dict, key: str, where: str) -> float:
    return np.radians(spec.number(t[key], f"{where}.{key}"))


def _profile(spec: _Spec, t: dict, where: str) -> Region:
    table = t["profile"]
    if not isinstance(table, dict):
        raise spec.error(f"{where}.profile", "expected a table describing a 2D shape")
    body = (
        _build_group(spec, table, f"{where}.profile", want_dim=2)
        if "part" in table
        else _build_part(spec, table, f"{where}.profile", want_dim=2)
    )
    if isinstance(body, Lamina):
        return body.region
    if isinstance(body, Composite) and all(isinstance(p, Lamina) for p in body.parts):
        rings: list[Ring] = []
        for part, sign in zip(body.parts, body.signs):
            rings += [r if sign > 0 else r.reversed() for r in part.region.rings]
        return Region(tuple(rings))
    if hasattr(body, "region"):
        return body.region
    raise spec.error(
        f"{where}.profile", "the profile must be a plain 2D shape (no placement of the whole)"
    )


def _outline(spec: _Spec, t: dict, where: str) -> Lamina:
    vertices = spec.points(t["vertices"], f"{where}.vertices")
    bulges = None
    if "bulges" in t:
        if not isinstance(t["bulges"], list) or len(t["bulges"]) != len(vertices):
            raise spec.error(f"{where}.bulges", "give one bulge per edge (as many as vertices)")
        bulges = np.array([spec.number(b, f"{where}.bulges") for b in t["bulges"]])
    region = Region((Ring(vertices, bulges),))
    if region.moments().m0 < 0:
        region = Region((region.rings[0].reversed(),))
    return Lamina(region)


def _simple(build: Callable[..., Body], *keys: str, angles: tuple[str, ...] = ()):
    """A builder passing the named values, in order, to ``build``: lengths scaled by the
    spec's units, ``angles`` (degrees in the spec) in radians."""

    def builder(spec: _Spec, table: dict, where: str) -> Body:
        return build(*(_angle(spec, table, k, where) if k in angles else _n(spec, table, k, where)
                       for k in keys))

    return builder


# Each entry: (dimension, required keys, optional keys, builder(spec, table, where) -> Body)
PRIMITIVES: dict[str, tuple[int, set[str], set[str], Callable[[_Spec, dict, str], Body]]] = {
    "rectangle": (2, {"width", "height"}, {"centered"}, _simple(prim.rectangle, "width", "height")),
    "square": (2, {"side"}, set(), _simple(lambda a: prim.rectangle(a, a), "side")),
    "triangle": (2, {"vertices"}, set(),
                 lambda s, t, w: prim.polygon(s.points(t["vertices"], f"{w}.vertices"))),
    "polygon": (2, {"vertices"}, {"holes"}, lambda s, t, w: prim.polygon(
        s.points(t["vertices"], f"{w}.vertices"),
        [s.points(h, f"{w}.holes[{i + 1}]") for i, h in enumerate(t.get("holes", []))])),
    "outline": (2, {"vertices"}, {"bulges"}, _outline),
    "regular_polygon": (2, {"sides", "radius"}, set(), lambda s, t, w: prim.regular_polygon(
        s.number(t["sides"], f"{w}.sides"), _n(s, t, "radius", w))),
    "disc": (2, {"radius"}, set(), _simple(prim.disc, "radius")),
    "semicircle": (2, {"radius"}, set(), _simple(prim.semicircle, "radius")),
    "sector": (2, {"radius", "angle"}, set(), _simple(prim.sector, "radius", "angle", angles=("angle",))),
    "segment": (2, {"radius", "angle"}, set(),
                _simple(prim.circular_segment, "radius", "angle", angles=("angle",))),
    "annulus": (2, {"inner_radius", "outer_radius"}, set(),
                _simple(prim.annulus, "inner_radius", "outer_radius")),
    "box": (3, {"length", "width", "height"}, {"centered"},
            _simple(prim.box, "length", "width", "height")),
    "cube": (3, {"side"}, {"centered"}, _simple(lambda a: prim.box(a, a, a), "side")),
    "cylinder": (3, {"radius", "height"}, set(), _simple(prim.cylinder, "radius", "height")),
    "cone": (3, {"radius", "height"}, set(), _simple(prim.cone, "radius", "height")),
    "frustum": (3, {"bottom_radius", "top_radius", "height"}, set(),
                _simple(prim.frustum, "bottom_radius", "top_radius", "height")),
    "sphere": (3, {"radius"}, set(), _simple(prim.sphere, "radius")),
    "hemisphere": (3, {"radius"}, set(), _simple(prim.hemisphere, "radius")),
    "torus": (3, {"major_radius", "minor_radius"}, set(),
              _simple(prim.torus, "major_radius", "minor_radius")),
    "pyramid": (3, {"base", "height"}, {"apex"}, lambda s, t, w: prim.pyramid(
        s.points(t["base"], f"{w}.base"), _n(s, t, "height", w),
        s.vector(t["apex"], f"{w}.apex", (2,)) if "apex" in t else None)),
    "tetrahedron": (3, {"vertices"}, set(),
                    lambda s, t, w: prim.tetrahedron(*s.points(t["vertices"], f"{w}.vertices", (3,)))),
    "extrude": (3, {"profile", "height"}, set(),
                lambda s, t, w: prim.prism(_profile(s, t, w), _n(s, t, "height", w))),
    "revolve": (3, {"profile"}, set(), lambda s, t, w: prim.revolve(_profile(s, t, w))),
    "mesh": (3, {"file"}, {"units"}, lambda s, t, w: _mesh_file(s, t, w)),
}


def _mesh_file(spec: _Spec, t: dict, where: str) -> Body:
    from ..io import read

    name = t["file"]
    if not isinstance(name, str):
        raise spec.error(f"{where}.file", "expected a file name")
    path = os.path.join(os.path.dirname(os.path.abspath(spec.path)), name)
    if os.path.splitext(path)[1].lower() == ".toml":
        raise spec.error(f"{where}.file", "a mesh part must name a mesh file, not another spec")
    return read(path, units=t.get("units")).body


def _suggest(key: str, allowed: set[str]) -> str:
    close = difflib.get_close_matches(key, sorted(allowed), n=1)
    return f"; did you mean {close[0]!r}?" if close else f"; allowed: {', '.join(sorted(allowed))}"


def _check_keys(spec: _Spec, table: dict, allowed: set[str], where: str) -> None:
    for key in table:
        if key not in allowed:
            raise spec.error(where, f"unknown key {key!r}{_suggest(key, allowed)}")


def _placement(spec: _Spec, body: Body, table: dict, where: str) -> Body:
    dim = body.dim
    if not PLACEMENT_KEYS & set(table):
        return body
    matrix = np.eye(dim)
    if "mirror" in table:
        normal = spec.vector(table["mirror"], f"{where}.mirror", (dim,), length=False)
        if not np.linalg.norm(normal) > 0:
            raise spec.error(f"{where}.mirror", "the mirror's normal must not be zero")
        normal = normal / np.linalg.norm(normal)
        matrix = np.eye(dim) - 2 * np.outer(normal, normal)
    if "rotate" in table:
        matrix = _rotation(spec, table["rotate"], f"{where}.rotate", dim) @ matrix
    offset = spec.vector(table["at"], f"{where}.at", (dim,)) if "at" in table else np.zeros(dim)
    return body.transformed(matrix, offset)


def _rotation(spec: _Spec, value: Any, where: str, dim: int) -> np.ndarray:
    if dim == 2:
        if isinstance(value, dict):
            raise spec.error(where, "a 2D shape turns by an angle in degrees: rotate = 90")
        angle = np.radians(spec.number(value, where))
        return rotation_matrix([0, 0, 1], angle)[:2, :2]
    steps = value if isinstance(value, list) and value and isinstance(value[0], dict) else [value]
    matrix = np.eye(3)
    for i, step in enumerate(steps):
        if not isinstance(step, dict) or set(step) != {"axis", "angle"}:
            raise spec.error(
                where, "a 3D rotation is {axis = [x, y, z], angle = DEGREES} (or a list of them)"
            )
        axis = spec.vector(step["axis"], f"{where}[{i + 1}].axis", (3,), length=False)
        if not np.linalg.norm(axis) > 0:
            raise spec.error(where, "a rotation axis must not be zero")
        matrix = (
            rotation_matrix(axis, np.radians(spec.number(step["angle"], f"{where}.angle"))) @ matrix
        )
    return matrix


@dataclass(frozen=True)
class _Material:
    """Density settings inherited from the shape by its parts."""

    density: float | Expression | None = None
    thickness: float | None = None
    label: str | None = None


def _material(spec: _Spec, table: dict, where: str, inherited: _Material) -> _Material:
    density, label = inherited.density, inherited.label
    if "density" in table and "material" in table:
        raise spec.error(where, "give a density or a material, not both")
    if "material" in table:
        name = table["material"]
        if not isinstance(name, str):
            raise spec.error(f"{where}.material", "expected a material name")
        try:
            density, label = lookup_material(name).density, name
        except PlumbobError as exc:
            raise spec.error(f"{where}.material", exc.message) from None
    elif "density" in table:
        raw = table["density"]
        label = None
        if isinstance(raw, str):
            try:
                expression = parse(raw)
            except PlumbobError as exc:
                raise spec.error(f"{where}.density", exc.message) from None
            field_names = expression.names & {"x", "y", "z"}
            density = expression if field_names else spec.number(raw, f"{where}.density")
        else:
            density = spec.number(raw, f"{where}.density")
        if isinstance(density, float):
            try:
                check_density(density)
            except PlumbobError as exc:
                raise spec.error(f"{where}.density", exc.message) from None
    thickness = inherited.thickness
    if "thickness" in table:
        thickness = spec.number(table["thickness"], f"{where}.thickness", length=True)
        if not thickness > 0:
            raise spec.error(f"{where}.thickness", "a thickness must be positive")
    return _Material(density, thickness, label)


def _apply_material(spec: _Spec, body: Body, mat: _Material, where: str) -> Body:
    """A part's uniform density (a density field is applied after placement)."""
    from dataclasses import replace

    if mat.thickness is not None and body.dim != 2:
        raise spec.error(where, "a thickness applies only to a lamina (2D shape)")
    density = None if isinstance(mat.density, Expression) else mat.density
    if isinstance(body, Lamina):
        if mat.label is not None and mat.thickness is None:
            raise spec.error(
                where,
                f"a lamina of {mat.label} needs a thickness (m) to turn the "
                "material's kg/m³ into kg/m²",
            )
        return replace(body, density=density, thickness=mat.thickness)
    return body if density is None else body.with_default_density(density)


def _apply_field(spec: _Spec, body: Body, mat: _Material, where: str) -> Body:
    """A density field over ``body`` in the spec's frame (x, y, z after placement)."""
    from ..bodies.density_field import DensityField
    from ..bodies.graded import with_density_field

    scale = mat.thickness if (mat.thickness is not None and body.dim == 2) else 1.0
    try:
        field = DensityField.from_expression(mat.density, scale=scale, constants=dict(spec.names))
        return with_density_field(body, field)
    except SpecError:
        raise
    except PlumbobError as exc:
        raise spec.error(f"{where}.density", exc.message) from None


def _own_field(mat: _Material, inherited: _Material) -> bool:
    return isinstance(mat.density, Expression) and mat.density is not inherited.density


def _build_part(
    spec: _Spec,
    table: dict,
    where: str,
    want_dim: int | None = None,
    inherited: _Material = _Material(),
) -> Body:
    kind = table.get("type")
    if not isinstance(kind, str):
        raise spec.error(where, 'every part needs a type, e.g. type = "rectangle"')
    if kind not in PRIMITIVES:
        raise spec.error(f"{where}.type", f"unknown type {kind!r}{_suggest(kind, set(PRIMITIVES))}")
    dim, required, optional, build = PRIMITIVES[kind]
    if want_dim is not None and dim != want_dim:
        raise spec.error(where, f"a {kind} is {dim}D; a {want_dim}D shape is needed here")
    _check_keys(spec, table, PART_KEYS | required | optional, where)
    missing = sorted(required - set(table))
    if missing:
        raise spec.error(where, f"a {kind} needs {', '.join(missing)}")
    try:
        body = build(spec, table, where)
    except SpecError:
        raise
    except PlumbobError as exc:
        raise spec.error(where, exc.message) from None
    if table.get("centered"):
        box = body.mass_properties().center_of_mass
        body = body.translated(-box)
    mat = _material(spec, table, where, inherited)
    body = _placement(spec, _apply_material(spec, body, mat, where), table, where)
    return _apply_field(spec, body, mat, where) if _own_field(mat, inherited) else body


def _build_group(
    spec: _Spec,
    table: dict,
    where: str,
    want_dim: int | None = None,
    inherited: _Material = _Material(),
) -> Body:
    parts = table["part"]
    if not isinstance(parts, list) or not parts:
        raise spec.error(where, "[[part]] must be a list of tables")
    mat = _material(spec, table, where, inherited)
    built: list[tuple[str, Body, str]] = []
    for i, part in enumerate(parts):
        label = f"part {i + 1}" + (
            f" ({part['name']})" if isinstance(part, dict) and "name" in part else ""
        )
        if not isinstance(part, dict):
            raise spec.error(label, "expected a table")
        op = part.get("op", "add")
        if op not in ("add", "subtract", "intersect"):
            raise spec.error(f"{label}.op", f"unknown op {op!r}; use add, subtract or intersect")
        if i == 0 and op != "add":
            raise spec.error(label, 'the first part must be added (op = "add")')
        if "part" in part:
            _check_keys(spec, part, (PART_KEYS - {"type"}) | {"part"}, label)
            body = _build_group(spec, part, label, want_dim, mat)
        else:
            body = _build_part(spec, part, label, want_dim, mat)
        body = _named(body, part.get("name"))
        built.append((op, body, label))
    dims = {b.dim for _, b, _ in built}
    if len(dims) > 1:
        raise spec.error(where, "all parts must be 2D (a lamina) or all 3D (a solid)")
    body = _placement(spec, _combine(spec, built), table, where)
    return _apply_field(spec, body, mat, where) if _own_field(mat, inherited) else body


def _combine(spec: _Spec, built: list[tuple[str, Body, str]]) -> Body:
    if len(built) == 1:
        return built[0][1]
    try:
        if all(op == "add" for op, _, _ in built):
            result = union(*(b for _, b, _ in built))
            if len(leaf_densities(result)) > 1 and isinstance(result, Composite):
                return Assembly(result.parts)
            return result
        result = built[0][1]
        for op, body, label in built[1:]:
            if op == "add":
                result = union(result, body)
            elif op == "subtract":
                result = difference(result, _hole_material(spec, result, body, label))
            else:
                result = intersection(result, body)
        return result
    except SpecError:
        raise
    except PlumbobError as exc:
        raise spec.error("parts", exc.message) from None


def _hole_material(spec: _Spec, parent: Body, hole: Body, label: str) -> Body:
    """A removed part must weigh what it is cut from (a hole given no density takes the
    parent's in :func:`difference`)."""
    hole_density = leaf_densities(hole)
    if hole_density == {None} or hole_density == leaf_densities(parent):
        return hole
    raise spec.error(
        label,
        "a removed part must have the same density as the part it is cut "
        "from (give the density on [shape], or on neither part)",
    )


def _named(body: Body, name: object) -> Body:
    from dataclasses import fields, replace

    if isinstance(name, str) and "name" in {f.name for f in fields(body)}:
        return replace(body, name=name)
    return body


# --------------------------------------------------------------- particles
def _build_particles(spec: _Spec, particles: Any) -> ParticleSystem:
    if not isinstance(particles, list) or not particles:
        raise spec.error("particle", "[[particle]] must be a list of tables")
    masses, positions, velocities, names = [], [], [], []
    for i, p in enumerate(particles):
        where = f"particle {i + 1}"
        if not isinstance(p, dict):
            raise spec.error(where, "expected a table")
        _check_keys(spec, p, PARTICLE_KEYS, where)
        for key in ("mass", "position"):
            if key not in p:
                raise spec.error(where, f"a particle needs a {key}")
        mass = spec.number(p["mass"], f"{where}.mass")
        if not mass > 0:
            raise spec.error(f"{where}.mass", f"a particle's mass must be positive, not {mass:g}")
        masses.append(mass)
        positions.append(spec.vector(p["position"], f"{where}.position", (2, 3)))
        if "velocity" in p:
            velocities.append(spec.vector(p["velocity"], f"{where}.velocity", (2, 3), length=True))
        names.append(str(p.get("name", f"particle {i + 1}")))
    if len({len(x) for x in positions}) != 1:
        raise spec.error("particle", "all positions must have the same number of coordinates")
    if velocities and len(velocities) != len(masses):
        raise spec.error("particle", "give a velocity for every particle or for none")
    return ParticleSystem(
        np.array(masses),
        np.array(positions),
        np.array(velocities) if velocities else None,
        tuple(names),
    )


# --------------------------------------------------------------- top level
def _parameters(path: str, table: Any, scale: float) -> dict[str, float]:
    if not isinstance(table, dict):
        raise SpecError("[parameters] must be a table of name = value", path=path)
    names: dict[str, float] = {}
    for key, value in table.items():
        if key in ("x", "y", "z", "pi", "e"):
            raise SpecError(
                f"parameters.{key}: {key!r} is reserved; choose another name", path=path
            )
        names[key] = _Spec(path, names, 1.0).number(value, f"parameters.{key}")
    return names


def build_spec(data: dict, path: str = "<spec>") -> Reading:
    """Build the body a parsed spec describes."""
    if not isinstance(data, dict):
        raise SpecError("a spec must be a TOML table", path=path)
    for key in data:
        if key not in TOP_KEYS:
            raise SpecError(f"unknown top-level key {key!r}{_suggest(key, TOP_KEYS)}", path=path)
    shape = data.get("shape", {})
    if not isinstance(shape, dict):
        raise SpecError("[shape] must be a table", path=path)
    spec0 = _Spec(path, {}, 1.0)
    _check_keys(spec0, shape, SHAPE_KEYS, "shape")
    unit = shape.get("units", "m")
    if unit not in LENGTH_UNITS:
        raise spec0.error(
            "shape.units", f"unknown unit {unit!r}; use one of {', '.join(LENGTH_UNITS)}"
        )
    scale = length_scale(unit)
    names = _parameters(path, data.get("parameters", {}), scale)
    spec = _Spec(path, names, scale)
    has_parts, has_particles = "part" in data, "particle" in data
    if has_parts == has_particles:
        raise SpecError(
            "a spec needs [[part]] tables or [[particle]] tables (one kind, not both)", path=path
        )
    if has_particles:
        _check_keys(
            spec, shape, {"name", "description", "kind", "units", "source", "figure"}, "shape"
        )
        body: Body = _build_particles(spec, data["particle"])
    else:
        inherited = _material(spec, shape, "shape", _Material())
        body = _build_group(spec, {"part": data["part"]}, "shape", None, inherited)
        if isinstance(inherited.density, Expression):
            body = _apply_field(spec, body, inherited, "shape")
    expected = shape.get("kind")
    if expected is not None and expected != body.kind:
        raise spec.error("shape.kind", f"the parts make a {body.kind}, not a {expected}")
    body = _named(body, shape.get("name"))
    return Reading(body, (), path)


def load_spec(path: str) -> Reading:
    """Read and build the TOML spec at ``path``."""
    try:
        size = os.path.getsize(path)
        if size > MAX_SPEC_BYTES:
            raise InputFileError(
                f"a spec is limited to {MAX_SPEC_BYTES >> 20} MiB; this one is {size} bytes",
                path=path,
            )
        with open(path, "rb") as handle:
            raw = handle.read()
    except OSError as exc:
        raise InputFileError(f"cannot read: {exc.strerror}", path=path) from None
    if not raw.strip():
        raise InputFileError(
            "the file is empty; a spec needs [[part]] or [[particle]] tables", path=path
        )
    try:
        data = tomllib.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise InputFileError("not a text file (a TOML spec must be UTF-8)", path=path) from None
    except tomllib.TOMLDecodeError as exc:
        raise SpecError(f"not valid TOML: {exc}", path=path) from None
    if data.get("kind") == "simulation":
        # A simulation spec (docs/simulate.md) also describes a particle system at t = 0.
        from ..dynamics.spec import parse_simulation

        simulation = parse_simulation(data, path)
        return Reading(simulation.model.system, (), path)
    return build_spec(data, path)
