"""``plumbob balance`` under loads or a standard (``--force``, ``--hang``, ``--push``,
``--press``, a spec's ``[[load]]``, ``--standard NAME``): the least ballast that stands
under them, and the ballast's options every mode of the command shares.
"""

from __future__ import annotations

from ._common import header, pose_down, print_json, requirement

__all__ = ["ballast_options", "run_loaded"]


def ballast_options(args, props) -> dict:
    """The ballast's options for :func:`plumbob.balance.result.balance`: its shape, and
    its material (and density) and region when given."""
    from ._common import load_body

    options = {"shape": args.ballast_shape, "props": props}
    if args.ballast_material:
        from ..materials import material

        options.update(material=args.ballast_material,
                       density=material(args.ballast_material).density)
    if args.ballast_region:
        options["region"] = load_body(args, path=args.ballast_region).body
    return options


def run_loaded(args, reading, props, notes, loads, units=None) -> int:
    """balance with --force/--hang/--push/--press or --standard: the least ballast that
    stands under the loads (factor of safety ≥ 1), or passes the standard."""
    from ..balance.loaded import balance_standard, balance_under_loads
    from ..errors import StabilityError

    if args.wall is not None or args.margin is not None or args.require_tilt is not None:
        raise StabilityError("with loads or --standard, balance finds the ballast for them "
                             "alone: leave out --wall, --margin and --require-tilt")
    if loads and args.standard is not None:
        raise StabilityError("give loads or --standard, not both (a standard sets its own)")
    if args.target_pose == "auto":
        raise StabilityError("--target-pose auto goes with --margin or --require-tilt; with "
                             "loads or --standard give the pose's number")
    body = reading.body
    down = args.down
    if args.target_pose is not None:
        down = pose_down(body, args.target_pose, "--target-pose", args.g, props)
    options = ballast_options(args, props)
    req = requirement(args, down, loads)
    if args.standard is not None:
        result = balance_standard(body, args.standard, req, **options)
    else:
        result = balance_under_loads(body, req, **options)
    kind = getattr(body, "kind", "solid")
    if args.json:
        out = {**header(reading, kind), **result.as_dict()}
        if args.standard is not None:
            out["standard"] = args.standard
        print_json(out, reading, notes)
    else:
        from ..report.balance import loaded_text
        from ..stability.support import body_size

        print(loaded_text(result, args.path, kind, notes, body_size(body), units, args.standard))
    return 0 if result.passes else 1

