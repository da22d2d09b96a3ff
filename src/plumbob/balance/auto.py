"""Which resting pose needs the least to meet a target (``balance --target-pose auto``).

Each of the most probable resting poses is asked what it needs — nothing, the least
mass emptied by hollowing, or the least ballast — and the one that needs the least
(the more probable on a tie) is chosen. The answers are numbers; a report words them.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from ..errors import StabilityError

__all__ = ["PoseNeed", "pose_needs", "cheapest", "AUTO_POSES"]

#: how many of the most probable resting poses are tried
AUTO_POSES = 4


class PoseNeed(NamedTuple):
    """What one resting pose needs to meet the target.

    pose: its rank (1-based, as ``plumbob poses`` numbers them). probability: of landing
    in it. down: (dim,) gravity's direction resting so. need: ``"none"`` (it meets the
    target as it is), ``"emptied"`` (hollowing), ``"ballast"``, ``"no carve"`` or
    ``"no ballast"`` (none does). mass: kg emptied or of ballast (for ``"ballast"`` also
    when the ballast found falls short). cost: the mass it needs, kg, ``inf`` when nothing
    meets the target. reason: why none does (a sentence), or ``""``.
    """

    pose: int
    probability: float
    down: np.ndarray
    need: str
    mass: float
    cost: float
    reason: str = ""


def pose_needs(body, target_for: Callable[[np.ndarray], tuple], *, g: float, props=None,
               hollowing=None, lightest: bool = False, count: int = AUTO_POSES
               ) -> list[PoseNeed]:
    """What each of the ``count`` most probable resting poses of ``body`` needs.

    target_for: gravity's direction resting in a pose → ``(down, margin, tilt in degrees,
    toward or None)``, the target as the caller reads it. hollowing: a prepared
    :class:`~plumbob.balance.hollow.Hollowing` to carve with (else ballast is placed by
    :func:`~plumbob.balance.result.balance`); lightest: empty as much as the target
    allows."""
    from ..stability.poses import resting_poses
    from .result import balance
    from .targets import target_for as hollow_target

    needs = []
    for k, pose in enumerate(resting_poses(body, g=g, props=props)[:count], start=1):
        down, margin, tilt, toward = target_for(pose.down)
        row = (k, pose.probability, down)
        if hollowing is not None:
            target = hollow_target(body, down=down, margin=margin, require_tilt_deg=tilt)
            try:
                plan = hollowing.plan(target, lightest=lightest)
                need = "none" if plan.cut is None else "emptied"
                needs.append(PoseNeed(*row, need, plan.removed_mass, plan.removed_mass))
            except StabilityError:
                bound = hollowing.plan(target, best_effort=True).bound
                needs.append(PoseNeed(*row, "no carve", math.nan, math.inf, bound.sentence()))
            continue
        try:
            r = balance(body, down, margin=margin, require_tilt_deg=tilt, toward=toward, g=g,
                        props=props)
            need = "none" if r.ballast_mass == 0 else "ballast"
            needs.append(PoseNeed(*row, need, r.ballast_mass,
                                  r.ballast_mass if r.passes else math.inf))
        except StabilityError as error:
            needs.append(PoseNeed(*row, "no ballast", math.nan, math.inf, str(error)))
    return needs


def cheapest(needs: list[PoseNeed]) -> PoseNeed | None:
    """The pose that needs the least (the more probable on a tie), or None when none of
    them can meet the target."""
    best = min(needs, key=lambda n: (n.cost, n.pose))
    return best if math.isfinite(best.cost) else None
