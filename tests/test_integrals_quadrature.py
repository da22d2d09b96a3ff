"""Quadrature rules and the density-field driver (plumbob.integrals.quadrature).

References are independent: closed forms ``a! b! c! / (a+b+c+d)!`` on the unit
simplices, exact rational arithmetic (fractions) for polynomials over general
simplices, and closed forms for smooth and discontinuous fields.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from plumbob.integrals import quadrature as q
from plumbob.integrals.quadrature import (
    ArcCells,
    BezierCells,
    ProductCells,
    SimplexCells,
    gauss_jacobi,
    gauss_legendre,
    integrate_field,
    tetrahedron_rule,
    triangle_rule,
)

# ------------------------------------------------------------------ exact references


def monomials(dim: int, degree: int) -> list[tuple[int, ...]]:
    return [e for e in itertools.product(range(degree + 1), repeat=dim) if sum(e) <= degree]


def _mul(p: dict, r: dict) -> dict:
    out: dict = {}
    for ea, ca in p.items():
        for eb, cb in r.items():
            e = tuple(x + y for x, y in zip(ea, eb))
            out[e] = out.get(e, 0) + ca * cb
    return out


def simplex_monomial_table(vertices, degree: int) -> dict:
    """Exact ∫ x^β over the simplex (signed) for every |β| ≤ degree, as fractions.

    vertices: (d+1, d) floats, converted exactly. With x = v0 + Σ λ_i (v_i − v0)
    every monomial becomes a polynomial in λ, and ∫_ref λ^γ = γ! / (|γ| + d)!.
    """
    v = [[Fraction(float(c)) for c in row] for row in vertices]
    d = len(v[0])
    edges = [[v[i + 1][j] - v[0][j] for j in range(d)] for i in range(d)]
    if d == 2:
        det = edges[0][0] * edges[1][1] - edges[0][1] * edges[1][0]
    else:
        a, b, c = edges
        det = (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
               + a[2] * (b[0] * c[1] - b[1] * c[0]))
    zero = (0,) * d
    powers = []  # powers[j][k]: (x_j as a polynomial in λ)^k
    for j in range(d):
        lin = {zero: v[0][j]}
        for i in range(d):
            e = tuple(1 if k == i else 0 for k in range(d))
            lin[e] = lin.get(e, 0) + edges[i][j]
        seq = [{zero: Fraction(1)}]
        for _ in range(degree):
            seq.append(_mul(seq[-1], lin))
        powers.append(seq)
    table = {}
    for beta in monomials(d, degree):
        term = powers[0][beta[0]]
        for j in range(1, d):
            term = _mul(term, powers[j][beta[j]])
        total = Fraction(0)
        for gamma, c in term.items():
            total += c * Fraction(math.prod(math.factorial(g) for g in gamma),
                                  math.factorial(sum(gamma) + d))
        table[beta] = det * total
    return table


def exact_simplex_integral(poly: dict, vertices) -> Fraction:
    """∫ poly over the simplex (signed by orientation), in exact rational arithmetic."""
    degree = max(sum(e) for e in poly)
    table = simplex_monomial_table(vertices, degree)
    return sum((Fraction(c) * table[e] for e, c in poly.items()), Fraction(0))


def evaluate_poly(poly: dict, points: np.ndarray) -> np.ndarray:
    out = np.zeros(len(points))
    for exps, coef in poly.items():
        term = np.full(len(points), float(coef))
        for j, power in enumerate(exps):
            if power:
                term = term * points[:, j] ** power
        out += term
    return out


def random_poly(rng: np.random.Generator, dim: int, degree: int) -> dict:
    """A polynomial with every monomial up to ``degree`` and coefficients in [0.5, 1.5]."""
    return {e: Fraction(float(rng.uniform(0.5, 1.5))) for e in monomials(dim, degree)}


def moment_polys(poly: dict, dim: int) -> list[dict]:
    """poly · m for m in 1, x_i, x_i x_j (the driver's sums, in its order)."""
    out = [poly]
    units = [tuple(1 if k == i else 0 for k in range(dim)) for i in range(dim)]
    out += [_mul(poly, {u: 1}) for u in units]
    out += [_mul(poly, {tuple(a + b for a, b in zip(ui, uj)): 1}) for ui in units for uj in units]
    return out


# ------------------------------------------------------------------ 1D and simplex rules


@pytest.mark.parametrize("n", [1, 2, 5, 12])
def test_gauss_legendre_integrates_degree_2n_minus_1(n):
    x, w = gauss_legendre(n)
    for k in range(2 * n):
        assert w @ x**k == pytest.approx(1 / (k + 1), rel=1e-14)
    # And no more: the squared node polynomial (degree 2n) is positive but vanishes at the nodes.
    fine, wf = gauss_legendre(n + 1)
    node_poly = np.prod((fine[:, None] - x[None, :]) ** 2, axis=1)
    assert wf @ node_poly > 0 and np.prod((x[:, None] - x[None, :]) ** 2 + np.eye(n), axis=1) @ w > 0


@pytest.mark.parametrize("alpha", [1, 2])
@pytest.mark.parametrize("n", [1, 3, 7])
def test_gauss_jacobi_integrates_with_its_weight(n, alpha):
    x, w = gauss_jacobi(n, alpha)
    for k in range(2 * n):
        exact = math.factorial(k) * math.factorial(alpha) / math.factorial(k + alpha + 1)
        assert w @ x**k == pytest.approx(exact, rel=1e-13)


@pytest.mark.parametrize("degree", range(0, 13))
def test_triangle_rule_exact_for_every_monomial(degree):
    bary, w = triangle_rule(degree)
    assert bary.shape == ((degree // 2 + 1) ** 2, 3)
    assert np.all(bary >= 0) and np.all(w > 0)  # interior points, positive weights
    u, v = bary[:, 1], bary[:, 2]
    for a, b in monomials(2, degree):
        exact = math.factorial(a) * math.factorial(b) / math.factorial(a + b + 2)
        assert w @ (u**a * v**b) == pytest.approx(exact, rel=1e-13, abs=0)


@pytest.mark.parametrize("degree", range(0, 11))
def test_tetrahedron_rule_exact_for_every_monomial(degree):
    bary, w = tetrahedron_rule(degree)
    assert np.all(bary >= 0) and np.all(w > 0)
    u, v, t = bary[:, 1], bary[:, 2], bary[:, 3]
    for a, b, c in monomials(3, degree):
        exact = (math.factorial(a) * math.factorial(b) * math.factorial(c)
                 / math.factorial(a + b + c + 3))
        assert w @ (u**a * v**b * t**c) == pytest.approx(exact, rel=1e-13, abs=0)


def test_rules_are_read_only_and_cached():
    bary, w = triangle_rule(4)
    assert triangle_rule(4)[0] is bary
    with pytest.raises(ValueError):
        w[0] = 1.0


def test_arc_points_grow_with_degree_and_angle():
    assert q.arc_points_for_degree(2, 0.1) <= q.arc_points_for_degree(8, 0.1)
    assert q.arc_points_for_degree(8, 0.1) <= q.arc_points_for_degree(8, np.pi)
    # The bound it enforces: Gauss's remainder for e^{iκs} below 1e-20.
    n = q.arc_points_for_degree(6, np.pi)
    assert q._gauss_remainder_log10(n, 8 * np.pi) <= -20


# ------------------------------------------------------------------ general simplices, exact


def _cells_integral(cells, poly, origin, degree):
    field = lambda p: evaluate_poly(poly, p)  # noqa: E731
    return integrate_field(cells, field, origin, degree)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("seed", range(3))
def test_polynomials_of_degree_6_exact_on_simplices_far_from_origin(dim, seed):
    """Degree ≤ 6 densities on random simplices 10⁴ m away, against exact rationals."""
    rng = np.random.default_rng(seed)
    far = rng.uniform(-1e4, 1e4, dim)
    count = 3 if dim == 2 else 1
    verts = far + rng.uniform(-1, 1, (count, dim + 1, dim))
    flip = np.linalg.det(verts[:, 1:] - verts[:, :1]) < 0  # positive: no cancellation
    verts[flip, 1:3] = verts[flip, 2:0:-1]
    # The density is a polynomial of the local coordinates w = x − far, so it stays
    # well conditioned; the driver sees world points.
    poly = random_poly(rng, dim, 6)
    origin = verts.reshape(-1, dim).mean(axis=0)
    result = integrate_field([SimplexCells(verts - origin)],
                             lambda p: evaluate_poly(poly, p - far), origin, 6)
    assert result.exact and result.error == 0
    local = verts - far
    shift = origin - far
    # moments about `origin`: ∫ρ (w − shift)…; build them from exact moments in w.
    tables = [simplex_monomial_table(v, 8) for v in local]
    exact = [float(sum(sum(Fraction(c) * t[e] for e, c in m.items()) for t in tables))
             for m in moment_polys(poly, dim)]
    mass, first_w = exact[0], np.array(exact[1:1 + dim])
    second_w = np.array(exact[1 + dim:]).reshape(dim, dim)
    first = first_w - mass * shift
    second = (second_w - np.outer(first_w, shift) - np.outer(shift, first_w)
              + mass * np.outer(shift, shift))
    assert result.mass == pytest.approx(mass, rel=1e-12)
    assert np.abs(result.first - first).max() <= 1e-12 * abs(mass) * 2  # |r − origin| ≤ 2
    assert np.abs(result.second - second).max() <= 1e-12 * np.abs(second_w).max()
    measure = sum(float(exact_simplex_integral({(0,) * dim: 1}, v)) for v in local)
    assert result.measure == pytest.approx(measure, rel=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_apex_at_origin_form_equals_full_simplices(dim):
    rng = np.random.default_rng(7)
    faces = rng.normal(size=(5, dim, dim))
    full = np.concatenate((np.zeros((5, 1, dim)), faces), axis=1)
    poly = random_poly(rng, dim, 3)
    a = _cells_integral([SimplexCells(faces)], poly, np.zeros(dim), 3)
    b = _cells_integral([SimplexCells(full)], poly, np.zeros(dim), 3)
    assert a.mass == pytest.approx(b.mass, rel=1e-13)
    np.testing.assert_allclose(a.second, b.second, rtol=1e-12, atol=1e-14)


@given(st.integers(2, 3), st.integers(0, 2**31), st.booleans())
def test_splitting_a_simplex_keeps_every_integral(dim, seed, negative):
    """Children tile the parent with its orientation (signed sums agree)."""
    rng = np.random.default_rng(seed)
    verts = rng.normal(size=(1, dim + 1, dim))
    if negative:
        verts[:, [1, 2]] = verts[:, [2, 1]]
    cells = SimplexCells(verts)
    kids = cells.split()
    assert len(kids) == cells.children
    poly = random_poly(rng, dim, 4)
    whole = _cells_integral([cells], poly, np.zeros(dim), 4)
    parts = _cells_integral([kids], poly, np.zeros(dim), 4)
    assert parts.measure == pytest.approx(whole.measure, rel=1e-12)
    assert parts.mass == pytest.approx(whole.mass, rel=1e-11)
    np.testing.assert_allclose(parts.first, whole.first, rtol=1e-10, atol=1e-12)


# ------------------------------------------------------------------ curved cells


def _arc(alpha: float, radius: float = 1.0, sign: float = 1.0) -> ArcCells:
    return ArcCells(box=np.array([[[0.0, 1.0], [0.0, 1.0]]]), centre=np.zeros((1, 2)),
                    radius=np.array([radius]), frame=np.eye(2)[None],
                    half_angle=np.array([alpha]), sign=np.array([sign]))


def _segment_reference(alpha: float, a: int, b: int, r: float = 1.0) -> float:
    """∫ x^a y^b over the circular segment x ≥ r cos α of the disc of radius r.

    With x = r cos t the y-integral is 2 (r sin t)^{b+1}/(b+1), leaving the smooth
    1D integral r^{a+b+2} ∫₀^α 2 cos^a t sin^{b+2} t / (b+1) dt (scipy's quad).
    """
    from scipy.integrate import quad

    if b % 2:
        return 0.0
    import warnings

    f = lambda t: np.cos(t) ** a * np.sin(t) ** (b + 2) * 2 / (b + 1)  # noqa: E731
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # quad reports reaching rounding, which is the point
        return r ** (a + b + 2) * quad(f, 0, alpha, epsabs=0, epsrel=2e-14, limit=200)[0]


@pytest.mark.parametrize("alpha", [0.3, np.pi / 2, 2.5])
def test_arc_cells_exact_for_polynomials(alpha):
    """A circular segment (small, half disc, and larger than half — with its rectangle)."""
    cells: list = [_arc(alpha)]
    if alpha > np.pi / 2:
        x0, h = np.cos(alpha), np.sin(alpha)
        rect = np.array([[[x0, -h], [0, -h], [0, h]], [[x0, -h], [0, h], [x0, h]]])
        cells.append(SimplexCells(rect))
    for a, b in [(0, 0), (1, 0), (0, 2), (3, 2), (6, 0), (2, 4)]:
        poly = {(a, b): 1}
        got = _cells_integral(cells, poly, np.zeros(2), a + b - 2 if a + b >= 2 else 0)
        # got.mass is ∫ x^a y^b (rule of degree a + b, exact)
        assert got.mass == pytest.approx(_segment_reference(alpha, a, b), rel=1e-12, abs=1e-15)


def test_arc_points_lie_inside_the_segment():
    for alpha in (0.4, np.pi / 2, 2.9):
        pts, w = _arc(alpha).rule(8)
        r = np.hypot(pts[..., 0], pts[..., 1])
        assert np.all(r <= 1 + 1e-12) and np.all(pts[..., 0] >= np.cos(alpha) - 1e-12)
        assert np.all(w > 0)


def test_split_arc_cells_sum_to_the_whole():
    whole = _cells_integral([_arc(1.2, 2.0, -1.0)], {(2, 1): 1, (0, 0): 3}, np.zeros(2), 3)
    kids = _arc(1.2, 2.0, -1.0).split().split()
    parts = _cells_integral([kids], {(2, 1): 1, (0, 0): 3}, np.zeros(2), 3)
    assert whole.mass < 0  # a negative bulge removes its cap
    assert parts.mass == pytest.approx(whole.mass, rel=1e-13)


def test_bezier_cells_exact_against_greens_line_integral():
    """∬ x^a y^b = ∮ x^{a+1} y^b/(a+1) dy along the loop (Bézier out, chord back)."""
    ctrl = np.array([[[0.0, 0.0], [0.3, 1.2], [1.4, 0.9], [1.0, 0.0]]])
    frame_along = (ctrl[0, 3] - ctrl[0, 0]) / np.linalg.norm(ctrl[0, 3] - ctrl[0, 0])
    frame = np.stack((np.array([frame_along[1], -frame_along[0]]), frame_along), axis=1)[None]
    cells = BezierCells(box=np.array([[[0.0, 1.0], [0.0, 1.0]]]), controls=ctrl, frame=frame)
    tau, wt = gauss_legendre(30)
    p0, c1, c2, p1 = ctrl[0]
    t = tau[:, None]
    curve = (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * c1 + 3 * (1 - t) * t**2 * c2 + t**3 * p1
    dcurve = 3 * ((1 - t) ** 2 * (c1 - p0) + 2 * (1 - t) * t * (c2 - c1) + t**2 * (p1 - c2))
    line = (1 - t) * p1 + t * p0
    dline = np.broadcast_to(p0 - p1, line.shape)
    for a, b in [(0, 0), (1, 0), (0, 1), (2, 3), (4, 2)]:
        ref = sum(float(np.sum(wt * pts[:, 0] ** (a + 1) * pts[:, 1] ** b * d[:, 1])) / (a + 1)
                  for pts, d in ((curve, dcurve), (line, dline)))
        got = _cells_integral([cells], {(a, b): 1}, np.zeros(2), max(a + b - 2, 0))
        assert got.mass == pytest.approx(ref, rel=1e-12)


def test_product_cells_turn_is_exact_for_trigonometric_integrands():
    """A unit square in (r, z) turned about z: a thick tube; ∫ x² dV = π ∫ r³ dr dz."""
    square = SimplexCells(np.array([[[1, 0], [2, 0], [2, 1]], [[1, 0], [2, 1], [1, 1]]], float))
    tube = ProductCells(square, np.tile([0.0, 2 * np.pi], (2, 1)), "phi", periodic=True)
    got = _cells_integral([tube], {(2, 0, 0): 1, (0, 0, 0): 1}, np.zeros(3), 2)
    exact = np.pi * (2**4 - 1) / 4 + np.pi * (4 - 1)  # ∫x² + volume
    assert got.mass == pytest.approx(exact, rel=1e-13)
    # Split, the angle takes Gauss–Legendre on half turns: converging, not exact at low degree.
    halves = _cells_integral([tube.split()], {(2, 0, 0): 1, (0, 0, 0): 1}, np.zeros(3), 24)
    assert halves.mass == pytest.approx(exact, rel=1e-13)
    assert _cells_integral([tube.split()], {(2, 0, 0): 1}, np.zeros(3), 2).mass != pytest.approx(
        np.pi * 15 / 4, rel=1e-6)


# ------------------------------------------------------------------ adaptive integration


TRIANGLE = SimplexCells(np.array([[[0, 0], [1, 0], [0, 1]]], dtype=float))


def test_smooth_field_converges_and_its_estimate_bounds_the_error():
    exact = np.e - 2  # ∫_T e^x = ∫₀¹ e^x (1 − x) dx
    for tol in (1e-4, 1e-8, 1e-12):
        r = integrate_field([TRIANGLE], lambda p: np.exp(p[:, 0]), np.zeros(2), None, tolerance=tol)
        assert not r.exact and r.converged
        assert abs(r.mass - exact) <= r.error <= tol * abs(r.mass)


@pytest.mark.parametrize("edge", [0.3, 0.5 + 1 / (3 * np.pi), 0.77])
def test_step_field_estimate_bounds_the_error(edge):
    """A jump across the unit square: the error concentrates on cut cells and is estimated."""
    square = SimplexCells(np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], float))
    field = lambda p: np.where(p[:, 0] >= edge, 3.0, 1.0)  # noqa: E731
    r = integrate_field([square], field, np.zeros(2), None, tolerance=1e-4)
    mass = 1 * edge + 3 * (1 - edge)
    xm = (edge**2 / 2 + 3 * (1 - edge**2) / 2) / mass
    assert r.converged
    assert abs(r.mass - mass) <= r.error <= 1e-4 * r.mass
    assert abs(r.first[0] / r.mass - xm) <= r.error / r.mass


def test_budget_stops_refinement_and_says_so():
    square = SimplexCells(np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], float))
    field = lambda p: np.where(p[:, 0] + 0.3 * p[:, 1] >= 0.61, 2.0, 1.0)  # noqa: E731
    r = integrate_field([square], field, np.zeros(2), None, tolerance=1e-12, max_evaluations=20_000)
    assert not r.converged
    assert r.evaluations <= 20_000
    exact = 1.0 + (1 - (0.61 - 0.15))  # mass: 1 + area where the step is on
    assert abs(r.mass - exact) <= r.error


def test_invalid_samples_are_kept_worst_first():
    r = integrate_field([TRIANGLE], lambda p: p[:, 0] - 0.5, np.zeros(2), 1)
    assert len(r.bad_values) > 0 and np.all(r.bad_values < 0)
    assert r.bad_values[0] == r.bad_values.min()
    np.testing.assert_allclose(r.bad_points[:, 0] - 0.5, r.bad_values)
    r = integrate_field([TRIANGLE], lambda p: np.where(p[:, 1] > 0.4, np.nan, 1.0), np.zeros(2), 0)
    assert np.isnan(r.bad_values[0])


def test_chunked_sweep_gives_the_same_sums(monkeypatch):
    rng = np.random.default_rng(3)
    tets = rng.normal(size=(500, 3, 3))
    poly = random_poly(rng, 3, 2)
    whole = _cells_integral([SimplexCells(tets)], poly, np.zeros(3), 2)
    monkeypatch.setattr(q, "CHUNK_POINTS", 64)
    chunked = _cells_integral([SimplexCells(tets)], poly, np.zeros(3), 2)
    assert chunked.mass == pytest.approx(whole.mass, rel=1e-12)
    np.testing.assert_allclose(chunked.second, whole.second, rtol=1e-11)


def test_a_field_returning_the_wrong_shape_is_refused():
    with pytest.raises(ValueError, match="one value per point"):
        integrate_field([TRIANGLE], lambda p: np.ones(3), np.zeros(2), 0)
