"""The density-field driver (plumbob.integrals.adaptive): adaptive error estimates, budgets,
invalid samples, chunking; references are closed forms for smooth and discontinuous fields.
"""

from __future__ import annotations

import numpy as np
import pytest
from polynomial_reference import cells_integral, random_poly

from plumbob.integrals import adaptive
from plumbob.integrals.adaptive import integrate_field
from plumbob.integrals.cells import SimplexCells

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
    whole = cells_integral([SimplexCells(tets)], poly, np.zeros(3), 2)
    monkeypatch.setattr(adaptive, "CHUNK_POINTS", 64)
    chunked = cells_integral([SimplexCells(tets)], poly, np.zeros(3), 2)
    assert chunked.mass == pytest.approx(whole.mass, rel=1e-12)
    np.testing.assert_allclose(chunked.second, whole.second, rtol=1e-11)


def test_a_field_returning_the_wrong_shape_is_refused():
    with pytest.raises(ValueError, match="one value per point"):
        integrate_field([TRIANGLE], lambda p: np.ones(3), np.zeros(2), 0)
