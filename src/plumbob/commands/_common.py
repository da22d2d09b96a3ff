"""What the commands share: argument types, reading the body, the JSON writer.

Every command module imports from here and from the library, never from another
command module. Only numpy and plumbob's reader load at import; the stability,
energy and dynamics code load when a command runs.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from typing import Any

from ..errors import DynamicsError
from ..loading import read
from ..materials import check_density
from ..reading import Reading
from ..results import jsonable
from ..tolerances import TEXT_ROUND_OFF
from ..units import LENGTH_UNITS, STANDARD_GRAVITY

__all__ = [
    "number",
    "positive",
    "non_negative",
    "count",
    "parse_vector",
    "number_option",
    "add_body_arguments",
    "add_stability_arguments",
    "load_body",
    "open_body",
    "print_notices",
    "header",
    "clean",
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
    return values


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


# ------------------------------------------------------------ body arguments
def add_body_arguments(parser: argparse.ArgumentParser) -> None:
    """PATH, --density/--material, --units, --repair, --json, --shell/--infill."""
    parser.add_argument("path", metavar="PATH", help="a shape spec (.toml), mesh or outline file")
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--density",
        type=float,
        metavar="RHO",
        help="density in kg/m³ (kg/m² for a lamina) for parts that give none",
    )
    group.add_argument(
        "--material",
        metavar="NAME",
        help="a material from 'plumbob materials' for parts that give no density",
    )
    parser.add_argument(
        "--units",
        choices=sorted(LENGTH_UNITS),
        help="length unit of the file's coordinates (default m)",
    )
    parser.add_argument(
        "--repair",
        action="store_true",
        help="repair small defects in meshes (holes, winding) and report them",
    )
    parser.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    printing = parser.add_argument_group("as printed (FDM/SLA; see docs/printing.md)")
    printing.add_argument("--shell", metavar="T", help="walls T thick at full density, e.g. "
                          "1.2mm (a bare number is in --units)")
    printing.add_argument("--infill", metavar="F", help="the interior's fill, e.g. 20%% or 0.2")


def add_stability_arguments(parser: argparse.ArgumentParser) -> None:
    """The body arguments (PATH, --density/--material, --units, --repair, --json) and --g,
    for the commands that put the body in a gravity field."""
    add_body_arguments(parser)
    parser.add_argument("--g", type=positive, default=STANDARD_GRAVITY, metavar="G",
                        help=f"gravitational acceleration, m/s² (default {STANDARD_GRAVITY})")


def load_body(args: argparse.Namespace) -> Reading:
    """Read ``args.path`` and apply ``--density`` / ``--material``, then ``--shell`` /
    ``--infill`` (the part as printed)."""
    reading = read(
        args.path, units=getattr(args, "units", None), repair=getattr(args, "repair", False)
    )
    density = None
    if getattr(args, "material", None):
        from ..materials import material

        density = material(args.material).density
    elif getattr(args, "density", None) is not None:
        density = check_density(args.density, "--density")
    body = reading.body if density is None else reading.body.with_default_density(density)
    if getattr(args, "shell", None) is not None or getattr(args, "infill", None) is not None:
        from ..bodies.printed import printed_from_options
        from ..units import length_scale

        body = printed_from_options(body, args.shell, args.infill,
                                    scale=length_scale(getattr(args, "units", None)))
    return reading if body is reading.body else Reading(body, reading.notices, reading.path)


def print_notices(reading: Reading, stream=None) -> None:
    """Notices go to stderr so stdout stays one JSON object."""
    for notice in reading.notices:
        print(f"plumbob: note: {notice}", file=stream or sys.stderr)


def open_body(args: argparse.Namespace) -> tuple:
    """(reading, mass properties, notes) for ``args.path``: the reader's notices go to
    stderr (and into the JSON), the body's own notes (assumed densities, faceted
    booleans) start the report's notes."""
    reading = load_body(args)
    print_notices(reading)
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


def clean(values, scale: float):
    """Round-off far below ``scale`` shown as 0 in text reports (the JSON keeps every digit)."""
    import numpy as np

    values = np.asarray(values, dtype=float)
    return np.where(np.abs(values) < TEXT_ROUND_OFF * scale, 0.0, values)


def _json_text(obj: Any, indent: int = 0) -> str:
    """JSON text, indented, with short lists of numbers kept on one line."""
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
