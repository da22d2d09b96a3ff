"""The part of a closed mesh on one side of a plane: its volume and centroid, exactly.

Why: the best carve is a plane cut of the interior (:mod:`plumbob.balance.hollow`),
and choosing the plane takes a few hundred cuts, so each must cost one vectorised pass
over the triangles, not a boolean.

How: by the divergence theorem the volume of the solid ``{p in interior : n·p ≥ τ}``
is the sum of the signed tetrahedra that its boundary's triangles span with an
origin ``o`` — and with ``o`` on the plane, the cap (the cut face, in the plane) spans
only flat tetrahedra, so it adds nothing to the volume nor to the first moment. The
boundary's other part is the mesh's triangles clipped to the half-space: kept whole
when all three corners are on the kept side, cut into one or two triangles when the
plane crosses them (the corners in their own order, so the winding is kept).
Coordinates are taken about the mesh's own centre first (then products stay exact far
from the world origin).
"""

from __future__ import annotations

import numpy as np

__all__ = ["PlaneCuts"]


class PlaneCuts:
    """A closed, outward-wound triangle mesh, ready to be cut by planes.

    triangles: (n, 3, 3) m.
    """

    def __init__(self, triangles: np.ndarray):
        tri = np.asarray(triangles, dtype=float).reshape(-1, 3, 3)
        self.centre = 0.5 * (tri.reshape(-1, 3).min(axis=0) + tri.reshape(-1, 3).max(axis=0))
        self.triangles = tri - self.centre

    def span(self, normal: np.ndarray) -> tuple[float, float]:
        """The least and greatest ``normal · p`` over the mesh, m (``normal`` a unit vector)."""
        heights = self.triangles.reshape(-1, 3) @ normal + float(self.centre @ normal)
        return float(heights.min()), float(heights.max())

    def along(self, normal: np.ndarray) -> _Along:
        """The cuts across one ``normal`` (a unit vector), ready for many offsets."""
        return _Along(self, np.asarray(normal, dtype=float))

    def moments(self, normal: np.ndarray, offset: float) -> tuple[float, np.ndarray]:
        """Volume (m³) and first moment about the world origin ((3,) m⁴) of the part of the
        mesh where ``normal · p ≥ offset`` (``normal`` a unit vector).

        >>> import manifold3d
        >>> from plumbob.bodies.offset import manifold_triangles
        >>> cube = PlaneCuts(manifold_triangles(manifold3d.Manifold.cube([2.0, 1.0, 1.0])))
        >>> volume, moment = cube.moments(np.array([1.0, 0.0, 0.0]), 0.5)
        >>> round(volume, 12), (moment / volume).round(12).tolist()
        (1.5, [1.25, 0.5, 0.5])
        """
        return self.along(normal).moments(offset)


def _clip(tri: np.ndarray, side: np.ndarray) -> np.ndarray:
    """The parts of triangles (m, 3, 3) where their corners' heights ``side`` (m, 3) are
    ≥ 0, as triangles in the same winding."""
    above = side >= 0
    count = above.sum(axis=1)
    pieces = [tri[count == 3]]
    for kept in (1, 2):
        sel = count == kept
        if not np.any(sel):
            continue
        t, h, a = tri[sel], side[sel], above[sel]
        # roll each triangle so the odd corner (the one alone on its side) comes first
        odd = a if kept == 1 else ~a
        first = np.argmax(odd, axis=1)
        order = (first[:, None] + np.arange(3)[None]) % 3
        t = np.take_along_axis(t, order[:, :, None], axis=1)
        h = np.take_along_axis(h, order, axis=1)
        p, q, r = t[:, 0], t[:, 1], t[:, 2]
        hp, hq, hr = h[:, :1], h[:, 1:2], h[:, 2:3]
        pq = p + (q - p) * (hp / (hp - hq))  # where the edges from the odd corner cross
        pr = p + (r - p) * (hp / (hp - hr))
        if kept == 1:
            pieces.append(np.stack((p, pq, pr), axis=1))
        else:
            pieces.append(np.stack((pq, q, r), axis=1))
            pieces.append(np.stack((pq, r, pr), axis=1))
    return np.concatenate(pieces)


class _Along:
    """Cuts across one normal. With ``o`` the plane's point ``τ n`` (about the mesh's
    centre), a whole triangle's tetrahedron has ``6 V = D − o·N`` (``D = det(a, b, c)``,
    ``N = a×b + b×c + c×a``) and first moment ``6 V (a + b + c + o) / 24``: polynomials in
    ``τ`` whose coefficients are summed once over the triangles ordered by their lowest
    corner, so a cut costs a search, a suffix of sums and the few triangles it crosses."""

    def __init__(self, cuts: PlaneCuts, normal: np.ndarray):
        self.cuts, self.normal = cuts, normal
        tri = cuts.triangles
        heights = tri @ normal  # (n, 3)
        low = heights.min(axis=1)
        order = np.argsort(low, kind="stable")
        self.tri, self.heights, self.low = tri[order], heights[order], low[order]
        self.high = self.heights.max(axis=1)
        a, b, c = self.tri[:, 0], self.tri[:, 1], self.tri[:, 2]
        d = np.einsum("ij,ij->i", a, np.cross(b, c))
        n = np.cross(a, b) + np.cross(b, c) + np.cross(c, a)
        s = a + b + c
        # per triangle: D, D S (3), N (3), N ⊗ S (9): summed from the top
        terms = np.hstack((d[:, None], d[:, None] * s, n,
                           (n[:, :, None] * s[:, None, :]).reshape(-1, 9)))
        self.suffix = np.vstack((np.cumsum(terms[::-1], axis=0)[::-1], np.zeros((1, 16))))

    def moments(self, offset: float) -> tuple[float, np.ndarray]:
        """Volume (m³) and first moment about the world origin ((3,) m⁴) of the part where
        ``normal · p ≥ offset``."""
        tau = float(offset) - float(self.cuts.centre @ self.normal)
        o = tau * self.normal
        start = int(np.searchsorted(self.low, tau, side="left"))  # whole from here on
        d, ds, n, ns = (self.suffix[start, :1], self.suffix[start, 1:4],
                        self.suffix[start, 4:7], self.suffix[start, 7:].reshape(3, 3))
        six = float(d[0] - o @ n)
        first = ds + o * float(d[0]) - o @ ns - o * float(o @ n)
        crossed = np.flatnonzero(self.high[:start] >= tau)
        if len(crossed):
            part = _clip(self.tri[crossed] - o, self.heights[crossed] - tau)
            a, b, c = part[:, 0], part[:, 1], part[:, 2]
            six_p = np.einsum("ij,ij->i", a, np.cross(b, c))
            six += float(six_p.sum())
            first = first + (six_p[:, None] * (a + b + c + 4 * o)).sum(axis=0)
        volume = six / 6.0
        return volume, first / 24.0 + volume * self.cuts.centre
