"""What every body offers the rest of plumbob.

A body knows its mass properties and enough of its shape for stability:
points spanning its convex hull, and the points it touches a plane with.
Downstream code (stability, energy, reports) uses only this interface.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import DensityError, GeometryError
from ..massprops import MassProperties

__all__ = ["Body", "Transformed", "check_density", "DEFAULT_DENSITY_NOTE", "lowest", "contact_sampling"]

DEFAULT_DENSITY_NOTE = "no density given: 1 kg/m³ (1 kg/m² for a lamina) assumed"


def check_density(density: float | None, what: str = "density") -> float | None:
    """A density must be a positive finite number (or None: not given)."""
    if density is None:
        return None
    try:
        value = float(density)
    except (TypeError, ValueError):
        raise DensityError(f"{what} must be a number, not {density!r}") from None
    if not np.isfinite(value) or value <= 0:
        raise DensityError(f"{what} must be a positive finite number, not {value:g}")
    return value


def contact_sampling(tolerance: float, size: float) -> float:
    """How finely to sample curved surfaces when looking for contact within ``tolerance``.

    Coarser than the contact tolerance on purpose: samples near a point of tangency
    (a sphere's bottom) then stay above the tolerance and only the exact contact
    points count, while samples on a flat contact (a cylinder's base rim) are exactly
    at the lowest level whatever the sampling.
    """
    return max(64 * tolerance, 1e-3 * size)


def lowest(points: np.ndarray, down: np.ndarray, tolerance: float) -> np.ndarray:
    """The distinct rows of ``points`` (n, d) within ``tolerance`` (m) of the lowest along
    ``down``."""
    depth = points @ down
    return np.unique(points[depth >= depth.max() - tolerance] + 0.0, axis=0)


class Body(ABC):
    """A lamina, solid, particle system or assembly.

    kind: ``"lamina"``, ``"solid"``, ``"particles"`` or ``"assembly"``.
    dim: 2 for laminas (their own plane), 3 otherwise.
    """

    kind: str
    dim: int
    name: str | None = None

    @abstractmethod
    def mass_properties(self) -> MassProperties:
        """Mass, size, centre of mass and inertia (see :class:`MassProperties`)."""

    @abstractmethod
    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        """Points (n, dim), m, whose convex hull is within ``tolerance`` of the body's.

        Exact (the polytope's vertices) for bodies bounded by planes and lines;
        curved boundaries are sampled so no point of the body lies further than
        ``tolerance`` outside the points' hull (default: 1e-4 of the body's size).
        """

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        """Points (k, dim) where the body touches a plane below it, ``down`` (dim,) a unit vector.

        The body's lowest points along ``down``, within ``tolerance`` m. Curved
        primitives give their true contact (a line for a cylinder on its side).
        """
        return lowest(self.hull_points(), np.asarray(down, dtype=float), tolerance)

    def transformed(self, matrix: np.ndarray, offset: np.ndarray | None = None) -> Body:
        """This body turned or mirrored by an orthogonal ``matrix`` (dim × dim), then moved."""
        return Transformed(
            self,
            np.asarray(matrix, dtype=float),
            np.zeros(self.dim) if offset is None else np.asarray(offset, dtype=float),
        )

    def translated(self, offset: np.ndarray | list[float]) -> Body:
        return self.transformed(np.eye(self.dim), np.asarray(offset, dtype=float))

    @property
    def size(self) -> float:
        """Diagonal of the bounding box of the hull points, m."""
        pts = self.hull_points()
        return float(np.linalg.norm(np.ptp(pts, axis=0)))

    def with_default_density(self, density: float) -> Body:
        """This body with ``density`` wherever no density was given."""
        return self

    def plot(self, ax=None, **options):
        """Draw the body and its centre of mass; returns the matplotlib figure (``ax=None``
        makes a new one). See :func:`plumbob.plot.plot_body`."""
        from ..plot.body import plot_body

        return plot_body(self, ax, **options)

    def to_geometry(self, segments: int = 128):
        """The shape for boolean operations: a shapely geometry (laminas) or a
        manifold3d ``Manifold`` (solids), curves cut into ``segments`` per turn."""
        raise GeometryError(f"a {self.kind} has no shape for boolean operations")


@dataclass(frozen=True, eq=False)
class Transformed(Body):
    """A body placed by a rigid motion: ``x ↦ matrix @ x + offset``."""

    body: Body
    matrix: np.ndarray
    offset: np.ndarray
    name: str | None = field(default=None)

    def __post_init__(self) -> None:
        n = self.body.dim
        if self.matrix.shape != (n, n) or self.offset.shape != (n,):
            raise GeometryError(f"a {n}D body needs a {n}×{n} matrix and an offset of {n} numbers")
        if not np.allclose(self.matrix @ self.matrix.T, np.eye(n), atol=1e-12):
            raise GeometryError("a placement must be a rotation or reflection (orthogonal matrix)")
        if not np.all(np.isfinite(self.offset)):
            raise GeometryError("a placement offset is not a finite number")

    @property
    def kind(self) -> str:  # type: ignore[override]
        return self.body.kind

    @property
    def dim(self) -> int:  # type: ignore[override]
        return self.body.dim

    def mass_properties(self) -> MassProperties:
        return self.body.mass_properties().transformed(self.matrix, self.offset)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        return self.body.hull_points(tolerance) @ self.matrix.T + self.offset

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        local = self.body.support_points(self.matrix.T @ np.asarray(down, dtype=float), tolerance)
        return local @ self.matrix.T + self.offset

    def transformed(self, matrix: np.ndarray, offset: np.ndarray | None = None) -> Body:
        matrix = np.asarray(matrix, dtype=float)
        offset = np.zeros(self.dim) if offset is None else np.asarray(offset, dtype=float)
        return replace(self, matrix=matrix @ self.matrix, offset=matrix @ self.offset + offset)

    def with_default_density(self, density: float) -> Body:
        return replace(self, body=self.body.with_default_density(density))

    def to_geometry(self, segments: int = 128):
        inner = self.body.to_geometry(segments)
        if self.dim == 2:
            import shapely

            m = self.matrix
            return shapely.affinity.affine_transform(
                inner, [m[0, 0], m[0, 1], m[1, 0], m[1, 1], self.offset[0], self.offset[1]]
            )
        affine = np.hstack((self.matrix, self.offset[:, None]))
        return inner.transform(affine)
