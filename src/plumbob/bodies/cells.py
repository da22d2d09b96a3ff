"""Where a density field over a body is integrated: :meth:`.base.Body.density_cells`'s answer.

Its own module so that a body that never integrates a field (a mesh's poses and mass
with a uniform density) does not create this frozen dataclass, about 0.5 ms of
start-up on Python 3.11.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["DensityCells"]


@dataclass(frozen=True, eq=False)
class DensityCells:
    """Where a density field over a body is integrated: what :meth:`Body.density_cells` gives.

    origin: (dim,) m, a point near the body; the cells' coordinates are relative
        to it, so products stay small.
    size: m, the body's size, which scales the adaptive integration.
    tiles: builds the signed cells (:class:`plumbob.integrals.cells.Cells`)
        that tile the body; called when integrating, it may raise a
        :class:`GeometryError` (an open mesh).
    corners: builds points (n, dim) on the body's boundary, where the field is
        checked before integrating.
    triangles: the closed mesh (n, 3, 3) bounding the body, when it is one: a
        polynomial field is then integrated in one pass over it
        (:func:`plumbob.integrals.mesh.mesh_field_moments`).
    """

    origin: np.ndarray
    size: float
    tiles: Callable[[], list]
    corners: Callable[[], np.ndarray]
    triangles: np.ndarray | None = None

    def __repr__(self) -> str:
        where = ", ".join(f"{v:.3g}" for v in self.origin)
        return f"<DensityCells about ({where}), size {self.size:.3g} m>"
