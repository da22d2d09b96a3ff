"""Applied loads: forces pushing on a body and masses hung from it.

A :class:`Force` is a force vector (N) acting at a point of the body's frame (m); a
:class:`Hang` is a mass (kg) hung at a point, pulling along gravity with ``m g``. Both
are checked when made, so a NaN force, a point with the wrong number of coordinates
or a negative mass never reaches the arithmetic. The verdict under loads (which edge
the body goes over, the resisting and overturning moments about it, the factor of
safety) is :mod:`plumbob.stability.loaded`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..arguments import non_negative, vector
from ..errors import StabilityError

__all__ = ["Force", "Hang", "Load", "load_forces"]


def _point(at, what: str) -> np.ndarray:
    return vector(at, what, (2, 3), error=StabilityError)


@dataclass(frozen=True)
class Force:
    """A force acting on the body.

    force: (dim,) N, body frame (a lamina's in its own plane: 2 numbers).
    at: (dim,) m, the point it acts at, body frame.
    name: what it is, for the report (optional).
    """

    force: np.ndarray
    at: np.ndarray
    name: str | None = None

    def __post_init__(self) -> None:
        label = f"the force {self.name!r}" if self.name else "a force"
        force = vector(self.force, f"{label}'s vector (N)", (2, 3), error=StabilityError)
        at = _point(self.at, f"{label}'s point")
        if force.shape != at.shape:
            raise StabilityError(f"{label} has {force.size} components but its point "
                                 f"{at.size} coordinates: give both in 2D or both in 3D")
        object.__setattr__(self, "force", force)
        object.__setattr__(self, "at", at)

    @property
    def dim(self) -> int:
        return int(self.at.size)

    def vector(self, gravity: np.ndarray) -> np.ndarray:
        """The force, N, body frame (``gravity``, the acceleration vector, is unused)."""
        return self.force

    def describe(self) -> str:
        return self.name or "force"


@dataclass(frozen=True)
class Hang:
    """A mass hung from the body: it pulls along gravity with ``mass · g``.

    mass: kg (≥ 0).
    at: (dim,) m, the point it hangs from, body frame.
    name: what it is, for the report (optional).
    """

    mass: float
    at: np.ndarray
    name: str | None = None

    def __post_init__(self) -> None:
        label = f"the hung mass {self.name!r}" if self.name else "a hung mass"
        object.__setattr__(self, "mass", non_negative(self.mass, f"{label} (kg)",
                                                      error=StabilityError))
        object.__setattr__(self, "at", _point(self.at, f"{label}'s point"))

    @property
    def dim(self) -> int:
        return int(self.at.size)

    def vector(self, gravity: np.ndarray) -> np.ndarray:
        """Its pull, N, body frame: ``mass`` times the acceleration vector ``gravity``."""
        return self.mass * np.asarray(gravity, dtype=float)

    def describe(self) -> str:
        return self.name or "hung mass"


Load = Force | Hang


def load_forces(loads, gravity: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, dim) m, forces (n, dim) N) of ``loads`` under the acceleration vector
    ``gravity`` (m/s², body frame)."""
    dim = len(gravity)
    if not loads:
        return np.zeros((0, dim)), np.zeros((0, dim))
    points = np.array([load.at for load in loads], dtype=float)
    forces = np.array([load.vector(gravity) for load in loads], dtype=float)
    return points, forces
