"""``plumbob poses --dynamic``: the options and the report of Monte Carlo drops in MuJoCo.

Kept apart from ``commands/poses.py`` (which only registers these options and hands
over when ``--dynamic`` is given), so the quasi-static report and the dynamic one can
change independently. Only the standard library is imported here; MuJoCo loads when
the drops run, and without it the error names the ``dynamic`` extra.
"""

from __future__ import annotations

import argparse

from ._common import count, header, non_negative, positive, print_json

__all__ = ["add_dynamic_arguments", "check_dynamic", "run_dynamic", "DYNAMIC_OPTIONS"]

#: the options that mean something only with --dynamic (dest names)
DYNAMIC_OPTIONS = ("drops", "seed", "drop_height", "restitution", "friction", "overdamped",
                   "jobs")


def _seed(text: str) -> int:
    """A whole number ≥ 0 (a random seed)."""
    value = non_negative(text)
    if not value.is_integer():
        raise argparse.ArgumentTypeError(f"a seed is a whole number, not {text}")
    return int(value)


def add_dynamic_arguments(parser: argparse.ArgumentParser) -> None:
    """--dynamic and its settings (each defaults to None, so one given without --dynamic
    is caught instead of ignored)."""
    group = parser.add_argument_group(
        "dynamic drops (MuJoCo, the optional extra: pip install 'plumbob[dynamic]')")
    group.add_argument("--dynamic", action="store_true",
                       help="drop the body in MuJoCo from random orientations and count where "
                            "it comes to rest, instead of the quasi-static probabilities")
    group.add_argument("--drops", type=count, metavar="N",
                       help="number of drops (default 1000)")
    group.add_argument("--seed", type=_seed, metavar="S",
                       help="seed of the random orientations (default 0): the same seed gives "
                            "the same answer")
    group.add_argument("--drop-height", type=non_negative, metavar="M",
                       help="height of the lowest point above the ground at release, m "
                            "(default 0)")
    group.add_argument("--restitution", type=non_negative, metavar="E",
                       help="coefficient of restitution of the contact, 0 to 0.95 (default 0)")
    group.add_argument("--friction", type=positive, metavar="MU",
                       help="coefficient of sliding friction (default 1)")
    group.add_argument("--overdamped", action="store_true", default=None,
                       help="heavily damped rotation, no bounce, released on the ground: the "
                            "drops whose limit is the quasi-static model")
    group.add_argument("--jobs", type=count, metavar="J",
                       help="processes to run the drops on (default: every core)")


def check_dynamic(args: argparse.Namespace) -> None:
    """Before any work: a dynamic setting given without --dynamic is an error (it would
    be ignored), and --dynamic without MuJoCo is one line naming the extra."""
    from ..errors import PlumbobError

    if getattr(args, "dynamic", False):
        from ..stability.drops import check_settings, require_mujoco

        if getattr(args, "plot", None):
            raise PlumbobError("--plot draws the quasi-static poses: leave out --dynamic")
        _settings(args)
        check_settings(args.drops, args.drop_height, args.restitution, args.friction,
                       args.jobs, args.overdamped)
        require_mujoco()
        return
    for dest in DYNAMIC_OPTIONS:
        if getattr(args, dest, None) is not None:
            option = "--" + dest.replace("_", "-")
            raise PlumbobError(f"{option} is a setting of the dynamic drops: add --dynamic")


def _settings(args: argparse.Namespace) -> None:
    """Fill in the defaults of the dynamic settings not given (in place)."""
    if args.jobs is None:
        from ..batch.runner import default_jobs

        args.jobs = default_jobs()
    for dest, default in (("drops", 1000), ("seed", 0), ("drop_height", 0.0),
                          ("restitution", 0.0), ("friction", 1.0), ("overdamped", False)):
        if getattr(args, dest) is None:
            setattr(args, dest, default)


def run_dynamic(args: argparse.Namespace, reading, props, poses, notes: list[str]) -> int:
    """Run the drops and print their report (text or ``--json``); returns the exit status.
    ``poses`` are the quasi-static poses the landings are matched to; ``args`` went
    through :func:`check_dynamic` first."""
    from ..report import format_number as num
    from ..report import format_vector
    from ..stability.drops import drop_poses

    body = reading.body
    result = drop_poses(
        body, drops=args.drops, seed=args.seed, drop_height=args.drop_height,
        restitution=args.restitution, friction=args.friction, overdamped=args.overdamped,
        jobs=args.jobs, g=args.g, poses=poses, props=props)  # settings: check_dynamic
    notes = notes + list(result.notes)
    if args.json:
        print_json({**header(reading, getattr(body, "kind", "solid")), **result.as_dict()},
                   reading, notes)
        return 0
    setting = ("overdamped" if result.overdamped else
               f"drop height {num(result.drop_height)} m, restitution {num(result.restitution)}")
    print(f"plumbob poses {args.path} --dynamic: {result.drops} drops in {result.engine} "
          f"(seed {result.seed}, {setting}, friction {num(result.friction)}, "
          f"time step {num(result.timestep, 3)} s); {result.landed} came to rest in a pose")
    print(f"{'#':>3}  {'probability':>11}  {'95% interval':<17}{'drops':>7}  "
          f"{'quasi-static':>12}  down")
    for k, p in enumerate(result.poses, 1):
        low, high = p.interval
        tag = "  rolls" if p.neutral else ""
        print(f"{k:>3}  {p.probability:>11.4f}  [{low:.4f}, {high:.4f}]{p.drops:>7}  "
              f"{p.quasi_static:>12.4f}  {format_vector(p.down, 4)}{tag}")
    for note in notes:
        print(f"note: {note}")
    return 0
