"""The linear-programming relaxation of hollowing over the interior's cells.

Emptying a fraction ``x_i ∈ [0, 1]`` of cell ``i`` (mass ``m_i``, centre ``c_i``) leaves
a body of mass ``W = M − Σ x_i m_i`` whose every target row reads
``W·slack_k(c') = M·slack_k(c) − Σ x_i m_i slack_k(c_i)``: linear in ``x``
(*Make It Stand*, Prévost et al. 2013).

* **The best any carve reaches** — the largest least slack ``z = min_k slack_k(c')`` —
  is a linear-fractional program; with ``y = x / W`` and ``t = 1 / W`` (Charnes and
  Cooper) it is the linear program ``max z`` subject to ``M t s_k(c) − Σ y_i m_i s_k(c_i)
  ≥ z``, ``M t − Σ m_i y_i = 1``, ``0 ≤ y_i ≤ t``.
* **The least material** meeting the target: ``min Σ m_i x_i`` subject to
  ``Σ x_i m_i s_k(c_i) ≤ M s_k(c)``.

Both are solved by HiGHS (``scipy.optimize.linprog``). By their optimality conditions the
optimum empties exactly the cells where a combination of the rows, weighted by the
duals ``λ_k``, is below a threshold: a half-space, whose normal ``−Σ λ_k ∇slack_k`` is
returned to start the exact search (:mod:`plumbob.balance.hollow`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..errors import StabilityError

__all__ = ["Relaxed", "best_relaxed", "least_relaxed", "row_gradients"]


class Relaxed(NamedTuple):
    """A relaxation's answer.

    value: the best least slack (m), or the least mass emptied (kg); nan when infeasible.
    normal: (3,) unit vector, the side of the cut that is emptied (zero if none).
    emptied: (n,) the fraction of each cell emptied.
    """

    value: float
    normal: np.ndarray
    emptied: np.ndarray


def row_gradients(target, dim: int = 3) -> np.ndarray:
    """The rows' gradients (k, dim): a target's slack is linear in the point."""
    points = np.vstack((np.zeros(dim), np.eye(dim)))
    values = np.asarray(target.slack(points), dtype=float)  # (k, dim + 1)
    return (values[:, 1:] - values[:, :1]).reshape(-1, dim)


def _normal(target, duals: np.ndarray) -> np.ndarray:
    grad = -(np.abs(duals)[:, None] * row_gradients(target)).sum(axis=0)
    length = float(np.linalg.norm(grad))
    return grad / length if length > 0 else grad


def _solve(cost, a_ub, b_ub, a_eq, b_eq, bounds):
    from scipy.optimize import linprog

    result = linprog(cost, A_ub=a_ub, b_ub=b_ub, A_eq=a_eq, b_eq=b_eq, bounds=bounds,
                     method="highs")
    if result.status not in (0, 2):
        raise StabilityError(f"the hollowing relaxation could not be solved ({result.message})")
    return result


def best_relaxed(masses: np.ndarray, centres: np.ndarray, mass: float, centre: np.ndarray,
                 target) -> Relaxed:
    """The best least slack (m) any fractional emptying of the cells reaches.

    >>> from plumbob.balance.targets import Target
    >>> t = Target(np.array([[-1.0, 0, 0]]), np.array([-1.2]))  # the centre at x ≤ 1.2
    >>> # a body of 2 kg centred at x = 1.5; cells of 1 kg at x = 1 and x = 2 (its two halves)
    >>> r = best_relaxed(np.ones(2), np.array([[1.0, 0, 0], [2.0, 0, 0]]), 2.0,
    ...                  np.array([1.5, 0, 0]), t)
    >>> round(r.value, 9), (r.normal + 0.0).tolist(), r.emptied.round(9).tolist()
    (0.2, [1.0, 0.0, 0.0], [0.0, 1.0])
    """
    from scipy.sparse import csr_matrix, diags, hstack, vstack

    n = len(masses)
    rows = masses[None, :] * np.asarray(target.slack(centres), dtype=float) / mass  # (k, n)
    s0 = np.asarray(target.slack(centre), dtype=float)  # (k,)
    k = len(s0)
    # in units where the variables are near 1: t' = M t, y' = M y, z' = z / L
    unit = max(float(np.abs(rows).max(initial=0.0)) * mass / max(float(masses.max()), 1e-300),
               float(np.abs(s0).max()), 1e-300)
    # variables (y', t', z'); rows: z' − t' s0 / L + Σ y' m s / (M L) ≤ 0 ; y' − t' ≤ 0 ;
    # t' − Σ y' m / M = 1
    a_rows = np.hstack((rows / unit, -s0[:, None] / unit, np.ones((k, 1))))
    a_box = hstack((diags(np.ones(n)), csr_matrix(-np.ones((n, 1))), csr_matrix((n, 1))))
    a_ub = vstack((csr_matrix(a_rows), a_box)).tocsr()
    a_eq = np.concatenate((-masses / mass, [1.0], [0.0]))[None, :]
    cost = np.zeros(n + 2)
    cost[-1] = -1.0
    bounds = [(0, None)] * (n + 1) + [(None, None)]
    result = _solve(cost, a_ub, np.zeros(k + n), a_eq, [1.0], bounds)
    y, t, z = result.x[:n], result.x[n], result.x[n + 1] * unit
    duals = result.ineqlin.marginals[:k]
    return Relaxed(float(z), _normal(target, duals), np.clip(y / t, 0.0, 1.0))


def least_relaxed(masses: np.ndarray, centres: np.ndarray, mass: float, centre: np.ndarray,
                  target, safety: float = 0.0) -> Relaxed:
    """The least mass (kg) emptied, in fractions of cells, that leaves every row's slack
    at least ``safety`` m; ``value`` nan when none does."""
    rows = masses[None, :] * (np.asarray(target.slack(centres), dtype=float) - safety)
    s0 = mass * (np.asarray(target.slack(centre), dtype=float) - safety)
    scale = max(float(np.abs(rows).max(initial=0.0)), float(np.abs(s0).max()), 1e-300)
    result = _solve(masses / mass, rows / scale, s0 / scale, None, None, [(0, 1)] * len(masses))
    if result.status != 0 or result.x is None:
        return Relaxed(float("nan"), np.zeros(3), np.zeros(len(masses)))
    duals = result.ineqlin.marginals
    return Relaxed(float(masses @ result.x), _normal(target, duals), result.x)
