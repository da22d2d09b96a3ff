"""Signed distances from a closed triangle mesh, on a regular grid of points.

Why a grid: an inward offset of a free-form surface is a level set of the
distance to it, and a level set is extracted from values on a grid
(:mod:`plumbob.bodies.offset`). Two questions per grid point, both vectorised:

* **inside or out** — exactly, by counting the mesh's crossings of each grid
  column (a vertical line), with a watertight tie rule: every edge function is
  evaluated with its two ends in one canonical order, so a column through a
  shared edge or vertex is claimed by exactly one of the faces meeting there;
* **how far** — the exact distance to the surface (:class:`SurfaceDistance`: libigl's
  bounding-box tree over the triangles, every triangle that could be nearer measured).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..limits import MAX_SAMPLES, check_count

__all__ = ["DistanceGrid", "SurfaceDistance", "distance_grid", "point_triangle_distances"]

#: grid points per pass (candidate arrays of a few tens of MB)
_BLOCK = 1 << 16
#: the coarse pre-pass of a banded grid takes every this many-th point along each axis
_COARSE = 4


@dataclass(frozen=True, eq=False)
class DistanceGrid:
    """Signed distances on a regular grid: positive inside the mesh.

    origin: (3,) m, the first grid point; step: m, the spacing; values: (nx, ny, nz), m.
    The distances are exact (to round-off) within the band asked for.
    """

    origin: np.ndarray
    step: float
    values: np.ndarray


class SurfaceDistance:
    """Exact distances from points to a triangle mesh's surface (the nearest point of any
    of its filled triangles), at array speed: libigl's axis-aligned bounding-box tree over
    the triangles, built once, searched in C++ for each point (every triangle whose box is
    nearer than the nearest found so far is measured, so none is missed). The triangles
    are shifted to a local origin first, so distances keep their digits far from the
    file's origin.

    >>> from plumbob.bodies.primitives import box
    >>> surface = SurfaceDistance(box(2, 2, 2).triangles)
    >>> distance, nearest = surface.query(np.array([[1.0, 1, 1], [1, 1, 3], [3, 3, 3]]))
    >>> distance.round(12).tolist(), nearest[2].tolist()
    ([1.0, 1.0, 1.732050807569], [2.0, 2.0, 2.0])
    """

    def __init__(self, triangles: np.ndarray):
        import igl

        tri = np.asarray(triangles, dtype=float).reshape(-1, 3, 3)
        if not len(tri):
            raise ValueError("a surface needs triangles")
        self.origin = tri.reshape(-1, 3).min(axis=0)
        # a soup: the tree needs no shared corners
        self.vertices = np.ascontiguousarray((tri - self.origin).reshape(-1, 3))
        self.faces = np.arange(3 * len(tri), dtype=np.int64).reshape(-1, 3)
        self.tree = igl.AABB()
        self.tree.init(self.vertices, self.faces)

    def query(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(the distance (n,) m, the nearest surface point (n, 3)) of each point (n, 3)."""
        local = np.ascontiguousarray(np.asarray(points, dtype=float).reshape(-1, 3) - self.origin)
        if not len(local):
            return np.zeros(0), np.zeros((0, 3))
        squared, _, nearest = self.tree.squared_distance(self.vertices, self.faces, local)
        return np.sqrt(np.maximum(squared, 0.0)), nearest + self.origin

    def distances(self, points: np.ndarray) -> np.ndarray:
        """The distance (n,) m from each point (n, 3)."""
        return self.query(points)[0]


def point_triangle_distances(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """The distance from each point (..., 3) to its own filled triangle (..., 3, 3), m.

    Ericson's closest-point regions (vertex, edge, face), vectorised.

    >>> tri = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    >>> point_triangle_distances(np.array([[0.2, 0.2, 3.0], [2.0, 0, 0], [-1, -1, 0]]),
    ...                          np.broadcast_to(tri, (3, 3, 3))).round(12).tolist()
    [3.0, 1.0, 1.414213562373]
    """
    p = np.asarray(points, dtype=float)
    a, b, c = (np.asarray(triangles, dtype=float)[..., k, :] for k in range(3))
    ab, ac, ap = b - a, c - a, p - a

    def dot(x, y):
        return np.einsum("...i,...i->...", x, y)

    d1, d2 = dot(ab, ap), dot(ac, ap)
    bp, cp = p - b, p - c
    d3, d4 = dot(ab, bp), dot(ac, bp)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        # the face region by default, then each edge and vertex region overrides it
        denom = va + vb + vc
        v = np.where(denom != 0, vb / np.where(denom != 0, denom, 1), 0.0)
        w = np.where(denom != 0, vc / np.where(denom != 0, denom, 1), 0.0)
        closest = a + v[..., None] * ab + w[..., None] * ac
        bc_w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        on_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        closest = np.where(on_bc[..., None], b + np.nan_to_num(bc_w)[..., None] * (c - b), closest)
        on_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        closest = np.where(on_ac[..., None], a + np.nan_to_num(d2 / (d2 - d6))[..., None] * ac, closest)
        on_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        closest = np.where(on_ab[..., None], a + np.nan_to_num(d1 / (d1 - d3))[..., None] * ab, closest)
    closest = np.where(((d6 >= 0) & (d5 <= d6))[..., None], c, closest)
    closest = np.where(((d3 >= 0) & (d4 <= d3))[..., None], b, closest)
    closest = np.where(((d1 <= 0) & (d2 <= 0))[..., None], a, closest)
    off = p - closest
    return np.sqrt(dot(off, off))


def _edge_function(p: np.ndarray, q: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The 2D cross product (q − p) × (point − p), evaluated with (p, q) in one canonical
    (lexicographic) order and the sign put back: bitwise the negative of the same edge
    seen from its other face, so shared edges split the plane without gaps or overlaps."""
    swap = (p[:, 0] > q[:, 0]) | ((p[:, 0] == q[:, 0]) & (p[:, 1] > q[:, 1]))
    lo = np.where(swap[:, None], q, p)
    hi = np.where(swap[:, None], p, q)
    value = (hi[:, 0] - lo[:, 0]) * (y - lo[:, 1]) - (hi[:, 1] - lo[:, 1]) * (x - lo[:, 0])
    return np.where(swap, -value, value), swap


def _column_winding(triangles: np.ndarray, xs: np.ndarray, ys: np.ndarray,
                    zs: np.ndarray) -> np.ndarray:
    """Winding numbers (nx, ny, nz) of the mesh about every grid point, by counting
    crossings of the column above each point (exact but for the grid's own round-off)."""
    t = triangles[:, :, :2]
    area = ((t[:, 1, 0] - t[:, 0, 0]) * (t[:, 2, 1] - t[:, 0, 1])
            - (t[:, 1, 1] - t[:, 0, 1]) * (t[:, 2, 0] - t[:, 0, 0]))
    keep = area != 0  # faces seen edge-on from above are crossed by no column
    tri, area = triangles[keep], area[keep]
    lo, hi = tri[:, :, :2].min(axis=1), tri[:, :, :2].max(axis=1)
    i0, i1 = np.searchsorted(xs, lo[:, 0]), np.searchsorted(xs, hi[:, 0], side="right")
    j0, j1 = np.searchsorted(ys, lo[:, 1]), np.searchsorted(ys, hi[:, 1], side="right")
    ni, nj = np.maximum(i1 - i0, 0), np.maximum(j1 - j0, 0)
    pairs = ni * nj
    check_count("column crossings tested", int(pairs.sum()), 50 * MAX_SAMPLES,
                hint="use a coarser offset step")
    face = np.repeat(np.arange(len(tri)), pairs)
    k = np.arange(len(face)) - np.repeat(np.cumsum(pairs) - pairs, pairs)
    ci, cj = i0[face] + k // np.maximum(nj[face], 1), j0[face] + k % np.maximum(nj[face], 1)
    x, y = xs[ci], ys[cj]
    f = tri[face]
    orient = np.sign(area[face])
    inside = np.ones(len(face), dtype=bool)
    for e in range(3):
        value, swap = _edge_function(f[:, e, :2], f[:, (e + 1) % 3, :2], x, y)
        value = value * orient
        # ties go to the face for which the canonical edge runs one way: a top-left rule
        inside &= (value > 0) | ((value == 0) & (swap == (orient > 0)))
    face, ci, cj, x, y, f = face[inside], ci[inside], cj[inside], x[inside], y[inside], f[inside]
    a, b, c = f[:, 0], f[:, 1], f[:, 2]
    normal = np.cross(b - a, c - a)
    z_hit = a[:, 2] - (normal[:, 0] * (x - a[:, 0]) + normal[:, 1] * (y - a[:, 1])) / normal[:, 2]
    # a column point below the crossing sees it above: +1 for a face leaving upward (nz > 0)
    below = np.searchsorted(zs, z_hit)
    counts = np.zeros((len(xs), len(ys), len(zs) + 1))
    np.add.at(counts, (ci, cj, np.zeros_like(ci)), np.sign(normal[:, 2]))
    np.add.at(counts, (ci, cj, below), -np.sign(normal[:, 2]))
    return np.cumsum(counts, axis=2)[:, :, :-1]


def distance_grid(triangles: np.ndarray, lower: np.ndarray, upper: np.ndarray, step: float,
                  *, band: tuple[float, float] | None = None,
                  surface: SurfaceDistance | None = None) -> DistanceGrid:
    """Signed distances (positive inside) from a closed, outward mesh at the points of a
    regular grid covering the box ``lower``..``upper`` (each (3,), m) at ``step`` m.

    Parameters
    ----------
    triangles : ndarray, shape (n, 3, 3)
        A closed, outward-wound mesh, m.
    lower, upper : array_like, shape (3,)
        The box to cover, m.
    step : float
        Grid spacing, m.
    band : (float, float), optional
        Only distances between these bounds (m, unsigned) need be exact: a grid
        point that a coarser grid shows to lie outside the band keeps that coarse
        estimate (on the right side of the band), which saves most of the work.
    surface : SurfaceDistance, optional
        The mesh's distance search, when the caller has built it already.

    Returns
    -------
    DistanceGrid

    Examples
    --------
    >>> from plumbob.bodies.primitives import box
    >>> g = distance_grid(box(2, 2, 2).triangles, [0.5] * 3, [1.5] * 3, 0.5)
    >>> g.values.shape, float(g.values[1, 1, 1]), float(g.values[0, 1, 1])
    ((3, 3, 3), 1.0, 0.5)
    """
    tri = np.asarray(triangles, dtype=float)
    lower, upper = np.asarray(lower, dtype=float), np.asarray(upper, dtype=float)
    counts = np.floor((upper - lower) / step + 1e-9).astype(np.int64) + 1
    check_count("offset grid points", float(np.prod(counts.astype(float))), MAX_SAMPLES,
                hint="give a coarser offset step")
    xs, ys, zs = (lower[k] + step * np.arange(counts[k]) for k in range(3))
    winding = _column_winding(tri, xs, ys, zs)
    grid = np.stack(np.meshgrid(xs, ys, zs, indexing="ij"), axis=-1).reshape(-1, 3)
    distance = np.full(len(grid), np.nan)
    if band is not None and np.all(counts > 2 * _COARSE):
        # A coarse pass first: the distance is 1-Lipschitz, so a fine point whose
        # nearest coarse point is far outside the band is outside it too, and keeps
        # that estimate (on the right side of the band).
        reach = _COARSE * step * np.sqrt(3) / 2
        coarse = distance_grid(tri, lower, upper, _COARSE * step, surface=surface)
        index = np.minimum(np.rint(np.stack(np.meshgrid(
            *(np.arange(n) / _COARSE for n in counts), indexing="ij"), axis=-1)).astype(np.int64),
            np.array(coarse.values.shape) - 1).reshape(-1, 3)
        estimate = np.abs(coarse.values[index[:, 0], index[:, 1], index[:, 2]])
        out = (estimate - reach > band[1]) | (estimate + reach < band[0])
        distance[out] = estimate[out]
    todo = np.flatnonzero(np.isnan(distance))
    if len(todo):
        surface = surface or SurfaceDistance(tri)
        for start in range(0, len(todo), _BLOCK):
            which = todo[start:start + _BLOCK]
            distance[which] = surface.distances(grid[which])
    sign = np.where(winding.reshape(-1) > 0.5, 1.0, -1.0)
    return DistanceGrid(lower, float(step), (sign * distance).reshape(tuple(counts)))
