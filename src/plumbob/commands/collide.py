"""``plumbob collide``: velocities after a collision of two smooth, non-rotating bodies
(Newton's law of restitution), with the kinetic energy lost and the elastic verdict."""

from __future__ import annotations

import argparse
import math

from ..errors import DynamicsError
from ..report import format_number, format_vector, table
from ._common import dump_json, number_option

HELP = "velocities, momentum and kinetic energy before and after a collision"
EPILOG = """\
Vectors are comma-separated components (1 to 3), e.g. --v1 3,4 or --v1 -3,4.
Use --m2 inf for a fixed surface (a wall or a floor). The normal points from
body 1 towards body 2 (into the wall); it defaults to the direction of the
relative velocity v1 - v2, a head-on impact."""


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "collide", help=HELP, description=HELP + ".", epilog=EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--m1", metavar="M", required=True, help="mass of body 1, kg")
    parser.add_argument("--v1", metavar="X,Y[,Z]", required=True,
                        help="velocity of body 1 before impact, m/s")
    parser.add_argument("--m2", metavar="M", required=True,
                        help="mass of body 2, kg ('inf' for a fixed surface)")
    parser.add_argument("--v2", metavar="X,Y[,Z]", default=None,
                        help="velocity of body 2 before impact, m/s (default: at rest)")
    parser.add_argument("--normal", metavar="X,Y[,Z]", default=None,
                        help="common normal, from body 1 towards body 2 (default: head-on)")
    parser.add_argument("--e", metavar="E", default="1",
                        help="coefficient of restitution, 0 (coalescing) to 1 (elastic); "
                             "default 1")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(func=run)


def _scalar(text: str, label: str) -> float:
    return number_option(text, label, infinite=True)


def _vector(text: str, label: str) -> list[float]:
    parts = [p.strip() for p in text.split(",")]
    if not 1 <= len(parts) <= 3 or any(not p for p in parts):
        raise DynamicsError(f"{label} must be 1 to 3 comma-separated numbers, like 3,4 "
                            f"(got {text!r})")
    values = [_scalar(p, label) for p in parts]
    if not all(math.isfinite(v) for v in values):
        raise DynamicsError(f"{label} has a component that is not finite (got {text!r})")
    return values


def run(args: argparse.Namespace) -> int:
    from ..dynamics.collisions import collide

    result = collide(
        _scalar(args.m1, "--m1"), _vector(args.v1, "--v1"), _scalar(args.m2, "--m2"),
        None if args.v2 is None else _vector(args.v2, "--v2"),
        None if args.normal is None else _vector(args.normal, "--normal"),
        _scalar(args.e, "--e"))
    if args.json:
        dump_json(result.as_dict())
        return 0
    body2 = "fixed surface" if result.wall else f"{format_number(result.m2)} kg"
    energy_note = " (body 1, relative to the surface)" if result.wall else ""
    momentum_note = " (body 1)" if result.wall else ""
    speed = max(abs(v) for v in (*result.v1_before, *result.v2_before))  # for round-off
    rows = [
        ("body 1", f"{format_number(result.m1)} kg"),
        ("body 2", body2),
        ("coefficient of restitution", format_number(result.e)),
        ("common normal", format_vector(result.normal)),
        ("v1 before → after", f"{format_vector(result.v1_before)} → "
                              f"{format_vector(result.v1_after, scale=speed)} m/s"),
        ("v2 before → after", f"{format_vector(result.v2_before)} → "
                              f"{format_vector(result.v2_after, scale=speed)} m/s"),
        ("impulse on body 2", f"{format_number(result.impulse)} N·s along the normal"),
        ("momentum before → after" + momentum_note,
         f"{format_vector(result.momentum_before)} → {format_vector(result.momentum_after)} "
         "kg·m/s"),
        ("kinetic energy before" + energy_note, f"{format_number(result.ke_before)} J"),
        ("kinetic energy after", f"{format_number(result.ke_after)} J"),
        ("kinetic energy lost", f"{format_number(0.0 if result.elastic else result.ke_loss)} J"),
        ("verdict", "elastic (no kinetic energy lost)" if result.elastic
         else "inelastic (kinetic energy lost)"),
    ]
    print(table(rows, "Collision"))
    return 0
