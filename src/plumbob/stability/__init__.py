"""Stability: will it stand, how far can it tilt, which way will it land.

* :func:`support_polygon` — the support polygon of a body resting on a plane;
* :func:`check` — the verdict (stands, topples, neutral), stability margins,
  tipping angles and energies, tilted planes, friction and design checks;
* :func:`resting_poses` — every stable resting pose and the quasi-static
  probability of landing in it;
* :func:`drop_poses` — how often Monte Carlo drops in MuJoCo (the ``dynamic`` extra)
  land in each pose.

Heavy dependencies (scipy) are imported only when a function needs them.
"""

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
