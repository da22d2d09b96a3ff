"""Bodies with density fields (plumbob.bodies.graded).

Every number is checked against a closed form (monomials over boxes, discs,
balls), exact rational arithmetic (polygons), an independent 1D quadrature
(sectors, annuli), or the uniform bodies' exact Green/divergence-theorem
integrals.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np
import pytest
from conftest import rel, star_polygon
from hypothesis import given
from hypothesis import strategies as st
from polynomial_reference import (
    evaluate_poly,
    moment_polys,
    monomials,
    simplex_monomial_table,
)

from plumbob.bodies import primitives as prim
from plumbob.bodies.csg import Assembly, Composite, union
from plumbob.bodies.density_field import DensityField
from plumbob.bodies.graded import (
    GradedLamina,
    GradedSolid,
    with_density_field,
)
from plumbob.bodies.lamina import Lamina
from plumbob.bodies.region import Region, Ring
from plumbob.bodies.solid import MeshSolid
from plumbob.errors import DensityError, ExpressionError, GeometryError
from plumbob.expr import parse
from plumbob.massprops import MassProperties, combine, rotation_matrix

F = DensityField.from_expression


# ------------------------------------------------------------------ references


def reference(poly: dict, centre, monomial_integral, dim: int) -> MassProperties:
    """Mass properties of the density poly(w), w = x − centre, from exact monomial integrals."""
    sums = [sum(float(c) * monomial_integral(e) for e, c in m.items())
            for m in moment_polys(poly, dim)]
    mass = sums[0]
    first = np.array(sums[1:1 + dim])
    second = np.array(sums[1 + dim:]).reshape(dim, dim)
    c = first / mass
    central = np.zeros((3, 3))
    central[:dim, :dim] = second - mass * np.outer(c, c)
    inertia = np.trace(central) * np.eye(3) - central
    return MassProperties(dim, mass, 0.0, np.asarray(centre, float) + c, inertia)


def bounded_poly(rng, dim: int, degree: int, scale: float) -> dict:
    """2 + Σ a_β (w/scale)^β with Σ|a| ≤ 1: positive wherever |w_i| ≤ scale."""
    terms = [e for e in monomials(dim, degree) if sum(e)]
    a = rng.uniform(-1, 1, len(terms))
    a /= np.abs(a).sum()
    poly = {(0,) * dim: Fraction(2)}
    for e, c in zip(terms, a):
        poly[e] = Fraction(float(c)) / Fraction(float(scale)) ** sum(e)
    return poly


def poly_field(poly: dict, centre, degree: int) -> DensityField:
    centre = np.asarray(centre, dtype=float)
    return DensityField.from_callable(lambda p: evaluate_poly(poly, p - centre[: p.shape[1]]),
                                      degree=degree)


def assert_matches(got: MassProperties, want: MassProperties, size: float, tol: float = 1e-12):
    assert got.mass == pytest.approx(want.mass, rel=tol)
    assert rel(got.center_of_mass, want.center_of_mass, scale=size) <= tol
    assert rel(got.inertia, want.inertia) <= tol


def disc_monomial(a: int, b: int, r: float) -> float:
    """∫ x^a y^b over the disc of radius r about the origin."""
    if a % 2 or b % 2:
        return 0.0
    return (2 * math.gamma((a + 1) / 2) * math.gamma((b + 1) / 2)
            / ((a + b + 2) * math.gamma((a + b + 2) / 2)) * r ** (a + b + 2))


def ball_monomial(a: int, b: int, c: int, r: float) -> float:
    if a % 2 or b % 2 or c % 2:
        return 0.0
    g = math.gamma
    return (2 * g((a + 1) / 2) * g((b + 1) / 2) * g((c + 1) / 2)
            / ((a + b + c + 3) * g((a + b + c + 3) / 2)) * r ** (a + b + c + 3))


def polar_monomial(a: int, b: int, r0: float, r1: float, t0: float, t1: float) -> float:
    """∫ x^a y^b over r0 ≤ r ≤ r1, t0 ≤ θ ≤ t1: exact in r, scipy's quad in θ."""
    from scipy.integrate import quad

    k = a + b + 2
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # quad says it reached rounding: that is the point
        ang = quad(lambda t: np.cos(t) ** a * np.sin(t) ** b, t0, t1, epsabs=0, epsrel=2e-14,
                   limit=200)[0]
    return (r1**k - r0**k) / k * ang


FAR2 = np.array([1.0e3, -7.0e2])  # a field in world coordinates carries eps·|x|/size
FAR3 = np.array([8.0e2, -3.0e2, 6.0e2])


# ------------------------------------------------------------------ the field object


def test_field_from_expression():
    f = F("2400 * (1 + 0.1*z)")
    assert f.degree == 1 and f.text == "2400 * (1 + 0.1*z)"
    np.testing.assert_allclose(f(np.array([[0, 0, 1.0], [5, 5, -1.0]])), [2640, 2160])
    assert f(np.array([[1.0, 2.0]])).tolist() == [2400.0]  # a lamina's points: z = 0
    assert F("x^2*y + 3").degree == 3 and F("(x+1)^6").degree == 6
    assert F("exp(x)").degree is None and F("step(x - 1)").degree is None
    assert F("sqrt(x)").degree is None and F("1/x").degree is None


def test_field_scale_and_constants():
    f = F(parse("rho * (1 + k*x)"), scale=0.01, constants={"rho": 1000, "k": 0.5})
    assert f.degree == 1
    assert f(np.array([[2.0, 0.0]]))[0] == pytest.approx(20.0)
    with pytest.raises(ExpressionError, match="unknown name"):
        F("rho * x")
    with pytest.raises(DensityError, match="scale"):
        F("x", scale=0)


def test_field_from_callable_checks_its_output():
    f = DensityField.from_callable(lambda p: np.ones(len(p) + 1))
    with pytest.raises(DensityError, match="values for"):
        f(np.zeros((3, 3)))
    assert DensityField.from_callable(lambda p: 7.0)(np.zeros((4, 2))).tolist() == [7.0] * 4
    with pytest.raises(DensityError):
        DensityField.from_callable(lambda p: p[:, 0], degree=-1)


def test_composed_field_moves_with_the_body():
    f = F("x + 2*y")
    m = rotation_matrix([0, 0, 1], 0.3)[:2, :2]
    g = f.composed(m, np.array([1.0, 2.0]))
    p = np.array([[0.4, -0.7]])
    assert g(p)[0] == pytest.approx(f(p @ m.T + [1, 2])[0])
    assert g.degree == 1


# ------------------------------------------------------------------ exactness, laminas


def test_graded_plate_closed_form():
    """The seed's lamina of surface density f = 1 + x on the unit square: x_G = 5/9."""
    props = with_density_field(prim.rectangle(1, 1), F("1 + x")).mass_properties()
    assert props.exact and props.relative_error == 0
    assert props.mass == pytest.approx(1.5, rel=1e-15)
    np.testing.assert_allclose(props.center_of_mass, [5 / 9, 0.5], rtol=1e-15)
    assert props.area == pytest.approx(1.0, rel=1e-15)
    # I_yy = ∫ x² f dA − M x_G² = (1/3 + 1/4) − 1.5 (5/9)²
    assert props.inertia[1, 1] == pytest.approx(7 / 12 - 1.5 * 25 / 81, rel=1e-14)


@pytest.mark.parametrize("seed", range(4))
def test_polynomial_density_on_polygon_exact_far_away(seed):
    rng = np.random.default_rng(seed)
    degree = int(rng.integers(1, 7))
    verts = star_polygon(rng, 9) + FAR2
    body = prim.polygon(verts)
    poly = bounded_poly(rng, 2, degree, 1.0)
    props = with_density_field(body, poly_field(poly, FAR2, degree)).mass_properties()
    # Exact rationals over a fan of the star polygon (about its kernel point FAR2).
    tris = [np.array([[0.0, 0.0], verts[i] - FAR2, verts[(i + 1) % 9] - FAR2]) for i in range(9)]
    tables = [simplex_monomial_table(t, degree + 2) for t in tris]
    want = reference(poly, FAR2, lambda e: float(sum(t[e] for t in tables)), 2)
    assert props.exact
    assert_matches(props, want, 2.0)


@pytest.mark.parametrize("shape", ["disc", "semicircle", "sector_big", "sector_small", "annulus"])
def test_polynomial_density_on_arc_laminas_exact(shape):
    rng = np.random.default_rng(hash(shape) % 2**32)
    r = 1.7
    if shape == "disc":
        body, mono = prim.disc(r), lambda e: disc_monomial(*e, r)
    elif shape == "semicircle":
        body, mono = prim.semicircle(r), lambda e: polar_monomial(*e, 0, r, 0, np.pi)
    elif shape == "sector_big":  # a cap larger than a half disc: the rectangle path
        body, mono = prim.sector(r, 5.0), lambda e: polar_monomial(*e, 0, r, -2.5, 2.5)
    elif shape == "sector_small":
        body, mono = prim.sector(r, 0.4), lambda e: polar_monomial(*e, 0, r, -0.2, 0.2)
    else:
        body, mono = prim.annulus(0.6, r), lambda e: polar_monomial(*e, 0.6, r, 0, 2 * np.pi)
    poly = bounded_poly(rng, 2, 6, r)
    moved = body.transformed(np.eye(2), FAR2)
    props = with_density_field(moved, poly_field(poly, FAR2, 6)).mass_properties()
    assert props.exact
    assert_matches(props, reference(poly, FAR2, mono, 2), r)


def test_bezier_lamina_uniform_and_linear():
    """A cubic-Bézier edge: the uniform field matches the exact Green's-theorem lamina;
    a linear field matches the lamina's own first and second moments (∫(1 + x) = A + ∫x)."""
    ring = Ring(np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]),
                controls=np.array([[[np.nan] * 2] * 2, [[np.nan] * 2] * 2,
                                   [[1.5, 2.0], [0.5, 1.6]], [[np.nan] * 2] * 2]))
    lam = Lamina(Region((ring,)))
    exact = lam.mass_properties()
    props = with_density_field(lam, F("1")).mass_properties()
    assert props.exact
    assert_matches(props, exact, 2.0, 1e-13)
    lin = with_density_field(lam, F("1 + x")).mass_properties()
    x_bar = exact.center_of_mass[0]
    assert lin.mass == pytest.approx(exact.mass * (1 + x_bar), rel=1e-13)


# ------------------------------------------------------------------ exactness, solids


@pytest.mark.parametrize("seed", range(3))
def test_polynomial_density_on_box_mesh_exact_far_away(seed):
    rng = np.random.default_rng(seed)
    dims = rng.uniform(0.5, 2.0, 3)
    body = prim.box(*dims).transformed(np.eye(3), FAR3)  # a MeshSolid with far coordinates
    assert isinstance(body, MeshSolid)
    poly = bounded_poly(rng, 3, 6, float(dims.max()))
    props = with_density_field(body, poly_field(poly, FAR3, 6)).mass_properties()

    def mono(e):
        return math.prod(d ** (k + 1) / (k + 1) for d, k in zip(dims, e))

    assert props.exact
    assert_matches(props, reference(poly, FAR3, mono, 3), float(np.linalg.norm(dims)))


def test_polynomial_density_on_nonconvex_mesh_exact():
    """A pyramid on an L-shaped base: the signed tetrahedra from the local origin reach
    outside the body; the field is a polynomial, so the sum is still exact."""
    base = np.array([[0, 0], [3, 0], [3, 1], [1, 1], [1, 3], [0, 3]], dtype=float)
    apex = np.array([0.5, 0.5, 2.0])
    body = prim.pyramid(base, 2.0, apex=apex[:2])
    rng = np.random.default_rng(11)
    poly = bounded_poly(rng, 3, 4, 3.0)
    props = with_density_field(body, poly_field(poly, np.zeros(3), 4)).mass_properties()
    # Reference: the pyramid as tetrahedra (apex, base fan from vertex 0... the L is not
    # convex, so fan from its reflex-free vertex 0 is fine: all triangles positive).
    fan = [(0, i, i + 1) for i in range(1, 5)]
    tets = [np.array([apex, [*base[a], 0], [*base[c], 0], [*base[b], 0]]) for a, b, c in fan]
    tables = [simplex_monomial_table(t, 6) for t in tets]
    want = reference(poly, np.zeros(3), lambda e: float(sum(t[e] for t in tables)), 3)
    assert props.exact
    assert_matches(props, want, 4.0)


@pytest.mark.parametrize("kind", ["sphere", "cylinder", "hemisphere"])
def test_polynomial_density_on_solids_of_revolution_exact(kind):
    rng = np.random.default_rng(len(kind))
    r, h = 0.8, 1.3
    if kind == "sphere":
        body, centre = prim.sphere(r), np.zeros(3)

        def mono(e):
            return ball_monomial(*e, r)
    elif kind == "cylinder":
        body, centre = prim.cylinder(r, h), np.zeros(3)

        def mono(e):
            return disc_monomial(e[0], e[1], r) * h ** (e[2] + 1) / (e[2] + 1)
    else:
        body, centre = prim.hemisphere(r), np.zeros(3)

        def mono(e):  # the upper half of the ball: even x, y powers; any z power
            if e[0] % 2 or e[1] % 2:
                return 0.0
            if e[2] % 2 == 0:
                return ball_monomial(*e, r) / 2
            from scipy.integrate import quad

            k = e[2]
            # ∫ z^k · (∫ over the disc of radius √(r² − z²) of x^a y^b) dz
            return quad(lambda z: z**k * disc_monomial(e[0], e[1], math.sqrt(r * r - z * z)),
                        0, r, epsabs=0, epsrel=2e-14)[0]
    poly = bounded_poly(rng, 3, 6, max(r, h))
    moved = body.translated(FAR3)
    props = with_density_field(moved, poly_field(poly, FAR3 + centre, 6)).mass_properties()
    assert props.exact
    assert_matches(props, reference(poly, FAR3 + centre, mono, 3), 2 * r)


def test_extrusion_exact_against_mesh_prism():
    """A prism as an Extrusion (profile × z) and as a mesh (tetrahedra): both exact."""
    verts = np.array([[0, 0], [2, 0], [2.5, 1], [1, 2], [-0.5, 1]], dtype=float)
    field = F("1 + x*y + z^3 + x^2*z")
    a = with_density_field(prim.prism(prim.polygon(verts), 1.5), field).mass_properties()
    n = len(verts)
    vv = np.vstack((np.pad(verts, ((0, 0), (0, 1))), np.pad(verts, ((0, 0), (0, 1)),
                                                             constant_values=1.5)))
    faces = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    tris = [[f[0], f[1], f[2]] for f in faces] + [[f[0], f[2], f[3]] for f in faces]
    tris += [[0, i + 1, i] for i in range(1, n - 1)] + [[n, n + i, n + i + 1] for i in range(1, n - 1)]
    mesh = MeshSolid(vv[np.array(tris)])
    b = with_density_field(mesh, field).mass_properties()
    assert a.exact and b.exact
    assert_matches(a, b, 3.0, 1e-12)


def test_uniform_field_equals_uniform_body_for_every_generator():
    field = F("2.5")
    bodies = [prim.disc(1.3), prim.annulus(0.5, 1), prim.sector(2, 4.0), prim.regular_polygon(7, 1),
              prim.box(1, 2, 3), prim.torus(2, 0.5), prim.cone(1, 2), prim.frustum(1, 0.5, 1),
              prim.prism(prim.semicircle(1), 2), prim.hemisphere(1.1),
              prim.tetrahedron([0, 0, 0], [1, 0, 0], [0, 1, 0], [0.2, 0.3, 1])]
    for body in bodies:
        want = body.mass_properties().scaled(2.5)
        got = with_density_field(body, field).mass_properties()
        assert got.exact
        assert got.measure == pytest.approx(want.measure, rel=1e-13)
        assert_matches(got, want, body.size, 1e-12)


# ------------------------------------------------------------------ non-polynomial fields


def test_exp_density_on_ball_converges_and_bounds_the_error():
    import warnings

    from scipy.integrate import quad

    warnings.simplefilter("ignore")  # quad's note that it reached rounding
    props = with_density_field(prim.sphere(1), F("exp(x)"), tolerance=1e-9).mass_properties()
    # ∫_ball e^x = ∫₋₁¹ e^x π (1 − x²) dx; ∫ x e^x likewise.
    mass = quad(lambda x: np.exp(x) * np.pi * (1 - x * x), -1, 1, epsabs=0, epsrel=2e-14)[0]
    mx = quad(lambda x: x * np.exp(x) * np.pi * (1 - x * x), -1, 1, epsabs=0, epsrel=2e-14)[0]
    assert not props.exact and 0 < props.relative_error <= 1e-9
    assert abs(props.mass - mass) <= props.relative_error * mass
    assert abs(props.center_of_mass[0] - mx / mass) <= props.relative_error * 2
    assert any("adaptively" in n for n in props.notes)


def test_step_density_on_lamina_bounds_the_error():
    """Half the unit square at density 3, half at 1, split along x = 0.6 + 1/(5π)."""
    edge = 0.6 + 1 / (5 * np.pi)
    props = with_density_field(prim.rectangle(1, 1), F(f"1 + 2*step(x - {edge!r})"),
                               tolerance=1e-4).mass_properties()
    mass = 1 + 2 * (1 - edge)
    xg = (0.5 + 2 * (1 - edge**2) / 2) / mass
    assert not props.exact
    assert abs(props.mass - mass) <= props.relative_error * mass
    assert abs(props.center_of_mass[0] - xg) <= props.relative_error * math.sqrt(2)
    assert props.relative_error <= 1e-4


def test_step_clipping_only_a_corner_is_not_missed():
    """A jump in a corner that no Gauss point of the first rules sees."""
    props = with_density_field(prim.rectangle(1, 1), F("1 + 50*step(x + y - 1.93)"),
                               tolerance=1e-3).mass_properties()
    mass = 1 + 50 * 0.07**2 / 2
    assert abs(props.mass - mass) <= props.relative_error * mass


# ------------------------------------------------------------------ motion, splitting


@given(st.floats(-np.pi, np.pi), st.floats(-50, 50), st.floats(-50, 50), st.floats(-50, 50),
       st.booleans())
def test_rigid_motion_of_body_and_field(angle, ox, oy, oz, mirror):
    """Placing a graded body moves its field with it: same as transforming the numbers."""
    m = rotation_matrix([1, 2, 2], angle)
    if mirror:
        m = m @ np.diag([1.0, 1.0, -1.0])
    offset = np.array([ox, oy, oz])
    body = prim.cone(0.7, 1.2)
    field = F("1 + x^2 + 0.5*y*z + z^3")
    graded = with_density_field(body, field)
    want = graded.mass_properties().transformed(m, offset)
    moved = graded.transformed(m, offset)
    assert_matches(moved.mass_properties(), want, 1.5, 1e-12)
    # …and grading a placed body with the field seen in the world is the same.
    world = field.composed(m.T, -m.T @ offset)
    again = with_density_field(body.transformed(m, offset), world).mass_properties()
    assert_matches(again, want, 1.5, 1e-11)


@given(st.floats(0.1, 0.9), st.sampled_from(["1 + x^3*y", "exp(x - y)"]))
def test_two_halves_sum_to_the_body(cut, text):
    field = F(text)
    whole = with_density_field(prim.rectangle(1, 1), field, tolerance=1e-11).mass_properties()
    left = with_density_field(prim.rectangle(cut, 1), field, tolerance=1e-11)
    right = with_density_field(prim.rectangle(1 - cut, 1).translated([cut, 0]), field,
                               tolerance=1e-11)
    parts = combine([left.mass_properties(), right.mass_properties()])
    tol = 1e-12 + 2 * (whole.relative_error + parts.relative_error)
    assert_matches(parts, whole, 1.5, tol)


def test_solid_halves_sum_to_the_body():
    field = F("2 + x*y*z + z^2")
    ball = with_density_field(prim.sphere(1), field).mass_properties()
    top = with_density_field(prim.hemisphere(1), field).mass_properties()
    bottom = with_density_field(prim.hemisphere(1).transformed(np.diag([1.0, 1, -1])), field)
    assert_matches(combine([top, bottom.mass_properties()]), ball, 2.0, 1e-12)


# ------------------------------------------------------------------ composites and assemblies


def test_composite_hole_subtracts_the_field():
    plate = prim.rectangle(4, 3)
    hole = prim.disc(0.5).translated([1, 1])
    body = Composite((plate, hole), (1.0, -1.0))
    field = F("1 + x + y^2")
    got = with_density_field(body, field).mass_properties()
    want = (with_density_field(plate, field).mass_properties()
            - with_density_field(hole, field).mass_properties())
    assert_matches(got, want, 5.0, 1e-13)
    # independent: area of the plate minus the disc
    assert got.measure == pytest.approx(12 - np.pi / 4, rel=1e-14)


def test_negative_density_inside_a_hole_is_allowed():
    plate = prim.rectangle(4, 4)
    hole = prim.disc(1).translated([2, 2])
    body = Composite((plate, hole), (1.0, -1.0))
    field = F("(x-2)^2 + (y-2)^2 - 0.5")  # negative only for r < 0.707, inside the hole
    props = with_density_field(body, field).mass_properties()
    assert props.mass > 0 and props.exact
    with pytest.raises(DensityError, match="negative"):
        with_density_field(plate, field).mass_properties()


def test_assembly_grades_every_part():
    asm = Assembly((prim.box(1, 1, 1), prim.sphere(0.5).translated([3, 0, 0])))
    graded = with_density_field(asm, F("1 + x"))
    assert isinstance(graded, Assembly)
    parts = graded.part_properties()
    assert parts[0].mass == pytest.approx(1.5, rel=1e-14)
    v = 4 / 3 * np.pi * 0.125
    assert parts[1].mass == pytest.approx(4 * v, rel=1e-13)  # 1 + x = 4 at the centre, odd part cancels


def test_graded_body_delegates_geometry():
    body = prim.cylinder(1, 2)
    graded = with_density_field(body, F("1 + z"))
    assert isinstance(graded, GradedSolid)
    np.testing.assert_array_equal(graded.hull_points(), body.hull_points())
    down = np.array([0.0, 0.0, -1.0])
    np.testing.assert_array_equal(graded.support_points(down, 1e-6), body.support_points(down, 1e-6))
    assert graded.kind == "solid" and graded.dim == 3
    assert graded.with_default_density(5.0) is graded
    lam = with_density_field(prim.disc(1), F("1"))
    assert isinstance(lam, GradedLamina) and lam.kind == "lamina"


def test_overlapping_graded_parts_refuse_a_faceted_boolean():
    a = with_density_field(prim.disc(1), F("1 + x"))
    b = with_density_field(prim.disc(1).translated([1, 0]), F("1 + x"))
    with pytest.raises(DensityError, match="combine the parts first"):
        union(a, b)


# ------------------------------------------------------------------ validation


def test_negative_density_names_a_point_inside():
    with pytest.raises(DensityError) as info:
        with_density_field(prim.box(1, 1, 1), F("x - 0.25")).mass_properties()
    message = str(info.value)
    assert "negative" in message and "kg/m³" in message
    x = float(message.split(" at (")[1].split(",")[0].replace("−", "-"))
    assert 0 <= x < 0.25


def test_not_finite_density_is_an_error():
    with pytest.raises(DensityError, match=r"not finite \(nan kg/m²\) at \(0, 0\)"):
        with_density_field(prim.rectangle(1, 1), F("sqrt(x - 0.5)")).mass_properties()
    with pytest.raises(DensityError, match="not finite"):  # infinite on the face x = 0
        with_density_field(prim.box(1, 1, 1), F("1/x")).mass_properties()
    with pytest.raises(DensityError, match=r"not finite \(inf kg/m³\) at \(0, 0, 1\)"):
        with_density_field(prim.sphere(1), F("1/(1 - z)")).mass_properties()  # the pole


def test_zero_density_everywhere_is_an_error():
    with pytest.raises(DensityError, match="zero everywhere"):
        with_density_field(prim.rectangle(1, 1), F("0*x")).mass_properties()
    with pytest.raises(DensityError, match="zero everywhere"):
        with_density_field(prim.rectangle(1, 1), F("step(x - 2)")).mass_properties()


def test_negative_outside_a_nonconvex_mesh_is_not_an_error():
    """The L-shaped pyramid's signed tetrahedra sample outside the body."""
    base = np.array([[0, 0], [3, 0], [3, 1], [1, 1], [1, 3], [0, 3]], dtype=float)
    body = prim.pyramid(base, 1.0, apex=[0.5, 0.5])
    # Negative only beyond the line x + y = 3.9, outside the L (whose corners reach x + y = 4
    # only at (3, 1) and (1, 3), where the density is 3.9 - 4 < 0)...
    field = F("4.5 - x - y")
    props = with_density_field(body, field).mass_properties()
    assert props.mass > 0


def test_particles_take_no_field():
    from plumbob.bodies.particles import ParticleSystem

    with pytest.raises(DensityError, match="particles"):
        with_density_field(ParticleSystem(np.ones(2), np.eye(2)), F("1"))


def test_open_mesh_is_refused():
    tris = prim.box(1, 1, 1).triangles[:-1]
    with pytest.raises(GeometryError, match="is open"):
        with_density_field(MeshSolid(tris), F("1 + x")).mass_properties()


def test_tolerance_must_be_sensible():
    with pytest.raises(DensityError, match="tolerance"):
        with_density_field(prim.disc(1), F("exp(x)"), tolerance=0)
