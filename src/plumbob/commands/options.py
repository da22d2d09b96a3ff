"""The options several commands share, declared once (``add_*_arguments``), and what
they mean as library values: the report units, the spec's parameters, the requirement,
the loads, a resting pose's down. One option, one meaning (docs/cli.md).
"""

from __future__ import annotations

import argparse
from collections.abc import Mapping
from typing import Any

from ..errors import ArgumentError, SpecError
from ..reading import Reading
from ..units import SEED_GRAVITY
from .types import (
    assignment,
    direction,
    length_unit,
    material_name,
    non_negative,
    number,
    parse_vector,
    positive,
)

__all__ = [
    "add_body_arguments",
    "add_report_units_argument",
    "report_units",
    "picture_units",
    "parameter_overrides",
    "add_stability_arguments",
    "add_orientation_arguments",
    "pose_down",
    "requirement",
    "frame_word",
    "frame_rows",
]


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


def picture_units(args: argparse.Namespace, reading: Reading):
    """The units ``--plot`` labels its picture in: the text report's (``--report-units``,
    else the part's own: mm and g for a part drawn in mm), with ``--json`` too (the JSON
    is SI; a picture is read by a person)."""
    from ..report import natural_units

    return getattr(args, "report_units", None) or natural_units(reading.length_unit)


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


def frame_word(text: str):
    """An argparse type, one word of ``--frame``: ``principal``, or an axis ``x=1,1,0``
    (``y=…``, ``z=…``) in the body's coordinates, as (name, vector)."""
    if text.strip().lower() == "principal":
        return "principal"
    name, sep, value = text.partition("=")
    if not sep or name.strip().lower() not in ("x", "y", "z"):
        raise argparse.ArgumentTypeError(
            f"expected 'principal' or two axes such as x=1,1,0 y=-1,1,0, not {text!r} (give "
            "--frame after PATH)")
    return name.strip().lower(), parse_vector(value, (3,))


def frame_rows(words: list | None):
    """``--frame``'s words as :meth:`~plumbob.massprops.MassProperties.inertia_in` takes
    them: ``"principal"``, or the rows of the frame two axes give
    (:func:`~plumbob.massprops.frame_axes`); None when not asked."""
    if not words:
        return None
    if words == ["principal"]:
        return "principal"
    if "principal" in words or len({w[0] for w in words}) != len(words) or len(words) != 2:
        raise ArgumentError("--frame takes 'principal' or two different axes, e.g. "
                            "--frame x=1,1,0 y=-1,1,0 (the third is their cross product)")
    from ..frames import frame_axes

    return frame_axes(**dict(words))
