"""Whether a hull library's convex hull holds every point it was built from.

manifold3d's quickhull can return a closed polytope, every edge convex, that leaves
input points far outside (points on a half-unit grid: 0.87 above a triangle's plane, a
volume of 51.25 for qhull's 53.5625) when points are exactly coplanar or collinear.
:func:`holds` decides whether the hull holds every point, within ``tol``, where it can
at a small cost, and says when it cannot.

The proof, for a closed surface of triangles through the hull's vertices ``P`` (input
points), every edge convex (the caller checked it), wound outward:

1. *An interior point* ``o``: the origin the points are given relative to (the centre
   of mass), or the vertices' centroid, at least :data:`INTERIOR` of the size inside
   every triangle's plane. Each triangle then projects from ``o`` onto the unit sphere
   keeping its orientation (its corners' determinant is twice its area times its
   offset).
2. *Degree 1*: one direction lies in the cone from ``o`` of exactly one triangle
   (:func:`_degree`). An orientation-keeping map of the sphere onto itself has as many
   preimages at every regular value as its degree, so every ray from ``o`` crosses the
   surface once: it bounds a body ``K`` star-shaped about ``o``, locally convex at every
   edge and so at every vertex (a simple fan, turning one way at each edge): convex
   (Tietze–Nakajima, as in :func:`~.convex.own_hull`), the hull of its vertices.
3. *Every input point in K*. A point of a convex body lies under every face's plane,
   and ``x`` lies in ``K`` when it lies under the plane of the triangle whose cone
   holds it (the ray from ``o`` leaves ``K`` there). A point that is a copy of a vertex
   lies in ``K`` (:func:`_vertex_copies`); so does one in the ball about ``o`` under
   every plane. The others, when few enough (points × planes), are compared with every
   plane; else, when at most :data:`WALKERS`, each is located (:func:`_walk`: from a
   triangle at the vertex nearest it in direction in its cell of a cube map of
   directions, across each edge whose plane through ``o`` the point lies beyond —
   across an edge between two planes this raises the gauge ``x · n / offset``, as the
   two triangles' ``n / offset`` differ by a multiple of that plane's normal, so only
   flat edges let a walk come back) and compared with its triangle's plane. Then
   ``K`` holds every input point and is their hull.

Round-off: a *sliver* (twice its area under :data:`SLIVER` of its longest side squared,
its corners on one line to round-off) has no reliable plane; it stands in for the
triangle across its longest edge, whose plane holds that line, so a point in its thin
cone is compared within the sliver's width. Cone tests allow round-off
(:data:`CONE_ROUND_OFF`). A point passes when it lies at most ``tol`` above a plane, so
none lies further than about ``tol`` times (the largest radius over the least offset)
outside ``K``.

:func:`holds` answers True (proved), False (a point outside, or the surface not a convex
body about ``o``: take another hull) or None (too many points left to compare, or walks
that did not end in :data:`WALK_STEPS` steps: not decided). Where it is run and what
None means there: :func:`~.convex.hull_mesh` and ``docs/stability.md`` (*Hull check*).
"""

from __future__ import annotations

import numpy as np

from ...arrays import cross, dot, expand, group_first, unit
from ...tolerances import size_of

__all__ = ["holds", "degenerate", "EXHAUSTIVE", "WALKERS"]

#: points × hull triangles up to which every point is compared with every plane (at
#: most 4·10⁶ products, 4–15 ms), so the answer is never None
EXHAUSTIVE = 1 << 22
#: the most points :func:`holds` locates by walks (:func:`_walk`)
WALKERS = 1 << 13
#: vertex-point pairs up to which :func:`_starts` compares every point with every vertex
#: in its cube-map cell
START_PAIRS = 1 << 20
#: steps of a walk before :func:`holds` gives up
WALK_STEPS = 256
#: more points than this still walking, and nine in ten of those 32 steps before: the
#: walks are given up (they circle over flat facets, a cylinder's cap)
STALLED = 64
#: round-off allowed in a walk's cone test, relative to the squared largest radius times
#: the point's radius (a triple product's rounding error is a few units in the last place)
CONE_ROUND_OFF = 1e-13
#: an interior point must lie at least this fraction of the hull's size inside every plane
INTERIOR = 1e-6
#: a triangle whose area is under this fraction of its longest side squared (halved) is a
#: sliver; its plane (normal error ~1e-16 / SLIVER) is not used
SLIVER = 1e-8
#: a direction in no simple ratio to the axes, for the degree count
_GENERIC = np.array([0.2679491924311227, 0.4142135623730950, 0.8696954551710463])


def _within(X: np.ndarray, tn: np.ndarray, off: np.ndarray, tol: float) -> bool:
    """Whether every point of ``X`` lies at most ``tol`` above every plane, in blocks of
    rows of about 2²⁰ products."""
    step = max(1, (1 << 20) // max(1, len(tn)))
    for s in range(0, len(X), step):
        if not float((X[s:s + step] @ tn.T - off).max(initial=-np.inf)) <= tol:
            return False
    return True


def _degree(Pc: np.ndarray, tri: np.ndarray) -> int:
    """How many triangles ``tri`` through ``Pc`` (relative to the interior point) hold the
    direction :data:`_GENERIC` in their cones, or -1 when it lies on a cone's boundary.

    ``u`` lies in the cone of (a, b, c) when det(a, b, u), det(b, c, u) and det(c, a, u)
    are all positive (Cramer's rule, det(a, b, c) > 0); det(a, b, u) is the 2D cross
    product of a and b projected on the plane across ``u``, in a right-handed frame."""
    u = _GENERIC / np.linalg.norm(_GENERIC)
    e1 = np.cross(u, [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(u, e1)
    x, y = Pc @ e1, Pc @ e2
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    xa, xb, xc, ya, yb, yc = x[a], x[b], x[c], y[a], y[b], y[c]
    lo = np.minimum(np.minimum(xa * yb - ya * xb, xb * yc - yb * xc), xc * ya - yc * xa)
    if np.any(lo == 0):
        return -1
    return int(np.count_nonzero(lo > 0))


def _vertex_copies(X: np.ndarray, P: np.ndarray) -> np.ndarray:
    """(n,) which rows of ``X`` are copies (equal coordinates) of rows of ``P``: hash
    tables of ``P``'s coordinate bits give each row of ``X`` candidates, compared exactly
    (a row of ``P`` that lost its slot to another goes to the next table, and only the
    rows of ``X`` that met another row in such a slot look again: a copy of the loser
    hashes to that slot and differs from its winner)."""
    def hashes(A: np.ndarray, salt: int) -> np.ndarray:
        b = np.ascontiguousarray(A, dtype=np.float64).view(np.uint64)
        h = b[:, 0] * np.uint64(0x9E3779B97F4A7C15 ^ salt)
        h ^= b[:, 1] * np.uint64(0xC2B2AE3D27D4EB4F)
        h ^= b[:, 2]
        h ^= h >> np.uint64(29)
        h *= np.uint64(0xBF58476D1CE4E5B9)
        h ^= h >> np.uint64(32)
        return h

    found = np.zeros(len(X), dtype=bool)
    left = np.arange(len(P))
    look = np.arange(len(X))
    for salt in range(4):
        if not (len(left) and len(look)):
            break
        bits = max(4, int(len(left)).bit_length() + 2)
        mask = np.uint64((1 << bits) - 1)
        slot = np.full(1 << bits, -1, dtype=np.int64)
        where = (hashes(np.take(P, left, axis=0) if salt else P, salt) & mask).astype(np.intp)
        slot[where] = left
        Z = X[look] if salt else X  # the first table: every row, in place
        cell = (hashes(Z, salt) & mask).astype(np.intp)
        j = slot[cell]
        Q = np.take(P, j, axis=0)  # j = -1 (no row of P there) is masked below
        same = (j >= 0) & (Q[:, 0] == Z[:, 0]) & (Q[:, 1] == Z[:, 1]) & (Q[:, 2] == Z[:, 2])
        found[look[same]] = True
        lost = slot[where] != left
        shared = np.zeros(1 << bits, dtype=bool)
        shared[where[lost]] = True  # slots a row of P lost: its copies met the winner
        again = ~same & (j >= 0) & shared[cell]
        left, look = left[lost], look[again]  # the next table
    return found


def _faces(A: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """For directions ``A`` (k, 3): the cube face of each (0..5: axis · 2 + (positive)),
    the face its major component picks, and its two gnomonic coordinates there (the
    next axes' components over the major one's size, in [-1, 1])."""
    x, y, z = A[:, 0], A[:, 1], A[:, 2]
    ax_, ay, az = np.abs(x), np.abs(y), np.abs(z)
    on_x = (ax_ >= ay) & (ax_ >= az)
    on_y = ~on_x & (ay >= az)
    on_z = ~(on_x | on_y)
    axis = on_y.astype(np.int64) + 2 * on_z
    major = np.where(on_x, ax_, np.where(on_y, ay, az))
    face = 2 * axis + (np.where(on_x, x, np.where(on_y, y, z)) > 0)
    u = np.where(on_x, y, np.where(on_y, z, x)) / major  # the axis after the major one
    v = np.where(on_x, z, np.where(on_y, x, y)) / major  # and the one after that
    return face, u, v


def _cell(u: np.ndarray, G: int) -> np.ndarray:
    """The cell (0..G-1) of gnomonic coordinates ``u``."""
    return np.clip(np.floor((u + 1) * (0.5 * G)), 0, G - 1).astype(np.int64)


def _starts(Pc: np.ndarray, tri: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """(k,) for each point of ``Y`` (relative to the interior point) a triangle to walk
    from (:func:`_walk`): one at the vertex of ``Pc`` nearest it in direction among the
    vertices in its cell of a cube map of directions (about 12 vertices a cell on
    average, but hundreds where a tapered tip packs many vertices into a small solid
    angle: a vertex picked at random there is a hundred steps away); at any vertex of
    the cell when the cells of ``Y`` hold more than :data:`START_PAIRS` pairs, triangle
    0 in a cell without vertices. Any start gives the same answer: only the walk's
    length depends on it."""
    G = int(np.clip(np.sqrt(len(Pc) / 12.0), 1, 1024))
    face, u, v = _faces(Pc)
    cell_p = (face * G + _cell(u, G)) * G + _cell(v, G)
    face, u, v = _faces(Y)
    cell_y = (face * G + _cell(u, G)) * G + _cell(v, G)
    incident = np.full(len(Pc), -1, dtype=np.int64)
    incident[tri.ravel()] = np.repeat(np.arange(len(tri)), 3)
    wanted = np.zeros(6 * G * G, dtype=bool)
    wanted[cell_y] = True
    cand = np.flatnonzero(wanted[cell_p] & (incident >= 0))  # vertices in Y's cells
    cand = cand[np.argsort(cell_p[cand], kind="stable")]
    ranked = cell_p[cand]
    first = np.searchsorted(ranked, cell_y)
    count = np.searchsorted(ranked, cell_y, side="right") - first
    t = np.zeros(len(Y), dtype=np.int64)  # a cell without a vertex: walk from anywhere
    if int(count.sum()) > START_PAIRS:  # too many to compare: any vertex of the cell
        some = count > 0
        t[some] = incident[cand[first[some]]]
        return t
    row, item = expand(count, first)
    closeness = dot(np.take(Y, row, axis=0), np.take(unit(Pc[cand]), item, axis=0))
    best = group_first(row, -closeness, len(Y))  # |y| cos(angle): the largest is nearest
    some = best >= 0
    t[some] = incident[cand[item[best[some]]]]
    return t


def _walk(Pc: np.ndarray, tri: np.ndarray, stand: np.ndarray, tn: np.ndarray,
          off: np.ndarray, twins: np.ndarray, Y: np.ndarray, tol: float) -> bool | None:
    """Whether every point of ``Y`` (relative to the interior point) lies at most ``tol``
    above the plane of (the stand-in of) the triangle whose cone holds it, found by
    walking from a triangle at the vertex nearest it in direction among those in its
    cube-map cell (:func:`_starts`) across each edge the point lies beyond (the most);
    None when some walk has not ended after :data:`WALK_STEPS` steps, or the walks stall
    (:data:`STALLED`): only flat edges let a walk come back, but walks around a vertex
    of many triangles are long."""
    t = _starts(Pc, tri, Y)
    allow = CONE_ROUND_OFF * float(dot(Pc, Pc).max()) * np.sqrt(dot(Y, Y))
    act = np.arange(len(Y))
    before = len(act)
    for step in range(WALK_STEPS):
        if step % 32 == 31:  # stalled: many points walk in circles over flat facets
            if len(act) > STALLED and len(act) > 0.9 * before:
                return None
            before = len(act)
        C = Pc[tri[t]]
        y = Y[act]
        s = np.stack([dot(cross(C[:, k], C[:, (k + 1) % 3]), y) for k in range(3)], axis=1)
        k = np.argmin(s, axis=1)
        done = np.take_along_axis(s, k[:, None], axis=1)[:, 0] >= -allow[act]
        if done.any():
            g = stand[t[done]]
            if not float((dot(y[done], tn[g]) - off[g]).max()) <= tol:
                return False
            act, t, k = act[~done], t[~done], k[~done]
            if not len(act):
                return True
        t = twins[3 * t + k] // 3
    return None


def degenerate(area: np.ndarray, beyond: np.ndarray, P: np.ndarray, eps: float) -> bool:
    """Whether a hull through ``P`` has exactly coplanar neighbouring triangles (the far
    corner across some edge within ``eps`` of the plane: ``beyond``, per half-edge) or a
    triangle no wider than ``eps`` (twice its ``area`` under ``eps`` times a bound on its
    longest side, 4 max|P|): the marks of points exactly coplanar or collinear, the
    inputs on which quickhull has been seen to leave points out."""
    reach = 4.0 * float(np.sqrt(dot(P, P).max()))
    return bool(np.any(np.abs(beyond) <= eps) or np.any(2 * area <= eps * reach))


def holds(X: np.ndarray, P: np.ndarray, tri: np.ndarray, tn: np.ndarray, off: np.ndarray,
          twins: np.ndarray, area: np.ndarray, tol: float) -> bool | None:
    """Whether the closed surface ``tri`` (F, 3) through ``P`` (V, 3), every edge convex,
    wound outward, with unit normals ``tn``, offsets ``off`` (n·x = offset), half-edge
    twins ``twins`` (3F,) and areas ``area``, bounds a convex body that holds every
    point of ``X`` (n, 3) to within ``tol`` (m): then it is the hull of ``X`` when ``P``
    are points of ``X``. False when it does not (take another hull); None when that was
    not decided (more than :data:`EXHAUSTIVE` products and more than :data:`WALKERS`
    points left, or walks that did not end); never None for n · F ≤ EXHAUSTIVE.

    >>> cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    >>> from plumbob.stability.poses.convex import hull_mesh
    >>> hm = hull_mesh(cube, 1e-12)
    >>> args = hm.points, hm.tri, hm.normals, hm.offsets, hm.twins, hm.area, 1e-9
    >>> holds(np.vstack((cube, [[0.5, 0.5, 1.0]])), *args)
    True
    >>> holds(np.vstack((cube, [[0.5, 0.5, 1.1]])), *args)
    False
    """
    # no side is longer than 2 max|P|: only triangles of twice their area under
    # SLIVER (2 max|P|)² can be slivers, and only their sides are measured
    reach = 2.0 * float(np.sqrt(dot(P, P).max()))
    small = np.flatnonzero(2 * area <= SLIVER * reach * reach)
    corners = P[tri[small]]
    sides = dot(corners[:, [1, 2, 0]] - corners, corners[:, [1, 2, 0]] - corners)
    k = np.argmax(sides, axis=1)
    thin = 2 * area[small] <= SLIVER * sides[np.arange(len(small)), k]
    stand = np.arange(len(tri))
    keep = stand
    if thin.any():  # the triangle across its longest edge stands in for a sliver
        s = small[thin]
        stand[s] = twins[3 * s + k[thin]] // 3
        used = np.zeros(len(tri), dtype=bool)
        used[stand] = True
        keep = np.flatnonzero(used)
    margin = INTERIOR * size_of(P)
    o = np.zeros(3)
    if not float(off[keep].min()) > margin:
        o = P.mean(axis=0)  # the vertices' centroid: strictly inside a solid
        off = off - tn @ o
        if not float(off[keep].min()) > margin:
            return False
    Pc = P - o
    if _degree(Pc, tri) != 1:
        return False  # wound about o more than once (or a tie: not proved)
    if len(X) * len(keep) <= EXHAUSTIVE:
        return _within(X - o, tn[keep], off[keep], tol)
    # left to locate: the points outside the ball about o under every plane (inside it: in
    # K) that are no vertex's copy. Both tests are a point's own, so either may go first:
    # the copies where most points are hull vertices (a smooth convex body), else the ball,
    # and only the points outside it are looked up among the vertices (a box with a tilted
    # cylinder: 26,000 of 50,000 points, 5,700 vertices)
    r = float(off[keep].min())
    if 2 * len(P) >= len(X):
        Y = X[~_vertex_copies(X, P)] - o
        Y = Y[dot(Y, Y) > r * r]
    else:
        Xo = X - o
        out = np.flatnonzero(dot(Xo, Xo) > r * r)
        Y = Xo[out[~_vertex_copies(X[out], P)]]
    if len(Y) * len(keep) <= EXHAUSTIVE:
        return _within(Y, tn[keep], off[keep], tol)
    if len(Y) > WALKERS:
        return None
    return _walk(Pc, tri, stand, tn, off, twins, Y, tol)
