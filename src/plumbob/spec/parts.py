"""The ``[[part]]`` tables of a shape spec: primitives placed, given a density and
combined (``op = "add" | "subtract" | "intersect"``) into one body.

The format is documented in ``docs/shapes.md``; :func:`build_parts` is the entry.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from ..bodies import primitives as prim
from ..bodies.base import Body
from ..bodies.csg import as_assembly, difference, intersection, leaf_densities, union
from ..bodies.lamina import Lamina
from ..bodies.region import Region, Ring
from ..bodies.validity import check_region
from ..errors import GeometryError
from ..expr import Expression, parse
from ..formats import UNITLESS
from ..formats import read as read_file
from ..massprops import rotation_matrix
from ..materials import check_density
from ..materials import material as lookup_material
from ..units import UNITS_ASSUMED
from .values import SpecContext, shown

__all__ = ["build_parts", "named", "spec_file", "PRIMITIVES", "PART_KEYS", "MATERIAL_KEYS",
           "MESH_NOTICE"]

PLACEMENT_KEYS = {"at", "rotate", "mirror"}
#: what a part, or the [shape] table for all its parts, may say of their material
MATERIAL_KEYS = {"density", "material", "thickness"}
#: a part as printed: walls ``shell`` thick, the inside at ``infill`` (bodies.printed)
PRINT_KEYS = {"shell", "infill"}
PART_KEYS = {"type", "name", "op"} | MATERIAL_KEYS | PLACEMENT_KEYS | PRINT_KEYS


# ----------------------------------------------------------------- primitives
def _n(spec: SpecContext, t: dict, key: str, where: str, length: bool = True) -> float:
    return spec.number(t[key], f"{where}.{key}", length)


def _angle(spec: SpecContext, t: dict, key: str, where: str) -> float:
    return np.radians(spec.number(t[key], f"{where}.{key}"))


def _profile(spec: SpecContext, t: dict, where: str) -> Region:
    table = t["profile"]
    if not isinstance(table, dict):
        raise spec.error(f"{where}.profile", "expected a table describing a 2D shape")
    body = (
        _build_group(spec, table, f"{where}.profile", want_dim=2)
        if "part" in table
        else _build_part(spec, table, f"{where}.profile", want_dim=2)
    )
    try:
        return body.exact_region()
    except GeometryError:
        raise spec.error(
            f"{where}.profile", "the profile must be a plain 2D shape (no placement of the whole)"
        ) from None


def _outline(spec: SpecContext, t: dict, where: str) -> Lamina:
    vertices = spec.points(t["vertices"], f"{where}.vertices")
    bulges = None
    if "bulges" in t:
        if not isinstance(t["bulges"], list) or len(t["bulges"]) != len(vertices):
            raise spec.error(f"{where}.bulges", "give one bulge per edge (as many as vertices)")
        bulges = np.array([spec.number(b, f"{where}.bulges") for b in t["bulges"]])
    region = Region((Ring(vertices, bulges),))
    check_region(region)  # as outline files are: a bow-tie would integrate to a wrong area
    if region.moments().m0 < 0:
        region = Region((region.rings[0].reversed(),))
    return Lamina(region)


def _list(spec: SpecContext, t: dict, key: str, where: str) -> list:
    """``t[key]`` (default empty) as an array, or an error naming it."""
    value = t.get(key, [])
    if not isinstance(value, list):
        raise spec.error(f"{where}.{key}", f"expected an array, not {shown(value)}")
    return value


def _simple(build: Callable[..., Body], *keys: str, angles: tuple[str, ...] = ()):
    """A builder passing the named values, in order, to ``build``: lengths scaled by the
    spec's units, ``angles`` (degrees in the spec) in radians."""

    def builder(spec: SpecContext, table: dict, where: str) -> Body:
        return build(*(_angle(spec, table, k, where) if k in angles else _n(spec, table, k, where)
                       for k in keys))

    return builder


# Each entry: (dimension, required keys, optional keys, builder(spec, table, where) -> Body)
PRIMITIVES: dict[str, tuple[int, set[str], set[str], Callable[[SpecContext, dict, str], Body]]] = {
    "rectangle": (2, {"width", "height"}, {"centered"}, _simple(prim.rectangle, "width", "height")),
    "square": (2, {"side"}, set(), _simple(lambda a: prim.rectangle(a, a), "side")),
    "triangle": (2, {"vertices"}, set(),
                 lambda s, t, w: prim.polygon(s.points(t["vertices"], f"{w}.vertices"))),
    "polygon": (2, {"vertices"}, {"holes"}, lambda s, t, w: prim.polygon(
        s.points(t["vertices"], f"{w}.vertices"),
        [s.points(h, f"{w}.holes[{i + 1}]") for i, h in enumerate(_list(s, t, "holes", w))])),
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
    "step": (3, {"file"}, {"units", "materials"}, lambda s, t, w: _step_file(s, t, w)),
}


#: how the notices of a mesh file read for a spec begin
MESH_NOTICE = "mesh "


def _mesh_file(spec: SpecContext, t: dict, where: str) -> Body:
    """A mesh file in the spec's folder, read by :mod:`plumbob.formats` (its errors name it).

    Its unit, first found first: the part's ``units``; the unit the file declares
    (3MF); the spec's unit (``[shape] units``, or the caller's); else metres, said in
    a notice."""
    name = spec.text(t["file"], f"{where}.file", what="a file name")
    path = spec_file(spec, name, f"{where}.file")
    if os.path.splitext(path)[1].lower() == ".toml":
        raise spec.error(f"{where}.file", "a mesh part must name a mesh file, not another spec")
    repair = spec.options.repair
    if "units" in t:
        # the part's own units: the spec's author overrides what the file declares
        reading = read_file(path, units=spec.unit_name(t["units"], f"{where}.units"),
                            repair=repair, units_override=True)
    else:
        # a file that states no unit is in the spec's unit, as every length of the spec: a
        # format that cannot state one is read in it at once, another read again if it did not
        units = spec.unit if os.path.splitext(path)[1].lower() in UNITLESS else None
        reading = read_file(path, units=units, repair=repair)
        if reading.units_assumed and spec.unit is not None:
            units = spec.unit
            reading = read_file(path, units=units, repair=repair)
        if units is not None:
            reading = replace(reading, notices=(f"units: {units} (the spec's)",) + reading.notices)
        elif reading.units_assumed:
            reading = replace(reading, notices=tuple(
                "units: none in the file or the spec; metres assumed (give units in [shape] "
                "or on the part)" if n == UNITS_ASSUMED else n for n in reading.notices))
    spec.notices.extend(f"{MESH_NOTICE}{name}: {notice}" for notice in reading.notices)
    if repair and not reading.notices:
        spec.notices.append(f"{MESH_NOTICE}{name}: nothing to repair")
    from ..formats.parts import with_file_materials

    return with_file_materials(reading).body  # a 3MF's materials, as plumbob.read gives them


def _step_file(spec: SpecContext, t: dict, where: str) -> Body:
    """A STEP (IGES, BREP) file in the spec's folder, its parts given materials by
    ``materials = { "base" = "steel", "post*" = "aluminium" }`` (names or globs; a
    density in kg/m³ also serves). Every part needs one, unless the part's own
    ``material`` or ``density`` gives the rest theirs."""
    from ..formats.parts import CAD_SUFFIXES, require_part_densities, with_part_materials

    name = spec.text(t["file"], f"{where}.file", what="a file name")
    path = spec_file(spec, name, f"{where}.file")
    if not path.lower().endswith(CAD_SUFFIXES):
        raise spec.error(f"{where}.file", f"a step part must name a CAD file ({', '.join(CAD_SUFFIXES)})")
    units = spec.unit_name(t["units"], f"{where}.units") if "units" in t else None
    reading = read_file(path, units=units)
    materials = t.get("materials", {})
    if not isinstance(materials, dict) or not all(isinstance(v, (str, int, float))
                                                  for v in materials.values()):
        raise spec.error(f"{where}.materials", 'expected a table of part names and materials, '
                         'e.g. materials = { "base" = "steel", "post*" = "aluminium" }')
    if materials:
        reading = with_part_materials(reading, {k: str(v) for k, v in materials.items()},
                                      f"{where}.materials")
    if not MATERIAL_KEYS & set(t):
        reading = require_part_densities(reading, f"{where}.materials")
    spec.notices.extend(f"{MESH_NOTICE}{name}: {notice}" for notice in reading.notices)
    if reading.materials:
        spec.notices.append(f"{MESH_NOTICE}{name}: materials: " + ", ".join(
            f"{part} = {material}" for part, material in reading.materials))
    return reading.body


def spec_file(spec: SpecContext, name: str, where: str) -> str:
    """The path of a file a spec names: in the spec's folder or below it. A name that
    is absolute or climbs out (``..``, or a link leading out) is refused unless the
    caller allows it (``allow_outside_files``, ``--allow-outside-files``): a spec from
    elsewhere must not read any file the user can."""
    if any(ord(c) < 32 or ord(c) == 127 for c in name):
        raise spec.error(where, f"{name!r} holds a control character; name a file plainly")
    folder = os.path.dirname(os.path.abspath(spec.path or "."))
    path = os.path.join(folder, name)
    if spec.options.allow_outside_files:
        return path
    inside = os.path.realpath(folder)
    target = os.path.realpath(path)
    if os.path.isabs(name) or os.path.commonpath([inside, target]) != inside:
        raise spec.error(where, f"{name!r} is outside the spec's folder; a spec reads files "
                         "only in its folder or below it (allow others with --allow-outside-"
                         "files, or allow_outside_files=True)")
    return path


def _placement(spec: SpecContext, body: Body, table: dict, where: str) -> Body:
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


def _rotation(spec: SpecContext, value: Any, where: str, dim: int) -> np.ndarray:
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


def _material(spec: SpecContext, table: dict, where: str, inherited: _Material) -> _Material:
    density, label = inherited.density, inherited.label
    if "density" in table and "material" in table:
        raise spec.error(where, "give a density or a material, not both")
    if "material" in table:
        name = spec.text(table["material"], f"{where}.material", what="a material name")
        with spec.at(f"{where}.material"):
            density, label = lookup_material(name).density, name
    elif "density" in table:
        raw = table["density"]
        label = None
        if isinstance(raw, str):
            with spec.at(f"{where}.density"):
                expression = parse(raw)
            field_names = expression.names & {"x", "y", "z"}
            density = expression if field_names else spec.number(raw, f"{where}.density")
        else:
            density = spec.number(raw, f"{where}.density")
        if isinstance(density, float):
            with spec.at(f"{where}.density"):
                check_density(density)
    thickness = inherited.thickness
    if "thickness" in table:
        thickness = spec.number(table["thickness"], f"{where}.thickness", length=True)
        if not thickness > 0:
            raise spec.error(f"{where}.thickness", "a thickness must be positive")
    return _Material(density, thickness, label)


def _apply_material(spec: SpecContext, body: Body, mat: _Material, where: str) -> Body:
    """A part's uniform density (a density field is applied after placement)."""
    if mat.thickness is not None and body.dim != 2:
        raise spec.error(where, "a thickness applies only to a lamina (2D shape)")
    density = None if isinstance(mat.density, Expression) else mat.density
    if body.dim == 2 and mat.label is not None and mat.thickness is None:
        raise spec.error(
            where,
            f"a lamina of {mat.label} needs a thickness (m) to turn the "
            "material's kg/m³ into kg/m²",
        )
    return body.with_material(density, mat.thickness)


def _apply_field(spec: SpecContext, body: Body, mat: _Material, where: str) -> Body:
    """A density field over ``body`` in the spec's frame (x, y, z after placement)."""
    from ..bodies.density_field import DensityField
    from ..bodies.graded import with_density_field

    scale = mat.thickness if (mat.thickness is not None and body.dim == 2) else 1.0
    with spec.at(f"{where}.density"):
        field = DensityField.from_expression(mat.density, scale=scale, constants=dict(spec.names))
        field = replace(field, path=spec.path, place=f"{where}.density")
        return with_density_field(body, field)


def _own_field(mat: _Material, inherited: _Material) -> bool:
    return isinstance(mat.density, Expression) and mat.density is not inherited.density


def _build_part(
    spec: SpecContext,
    table: dict,
    where: str,
    want_dim: int | None = None,
    inherited: _Material = _Material(),
) -> Body:
    if "type" not in table:
        raise spec.error(where, 'every part needs a type, e.g. type = "rectangle"')
    kind = spec.text(table["type"], f"{where}.type", PRIMITIVES, what="type")
    dim, required, optional, build = PRIMITIVES[kind]
    if want_dim is not None and dim != want_dim:
        raise spec.error(where, f"a {kind} is {dim}D; a {want_dim}D shape is needed here")
    spec.table(table, PART_KEYS | required | optional, where)
    missing = sorted(required - set(table))
    if missing:
        raise spec.error(where, f"a {kind} needs {', '.join(missing)}")
    with spec.at(where):
        body = build(spec, table, where)
    if "centered" in table and spec.flag(table["centered"], f"{where}.centered"):
        box = body.mass_properties().center_of_mass
        body = body.translated(-box)
    mat = _material(spec, table, where, inherited)
    body = _placement(spec, _apply_material(spec, body, mat, where), table, where)
    body = _apply_field(spec, body, mat, where) if _own_field(mat, inherited) else body
    return _printed(spec, body, table, where) if PRINT_KEYS & set(table) else body


def _printed(spec: SpecContext, body: Body, table: dict, where: str) -> Body:
    """A part with ``shell`` (a length) and ``infill`` (0.2 or "20%"): the part as printed."""
    from ..bodies.printed import parse_fraction, printed

    if not PRINT_KEYS <= set(table):
        raise spec.error(where, 'give both shell (the wall thickness) and infill (0.2 or "20%")')
    raw = table["infill"]
    with spec.at(f"{where}.infill"):
        infill = parse_fraction(raw) if isinstance(raw, str) and raw.strip().endswith("%") \
            else spec.number(raw, f"{where}.infill")
    shell = spec.number(table["shell"], f"{where}.shell", length=True)
    with spec.at(where):
        return printed(body, shell, infill)


def _build_group(
    spec: SpecContext,
    table: dict,
    where: str,
    want_dim: int | None = None,
    inherited: _Material = _Material(),
) -> Body:
    parts = table["part"]
    if not isinstance(parts, list) or not parts:
        raise spec.error(where, f"[[part]] must be a list of tables, not {shown(parts)}")
    mat = _material(spec, table, where, inherited)
    built: list[tuple[str, Body, str]] = []
    for i, part in enumerate(parts):
        label = f"part {i + 1}"
        if not isinstance(part, dict):
            raise spec.error(label, f"expected a table, not {shown(part)}")
        if "name" in part:
            label += f" ({spec.text(part['name'], f'{label}.name', what='a name')})"
        op = spec.text(part.get("op", "add"), f"{label}.op", ("add", "subtract", "intersect"),
                       what="op")
        if i == 0 and op != "add":
            raise spec.error(label, 'the first part must be added (op = "add")')
        if "part" in part:
            spec.table(part, (PART_KEYS - {"type"}) | {"part"}, label)
            body = _build_group(spec, part, label, want_dim, mat)
        else:
            body = _build_part(spec, part, label, want_dim, mat)
        body = named(body, part.get("name"))
        built.append((op, body, label))
    dims = {b.dim for _, b, _ in built}
    if len(dims) > 1:
        raise spec.error(where, "all parts must be 2D (a lamina) or all 3D (a solid)")
    body = _placement(spec, _combine(spec, built), table, where)
    return _apply_field(spec, body, mat, where) if _own_field(mat, inherited) else body


def _combine(spec: SpecContext, built: list[tuple[str, Body, str]]) -> Body:
    if len(built) == 1:
        return built[0][1]
    if all(op == "add" for op, _, _ in built):
        with spec.at("parts"):
            return as_assembly(union(*(b for _, b, _ in built), segments=spec.segments))
    # each run of one op is one boolean: a run of holes is cut in one pass; an error
    # names the run's parts ("part 2 (subtract): the difference is empty ...")
    result = built[0][1]
    start = 1
    while start < len(built):
        op = built[start][0]
        end = start
        while end < len(built) and built[end][0] == op:
            end += 1
        run = built[start:end]
        place = run[0][2] if len(run) == 1 else f"{run[0][2]} to {run[-1][2]}"
        with spec.at(f"{place} ({op})"):
            result = _apply(spec, op, result, run)
        start = end
    return result


def _apply(spec: SpecContext, op: str, result: Body, run: list[tuple[str, Body, str]]) -> Body:
    """``result`` with one run of parts of one ``op`` added, removed or intersected."""
    bodies = [body for _, body, _ in run]
    if op == "add":
        return union(result, *bodies, segments=spec.segments)
    if op == "subtract":
        return difference(result, *(_hole_material(spec, result, body, label)
                                    for _, body, label in run), segments=spec.segments)
    return intersection(result, *bodies, segments=spec.segments)


def _hole_material(spec: SpecContext, parent: Body, hole: Body, label: str) -> Body:
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


def named(body: Body, name: object) -> Body:
    """``body`` carrying the spec's ``name`` for reports, when its kind has one."""
    if isinstance(name, str) and "name" in {f.name for f in fields(body)}:
        return replace(body, name=name)
    return body




def build_parts(spec: SpecContext, shape: dict, parts: Any) -> Body:
    """The body the ``[[part]]`` tables make, with the material ``[shape]`` gives them
    all (a density field on ``[shape]`` is laid over the whole, in the spec's frame)."""
    inherited = _material(spec, shape, "shape", _Material())
    body = _build_group(spec, {"part": parts}, "shape", None, inherited)
    if isinstance(inherited.density, Expression):
        body = _apply_field(spec, body, inherited, "shape")
    return body
