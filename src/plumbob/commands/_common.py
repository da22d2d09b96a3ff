"""What the commands share: argument types, reading the body, the JSON writer.

Every command module imports from here and from the library, never from another
command module. Only numpy and plumbob's reader load at import; the stability,
energy and dynamics code load when a command runs.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Mapping
from typing import Any

from ..errors import ArgumentError, DynamicsError, PlumbobError, SpecError
from ..loading import read
from ..reading import Reading
from ..results import jsonable
from ..units import SEED_GRAVITY, length_scale
from ._notices import default_down, flush_notices, oriented, print_notices

__all__ = [
    "number",
    "positive",
    "non_negative",
    "length",
    "count",
    "parse_vector",
    "material_name",
    "direction",
    "tilt_limit",
    "require_finite",
    "add_report_units_argument",
    "report_units",
    "number_option",
    "add_body_arguments",
    "assignment",
    "parameter_overrides",
    "add_stability_arguments",
    "add_orientation_arguments",
    "pose_down",
    "add_load_arguments",
    "force_option",
    "hang_option",
    "option_loads",
    "requirement",
    "load_body",
    "open_body",
    "print_notices",
    "flush_notices",
    "default_down",
    "header",
    "dump_json",
    "print_json",
]


# ------------------------------------------------------------ argument types
def number(text: str) -> float:
    """An argparse type: a finite number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"not a finite number: {text!r}")
    return value


def positive(text: str) -> float:
    """An argparse type: a positive finite number."""
    value = number(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"must be positive, not {text}")
    return value


def count(text: str) -> int:
    """A whole number of at least 1 (people in a crew, worker processes)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, not {value}")
    return value


def non_negative(text: str) -> float:
    """An argparse type: a finite number ≥ 0."""
    value = number(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must not be negative, not {text}")
    return value


def length(text: str) -> float:
    """An argparse type: a length ≥ 0 in metres, or with a unit (``3mm``, ``0.5 in``), read
    by :func:`plumbob.units.parse_length`."""
    from ..units import parse_length

    try:
        value = parse_length(text)
    except PlumbobError as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite length, not {text}")
    if value < 0:
        raise argparse.ArgumentTypeError(f"must not be negative, not {text}")
    return value


def parse_vector(text: str, dims: tuple[int, ...] = (2, 3)) -> list[float]:
    """'X,Y[,Z]' → floats (for argparse ``type=``)."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected numbers separated by commas, not {text!r}"
        ) from None
    if len(values) not in dims:
        raise argparse.ArgumentTypeError(
            f"expected {' or '.join(map(str, dims))} numbers, not {text!r}"
        )
    if not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected finite numbers, not {text!r}")
    return values


def direction(text: str) -> list[float]:
    """An argparse type: 'X,Y[,Z]', a direction (``--down``): finite and not zero."""
    values = parse_vector(text)
    if not any(values):
        raise argparse.ArgumentTypeError(f"a direction must not be the zero vector: {text!r}")
    return values


def material_name(text: str) -> str:
    """An argparse type: a material name, not empty (``--material ''`` is a mistake,
    never "no material")."""
    if not text.strip():
        raise argparse.ArgumentTypeError("a material name must not be empty; "
                                         "'plumbob materials' lists them")
    return text


def tilt_limit(text: str) -> float:
    """An argparse type: a tilt in degrees from 0 to 90 (``--require-tilt``)."""
    value = number(text)
    if not 0 <= value <= 90:
        raise argparse.ArgumentTypeError(f"a tilt must be from 0 to 90 degrees, not {text}")
    return value


def number_option(text: str, label: str, *, infinite: bool = False) -> float:
    """The number given as option ``label`` of the dynamics commands, or a
    :class:`DynamicsError` naming it; ``infinite`` lets ``inf`` through (a wall's mass)."""
    try:
        value = float(text)
    except ValueError:
        raise DynamicsError(f"{label} must be a number (got {text!r})") from None
    if math.isnan(value) or (math.isinf(value) and not infinite):
        kind = "a number" if infinite else "a finite number"
        raise DynamicsError(f"{label} must be {kind} (got {text!r})")
    return value


def length_unit(text: str) -> str:
    """``--units``: a length unit in any spelling a person types, as its symbol."""
    from ..units import unit_symbol

    try:
        return unit_symbol(text)
    except PlumbobError as error:
        raise argparse.ArgumentTypeError(error.message) from None


# ------------------------------------------------------------ body arguments
def add_body_arguments(parser: argparse.ArgumentParser) -> None:
    """PATH, --density/--material, --units, --repair, --set, --json, --shell/--infill."""
    parser.add_argument("path", metavar="PATH", help="a shape spec (.toml), mesh or outline file")
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--density",
        type=float,  # checked by check_density (finite, positive) when it applies
        metavar="RHO",
        help="density in kg/m³ (kg/m² for a lamina) for parts that give none",
    )
    group.add_argument(
        "--material",
        type=material_name,
        metavar="NAME",
        help="a material from 'plumbob materials' for parts that give no density",
    )
    parser.add_argument(
        "--part-material",
        action="append",
        metavar="NAME=MATERIAL",
        help="a material (or a density, kg/m³) for the assembly's parts named NAME, a glob "
             "such as 'post*'; repeat for each part (a STEP assembly needs one for every part)",
    )
    parser.add_argument(
        "--units",
        type=length_unit,
        metavar="UNIT",
        help="length unit of the file's coordinates: m, cm, mm, km, in or ft, in any case or "
        "spelled out (millimetre, inch); default: the unit the file declares, else metres. "
        "One that contradicts the file's declared unit (3MF, glTF, DXF, a spec's units) is "
        "refused unless --units-override",
    )
    parser.add_argument(
        "--units-override",
        action="store_true",
        help="use --units even where the file declares another unit (said in a notice)",
    )
    parser.add_argument(
        "--repair",
        action="store_true",
        help="repair small defects in meshes (holes, winding) and report them",
    )
    parser.add_argument(
        "--set",
        action="append",
        type=assignment,
        dest="parameters",
        metavar="NAME=VALUE",
        help="override a spec's [parameters] entry (repeatable): a number, an expression, "
        "or a number with a length unit such as 30cm",
    )
    parser.add_argument(
        "--allow-outside-files",
        action="store_true",
        help="let a spec read mesh files outside its own folder (refused by default)",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    printing = parser.add_argument_group("as printed (FDM/SLA; see docs/printing.md)")
    printing.add_argument("--shell", metavar="T", help="walls T thick at full density, e.g. "
                          "1.2mm (a bare number is in --units)")
    printing.add_argument("--infill", metavar="F", help="the interior's fill, e.g. 20%% or 0.2")


def add_report_units_argument(parser: argparse.ArgumentParser) -> None:
    """--report-units: the text report in other length and mass units (JSON stays SI)."""
    parser.add_argument("--report-units", type=_report_units, metavar="LENGTH,MASS",
                        help="show the text report in these units, e.g. mm,g or in,lb "
                             "(lengths: m, cm, mm, km, in, ft; masses: kg, g, t, lb); "
                             "the JSON stays in SI units")


def _report_units(text: str):
    from ..report import ReportUnits

    try:
        return ReportUnits.parse(text)
    except ArgumentError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def report_units(args: argparse.Namespace, reading: Reading | None = None):
    """The units of the text report: ``--report-units``, else the part's own (a part
    read in millimetres is shown in mm and g: :func:`~plumbob.report.natural_units`),
    else SI. Asked for with ``--json`` it is an error (the JSON is always SI), never
    silently ignored; with ``--json`` there is no text report: None."""
    units = getattr(args, "report_units", None)
    if getattr(args, "json", False):
        if units is not None:
            raise ArgumentError("--report-units changes the text report only; the JSON is "
                                "always in SI units (leave out one of them)")
        return None
    from ..report import natural_units  # the text report's, loaded only for text

    return units or natural_units(reading.length_unit if reading is not None else None)


def assignment(text: str) -> tuple[str, str]:
    """An argparse type: ``NAME=VALUE`` (``--set``) as (name, value)."""
    name, sep, value = text.partition("=")
    if not sep or not name.strip() or not value.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, not {text!r}")
    return name.strip(), value.strip()


def parameter_overrides(pairs: list[tuple[str, str]] | Mapping[str, Any] | None
                        ) -> dict[str, Any] | None:
    """The ``--set`` pairs as a mapping; a name set twice is an error, not a silent choice
    (a mapping, already checked, is taken as it is)."""
    if not pairs:
        return None
    if isinstance(pairs, Mapping):
        return dict(pairs)
    out: dict[str, str] = {}
    for name, value in pairs:
        if name in out:
            raise SpecError(f"--set {name} is given twice ({out[name]!r} and {value!r}); "
                            "give it once")
        out[name] = value
    return out


def add_stability_arguments(parser: argparse.ArgumentParser) -> None:
    """The body arguments (PATH, --density/--material, --units, --repair, --json) and --g,
    for the commands that put the body in a gravity field."""
    add_body_arguments(parser)
    parser.add_argument("--g", type=positive, default=SEED_GRAVITY, metavar="G",
                        help=f"gravitational acceleration, m/s² (default {SEED_GRAVITY})")


def add_orientation_arguments(parser: argparse.ArgumentParser, pose: str = "--pose",
                              tilt_help: str = "also check it on a plane tilted by DEG "
                                               "degrees", pose_type=int,
                              pose_help: str = "rest it in its K-th most probable resting pose "
                                               "(see 'plumbob poses')") -> None:
    """--down X,Y,Z or ``pose`` K (the K-th resting pose), and --tilt DEG --toward DEG: how
    the body rests, for check and balance alike."""
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--down", type=direction, metavar="X,Y,Z",
                       help="direction of gravity in the body's frame (default -z; -y for a "
                            "lamina)")
    where.add_argument(pose, type=pose_type, metavar="K", help=pose_help)
    parser.add_argument("--tilt", type=non_negative, metavar="DEG", help=tilt_help)
    parser.add_argument("--toward", type=number, metavar="DEG",
                        help="the tilted plane descends toward this direction, degrees from "
                             "+x toward +y (default: the worst direction)")


def pose_down(body, index: int, option: str, g: float, props):
    """The down vector of the body's ``index``-th most probable resting pose (1-based);
    ``option`` names the command-line option in the error for an index out of range.
    The rank is by probability, so every pose is found and weighed: no cheaper call
    answers it (``Poses.ranked`` holds the rule)."""
    from ..stability.poses import resting_poses

    return resting_poses(body, g=g, props=props).ranked(index, option).down


def _numbers(text: str, what: str, dims: tuple[int, ...]) -> list[float]:
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{what}: expected numbers separated by commas, not "
                                         f"{text!r}") from None
    if len(values) not in dims:
        raise argparse.ArgumentTypeError(f"{what}: expected {' or '.join(map(str, dims))} "
                                         f"numbers, not {len(values)} ({text!r})")
    if not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"{what}: expected finite numbers, not {text!r}")
    return values


def _at(text: str, option: str, example: str) -> tuple[str, str]:
    head, sep, tail = text.partition("@")
    if not sep or not head.strip() or not tail.strip():
        raise argparse.ArgumentTypeError(f"expected {example} (an @ before the point), not "
                                         f"{text!r}")
    return head, tail


def force_option(text: str) -> tuple:
    """An argparse type: ``FX,FY,FZ@X,Y,Z`` (``--force``): N at a point (the body's unit)."""
    head, tail = _at(text, "--force", "FX,FY,FZ@X,Y,Z")
    force = _numbers(head, "the force", (2, 3))
    at = _numbers(tail, "the point", (2, 3))
    if len(force) != len(at):
        raise argparse.ArgumentTypeError(f"the force has {len(force)} components but the point "
                                         f"{len(at)} coordinates: {text!r}")
    return ("force", force, at)


def hang_option(text: str) -> tuple:
    """An argparse type: ``M@X,Y,Z`` (``--hang``): kg hung at a point (the body's unit)."""
    head, tail = _at(text, "--hang", "M@X,Y,Z")
    mass = _numbers(head, "the mass", (1,))[0]
    if mass < 0:
        raise argparse.ArgumentTypeError(f"a hung mass must be ≥ 0 kg, not {mass:g}")
    return ("hang", mass, _numbers(tail, "the point", (2, 3)))


def _search_option(kind: str, text: str) -> tuple:
    head, sep, tail = text.partition("@")
    force = _numbers(head, "the force", (1,))[0]
    if force < 0:
        raise argparse.ArgumentTypeError(f"a {kind}'s force must be ≥ 0 N, not {force:g}")
    height = _numbers(tail, "the highest point", (1,))[0] if sep else None
    if height is not None and height <= 0:
        raise argparse.ArgumentTypeError(f"a {kind}'s highest point must be above the floor, "
                                         f"not {height:g}")
    return (kind, force, height)


def add_load_arguments(parser: argparse.ArgumentParser) -> None:
    """--force, --hang, --push, --press: applied loads (repeatable), points in the body's
    own length unit (like every coordinate of its file)."""
    group = parser.add_argument_group("applied loads (see docs/loads.md)")
    group.add_argument("--force", type=force_option, action="append", dest="load_options",
                       metavar="FX,FY,FZ@X,Y,Z",
                       help="a force in newtons at a point (in the body's own length unit); "
                            "repeatable")
    group.add_argument("--hang", type=hang_option, action="append", dest="load_options",
                       metavar="M@X,Y,Z", help="a mass in kg hung at a point (pulls along "
                                               "gravity); repeatable")
    group.add_argument("--push", type=lambda t: _search_option("push", t), action="append",
                       dest="load_options", metavar="F[@H]",
                       help="a horizontal force of F newtons at the worst point and direction, "
                            "no higher than H (the body's unit)")
    group.add_argument("--press", type=lambda t: _search_option("press", t), action="append",
                       dest="load_options", metavar="F[@H]",
                       help="a downward force of F newtons at the worst point of its top, no "
                            "higher than H")


def option_loads(args: argparse.Namespace, reading: Reading) -> tuple:
    """The loads of the options (``--force``, ``--hang``, ``--push``, ``--press``) with the
    spec's ``[[load]]`` tables, points and heights scaled to metres by the body's unit."""
    from ..loads import loads_from_options

    made = loads_from_options(getattr(args, "load_options", None),
                              length_scale(reading.length_unit))
    return tuple(reading.loads) + tuple(made)


def requirement(args: argparse.Namespace, down=None, loads: tuple = ()):
    """The :class:`~plumbob.stability.requirement.Requirement` the options ask (``--g``,
    ``--tilt``, ``--toward``, ``--friction``, ``--margin``, ``--require-tilt``), with
    gravity along ``down`` (``--down``, or a resting pose's, resolved by the command) and
    the ``loads`` of :func:`option_loads`."""
    from ..stability.requirement import Requirement

    return Requirement(
        down, getattr(args, "g", SEED_GRAVITY), getattr(args, "tilt", None),
        getattr(args, "toward", None), getattr(args, "friction", None),
        getattr(args, "margin", None), getattr(args, "require_tilt", None), tuple(loads))


def part_materials(given: list[str] | None) -> dict[str, str] | None:
    """``--part-material NAME=MATERIAL`` options as ``{name or glob: material}``, in order."""
    if not given:
        return None
    out: dict[str, str] = {}
    for item in given:
        name, sep, value = item.partition("=")
        if not sep or not name.strip() or not value.strip():
            raise ArgumentError(f"--part-material {item!r}: write NAME=MATERIAL, e.g. "
                                "--part-material 'post*=aluminium'")
        out[name.strip()] = value.strip()
    return out


def load_body(args: argparse.Namespace, *, path: str | None = None,
              parameters: Mapping[str, Any] | None = None) -> Reading:
    """Read ``path`` (default ``args.path``) with the body options of ``args``: ``--units``,
    ``--repair``, ``--set`` (or ``parameters``), ``--density`` / ``--material``,
    ``--part-material``, ``--shell`` / ``--infill``, all applied by
    :func:`plumbob.loading.read`."""
    if parameters is None:
        parameters = parameter_overrides(getattr(args, "parameters", None))
    return read(
        args.path if path is None else path, units=getattr(args, "units", None),
        repair=getattr(args, "repair", False), parameters=parameters,
        units_override=getattr(args, "units_override", False),
        allow_outside_files=getattr(args, "allow_outside_files", False),
        material=getattr(args, "material", None), density=getattr(args, "density", None),
        shell=getattr(args, "shell", None), infill=getattr(args, "infill", None),
        part_materials=part_materials(getattr(args, "part_material", None)), spelled="option",
    )


def open_body(args: argparse.Namespace) -> tuple:
    """(reading, mass properties, notes) for ``args.path``: the reader's notices go to
    stderr (and into the JSON), the body's own notes (assumed densities, faceted
    booleans) start the report's notes."""
    reading = load_body(args)
    print_notices(reading, oriented=oriented(args))
    props = reading.body.mass_properties()
    return reading, props, list(props.notes)


# ------------------------------------------------------------------- output
def header(reading: Reading, kind: str) -> dict[str, Any]:
    """The keys every report on a body read from a file starts with: path, name, kind."""
    out: dict[str, Any] = {}
    if reading.path:
        out["path"] = reading.path
    name = getattr(reading.body, "name", None)
    if name:
        out["name"] = name
    out["kind"] = kind
    return out


def require_finite(out: Any, where: str = "") -> Any:
    """``out`` (a report's ``as_dict()``) when every number in it is finite; else an
    :class:`ArgumentError` naming the key: finite inputs whose answer overflows double
    precision (``--g 1e308``, ``--density 1e308``) are bad input, never a ``nan``,
    ``inf`` or JSON ``null`` with exit status 0."""
    items = out.items() if isinstance(out, dict) else enumerate(out) \
        if isinstance(out, (list, tuple)) else None
    if items is not None:
        for key, value in items:
            require_finite(value, f"{where}.{key}" if where else str(key))
        return out
    import numpy as np

    if isinstance(out, (float, np.floating, np.ndarray)) and not np.all(np.isfinite(out)):
        raise ArgumentError(f"the result overflows double precision ({where} is not finite): "
                            "an input (--g, --density, a coordinate) is too large")
    return out


def _json_text(obj: Any, indent: int = 0) -> str:
    """JSON text, indented, with short lists of numbers kept on one line."""
    import json  # here: only --json output needs it

    pad = "  " * (indent + 1)
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = [f"{pad}{json.dumps(k)}: {_json_text(v, indent + 1)}" for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if isinstance(obj, list):
        flat = all(not isinstance(v, (dict, list)) for v in obj)
        if flat and len(obj) <= 16:
            return (
                "["
                + ", ".join(json.dumps(v, allow_nan=False, ensure_ascii=False) for v in obj)
                + "]"
            )
        small = all(
            isinstance(v, list) and all(not isinstance(u, (dict, list)) for u in v) for v in obj
        )
        if small and obj and len(obj) <= 4:
            return "[" + ", ".join(_json_text(v) for v in obj) + "]"
        if not obj:
            return "[]"
        return (
            "[\n"
            + ",\n".join(pad + _json_text(v, indent + 1) for v in obj)
            + "\n"
            + "  " * indent
            + "]"
        )
    return json.dumps(obj, allow_nan=False, ensure_ascii=False)


def dump_json(obj: dict, stream=None) -> None:
    """Write exactly one JSON object (an ``as_dict()``, arrays and all) and a newline."""
    stream = stream or sys.stdout
    stream.write(_json_text(jsonable(obj)) + "\n")


def print_json(out: dict, reading: Reading, notes: list[str]) -> None:
    """A body's report as JSON: ``notes`` and the reader's ``notices`` close it."""
    if notes:
        out["notes"] = notes
    if reading.notices:
        out["notices"] = list(reading.notices)
    dump_json(out)
