"""``plumbob check PATH``: will it stand, how far can it tilt, does it pass a tilt test.

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
    clean,
    header,
    length,
    non_negative,
    open_body,
    option_loads,
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


def _text(v, path: str, kind: str, notes: list[str], u, all_edges: bool = False) -> str:
    import numpy as np

    from ..errors import printable
    from ..report import format_number, table
    from ..report import format_vector as vector

    scale = v.support.size  # round-off is relative to the body's size

    def num(value: float, digits: int = 6) -> str:
        return format_number(float(clean(value, scale)), digits)

    def vec(values, digits: int = 6) -> str:
        return vector(clean(values, scale), digits)

    def at(value, digits: int = 6) -> str:  # a length or a point, in the report's unit
        if np.ndim(value):
            return f"{vector(u.length(clean(value, scale)), digits)} {u.length_unit}"
        return f"{format_number(u.length(float(clean(value, scale))), digits)} {u.length_unit}"

    def pt(value, digits: int = 4) -> str:  # a point without its unit, in the report's unit
        return vector(u.length(clean(value, scale)), digits)

    s = v.support
    groups = v.edge_groups()
    if s.kind == "point":
        where = f"a point, {at(s.polygon[0])}"
    elif s.kind == "segment":
        where = f"a segment from {pt(s.polygon[0], 6)} to {at(s.polygon[1])}"
    else:
        arcs = [g for g in groups if g.kind == "arc"]
        where = f"a polygon of {len(s.vertices)} corners"
        if arcs:
            on = sum(g.count for g in arcs)
            where += (f" ({on} short edges on {len(arcs)} arc{'s' if len(arcs) > 1 else ''}, "
                      "of a round base)")
    verdict = {"stands": "stands", "topples": "TOPPLES",
               "neutral": "neutral (centre of mass over the edge of its support)"}[v.verdict]
    settled = v.settling
    if settled is not None:  # set down on a point, a line or a sliver: where it comes to rest
        verdict = f"{verdict.split(' (')[0]} ({settled.phrase})"
    if v.verdict == "topples":
        margin = (f"{at(v.margin)}: the centre of mass is {at(v.overhang)} beyond "
                  "the support")
        critical = (f"none: it is over by {num(v.over_by_deg, 4)}°, falling toward "
                    f"{vec(v.critical_direction, 4)}")
    else:
        margin = at(v.margin)
        critical = f"{num(v.critical_tilt_deg, 4)}° toward {vec(v.critical_direction, 4)}"
    rows = [
        ("verdict", verdict),
        ("mass", f"{format_number(u.mass(v.mass))} {u.mass_unit}"),
        ("centre of mass", at(v.center_of_mass)),
        ("down", vec(v.down)),
    ]
    if settled is not None:
        contact = {"point": "a point", "line": "a line", "sliver": "a sliver of a face"}
        rest_on = {"face": "on its face", "rocking": "at the bottom of its curved bowl",
                   "rolling": "on the surface it rolls along"}[settled.pose_kind]
        if not settled.own_face:
            rest_on = "on another face of its family"
        rows.append(("set down", f"down {vec(settled.down_from)}, touching on "
                                 f"{contact[settled.contact]}"))
        rows.append(("comes to rest", f"down {vec(settled.down)} after turning "
                                      f"{num(settled.angle_deg, 4)}°: pose {settled.pose} "
                                      f"({rest_on}), centre {at(settled.drop)} lower"))
        if not settled.stays:
            rows.append(("", "the numbers below are where it was set down"))
    rows += [
        ("height of centre", at(v.com_height)),
        ("support", where),
        ("stability margin", margin),
        ("critical tilt", critical),
        ("energy to topple", f"{num(v.energy_to_topple)} J"),
    ]
    lines = [table(rows, title=f"plumbob check {path} ({kind})")]
    if groups:
        shown = groups if all_edges else groups[:WEAKEST]
        lines.append("")
        title = "tipping over" if len(shown) == len(groups) else "weakest tipping edges"
        labels = []
        for g in shown:
            if g.kind == "arc" and g.count == len(v.edges):
                labels.append(f"the whole round rim ({g.count} edges)")
            elif g.kind == "arc":
                labels.append(f"arc of {g.count} edges {pt(g.start)}-{pt(g.end)}")
            elif np.allclose(g.start, g.end):
                labels.append(pt(g.start))
            else:
                labels.append(f"{pt(g.start)}-{pt(g.end)}")
        width = max(33, *(len(label) for label in labels)) + 1
        lines.append(f"{title:<{width}}{f'distance {u.length_unit}':>13}{'angle °':>10}"
                     f"{'energy J':>14}")
        for label, g in zip(labels, shown):
            distance = format_number(u.length(float(clean(g.distance, scale))), 5)
            lines.append(f"{label:<{width}} {distance:>12} "
                         f"{num(g.tipping_angle_deg, 4):>9} {num(g.energy, 5):>13}")
        if len(shown) < len(groups):
            rest = groups[len(shown):]
            edges = sum(g.count for g in rest)
            lines.append(f"… and {len(rest)} more ({edges} edge{'s' if edges > 1 else ''}, "
                         "--all-edges lists them)")
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
        required = num(v.required_tilt_deg, 4)
        if v.passes:
            status = f"PASS (critical tilt {num(v.critical_tilt_deg, 4)}°)"
        elif v.verdict == "topples":
            status = (f"FAIL (it topples, over by {num(v.over_by_deg, 4)}°: "
                      f"{num(v.shortfall_deg, 4)}° short of {required}°)")
        elif v.verdict == "neutral":
            status = "FAIL (it is balanced on the edge of its support: critical tilt 0°)"
        else:
            status = (f"FAIL (critical tilt {num(v.critical_tilt_deg, 4)}°, "
                      f"{num(v.shortfall_deg, 4)}° short of {required}°)")
        lines.append(f"design check, no overturning at {required}° in any direction: {status}")
    if v.loaded is not None:
        from ..report import loads_report

        lines += ["", loads_report(v.loaded, u, scale)]
    for note in notes:
        lines.append(f"note: {printable(note)}")
    return "\n".join(lines)


def _verdict(args, body, props, loads: tuple = ()):
    """plumbob's check of ``body`` with the command's options and ``loads``."""
    from ..stability.verdict import check

    down = args.down if args.pose is None else pose_down(body, args.pose, "--pose", args.g,
                                                         props)
    return check(body, requirement=requirement(args, down, loads), tolerance=args.tolerance,
                 props=props)


def _spec_parameters(path: str) -> dict:
    """The parameters of the spec at ``path``, or a SpecError when it is not a spec."""
    import os

    from ..errors import SpecError
    from ..loading import SUFFIXES
    from ..spec.loader import spec_parameters

    if SUFFIXES.get(os.path.splitext(path)[1].lower()) != "spec":
        raise SpecError("--solve-for changes a spec's parameter: give a spec (.toml) with "
                        "[parameters]", path=path)
    return spec_parameters(path)


def _solve(args):
    """The smallest change of ``--solve-for``'s parameter that meets the requirement."""
    import argparse as _argparse

    from ..balance.solve import solve_parameter
    from ..errors import SpecError, StabilityError
    from ._common import load_body, parameter_overrides

    if (args.require_tilt is None) == (args.margin is None):
        raise StabilityError("--solve-for needs one requirement: --require-tilt DEG or "
                             "--margin M")
    known = _spec_parameters(args.path)
    name = args.solve_for
    if name not in known:
        listed = ", ".join(known) if known else "none (the spec has no [parameters])"
        raise SpecError(f"--solve-for: unknown parameter {name!r}; the spec's parameters: "
                        f"{listed}", path=args.path)
    tilt = args.require_tilt is not None

    def evaluate(value: float) -> float:
        given = {**(parameter_overrides(getattr(args, "parameters", None)) or {}), name: value}
        body = load_body(_argparse.Namespace(**{**vars(args), "parameters": given})).body
        v = _verdict(args, body, body.mass_properties())
        if v.verdict == "neutral":
            return 0.0
        return v.critical_tilt_deg if tilt else v.margin

    return solve_parameter(name, known[name], evaluate,
                           args.require_tilt if tilt else args.margin,
                           measure="critical_tilt_deg" if tilt else "margin")


def _solution_text(sol) -> str:
    from ..report import format_number as num

    what = (f"critical tilt {num(sol.achieved, 6)}° (≥ {num(sol.required, 4)}°)"
            if sol.measure == "critical_tilt_deg"
            else f"stability margin {num(sol.achieved)} m (≥ {num(sol.required)} m)")
    if sol.change == 0:
        return f"{sol.name} = {num(sol.start)} meets it already: {what}"
    return (f"smallest change of {sol.name} that meets it: {num(sol.start)} → "
            f"{num(sol.value)} ({sol.change:+.6g}): {what}, by the check of the rebuilt body")


def run(args) -> int:
    from ..errors import StabilityError

    if args.toward is not None and args.tilt is None:
        raise StabilityError("--toward needs --tilt DEG")
    if args.solve_for is not None and args.require_tilt is None and args.margin is None:
        raise StabilityError("--solve-for needs a requirement: --require-tilt DEG or "
                             "--margin M")
    if args.solve_for is not None:
        _spec_parameters(args.path)  # a mesh has no parameters: say so before reading it
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
    v = _verdict(args, body, props, option_loads(args, reading))
    require_finite(v.as_dict())
    solution = _solve(args) if args.solve_for is not None else None
    standard = None
    if args.standard is not None:
        from ..stability.standards import run_standard

        standard = run_standard(body, args.standard, v.requirement.replace(loads=()),
                                extendables=reading.extendables, props=props)
    if args.plot:
        write_plot(args.plot, "check", v, body, path=args.path)
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
        out = {**header(reading, kind), **v.as_dict()}
        if solution is not None:
            out["solution"] = solution.as_dict()
        if standard is not None:
            out["standard"] = standard.as_dict()
        print_json(out, reading, notes)
    else:
        lines = [_text(v, args.path, kind, notes, units, args.all_edges)]
        if v.required_margin is not None:
            status = "PASS" if v.margin_passes else (
                f"FAIL ({max(v.required_margin - v.margin, 0.0):.6g} m short)")
            lines.append(f"design check, stability margin at least {v.required_margin:g} m: "
                         f"{status}")
        if solution is not None:
            lines.append(_solution_text(solution))
        if standard is not None:
            from ..report import standard_report

            lines += ["", standard_report(standard, units, v.support.tolerance * 1e6)]
        if explain == "-":
            lines += ["", sheet]
        print("\n".join(lines))
    failed = v.meets_requirement is False or (standard is not None and not standard.passes)
    return 1 if failed else 0
