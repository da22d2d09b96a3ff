"""Solids: closed triangle meshes, and what every uniform solid shares.

A mesh is exact by the divergence theorem. With the prisms and solids of revolution
of :mod:`plumbob.bodies.profiled` (exact from their profile's area moments) it is one
of the three generators every closed-form primitive in :mod:`plumbob.bodies.primitives`
is built on.
"""

from __future__ import annotations

from dataclasses import InitVar, dataclass, field, replace
from functools import cached_property, partial
from typing import TYPE_CHECKING

import numpy as np

from ..arguments import placement
from ..errors import GeometryError
from ..integrals.mesh import CHUNK, VolumeMoments, triangle_soup_moments
from ..massprops import MassProperties
from ..mesh.closure import require_closed, require_sums_close, surface_summary
from ..mesh.weld import merge_vertices
from .base import Body, Surface, check_density, density_words, measure_words
from .uniform import uniform_mass_properties

if TYPE_CHECKING:
    from .cells import DensityCells

# containment and tiling (and the region and polygon modules under them) load when a
# solid is asked what contains a point or for its integration cells: reading a mesh and
# its mass properties never need them.

__all__ = ["MeshSolid"]


def _closed_mesh_cells(triangles: np.ndarray, origin: np.ndarray) -> list:
    """The mesh's tetrahedra from ``origin``, once its closure is checked (in chunks)."""
    vector = np.zeros(3)
    area = 0.0
    for start in range(0, len(triangles), CHUNK):
        t = triangles[start:start + CHUNK].astype(float, copy=False)
        normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        vector += normal.sum(axis=0)
        area += float(np.sqrt(np.einsum("ij,ij->i", normal, normal)).sum())
    require_sums_close(vector, area)
    from .tiling import mesh_cells

    return mesh_cells(triangles, origin)


class _UniformSolid(Body):
    kind = "solid"
    dim = 3
    density: float | None
    exact: bool = True
    relative_error: float = 0.0
    note: str | None = None

    def _finish(self, volume: float, centre: np.ndarray, central: np.ndarray) -> MassProperties:
        """Mass properties from volume (m³), centre (3,) and ``∫ r rᵀ dV`` about it (3, 3)."""
        return uniform_mass_properties(3, volume, centre, central, self.density, exact=self.exact,
                                       relative_error=self.relative_error, note=self.note)

    def with_default_density(self, density: float) -> Body:
        return self if self.density is not None else replace(self, density=check_density(density))

    def densities(self) -> set:
        return {self.density}

    def _describe(self) -> str:
        return f"{self._shape_words()}, {measure_words(self)}{density_words(self.density)}"

    def _shape_words(self) -> str:
        return "solid"


@dataclass(frozen=True, eq=False, repr=False)
class MeshSolid(_UniformSolid):
    """A solid bounded by a closed, outward-wound triangle mesh.

    triangles: (n, 3, 3) m, any float dtype (float32 from binary STL is kept).
    density: kg/m³ or None (not given: 1).
    moments: the triangles' volume moments if a reader already summed them (one
        pass over a large file instead of two); dropped when the mesh moves.
    checked: the triangles are known to close (:func:`plumbob.mesh.check_solid` found
        them so, or they are a closed mesh moved); otherwise the constructor checks
        (:func:`plumbob.mesh.closure.require_closed`) and an open mesh raises
        :class:`GeometryError` naming its holes.
    vertices: (init only) the triangles' distinct corners as
        :func:`~plumbob.mesh.weld.merge_vertices` gives them, when a reader's check has
        them already (:attr:`plumbob.mesh.CheckedSolid.vertices`): not welded again.
    index: (init only) with ``vertices``, each triangle's corners as rows of them
        (:attr:`plumbob.mesh.CheckedSolid.index`): :attr:`welded` without a weld.
    keys: (init only) the hashes (n, 3) of the corners that
        :func:`~plumbob.mesh.weld.merge_vertices` welds them by, when a reader's check has
        them (:attr:`plumbob.mesh.CheckedSolid.keys`): :attr:`welded` does not hash again.
    """

    triangles: np.ndarray
    density: float | None = None
    name: str | None = None
    exact: bool = True
    relative_error: float = 0.0
    note: str | None = None
    moments: VolumeMoments | None = field(default=None, repr=False)
    checked: bool = field(default=False, repr=False)
    vertices: InitVar[np.ndarray | None] = None
    index: InitVar[np.ndarray | None] = None
    keys: InitVar[np.ndarray | None] = None

    def __post_init__(self, vertices: np.ndarray | None, index: np.ndarray | None,
                      keys: np.ndarray | None) -> None:
        tri = np.asarray(self.triangles)
        if tri.dtype.kind in "iu":
            tri = tri.astype(float)
        if tri.ndim != 3 or tri.shape[1:] != (3, 3) or tri.dtype.kind != "f":
            raise GeometryError("a mesh needs an (n, 3, 3) array of real numbers: its "
                                "triangles' corners, m")
        if len(tri) < 4:
            raise GeometryError(
                f"a closed mesh needs at least 4 triangles, this one has {len(tri)}"
            )
        if not self.checked:
            summary = surface_summary(tri)
            require_closed(tri, summary=summary)
            object.__setattr__(self, "moments", summary.moments)
            object.__setattr__(self, "checked", True)
        object.__setattr__(self, "triangles", tri)
        object.__setattr__(self, "density", check_density(self.density))
        if vertices is not None:  # welded already (by check_solid): not again
            vertices.setflags(write=False)
            self.__dict__["_distinct_vertices"] = vertices
            if index is not None and index.shape == (len(tri), 3):
                index = index.astype(np.int64, copy=True)
                index.setflags(write=False)
                self.__dict__["welded"] = (vertices, index)
        elif keys is not None and keys.shape == (len(tri), 3) and keys.dtype == np.uint64:
            self.__dict__["_weld_keys"] = keys  # taken (and let go) by the weld

    def mass_properties(self) -> MassProperties:
        m = self.moments if self.moments is not None else triangle_soup_moments(self.triangles)
        if not np.isfinite(m.m0):
            raise GeometryError("the mesh has a coordinate that is not a finite number")
        require_sums_close(m.vector_area, m.area)
        if not m.m0 > 0:
            raise GeometryError(
                "the mesh encloses no volume"
                if m.m0 == 0
                else "the mesh is inside out (its faces point inward): flip its winding"
            )
        centre = m.m1 / m.m0
        central = m.m2 - m.m0 * np.outer(centre, centre)
        return self._finish(m.m0, m.origin + centre, central)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        return self._distinct_vertices

    @cached_property
    def _distinct_vertices(self) -> np.ndarray:
        """The mesh's distinct vertices (n, 3), m: computed once (stability asks often)."""
        return self.welded[0]

    def surface(self, segments: int = 128) -> Surface:
        return Surface(self.triangles.astype(float), True)

    def as_mesh(self) -> MeshSolid:
        return self

    @cached_property
    def welded(self) -> tuple[np.ndarray, np.ndarray]:
        """The mesh as distinct vertices (n, 3), m, and triangles (m, 3) indexing them
        (:func:`~plumbob.mesh.weld.merge_vertices`, exact copies only): welded once."""
        points, index = merge_vertices(self.triangles.reshape(-1, 3),
                                       keys=self.__dict__.pop("_weld_keys", None))
        points.setflags(write=False)
        index = index.reshape(-1, 3)
        index.setflags(write=False)
        return points, index

    def transformed(self, matrix: np.ndarray, offset: np.ndarray | None = None) -> Body:
        matrix, offset = placement(matrix, offset, 3, error=GeometryError)
        tri = self.triangles.astype(float) @ matrix.T + offset
        if np.linalg.det(matrix) < 0:
            tri = tri[:, ::-1]  # a mirror turns the winding inside out
        return replace(self, triangles=tri, moments=None)

    def to_geometry(self, segments: int = 128):
        import manifold3d

        verts, index = merge_vertices(self.triangles.reshape(-1, 3))
        mesh = manifold3d.Mesh64(
            vert_properties=np.ascontiguousarray(verts, dtype=np.float64),
            tri_verts=index.reshape(-1, 3).astype(np.uint32),
        )
        return manifold3d.Manifold(mesh)

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        from .containment import mesh_contains

        return mesh_contains(self.triangles, points, self._contains_tolerance(tolerance))

    @property
    def is_polytope(self) -> bool:
        return True

    def density_cells(self) -> DensityCells:
        from .cells import DensityCells  # only a density field asks (see bodies.cells)

        tri = self.triangles
        origin = tri[: min(len(tri), 1024)].reshape(-1, 3).mean(axis=0, dtype=float)
        size = float(np.linalg.norm(np.ptp(tri[: min(len(tri), 4096)].reshape(-1, 3), axis=0)))
        return DensityCells(origin, size, partial(_closed_mesh_cells, tri, origin),
                            lambda: tri.reshape(-1, 3).astype(float), triangles=tri)

    def _shape_words(self) -> str:
        return f"{len(self.triangles)} triangles"
