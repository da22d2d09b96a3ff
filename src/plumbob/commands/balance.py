"""``plumbob balance PATH``: what to add so it stands — the least ballast that meets a
stability target, where it goes, and the check of the body with it.

Exit status 0 when the balanced body meets the target (by plumbob's own check of the
body plus the ballast), 1 when it does not, 2 on bad input (handled by the CLI). The
balance code loads when the command runs.
"""

from __future__ import annotations

import argparse

from ._balance_loads import ballast_options, run_loaded
from ._common import (
    add_load_arguments,
    add_orientation_arguments,
    add_report_units_argument,
    add_stability_arguments,
    default_down,
    header,
    length,
    open_body,
    option_loads,
    pose_down,
    pose_or_auto,
    print_json,
    report_units,
    requirement,
    tilt_limit,
)

__all__ = ["register", "run"]

DESCRIPTION = """\
Make it stand. Given a target -- a static stability margin (--margin), a critical tilt
in every direction (--require-tilt) or on a plane tilted one way (--require-tilt with
--toward), in the orientation given by --down or by a resting pose (--target-pose) --
finds the least added mass that meets it and where it goes: a point inside the body
(or inside --ballast-region), or with --ballast-material a box or cylinder of that
material that fits inside. The margin and tilt reported after are plumbob's check of
the body with the ballast added, not the plan's."""



def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "balance", help="make it stand: the least ballast that meets a margin or tilt",
        description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_stability_arguments(parser)
    add_orientation_arguments(parser, "--target-pose",
                              tilt_help="it must stand on a plane tilted DEG degrees (toward "
                                        "--toward, else in every direction)",
                              pose_type=pose_or_auto,
                              pose_help="rest it in its K-th most probable resting pose (see "
                                        "'plumbob poses'), or 'auto': try the most probable "
                                        "poses and take the one that needs the least carving "
                                        "(with --wall) or ballast")
    parser.add_argument("--margin", type=length, metavar="M",
                        help="static stability margin to reach, m (or with a unit: 3mm)")
    parser.add_argument("--require-tilt", type=tilt_limit, metavar="DEG",
                        help="critical tilt to reach in every direction, degrees (IEC 62368-1: "
                             "10)")
    parser.add_argument("--ballast-region", metavar="FILE",
                        help="a body (mesh or spec) the ballast must lie in (default: the body)")
    parser.add_argument("--ballast-material", metavar="NAME",
                        help="the ballast's material ('plumbob materials'): report its volume "
                             "and a shape for it that fits")
    parser.add_argument("--ballast-shape", choices=("box", "cylinder"), default="box",
                        help="the ballast's shape with --ballast-material (default box; a "
                             "lamina's is a square through its thickness)")
    add_load_arguments(parser)
    add_report_units_argument(parser)
    parser.add_argument("--standard", metavar="NAME",
                        help="the least ballast that passes a standard's bundle (iec62368-1: "
                             "its tilt test or its force test, whichever needs less; "
                             "docs/standards.md)")
    hollowing = parser.add_argument_group("hollowing (see docs/printing.md)")
    hollowing.add_argument("--wall", type=length, metavar="T",
                           help="hollow it first: keep walls T thick (e.g. 2mm) and empty cells "
                                "of the inside so it meets the target")
    hollowing.add_argument("--out", metavar="FILE",
                           help="with --wall: write the carved body here (.stl or .3mf)")
    hollowing.add_argument("--void", metavar="FILE",
                           help="with --wall: also write the emptied volume (a slicer modifier)")
    hollowing.add_argument("--lightest", action="store_true",
                           help="with --wall: empty as much as the target allows, not as little")
    hollowing.add_argument("--cell", type=length, metavar="L",
                           help="with --wall: the cells of the linear-programming relaxation that "
                                "starts the search (default: the interior's longest extent / 16)")
    parser.set_defaults(func=run)


def _target(args, body, props, down=None, chosen=None):
    """(down, margin, tilt in degrees, toward vector or None) from the options, checked
    once as a :class:`~plumbob.stability.requirement.Requirement`; ``down``: gravity's
    direction unless a target pose is asked for (None: the default);
    ``chosen``: the pose already chosen (``--target-pose auto``)."""
    from ..errors import StabilityError

    if args.tilt is not None and args.require_tilt is not None:
        raise StabilityError("give --require-tilt DEG or --tilt DEG (with --toward), not both")
    if args.toward is not None and args.tilt is None:
        raise StabilityError("--toward needs --tilt DEG")
    if args.margin is None and args.tilt is None and args.require_tilt is None:
        raise StabilityError("give a target: --margin M, --require-tilt DEG or --tilt DEG")
    if chosen is not None:
        down = chosen
    elif args.target_pose is not None:
        down = pose_down(body, args.target_pose, "--target-pose", args.g, props)
    req = requirement(args, down)
    dim = getattr(body, "dim", 3)
    tilt = req.require_tilt_deg if req.require_tilt_deg is not None else req.tilt_deg
    return req.gravity_down(dim), req.margin, tilt, req.toward_direction(dim)


def _hollow(args, reading, props, down=None, hollowing=None):
    """With --wall: carve the body (plumbob.balance.hollow), write --out (and --void), and
    go on with the body read back from --out. Returns (body, props, written or None).
    ``down``: the pose already chosen; ``hollowing``: the interior already prepared."""
    from ..errors import StabilityError

    if args.wall is None:
        if args.out or args.void or args.lightest or args.cell is not None:
            raise StabilityError("--out, --void, --lightest and --cell go with --wall T")
        return reading.body, props, None
    if not args.out:
        raise StabilityError("--wall needs --out FILE.stl: where to write the carved body")
    if getattr(args, "shell", None) is not None or getattr(args, "infill", None) is not None:
        raise StabilityError("--wall carves a solid body: give it without --shell/--infill")

    from ..balance.hollow import Hollowing, write_hollow
    from ..balance.targets import target_for

    down, margin, tilt, toward = _target(args, reading.body, props,
                                         default_down(args, reading), down)
    if toward is not None:
        raise StabilityError("hollowing meets a margin, or a tilt in every direction: "
                             "--toward is for ballast alone")
    target = target_for(reading.body, down=down, margin=margin,
                        require_tilt_deg=tilt)
    if hollowing is None:
        hollowing = Hollowing.prepare(reading.body, args.wall, cell_size=args.cell)
    # with ballast to make up the rest, the best carve is taken when no carve alone meets it
    plan = hollowing.plan(target, lightest=args.lightest,
                          best_effort=bool(args.ballast_material or args.ballast_region))
    written = write_hollow(plan, args.out, void=args.void, units=args.units, down=down)
    return written.body, written.mass_properties, written


def _auto_pose(args, reading, props):
    """``--target-pose auto``: what each of the most probable resting poses needs
    (:func:`plumbob.balance.auto.pose_needs`: with --wall the mass emptied, else the
    ballast) and the one that needs the least. Returns (the needs, the chosen one, the
    prepared hollowing or None)."""
    from ..balance.auto import cheapest, pose_needs
    from ..errors import StabilityError
    from ..report.balance import need_text

    hollowing = None
    if args.wall is not None:
        from ..balance.hollow import Hollowing

        hollowing = Hollowing.prepare(reading.body, args.wall, cell_size=args.cell)
    needs = pose_needs(reading.body, lambda down: _target(args, reading.body, props, chosen=down),
                       g=args.g, props=props, hollowing=hollowing, lightest=args.lightest)
    best = cheapest(needs)
    if best is None:
        units = report_units(args, reading)
        raise StabilityError(f"--target-pose auto: none of the {len(needs)} most probable poses "
                             "can meet the target; " + "; ".join(
                                 f"pose {n.pose}: {need_text(n, units)}" for n in needs))
    return needs, best, hollowing


def run(args) -> int:
    from ..balance.result import balance

    reading, props, notes = open_body(args)
    units = report_units(args, reading)  # the part's own (mm and g for mm), or asked
    loads = option_loads(args, reading)
    if loads or args.standard is not None:
        return run_loaded(args, reading, props, notes, loads, units)
    needs = best = hollowing = None
    if args.target_pose == "auto":
        needs, best, hollowing = _auto_pose(args, reading, props)
    chosen = None if best is None else best.down
    body, props, carved = _hollow(args, reading, props, chosen, hollowing)
    down, margin, tilt, toward = _target(args, body, props, default_down(args, reading), chosen)
    result = balance(body, down, margin=margin, require_tilt_deg=tilt, toward=toward,
                     g=args.g, **ballast_options(args, props))
    kind = getattr(body, "kind", "solid")
    if args.json:
        from ..report.balance import need_text

        out = {**header(reading, kind), **result.as_dict()}
        if carved is not None:
            out["hollow"] = carved.as_dict()
        if needs is not None:
            out["poses_tried"] = [{"pose": n.pose, "probability": n.probability, "down": n.down,
                                   "needs": need_text(n, units),
                                   "cost": n.cost if n.cost != float("inf") else None}
                                  for n in needs]
            out["pose"] = best.pose
        print_json(out, reading, notes)
    else:
        from dataclasses import replace

        from ..report.balance import auto_pose_text, hollow_text
        from ..stability.support import body_size

        scale = body_size(body)
        if needs is not None:
            print(auto_pose_text(needs, best.pose, units))
        if carved is not None:
            print(hollow_text(carved, scale, units))
        source = replace(reading.source(props, scale), kind=kind, notes=tuple(notes))
        print(result.described(source).text(units))  # str(result) with its file
    return 0 if result.passes else 1
