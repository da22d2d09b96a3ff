"""Solids: closed triangle meshes, prisms (extrusions) and solids of revolution.

These three generators are exact: a mesh by the divergence theorem, a prism
and a solid of revolution from the exact area moments of their profile
(Pappus–Guldin, extended to second moments). Every closed-form primitive in
:mod:`plumbob.bodies.primitives` is one of them.
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
from ..tolerances import contact_tolerance, sampling_tolerance
from .base import (
    Body,
    DensityCells,
    Surface,
    check_density,
    contact_sampling,
    density_words,
    lowest,
    measure_words,
)
from .uniform import uniform_mass_properties

if TYPE_CHECKING:
    from .region import Region

# containment and tiling (and the region and polygon modules under them) load when a
# solid is asked what contains a point or for its integration cells: reading a mesh and
# its mass properties never need them.

__all__ = ["MeshSolid", "Extrusion", "Revolution"]


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


def _circle_steps(radius: float, tolerance: float) -> int:
    """Points per turn so that chords stay within ``tolerance`` of a circle."""
    if radius <= tolerance:
        return 4
    # the half-angle of a chord whose sagitta is the tolerance, arccos(1 - t/r), written
    # 2 arcsin(sqrt(t/2r)) so that a tolerance below round-off of r (1e-300) stays > 0
    half_angle = 2.0 * np.arcsin(np.sqrt(tolerance / (2.0 * radius)))
    return int(min(4096, max(8, np.ceil(np.pi / half_angle))))


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
        tri = self.triangles
        origin = tri[: min(len(tri), 1024)].reshape(-1, 3).mean(axis=0, dtype=float)
        size = float(np.linalg.norm(np.ptp(tri[: min(len(tri), 4096)].reshape(-1, 3), axis=0)))
        return DensityCells(origin, size, partial(_closed_mesh_cells, tri, origin),
                            lambda: tri.reshape(-1, 3).astype(float), triangles=tri)

    def _shape_words(self) -> str:
        return f"{len(self.triangles)} triangles"


def _cross_section(region: Region, segments: int):
    import manifold3d

    tol = region.size * (1 - np.cos(np.pi / segments))
    rings = [r.flattened(tol, segments) for r in region.rings]
    return manifold3d.CrossSection(rings, manifold3d.FillRule.Positive)


@dataclass(frozen=True, eq=False, repr=False)
class Extrusion(_UniformSolid):
    """A prism: ``profile`` (in the xy-plane) swept from z = 0 to z = ``height`` (m)."""

    profile: Region
    height: float
    density: float | None = None
    name: str | None = None

    def __post_init__(self) -> None:
        if not (np.isfinite(self.height) and self.height > 0):
            raise GeometryError(f"an extrusion needs a positive height, not {self.height}")
        object.__setattr__(self, "density", check_density(self.density))

    def mass_properties(self) -> MassProperties:
        from .lamina import lamina_mass_properties

        area, centre2, central2 = lamina_mass_properties(self.profile)
        h = self.height
        central = np.zeros((3, 3))
        central[:2, :2] = h * central2
        central[2, 2] = area * h**3 / 12
        return self._finish(area * h, np.append(centre2, h / 2), central)

    def _profile_points(self, tolerance: float | None) -> np.ndarray:
        from .lamina import Lamina

        return Lamina(self.profile).hull_points(tolerance)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        pts = self._profile_points(tolerance)
        return np.concatenate(
            (
                np.pad(pts, ((0, 0), (0, 1))),
                np.pad(pts, ((0, 0), (0, 1)), constant_values=self.height),
            )
        )

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        from .lamina import Lamina

        down = np.asarray(down, dtype=float)
        flat = down[:2]
        size = self.profile.size
        # Down along the axis: a whole end face touches, sampled finely; otherwise
        # coarse samples plus the exact extreme points (see contact_sampling).
        face_down = np.linalg.norm(flat) * size <= tolerance
        pts = self._profile_points(tolerance / 4 if face_down else contact_sampling(tolerance, size))
        if np.linalg.norm(flat) > 0:
            exact = Lamina(self.profile).support_points(flat / np.linalg.norm(flat), tolerance)
            pts = np.concatenate((pts, exact))
        levels = [np.pad(pts, ((0, 0), (0, 1)), constant_values=z) for z in (0.0, self.height)]
        return lowest(np.concatenate(levels), down, tolerance)

    def to_geometry(self, segments: int = 128):
        import manifold3d

        return manifold3d.Manifold.extrude(_cross_section(self.profile, segments), self.height)

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        from .containment import region_contains

        pts = points
        tol = self._contains_tolerance(tolerance)
        z = pts[:, 2]
        return region_contains(self.profile, pts, tol) & (z >= -tol) & (z <= self.height + tol)

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return contact_tolerance(self.profile.size, tolerance)

    @property
    def is_polytope(self) -> bool:
        return not self.profile.is_curved

    def density_cells(self) -> DensityCells:
        from .tiling import prism_cells

        o2 = self.profile.local_origin()
        return DensityCells(np.append(o2, 0.0), float(np.hypot(self.profile.size, self.height)),
                            partial(prism_cells, self.profile, self.height, o2), self.hull_points)

    def _shape_words(self) -> str:
        return f"prism of {self.profile.describe()}, height {self.height:.4g} m"


@dataclass(frozen=True, eq=False, repr=False)
class Revolution(_UniformSolid):
    """The solid swept by ``profile`` — a region in the (r, z) half-plane r ≥ 0,
    given as (x, y) = (r, z) — turning a full circle about the z-axis.

    Exact from the profile's area moments up to degree 3:
    ``V = 2π∫r dA``, ``∫z dV = 2π∫r z dA``, ``∫z² dV = 2π∫r z² dA``,
    ``∫x² dV = ∫y² dV = π∫r³ dA``.
    """

    profile: Region
    density: float | None = None
    name: str | None = None

    def __post_init__(self) -> None:
        if self.profile.bounds[0, 0] < -1e-12 * self.profile.size:
            raise GeometryError("a profile to revolve must lie where x ≥ 0 (x is the radius)")
        object.__setattr__(self, "density", check_density(self.density))

    def mass_properties(self) -> MassProperties:
        z0 = float(self.profile.local_origin()[1])
        m = self.profile.moments(np.array([0.0, z0]), degree=3)
        s_r = m.m1[0]
        if not s_r > 0:
            raise GeometryError("the profile has no area to revolve (or its rings run clockwise)")
        volume = 2 * np.pi * s_r
        zc = m.m2[0, 1] / s_r  # relative to z0
        czz = 2 * np.pi * m.m3[0, 1, 1] - volume * zc * zc
        cxx = np.pi * m.m3[0, 0, 0]
        central = np.diag([cxx, cxx, czz])
        return self._finish(volume, np.array([0.0, 0.0, z0 + zc]), central)

    def _rings(self, tolerance: float | None) -> tuple[np.ndarray, int]:
        from .lamina import Lamina

        # Half the tolerance each: the profile's chords fall short of the profile by up
        # to its share, and the rings' chords short of the swept profile by up to theirs,
        # and the two shortfalls add up.
        tol = sampling_tolerance(self.profile.size, tolerance) / 2
        pts = Lamina(self.profile).hull_points(tol)
        return pts, _circle_steps(float(pts[:, 0].max()), tol)

    @staticmethod
    def _sweep(pts: np.ndarray, angles: np.ndarray) -> np.ndarray:
        c, s = np.cos(angles), np.sin(angles)
        r, z = pts[:, 0:1], pts[:, 1:2]
        return np.stack(
            (r * c, r * s, np.broadcast_to(z, (len(pts), len(angles)))), axis=-1
        ).reshape(-1, 3)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        pts, steps = self._rings(tolerance)
        return self._sweep(pts, 2 * np.pi * np.arange(steps) / steps)

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        from .lamina import Lamina

        down = np.asarray(down, dtype=float)
        radial = np.hypot(down[0], down[1])
        size = self.profile.size
        profile = Lamina(self.profile)
        direction = np.array([radial, down[2]])
        # The profile's own lowest points in the half-plane facing down: exact.
        exact = profile.support_points(direction / np.linalg.norm(direction), tolerance)
        coarse = np.concatenate((profile.hull_points(contact_sampling(tolerance, size)), exact))
        on_axis = coarse[:, 0] <= 1e-12 * size
        axis_points = np.stack((0 * coarse[on_axis, 1], 0 * coarse[on_axis, 1], coarse[on_axis, 1]), axis=1)
        if radial * size <= tolerance:
            # Down along the axis: whole rings may touch (a cylinder's base rim): sweep
            # finely in angle; the profile itself stays coarse but for its exact points.
            steps = _circle_steps(float(coarse[:, 0].max()), tolerance / 4)
            swept = self._sweep(coarse[~on_axis], 2 * np.pi * np.arange(steps) / steps)
            return lowest(np.concatenate((swept, axis_points)), down, tolerance)
        # Otherwise every lowest point lies in the half-plane facing down.
        psi = np.arctan2(down[1], down[0])
        candidates = (self._sweep(coarse[~on_axis], np.array([psi])), axis_points)
        return lowest(np.concatenate(candidates), down, tolerance)

    def to_geometry(self, segments: int = 128):
        import manifold3d

        return manifold3d.Manifold.revolve(_cross_section(self.profile, segments), segments)

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        from .containment import region_contains

        pts = points
        rz = np.stack((np.hypot(pts[:, 0], pts[:, 1]), pts[:, 2]), axis=1)
        return region_contains(self.profile, rz, self._contains_tolerance(tolerance))

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return contact_tolerance(self.profile.size, tolerance)

    @property
    def is_polytope(self) -> bool:
        return False

    def density_cells(self) -> DensityCells:
        from .tiling import revolution_cells

        z0 = float(self.profile.local_origin()[1])
        return DensityCells(np.array([0.0, 0.0, z0]), 2 * self.profile.size,
                            partial(revolution_cells, self.profile, z0), self.hull_points)

    def _shape_words(self) -> str:
        return f"turned profile of {self.profile.describe()}"
