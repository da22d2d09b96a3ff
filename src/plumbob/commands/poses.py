"""``plumbob poses PATH``: every stable resting pose and how likely a random drop lands in it.

Only the standard library is imported here; the pose code (numpy) loads when the
command runs.
"""

from __future__ import annotations

import argparse

from ..plot.files import add_plot_argument, write_plot
from ._common import (
    add_report_units_argument,
    add_stability_arguments,
    count,
    header,
    non_negative,
    open_body,
    picture_units,
    positive,
    report_units,
)
from ._common import dump_json as to_json
from ._dynamic import add_dynamic_arguments, check_dynamic, run_dynamic

__all__ = ["register", "run"]

ROLL_ANGLE = 15.0  # degrees: plumbob.stability.poses.families.ROLL_ANGLE_DEG (not imported: numpy)

DESCRIPTION = """\
All stable resting poses of a solid (faces of its convex hull; faces coplanar within
the tolerance are one face) or of a lamina (edges of its hull), most probable first.
For each: the down direction in the body's frame, the height of the centre of mass,
the quasi-static probability of landing in it from a random drop (the area of its
basin on the sphere of directions over 4 pi, after Baktash, Sharp, Zhou, Crane and
Jacobson, 2025), the critical tilt, the energy barrier to leave it, and (in the
JSON) the 4x4 transform that sets the body down in it on z = 0. Faces a small tilt
rolls the body between (a cylinder's side, a cone's, a ball) are one rolling pose,
with the axis it rolls about; the bottom of a bowl is one rocking pose."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "poses", help="stable resting poses and their landing probabilities",
        description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_stability_arguments(parser)
    add_quasi_static_arguments(parser)
    add_shown_arguments(parser)
    add_plot_argument(parser)
    add_report_units_argument(parser)
    add_dynamic_arguments(parser)  # --dynamic and its settings: commands/_dynamic.py
    parser.set_defaults(func=run)


def add_quasi_static_arguments(parser: argparse.ArgumentParser) -> None:
    """How faces are grouped into poses: --tolerance, --sampling-tolerance, --roll-angle."""
    parser.add_argument("--tolerance", type=positive, metavar="M",
                        help="faces within M metres of a resting face's plane are one face "
                             "(default 1e-6 of the body's size)")
    parser.add_argument("--sampling-tolerance", "--hull-tolerance", type=positive, metavar="M",
                        dest="sampling_tolerance",
                        help="how closely curved surfaces of shapes are sampled, m (default "
                             "1e-4 of the size); a mesh's own vertices are used as they are")
    parser.add_argument("--roll-angle", type=non_negative, metavar="DEG", default=ROLL_ANGLE,
                        help="faces a tilt of DEG degrees or less rolls the body between are "
                             f"one rolling (or rocking) pose (default {ROLL_ANGLE:g}; 0: none)")


def add_shown_arguments(parser: argparse.ArgumentParser) -> None:
    """Which poses are shown and written: --top, --min-probability, --export(-format)."""
    parser.add_argument("--top", type=count, metavar="N", help="show only the N most probable")
    parser.add_argument("--min-probability", type=probability, metavar="P",
                        help="show only poses at least P likely (the most probable always)")
    parser.add_argument("--export", metavar="DIR",
                        help="write each shown pose, placed on z = 0, as a mesh file in DIR "
                             "(pose-01-p0.4123.stl: rank and probability)")
    parser.add_argument("--export-format", choices=("stl", "3mf"), default="stl",
                        help="STL in the --units length (default), or 3MF, which states it")


def probability(text: str) -> float:
    """An argparse type: a probability, 0 ≤ P ≤ 1."""
    value = non_negative(text)
    if value > 1:
        raise argparse.ArgumentTypeError(f"a probability is at most 1, not {text}")
    return value


def run(args) -> int:
    from ..stability.poses import resting_poses

    check_dynamic(args)  # before any work: --dynamic needs MuJoCo, its settings --dynamic
    reading, props, notes = open_body(args)
    body = reading.body
    result = resting_poses(body, g=args.g, tolerance=args.tolerance,
                           sampling_tolerance=args.sampling_tolerance,
                           roll_angle_deg=args.roll_angle, props=props)
    if args.dynamic:  # Monte Carlo drops in MuJoCo, matched to these poses
        return run_dynamic(args, reading, props, result, notes)
    notes += list(result.notes)
    shown, rest, rest_p = result.shown(args.top, args.min_probability)
    units = report_units(args, reading)
    written = []
    if args.export:
        from ..export.placed import export_poses

        written = export_poses(body, shown, args.export, args.export_format,
                               getattr(args, "units", None))
    if args.plot:
        write_plot(args.plot, "poses", result, body, path=args.path,
                   units=picture_units(args, reading))
    if args.json:
        out = {**header(reading, getattr(body, "kind", "solid")), **result.as_dict()}
        out["poses"] = [p.as_dict() for p in shown]
        if rest:
            out["more"] = {"poses": rest, "probability": rest_p}
        if written:
            out["exported"] = written
        if notes:
            out["notes"] = notes
        if reading.notices:
            out["notices"] = list(reading.notices)
        to_json(out)
        return 0
    from ..stability.ground import body_size

    # the result's own report: str(plumbob.poses(path)) with these options
    print(result.described(reading.source(props, body_size(body))).text(
        units, top=args.top, min_probability=args.min_probability, written=written))
    return 0
