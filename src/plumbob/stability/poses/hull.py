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

from typing import NamedTuple

import numpy as np

from ...arrays import connected_components, dot, row_max, row_min, stable_order, unit
from ...errors import GeometryError
from .convex import HullMesh, corner_levels, hull_mesh

__all__ = ["Hull3", "build_hull3", "shifted"]


class Hull3(NamedTuple):
    """The exact convex hull, relative to the centre of mass (at the origin).

    X: (n, 3) hull points (only those with out-edges are vertices).
    normals, heights, areas: per face (F, 3), (F,), (F,): outward unit normal, h(normal)
        and area. Faces are exactly coplanar groups of the hull's triangles.
    ea, eb, ef, eg: (E,) directed edges a → b with face ef on the left (counter-clockwise
        about its normal) and eg on the right. Sorted by (ea, eb).
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


def _face_firsts(comp: np.ndarray, nfaces: int, merged: np.ndarray) -> np.ndarray:
    """(nfaces,) each face's least triangle, for the face labels ``comp`` (F,) whose
    faces of more than one triangle hold the triangles ``merged`` (ascending): a face
    of one triangle is its own, and only the merged faces' are sought."""
    first = np.empty(nfaces, dtype=np.int64)
    first[comp] = np.arange(len(comp))
    if len(merged):
        g = comp[merged]
        first[g] = len(comp)
        np.minimum.at(first, g, merged)
    return first


def _weighted_normals(comp: np.ndarray, nfaces: int, normals: np.ndarray, area: np.ndarray,
                      merged: np.ndarray | None = None, firsts: np.ndarray | None = None
                      ) -> np.ndarray:
    """Area-weighted unit normals of groups (``np.bincount`` adds in the same order as
    ``np.add.at``, so the sums are the same to the bit). A group of one is its own
    weighted normal plus 0.0 (the sum a bincount starts from: −0.0 becomes 0.0),
    weighted only at its triangle (``firsts``: :func:`_face_firsts`); only the larger
    groups' triangles (``merged``, ascending) are summed."""
    if merged is None:
        merged = np.flatnonzero(np.bincount(comp, minlength=nfaces)[comp] > 1)
    if firsts is None:
        firsts = _face_firsts(comp, nfaces, merged)
    out = np.take(normals, firsts, axis=0)
    out *= np.take(area, firsts)[:, None]
    out += 0.0
    if len(merged):
        g = comp[merged]
        weighted = np.take(normals, merged, axis=0) * np.take(area, merged)[:, None]
        for k in range(normals.shape[1]):
            out[g, k] = np.bincount(g, weights=weighted[:, k], minlength=nfaces)[g]
    norm = np.sqrt(dot(out, out))
    bad = norm == 0
    if bad.any():  # zero-area groups: the plain normals
        w = bad[comp]
        out += np.stack([np.bincount(comp, weights=normals[:, k] * w, minlength=nfaces)
                         for k in range(normals.shape[1])], axis=1)
        return unit(out)
    out /= norm[:, None]  # unit(out), its norm measured once
    return out


def _split_bent(comp: np.ndarray, nfaces: int, level: np.ndarray, tol: float,
                merged: np.ndarray | None = None, firsts: np.ndarray | None = None,
                top: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, int]:
    """Groups whose corners stray more than ``tol`` from the group's plane go back to their
    parts (a chain of nearly coplanar slivers can bend). ``level`` (F, 3): each part's
    corners' heights along its group's normal; ``merged``, ``firsts``: as for
    :func:`_weighted_normals`; ``top``: ``row_max(level)``, when the caller has it.
    Returns (comp, bent mask of old groups, nfaces)."""
    if merged is None:
        merged = np.flatnonzero(np.bincount(comp, minlength=nfaces)[comp] > 1)
    if firsts is None:
        firsts = _face_firsts(comp, nfaces, merged)
    # right for a face of one triangle; the others' over their parts below
    hi = np.take(row_max(level) if top is None else top, firsts)
    lo = row_min(np.take(level, firsts, axis=0))
    if len(merged):
        g = comp[merged]
        hi[g], lo[g] = -np.inf, np.inf
        np.maximum.at(hi, g, row_max(level[merged]))
        np.minimum.at(lo, g, row_min(level[merged]))
    bent = hi - lo > tol
    if bent.any():
        comp = np.where(bent[comp], nfaces + np.arange(len(comp)), comp)
        _, comp = np.unique(comp, return_inverse=True)
        nfaces = int(comp.max()) + 1
    return comp, bent, nfaces


def _coplanar_pairs(hm: HullMesh, eps: float) -> tuple[np.ndarray, np.ndarray]:
    """Neighbouring triangles (i < j) whose corners all lie within ``eps`` of each other's
    planes and that face the same way, and each sliver (no wider than ``eps``) with the
    triangle across its longest edge. A triangle's own corners lie on its plane to
    rounding error, so of the neighbour only the far corner can stray (``hm.beyond``)."""
    # how far the triangle across each half-edge strays from this one's plane: the far
    # corner (``beyond``) or an own corner off the own plane; few are within eps (the
    # hull's split flat facets), and the own corners are measured for those alone
    cand = np.flatnonzero(np.abs(hm.beyond) <= eps)
    twin = hm.twins[cand]
    both = np.concatenate((cand, twin))
    t, k = both // 3, both % 3
    dev = np.abs(corner_levels(hm.points, np.take(hm.tri, t, axis=0),
                               np.take(hm.normals, t, axis=0)) - hm.offsets[t][:, None])
    rows = np.arange(len(both))
    stray = np.maximum(np.abs(hm.beyond[both]),
                       np.maximum(dev[rows, k], dev[rows, (k + 1) % 3]))
    i, j = cand // 3, twin // 3
    keep = (i < j) & (stray[:len(cand)] <= eps) & (stray[len(cand):] <= eps)
    i, j = i[keep], j[keep]
    same = dot(hm.normals[i], hm.normals[j]) > 0
    i, j = i[same], j[same]
    # A sliver whose corners lie on one line (within eps: a hull of points on a grid
    # can hold one) has no plane of its own: it joins the triangle across its longest
    # edge, whose plane holds that line. No side is longer than 2 max|P| (4 max|P| with
    # room for round-off), so only triangles of twice their area under eps · 4 max|P|
    # can be slivers: their sides alone are measured.
    reach = 4.0 * float(np.sqrt(dot(hm.points, hm.points)).max())
    small = np.flatnonzero(2 * hm.area <= eps * reach)
    corners = hm.points[hm.tri[small]]
    sides = corners[:, [1, 2, 0]] - corners
    lengths = np.sqrt(np.einsum("fkc,fkc->fk", sides, sides))
    longest = np.argmax(lengths, axis=1)
    thin = 2 * hm.area[small] <= eps * lengths[np.arange(len(small)), longest]
    sliver, longest = small[thin], longest[thin]
    if len(sliver):
        other = hm.twins[3 * sliver + longest] // 3
        i = np.concatenate((i, np.minimum(sliver, other)))
        j = np.concatenate((j, np.maximum(sliver, other)))
    return i, j


def _single(hm: HullMesh, area: np.ndarray) -> Hull3:
    """Every triangle a face of its own: the half-edges are the edges."""
    tri, order, etwin = hm.tri, hm.ends, hm.end_twins  # by (from, to); the reverse's place
    n = len(hm.points)
    ea, eb = hm.end_points
    ef = order // 3
    eg = np.take(ef, etwin)
    degree = np.bincount(ea, minlength=n)
    start = np.cumsum(degree) - degree
    und = np.minimum(np.arange(len(ea)), etwin)
    heights = row_max(corner_levels(hm.points, tri, hm.normals))
    return Hull3(hm.points, hm.normals, heights, area, ea, eb, ef, eg, start, degree, etwin,
                 und)


def _chain_next(face: np.ndarray, frm: np.ndarray, to: np.ndarray, sub: np.ndarray, n: int
                ) -> np.ndarray:
    """For the boundary half-edges ``sub`` of merged faces (ascending; ``face``, ``frm``,
    ``to``: theirs), the boundary half-edge of the same face that starts where each ends,
    found by sorting them by (face, start)."""
    key = face * n + frm
    order = stable_order(key)
    want = face * n + to
    pos = np.minimum(np.searchsorted(key[order], want), max(len(sub) - 1, 0))
    if len(sub) and not np.array_equal(key[order[pos]], want):
        raise GeometryError("a face of the hull is not a simple polygon (degenerate hull)")
    return sub[order[pos]] if len(sub) else sub


def _chain_ends(tri: np.ndarray, bnd: np.ndarray, real: np.ndarray, sub: np.ndarray,
                nxt_sub: np.ndarray) -> np.ndarray | None:
    """Per half-edge, the last half-edge of the chain it starts: the next boundary
    half-edge of its face (``sub``'s are ``nxt_sub``, the others' the next in their
    triangle) followed while it ends at a point that is no corner (not ``real``); None
    when every point is a corner (then every chain is one half-edge)."""
    if real.all():
        return None
    m3 = 3 * len(tri)
    nxt = np.arange(m3).reshape(-1, 3)[:, [1, 2, 0]].ravel()
    nxt[sub] = nxt_sub
    term = ~bnd | real[tri[:, [1, 2, 0]].ravel()]
    ptr = np.where(term, np.arange(m3), nxt)
    for _ in range(64):
        if term[ptr].all():
            return ptr
        ptr = np.where(term[ptr], ptr, ptr[ptr])
    raise GeometryError("a face of the hull has no corners (degenerate hull)")


def _edge_twins(ea: np.ndarray, eb: np.ndarray, first: np.ndarray, last: np.ndarray,
                twin: np.ndarray, n: int) -> np.ndarray:
    """The reversed edge of each edge ``ea → eb`` (sorted by (a, b)), whose chain of
    half-edges runs from ``first`` to ``last``: it starts with the twin of ``last``. Where
    that does not settle it (a degenerate hull with an edge twice, or a chain that does
    not retrace), the first edge ``eb → ea`` in the sorted keys."""
    edge_of = np.full(len(twin), -1, dtype=np.int64)
    edge_of[first] = np.arange(len(first))
    etwin = edge_of[twin[last]]
    if (np.all(etwin >= 0) and np.array_equal(ea[etwin], eb) and np.array_equal(eb[etwin], ea)
            and not np.any((ea[1:] == ea[:-1]) & (eb[1:] == eb[:-1]))):
        return etwin
    key = ea * n + eb
    want = eb * n + ea
    pos = np.minimum(np.searchsorted(key, want), len(key) - 1)
    if not np.array_equal(key[pos], want):
        raise GeometryError("the hull's edges do not pair up (degenerate hull)")
    return pos


def build_hull3(X: np.ndarray, eps: float, surface: np.ndarray | None = None) -> Hull3:
    """The hull of ``X`` (n, 3), m, relative to the centre of mass, with the hull's triangles
    merged into faces where coplanar within ``eps`` (m; meant as round-off, so that the
    faces are exact). ``surface``: the body's own closed mesh through ``X`` (triangles
    indexing it), taken as the hull when proved convex (:func:`~.convex.hull_triangles`).

    Raises GeometryError when the points span no volume or the hull is not a
    closed surface of simple polygons.

    >>> cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    >>> h = build_hull3(cube, 1e-12)
    >>> len(h.normals), len(h.ea), h.heights.tolist()
    (6, 24, [1.0, 1.0, 1.0, 1.0, 1.0, 1.0])
    """
    hm = hull_mesh(X, eps, surface)  # the mesh itself if convex, manifold3d, or qhull
    X, tri, tn, twin = hm.points, hm.tri, hm.normals, hm.twins
    area = hm.area
    m, n = len(tri), len(X)

    # --- exactly coplanar neighbours (the hull's triangulated facets) make one face
    i, j = _coplanar_pairs(hm, eps)
    if len(i) == 0:
        return _single(hm, area)
    comp = connected_components(m, i, j)
    nfaces = int(comp.max()) + 1
    # the triangles of faces of more than one (few on a smooth hull: each pass over
    # every face is made once, the merged faces' sums over their triangles alone)
    in_merged = np.bincount(comp, minlength=nfaces)[comp] > 1
    merged = np.flatnonzero(in_merged)
    firsts = _face_firsts(comp, nfaces, merged)
    normals = _weighted_normals(comp, nfaces, tn, area, merged, firsts)
    level = corner_levels(X, tri, normals, comp)  # along the face's normal
    top = row_max(level)
    comp, bent, nfaces = _split_bent(comp, nfaces, level, eps, merged, firsts, top)
    if bent.any():
        in_merged = np.bincount(comp, minlength=nfaces)[comp] > 1
        merged = np.flatnonzero(in_merged)
        firsts = _face_firsts(comp, nfaces, merged)
        normals = _weighted_normals(comp, nfaces, tn, area, merged, firsts)
        level = corner_levels(X, tri, normals, comp)
        top = row_max(level)
    areas = np.bincount(comp, weights=area, minlength=nfaces)

    # --- face boundaries: chains of half-edges between different faces
    frm = tri.ravel()
    sub = (3 * merged[:, None] + np.arange(3)).ravel()  # their half-edges, ascending
    # only a merged face's half-edges can lie inside it (a face of one triangle has its
    # own number, its twins' triangles others): the rest are boundaries, unmeasured
    face_sub = comp[sub // 3]
    inside = face_sub == comp[twin[sub] // 3]
    bnd = np.ones(len(frm), dtype=bool)
    bnd[sub[inside]] = False
    # a corner: a point with three boundary half-edges out of it
    real = np.bincount(frm, minlength=n) - np.bincount(frm[sub[inside]], minlength=n) >= 3
    sub, face_sub = sub[~inside], face_sub[~inside]
    nxt_sub = _chain_next(face_sub, frm[sub], frm[sub - sub % 3 + (sub + 1) % 3], sub, n)
    ptr = _chain_ends(tri, bnd, real, sub, nxt_sub)
    # an edge per chain: from its first half-edge (at a corner) to its last one's end
    at_corner = bnd[hm.ends]  # corners, in the order of (from, to)
    if not real.all():
        at_corner &= real[hm.end_points[0]]
    placed = np.flatnonzero(at_corner)
    first = hm.ends[placed]
    last = first if ptr is None else ptr[first]
    etwin = None
    if ptr is None or np.array_equal(first, last):  # every edge one half-edge
        ea, eb = np.compress(at_corner, hm.end_points, axis=1)
        back = hm.end_twins[placed]  # its twin's is the reverse
        if np.all(at_corner[back]):
            etwin = (np.cumsum(at_corner) - 1)[back]
    else:
        to = tri[:, [1, 2, 0]].ravel()
        ea, eb = frm[first], to[last]
        if len(ea) > 1 and not np.all((ea[1:] > ea[:-1])
                                      | ((ea[1:] == ea[:-1]) & (eb[1:] > eb[:-1]))):
            # a chain past a straight corner ends elsewhere: sort by (a, b) again
            first = np.flatnonzero(bnd & real[frm])
            last = ptr[first]
            order = stable_order(frm[first] * n + to[last])
            first, last = first[order], last[order]
            ea, eb = frm[first], to[last]
    ef = comp[first // 3]
    # the face across: the twin edge's own (or, past a chain, the twin half-edge's)
    eg = ef[etwin] if etwin is not None else comp[twin[first] // 3]
    degree = np.bincount(ea, minlength=n)
    start = np.cumsum(degree) - degree
    if etwin is None:
        etwin = _edge_twins(ea, eb, first, last, twin, n)
    und = np.minimum(np.arange(len(ea)), etwin)
    # a face's height: its highest corner, along its normal (``top``)
    # (only a merged face's triangle, or one at a point that is no corner, has a
    # half-edge that starts no edge)
    odd = merged if ptr is None else np.flatnonzero(in_merged | ~real[tri].all(axis=1))
    corner = bnd[(3 * odd[:, None] + np.arange(3))] & real[tri[odd]]
    top[odd] = row_max(np.where(corner, level[odd], -np.inf))
    heights = np.full(nfaces, -np.inf)
    heights[comp] = top  # a face alone; merged faces' highest below
    heights[comp[merged]] = -np.inf
    np.maximum.at(heights, comp[merged], top[merged])
    return Hull3(X, normals, heights, areas, ea, eb, ef, eg, start, degree, etwin, und)


def shifted(h: Hull3, delta: np.ndarray) -> Hull3:
    """The same hull seen from a centre moved by ``delta``: only heights change."""
    return h._replace(X=h.X - delta, heights=h.heights - h.normals @ delta)
