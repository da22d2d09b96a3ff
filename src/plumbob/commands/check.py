"""``plumbob check PATH``: will it stand, how far can it tilt, does it pass a tilt test.

Exit status 0 with the report; 1 when ``--require-tilt`` is given and the design
fails it (so the command can gate a pipeline); 2 on bad input (handled by the CLI).
plumbob's stability code loads when the command runs.
"""

from __future__ import annotations

import argparse

from ..plot.files import add_plot_argument, write_plot
from ._common import (
    add_report_units_argument,
    add_stability_arguments,
    clean,
    direction,
    header,
    non_negative,
    number,
    open_body,
    positive,
    print_json,
    report_units,
    require_finite,
    tilt_limit,
)

__all__ = ["register", "run"]

DESCRIPTION = """\
Will the body stand on a horizontal plane? Reports the verdict (stands, topples,
neutral), the static stability margin (distance from the foot of the centre of mass
to the support boundary, negative outside), the critical tilt and its direction, the
energy to tip it over, and per support edge the tipping angle and energy. Directions
in the ground plane are angles from +x toward +y (for the default down, -z). A lamina
stands in its own plane on its lowest edge (down -y by default)."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "check", help="will it stand? stability margin, tilt limits, tilt test",
        description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_stability_arguments(parser)
    add_report_units_argument(parser)
    where = parser.add_mutually_exclusive_group()
    where.add_argument("--down", type=direction, metavar="X,Y,Z",
                       help="direction of gravity in the body's frame (default -z; -y for a "
                            "lamina)")
    where.add_argument("--pose", type=int, metavar="K",
                       help="rest it in its K-th most probable resting pose (see 'plumbob "
                            "poses')")
    parser.add_argument("--tilt", type=non_negative, metavar="DEG",
                        help="also check it on a plane tilted by DEG degrees")
    parser.add_argument("--toward", type=number, metavar="DEG",
                        help="the tilted plane descends toward this direction, degrees from "
                             "+x toward +y (default: the worst direction)")
    parser.add_argument("--friction", type=non_negative, metavar="MU",
                        help="friction coefficient: does it slide before it topples?")
    parser.add_argument("--require-tilt", type=tilt_limit, metavar="DEG",
                        help="design check: it must not topple when tilted DEG degrees in any "
                             "direction (IEC 62368-1: 10); exit status 1 if it fails")
    parser.add_argument("--tolerance", type=positive, metavar="M",
                        help="contact tolerance, m (default 1e-6 of the body's size)")
    add_plot_argument(parser)
    parser.set_defaults(func=run)


def _text(v, path: str, kind: str, notes: list[str], u) -> str:
    import numpy as np

    from ..errors import printable
    from ..report import format_number, table
    from ..report import format_vector as vector

    scale = v.support.tolerance * 1e6  # the body's size

    def num(value: float, digits: int = 6) -> str:
        return format_number(float(clean(value, scale)), digits)

    def vec(values, digits: int = 6) -> str:
        return vector(clean(values, scale), digits)

    def at(value, digits: int = 6) -> str:  # a length or a point, in the report's unit
        if np.ndim(value):
            return f"{vector(u.length(clean(value, scale)), digits)} {u.length_unit}"
        return f"{format_number(u.length(float(clean(value, scale))), digits)} {u.length_unit}"

    s = v.support
    if s.kind == "point":
        where = f"a point, {at(s.polygon[0])}"
    elif s.kind == "segment":
        where = f"a segment from {at(s.polygon[0])[:-len(u.length_unit) - 1]} to " \
                f"{at(s.polygon[1])}"
    else:
        where = f"a polygon of {len(s.vertices)} corners"
    verdict = {"stands": "stands", "topples": "TOPPLES",
               "neutral": "neutral (centre of mass over the edge of its support)"}[v.verdict]
    rows = [
        ("verdict", verdict),
        ("mass", f"{format_number(u.mass(v.mass))} {u.mass_unit}"),
        ("centre of mass", at(v.center_of_mass)),
        ("down", vec(v.down)),
        ("height of centre", at(v.com_height)),
        ("support", where),
        ("stability margin", at(v.margin)),
        ("critical tilt", f"{num(v.critical_tilt_deg, 4)}° toward {vec(v.critical_direction, 4)}"),
        ("energy to topple", f"{num(v.energy_to_topple)} J"),
    ]
    lines = [table(rows, title=f"plumbob check {path} ({kind})")]
    if v.edges:
        lines.append("")
        lines.append(f"{'tipping over':<34}{f'distance {u.length_unit}':>13}{'angle °':>10}"
                     f"{'energy J':>14}")
        for e in v.edges:
            start, end = (vector(u.length(clean(p, scale)), 4) for p in (e.start, e.end))
            where = start if np.allclose(e.start, e.end) else f"{start}-{end}"
            distance = format_number(u.length(float(clean(e.distance, scale))), 5)
            lines.append(f"{where:<34} {distance:>12} {num(e.tipping_angle_deg, 4):>9}"
                         f" {num(e.energy, 5):>13}")
    if v.slope is not None:
        sl = v.slope
        lines.append("")
        text = (f"on a plane tilted {num(sl.tilt_deg, 4)}° toward {num(sl.toward_deg, 4)}° "
                f"{vec(sl.direction, 4)}: {sl.verdict} (it goes over at "
                f"{num(sl.tipping_angle_deg, 4)}° that way)")
        lines.append(text)
        if sl.friction is not None:
            first = "slides before it topples" if sl.slides_first else "topples before it slides"
            at = "slides" if sl.slides else "does not slide"
            lines.append(f"with friction {num(sl.friction)}: {at} at this tilt; tilted further "
                         f"that way it {first}")
    elif v.friction is not None:
        lines.append("")
        if v.slides_first:
            lines.append(f"with friction {num(v.friction)}: it slides before it topples, "
                         "whichever way the plane is tilted")
        else:
            lines.append(f"with friction {num(v.friction)}: tilted toward the critical "
                         "direction it topples before it slides")
    if v.required_tilt_deg is not None:
        lines.append("")
        status = "PASS" if v.passes else "FAIL"
        lines.append(f"design check, no overturning at {num(v.required_tilt_deg, 4)}° in any "
                     f"direction: {status} (critical tilt {num(v.critical_tilt_deg, 4)}°)")
    for note in notes:
        lines.append(f"note: {printable(note)}")
    return "\n".join(lines)


def run(args) -> int:
    from ..errors import StabilityError
    from ..stability.poses import resting_poses
    from ..stability.verdict import check

    if args.toward is not None and args.tilt is None:
        raise StabilityError("--toward needs --tilt DEG")
    units = report_units(args)
    reading, props, notes = open_body(args)
    body = reading.body
    down = args.down
    if args.pose is not None:
        poses = resting_poses(body, g=args.g, props=props)
        if not 1 <= args.pose <= len(poses):
            raise StabilityError(f"--pose must be between 1 and {len(poses)} (the body has "
                                 f"{len(poses)} resting poses)")
        down = poses[args.pose - 1].down
    v = check(body, down, g=args.g, tilt_deg=args.tilt, toward_deg=args.toward,
              friction=args.friction, require_tilt_deg=args.require_tilt,
              tolerance=args.tolerance, props=props)
    require_finite(v.as_dict())
    if args.plot:
        write_plot(args.plot, "check", v, body, path=args.path)
    kind = getattr(body, "kind", "solid")
    if args.json:
        print_json({**header(reading, kind), **v.as_dict()}, reading, notes)
    else:
        print(_text(v, args.path, kind, notes, units))
    return 1 if v.passes is False else 0
