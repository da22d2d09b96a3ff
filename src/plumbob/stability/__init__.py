"""Stability: will it stand, how far can it tilt, which way will it land.

* :func:`support_polygon` — the support polygon of a body resting on a plane;
* :func:`check` — the verdict (stands, topples, neutral), stability margins,
  tipping angles and energies, tilted planes, friction and design checks;
* :func:`resting_poses` — every stable resting pose and the quasi-static
  probability of landing in it;
* :func:`drop_poses` — how often Monte Carlo drops in MuJoCo (the ``dynamic`` extra)
  land in each pose.

Heavy dependencies (scipy) are imported only when a function needs them, and each
of the names below only when first used: ``plumbob poses`` loads neither the verdict
nor the drops room, ``plumbob check`` not the poses.
"""

from typing import TYPE_CHECKING as _TYPE_CHECKING

from ..lazy import lazy_exports as _lazy_exports

if _TYPE_CHECKING:  # for readers and type checkers; at run time see __getattr__
    from .drops import DropPose, Drops, drop_poses
    from .poses import Pose, Poses, poses_from_points, resting_poses
    from .support import Support, default_down, ground_frame, support_polygon
    from .verdict import SlopeCheck, TippingEdge, Verdict, check

__all__ = [
    "DropPose",
    "Drops",
    "Pose",
    "Poses",
    "SlopeCheck",
    "Support",
    "TippingEdge",
    "Verdict",
    "check",
    "default_down",
    "drop_poses",
    "ground_frame",
    "poses_from_points",
    "resting_poses",
    "support_polygon",
]

#: public name → the module (of this package) that defines it, imported on first use
_LAZY = {
    **dict.fromkeys(("DropPose", "Drops", "drop_poses"), ".drops"),
    **dict.fromkeys(("Pose", "Poses", "poses_from_points", "resting_poses"), ".poses"),
    **dict.fromkeys(("Support", "default_down", "ground_frame", "support_polygon"), ".support"),
    **dict.fromkeys(("SlopeCheck", "TippingEdge", "Verdict", "check"), ".verdict"),
}

__getattr__, __dir__ = _lazy_exports(__name__, _LAZY, __all__)
