"""Integration cells (plumbob.integrals.cells): exact on polynomials, splitting keeps sums.

References are independent: exact rational arithmetic (fractions) for
polynomials over general simplices, scipy's quad for circular segments, and
Green's line integral for Bézier caps.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from polynomial_reference import (
    cells_integral,
    evaluate_poly,
    exact_simplex_integral,
    moment_polys,
    random_poly,
    simplex_monomial_table,
)

from plumbob.integrals.adaptive import integrate_field
from plumbob.integrals.cells import ArcCells, BezierCells, ProductCells, SimplexCells
from plumbob.integrals.rules import gauss_legendre

# ------------------------------------------------------------------ general simplices, exact


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
    a = cells_integral([SimplexCells(faces)], poly, np.zeros(dim), 3)
    b = cells_integral([SimplexCells(full)], poly, np.zeros(dim), 3)
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
    whole = cells_integral([cells], poly, np.zeros(dim), 4)
    parts = cells_integral([kids], poly, np.zeros(dim), 4)
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
        got = cells_integral(cells, poly, np.zeros(2), a + b - 2 if a + b >= 2 else 0)
        # got.mass is ∫ x^a y^b (rule of degree a + b, exact)
        assert got.mass == pytest.approx(_segment_reference(alpha, a, b), rel=1e-12, abs=1e-15)


def test_arc_points_lie_inside_the_segment():
    for alpha in (0.4, np.pi / 2, 2.9):
        pts, w = _arc(alpha).rule(8)
        r = np.hypot(pts[..., 0], pts[..., 1])
        assert np.all(r <= 1 + 1e-12) and np.all(pts[..., 0] >= np.cos(alpha) - 1e-12)
        assert np.all(w > 0)


def test_split_arc_cells_sum_to_the_whole():
    whole = cells_integral([_arc(1.2, 2.0, -1.0)], {(2, 1): 1, (0, 0): 3}, np.zeros(2), 3)
    kids = _arc(1.2, 2.0, -1.0).split().split()
    parts = cells_integral([kids], {(2, 1): 1, (0, 0): 3}, np.zeros(2), 3)
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
        got = cells_integral([cells], {(a, b): 1}, np.zeros(2), max(a + b - 2, 0))
        assert got.mass == pytest.approx(ref, rel=1e-12)


def test_product_cells_turn_is_exact_for_trigonometric_integrands():
    """A unit square in (r, z) turned about z: a thick tube; ∫ x² dV = π ∫ r³ dr dz."""
    square = SimplexCells(np.array([[[1, 0], [2, 0], [2, 1]], [[1, 0], [2, 1], [1, 1]]], float))
    tube = ProductCells(square, np.tile([0.0, 2 * np.pi], (2, 1)), "phi", periodic=True)
    got = cells_integral([tube], {(2, 0, 0): 1, (0, 0, 0): 1}, np.zeros(3), 2)
    exact = np.pi * (2**4 - 1) / 4 + np.pi * (4 - 1)  # ∫x² + volume
    assert got.mass == pytest.approx(exact, rel=1e-13)
    # Split, the angle takes Gauss–Legendre on half turns: converging, not exact at low degree.
    halves = cells_integral([tube.split()], {(2, 0, 0): 1, (0, 0, 0): 1}, np.zeros(3), 24)
    assert halves.mass == pytest.approx(exact, rel=1e-13)
    assert cells_integral([tube.split()], {(2, 0, 0): 1}, np.zeros(3), 2).mass != pytest.approx(
        np.pi * 15 / 4, rel=1e-6)
