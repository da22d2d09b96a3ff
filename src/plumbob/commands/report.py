"""``plumbob report PATH -o report.html``: one self-contained HTML page for a design review.

The page holds an interactive 3-D view of the body (centre of mass, support polygon,
ground), the mass-properties table, the stability verdict with its tilt rose and the
pose gallery; it needs no network to view. A section that does not apply to the body
(no resting poses for a particle system, say) is left out with a note saying why.
"""

from __future__ import annotations

import argparse
import os

from ._common import (
    add_load_arguments,
    add_report_units_argument,
    add_stability_arguments,
    open_body,
    option_loads,
    report_units,
    tilt_limit,
)

__all__ = ["register", "run"]

DESCRIPTION = """\
Write one self-contained HTML page about the body in PATH: an interactive 3-D view
(rotate, zoom) with its centre of mass, support polygon and the ground; its mass
properties; whether it stands, with the tilt rose (the critical tilt in every
direction); and its resting poses with their probabilities. Large meshes are decimated
for the view only; every number comes from the full mesh."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "report", help="one self-contained HTML page: 3-D view, mass properties, verdict, poses",
        description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_stability_arguments(parser)
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="the HTML file to write (default: PATH's name with .html, here)")
    parser.add_argument("--require-tilt", type=tilt_limit, metavar="DEG",
                        help="draw this tilt on the tilt rose and say whether it passes")
    add_load_arguments(parser)
    parser.add_argument("--standard", metavar="NAME",
                        help="add a standard's tests and their verdicts (docs/standards.md)")
    add_report_units_argument(parser)
    parser.set_defaults(func=run)


def _attempt(what: str, compute, notes: list[str]):
    """A section's result, or None with a note when the body does not allow it."""
    from ..errors import PlumbobError

    try:
        return compute()
    except PlumbobError as error:
        notes.append(f"{what}: not shown ({error})")
        return None


def run(args) -> int:
    from ..errors import printable
    from ..files import write_atomic
    from ..plot.html import report_page
    from ..stability.poses import resting_poses
    from ..stability.verdict import check
    from ._common import dump_json
    from .mass_report import MassReport

    reading, props, notes = open_body(args)
    units = report_units(args, reading)
    body = reading.body
    loads = option_loads(args, reading)
    verdict = _attempt("stability", lambda: check(body, reading.default_down(), g=args.g, props=props,
                                                  require_tilt_deg=args.require_tilt,
                                                  loads=loads), notes)
    standard = None
    if args.standard is not None:
        from ..stability.standards import run_standard

        standard = _attempt("standard", lambda: run_standard(
            body, args.standard, extendables=reading.extendables, props=props), notes)
    poses = _attempt("resting poses", lambda: resting_poses(body, g=args.g, props=props), notes)
    if poses is not None:
        notes += list(poses.notes)
    output = args.output or os.path.splitext(os.path.basename(args.path))[0] + ".html"
    page = report_page(body, props, verdict, poses, path=args.path,
                       notes=notes + list(reading.notices), units=units,
                       parts=MassReport.of(reading).parts, standard=standard)
    write_atomic(output, page.encode("utf-8"))
    if args.json:
        dump_json({"path": args.path, "report": output, "bytes": len(page.encode("utf-8"))})
    else:
        print(f"plumbob report: wrote {printable(output)}")
    return 0
