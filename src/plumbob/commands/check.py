"""``plumbob check PATH``: will it stand, how far can it tilt, does it pass a tilt test.

The command reads its options, asks :func:`plumbob.stability.check` and prints
:func:`plumbob.report.check.check_text` (or the verdict's JSON).

Exit status 0 with the report; 1 when ``--require-tilt`` is given and the design
fails it (so the command can gate a pipeline); 2 on bad input (handled by the CLI).
plumbob's stability code loads when the command runs.
"""

from __future__ import annotations

import argparse

from ..plot.files import add_plot_argument, write_plot
from ._common import (
    add_load_arguments,
    add_orientation_arguments,
    add_report_units_argument,
    add_stability_arguments,
    default_down,
    header,
    length,
    non_negative,
    open_body,
    option_loads,
    picture_units,
    pose_down,
    positive,
    print_json,
    report_units,
    require_finite,
    requirement,
    tilt_limit,
)

__all__ = ["register", "run"]

#: how many tipping edges (or arcs) the text report lists without --all-edges
WEAKEST = 4

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
    add_orientation_arguments(parser)
    add_load_arguments(parser)
    parser.add_argument("--friction", type=non_negative, metavar="MU",
                        help="friction coefficient: does it slide before it topples?")
    parser.add_argument("--require-tilt", type=tilt_limit, metavar="DEG",
                        help="design check: it must not topple when tilted DEG degrees in any "
                             "direction (IEC 62368-1: 10); exit status 1 if it fails")
    parser.add_argument("--margin", type=length, metavar="M",
                        help="design check: the static stability margin must be at least M "
                             "metres (or with a unit: 3mm); exit status 1 if it is not")
    parser.add_argument("--standard", metavar="NAME",
                        help="run a standard's stability tests as a bundle (iec62368-1, "
                             "iec62368-1-display, astm-f2057; docs/standards.md); exit status "
                             "1 if it fails")
    parser.add_argument("--explain", nargs="?", const="-", metavar="FILE",
                        help="print the calculation sheet (parts, equation (15), support, "
                             "critical edge, moments, factor of safety, verdict) after the "
                             "report, or write it to FILE (.md or .html)")
    parser.add_argument("--solve-for", metavar="NAME",
                        help="with --require-tilt or --margin: the smallest change of the "
                             "spec's parameter NAME that meets it (a 1-D root find)")
    parser.add_argument("--tolerance", type=positive, metavar="M",
                        help="contact tolerance, m (default 1e-6 of the body's size)")
    parser.add_argument("--all-edges", action="store_true",
                        help=f"list every tipping edge (default: the {WEAKEST} weakest; runs of "
                             "short edges of a round base are one arc either way; the JSON "
                             "always has every edge)")
    add_plot_argument(parser)
    parser.set_defaults(func=run)


def _verdict(args, body, props, loads: tuple = (), down=None):
    """plumbob's check of ``body`` with the command's options and ``loads`` (``down``:
    gravity's direction when no pose is asked for; None: the default)."""
    from ..stability.verdict import check

    down = down if args.pose is None else pose_down(body, args.pose, "--pose", args.g, props)
    return check(body, requirement=requirement(args, down, loads), tolerance=args.tolerance,
                 props=props)


def _solve(args, down=None, loaded: bool = False):
    """The smallest change of ``--solve-for``'s parameter that meets the requirement
    (``loaded``: that it stands under its loads), by
    :func:`plumbob.balance.solve.solve_spec_parameter`: each value's body read with the
    command's options and checked as the command checks it."""
    from ..balance.solve import solve_spec_parameter
    from ._common import load_body, parameter_overrides

    def verdict_for(value: float):
        given = {**(parameter_overrides(getattr(args, "parameters", None)) or {}),
                 args.solve_for: value}
        reading = load_body(args, parameters=given)
        loads = option_loads(args, reading) if loaded else ()
        return _verdict(args, reading.body, reading.body.mass_properties(), loads, down=down)

    return solve_spec_parameter(args.path, args.solve_for, verdict_for,
                                require_tilt_deg=args.require_tilt, margin=args.margin,
                                loaded=loaded)


def run(args) -> int:
    from ..errors import StabilityError

    if args.toward is not None and args.tilt is None:
        raise StabilityError("--toward needs --tilt DEG")
    if args.solve_for is not None:
        from ..balance.solve import spec_parameters_of

        spec_parameters_of(args.path)  # a mesh has no parameters: say so before reading it
    explain = getattr(args, "explain", None)
    if explain is not None and explain != "-" and not explain.lower().endswith((".md", ".html")):
        raise StabilityError(f"--explain writes a .md or .html file, not {explain!r} (or give "
                             "no file: the sheet goes to stdout)")
    if explain == "-" and args.json:
        raise StabilityError("--explain prints the sheet as text: with --json give it a file "
                             "(--explain sheet.md)")
    reading, props, notes = open_body(args)
    units = report_units(args, reading)
    body = reading.body
    down = default_down(args, reading)
    v = _verdict(args, body, props, option_loads(args, reading), down)
    answer = require_finite(v.as_dict())  # built once: checked here, printed below
    solution = (_solve(args, down, bool(v.loaded is not None)) if args.solve_for is not None
                else None)
    standard = None
    if args.standard is not None:
        from ..stability.standards import run_standard

        standard = run_standard(body, args.standard, v.requirement.replace(loads=()),
                                extendables=reading.extendables, props=props)
    if args.plot:
        write_plot(args.plot, "check", v, body, path=args.path,
                   units=picture_units(args, reading))
    sheet = None
    if explain is not None:
        from ..report import sheet_html, sheet_markdown
        from ..stability.sheet import calculation_sheet

        made = calculation_sheet(body, v, getattr(body, "name", None) or args.path)
        sheet = sheet_html(made) if explain.lower().endswith(".html") else sheet_markdown(made)
        if explain != "-":
            from ..files import write_atomic

            write_atomic(explain, sheet.encode("utf-8"))
    kind = getattr(body, "kind", "solid")
    if args.json:
        out = {**header(reading, kind), **answer}
        if solution is not None:
            out["solution"] = solution.as_dict()
        if standard is not None:
            out["standard"] = standard.as_dict()
        print_json(out, reading, notes)
    else:
        # the verdict's own report, str(plumbob.check(path)) with these options
        text = v.described(reading.source(props)).text(
            units, solution=solution, standard=standard, edges=None if args.all_edges else WEAKEST)
        print(text if explain != "-" else f"{text}\n\n{sheet}")
    failed = v.meets_requirement is False or (standard is not None and not standard.passes)
    return 1 if failed else 0
