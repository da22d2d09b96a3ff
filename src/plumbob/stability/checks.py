"""The checks a :class:`~plumbob.stability.requirement.Requirement` adds to a verdict:
the body on a tilted plane (with friction: does it slide first?) and the design checks
(a required tilt in every direction, a required static stability margin).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..results import Key, Result
from .requirement import Requirement
from .rocking_result import Rocking
from .support import Support
from .tipping import tipping_angle_deg

__all__ = ["SlopeCheck", "DesignCheck", "slope_check", "tipping_toward"]


@dataclass(frozen=True, repr=False)
class SlopeCheck(Result):
    """The body on a plane tilted by ``tilt_deg`` toward ``direction``.

    toward_deg: the direction's angle in the ground plane from e1 toward e2, degrees.
    direction: horizontal unit vector (body frame) the plane descends toward.
    tipping_angle_deg: the tilt at which it goes over in that direction, degrees.
    topples: whether it goes over at ``tilt_deg``.
    friction: the friction coefficient, or None.
    slides: whether it slides at ``tilt_deg`` (``tan θ > μ``), or None without friction.
    slides_first: whether, tilting ever further that way, it slides before it topples.
    """

    tilt_deg: float
    toward_deg: float
    direction: np.ndarray
    tipping_angle_deg: float
    topples: bool
    friction: float | None = None
    slides: bool | None = None
    slides_first: bool | None = None

    _repr_fields = ("tilt_deg", "toward_deg", "verdict", "tipping_angle_deg", "friction",
                    "slides_first")

    @property
    def verdict(self) -> str:
        """``"topples"``, ``"slides"`` or ``"stands"`` at ``tilt_deg``."""
        if self.topples:
            return "topples"
        if self.slides:
            return "slides"
        return "stands"

    #: the keys of the ``slope`` object of ``plumbob check --json`` (the friction
    #: coefficient itself is the verdict's)
    KEYS = (
        Key("tilt_deg", "°", "the plane's tilt", type="float"),
        Key("toward_deg", "°", "the direction it descends toward, from +x toward +y",
            type="float"),
        Key("direction", "", "that direction, body frame (unit vector)", type="xyz"),
        Key("tipping_angle_deg", "°", "the tilt at which it goes over that way",
            type="float"),
        Key("topples", "", "whether it goes over at `tilt_deg`", type="bool"),
        Key("verdict", "", "`topples`, `slides` or `stands` at `tilt_deg`", type="str"),
        Key("slides", "", "whether it slides at `tilt_deg`", "with `--friction MU`",
            type="bool"),
        Key("slides_first", "", "whether, tilting further, it slides before it topples",
            "with `--friction MU`", type="bool"),
    )


@dataclass(frozen=True, repr=False)
class DesignCheck(Result):
    """The design checks a :class:`Requirement` asks, and whether the body meets them.

    required_tilt_deg: the tilt it must withstand in every direction, degrees, or None.
    passes: whether it stands with a critical tilt of at least that (None: not asked).
    required_margin: the static stability margin it must have, m, or None.
    margin_passes: whether it stands with at least that margin (None: not asked).
    """

    required_tilt_deg: float | None = None
    passes: bool | None = None
    required_margin: float | None = None
    margin_passes: bool | None = None

    @property
    def met(self) -> bool | None:
        """Whether every check asked is met (None when none is asked)."""
        asked = [ok for ok in (self.passes, self.margin_passes) if ok is not None]
        return all(asked) if asked else None


def tipping_toward(sup: Support, verdict: str, margin: float, roll: Rocking | None,
                    direction) -> float:
    """:meth:`Verdict.tipping_angle_deg` from the verdict's parts."""
    if roll is not None and verdict == "stands":
        # a plane descending toward d turns the contact direction toward −d
        d = np.asarray(direction, dtype=float)
        k = int(np.argmax(-roll.directions @ (d / np.linalg.norm(d))))
        return float(roll.tilts_deg[k])
    d = sup.frame.to_ground(np.asarray(direction, dtype=float))
    s = sup.ray_distance(d / np.linalg.norm(d))
    if verdict != "stands":
        s = min(s, margin)
    return tipping_angle_deg(s, sup.com_height)


def slope_check(sup: Support, verdict: str, margin: float, roll: Rocking | None,
           critical_direction: np.ndarray, req: Requirement) -> SlopeCheck:
    """The check on the plane the requirement tilts (0° when only ``toward_deg`` is
    given), toward ``toward_deg`` or else the critical direction."""
    tilt = 0.0 if req.tilt_deg is None else req.tilt_deg
    frame = sup.frame
    if req.toward_deg is None:  # the worst way
        direction = critical_direction
        g = frame.to_ground(direction)
        toward = float(np.degrees(np.arctan2(g[1], g[0]))) if frame.dim == 3 else (
            0.0 if g[0] > 0 else 180.0)
    else:
        toward = req.toward_deg
        direction = frame.direction(toward)
    limit = tipping_toward(sup, verdict, margin, roll, direction)
    topples = bool(tilt > limit) if verdict == "stands" else (verdict == "topples" or tilt > 0)
    slides = slides_first = None
    friction = req.friction
    if friction is not None:
        slides = bool(np.tan(np.radians(tilt)) > friction)
        s = np.tan(np.radians(limit)) * sup.com_height
        slides_first = bool(verdict == "stands" and friction * sup.com_height < s)
    return SlopeCheck(tilt, toward, direction, limit, topples, friction, slides, slides_first)
