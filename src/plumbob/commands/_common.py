"""Arguments and loading shared by the commands that read a body from a file."""

from __future__ import annotations

import argparse
import sys

from ..bodies.base import check_density
from ..loading import read
from ..reading import Reading
from ..units import LENGTH_UNITS

__all__ = ["add_body_arguments", "load_body", "print_notices", "parse_vector"]


def add_body_arguments(parser: argparse.ArgumentParser) -> None:
    """PATH, --density/--material, --units, --repair, --json."""
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


def load_body(args: argparse.Namespace) -> Reading:
    """Read ``args.path`` and apply ``--density`` / ``--material``."""
    reading = read(
        args.path, units=getattr(args, "units", None), repair=getattr(args, "repair", False)
    )
    density = None
    if getattr(args, "material", None):
        from ..materials import material

        density = material(args.material).density
    elif getattr(args, "density", None) is not None:
        density = check_density(args.density, "--density")
    if density is None:
        return reading
    return Reading(reading.body.with_default_density(density), reading.notices, reading.path)


def print_notices(reading: Reading, stream=None) -> None:
    """Notices go to stderr so stdout stays one JSON object."""
    for notice in reading.notices:
        print(f"plumbob: note: {notice}", file=stream or sys.stderr)


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
