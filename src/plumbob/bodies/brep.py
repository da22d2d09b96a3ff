"""A solid read from a CAD B-rep (STEP, IGES, BREP): exact mass properties, tessellated shape.

The B-rep itself stays with OpenCASCADE (:mod:`plumbob.formats.step`, in a child
process); a :class:`BRepSolid` keeps what was asked of it there: the volume, centre
and inertia integrated over the B-rep's surfaces (for unit density), and a
tessellation of those surfaces within ``deviation`` m, which answers every
question of shape (hull, contact, containment, surface, booleans). Mass
properties are never taken from the tessellation.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from ..errors import GeometryError
from ..massprops import MassProperties
from .base import Surface
from .solid import MeshSolid, _UniformSolid
from .uniform import uniform_mass_properties

__all__ = ["BRepSolid"]


@dataclass(frozen=True, eq=False, repr=False)
class BRepSolid(_UniformSolid):
    """One part of a CAD file, read from its boundary representation.

    volume: m³. centre: (3,) m. central: (3, 3) m⁵, ``∫ r rᵀ dV`` about the centre.
    triangles: (n, 3, 3) m, the tessellation, outward-wound, every vertex on the
    B-rep and every point of it within ``deviation`` m of the B-rep's surface.
    planar: every face is a plane (the tessellation is then the surface itself).
    density: kg/m³, or None (not given). relative_error: the integration's bound.
    """

    volume: float
    centre: np.ndarray
    central: np.ndarray
    triangles: np.ndarray
    deviation: float
    planar: bool = False
    density: float | None = None
    name: str | None = None
    exact: bool = False
    relative_error: float = 1e-10
    note: str | None = field(default=None)

    @classmethod
    def from_gprops(cls, *, inertia: np.ndarray, **values) -> BRepSolid:
        """From OpenCASCADE's inertia tensor of unit density about the centre (3, 3), m⁵."""
        inertia = np.asarray(inertia, dtype=float)
        central = 0.5 * np.trace(inertia) * np.eye(3) - inertia
        return cls(central=central, **values)

    def __post_init__(self) -> None:
        if not (np.isfinite(self.volume) and self.volume > 0):
            raise GeometryError(f"a B-rep part needs a positive volume, not {self.volume!r}")
        tri = np.asarray(self.triangles, dtype=float)
        if tri.ndim != 3 or tri.shape[1:] != (3, 3) or not len(tri):
            raise GeometryError("a B-rep part needs its tessellation as (n, 3, 3) triangles")

    def mass_properties(self) -> MassProperties:
        return uniform_mass_properties(
            3, self.volume, np.asarray(self.centre, dtype=float), self.central, self.density,
            exact=False, relative_error=self.relative_error, note=self.note)

    @cached_property
    def _mesh(self) -> MeshSolid:
        return MeshSolid(self.triangles, self.density)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        """The tessellation's vertices: every one on the B-rep, their hull within
        :attr:`deviation` of the B-rep's (whatever ``tolerance`` asks)."""
        return self._mesh.hull_points()

    def surface(self, segments: int = 128) -> Surface:
        return Surface(np.asarray(self.triangles, dtype=float), bool(self.planar))

    def to_geometry(self, segments: int = 128):
        return self._mesh.to_geometry(segments)

    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        """Which points lie in the part within ``tolerance`` (default 1e-6 of its size),
        widened by the tessellation's :attr:`deviation` so no point of the B-rep is missed."""
        from .containment import mesh_contains

        tol = self._contains_tolerance(tolerance)
        return mesh_contains(self._mesh.triangles, points,
                             tol + self.deviation if tol >= 0 else tol - self.deviation)

    @property
    def is_polytope(self) -> bool:
        return bool(self.planar)

    def _shape_words(self) -> str:
        return f"B-rep, tessellated within {self.deviation:.2g} m"
