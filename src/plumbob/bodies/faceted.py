"""The result of a boolean computed on facets in float64, and its integration.

Polytopes (boxes, prisms of polygons, meshes) have no curves to facet: their boolean is
integrated once and is exact but for round-off, whose bound it states. Curved parts are
cut into ``n`` and ``n / 2`` segments per turn and the results Richardson-extrapolated
(the faceting error falls as 1/n², so ``(4 P_n − P_n/2) / 3`` removes its leading term);
the stated error bounds the true one (:mod:`plumbob.bodies.bounds`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import DensityError, GeometryError
from ..massprops import MassProperties, combine
from .base import DEFAULT_DENSITY_NOTE, Body, check_density, density_words, lowest
from .booleans import measure as geometry_measure
from .bounds import change, faceting_moved, relative_bound, roundoff_moved
from .cells import DensityCells

__all__ = ["Faceted", "integrate_boolean"]


@dataclass(frozen=True, eq=False, repr=False)
class Faceted(Body):
    """The result of a boolean computed on facets (float64).

    shape: the faceted result (a Lamina or MeshSolid of unit density), for its hull,
        contact and further booleans.
    unit_properties: mass properties at unit density: of the result itself when every
        operand is a polytope; else Richardson-extrapolated from the faceting at n and
        n/2 segments per turn (the faceting error falls as 1/n², so (4 P_n − P_n/2) / 3
        removes its leading term).
    density: kg/m³ (kg/m² for a lamina), or None (not given: 1).
    relative_error: a bound on the relative error of the measure, the centre (relative
        to the body's radius about it) and the inertia (:mod:`plumbob.bodies.bounds`):
        round-off alone for polytopes, the faceting's for curved parts.
    exact: True when no curve was faceted (a boolean of polytopes).
    origin: m, where ``unit_properties`` are measured from (None: the origin), so a
        result far away keeps its digits until the last step.
    operands: the bodies a union was made of, placed as the result is (empty for a
        difference or an intersection): where the union touches a plane below it is
        where its lowest operands do, exactly, not on the facets' chords.
    """

    shape: Body
    unit_properties: MassProperties
    density: float | None
    relative_error: float
    note: str
    name: str | None = None
    exact: bool = False
    origin: np.ndarray | None = None
    operands: tuple[Body, ...] = ()

    @property
    def kind(self) -> str:  # type: ignore[override]
        return self.shape.kind

    @property
    def dim(self) -> int:  # type: ignore[override]
        return self.shape.dim

    def mass_properties(self) -> MassProperties:
        props = self.unit_properties.scaled(1.0 if self.density is None else self.density)
        if self.origin is not None:
            props = props.transformed(np.eye(self.dim), self.origin)
        notes = (DEFAULT_DENSITY_NOTE,) if self.density is None else ()
        return replace(props, exact=self.exact, relative_error=self.relative_error,
                       notes=notes + (self.note,))

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        return self.shape.hull_points(tolerance)

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        if self.exact or not self.operands:
            return self.shape.support_points(down, tolerance)
        # every operand lies in the union, so the union's lowest points are its lowest
        # operands' own (a sphere's true pole, not the facets' flat cap around it)
        return lowest(np.vstack([b.support_points(down, tolerance) for b in self.operands]),
                      down, tolerance)

    def to_geometry(self, segments: int = 128):
        return self.shape.to_geometry(segments)

    def surface(self, segments: int = 128):
        return self.shape.surface(segments)._replace(exact=self.exact)

    def outline(self, tolerance: float, segments: int = 384) -> list[np.ndarray]:
        return self.shape.outline(tolerance, segments)

    def transformed(self, matrix: np.ndarray, offset: np.ndarray | None = None) -> Body:
        """Turned about the origin, then moved: the shape, and the properties about their
        own origin (so moving a far result back near 0 loses nothing)."""
        moved = Body.transformed(self.shape, matrix, offset)  # checks the arguments
        matrix, offset = moved.matrix, moved.offset
        origin = np.zeros(self.dim) if self.origin is None else self.origin
        return replace(self, shape=self.shape.transformed(matrix, offset),
                       unit_properties=self.unit_properties.transformed(matrix),
                       origin=matrix @ origin + offset,
                       operands=tuple(b.transformed(matrix, offset) for b in self.operands))

    def with_default_density(self, density: float) -> Body:
        return self if self.density is not None else replace(self, density=check_density(density))

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        """Which points lie in the faceted shape (curves cut into chords; see ``note``)."""
        return self.shape.contains(points, tolerance)

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return self.shape._contains_tolerance(tolerance)

    @property
    def is_polytope(self) -> bool:
        # the facets of curved parts are chords of them, not the body's own corners
        return self.exact and self.shape.is_polytope

    def densities(self) -> set:
        return {self.density}

    def density_cells(self) -> DensityCells:
        raise DensityError(
            "a density field cannot be integrated over the faceted result of a boolean of "
            "overlapping parts: give the field to a body whose parts do not overlap")

    def _describe(self) -> str:
        what = "area" if self.dim == 2 else "volume"
        unit = "m²" if self.dim == 2 else "m³"
        kgs = "kg/m²" if self.dim == 2 else "kg/m³"
        return (f"{self.kind} from a boolean on facets, {what} {self.unit_properties.measure:.3g} "
                f"{unit}{density_words(self.density, kgs)}, relative error {self.relative_error:.1e}")


def integrate_boolean(bodies: tuple[Body, ...], build, segments: int, what: str,
                      density: float | None, geometries: list | None = None,
                      origin: np.ndarray | None = None) -> Faceted:
    """Integrate a boolean of ``bodies`` computed on their facets in float64
    (``geometries``: the bodies' shapes at ``segments``, when already made, placed
    relative to ``origin``). With an ``origin`` the facets are built and integrated
    about it and the result moved back, so the boolean costs no digits to the
    coordinates' size.

    Polytopes (boxes, prisms of polygons, meshes) have no curves to facet: the boolean
    is integrated once and is exact but for round-off, whose bound it states. Curved
    parts are faceted at ``segments`` and ``segments / 2`` per turn and the results
    Richardson-extrapolated; the stated error bounds the true one (:mod:`.bounds`)."""
    from .lamina import Lamina
    from .region import Region
    from .solid import MeshSolid

    dim = bodies[0].dim
    local = bodies if origin is None else tuple(b.translated(-origin) for b in bodies)

    def integrated(count: int) -> tuple[Body, MassProperties, float]:
        """The result faceted at ``count`` per turn, its unit-density properties, and a
        bound on the region between it and the true result (m³, m²)."""
        parts = geometries if count == segments and geometries else [b.to_geometry(count) for b in local]
        geometry = build(parts)
        if not geometry_measure(geometry, dim) > 0:
            raise GeometryError(
                "the difference is empty: what is removed covers all of the body"
                if what == "difference" else f"the {what} is empty: the parts do not overlap")
        moved = roundoff_moved(geometry, dim) + sum(
            faceting_moved(b, g, count, dim) for b, g in zip(local, parts))
        if dim == 2:
            import shapely

            shape: Body = Lamina(Region.from_shapely(shapely.make_valid(geometry)), 1.0)
        else:
            mesh = geometry.to_mesh64()
            verts = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
            shape = MeshSolid(verts[np.asarray(mesh.tri_verts, dtype=np.int64)], 1.0)
        return shape, shape.mass_properties(), moved

    polytopes = all(b.is_polytope and b.mass_properties().exact for b in bodies)
    shape, fine, moved = integrated(segments)
    points = shape.hull_points()
    if polytopes:
        unit, exact = fine, True
        error = relative_bound(moved, fine, points)
        note = (f"the {what} of overlapping polytopes was computed on their faces in float64 "
                f"(no curves to facet): exact but for round-off, at most {error:.1e} (relative)")
    else:
        coarse = integrated(max(8, segments // 2))[1]
        unit, exact = combine([fine, coarse], [4 / 3, -1 / 3]), False
        # the faceted result's own bound, plus what the extrapolation changed
        error = relative_bound(moved, fine, points) + change(unit, fine, points)
        note = (
            f"the {what} of overlapping parts was computed on facets ({segments} and "
            f"{max(8, segments // 2)} segments per turn, extrapolated); relative error at most "
            f"{error:.1e}"
        )
    unit = replace(unit, notes=(), parts=1, exact=True, relative_error=0.0)
    if origin is not None:
        shape = shape.translated(origin)
    return Faceted(shape, unit, density, error, note, exact=exact, origin=origin,
                   operands=bodies if what == "union" else ())
