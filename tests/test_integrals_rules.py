"""Quadrature rules (plumbob.integrals.rules) against closed forms.

``∫₀¹ x^k = 1/(k+1)``, ``∫₀¹ (1−x)^α x^k = k! α! / (k+α+1)!`` and, on the unit
simplices, ``∫ u^a v^b (t^c) = a! b! (c!) / (a+b(+c)+d)!``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from polynomial_reference import monomials

from plumbob.integrals import rules
from plumbob.integrals.rules import gauss_jacobi, gauss_legendre, tetrahedron_rule, triangle_rule


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
    assert rules.arc_points_for_degree(2, 0.1) <= rules.arc_points_for_degree(8, 0.1)
    assert rules.arc_points_for_degree(8, 0.1) <= rules.arc_points_for_degree(8, np.pi)
    # The bound it enforces: Gauss's remainder for e^{iκs} below 1e-20.
    n = rules.arc_points_for_degree(6, np.pi)
    assert rules._gauss_remainder_log10(n, 8 * np.pi) <= -20
