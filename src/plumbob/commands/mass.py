"""``plumbob mass PATH``: mass, size, centre of mass and inertia of a body."""

from __future__ import annotations

import argparse

from ._common import add_body_arguments, load_body, print_notices


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "mass",
        help="mass properties of a body",
        description="Mass, area or volume, centre of mass, inertia tensor about the centre of mass "
        "and principal axes of the body in PATH.",
    )
    add_body_arguments(parser)
    parser.add_argument("--format", choices=("urdf", "sdf", "mjcf"),
                        help="print the simulator's inertial block instead (SI units)")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..report import dump_json
    from .mass_report import mass_json, mass_text

    reading = load_body(args)
    print_notices(reading)
    if getattr(args, "format", None):
        from ..export.inertial import inertial_xml

        print(inertial_xml(reading.body.mass_properties(), args.format))
    elif args.json:
        dump_json(mass_json(reading))
    else:
        print(mass_text(reading))
    return 0
