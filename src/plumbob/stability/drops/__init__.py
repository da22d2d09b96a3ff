"""Dynamic resting poses: Monte Carlo drops in a physics engine (MuJoCo, the ``dynamic`` extra).

The quasi-static poses (:mod:`plumbob.stability.poses`) answer for a body that loses
its energy at once; a body that tumbles lands otherwise (shallow basins almost
vanish). :func:`drop_poses` drops the body in MuJoCo from orientations uniform on
SO(3) — seeded, reproducible, on several processes — with a drop height, restitution
and friction, runs each drop until the body rests, and matches the final orientation
to a quasi-static pose. Each pose gets its landing probability, a Wilson 95 %
confidence interval and its count of drops. In the overdamped setting (rotation
heavily damped, no bounce, released on the ground) the drops reproduce the
quasi-static probabilities (a test checks within two standard errors).

* :mod:`.engine` — the MuJoCo model in scaled units and the worker that runs drops;
* :mod:`.result` — :class:`DropPose`, :class:`Drops` and :func:`wilson_interval`;
* :mod:`.run` — :func:`drop_poses`: set-up, processes, classification.

MuJoCo is imported only when drops run; without it the error names the extra.
"""

from .engine import EXTRA, require_mujoco
from .result import DropPose, Drops, wilson_interval
from .run import check_settings, classify, drop_poses

__all__ = ["drop_poses", "DropPose", "Drops", "wilson_interval", "classify",
           "check_settings", "require_mujoco", "EXTRA"]
