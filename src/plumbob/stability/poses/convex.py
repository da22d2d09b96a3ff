"""Convex hulls for the pose code, chosen by measurement: manifold3d first, qhull as fallback.

Measured on this project's 2-core machine (``python bench/poses.py --hulls``), welded
points of float32 STL files:

=============================  =======  ==========  ===========
mesh                           points   manifold3d  scipy qhull
=============================  =======  ==========  ===========
box with cylinder, 10k faces     5 002       12 ms       381 ms
box with cylinder, 100k faces   50 008       12 ms    18 194 ms
capsule, 100k faces             49 730      151 ms       443 ms
counter.unitsmm.STL, 84k        41 837        2 ms        12 ms
=============================  =======  ==========  ===========

(qhull slows badly on the nearly co-circular points of a finely tessellated circle),
and manifold3d imports in 3–11 ms where ``scipy.spatial`` takes 300–850 ms, which
alone would be a large part of the start-up of ``plumbob poses``. So
:func:`hull_triangles` asks manifold3d, checks its answer (a closed surface of
non-degenerate triangles, every edge convex to rounding error, a volume) and falls
back to qhull only when that check fails.

manifold3d returns the hull's vertices as exact copies of input points
(``to_mesh64``), so the facet planes are planes through input points, as qhull's are.
Its quickhull leaves out points within its own epsilon (about 1e-7 of the size) of a
facet, an order of magnitude below the contact tolerance (1e-6 of the size) at which
faces are merged, so no pose can change.
"""

from __future__ import annotations

import numpy as np

from ...errors import GeometryError
from .vectors import cross, dot

__all__ = ["hull_triangles", "half_edge_twins"]


def half_edge_twins(tri: np.ndarray, n: int) -> np.ndarray | None:
    """For the half-edges ``tri[t, k] → tri[t, (k + 1) % 3]`` (numbered ``3 t + k``), the
    reversed half-edge of each; None when the triangles are not a closed surface (an
    edge without exactly one reversed partner)."""
    frm = tri.ravel()
    to = tri[:, [1, 2, 0]].ravel()
    key = frm * n + to
    order = np.argsort(key, kind="stable")
    skey = key[order]
    if len(skey) > 1 and np.any(skey[1:] == skey[:-1]):
        return None  # an edge used twice in one direction: not a 2-manifold
    pos = np.minimum(np.searchsorted(skey, to * n + frm), len(skey) - 1)
    twin = order[pos]
    if not np.array_equal(key[twin], to * n + frm):
        return None
    return twin


def _planes(P: np.ndarray, tri: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit normals, offsets (the plane n·x = offset) and the raw cross products."""
    cr = cross(P[tri[:, 1]] - P[tri[:, 0]], P[tri[:, 2]] - P[tri[:, 0]])
    norm = np.linalg.norm(cr, axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        tn = cr / norm[:, None]
    off = dot(P[tri].mean(axis=1), tn)
    return tn, off, cr


def _manifold_hull(X: np.ndarray, eps: float):
    """manifold3d's hull as (points, outward triangles, normals, offsets, twins), or None
    when its answer fails the checks (then qhull decides)."""
    import manifold3d

    mesh = manifold3d.Manifold.hull_points(np.ascontiguousarray(X, dtype=np.float64)).to_mesh64()
    P = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    tri = np.asarray(mesh.tri_verts, dtype=np.int64).reshape(-1, 3)
    if len(tri) < 4 or len(P) < 4:
        return None
    tn, off, cr = _planes(P, tri)
    if not np.all(np.isfinite(tn)):
        return None  # a degenerate triangle has no plane
    area = 0.5 * np.linalg.norm(cr, axis=1)
    if not float(np.dot(off, area)) / 3 > eps * area.sum():
        return None  # no volume: flat points make a two-sided polygon, not a solid
    twin = half_edge_twins(tri, len(P))
    if twin is None:
        return None
    # every edge convex: the far corner of the triangle across it lies under this one's plane
    across = twin // 3
    far = tri[across, (twin + 2) % 3]
    if np.max(dot(P[far], tn[np.repeat(np.arange(len(tri)), 3)]) - np.repeat(off, 3)) > eps:
        return None
    return P, tri, tn, off, twin


def _qhull(X: np.ndarray):
    """scipy's qhull: (points, outward triangles, normals, offsets, twins)."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(X)
    except QhullError as exc:
        raise GeometryError("the body is flat or degenerate: its points span no volume, so "
                            "it has no resting poses as a solid") from exc
    tri = hull.simplices.astype(np.int64).copy()
    eq = hull.equations
    scale = np.linalg.norm(eq[:, :3], axis=1)
    tn = eq[:, :3] / scale[:, None]
    off = -eq[:, 3] / scale
    flip = dot(cross(X[tri[:, 1]] - X[tri[:, 0]], X[tri[:, 2]] - X[tri[:, 0]]), tn) < 0
    tri[flip] = tri[flip][:, [0, 2, 1]]
    twin = half_edge_twins(tri, len(X))
    if twin is None:
        raise GeometryError("the convex hull is not a closed surface (qhull failure)")
    return X, tri, tn, off, twin


def hull_triangles(X: np.ndarray, eps: float
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The convex hull of ``X`` (n, 3) as triangles.

    Returns ``(P, tri, normals, offsets, twins)``: points (m, 3) that ``tri`` (F, 3)
    indexes, wound counter-clockwise seen from outside, each triangle's outward unit
    normal and plane offset (n·x = offset), and for each half-edge ``3 t + k`` (from
    ``tri[t, k]`` to ``tri[t, (k + 1) % 3]``) its reversed twin. ``eps`` (m) is the
    rounding error within which an edge may look concave.

    Raises GeometryError when the points span no volume.

    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> P, tri, normals, offsets, twins = hull_triangles(cube, 1e-12)
    >>> len(tri), sorted(set(np.round(offsets, 12).tolist()))
    (12, [0.0, 1.0])
    """
    found = _manifold_hull(X, eps)
    P, tri, tn, off, twin = found if found is not None else _qhull(X)
    # triangles in an order of their own geometry (by normal), not the hull library's: so
    # faces, and poses of equal probability, come out in the same order from either path
    key = np.round(tn, 9)
    order = np.lexsort((-key[:, 2], -key[:, 1], -key[:, 0]))
    old = (3 * order[:, None] + np.arange(3)).ravel()  # new half-edge i was old[i]
    new = np.empty_like(old)
    new[old] = np.arange(len(old))
    return P, tri[order], tn[order], off[order], new[twin[old]]
