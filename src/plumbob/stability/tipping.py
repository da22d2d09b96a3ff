"""The tipping angle: how far a plane may tilt toward an edge before a body goes over it.

A body whose centre of mass is ``h`` above the plane and ``d`` inside a support
edge (horizontally) tips over that edge when the plane tilts by ``atan(d / h)``
toward it: the one formula of the seed's section 2.2, used by the verdict (its
critical tilt and every edge's tipping angle) and by the resting poses (each pose's
critical tilt). It is evaluated in scalar math, so a worker process and its parent
agree to the last bit (numpy's vectorised ``arctan2`` may round an element
differently by where it lies in memory).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["tipping_angle_deg", "tipping_angles_deg"]


def tipping_angle_deg(distance: float, height: float) -> float:
    """``atan(distance / height)`` in degrees: the tilt toward an edge ``distance`` m
    inside the foot of the centre of mass (negative: beyond it) that tips a body whose
    centre is ``height`` m above the plane.

    >>> tipping_angle_deg(0.5, 2.0) == math.degrees(math.atan(0.25))
    True
    >>> tipping_angle_deg(-1.0, 1.0)
    -45.0
    """
    return math.degrees(math.atan2(float(distance), float(height)))


def tipping_angles_deg(distances: np.ndarray, height: float) -> np.ndarray:
    """:func:`tipping_angle_deg` for each of the ``distances`` (m), degrees (a support
    polygon's edges: a few, so the scalar formula element by element)."""
    return np.array([tipping_angle_deg(d, height) for d in np.asarray(distances).ravel()],
                    dtype=float).reshape(np.shape(distances))
