"""Does a triangle soup close? The one closure test, and the one pass that feeds it.

A closed surface has zero vector area (Σ of its faces' area vectors): the
test needs no topology, costs one pass, and is what makes the divergence
theorem's volume independent of the origin — so it is *the* criterion, used
by every reader and body. The topological checks (:mod:`plumbob.mesh.topology`)
only say where a surface that fails it is open.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..integrals.mesh import VolumeMoments, triangle_soup_moments

__all__ = ["CLOSURE_TOLERANCE", "ZERO_VOLUME", "is_closed", "SurfaceSummary", "surface_summary"]

#: |vector area| / area above which a surface is open
CLOSURE_TOLERANCE = 1e-9
#: volume below this share of area^1.5 counts as none
ZERO_VOLUME = 1e-9


def is_closed(vector_area: np.ndarray, area: float) -> bool:
    """Whether a surface with this vector area (3,) m² and area (m²) is closed.

    Its faces' area vectors must cancel to :data:`CLOSURE_TOLERANCE` of its area.

    Examples
    --------
    >>> import numpy as np
    >>> is_closed(np.array([0.0, 0.0, 1e-12]), 6.0)
    True
    >>> is_closed(np.array([0.0, 0.0, 1.0]), 5.0)  # a box without its lid
    False
    >>> is_closed(np.zeros(3), 0.0)  # no surface at all cancels trivially
    True
    """
    return bool(np.linalg.norm(vector_area) <= CLOSURE_TOLERANCE * max(area, 1e-300))


@dataclass(frozen=True, eq=False)
class SurfaceSummary:
    """What one pass over a triangle soup tells: enough to judge closure and sign.

    origin: (3,) m, the point volumes are summed about.
    volume: signed enclosed volume, m³ (meaningful only when closed).
    vector_area: (3,) m², zero on a closed surface.
    area: m².
    lo, hi: (3,) m, the bounding box.
    moments: the pass's volume moments, for a solid to reuse.
    """

    origin: np.ndarray
    volume: float
    vector_area: np.ndarray
    area: float
    lo: np.ndarray
    hi: np.ndarray
    moments: VolumeMoments | None = None

    @property
    def closed(self) -> bool:
        """The surface closes (:func:`is_closed`)."""
        return is_closed(self.vector_area, self.area)

    @property
    def flat(self) -> bool:
        """The surface encloses no volume worth the name (:data:`ZERO_VOLUME`)."""
        return abs(self.volume) <= ZERO_VOLUME * self.area ** 1.5


def surface_summary(triangles: np.ndarray) -> SurfaceSummary:
    """Volume, vector area, area and bounding box of a triangle soup, in one pass.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray
        Any float dtype, m.

    Returns
    -------
    SurfaceSummary
        Its moments are the divergence-theorem kernel's, which a solid reuses.

    Examples
    --------
    >>> import numpy as np
    >>> tetra = np.array([[[0, 0, 0], [0, 1, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
    ...                   [[0, 0, 0], [0, 0, 1], [0, 1, 0]], [[1, 0, 0], [0, 1, 0], [0, 0, 1]]],
    ...                  dtype=float)
    >>> s = surface_summary(tetra)
    >>> s.closed, round(s.volume * 6, 12)
    (True, 1.0)
    >>> surface_summary(tetra[:3]).closed  # one face missing
    False
    """
    m = triangle_soup_moments(triangles)
    return SurfaceSummary(m.origin, m.m0, m.vector_area, m.area, m.lower, m.upper, m)
