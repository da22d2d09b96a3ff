"""Planar convex hulls in numpy: quickhull with every edge split at once.

A lamina rests on the edges of its planar hull, and a solid stands on the hull of
its lowest points (the support polygon). scipy's qhull would do, but importing
``scipy.spatial`` costs 0.3–0.6 s, many times the rest of ``plumbob poses`` or
``plumbob check``. Quickhull splits each hull edge at the point farthest outside it; here every
edge that has points outside is split in the same round, so the rounds number about
``log₂`` of the corners (a circle of 4 096 points: 12), each a handful of vectorised
passes over the points still outside.

The corners are input points (exact copies), counter-clockwise. A point is split off
an edge only where the sign of its side is certain (Shewchuk's error bound), so a point
on a hull edge's line, exactly or to round-off, is never a corner (a point outside by
less than the round-off of the test is left out: the hull misses it by that much).
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError

__all__ = ["planar_hull", "drop_collinear"]


#: Shewchuk's bound on the error of orient2d evaluated in floating point, (3 + 16ε)ε
#: times |detleft| + |detright| (ε = 2⁻⁵³; "Adaptive Precision Floating-Point
#: Arithmetic and Fast Robust Geometric Predicates", 1997): within it the sign is unknown
_ORIENT_BOUND = (3.0 + 16.0 * 2.0**-53) * 2.0**-53


def _outside(X: np.ndarray, start: np.ndarray, end: np.ndarray, point: np.ndarray
             ) -> np.ndarray:
    """How far (times the edge's length) each ``point`` lies right of the directed edge
    ``start → end`` (all index arrays into X): positive outside a counter-clockwise hull.

    0 where the sign is not certain (the point is on the edge's line to round-off): a
    point split off by an uncertain sign could lie beyond the edge's end, and the hull
    would fold back on itself along the line (a rotated row of collinear points did)."""
    d = X[end] - X[start]
    r = X[point] - X[start]
    left, right = d[:, 1] * r[:, 0], d[:, 0] * r[:, 1]
    value = left - right
    return np.where(np.abs(value) > _ORIENT_BOUND * (np.abs(left) + np.abs(right)), value, 0.0)


def planar_hull(points: np.ndarray) -> np.ndarray:
    """Indices of the corners of the convex hull of ``points`` (n, 2), counter-clockwise,
    starting at the leftmost point (the lowest of those).

    Raises GeometryError when the points span no area (all on one line, or one point).

    >>> square = np.array([[0, 0], [2, 0], [1, 0], [2, 2], [0, 2], [1, 1], [1, 2]], float)
    >>> planar_hull(square).tolist()
    [0, 1, 3, 4]
    """
    X = np.asarray(points, dtype=float)
    n = len(X)
    if n < 3:
        raise GeometryError("the lamina is degenerate: its points span no area")
    order = np.lexsort((X[:, 1], X[:, 0]))
    a, b = int(order[0]), int(order[-1])
    start = np.array([a, b])
    end = np.array([b, a])
    pts = np.arange(n)
    below = _outside(X, start[[0]].repeat(n), end[[0]].repeat(n), pts)
    owner = np.where(below > 0, 0, np.where(below < 0, 1, -1))
    keep = owner >= 0
    pts, owner, dist = pts[keep], owner[keep], np.abs(below[keep])
    if len(pts) == 0:
        raise GeometryError("the lamina is degenerate: its points span no area")
    for _ in range(n):
        if len(pts) == 0:
            break
        # the point farthest outside each edge that has any; ties: farthest along the edge
        base = X[start[owner]]
        along = ((X[pts] - base) * (X[end[owner]] - base)).sum(axis=1)
        rank = np.lexsort((pts, -along, -dist, owner))
        first = np.ones(len(rank), dtype=bool)
        first[1:] = owner[rank][1:] != owner[rank][:-1]
        split_edges = owner[rank][first]
        apex = np.full(len(start), -1, dtype=np.int64)
        apex[split_edges] = pts[rank][first]
        # each split edge becomes two, in place: start → apex, apex → end
        split = apex >= 0
        width = 1 + split
        new_first = np.cumsum(width) - width
        new_start = np.empty(int(width.sum()), dtype=np.int64)
        new_end = np.empty_like(new_start)
        new_start[new_first] = start
        new_end[new_first] = np.where(split, apex, end)
        second = new_first[split] + 1
        new_start[second] = apex[split]
        new_end[second] = end[split]
        # the points outside a split edge: outside its first half, its second, or neither
        e = owner
        c = apex[e]
        left_part = _outside(X, start[e], c, pts)
        right_part = _outside(X, c, end[e], pts)
        owner = np.where(left_part > 0, new_first[e],
                         np.where(right_part > 0, new_first[e] + 1, -1))
        dist = np.where(left_part > 0, left_part, right_part)
        keep = owner >= 0
        pts, owner, dist = pts[keep], owner[keep], dist[keep]
        start, end = new_start, new_end
    return start


def drop_collinear(V: np.ndarray, tol: float) -> np.ndarray:
    """The corners of the convex polygon ``V`` (k, 2), counter-clockwise, without those
    lying within ``tol`` (m) of the line through their neighbours (at least 3 kept).

    >>> drop_collinear(np.array([[0, 0], [1, 0], [2, 0], [2, 2], [0, 2]], float), 1e-9).tolist()
    [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]
    """
    for _ in range(len(V)):
        prev, nxt = np.roll(V, 1, axis=0), np.roll(V, -1, axis=0)
        d = nxt - prev
        off = np.abs(d[:, 0] * (V - prev)[:, 1] - d[:, 1] * (V - prev)[:, 0])
        off /= np.linalg.norm(d, axis=1)
        flat = off <= tol
        if not flat.any() or len(V) - flat.sum() < 3:
            break
        V = V[~(flat & ~np.roll(flat, 1))]  # the first of each run: neighbours change
    return V
