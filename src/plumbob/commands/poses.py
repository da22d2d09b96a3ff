"""``plumbob poses PATH``: every stable resting pose and how likely a random drop lands in it.

Only the standard library is imported here; the pose code (numpy, scipy) loads when
the command runs.
"""

from __future__ import annotations

import argparse

from ..plot.files import add_plot_argument, write_plot
from ._common import add_stability_arguments, clean, header, open_body, positive
from ._common import dump_json as to_json
from ._dynamic import add_dynamic_arguments, check_dynamic, run_dynamic

__all__ = ["register", "run"]

DESCRIPTION = """\
All stable resting poses of a solid (faces of its convex hull, coplanar triangles
merged into one physical face) or of a lamina (edges of its hull), most probable
first. For each: the down direction in the body's frame, the height of the centre of
mass, the quasi-static probability of landing in it from a random drop (the area of
its basin on the sphere of directions over 4 pi, after Baktash, Sharp, Zhou, Crane
and Jacobson, 2025), the critical tilt and the energy barrier to leave it. Poses of a
rolling surface (a cylinder's side) are merged into one neutral pose."""


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "poses", help="stable resting poses and their landing probabilities",
        description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_stability_arguments(parser)
    parser.add_argument("--tolerance", type=positive, metavar="M",
                        help="faces coplanar within M metres are one face (default 1e-6 of "
                             "the body's size)")
    parser.add_argument("--hull-tolerance", type=positive, metavar="M",
                        help="how closely curved surfaces are sampled, m (default 1e-4 of the "
                             "body's size)")
    add_plot_argument(parser)
    add_dynamic_arguments(parser)  # --dynamic and its settings: commands/_dynamic.py
    parser.set_defaults(func=run)


def run(args) -> int:
    from ..report import format_number as num
    from ..report import format_vector
    from ..stability.poses import resting_poses
    from ..stability.support import body_size

    check_dynamic(args)  # before any work: --dynamic needs MuJoCo, its settings --dynamic
    reading, props, notes = open_body(args)
    body = reading.body
    result = resting_poses(body, g=args.g, tolerance=args.tolerance,
                           hull_tolerance=args.hull_tolerance, props=props)
    if args.dynamic:  # Monte Carlo drops in MuJoCo, matched to these poses
        return run_dynamic(args, reading, props, result, notes)
    notes += list(result.notes)
    if args.plot:
        write_plot(args.plot, "poses", result, body, path=args.path)
    if args.json:
        out = {**header(reading, getattr(body, "kind", "solid")), **result.as_dict()}
        if notes:
            out["notes"] = notes
        if reading.notices:
            out["notices"] = list(reading.notices)
        to_json(out)
        return 0
    size = body_size(body)

    def vec(values, digits: int = 6) -> str:
        return format_vector(clean(values, size), digits)

    print(f"plumbob poses {args.path}: {len(result)} stable pose(s), mass {num(props.mass)} kg, "
          f"centre of mass {vec(result.center_of_mass)} m")
    print(f"{'#':>3}  {'probability':>11}  {'down':<28}{'height m':>11}{'tilt °':>9}"
          f"{'barrier J':>13}")
    for k, p in enumerate(result.poses, 1):
        barrier = "—" if p.energy_barrier is None else num(p.energy_barrier, 5)
        tag = "  rolls" if p.neutral else ""
        print(f"{k:>3}  {p.probability:>11.6f}  {vec(p.down, 4):<28}{num(p.com_height, 5):>11}"
              f"{num(p.critical_tilt_deg, 4):>9}{barrier:>13}{tag}")
    for note in notes:
        print(f"note: {note}")
    return 0
