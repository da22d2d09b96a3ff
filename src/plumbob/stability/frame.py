"""The ground frame of a ``down``: its unit vector and the ground's axes, the frame the
support polygon, tilts and placements are measured in.

Its own module so that a command which only places a body by the axes
(:func:`.ground.ground_axes`: ``plumbob poses``) does not create this frozen dataclass,
about 0.6 ms of start-up on Python 3.11.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import StabilityError
from .ground import ground_axes

__all__ = ["GroundFrame", "ground_frame"]


@dataclass(frozen=True)
class GroundFrame:
    """Orthonormal axes of the ground for a given ``down`` (all in the body's frame).

    down: (dim,) unit vector; up = −down.
    axes: (dim − 1, dim): the ground directions as rows (``e1`` and, for solids, ``e2``).
    """

    down: np.ndarray
    axes: np.ndarray

    @property
    def up(self) -> np.ndarray:
        return -self.down

    @property
    def dim(self) -> int:
        return self.down.size

    def to_ground(self, vectors: np.ndarray) -> np.ndarray:
        """Components along the ground axes of vectors (…, dim) → (…, dim − 1)."""
        return np.asarray(vectors, dtype=float) @ self.axes.T

    def from_ground(self, coords: np.ndarray) -> np.ndarray:
        """Vectors (…, dim) with ground components (…, dim − 1)."""
        return np.asarray(coords, dtype=float) @ self.axes

    def direction(self, toward_deg: float) -> np.ndarray:
        """The horizontal unit vector at ``toward_deg`` from ``e1`` toward ``e2``.

        For a lamina the ground is a line: only 0° (+e1) and 180° (−e1) make sense,
        other angles are taken along the line by the sign of their cosine.
        """
        angle = np.radians(float(toward_deg))
        if self.dim == 2:
            c = np.cos(angle)
            if abs(c) < 1e-9:
                raise StabilityError(
                    "a lamina can only be tilted within its own plane: toward 0° or 180°")
            return self.axes[0] * np.sign(c)
        return np.cos(angle) * self.axes[0] + np.sin(angle) * self.axes[1]


def ground_frame(down: np.ndarray) -> GroundFrame:
    """The deterministic ground frame of a unit ``down`` (2 or 3 components).

    >>> ground_frame(np.array([0.0, 0.0, -1.0])).axes
    array([[1., 0., 0.],
           [0., 1., 0.]])
    >>> ground_frame(np.array([0.0, -1.0])).axes
    array([[1., 0.]])
    """
    down = np.asarray(down, dtype=float)
    return GroundFrame(down, ground_axes(down))
