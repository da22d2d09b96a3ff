"""Exact references for the quadrature tests: polynomials as {exponents: coefficient} dicts.

Independent of the code under test: closed forms ``a! b! c! / (a+b+c+d)!`` on
the unit simplices, and exact rational arithmetic (fractions) for polynomials
over general simplices. Shared by the rule, cell, driver and graded-body tests.
"""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import numpy as np

from plumbob.integrals.adaptive import integrate_field


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


def cells_integral(cells, poly, origin, degree):
    """The driver's exact pass over ``cells`` for the density ``poly``."""
    field = lambda p: evaluate_poly(poly, p)  # noqa: E731
    return integrate_field(cells, field, origin, degree)

