"""``plumbob simulate SPEC --until T``: integrate a particle system and report the paths
of the particles and of their centre of mass (JSON: ``times``, ``positions``,
``center_of_mass``, ``momentum`` and more; SI units)."""

from __future__ import annotations

import argparse

import numpy as np

from ..arguments import count
from ..errors import DynamicsError, printable
from ..limits import MAX_SAMPLES
from ..report import format_number, format_vector, table
from ._common import dump_json, number_option, require_finite

HELP = "integrate a particle system (springs, rods, strings, gravity, friction) over time"


def register(subparsers: argparse._SubParsersAction) -> None:
    parser = subparsers.add_parser(
        "simulate", help=HELP, description=HELP + ". The spec format is in docs/simulate.md.")
    parser.add_argument("spec", metavar="SPEC", help="simulation spec (.toml)")
    parser.add_argument("--until", metavar="T", required=True,
                        help="end time in seconds (the run starts at t = 0)")
    parser.add_argument("--samples", metavar="N", default="201",
                        help="number of equally spaced output instants (default 201)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from ..dynamics.motion import simulate
    from ..spec import load_simulation

    until = number_option(args.until, "--until")
    if until <= 0:
        raise DynamicsError(f"--until must be a positive number of seconds (got {args.until})")
    samples = count(number_option(args.samples, "--samples"), "--samples", MAX_SAMPLES,
                    minimum=2, error=DynamicsError)
    spec = load_simulation(args.spec)
    result = simulate(spec.model, until, samples, **spec.options)
    answer = require_finite(result.as_dict())  # built once: checked here, printed below
    if args.json:
        out = {"spec": args.spec, "title": spec.title, "until": until}
        out.update(answer)
        dump_json(out)
        return 0
    print(_text(spec.title or args.spec, result))
    return 0


def _text(title: str, result) -> str:
    first, last = 0, len(result.times) - 1
    rows = [
        ("particles", ", ".join(f"{n} ({format_number(m)} kg)"
                                for n, m in zip(result.names, result.masses, strict=True))),
        ("total mass", f"{format_number(result.total_mass)} kg"),
        ("time", f"0 to {format_number(float(result.times[last]))} s, "
                 f"{len(result.times)} samples"),
        ("centre of mass", f"{format_vector(result.center_of_mass[first])} → "
                           f"{format_vector(result.center_of_mass[last])} m"),
        ("momentum", f"{format_vector(result.momentum[first])} → "
                     f"{format_vector(result.momentum[last])} kg·m/s"),
        ("kinetic energy", f"{format_number(float(result.kinetic_energy[first]))} → "
                           f"{format_number(float(result.kinetic_energy[last]))} J"),
        ("F = M a_G check", f"relative residual {result.newton_residual:.2g}"),
    ]
    if result.max_constraint_error:
        rows.append(("rod/string length error", f"{result.max_constraint_error:.2g} (relative)"))
    for time, string in result.string_jerks:
        rows.append(("string snapped taut", f"{string} at t = {format_number(time)} s"))
    lines = [table(rows, title), "", "Paths (m)"]
    picks = np.unique(np.linspace(0, last, min(11, last + 1)).round().astype(int))
    header = ["t (s)", "centre of mass", *map(printable, result.names)]
    body = [[format_number(float(result.times[k]), 4), format_vector(result.center_of_mass[k], 5),
             *(format_vector(p, 5) for p in result.positions[k])] for k in picks]
    widths = [max(len(row[c]) for row in [header, *body]) for c in range(len(header))]
    for row in [header, *body]:
        lines.append("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip())
    return "\n".join(lines)
