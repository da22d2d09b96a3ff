"""The exact 3D convex hull as the pose landscape sees it, and its physical faces.

:func:`build_hull3` turns the hull's triangles (:mod:`.convex`: manifold3d's quickhull,
qhull as fallback) into a :class:`Hull3`: faces merged only
where *exactly* coplanar (to rounding error), with a directed edge list that says,
for every edge, which face lies on each side — the Gauss map's arcs, on which the
rolling and the basin tracing run. Grouping exact faces into the faces a reader
would call one is :mod:`.faces`' job, done only when poses are reported, so the
landscape itself stays consistent.

Everything is relative to the centre of mass, which sits at the origin.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...errors import GeometryError
from ...mesh.topology import connected_components
from .convex import hull_triangles
from .vectors import cross, dot, unit

__all__ = ["Hull3", "build_hull3", "shifted"]


@dataclass(frozen=True)
class Hull3:
    """The exact convex hull, relative to the centre of mass (at the origin).

    X: (n, 3) hull points (only those with out-edges are vertices).
    normals, heights, areas: per face (F, 3), (F,), (F,): outward unit normal, h(normal)
        and area. Faces are exactly coplanar groups of the hull's triangles.
    ea, eb, ef, eg: (E,) directed edges a → b with face ef on the left (counter-clockwise
        about its normal) and eg on the right. Sorted by ``ea``.
    start, degree: per point, its out-edges are ``start .. start + degree``.
    twin: (E,) the reversed edge. und: (E,) undirected edge id (shared by a pair).
    """

    X: np.ndarray
    normals: np.ndarray
    heights: np.ndarray
    areas: np.ndarray
    ea: np.ndarray
    eb: np.ndarray
    ef: np.ndarray
    eg: np.ndarray
    start: np.ndarray
    degree: np.ndarray
    twin: np.ndarray
    und: np.ndarray


def _weighted_normals(comp: np.ndarray, nfaces: int, normals: np.ndarray, area: np.ndarray
                      ) -> np.ndarray:
    """Area-weighted unit normals of groups."""
    out = np.zeros((nfaces, normals.shape[1]))
    np.add.at(out, comp, normals * area[:, None])
    bad = np.linalg.norm(out, axis=1) == 0
    if bad.any():  # zero-area groups: the plain normals
        np.add.at(out, comp, normals * (bad[comp])[:, None])
    return unit(out)


def _split_bent(comp: np.ndarray, nfaces: int, corners: np.ndarray, owner: np.ndarray,
                X: np.ndarray, normals: np.ndarray, tol: float
                ) -> tuple[np.ndarray, np.ndarray, int]:
    """Groups whose corners stray more than ``tol`` from the group's plane go back to their
    parts (a chain of nearly coplanar slivers can bend). ``corners`` are point indices,
    ``owner`` the part each belongs to; returns (comp, bent mask of old groups, nfaces)."""
    level = dot(X[corners], normals[comp[owner]])
    hi = np.full(nfaces, -np.inf)
    lo = np.full(nfaces, np.inf)
    np.maximum.at(hi, comp[owner], level)
    np.minimum.at(lo, comp[owner], level)
    bent = hi - lo > tol
    if bent.any():
        comp = np.where(bent[comp], nfaces + np.arange(len(comp)), comp)
        _, comp = np.unique(comp, return_inverse=True)
        nfaces = int(comp.max()) + 1
    return comp, bent, nfaces


def build_hull3(X: np.ndarray, eps: float) -> Hull3:
    """The hull of ``X`` (n, 3), m, relative to the centre of mass, with the hull's triangles
    merged into faces where coplanar within ``eps`` (m; meant as round-off, so that the
    faces are exact).

    Raises GeometryError when the points span no volume or the hull is not a
    closed surface of simple polygons.

    >>> cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    >>> h = build_hull3(cube, 1e-12)
    >>> len(h.normals), len(h.ea), h.heights.tolist()
    (6, 24, [1.0, 1.0, 1.0, 1.0, 1.0, 1.0])
    """
    X, tri, tn, toff, twin = hull_triangles(X, eps)  # manifold3d, or qhull as fallback
    cr = cross(X[tri[:, 1]] - X[tri[:, 0]], X[tri[:, 2]] - X[tri[:, 0]])
    area = 0.5 * np.linalg.norm(cr, axis=1)
    m = len(tri)

    # --- half-edges: a → b of triangle t (numbered 3 t + k); twin: the reversed one
    n = len(X)
    frm = tri.ravel()
    to = tri[:, [1, 2, 0]].ravel()
    across = twin // 3  # the triangle beyond each half-edge
    tri_of = np.repeat(np.arange(m), 3)

    # --- exactly coplanar neighbours (the hull's triangulated facets) make one face
    i, j = tri_of, across
    pair = i < j
    i, j = i[pair], j[pair]
    dij = np.abs(np.einsum("kvc,kc->kv", X[tri[j]], tn[i]) - toff[i][:, None]).max(axis=1)
    dji = np.abs(np.einsum("kvc,kc->kv", X[tri[i]], tn[j]) - toff[j][:, None]).max(axis=1)
    same = (dij <= eps) & (dji <= eps) & (dot(tn[i], tn[j]) > 0)
    if not same.any():  # every triangle a face of its own: the half-edges are the edges
        order = np.argsort(frm, kind="stable")
        inverse = np.empty_like(order)
        inverse[order] = np.arange(len(order))
        ea, eb = frm[order], to[order]
        ef, eg = tri_of[order], tri_of[twin[order]]
        etwin = inverse[twin[order]]
        degree = np.bincount(ea, minlength=n)
        start = np.cumsum(degree) - degree
        und = np.minimum(np.arange(len(ea)), etwin)
        heights = np.max(dot(X[tri], tn[:, None, :]), axis=1)
        return Hull3(X, tn, heights, area, ea, eb, ef, eg, start, degree, etwin, und)
    comp = connected_components(m, i[same], j[same])
    nfaces = int(comp.max()) + 1
    normals = _weighted_normals(comp, nfaces, tn, area)
    comp, bent, nfaces = _split_bent(comp, nfaces, tri.ravel(), tri_of, X, normals, eps)
    if bent.any():
        normals = _weighted_normals(comp, nfaces, tn, area)
    areas = np.bincount(comp, weights=area, minlength=nfaces)

    # --- face boundaries: chains of half-edges between different faces
    face = comp[tri_of]
    bnd = face != face[twin]
    bf, bt, bF, bG = frm[bnd], to[bnd], face[bnd], face[twin][bnd]
    real = np.bincount(bf, minlength=n) >= 3
    key2 = bF * n + bf
    order2 = np.argsort(key2)
    pos2 = np.minimum(np.searchsorted(key2[order2], bF * n + bt), len(order2) - 1)
    nxt = order2[pos2]
    if not np.array_equal(key2[nxt], bF * n + bt):
        raise GeometryError("a face of the hull is not a simple polygon (degenerate hull)")
    term = real[bt]
    ptr = np.where(term, np.arange(len(bt)), nxt)
    for _ in range(64):
        if term[ptr].all():
            break
        ptr = np.where(term[ptr], ptr, ptr[ptr])
    else:
        raise GeometryError("a face of the hull has no corners (degenerate hull)")
    sel = real[bf]
    ea, eb, ef, eg = bf[sel], bt[ptr[sel]], bF[sel], bG[sel]
    order3 = np.lexsort((eb, ea))
    ea, eb, ef, eg = ea[order3], eb[order3], ef[order3], eg[order3]
    degree = np.bincount(ea, minlength=n)
    start = np.cumsum(degree) - degree
    key3 = ea * n + eb
    pos3 = np.minimum(np.searchsorted(key3, eb * n + ea), len(key3) - 1)
    if not np.array_equal(key3[pos3], eb * n + ea):
        raise GeometryError("the hull's edges do not pair up (degenerate hull)")
    und = np.minimum(np.arange(len(ea)), pos3)
    heights = np.full(nfaces, -np.inf)
    np.maximum.at(heights, ef, dot(X[ea], normals[ef]))
    return Hull3(X, normals, heights, areas, ea, eb, ef, eg, start, degree, pos3, und)


def shifted(h: Hull3, delta: np.ndarray) -> Hull3:
    """The same hull seen from a centre moved by ``delta``: only heights change."""
    return replace(h, X=h.X - delta, heights=h.heights - h.normals @ delta)
