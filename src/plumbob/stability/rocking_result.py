"""How a body resting on a curved surface rocks: :func:`.rocking.rocking`'s result.

Its own module so that a command which asks only a rocker's least tilt
(:func:`.rocking.least_tilt`: ``plumbob poses`` on a mesh with a rounded bottom) does
not create this frozen dataclass, about 0.7 ms of start-up on Python 3.11.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["PROBE_DEG", "Rocking"]

PROBE_DEG = 8.0  # how far u turns to judge curvature: past the sampling's ripple


@dataclass(frozen=True)
class Rocking:
    """How a body resting on a curved surface responds to being turned.

    directions: (k, dim) unit vectors perpendicular to ``down`` (body frame): the
        ways the contact direction is turned.
    alpha: (m,) how far it is turned, radians.
    heights: (k, m) height of the centre of mass, m, with contact direction
        u = cos α · down + sin α · direction.
    tilts_deg: (k,) the tilt of the plane, degrees, each way, before the rocker's
        equilibrium ends.
    """

    down: np.ndarray
    directions: np.ndarray
    alpha: np.ndarray
    heights: np.ndarray
    tilts_deg: np.ndarray

    @property
    def rest_height(self) -> float:
        """Height of the centre of mass at rest, m."""
        return float(self.heights[:, 0].min())

    def rise(self, probe_deg: float = PROBE_DEG) -> np.ndarray:
        """(k,) how much the centre of mass rises, m, when turned ``probe_deg`` each way."""
        i = int(np.argmin(np.abs(self.alpha - np.radians(probe_deg))))
        return self.heights[:, i] - self.heights[:, 0]

    def kind(self, noise: float) -> str:
        """``"stands"`` (rocks back), ``"topples"`` or ``"neutral"`` (rolls), judging rises
        against ``noise`` (m, the sampling's error in heights)."""
        rise = self.rise()
        if np.all(rise > noise):
            return "stands"
        if np.any(rise < -noise):
            return "topples"
        return "neutral"

    def barrier(self) -> float:
        """Least rise of the centre of mass, m, that rolls it out of its bowl (over the
        highest point of the way it rolls, in the easiest direction)."""
        return float((self.heights.max(axis=1) - self.heights[:, 0]).min())
