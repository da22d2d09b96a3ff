"""``plumbob mass PATH``: mass, size, centre of mass and inertia of a body."""

from __future__ import annotations

import argparse

from ..plot.files import add_plot_argument, write_plot
from ._common import (
    add_body_arguments,
    add_report_units_argument,
    dump_json,
    frame_rows,
    frame_word,
    load_body,
    parse_vector,
    picture_units,
    print_notices,
    report_units,
    require_finite,
)


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "mass",
        help="mass properties of a body",
        description="Mass, area or volume, centre of mass, inertia tensor about the centre of mass "
        "and principal axes of the body in PATH.",
    )
    add_body_arguments(parser)
    add_report_units_argument(parser)
    add_plot_argument(parser)
    parser.add_argument("--about", type=parse_vector, metavar="X,Y,Z",
                        help="also give the inertia tensor about this point (in the file's "
                             "length unit, like its coordinates)")
    parser.add_argument("--frame", type=frame_word, nargs="+", metavar="AXES",
                        help="also give the inertia tensor in another frame, about the centre "
                             "of mass (or the --about point): 'principal' (its principal axes), "
                             "or two axes in the body's coordinates, e.g. --frame x=1,1,0 "
                             "y=-1,1,0 (at right angles; the third is their cross product)")
    parser.add_argument("--sizes", action="store_true",
                        help="also the bounding box and, for solids, the surface area (curved "
                             "faces faceted, with a stated bound)")
    parser.add_argument("--format", choices=("urdf", "sdf", "mjcf"),
                        help="print the simulator's inertial block instead (SI units); needs "
                             "a density for every part (--density, --material or the file's)")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from .mass_report import MassReport

    reading = load_body(args)
    if getattr(args, "format", None) and None in reading.body.densities():
        from ..errors import DensityError

        raise DensityError(f"--format {args.format} writes a simulator's inertial block, and a "
                           "part gives no density: 1 kg/m³ would be a wrong mass; give "
                           "--density or --material", path=args.path)
    units = report_units(args, reading)
    print_notices(reading)
    about = None
    if args.about is not None:  # a point given in the file's unit, like its coordinates
        from ..units import length_scale

        about = [v * length_scale(reading.length_unit) for v in args.about]
    report = MassReport.of(reading, about=about, sizes=args.sizes, frame=frame_rows(args.frame))
    answer = require_finite(report.as_dict())  # built once: checked here, printed below
    if args.plot:
        write_plot(args.plot, "mass", reading.body, props=report.props, path=args.path,
                   units=picture_units(args, reading))
    if getattr(args, "format", None):
        from ..export.inertial import inertial_xml

        print(inertial_xml(reading.body.mass_properties(), args.format))
    elif args.json:
        dump_json(answer)
    else:
        print(report.text(units))
    return 0
