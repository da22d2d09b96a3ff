"""Moments of a density field over integration cells: one exact pass, or adaptive refinement.

:func:`integrate_field` sums, over signed cells (:mod:`plumbob.integrals.cells`),

* ``∫ ρ dV`` (mass), ``∫ ρ r dV`` and ``∫ ρ r rᵀ dV`` about a local origin,
* ``∫ 1 dV`` (the measure: area or volume),

in one pass when ρ is a polynomial of known degree ``d`` (rule degree ``d + 2``),
and adaptively otherwise. The result is a :class:`FieldIntegral`, which the
closed-mesh kernel (:func:`plumbob.integrals.mesh.mesh_field_moments`) returns too.

Adaptive integration (ρ not a polynomial): each cell is integrated with two
rules of ``n`` and ``n + 1`` points per direction; the difference is the cell's
error estimate for the lower rule, and the higher one is kept. While raising
``n`` shrinks the total estimate at least fourfold, ``n`` is raised (smooth
fields converge geometrically); after that, the cells whose estimate exceeds
their share of the tolerance (proportional to their size) are split in two
along every direction, until the total estimate is below the tolerance or the
evaluation budget is spent. The reported error is the sum of the cells' estimates.

A jump that only clips a cell's corner can fall between every Gauss point of
both rules, which then agree. So the field is also sampled at every cell's
corners: a corner value outside the range of the cell's quadrature samples by
more than that range marks the cell, and it is charged ``3 |size| × excess``
(a bound on what the corner can hide). Smooth fields are not marked; steps are
charged honestly, which makes their estimates pessimistic (in the tests, 10²–10³
times the true error).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from .cells import Cells

__all__ = [
    "FieldIntegral",
    "integrate_field",
    "InvalidSamples",
    "sample_density",
    "CHUNK_POINTS",
    "MAX_EVALUATIONS",
]

CHUNK_POINTS = 1 << 20  # quadrature points per pass: ~100 MB of float64 temporaries
MAX_EVALUATIONS = 20_000_000  # default budget of density evaluations for adaptive integration
_KEEP_BAD = 64  # invalid density samples kept for the caller to report

Density = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True, eq=False)
class FieldIntegral:
    """Moments of a density field over cells, about ``origin``.

    Attributes
    ----------
    origin : ndarray of shape (d,)
        The local origin the moments are taken about, m.
    mass : float
        ∫ρ, kg.
    first : ndarray of shape (d,)
        ∫ρ r, kg·m.
    second : ndarray of shape (d, d)
        ∫ρ r rᵀ, kg·m², symmetric.
    measure : float
        ∫1: area (m²) or volume (m³).
    exact : bool
        The rule was exact for the field's polynomial degree.
    error : float
        Estimated absolute error in kg (moments scaled by the body's size); 0 when exact.
    converged : bool
        The error is within the tolerance.
    evaluations : int
        Density evaluations spent.
    cells : int
        Cells in the final partition.
    bad_points : ndarray of shape (m, d)
        World points where the density was negative or not finite (at most a
        few, the worst first), and ``bad_values`` (m,) the values there.
    vector_area, surface_area, corner_points, corner_values
        Set by the closed-mesh kernel only: the surface's vector area (3,) m²
        (zero when closed), its area m², and the worst invalid samples at the
        mesh's vertices.
    """

    origin: np.ndarray
    mass: float
    first: np.ndarray
    second: np.ndarray
    measure: float
    exact: bool
    error: float
    converged: bool
    evaluations: int
    cells: int
    bad_points: np.ndarray
    bad_values: np.ndarray
    vector_area: np.ndarray | None = None
    surface_area: float = 0.0
    corner_points: np.ndarray | None = None
    corner_values: np.ndarray | None = None

    @classmethod
    def from_sums(cls, origin: np.ndarray, sums: np.ndarray, bad: InvalidSamples, *,
                  exact: bool, error: float, converged: bool, evaluations: int, cells: int,
                  **extra) -> FieldIntegral:
        """From flat sums ``[∫1, ∫ρ, ∫ρ r (d), ∫ρ r rᵀ (d²)]``; the second moment is symmetrised."""
        d = len(origin)
        second = sums[2 + d:].reshape(d, d)
        return cls(
            origin=np.asarray(origin, dtype=float), mass=float(sums[1]), first=sums[2:2 + d].copy(),
            second=(second + second.T) / 2, measure=float(sums[0]), exact=exact,
            error=float(error), converged=converged, evaluations=int(evaluations),
            cells=int(cells), bad_points=bad.points, bad_values=bad.values, **extra)


class InvalidSamples:
    """Keeps a few of the worst invalid density samples seen (non-finite first, then most negative).

    The callers decide what an invalid sample means (outside the body, signed
    decompositions sample a little beyond it); this only remembers where to look.
    """

    def __init__(self, dim: int) -> None:
        self.points = np.zeros((0, dim))
        self.values = np.zeros(0)

    def add(self, points: np.ndarray, values: np.ndarray) -> None:
        """Record the invalid ones among ``values`` (n,) at ``points`` (n, dim)."""
        if not values.size or (values.min() >= 0 and np.isfinite(values.sum())):
            return  # the common case, without a temporary mask
        bad = ~(np.isfinite(values) & (values >= 0))
        if not bad.any():
            return  # all valid, only their sum overflowed
        pts = np.concatenate((self.points, np.asarray(points, dtype=float)[bad]))
        vals = np.concatenate((self.values, values[bad]))
        key = np.where(np.isfinite(vals), vals, -np.inf)
        order = np.argsort(key, kind="stable")[:_KEEP_BAD]
        self.points, self.values = pts[order], vals[order]


def sample_density(density: Density, points: np.ndarray, bad: InvalidSamples) -> np.ndarray:
    """Evaluate ``density`` at world ``points`` (n, d): one value each, invalid ones recorded.

    Parameters
    ----------
    density : callable
        Maps points (n, d) m to densities (n,).
    points : ndarray of shape (n, d)
        World coordinates, m.
    bad : InvalidSamples
        Receives the negative or non-finite samples.

    Returns
    -------
    ndarray of shape (n,)
        The densities, as float.

    Raises
    ------
    ValueError
        If ``density`` does not return one value per point.

    Examples
    --------
    >>> bad = InvalidSamples(1)
    >>> sample_density(lambda p: p[:, 0] - 1, np.array([[0.0], [2.0]]), bad).tolist()
    [-1.0, 1.0]
    >>> bad.points.tolist(), bad.values.tolist()
    ([[0.0]], [-1.0])
    >>> sample_density(lambda p: np.ones(3), np.zeros((2, 1)), bad)
    Traceback (most recent call last):
    ...
    ValueError: a density field must return one value per point, got shape (3,)
    """
    values = np.asarray(density(points), dtype=float).reshape(-1)
    if values.shape != (len(points),):
        raise ValueError("a density field must return one value per point, "
                         f"got shape {values.shape}")
    bad.add(points, values)
    return values


# ------------------------------------------------------------------ sweeps over cells
def _evaluate(density: Density, points: np.ndarray, origin: np.ndarray,
              bad: InvalidSamples) -> np.ndarray:
    """The density at cell points (k, q, d) relative to ``origin`` → (k, q)."""
    k, q, d = points.shape
    return sample_density(density, points.reshape(-1, d) + origin, bad).reshape(k, q)


def _cell_sums(points: np.ndarray, weights: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Per-cell [∫1, ∫ρ, ∫ρ r (d), ∫ρ r rᵀ (d²)] → (k, 2 + d + d²)."""
    k, q, d = points.shape
    wr = weights * values
    out = np.empty((k, 2 + d + d * d))
    out[:, 0] = weights.sum(axis=1)
    out[:, 1] = wr.sum(axis=1)
    pw = points * wr[..., None]
    out[:, 2:2 + d] = pw.sum(axis=1)
    out[:, 2 + d:] = np.matmul(pw.transpose(0, 2, 1), points).reshape(k, d * d)
    return out


def _total_sums(points: np.ndarray, weights: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Sums over all cells (the fast path: one matrix product)."""
    k, q, d = points.shape
    flat = points.reshape(-1, d)
    wr = (weights * values).reshape(-1)
    out = np.empty(2 + d + d * d)
    out[0] = weights.sum()
    out[1] = wr.sum()
    pw = flat * wr[:, None]
    out[2:2 + d] = pw.sum(axis=0)
    out[2 + d:] = (pw.T @ flat).reshape(-1)
    return out


def _chunks(cells: Cells, per_cell: int) -> Iterator[Cells]:
    """Batches of cells of about :data:`CHUNK_POINTS` points, so temporaries stay bounded."""
    step = max(1, CHUNK_POINTS // max(per_cell, 1))
    for start in range(0, len(cells), step):
        yield cells.take(slice(start, start + step))


def _sweep(cells: Sequence[Cells], degree: int, density: Density, origin: np.ndarray,
           bad: InvalidSamples, per_cell: bool):
    """Rule of ``degree`` over every family.

    Returns (totals (s,) or, per family, (sums (k, s), sample min (k,), sample max (k,))),
    and the number of evaluations.
    """
    d = len(origin)
    size = 2 + d + d * d
    totals = np.zeros(size)
    parts = []
    evaluations = 0
    for family in cells:
        if not len(family):
            parts.append((np.zeros((0, size)), np.zeros(0), np.zeros(0)))
            continue
        q = family.points_per_cell(degree)
        rows, lows, highs = [], [], []
        for chunk in _chunks(family, q):
            pts, w = chunk.rule(degree)
            values = _evaluate(density, pts, origin, bad)
            evaluations += values.size
            if per_cell:
                rows.append(_cell_sums(pts, w, values))
                lows.append(values.min(axis=1))
                highs.append(values.max(axis=1))
            else:
                totals += _total_sums(pts, w, values)
        if per_cell:
            parts.append((np.concatenate(rows), np.concatenate(lows), np.concatenate(highs)))
    return (parts if per_cell else totals), evaluations


def _corner_ranges(cells: Sequence[Cells], density: Density, origin: np.ndarray,
                   bad: InvalidSamples):
    """Per family: the density's (min, max) over each cell's corners, and evaluations."""
    out, evaluations = [], 0
    for family in cells:
        lows, highs = [], []
        c = family.corners().shape[1] if len(family) else 1
        for chunk in _chunks(family, c):
            values = _evaluate(density, chunk.corners(), origin, bad)
            evaluations += values.size
            lows.append(values.min(axis=1))
            highs.append(values.max(axis=1))
        out.append((np.concatenate(lows) if lows else np.zeros(0),
                    np.concatenate(highs) if highs else np.zeros(0)))
    return out, evaluations


# ------------------------------------------------------------------ error estimates
def _blind_spots(sums: np.ndarray, lo: tuple, hi: tuple, corners: tuple) -> np.ndarray:
    """Error bound (kg) for cells whose corners see values their quadrature points miss.

    A jump that only clips a cell's corner can fall between every Gauss point of
    both rules, so the two agree; the corners see it. A corner value outside
    the samples' range by more than that range marks such a cell, and its error
    is bounded by ``|cell size| × excess`` (a smooth field's corners stay
    within about one range of its samples).
    """
    smin = np.minimum(lo[1], hi[1])
    smax = np.maximum(lo[2], hi[2])
    excess = np.maximum(np.maximum(corners[1] - smax, smin - corners[0]), 0.0)
    spread = smax - smin
    scale = np.maximum(np.abs(smax), np.abs(smin))
    flagged = excess > spread + 1e-9 * scale
    return np.where(flagged, 3 * np.abs(sums[:, 0]) * excess, 0.0)


def _norm(diff: np.ndarray, d: int, size: float) -> np.ndarray:
    """Errors in kg from differences of per-cell sums (k, s): mass + moments / size^k."""
    return (np.abs(diff[:, 1]) + np.abs(diff[:, 2:2 + d]).sum(axis=1) / size
            + np.abs(diff[:, 2 + d:]).sum(axis=1) / size**2)


# ------------------------------------------------------------------ the driver
def integrate_field(
    cells: Sequence[Cells],
    density: Density,
    origin: np.ndarray,
    degree: int | None,
    *,
    tolerance: float = 1e-10,
    size: float = 1.0,
    max_evaluations: int = MAX_EVALUATIONS,
) -> FieldIntegral:
    """Integrate a density field and its first and second moments over signed cells.

    With ``degree`` (the field's polynomial degree) one pass of a rule of
    degree ``degree + 2`` is exact. Without it the integral is adaptive (see
    the module docstring): rules are raised, then cells split, until the
    estimated error is within ``tolerance``, or the budget is spent.

    Parameters
    ----------
    cells : sequence of Cells
        Families of signed cells, coordinates relative to ``origin``.
    density : callable
        Maps world points (n, d), m, to densities (n,), kg/m^d.
    origin : array_like of shape (d,)
        The cells' local origin in world coordinates, m; moments are about it.
    degree : int or None
        The field's polynomial degree, or None for any other field.
    tolerance : float, default 1e-10
        Adaptive only: the error allowed, relative to the mass.
    size : float, default 1.0
        Adaptive only: the body's size, m, against which moment errors are
        measured (a first-moment error δ counts as δ / size kg).
    max_evaluations : int, default MAX_EVALUATIONS
        Adaptive only: the budget of density evaluations.

    Returns
    -------
    FieldIntegral
        The moments; ``exact`` when ``degree`` was given, else ``error`` is the
        estimate and ``converged`` whether it met the tolerance. Negative or
        non-finite samples are reported in ``bad_points`` / ``bad_values``,
        not raised: whether they lie inside the body is the caller's question.

    Raises
    ------
    ValueError
        From :func:`sample_density`, if ``density`` gives other than one value per point.

    Examples
    --------
    >>> from plumbob.integrals.cells import SimplexCells
    >>> tri = SimplexCells(np.array([[[0, 0], [1, 0], [0, 1]]], dtype=float))
    >>> r = integrate_field([tri], lambda p: 1 + p[:, 0], np.zeros(2), 1)
    >>> round(r.mass, 15), r.exact            # ∫(1 + x) over the triangle = 1/2 + 1/6
    (0.666666666666667, True)
    >>> r = integrate_field([tri], lambda p: np.exp(p[:, 0]), np.zeros(2), None)
    >>> abs(r.mass - (np.e - 2)) <= r.error, r.exact
    (True, False)
    >>> r = integrate_field([], lambda p: p[:, 0], np.zeros(2), 1)   # no cells: nothing
    >>> r.mass, r.measure, r.cells
    (0.0, 0.0, 0)
    """
    origin = np.asarray(origin, dtype=float)
    d = len(origin)
    bad = InvalidSamples(d)
    ncells = sum(len(c) for c in cells)
    if degree is not None:
        sums, evaluations = _sweep(cells, int(degree) + 2, density, origin, bad, per_cell=False)
        return FieldIntegral.from_sums(origin, sums, bad, exact=True, error=0.0, converged=True,
                                       evaluations=evaluations, cells=ncells)

    size = float(size) if size > 0 else 1.0
    families = [c for c in cells if len(c)]

    def cost(fams: Sequence[Cells], n: int) -> int:
        return sum(len(f) * (f.points_per_cell(2 * n - 1) + f.points_per_cell(2 * n + 1))
                   for f in fams)

    def result(sums: np.ndarray, error: float, converged: bool, cells: int) -> FieldIntegral:
        return FieldIntegral.from_sums(origin, sums, bad, exact=False, error=error,
                                       converged=converged, evaluations=spent, cells=cells)

    # Start as high as the budget allows (3 points per direction, down to 1).
    n = next((m for m in (3, 2) if cost(families, m) <= max_evaluations / 4), 1)
    lo_parts, spent = _sweep(families, 2 * n - 1, density, origin, bad, per_cell=True)
    corner_parts, ev = _corner_ranges(families, density, origin, bad)
    spent += ev
    done = np.zeros(2 + d + d * d)
    done_error = 0.0
    done_cells = 0
    total_measure = None
    previous = math.inf
    p_phase = True
    while True:
        hi_parts, ev = _sweep(families, 2 * n + 1, density, origin, bad, per_cell=True)
        spent += ev
        errors = [_norm(h[0] - lo[0], d, size) + _blind_spots(h[0], lo, h, c)
                  for h, lo, c in zip(hi_parts, lo_parts, corner_parts)]
        total = done + sum((h[0].sum(axis=0) for h in hi_parts), np.zeros_like(done))
        error = done_error + sum(float(e.sum()) for e in errors)
        target = tolerance * abs(total[1])
        active = sum(len(f) for f in families)
        if total_measure is None:
            total_measure = sum(float(np.abs(h[0][:, 0]).sum()) for h in hi_parts) or 1.0
        if error <= target or not active:
            return result(total, error, error <= target, done_cells + active)
        if (p_phase and error < previous / 4 and n < 8
                and spent + cost(families, n + 1) <= max_evaluations / 2):
            previous = error
            n += 1
            lo_parts = hi_parts
            continue
        p_phase = False
        # h-phase: accept cells within their share of the tolerance, split the rest.
        kept = []
        for family, h, e in zip(families, hi_parts, errors):
            share = 0.5 * target * np.abs(h[0][:, 0]) / total_measure
            refine = e > share
            done += h[0][~refine].sum(axis=0)
            done_error += float(e[~refine].sum())
            done_cells += int((~refine).sum())
            if refine.any():
                kept.append(family.take(np.flatnonzero(refine)).split())
        if spent + cost(kept, n) > max_evaluations:
            return result(total, error, False, done_cells + active)
        families = kept
        lo_parts, ev = _sweep(families, 2 * n - 1, density, origin, bad, per_cell=True)
        spent += ev
        corner_parts, ev = _corner_ranges(families, density, origin, bad)
        spent += ev
