"""Bodies of variable density: a density field ρ(x, y, z) integrated by quadrature.

The seed's section 2.3 defines the centre of mass of a lamina of surface
density f(x, y) as ``x_G = ∫ x f dA / ∫ f dA``; the same holds for a solid of
density ρ(x, y, z) with volume integrals. :func:`with_density_field` gives any
body a :class:`DensityField` and returns a body whose ``mass_properties()``
evaluates those integrals (and the inertia tensor ``∫ (|r|² 1 − r rᵀ) ρ dV``):

* laminas — the region's chord polygon is triangulated (shapely's constrained
  Delaunay triangulation, signed per ring when the rings do not nest cleanly),
  and every curved edge adds or removes its cap: circular caps by Gauss–Legendre
  in the arc's angle (exact to rounding: see
  :func:`plumbob.integrals.quadrature.arc_points_for_degree`), Bézier caps by
  Green's theorem along the curve (exact);
* closed meshes — the signed tetrahedra from a local origin near the mesh;
* prisms — the profile's cells times Gauss–Legendre in z (exact);
* solids of revolution — the profile's cells in (r, z) times the equally
  spaced rule in the angle (exact for polynomial densities: a polynomial in
  x, y is a trigonometric polynomial in the angle);
* placed bodies, composites (a hole subtracts the field over the hole) and
  assemblies — part by part, the field moving with each part.

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

from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np

from ..errors import DensityError, ExpressionError, GeometryError
from ..integrals.adaptive import MAX_EVALUATIONS, FieldIntegral, integrate_field
from ..integrals.cells import ArcCells, BezierCells, Cells, ProductCells, SimplexCells
from ..integrals.mesh import CHUNK as MESH_CHUNK
from ..integrals.mesh import mesh_field_moments
from ..massprops import MassProperties
from .base import Body, Transformed
from .lamina import Lamina, second_moments_to_inertia
from .region import Region
from .solid import CLOSURE_TOLERANCE, Extrusion, MeshSolid, Revolution

__all__ = ["DensityField", "GradedBody", "GradedLamina", "GradedSolid", "with_density_field",
           "region_cells"]

COORDINATES = ("x", "y", "z")


# ------------------------------------------------------------------ fields
class _FieldMarker(str):
    """The string "field", standing for a density field where a number is expected.

    Equal to "field"; ``float()`` of it raises a :class:`DensityError`, so code
    that would turn a graded body into a uniform one (a faceted boolean) stops
    with a message instead of silently dropping the field.
    """

    def __float__(self) -> float:
        raise DensityError(
            "a density field cannot be carried through a boolean of overlapping parts: "
            "combine the parts first, then give the combined body the field")


FIELD_DENSITY = _FieldMarker("field")


@dataclass(frozen=True, eq=False)
class DensityField:
    """A density given as a function of position.

    function: vectorised, points (n, d) m → values (n,): kg/m³ for solids,
        kg/m² (areal) for laminas, whose points have d = 2 (z = 0).
    degree: the polynomial degree in x, y, z, or None (not a polynomial, or
        not known): a polynomial field is integrated exactly.
    text: how the field is named in messages and notes.

    >>> f = DensityField.from_expression("1 + x")
    >>> f.degree, f(np.array([[0.5, 0.0]])).tolist()
    (1, [1.5])
    """

    function: Callable[[np.ndarray], np.ndarray]
    degree: int | None = None
    text: str = "the density field"

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise DensityError(f"a density field needs a function, not {self.function!r}")
        if self.degree is not None:
            if int(self.degree) != self.degree or self.degree < 0:
                raise DensityError(f"a polynomial degree is a whole number ≥ 0, not {self.degree!r}")
            object.__setattr__(self, "degree", int(self.degree))

    def __call__(self, points: np.ndarray) -> np.ndarray:
        """Values (n,) at ``points`` (n, d), d = 2 or 3 (m)."""
        pts = np.asarray(points, dtype=float)
        if pts.ndim == 1:
            pts = pts[None, :]
        values = np.asarray(self.function(pts), dtype=float)
        if values.ndim == 0:
            values = np.full(len(pts), float(values))
        values = values.reshape(-1)
        if values.shape != (len(pts),):
            raise DensityError(
                f"{self.text} gave {values.size} values for {len(pts)} points: a density "
                "function takes points (n, d) and returns n values")
        return values

    def __float__(self) -> float:
        raise DensityError(
            f"{self.text} is a density field, not a number: a boolean of overlapping "
            "parts cannot carry it; combine the parts first, then give the body the field")

    # ---------------------------------------------------------- constructors
    @classmethod
    def from_expression(cls, expression, scale: float = 1.0, *,
                        constants: Mapping[str, float] | None = None) -> DensityField:
        """A field from a spec expression in x, y, z (an ``Expression`` or its text).

        ``scale`` multiplies every value (e.g. a lamina's thickness, m, turning
        kg/m³ into kg/m²); ``constants`` supplies other names (parameters).

        >>> DensityField.from_expression("2400 * (1 + 0.1*z)").degree
        1
        >>> DensityField.from_expression("exp(x)").degree is None
        True
        """
        from ..expr import Expression, parse

        if isinstance(expression, str):
            expression = parse(expression)
        if not isinstance(expression, Expression):
            raise DensityError(f"a density expression must be text, not {expression!r}")
        constants = {k: float(v) for k, v in (constants or {}).items()}
        unknown = set(expression.names) - set(COORDINATES) - set(constants)
        if unknown:
            raise ExpressionError(
                f"in {expression.text!r}: unknown name(s) {', '.join(sorted(unknown))}; "
                "a density field may use x, y, z and the spec's parameters")
        scale = float(scale)
        if not (np.isfinite(scale) and scale > 0):
            raise DensityError(f"a density scale must be a positive number, not {scale:g}")
        coordinates = {n for n in expression.names if n in COORDINATES}
        degree = expression.degree(set(COORDINATES)) if coordinates else 0

        def function(points: np.ndarray) -> np.ndarray:
            env: dict[str, float | np.ndarray] = dict(constants)
            env["x"], env["y"] = points[:, 0], points[:, 1]
            env["z"] = points[:, 2] if points.shape[1] > 2 else np.zeros(len(points))
            values = expression.evaluate(env)
            return values * scale if scale != 1.0 else values

        text = expression.text if scale == 1.0 else f"({expression.text}) × {scale:g}"
        return cls(function, degree, text)

    @classmethod
    def from_callable(cls, f: Callable[[np.ndarray], np.ndarray], degree: int | None = None,
                      text: str | None = None) -> DensityField:
        """A field from a Python function of points (n, d) → (n,).

        Give ``degree`` only when ``f`` is a polynomial of at most that degree:
        the rule is then chosen to be exact for it, and nothing checks the claim.

        >>> DensityField.from_callable(lambda p: 1 + p[:, 0] ** 2, degree=2).degree
        2
        """
        return cls(f, degree, text or getattr(f, "__name__", "the density field"))

    # ---------------------------------------------------------- algebra
    def composed(self, matrix: np.ndarray, offset: np.ndarray) -> DensityField:
        """The field seen from a body placed by ``p ↦ matrix @ p + offset``: ``p ↦ f(M p + o)``.

        An affine substitution keeps the polynomial degree.
        """
        matrix = np.asarray(matrix, dtype=float)
        offset = np.asarray(offset, dtype=float)
        outer = self

        def function(points: np.ndarray) -> np.ndarray:
            return outer.function(points @ matrix.T + offset)

        return DensityField(function, self.degree, self.text)

    def scaled(self, factor: float) -> DensityField:
        """Every value multiplied by ``factor`` (> 0)."""
        factor = float(factor)
        if not (np.isfinite(factor) and factor > 0):
            raise DensityError(f"a density scale must be a positive number, not {factor:g}")
        outer = self
        return DensityField(lambda p: outer.function(p) * factor, self.degree,
                            f"({self.text}) × {factor:g}")


# ------------------------------------------------------------------ regions → cells
def _num(value: float) -> str:
    text = f"{value:.6g}"
    return "−" + text[1:] if text.startswith("-") else text


def _point(p: np.ndarray) -> str:
    return "(" + ", ".join(_num(float(v)) for v in p) + ")"


def _signed_area(v: np.ndarray) -> float:
    x, y = v[:, 0] - v[0, 0], v[:, 1] - v[0, 1]
    return float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)) / 2


def _orient(triangles: np.ndarray, sign: float) -> np.ndarray:
    """Triangles (m, 3, 2) turned so their orientation has ``sign``."""
    e = triangles[:, 1:] - triangles[:, :1]
    det = e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0]
    flip = np.sign(det) == -np.sign(sign)
    out = triangles.copy()
    out[flip, 1:] = out[flip, 1:][:, ::-1]
    return out


def _cdt(geometry) -> np.ndarray:
    import shapely

    parts = shapely.get_parts(shapely.constrained_delaunay_triangles(geometry))
    if len(parts) == 0:
        return np.zeros((0, 3, 2))
    coords = shapely.get_coordinates(parts)
    return coords.reshape(len(parts), 4, 2)[:, :3]


def _fan(v: np.ndarray) -> np.ndarray:
    """Signed fan of a closed polygon (n, 2) from its first vertex: exact for any polygon."""
    n = len(v)
    return np.stack((np.broadcast_to(v[0], (n - 2, 2)), v[1:-1], v[2:]), axis=1)


def _chord_triangles(region: Region) -> np.ndarray:
    """Signed triangles (m, 3, 2), world coordinates, tiling the region's chord polygons.

    Clean regions (outer rings disjoint, holes inside them and disjoint) are
    triangulated as one polygon, so no point falls in a hole; otherwise each
    ring is triangulated on its own and signed by its orientation (the sum is
    the same, by Green's theorem).
    """
    import shapely

    rings = [r.vertices for r in region.rings if len(r.vertices) >= 3]
    areas = [_signed_area(v) for v in rings]
    scale = sum(abs(a) for a in areas)
    if scale == 0:
        return np.zeros((0, 3, 2))
    rings = [(v, a) for v, a in zip(rings, areas) if abs(a) > 1e-15 * scale]
    polys = [shapely.Polygon(v) for v, _ in rings]
    simple = [bool(p.is_valid) for p in polys]
    if all(simple):
        shells = [p for p, (_, a) in zip(polys, rings) if a > 0]
        holes = [p for p, (_, a) in zip(polys, rings) if a < 0]
        tol = 1e-12 * scale
        union = shapely.union_all(shells)
        clean = abs(union.area - sum(p.area for p in shells)) <= tol
        if clean and holes:
            hole_union = shapely.union_all(holes)
            clean = (abs(hole_union.area - sum(p.area for p in holes)) <= tol
                     and abs(shapely.intersection(union, hole_union).area - hole_union.area) <= tol)
            union = shapely.difference(union, hole_union) if clean else union
        if clean:
            tris = _orient(_cdt(union), 1.0)
            if abs(_tri_area(tris) - sum(areas)) <= 1e-11 * scale:
                return tris
    pieces = []
    for poly, ok, (v, a) in zip(polys, simple, rings):
        tris = _cdt(poly) if ok else np.zeros((0, 3, 2))
        if not ok or abs(_tri_area(tris) - abs(a)) > 1e-11 * abs(a):
            pieces.append(_fan(v))  # signed by construction
        else:
            pieces.append(_orient(tris, np.sign(a)))
    return np.concatenate(pieces) if pieces else np.zeros((0, 3, 2))


def _tri_area(t: np.ndarray) -> float:
    e = t[:, 1:] - t[:, :1]
    return float(np.abs(e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0]).sum() / 2)


def region_cells(region: Region, origin: np.ndarray) -> list[Cells]:
    """Signed cells tiling ``region`` (coordinates relative to ``origin`` (2,), m).

    Triangles of the chord polygon, one :class:`ArcCells` per circular edge (plus
    a rectangle of two triangles for a cap larger than a half disc) and one
    :class:`BezierCells` per Bézier edge.
    """
    from ..integrals.polygon import bulge_arc_geometry

    origin = np.asarray(origin, dtype=float)
    tris = [_chord_triangles(region)]
    arcs: list[tuple[np.ndarray, ...]] = []
    beziers: list[np.ndarray] = []
    for ring in region.rings:
        if ring.bulges is not None:
            mask = ring.bulges != 0
            p0, p1 = ring._ends(mask)
            centre, radius, alpha, bisector = bulge_arc_geometry(p0, p1, ring.bulges[mask])
            normal = np.stack((-bisector[:, 1], bisector[:, 0]), axis=1)
            frame = np.stack((bisector, normal), axis=2)  # columns
            sign = np.sign(ring.bulges[mask])
            arcs.append((centre, radius, frame, alpha, sign))
            big = alpha > np.pi / 2
            if big.any():
                x0 = radius[big] * np.cos(alpha[big])
                h = radius[big] * np.sin(alpha[big])
                z = np.zeros_like(x0)
                corners = np.stack([np.stack(c, axis=1) for c in
                                    ((x0, -h), (z, -h), (z, h), (x0, h))], axis=1)  # (m, 4, 2)
                world = centre[big][:, None, :] + np.einsum("kij,knj->kni", frame[big], corners)
                for s in (1.0, -1.0):
                    pick = sign[big] == s
                    quads = world[pick]
                    t = np.concatenate((quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]))
                    tris.append(_orient(t, s))
        if ring.controls is not None:
            curved = ~np.isnan(ring.controls).any(axis=(1, 2))
            p0, p1 = ring._ends(curved)
            beziers.append(np.concatenate((p0[:, None], ring.controls[curved], p1[:, None]), axis=1))
    cells: list[Cells] = [SimplexCells(np.concatenate(tris) - origin)]
    if arcs:
        centre, radius, frame, alpha, sign = (np.concatenate(a) for a in zip(*arcs))
        box = np.tile(np.array([[0.0, 1.0], [0.0, 1.0]]), (len(radius), 1, 1))
        cells.append(ArcCells(box=box, centre=centre - origin, radius=radius, frame=frame,
                              half_angle=alpha, sign=sign))
    if beziers:
        ctrl = np.concatenate(beziers)
        along = ctrl[:, 3] - ctrl[:, 0]
        length = np.hypot(along[:, 0], along[:, 1])
        along = np.where(length[:, None] > 0, along / np.where(length > 0, length, 1)[:, None],
                         np.array([0.0, 1.0]))
        across = np.stack((along[:, 1], -along[:, 0]), axis=1)
        frame = np.stack((across, along), axis=2)
        box = np.tile(np.array([[0.0, 1.0], [0.0, 1.0]]), (len(ctrl), 1, 1))
        cells.append(BezierCells(box=box, controls=ctrl - origin, frame=frame))
    return cells


# ------------------------------------------------------------------ inside tests
def _region_contains(region: Region, points: np.ndarray, tol: float) -> np.ndarray:
    import shapely

    geometry = region.to_shapely(tol / 4)
    return shapely.dwithin(geometry, shapely.points(points[:, :2]), tol)


def _winding(triangles: np.ndarray, point: np.ndarray) -> float:
    """Generalised winding number of a closed mesh (n, 3, 3) about ``point`` (3,)."""
    total = 0.0
    for start in range(0, len(triangles), MESH_CHUNK):
        t = triangles[start:start + MESH_CHUNK].astype(float) - point
        a, b, c = t[:, 0], t[:, 1], t[:, 2]
        la, lb, lc = (np.sqrt(np.einsum("ij,ij->i", v, v)) for v in (a, b, c))
        num = np.einsum("ij,ij->i", a, np.cross(b, c))
        den = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc
               + np.einsum("ij,ij->i", a, c) * lb + np.einsum("ij,ij->i", b, c) * la)
        total += float(np.arctan2(num, den).sum())
    return total / (2 * np.pi)


def _contains(body: Body, points: np.ndarray) -> np.ndarray:
    """Which of ``points`` (m, d) lie in ``body`` or within 1e-6 of its size of it."""
    points = np.asarray(points, dtype=float)
    if isinstance(body, GradedBody):
        return _contains(body.base, points)
    if isinstance(body, Transformed):
        return _contains(body.body, (points - body.offset) @ body.matrix)
    if isinstance(body, Lamina):
        return _region_contains(body.region, points, 1e-6 * body.region.size)
    if isinstance(body, Extrusion):
        tol = 1e-6 * body.profile.size
        z = points[:, 2]
        return (_region_contains(body.profile, points, tol) & (z >= -tol)
                & (z <= body.height + tol))
    if isinstance(body, Revolution):
        tol = 1e-6 * body.profile.size
        rz = np.stack((np.hypot(points[:, 0], points[:, 1]), points[:, 2]), axis=1)
        return _region_contains(body.profile, rz, tol)
    if isinstance(body, MeshSolid):
        return np.array([_winding(body.triangles, p) > 0.5 for p in points], dtype=bool)
    parts = getattr(body, "parts", None)
    if parts is not None:
        signs = getattr(body, "signs", (1.0,) * len(parts))
        inside = np.zeros(len(points), dtype=bool)
        for part, sign in zip(parts, signs):
            if sign > 0:
                inside |= _contains(part, points)
        for part, sign in zip(parts, signs):
            if sign < 0:
                inside &= ~_contains(part, points)
        return inside
    return np.ones(len(points), dtype=bool)  # unknown kind of body: assume inside


# ------------------------------------------------------------------ graded bodies
@dataclass(frozen=True, eq=False)
class GradedBody(Body):
    """A lamina or solid whose density is a field (see the module docstring).

    base: the geometry (a Lamina, MeshSolid, Extrusion or Revolution); its own
        density is ignored.
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
        """``"field"`` (as :func:`plumbob.bodies.csg.leaf_densities` reports a field); asking
        it for a number (a faceted boolean would) is a :class:`DensityError`."""
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

    def with_default_density(self, density: float) -> Body:
        return self

    # -------------------------------------------------------- integration
    def _cells(self) -> tuple[list[Cells], np.ndarray, float]:
        """Cells, the local origin (dim,) and the body's size (m)."""
        raise NotImplementedError

    def _boundary_points(self) -> np.ndarray:
        return self.base.hull_points()

    def _where(self) -> str:
        return f" in part {self.name!r}" if self.name else ""

    def _check_boundary(self) -> None:
        points = self._boundary_points()
        values = self.field(points)
        ok = np.isfinite(values) & (values >= 0)
        if not ok.all():
            i = int(np.flatnonzero(~ok)[np.argmin(np.where(np.isfinite(values[~ok]),
                                                           values[~ok], -np.inf))])
            self._fail(points[i], values[i], "")

    def _fail(self, point: np.ndarray, value: float, where: str) -> None:
        what = "not finite" if not np.isfinite(value) else "negative"
        raise DensityError(
            f"density {self.field.text!r} is {what} ({_num(value)} {self.units}) at "
            f"{_point(point)}{self._where()}{where}")

    def _check_samples(self, integral: FieldIntegral) -> None:
        points, values = integral.bad_points, integral.bad_values
        if not len(values):
            return
        finite = np.isfinite(values)
        if not finite.all():
            i = int(np.flatnonzero(~finite)[0])
            inside = bool(_contains(self.base, points[i:i + 1])[0]) and not self.hole
            if inside and self.exclude:
                inside = not any(_contains(e, points[i:i + 1])[0] for e in self.exclude)
            self._fail(points[i], values[i], "" if inside else (
                ", a point outside the body that its integration passes through (a hole, "
                "or the signed decomposition of a non-convex shape): the density must be "
                "finite there too"))
        if self.hole:
            return  # negative values over a hole are subtracted: nothing is wrong
        for i in range(min(len(values), 16)):  # the worst first
            p = points[i:i + 1]
            if _contains(self.base, p)[0] and not any(_contains(e, p)[0] for e in self.exclude):
                self._fail(points[i], values[i], "")

    @cached_property
    def integral(self) -> FieldIntegral:
        """The raw moments of the field (see :class:`FieldIntegral`)."""
        if isinstance(self.base, MeshSolid) and self.field.degree is not None:
            return self._mesh_integral()
        self._check_boundary()
        cells, origin, size = self._cells()
        result = integrate_field(cells, self.field, origin, self.field.degree,
                                 tolerance=self.tolerance, size=size,
                                 max_evaluations=self.max_evaluations)
        self._check_samples(result)
        return result

    def _mesh_integral(self) -> FieldIntegral:
        """The fast exact path for a polynomial field over a closed mesh (one pass)."""
        tri = self.base.triangles  # type: ignore[attr-defined]
        origin = tri[: min(len(tri), 1024)].reshape(-1, 3).mean(axis=0, dtype=float)
        result = mesh_field_moments(tri, self.field, origin, self.field.degree)
        if not np.all(np.isfinite(result.vector_area)):
            raise GeometryError("the mesh has a coordinate that is not a finite number")
        if np.linalg.norm(result.vector_area) > CLOSURE_TOLERANCE * max(result.surface_area, 1e-300):
            raise GeometryError(
                "the mesh is not closed (its faces do not enclose a volume, so any "
                "volume would depend on the origin): repair it or pass --repair")
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
            raise DensityError(f"density {self.field.text!r} is zero everywhere in the body"
                               f"{self._where()}" if m.mass == 0 else
                               f"density {self.field.text!r} gives the body{self._where()} "
                               f"no positive mass ({_num(m.mass)} kg)")
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


@dataclass(frozen=True, eq=False)
class GradedLamina(GradedBody):
    """A lamina whose areal density (kg/m²) is a field f(x, y)."""

    def _cells(self) -> tuple[list[Cells], np.ndarray, float]:
        region = self.base.region  # type: ignore[attr-defined]
        origin = region.local_origin()
        return region_cells(region, origin), origin, region.size


@dataclass(frozen=True, eq=False)
class GradedSolid(GradedBody):
    """A solid (closed mesh, prism or solid of revolution) whose density is a field ρ(x, y, z)."""

    def _boundary_points(self) -> np.ndarray:
        if isinstance(self.base, MeshSolid):
            return self.base.triangles.reshape(-1, 3).astype(float)
        return self.base.hull_points()

    def _cells(self) -> tuple[list[Cells], np.ndarray, float]:
        base = self.base
        if isinstance(base, MeshSolid):
            tri = base.triangles
            n = len(tri)
            origin = tri[: min(n, 1024)].reshape(-1, 3).mean(axis=0, dtype=float)
            _check_closed(tri)
            size = float(np.linalg.norm(np.ptp(tri[: min(n, 4096)].reshape(-1, 3), axis=0)))
            return [SimplexCells(tri.astype(float) - origin)], origin, size
        if isinstance(base, Extrusion):
            o2 = base.profile.local_origin()
            flat = region_cells(base.profile, o2)
            cells = [ProductCells(c, np.tile([0.0, base.height], (len(c), 1)), "z") for c in flat]
            return cells, np.append(o2, 0.0), float(np.hypot(base.profile.size, base.height))
        if isinstance(base, Revolution):
            z0 = float(base.profile.local_origin()[1])
            flat = region_cells(base.profile, np.array([0.0, z0]))
            cells = [ProductCells(c, np.tile([0.0, 2 * np.pi], (len(c), 1)), "phi", periodic=True)
                     for c in flat]
            return cells, np.array([0.0, 0.0, z0]), 2 * base.profile.size
        raise DensityError(f"a density field cannot be integrated over a {type(base).__name__}")


def _check_closed(triangles: np.ndarray) -> None:
    """The mesh must be closed, as :class:`MeshSolid` requires: its vector area vanishes."""
    vector = np.zeros(3)
    area = 0.0
    for start in range(0, len(triangles), MESH_CHUNK):
        t = triangles[start:start + MESH_CHUNK].astype(float, copy=False)
        normal = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        vector += normal.sum(axis=0)
        area += float(np.sqrt(np.einsum("ij,ij->i", normal, normal)).sum())
    if not np.all(np.isfinite(vector)):
        raise GeometryError("the mesh has a coordinate that is not a finite number")
    if np.linalg.norm(vector) > CLOSURE_TOLERANCE * max(area, 1e-300):
        raise GeometryError(
            "the mesh is not closed (its faces do not enclose a volume, so any "
            "volume would depend on the origin): repair it or pass --repair")


# ------------------------------------------------------------------ the entry point
def with_density_field(body: Body, field: DensityField | Callable[[np.ndarray], np.ndarray], *,
                       tolerance: float = 1e-10, max_evaluations: int = MAX_EVALUATIONS,
                       _exclude: tuple[Body, ...] = (), _hole: bool = False) -> Body:
    """``body`` with its density given by ``field`` (kg/m³; kg/m² for a lamina), in world coordinates.

    Laminas, meshes, prisms and solids of revolution become :class:`GradedLamina`
    / :class:`GradedSolid`; placed bodies, composites and assemblies are
    rebuilt with every part graded (the field moves with the part when it is
    placed later). ``tolerance`` is the relative accuracy asked of
    non-polynomial fields.

    >>> from plumbob.bodies.primitives import rectangle
    >>> plate = with_density_field(rectangle(1, 1), DensityField.from_expression("1 + x"))
    >>> props = plate.mass_properties()
    >>> round(float(props.center_of_mass[0]), 15), props.exact   # the seed's x_G: 5/9
    (0.555555555555556, True)
    """
    if not isinstance(field, DensityField):
        if not callable(field):
            raise DensityError(f"a density field must be a DensityField or a function, not {field!r}")
        field = DensityField.from_callable(field)
    kw = {"tolerance": tolerance, "max_evaluations": max_evaluations}
    if isinstance(body, GradedBody):
        body = body.base
    if isinstance(body, Lamina):
        return GradedLamina(body, field, tolerance, _exclude, _hole, max_evaluations)
    if isinstance(body, (MeshSolid, Extrusion, Revolution)):
        return GradedSolid(body, field, tolerance, _exclude, _hole, max_evaluations)
    if isinstance(body, Transformed):
        inverse = body.matrix.T
        back = -inverse @ body.offset
        exclude = tuple(e.transformed(inverse, back) for e in _exclude)
        inner = with_density_field(body.body, field.composed(body.matrix, body.offset), **kw,
                                   _exclude=exclude, _hole=_hole)
        return replace(body, body=inner)
    from .csg import Assembly, Composite

    if isinstance(body, Composite):
        holes = tuple(p for p, s in zip(body.parts, body.signs) if s < 0)
        parts = []
        for part, sign in zip(body.parts, body.signs):
            is_hole = _hole != (sign < 0)
            exclude = _exclude if is_hole or _hole else _exclude + holes
            parts.append(with_density_field(part, field, **kw, _exclude=exclude, _hole=is_hole))
        return replace(body, parts=tuple(parts))
    if isinstance(body, Assembly):
        return replace(body, parts=tuple(with_density_field(p, field, **kw) for p in body.parts))
    if getattr(body, "kind", None) == "particles":
        raise DensityError("particles have their own masses: a density field needs a lamina or a solid")
    raise DensityError(f"a density field cannot be applied to a {type(body).__name__}")
