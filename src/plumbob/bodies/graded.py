"""Bodies of variable density: a density field ρ(x, y, z) integrated by quadrature.

The seed's section 2.3 defines the centre of mass of a lamina of surface
density f(x, y) as ``x_G = ∫ x f dA / ∫ f dA``; the same holds for a solid of
density ρ(x, y, z) with volume integrals. :func:`with_density_field` gives any
body a :class:`~plumbob.bodies.density_field.DensityField` and returns a body
whose ``mass_properties()`` evaluates those integrals (and the inertia tensor
``∫ (|r|² 1 − r rᵀ) ρ dV``) over the cells the body gives
(:meth:`~plumbob.bodies.base.Body.density_cells`; how each shape is tiled is
in :mod:`plumbob.bodies.tiling`). Placed bodies, composites (a hole subtracts
the field over the hole) and assemblies take the field part by part
(:meth:`~plumbob.bodies.base.Body.graded`), the field moving with each part.

A field with a known polynomial degree d is integrated in one pass by a rule of
degree d + 2 — exact, ``exact=True`` when the geometry is exact. Any other field
is integrated adaptively to ``tolerance`` (relative), reported with
``exact=False``, ``relative_error`` the estimate and a note.

The density is checked at the body's vertices and at every quadrature point: a
negative or non-finite value inside the body is a :class:`DensityError` naming
the point. Negative values outside the body (the signed decompositions sample
a little outside non-convex bodies, and over holes) cancel exactly and are
allowed; non-finite ones cannot cancel and are reported as such.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from ..errors import DensityError, GeometryError
from ..integrals.adaptive import MAX_EVALUATIONS, FieldIntegral, integrate_field
from ..integrals.mesh import mesh_field_moments
from ..massprops import MassProperties
from ..mesh.closure import require_sums_close
from .base import Body, Grader
from .cells import DensityCells
from .density_field import FIELD_DENSITY, DensityField
from .uniform import second_moments_to_inertia

__all__ = ["GradedBody", "GradedLamina", "GradedSolid", "with_density_field"]


def _num(value: float) -> str:
    text = f"{value:.6g}"
    return "−" + text[1:] if text.startswith("-") else text


def _point(p: np.ndarray) -> str:
    return "(" + ", ".join(_num(float(v)) for v in p) + ")"


# ------------------------------------------------------------------ graded bodies
@dataclass(frozen=True, eq=False, repr=False)
class GradedBody(Body):
    """A lamina or solid whose density is a field (see the module docstring).

    base: the geometry, a body with :meth:`~Body.density_cells` (a Lamina,
        MeshSolid, Extrusion or Revolution); its own density is ignored.
    field: the density, kg/m² on a lamina, kg/m³ on a solid, in the base's frame.
    tolerance: relative tolerance of adaptive integration (non-polynomial fields).
    exclude: holes of an enclosing composite: points in them are not in the body.
    hole: this body is itself a hole of a composite (its field is subtracted).
    max_evaluations: the budget of density evaluations for adaptive integration.
    """

    base: Body
    field: DensityField
    tolerance: float = 1e-10
    exclude: tuple[Body, ...] = ()
    hole: bool = False
    max_evaluations: int = MAX_EVALUATIONS

    def __post_init__(self) -> None:
        if not (0 < self.tolerance < 1):
            raise DensityError(f"a tolerance must lie between 0 and 1, not {self.tolerance:g}")
        object.__setattr__(self, "exclude", tuple(self.exclude))

    @property
    def kind(self) -> str:  # type: ignore[override]
        return self.base.kind

    @property
    def dim(self) -> int:  # type: ignore[override]
        return self.base.dim

    @property
    def name(self) -> str | None:  # type: ignore[override]
        return self.base.name

    @property
    def density(self) -> str:
        """``"field"`` (as :meth:`densities` reports a field); asking it for a number (a
        faceted boolean would) is a :class:`DensityError`."""
        return FIELD_DENSITY

    @property
    def units(self) -> str:
        return "kg/m²" if self.dim == 2 else "kg/m³"

    # -------------------------------------------------------- geometry, delegated
    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        return self.base.hull_points(tolerance)

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        return self.base.support_points(down, tolerance)

    def to_geometry(self, segments: int = 128):
        return self.base.to_geometry(segments)

    def surface(self, segments: int = 128):
        return self.base.surface(segments)

    def outline(self, tolerance: float, segments: int = 384) -> list[np.ndarray]:
        return self.base.outline(tolerance, segments)

    def with_default_density(self, density: float) -> Body:
        return self

    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        return self.base.contains(points, tolerance)

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return self.base._contains_tolerance(tolerance)

    @property
    def is_polytope(self) -> bool:
        return self.base.is_polytope

    def density_cells(self) -> DensityCells:
        return self.base.density_cells()

    def densities(self) -> set:
        return {FIELD_DENSITY}

    def graded(self, grader: Grader) -> Body:
        return self.base.graded(grader)  # a new field replaces this one

    def _describe(self) -> str:
        return f"density {self.field.text!r} {self.units} over {self.base!r}"

    # -------------------------------------------------------- checks
    def _where(self) -> str:
        return f" in part {self.name!r}" if self.name else ""

    def _fail(self, point: np.ndarray, value: float, where: str) -> None:
        what = "not finite" if not np.isfinite(value) else "negative"
        place = f"{self.field.place}: " if self.field.place else ""
        raise DensityError(
            f"{place}density {self.field.text!r} is {what} ({_num(value)} {self.units}) at "
            f"{_point(point)}{self._where()}{where}; a density must be finite and at least 0 "
            "everywhere in the body", path=self.field.path)

    def _check_corners(self, points: np.ndarray) -> None:
        """The field must be finite and ≥ 0 at the body's corners: the worst is reported."""
        values = self.field(points)
        ok = np.isfinite(values) & (values >= 0)
        if not ok.all():
            i = int(np.flatnonzero(~ok)[np.argmin(np.where(np.isfinite(values[~ok]),
                                                           values[~ok], -np.inf))])
            self._fail(points[i], values[i], "")

    def _inside(self, points: np.ndarray) -> np.ndarray:
        """Which points are in this body: in its base and in no hole of an enclosing composite."""
        inside = self.base.contains(points)
        for hole in self.exclude:
            if inside.any():
                inside &= ~hole.contains(points)
        return inside

    def _check_samples(self, integral: FieldIntegral) -> None:
        points, values = integral.bad_points, integral.bad_values
        if not len(values):
            return
        finite = np.isfinite(values)
        if not finite.all():
            i = int(np.flatnonzero(~finite)[0])
            inside = not self.hole and bool(self._inside(points[i:i + 1])[0])
            self._fail(points[i], values[i], "" if inside else (
                ", a point outside the body that its integration passes through (a hole, "
                "or the signed decomposition of a non-convex shape): the density must be "
                "finite there too"))
        if self.hole:
            return  # negative values over a hole are subtracted: nothing is wrong
        worst = min(len(values), 16)  # the worst first
        inside = self._inside(points[:worst])
        if inside.any():
            i = int(np.argmax(inside))
            self._fail(points[i], values[i], "")

    # -------------------------------------------------------- integration
    @cached_property
    def integral(self) -> FieldIntegral:
        """The raw moments of the field (see :class:`FieldIntegral`)."""
        cells = self.base.density_cells()
        if cells.triangles is not None and self.field.degree is not None:
            return self._mesh_integral(cells)
        self._check_corners(cells.corners())
        result = integrate_field(cells.tiles(), self.field, cells.origin, self.field.degree,
                                 tolerance=self.tolerance, size=cells.size,
                                 max_evaluations=self.max_evaluations)
        self._check_samples(result)
        return result

    def _mesh_integral(self, cells: DensityCells) -> FieldIntegral:
        """The fast exact path for a polynomial field over a closed mesh (one pass)."""
        result = mesh_field_moments(cells.triangles, self.field, cells.origin, self.field.degree)
        require_sums_close(result.vector_area, result.surface_area)
        if result.corner_values is not None and len(result.corner_values):
            self._fail(result.corner_points[0], result.corner_values[0], "")
        self._check_samples(result)
        return result

    def mass_properties(self) -> MassProperties:
        m = self.integral
        if not m.measure > 0:
            raise GeometryError(f"the body{self._where()} has no {'area' if self.dim == 2 else 'volume'}"
                                " (or its boundary runs the wrong way)")
        if not np.isfinite(m.mass) or m.mass <= 0:
            place = f"{self.field.place}: " if self.field.place else ""
            raise DensityError(f"{place}density {self.field.text!r} is zero everywhere in the "
                               f"body{self._where()}" if m.mass == 0 else
                               f"{place}density {self.field.text!r} gives the body"
                               f"{self._where()} no positive mass ({_num(m.mass)} kg)",
                               path=self.field.path)
        local = m.first / m.mass
        central = m.second - m.mass * np.outer(local, local)
        base_exact = bool(getattr(self.base, "exact", True))
        base_error = float(getattr(self.base, "relative_error", 0.0))
        error = m.error / m.mass
        notes = []
        base_note = getattr(self.base, "note", None)
        if base_note:
            notes.append(base_note)
        if m.exact:
            notes.append(f"density {self.field.text} (a polynomial of degree {self.field.degree}) "
                         "integrated exactly by Gauss–Jacobi quadrature")
        else:
            status = "" if m.converged else (
                f"; the tolerance {self.tolerance:.0e} was not reached within "
                f"{m.evaluations} evaluations")
            notes.append(f"density {self.field.text} integrated adaptively over {m.cells} cells: "
                         f"estimated relative error {error:.1e}{status}")
        return MassProperties(
            dim=self.dim, mass=m.mass, measure=m.measure, center_of_mass=m.origin + local,
            inertia=second_moments_to_inertia(central), exact=m.exact and base_exact,
            relative_error=(0.0 if m.exact else error) + (0.0 if base_exact else base_error),
            notes=tuple(notes))


@dataclass(frozen=True, eq=False, repr=False)
class GradedLamina(GradedBody):
    """A lamina whose areal density (kg/m²) is a field f(x, y)."""


@dataclass(frozen=True, eq=False, repr=False)
class GradedSolid(GradedBody):
    """A solid (closed mesh, prism or solid of revolution) whose density is a field ρ(x, y, z)."""


# ------------------------------------------------------------------ the entry point
@dataclass(frozen=True)
class _Grading:
    """The :class:`~plumbob.bodies.base.Grader` :func:`with_density_field` hands down a
    body's structure: the field as the current part sees it, and that part's holes."""

    field: DensityField
    tolerance: float
    max_evaluations: int
    exclude: tuple[Body, ...] = ()
    hole: bool = False

    def leaf(self, body: Body) -> Body:
        graded = GradedLamina if body.dim == 2 else GradedSolid
        return graded(body, self.field, self.tolerance, self.exclude, self.hole, self.max_evaluations)

    def placed(self, matrix: np.ndarray, offset: np.ndarray) -> _Grading:
        inverse = matrix.T
        back = -inverse @ offset
        return replace(self, field=self.field.composed(matrix, offset),
                       exclude=tuple(e.transformed(inverse, back) for e in self.exclude))

    def part(self, removed: bool, holes: tuple[Body, ...]) -> _Grading:
        hole = self.hole != removed
        return replace(self, hole=hole,
                       exclude=self.exclude if hole or self.hole else self.exclude + holes)

    def separate(self) -> _Grading:
        return replace(self, exclude=(), hole=False)


def with_density_field(body: Body, field: DensityField | Callable[[np.ndarray], np.ndarray], *,
                       tolerance: float = 1e-10, max_evaluations: int = MAX_EVALUATIONS) -> Body:
    """``body`` with its density given by ``field``, in world coordinates.

    Laminas, meshes, prisms and solids of revolution become :class:`GradedLamina`
    / :class:`GradedSolid`; placed bodies, composites and assemblies are
    rebuilt with every part graded (the field moves with the part when it is
    placed later). A graded body's field is replaced.

    Parameters
    ----------
    body : Body
        A lamina, solid, or a placement, composite or assembly of them.
    field : DensityField or callable
        kg/m³ on a solid, kg/m² on a lamina; a function of points (n, d) → (n,)
        is taken as a field of unknown degree (integrated adaptively).
    tolerance : float, default 1e-10
        Relative accuracy asked of non-polynomial fields, in (0, 1).
    max_evaluations : int
        Budget of density evaluations for adaptive integration.

    Returns
    -------
    Body
        Its ``mass_properties()`` integrate the field (lazily, on first call).

    Raises
    ------
    DensityError
        A field that is not a field, a tolerance outside (0, 1), or a body
        that takes no field (particles, a faceted boolean).

    Examples
    --------
    >>> from plumbob.bodies.primitives import rectangle
    >>> plate = with_density_field(rectangle(1, 1), DensityField.from_expression("1 + x"))
    >>> props = plate.mass_properties()
    >>> round(float(props.center_of_mass[0]), 15), props.exact   # the seed's x_G: 5/9
    (0.555555555555556, True)
    >>> from plumbob.bodies.particles import ParticleSystem
    >>> with_density_field(ParticleSystem([1.0], [[0, 0]]), lambda p: p[:, 0])
    Traceback (most recent call last):
    ...
    plumbob.errors.DensityError: particles have their own masses: a density field needs a lamina or a solid
    """
    if not isinstance(field, DensityField):
        if not callable(field):
            raise DensityError(f"a density field must be a DensityField or a function, not {field!r}")
        field = DensityField.from_callable(field)
    return body.graded(_Grading(field, tolerance, max_evaluations))
