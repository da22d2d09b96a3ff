"""What every body offers the rest of plumbob.

A body knows its mass properties and enough of its shape for stability:
points spanning its convex hull, and the points it touches a plane with.
Downstream code (stability, energy, reports) uses only this interface.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, NamedTuple, Protocol

import numpy as np

from ..arguments import check_density, placement, vector
from ..errors import BodyQueryError, GeometryError, PlumbobError
from ..lazy import lazy_exports
from ..massprops import MassProperties
from ..tolerances import contact_tolerance, size_of
from .checked import check_questions

if TYPE_CHECKING:
    from .cells import DensityCells

__all__ = ["Body", "DensityCells", "Grader", "Surface", "Transformed", "check_density",
           "DEFAULT_DENSITY_NOTE", "lowest", "contact_sampling", "manifold_surface"]

#: the cells a density field is integrated on live in :mod:`.cells`, loaded on first use
#: (a mesh read for its mass or poses never asks for them)
__getattr__, __dir__ = lazy_exports(__name__, {"DensityCells": "plumbob.bodies.cells"}, __all__)

DEFAULT_DENSITY_NOTE = "no density given: 1 kg/m³ (1 kg/m² for a lamina) assumed"


class Surface(NamedTuple):
    """A solid's closed boundary as triangles: what :meth:`Body.surface` gives.

    triangles: (n, 3, 3) float64, m, wound outward.
    exact: whether the triangles are the body's own boundary (a mesh, or a placement of
        one) rather than a faceting of curved faces.
    """

    triangles: np.ndarray
    exact: bool


def manifold_surface(manifold) -> np.ndarray:
    """The triangles (n, 3, 3), float64, of a manifold3d ``Manifold``."""
    mesh = manifold.to_mesh64()
    verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    return verts[np.asarray(mesh.tri_verts, dtype=np.int64)]


def _shapely_rings(geometry) -> list[np.ndarray]:
    """Closed rings (k, 2) of a shapely (multi)polygon."""
    rings = []
    for polygon in getattr(geometry, "geoms", [geometry]):
        if polygon.is_empty or polygon.geom_type != "Polygon":
            continue
        rings.append(np.asarray(polygon.exterior.coords)[::-1])
        rings += [np.asarray(r.coords)[::-1] for r in polygon.interiors]
    return rings


def contact_sampling(tolerance: float, size: float) -> float:
    """How finely to sample curved surfaces when looking for contact within ``tolerance``.

    Coarser than the contact tolerance on purpose: samples near a point of tangency
    (a sphere's bottom) then stay above the tolerance and only the exact contact
    points count, while samples on a flat contact (a cylinder's base rim) are exactly
    at the lowest level whatever the sampling.

    Parameters
    ----------
    tolerance : float
        The contact tolerance, m.
    size : float
        The body's size, m.

    Returns
    -------
    float
        The sampling tolerance, m.

    Examples
    --------
    >>> contact_sampling(1e-6, 1.0), contact_sampling(1e-4, 1.0)
    (0.001, 0.0064)
    """
    return max(64 * tolerance, 1e-3 * size)


def lowest(points: np.ndarray, down: np.ndarray, tolerance: float) -> np.ndarray:
    """The distinct points within ``tolerance`` of the lowest along ``down``.

    Parameters
    ----------
    points : ndarray, shape (n, d)
        m.
    down : ndarray, shape (d,)
        A unit vector.
    tolerance : float
        m.

    Returns
    -------
    ndarray, shape (k, d)
        Sorted, without repeats (and without negative zeros).

    Examples
    --------
    >>> pts = np.array([[1.0, 1e-9], [0.0, 0.0], [1.0, 1e-9], [0.5, 1.0]])
    >>> lowest(pts, np.array([0.0, -1.0]), 1e-6).tolist()
    [[0.0, 0.0], [1.0, 1e-09]]
    """
    depth = points @ down
    # return_index: without it numpy 2.3 imports numpy.ma (~10 ms) to rule out a masked array
    return np.unique(points[depth >= depth.max() - tolerance] + 0.0, axis=0, return_index=True)[0]


class Body(ABC):
    """A lamina, solid, particle system or assembly: what every body answers.

    kind: ``"lamina"``, ``"solid"``, ``"particles"`` or ``"assembly"``.
    dim: 2 for laminas (their own plane), 3 otherwise.

    Other rooms ask a body questions instead of testing its type. Every kind
    answers the abstract ones: :meth:`mass_properties`, :meth:`hull_points`,
    :meth:`contains`, :attr:`is_polytope` and :meth:`densities`. The others have a
    default that is right for most kinds and is overridden where it is not: the
    contact points (:meth:`support_points`), placements (:meth:`transformed`), a
    default density (:meth:`with_default_density`, :meth:`with_material`), its
    shape for booleans (:meth:`to_geometry`), its closed surface (:meth:`surface`,
    :meth:`as_mesh`, solids) or outline (:meth:`outline`, :meth:`exact_region`, laminas), its separate
    parts (:meth:`assembly_parts`), the cells a density field over it is
    integrated on (:meth:`density_cells`) and how it takes a density field
    (:meth:`graded`). A kind of body that cannot answer one raises
    :class:`~plumbob.errors.BodyQueryError` (or, where the question has a
    physical no, a :class:`~plumbob.errors.DensityError` or
    :class:`~plumbob.errors.GeometryError` saying why): nothing is guessed.
    """

    kind: str
    dim: int
    name: str | None = None

    def __init_subclass__(cls, **options) -> None:
        # every kind's questions check their arguments the same way (see bodies/checked.py)
        super().__init_subclass__(**options)
        check_questions(cls)

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
        """This body turned or mirrored by an orthogonal ``matrix`` (dim × dim), then moved
        by ``offset`` (dim,), m; a :class:`~plumbob.errors.GeometryError` naming the argument
        for anything else (a 2×2 matrix for a solid, a stretch, a NaN)."""
        matrix, offset = placement(matrix, offset, self.dim, error=GeometryError)
        return Transformed(self, matrix, offset)

    def translated(self, offset: np.ndarray | list[float]) -> Body:
        """This body moved by ``offset`` (dim,), m."""
        return self.transformed(np.eye(self.dim),
                                vector(offset, "offset", (self.dim,), error=GeometryError))

    @property
    def size(self) -> float:
        """Diagonal of the bounding box of the hull points, m."""
        return size_of(self.hull_points())

    def with_default_density(self, density: float) -> Body:
        """This body with ``density`` wherever no density was given."""
        return self

    def with_material(self, density: float | None, thickness: float | None = None) -> Body:
        """This body of one uniform material: ``density`` (kg/m³; None: none given) where
        no density was given. Only a lamina takes a ``thickness`` (m), which turns its
        kg/m³ into kg/m² (without one its density is areal, kg/m²)."""
        if thickness is not None:
            raise GeometryError("a thickness applies only to a lamina (2D shape)")
        return self if density is None else self.with_default_density(density)

    def plot(self, ax=None, **options):
        """Draw the body and its centre of mass; returns the matplotlib figure (``ax=None``
        makes a new one). See :func:`plumbob.plot.plot_body`."""
        from ..plot.body import plot_body

        return plot_body(self, ax, **options)

    def _repr_png_(self) -> bytes:  # notebooks show the picture
        from ..plot.files import png_bytes

        return png_bytes(self.plot())

    def _repr_html_(self) -> str:  # and, beside it, what it is and its mass properties
        return self.mass_properties()._repr_html_().replace(
            "<caption>MassProperties", f"<caption>{type(self).__name__}: mass properties", 1)

    def to_geometry(self, segments: int = 128):
        """The shape for boolean operations: a shapely geometry (laminas) or a
        manifold3d ``Manifold`` (solids), curves cut into ``segments`` per turn.
        Rooms outside ``bodies/`` ask for :meth:`surface` or :meth:`outline` instead."""
        raise GeometryError(f"a {self.kind} has no shape for boolean operations")

    def surface(self, segments: int = 128) -> Surface:
        """The solid's closed boundary as outward-wound triangles (see :class:`Surface`):
        a mesh's own triangles, else its boolean shape (:meth:`to_geometry`) with curves
        cut into ``segments`` chords a turn (a sagitta of at most 1 − cos(π/segments)
        of a radius, 3·10⁻⁴ at 128).

        Examples
        --------
        >>> from plumbob.bodies.primitives import box, sphere
        >>> box(1, 2, 3).surface().triangles.shape, box(1, 2, 3).surface().exact  # its own mesh
        ((12, 3, 3), True)
        >>> sphere(1).surface(16).exact
        False
        """
        if self.dim != 3:
            raise GeometryError(f"a {self.dim}D {self.kind} has no closed surface; ask for its outline")
        return Surface(manifold_surface(self.to_geometry(segments)), False)

    def as_mesh(self) -> Body | None:
        """The body as a triangle-mesh body (a :class:`~plumbob.bodies.solid.MeshSolid`,
        whose ``triangles`` and ``welded`` vertices are its own boundary) when it is one,
        placed as it is; None for other kinds. Cheap: nothing is welded until asked."""
        return None

    def outline(self, tolerance: float, segments: int = 384) -> list[np.ndarray]:
        """The lamina's boundary as closed rings (k, 2), m (first point repeated last),
        curves flattened to within ``tolerance`` m where the body knows them exactly,
        else cut into ``segments`` chords a turn by its boolean shape."""
        if self.dim != 2:
            raise GeometryError(f"a {self.dim}D {self.kind} has no outline; ask for its surface")
        return _shapely_rings(self.to_geometry(segments))

    def exact_region(self):
        """The lamina's exact shape as a :class:`~plumbob.bodies.region.Region` (lines,
        arcs and Béziers kept), to extrude or revolve: a plain lamina, or a composite of
        them (holes reversed). Other bodies (a placed lamina, a solid) raise a
        :class:`GeometryError`."""
        raise GeometryError(f"a {type(self).__name__} has no plain 2D profile")

    def assembly_parts(self) -> tuple[Body, ...]:
        """The separate parts an assembly is reported by, each a body of its own with its
        own material; empty for a body of one piece."""
        return ()

    # ------------------------------------------------------------ questions
    @abstractmethod
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        """Which points lie in the body or on its boundary.

        Parameters
        ----------
        points : array_like, shape (m, dim) or (dim,)
            m, in the body's frame.
        tolerance : float, optional
            m. Points within it of the body count as inside; a negative value
            asks for points at least that far inside. Default: 1e-6 of the
            body's size.

        Returns
        -------
        ndarray of bool, shape (m,)

        Examples
        --------
        >>> from plumbob.bodies.primitives import disc
        >>> disc(1).contains([[0, 0], [1, 0], [1, 1]]).tolist()
        [True, True, False]
        """

    def _contains_tolerance(self, tolerance: float | None) -> float:
        """The tolerance of :meth:`contains`, m: the one given, else 1e-6 of the size."""
        return contact_tolerance(self.size, tolerance)

    @property
    @abstractmethod
    def is_polytope(self) -> bool:
        """Whether :meth:`hull_points` are exact: the vertices of the body's convex hull,
        with no curved boundary sampled (meshes, polygons, prisms of polygons,
        particles, and placements and unions of them).

        Examples
        --------
        >>> from plumbob.bodies.primitives import box, cylinder
        >>> box(1, 1, 1).is_polytope, cylinder(1, 1).is_polytope
        (True, False)
        """

    def density_cells(self) -> DensityCells:
        """Where a density field over this body is integrated (see :class:`DensityCells`).

        Only bodies of one piece of geometry have cells (laminas, meshes, prisms,
        solids of revolution); placements and bodies of parts take a field part
        by part (:meth:`graded`).

        Raises
        ------
        BodyQueryError
            When this kind of body does not implement it.
        DensityError
            When no density field can be given to it (particles).

        Examples
        --------
        >>> from plumbob.bodies.primitives import rectangle
        >>> rectangle(2, 1).density_cells()
        <DensityCells about (0, 0), size 2.24 m>
        """
        raise BodyQueryError(f"a density field cannot be integrated over a {type(self).__name__}")

    @abstractmethod
    def densities(self) -> set:
        """The densities of the body's parts: kg/m³, areal kg/m² for laminas, None where
        not given, ``"field"`` for a density field; empty for particles (their
        masses are given).

        Examples
        --------
        >>> from plumbob.bodies.primitives import box, rectangle
        >>> box(1, 1, 1, density=2.0).densities(), rectangle(1, 1, density=3, thickness=0.5).densities()
        ({2.0}, {1.5})
        """

    def graded(self, grader: Grader) -> Body:
        """This body with a density field, as ``grader`` gives it (see
        :func:`plumbob.bodies.graded.with_density_field`, which makes the grader).

        A body with :meth:`density_cells` becomes one graded body; bodies made of
        parts (placements, composites, assemblies) override this to grade each
        part, telling the grader where the part sits.
        """
        self.density_cells()  # a body that cannot carry a field says so now
        return grader.leaf(self)

    # ------------------------------------------------------------ printing
    def __repr__(self) -> str:
        name = f" {self.name!r}" if self.name else ""
        text = self._describe()
        return f"<{type(self).__name__}{name}{' ' if text else ''}{text}>"

    def _describe(self) -> str:
        """A few words saying what the body is, for its repr: never its arrays."""
        return f"{self.dim}D {self.kind}"


def measure_words(body: Body) -> str:
    """The body's area or volume in words, for a repr; ``"no valid volume"`` (area) when
    its mass properties cannot be computed (an open mesh), so a repr never raises.

    >>> from plumbob.bodies.primitives import box, disc
    >>> measure_words(box(1, 2, 3)), measure_words(disc(1))
    ('volume 6 m³', 'area 3.14 m²')
    """
    what = "area" if body.dim == 2 else "volume"
    try:
        measure = body.mass_properties().measure
    except PlumbobError:
        return f"no valid {what}"
    return f"{what} {measure:.3g} {'m²' if body.dim == 2 else 'm³'}"


def density_words(density: float | None, unit: str = "kg/m³") -> str:
    """A density in words, for a repr, or nothing when no density was given.

    >>> density_words(2700.0), density_words(None)
    (', density 2700 kg/m³', '')
    """
    return "" if density is None else f", density {density:.4g} {unit}"


check_questions(Body)  # the defaults Body itself gives, as its subclasses' own are


class Grader(Protocol):
    """How a density field is given to a body, part by part (implemented by
    :func:`plumbob.bodies.graded.with_density_field`; bodies only call it)."""

    def leaf(self, body: Body) -> Body:
        """``body`` — one that has :meth:`Body.density_cells` — with the field."""

    def placed(self, matrix: np.ndarray, offset: np.ndarray) -> Grader:
        """The grader for the body inside a placement ``x ↦ matrix @ x + offset``."""

    def part(self, removed: bool, holes: tuple[Body, ...]) -> Grader:
        """The grader for one part of a composite (``removed``: a hole), whose
        ``holes`` are not in its added parts."""

    def separate(self) -> Grader:
        """The grader for one part of an assembly (a body of its own)."""


@dataclass(frozen=True, eq=False, repr=False)
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
        matrix, offset = placement(matrix, offset, self.dim, error=GeometryError)
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

    def surface(self, segments: int = 128) -> Surface:
        inner = self.body.surface(segments)
        moved = inner.triangles @ self.matrix.T + self.offset
        return Surface(moved[:, ::-1] if np.linalg.det(self.matrix) < 0 else moved, inner.exact)

    def as_mesh(self) -> Body | None:
        inner = self.body.as_mesh()
        return None if inner is None else inner.transformed(self.matrix, self.offset)

    def outline(self, tolerance: float, segments: int = 384) -> list[np.ndarray]:
        rings = [r @ self.matrix.T + self.offset for r in self.body.outline(tolerance, segments)]
        return [r[::-1] for r in rings] if np.linalg.det(self.matrix) < 0 else rings

    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        return self.body.contains((points - self.offset) @ self.matrix, tolerance)

    @property
    def is_polytope(self) -> bool:
        return self.body.is_polytope

    def densities(self) -> set:
        return self.body.densities()

    def graded(self, grader: Grader) -> Body:
        return replace(self, body=self.body.graded(grader.placed(self.matrix, self.offset)))

    def _describe(self) -> str:
        moves = []
        if not np.array_equal(self.matrix, np.eye(self.dim)):
            moves.append("mirrored" if np.linalg.det(self.matrix) < 0 else "turned")
        if np.any(self.offset):
            moves.append("moved by (" + ", ".join(f"{v:.4g}" for v in self.offset) + ")")
        return f"{self.body!r} {' and '.join(moves) or 'in place'}"
