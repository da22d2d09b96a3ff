"""Curves as exact ring edges: circular arcs as bulges, elliptical arcs as cubics.

Shared by the drawing readers (SVG, DXF). A circular arc is exact as a bulge
edge; an elliptical arc, not polynomial, becomes cubic Béziers — the affine
image of the standard cubic for a circular arc — within a stated area error.
An unclamped (periodic, closed) B-spline is clamped exactly to its own domain
by knot insertion, so it splits into Bézier pieces like any clamped one.
"""

from __future__ import annotations

import numpy as np

__all__ = ["ELLIPSE_STEP", "arc_bulges", "clamped_bspline", "elliptic_arc_cubics"]

#: parameter step of the cubic pieces approximating elliptical arcs (64 per turn)
ELLIPSE_STEP = 2 * np.pi / 64


def _arc_error(step: float) -> float:
    """Largest radial deviation of the standard cubic (k = 4/3 tan(step/4)) from a unit
    circular arc of angle ``step``."""
    k = 4 / 3 * np.tan(step / 4)
    t = np.linspace(0, 1, 257)[:, None]
    p0, p3 = np.array([1.0, 0.0]), np.array([np.cos(step), np.sin(step)])
    p1, p2 = p0 + k * np.array([0.0, 1.0]), p3 - k * np.array([-np.sin(step), np.cos(step)])
    b = (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t**2 * p2 + t**3 * p3
    return float(np.abs(np.hypot(b[:, 0], b[:, 1]) - 1).max())


def elliptic_arc_cubics(centre: np.ndarray, u: np.ndarray, v: np.ndarray, t0: float,
                        sweep: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Cubic Béziers for ``E(t) = centre + cos t·u + sin t·v``, t from t0 through ``sweep``.

    u, v: conjugate semi-diameters (2,), m. Returns the piece ends (m+1, 2), their
    inner controls (m, 2, 2) and a bound on the area between curve and cubics, m².
    Each piece is the affine image of the standard cubic for a circular arc of at
    most :data:`ELLIPSE_STEP` (error ~1e-11 of the radius).
    """
    pieces = max(1, int(np.ceil(abs(sweep) / ELLIPSE_STEP - 1e-9)))
    h = sweep / pieces
    t = t0 + h * np.arange(pieces + 1)
    c, s = np.cos(t), np.sin(t)
    points = centre + c[:, None] * u + s[:, None] * v
    tangent = -s[:, None] * u + c[:, None] * v
    k = 4 / 3 * np.tan(h / 4)
    controls = np.stack((points[:-1] + k * tangent[:-1], points[1:] - k * tangent[1:]), axis=1)
    stretch = float(np.linalg.norm(np.column_stack((u, v)), 2))
    error = _arc_error(abs(h)) * stretch * stretch * abs(sweep)
    return points, controls, error


def arc_bulges(centre: np.ndarray, radius: float, start: float, sweep: float
               ) -> tuple[np.ndarray, np.ndarray]:
    """A circular arc as bulge edges: start points (m, 2) and bulges (m,), m ≤ 2.

    ``start``, ``sweep``: radians, positive sweep counter-clockwise; sweeps over
    half a turn are split in two so no bulge nears infinity. Quarter-turn angles
    give exact cosines.

    >>> starts, bulges = arc_bulges(np.zeros(2), 2.0, 0.0, 2 * np.pi)  # a whole circle
    >>> starts.tolist(), bulges.round(12).tolist()
    ([[2.0, 0.0], [-2.0, 0.0]], [1.0, 1.0])
    """
    pieces = 2 if abs(sweep) > np.pi else 1
    angles = start + sweep * np.arange(pieces) / pieces
    cos, sin = _exact_cos_sin(angles)
    points = centre + radius * np.stack((cos, sin), axis=1)
    return points, np.full(pieces, np.tan(sweep / pieces / 4))


def _exact_cos_sin(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    cos, sin = np.cos(angles), np.sin(angles)
    quarter = angles / (np.pi / 2)
    on_axis = np.abs(quarter - np.rint(quarter)) < 1e-12
    q = np.rint(quarter[on_axis]).astype(int) % 4
    cos[on_axis] = np.array([1.0, 0.0, -1.0, 0.0])[q]
    sin[on_axis] = np.array([0.0, 1.0, 0.0, -1.0])[q]
    return cos, sin


def clamped_bspline(control: np.ndarray, knots: np.ndarray, degree: int
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The same curve as the B-spline (``control`` (n, d), ``knots`` (n + degree + 1,)) on
    its domain ``[knots[degree], knots[n]]``, with clamped knots (each end repeated
    degree + 1 times), by Boehm's knot insertion: exact, not a fit.

    An unclamped spline (a DXF closed periodic SPLINE) is defined only on that domain;
    evaluated outside it — over its whole knot vector — it runs off its own curve.
    Rational splines are clamped the same way in homogeneous coordinates (x·w, y·w, w).

    >>> control = np.array([[0.0, 0.0], [1.0, 2.0], [2.0, 0.0], [3.0, 2.0]])
    >>> c, k = clamped_bspline(control, np.arange(7.0), 2)   # uniform: domain [2, 4]
    >>> c.tolist(), k.tolist()
    ([[0.5, 1.0], [1.0, 2.0], [2.0, 0.0], [2.5, 1.0]], [2.0, 2.0, 2.0, 3.0, 4.0, 4.0, 4.0])
    """
    points = np.asarray(control, dtype=float)
    u = np.asarray(knots, dtype=float)
    p, n = int(degree), len(points)
    if p < 1 or n <= p or u.shape != (n + p + 1,) or not np.isfinite(u).all() \
            or (np.diff(u) < 0).any() or not u[p] < u[n]:
        raise ValueError(f"a degree-{p} spline of {n} control points needs {n + p + 1} "
                         "finite, non-decreasing knots spanning a domain")
    a, b = u[p], u[n]
    for t in (a, b):  # each end up to multiplicity p
        for _ in range(p - int(np.count_nonzero(u == t))):
            points, u = _insert_knot(points, u, p, t)
    last_a = int(np.searchsorted(u, a, side="right")) - 1
    first_b = int(np.searchsorted(u, b, side="left"))
    inner = u[last_a + 1:first_b]
    knots_out = np.concatenate((np.full(p + 1, a), inner, np.full(p + 1, b)))
    return points[last_a - p:first_b], knots_out


def _insert_knot(points: np.ndarray, u: np.ndarray, p: int, t: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Boehm: insert ``t`` once (the curve unchanged; one control point more)."""
    k = int(np.searchsorted(u, t, side="right")) - 1
    s = int(np.count_nonzero(u == t))
    i = np.arange(k - p + 1, k - s + 1)
    alpha = ((t - u[i]) / (u[i + p] - u[i]))[:, None]
    new = (1 - alpha) * points[i - 1] + alpha * points[i]
    points = np.concatenate((points[:k - p + 1], new, points[k - s:]))
    return points, np.insert(u, k + 1, t)

