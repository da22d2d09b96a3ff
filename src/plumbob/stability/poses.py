"""Resting poses: where a body can come to rest, and how likely each landing is.

The model is the quasi-static one of Baktash, Sharp, Zhou, Crane and Jacobson,
"Putting Rigid Bodies to Rest" (SIGGRAPH 2025). Over all down directions ``u``
(unit vectors in the body's frame) the height of the centre of mass ``c`` above
the plane the body rests on is the support function of its convex hull,

    h(u) = max over hull vertices v of (v − c)·u,

and a body dropped without momentum rolls downhill on ``h`` until it rests.
On the sphere of directions (the Gauss map of the hull):

* a face's normal is a point; the face is a **stable pose** — a minimum of ``h``
  — when the foot of the centre of mass lies strictly inside it;
* an edge is an arc between its two faces' normals; it holds a **saddle** where
  the direction from ``c`` square to the edge's line falls within the arc and
  the foot lies inside the edge;
* a vertex ``v`` owns a spherical polygon, on which the body pivots about ``v``:
  directions move along great circles away from ``w = (v − c)/|v − c|``; a vertex
  whose ``w`` lies in its own polygon is a **maximum** (balanced on that tip).

A pose's probability is the area of its basin — the directions that roll into
it — divided by 4π. Basins are bounded by the curves that flow into saddles,
traced back uphill, region by region, to maxima; each basin's area is the
exact sum of signed spherical triangles fanned from its face's normal over its
boundary. Every step is vectorised over all saddles (and all rolls) at once.

The landscape is traced on the *exact* hull — qhull's triangles merged only
where exactly coplanar — so that it is consistent to rounding error; faces
coplanar within the tolerance are merged into physical faces only when the
poses are reported (their probabilities summed). The areas are checked to add
up to 4π. A degenerate landscape (a centre of mass exactly above a vertex or an
edge's end, as symmetric meshes have) is traced again from a centre nudged by
a hair, and the directions landing on a face the true centre sees on its edge
roll on from there; should that fail too, the probabilities come from rolling
a deterministic Fibonacci lattice of directions downhill (and the result says
so). Probabilities add up to 1 by construction, and no NaN can arise.

For a lamina the same holds one dimension down: the hull's edges are the
poses, the circle of directions is cut into arcs, and the basins are exact arcs.

For bodies with curved surfaces (sampled hulls) neighbouring facets of a
rolling surface — a cylinder's side, a sphere — are all stable with barriers
no higher than the sampling's sagitta; poses joined by such saddles are merged
into one *neutral* pose (a body that rolls), whose probability is their sum.
Exact polytopes are never merged that way.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import GeometryError, StabilityError
from .rocking import rocking
from .support import body_dim, body_size, hull_points, is_polytope
from .verdict import STANDARD_GRAVITY

__all__ = ["Pose", "Poses", "resting_poses", "poses_from_points", "FALLBACK_SAMPLES"]

FALLBACK_SAMPLES = 200_000  # Fibonacci directions when the exact basins cannot be traced
# A family of stable sampled faces whose normals all lie within this angle of its lowest
# face is the bottom of a bowl (a self-righting rocker), not a rolling surface.
BOWL_SPREAD_DEG = 5.0
_AREA_CHECK = 1e-7  # relative tolerance on the basins' total area (4π)
_THETA_EPS = 1e-12  # rad: intersections closer than this to a trace's start are its own arc
_RELAXED = 1e-4  # how far outside an arc (sine of the angle) a trace may still cross it
_FLAT = 1e-12  # |t| below this: the centre's foot is at the edge's end (a balanced vertex)
_NUDGES = (0.0, 1e-9, 1e-7, 1e-5)  # relative moves of the centre for degenerate landscapes
_NUDGE_DIRECTION = np.array([0.5773, 0.2245, 0.7853]) / np.linalg.norm([0.5773, 0.2245, 0.7853])
# (a fixed, deterministic direction with no special relation to any axis)


@dataclass(frozen=True)
class Pose:
    """One stable resting pose.

    down: unit vector (dim,) in the body's frame: the outward normal of the face it
        rests on, pointing to the ground.
    com_height: height of the centre of mass above the ground, m.
    probability: quasi-static probability of landing in this pose from a random drop.
    critical_tilt_deg: least tilt of the ground, over every direction, that topples it
        out of this pose, degrees (0 for a neutral pose: it rolls).
    energy_barrier: energy to leave the pose over the lowest saddle of its basin's
        boundary, J; None when it is the only pose.
    face: (k, dim) the vertices of the face it rests on, m, body frame.
    neutral: True when the pose is a rolling family (a cylinder on its side, a sphere)
        merged from neighbouring sampled facets.
    members: how many hull faces the pose stands for.
    """

    down: np.ndarray
    com_height: float
    probability: float
    critical_tilt_deg: float
    energy_barrier: float | None
    face: np.ndarray
    neutral: bool = False
    members: int = 1


@dataclass(frozen=True)
class Poses:
    """All stable resting poses of a body, most probable first.

    poses: the poses; their probabilities add up to 1.
    mass: kg. g: m/s². center_of_mass: (dim,) m.
    method: ``"exact"`` (basin areas traced exactly) or ``"sampled"`` (the fallback:
        a descent from a Fibonacci lattice of directions).
    hull_faces: faces of the hull after merging coplanar triangles.
    saddles: how many saddles (3D) or maxima (2D) bound the basins.
    area_error: |Σ basin areas − 4π| / 4π (2π for a lamina) before normalising.
    notes: what a reader should know (merged families, fallbacks).
    """

    poses: tuple[Pose, ...]
    mass: float
    g: float
    center_of_mass: np.ndarray
    method: str
    hull_faces: int
    saddles: int
    area_error: float
    notes: tuple[str, ...] = field(default=())

    def __len__(self) -> int:
        return len(self.poses)

    def __getitem__(self, index: int) -> Pose:
        return self.poses[index]

    @property
    def probabilities(self) -> np.ndarray:
        return np.array([p.probability for p in self.poses])

    def plot(self, fig=None, *, body=None, **options):
        """Draw the pose gallery (the body in each pose if given); returns the matplotlib
        figure. See :func:`plumbob.plot.plot_poses`."""
        from ..plot.gallery import plot_poses

        return plot_poses(self, body, fig, **options)

    def _repr_png_(self) -> bytes:  # notebooks show the gallery
        from ..plot.files import png_bytes

        return png_bytes(self.plot())


# ====================================================================== helpers
def _unit(v: np.ndarray) -> np.ndarray:
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(norm > 0, norm, 1.0)


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross products of (…, 3) arrays (faster than ``np.cross`` for many small vectors)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0), axis=-1)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise dot products of (…, 3) arrays."""
    return (a * b).sum(axis=-1)


def _solid_angle(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Signed area of the spherical triangles (a, b, c) of unit vectors (…, 3), sr
    (Van Oosterom and Strackee); positive when a → b → c turns counter-clockwise
    seen from outside."""
    num = _dot(a, _cross(b, c))
    den = 1.0 + _dot(a, b) + _dot(b, c) + _dot(c, a)
    return 2.0 * np.arctan2(num, den)


def _group_first(keys: np.ndarray, values: np.ndarray, n: int) -> np.ndarray:
    """For each group ``0..n-1`` of ``keys``, the index (into keys) of its least value, the
    first such on ties (−1 for an empty group)."""
    least = np.full(n, np.inf)
    np.minimum.at(least, keys, values)
    idx = np.flatnonzero(values == least[keys])[::-1]
    first = np.full(n, -1, dtype=np.int64)
    first[keys[idx]] = idx  # the last write wins: the first index of each group
    if np.any(np.isinf(least)):  # groups whose values are all inf: their first member
        allinf = np.flatnonzero(np.isinf(values) & np.isinf(least[keys]))[::-1]
        first[keys[allinf]] = allinf
    return first


def _expand(counts: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Ragged expansion: for each row ``i``, indices ``starts[i] .. starts[i]+counts[i]-1``.
    Returns (row of each item, item index)."""
    total = int(counts.sum())
    rows = np.repeat(np.arange(len(counts)), counts)
    offsets = np.arange(total) - np.repeat(np.cumsum(counts) - counts, counts)
    return rows, np.repeat(starts, counts) + offsets


def _pointer_sinks(nxt: np.ndarray) -> np.ndarray:
    """Follow ``nxt`` (a forest whose roots point to themselves) to the roots."""
    ptr = nxt.copy()
    for _ in range(64):
        jumped = ptr[ptr]
        if np.array_equal(jumped, ptr):
            return ptr
        ptr = jumped
    raise StabilityError("the resting poses could not be resolved: the rolling graph has a "
                         "cycle (a degenerate hull?)")


def _fibonacci_sphere(n: int) -> np.ndarray:
    i = np.arange(n) + 0.5
    z = 1.0 - 2.0 * i / n
    phi = np.pi * (3.0 - np.sqrt(5.0)) * i
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    return np.stack((r * np.cos(phi), r * np.sin(phi), z), axis=1)


# ================================================================= the 3D hull
@dataclass(frozen=True)
class _Hull3:
    """The exact convex hull, relative to the centre of mass (at the origin).

    X: (n, 3) hull points (only those with out-edges are vertices).
    normals, heights, areas: per face (F, 3), (F,), (F,): outward unit normal, h(normal)
        and area. Faces are exactly coplanar groups of qhull's triangles.
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
    return _unit(out)


def _split_bent(comp: np.ndarray, nfaces: int, corners: np.ndarray, owner: np.ndarray,
                X: np.ndarray, normals: np.ndarray, tol: float
                ) -> tuple[np.ndarray, np.ndarray, int]:
    """Groups whose corners stray more than ``tol`` from the group's plane go back to their
    parts (a chain of nearly coplanar slivers can bend). ``corners`` are point indices,
    ``owner`` the part each belongs to; returns (comp, bent mask of old groups, nfaces)."""
    level = _dot(X[corners], normals[comp[owner]])
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


def _build_hull3(X: np.ndarray, eps: float) -> _Hull3:
    """The hull with qhull's triangles merged into faces where coplanar within ``eps``."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(X)
    except QhullError as exc:
        raise GeometryError("the body is flat or degenerate: its points span no volume, so "
                            "it has no resting poses as a solid") from exc
    tri = hull.simplices.astype(np.int64).copy()
    eq = hull.equations
    tn = eq[:, :3] / np.linalg.norm(eq[:, :3], axis=1)[:, None]
    toff = -eq[:, 3] / np.linalg.norm(eq[:, :3], axis=1)
    cr = _cross(X[tri[:, 1]] - X[tri[:, 0]], X[tri[:, 2]] - X[tri[:, 0]])
    flip = _dot(cr, tn) < 0
    tri[flip] = tri[flip][:, [0, 2, 1]]
    area = 0.5 * np.linalg.norm(cr, axis=1)
    m = len(tri)

    # --- half-edges: a → b of triangle t, its twin found through qhull's neighbours
    nb = hull.neighbors.astype(np.int64)
    nb[flip] = nb[flip][:, [0, 2, 1]]  # neighbour k is opposite vertex k
    n = len(X)
    frm = tri.ravel()
    to = tri[:, [1, 2, 0]].ravel()
    across = nb[:, [2, 0, 1]].ravel()  # the triangle beyond half-edge k (opposite k + 2)
    twin = 3 * across + np.argmax(tri[across] == to[:, None], axis=1)
    if not np.array_equal(frm[twin], to) or not np.array_equal(to[twin], frm):
        raise GeometryError("the convex hull is not a closed surface (qhull failure)")
    tri_of = np.repeat(np.arange(m), 3)

    # --- exactly coplanar neighbours (qhull's own triangulated facets) make one face
    i, j = tri_of, across
    pair = i < j
    i, j = i[pair], j[pair]
    dij = np.abs(np.einsum("kvc,kc->kv", X[tri[j]], tn[i]) - toff[i][:, None]).max(axis=1)
    dji = np.abs(np.einsum("kvc,kc->kv", X[tri[i]], tn[j]) - toff[j][:, None]).max(axis=1)
    same = (dij <= eps) & (dji <= eps) & (_dot(tn[i], tn[j]) > 0)
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
        heights = np.max(_dot(X[tri], tn[:, None, :]), axis=1)
        return _Hull3(X, tn, heights, area, ea, eb, ef, eg, start, degree, etwin, und)
    graph = coo_matrix((np.ones(int(same.sum())), (i[same], j[same])), shape=(m, m))
    nfaces, comp = connected_components(graph, directed=False)
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
    np.maximum.at(heights, ef, _dot(X[ea], normals[ef]))
    return _Hull3(X, normals, heights, areas, ea, eb, ef, eg, start, degree, pos3, und)


def _physical_faces(h: _Hull3, tol: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Exact faces grouped into physical ones: neighbours coplanar within ``tol`` (m).

    Returns the group of each face, and per group its unit normal and height h(normal).
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    nF = len(h.normals)
    # a face's extent bounds how far its corners stray from a neighbour's plane
    ext = np.zeros(nF)
    np.maximum.at(ext, h.ef, np.linalg.norm(h.X[h.ea] - h.X[h.eb], axis=1))
    f, g = h.ef, h.eg
    pair = f < g
    f, g = f[pair], g[pair]
    cos = np.clip(_dot(h.normals[f], h.normals[g]), -1.0, 1.0)
    sin = np.sqrt(np.maximum(0.0, 1.0 - cos * cos))
    same = (cos > 0) & (sin * np.maximum(ext[f], ext[g]) <= tol)
    if not same.any():
        return np.arange(nF), h.normals, h.heights
    graph = coo_matrix((np.ones(int(same.sum())), (f[same], g[same])), shape=(nF, nF))
    ngroups, group = connected_components(graph, directed=False)
    normals = _weighted_normals(group, ngroups, h.normals, h.areas)
    group, bent, ngroups = _split_bent(group, ngroups, h.ea, h.ef, h.X, normals, tol)
    if bent.any():
        normals = _weighted_normals(group, ngroups, h.normals, h.areas)
    heights = np.full(ngroups, -np.inf)
    np.maximum.at(heights, group[h.ef], _dot(h.X[h.ea], normals[group[h.ef]]))
    return group, normals, heights


def _group_margin3(pts: np.ndarray, normal: np.ndarray) -> tuple[float, np.ndarray]:
    """Signed distance from the foot of the centre (the origin) to the boundary of the
    physical face with corners ``pts`` (k, 3) (positive inside), m, and its corners
    counter-clockwise about ``normal``."""
    from scipy.spatial import ConvexHull, QhullError

    seed = np.array([1.0, 0.0, 0.0]) if abs(normal[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = _unit(seed - (seed @ normal) * normal)
    e2 = _cross(normal, e1)
    q = np.stack((pts @ e1, pts @ e2), axis=1)  # the foot h·normal is at the origin
    try:
        ring = ConvexHull(q).vertices
    except QhullError:
        return 0.0, pts
    v = q[ring]
    d = np.roll(v, -1, axis=0) - v
    out = np.stack((d[:, 1], -d[:, 0]), axis=1) / np.linalg.norm(d, axis=1)[:, None]
    return float(_dot(v, out).min()), pts[ring]


# ============================================================ 3D basin tracing
@dataclass(frozen=True)
class _Edges3:
    """Per directed edge: geometry for the Gauss-map flow."""

    pole: np.ndarray  # (E, 3) unit edge direction: the arc n_F → n_G turns about it
    t: np.ndarray  # (E,) foot of c on the edge's line, as a fraction from a to b
    saddle: np.ndarray  # (E,) bool: the arc holds a saddle
    spoint: np.ndarray  # (E, 3) unit direction from c square to the edge line
    sheight: np.ndarray  # (E,) |c to the edge line|, m
    after_f: np.ndarray  # (E, 3) pole × n_F: q·after_f ≥ 0 when q lies past n_F on the arc
    before_g: np.ndarray  # (E, 3) n_G × pole: q·before_g ≥ 0 when q lies before n_G
    toward_f: np.ndarray  # (E, 3) spoint × pole: q·toward_f > 0 when q lies on n_F's side


def _edge_geometry(h: _Hull3) -> _Edges3:
    A, B = h.X[h.ea], h.X[h.eb]
    D = B - A
    L2 = _dot(D, D)
    t = -_dot(A, D) / L2
    pole = D / np.sqrt(L2)[:, None]
    p = A + t[:, None] * D
    sheight = np.linalg.norm(p, axis=1)
    s = p / sheight[:, None]
    nf, ng = h.normals[h.ef], h.normals[h.eg]
    after_f, before_g = _cross(pole, nf), _cross(ng, pole)
    in_arc = (_dot(s, after_f) >= 0) & (_dot(s, before_g) >= 0)
    saddle = (t > 0) & (t < 1) & in_arc
    return _Edges3(pole, t, saddle, s, sheight, after_f, before_g, _cross(s, pole))


def _arc_hits(h: _Hull3, eg3: _Edges3, rows: np.ndarray, cand: np.ndarray, p: np.ndarray,
              tang: np.ndarray, limit: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where the great circle ``cos θ p + sin θ tang`` (θ > 0) first meets each candidate arc.

    rows: trace of each candidate; cand: directed edge id; p, tang: per trace.
    Returns θ (inf when the great circle is not met before ``limit``), how far outside
    the arc the meeting point lies (0 inside; sines of angles) and the meeting points.
    """
    k = eg3.pole[cand]
    pr, tr = p[rows], tang[rows]
    a, b = _dot(pr, k), _dot(tr, k)
    theta = np.arctan2(-a, b)
    theta = np.where(theta <= _THETA_EPS, theta + np.pi, theta)
    q = np.cos(theta)[:, None] * pr + np.sin(theta)[:, None] * tr
    miss = np.maximum(0.0, -np.minimum(_dot(q, eg3.after_f[cand]), _dot(q, eg3.before_g[cand])))
    ok = (theta > _THETA_EPS) & (theta <= limit[rows] + 1e-12)
    return np.where(ok, theta, np.inf), miss, q


def _step(h: _Hull3, eg3: _Edges3, v: np.ndarray, p: np.ndarray, tang: np.ndarray,
          limit: np.ndarray, exclude: np.ndarray, want: np.ndarray, face: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray]:
    """For traces at vertices ``v`` from points ``p`` along ``tang``: the first arc of
    the vertex's region met, among out-edges selected by the mask ``want`` (per edge),
    leaving out the undirected edge ``exclude`` and the arcs ending at the face ``face``
    (≥ 0 for a trace starting at that face's normal, a corner of the region);
    returns (edge id or −1, meeting point)."""
    rows, cand = _expand(h.degree[v], h.start[v])
    theta, miss, q = _arc_hits(h, eg3, rows, cand, p, tang, limit)
    fr = face[rows]
    keep = want[cand] & (h.und[cand] != exclude[rows]) & np.isfinite(theta)
    keep &= (fr < 0) | ((h.ef[cand] != fr) & (h.eg[cand] != fr))
    # the first arc met inside; failing that (a point a rounding error outside its
    # region), the arc met least far outside
    score = np.where(keep & (miss <= 1e-12), theta,
                     np.where(keep & (miss <= _RELAXED), 10.0 + miss, np.inf))
    best = _group_first(rows, score, len(v))
    found = (best >= 0) & np.isfinite(score[np.maximum(best, 0)])
    edge = np.where(found, cand[np.maximum(best, 0)], -1)
    point = np.where(found[:, None], q[np.maximum(best, 0)], p)
    return edge, _unit(point)


class _Roller:
    """The quasi-static roll downhill: which faces are stable, and where anything ends."""

    def __init__(self, h: _Hull3, eg3: _Edges3, W: np.ndarray, tol: float) -> None:
        self.h, self.eg3, self.W, self.tol = h, eg3, W, tol
        nF = len(h.normals)
        A, B = h.X[h.ea], h.X[h.eb]
        D = B - A
        self.length = np.sqrt(_dot(D, D))
        n = h.normals[h.ef]
        self.foot = h.heights[h.ef][:, None] * n
        s = _dot(_cross(D, self.foot - A), n) / self.length  # signed, positive inside
        self.margin = np.full(nF, np.inf)
        np.minimum.at(self.margin, h.ef, s)
        self.stable = self.margin > tol
        self._memo = np.where(self.stable, np.arange(nF), -1)  # sinks found so far
        # an unstable face tips over the point of its boundary nearest the foot
        A, D, L = h.X[h.ea], h.X[h.eb] - h.X[h.ea], self.length
        tau = np.clip(_dot(self.foot - A, D) / (L * L), 0.0, 1.0)
        dist = np.linalg.norm(A + tau[:, None] * D - self.foot, axis=1)
        tip = _group_first(h.ef, dist, nF)
        self.tip_edge = tip
        along = (tau * L)[tip]
        self.pivots = ~self.stable & ~((along > tol) & (along < L[tip] - tol))
        self.pivot_vertex = np.where(along <= tol, h.ea[tip], h.eb[tip])
        # rolls over edges chain faces: jump along them to a stable face or a pivot
        over = np.where(self.stable | self.pivots, np.arange(nF), h.eg[tip])
        for _ in range(64):
            jumped = over[over]
            if np.array_equal(jumped, over):
                break
            over = jumped
        else:
            raise StabilityError("the resting poses could not be resolved: rolling over "
                                 "edges never ends (a degenerate hull?)")
        self.lands = over

    def roll(self, face: np.ndarray | None = None, vertex: np.ndarray | None = None,
             point: np.ndarray | None = None) -> np.ndarray:
        """The stable face each trace ends on: traces start at faces (their normals) or at
        directions ``point`` (k, 3) in the regions of ``vertex``. −1 where a roll is lost.

        One loop advances every trace by one move — over a face's edge, from a face into
        the region of the corner it pivots about, across a region — so the loop runs as
        long as the longest roll, not the sum of them.
        """
        h, eg3 = self.h, self.eg3
        if face is not None:
            k = len(face)
            cur = np.asarray(face, dtype=np.int64).copy()
            v = np.zeros(k, dtype=np.int64)
            p = np.zeros((k, 3))
            in_region = np.zeros(k, dtype=bool)
        else:
            k = len(vertex)
            cur = np.full(k, -1, dtype=np.int64)
            v = np.asarray(vertex, dtype=np.int64).copy()
            p = _unit(np.asarray(point, dtype=float).copy())
            in_region = np.ones(k, dtype=bool)
        start_face = np.full(k, -1, dtype=np.int64)  # the face a region move started at
        exclude = np.full(k, -1, dtype=np.int64)
        result = np.full(k, -1, dtype=np.int64)
        alive = np.ones(k, dtype=bool)
        far = eg3.t > 0
        for _ in range(4 * len(h.normals) + 16):
            at_face = np.flatnonzero(alive & ~in_region)
            if len(at_face):
                f = self.lands[cur[at_face]]  # over edges, as far as that goes
                done = self.stable[f]
                result[at_face[done]] = f[done]
                alive[at_face[done]] = False
                piv, f = at_face[~done], f[~done]  # over a corner: pivot about it
                v[piv] = self.pivot_vertex[f]
                p[piv] = h.normals[f]
                start_face[piv] = f
                exclude[piv] = -1
                in_region[piv] = True
            rolling = np.flatnonzero(alive & in_region)
            if len(rolling) == 0:
                if not alive.any():
                    return result
                continue
            va, pa = v[rolling], p[rolling]
            w = self.W[va]
            tang = _unit(_dot(w, pa)[:, None] * pa - w)
            edge, q = _step(h, eg3, va, pa, tang, np.full(len(rolling), np.pi),
                            exclude[rolling], far, start_face[rolling])
            lost = edge < 0
            from_face = start_face[rolling]
            # lost leaving a corner along its own arc: over the face's nearest edge
            rescue = lost & (from_face >= 0)
            if rescue.any():
                cur[rolling[rescue]] = h.eg[self.tip_edge[from_face[rescue]]]
                in_region[rolling[rescue]] = False
            gone = lost & (from_face < 0)
            alive[rolling[gone]] = False
            e = np.maximum(edge, 0)
            sliding = ~lost & (eg3.t[e] < 1)
            # on a sliding arc: to the side of its saddle, or to its lower end
            fa, ga = h.ef[e], h.eg[e]
            towards_f = np.where(eg3.saddle[e], _dot(q, eg3.toward_f[e]) > 0,
                                 h.heights[fa] <= h.heights[ga])
            slid = rolling[sliding]
            cur[slid] = np.where(towards_f, fa, ga)[sliding]
            in_region[slid] = False
            crossing = ~lost & ~sliding
            cr = rolling[crossing]
            v[cr], p[cr], exclude[cr] = h.eb[e[crossing]], q[crossing], h.und[e[crossing]]
            start_face[rolling[~lost]] = -1
        raise StabilityError("the resting poses could not be resolved: a roll never ends "
                             "(a degenerate hull?)")

    def sinks(self, faces: np.ndarray) -> np.ndarray:
        """The stable face each of ``faces`` ends up on (remembered once rolled)."""
        faces = np.asarray(faces, dtype=np.int64)
        todo = np.unique(faces[self._memo[faces] < 0])
        if len(todo):
            out = self.roll(face=todo)
            if np.any(out < 0):
                raise StabilityError("a roll from a face of the hull was lost "
                                     "(degenerate hull)")
            self._memo[todo] = out
        return self._memo[faces]


def _trace_basins(h: _Hull3, eg3: _Edges3, W: np.ndarray, roller: _Roller
                  ) -> tuple[np.ndarray, bool]:
    """Basin areas (per face, sr) from the separatrices traced back from every saddle."""
    nF = len(h.normals)
    area = np.zeros(nF)
    sad = np.flatnonzero(eg3.saddle & (h.ea < h.eb))
    if len(sad) == 0:
        return area, False
    s = eg3.spoint[sad]
    # two traces per saddle: into the regions of both its ends
    v = np.concatenate((h.ea[sad], h.eb[sad]))
    p = np.concatenate((s, s))
    edge = np.concatenate((sad, sad))
    exclude = h.und[edge]
    ends = roller.sinks(np.concatenate((h.ef[edge], h.eg[edge])))
    f, g = ends[:len(edge)], ends[len(edge):]
    w0 = W[v]
    side = _dot(_cross(p, w0), h.normals[h.ef[edge]]) > 0
    left, right = np.where(side, f, g), np.where(side, g, f)
    nl, nr = h.normals[left], h.normals[right]
    near = eg3.t < -_FLAT  # arcs a region's flow leaves: traced back through them
    ismax = np.ones(len(h.X), dtype=bool)  # balanced on the tip: no region flows into it
    np.logical_and.at(ismax, h.ea, ~near)
    alive = np.arange(len(v))
    ok = True
    for _ in range(len(h.X) + 8):
        if len(alive) == 0:
            break
        va, pa = v[alive], p[alive]
        w = W[va]
        done = ismax[va] | (_dot(pa, w) >= 1.0 - 1e-24)  # at its maximum already
        if done.any():
            d = alive[done]
            area_l = _solid_angle(nl[d], pa[done], w[done])
            area_r = _solid_angle(nr[d], w[done], pa[done])
            np.add.at(area, left[d], area_l)
            np.add.at(area, right[d], area_r)
            alive, va, pa, w = alive[~done], va[~done], pa[~done], w[~done]
            if len(alive) == 0:
                break
        tang = _unit(w - _dot(w, pa)[:, None] * pa)
        limit = np.arccos(np.clip(_dot(pa, w), -1.0, 1.0))
        e, q = _step(h, eg3, va, pa, tang, limit, exclude[alive], near,
                     np.full(len(alive), -1))
        lost = e < 0
        if lost.any():  # passes through a corner, or numerically lost: end it at w
            ok = False
            d = alive[lost]
            np.add.at(area, left[d], _solid_angle(nl[d], pa[lost], w[lost]))
            np.add.at(area, right[d], _solid_angle(nr[d], w[lost], pa[lost]))
        go = ~lost
        d = alive[go]
        np.add.at(area, left[d], _solid_angle(nl[d], pa[go], q[go]))
        np.add.at(area, right[d], _solid_angle(nr[d], q[go], pa[go]))
        v[d], p[d], exclude[d] = h.eb[e[go]], q[go], h.und[e[go]]
        alive = d
    else:
        ok = False
    return np.mod(area, 4 * np.pi), ok


def _sampled_basins(h: _Hull3, roller: _Roller, samples: int) -> np.ndarray:
    """Basin areas from rolling a Fibonacci lattice of directions downhill."""
    u = _fibonacci_sphere(samples)
    area = np.zeros(len(h.normals))
    real = np.flatnonzero(h.degree > 0)
    for chunk in np.array_split(np.arange(samples), max(1, samples // 20000)):
        start = real[np.argmax(u[chunk] @ h.X[real].T, axis=1)]
        face = roller.roll(vertex=start, point=u[chunk])
        np.add.at(area, face[face >= 0], 4 * np.pi / samples)
    return area


@dataclass(frozen=True)
class _Landscape:
    """The height function's landscape over physical faces (3D) or edges (2D).

    normals, heights: (G, dim), (G,) per physical face.
    area: (G,) area of its basin (sr, or rad for a lamina); stable: (G,) it is a minimum.
    sa, sb, sh: saddles (maxima for a lamina) between the basins of sa and sb, at height sh.
    margin: ``margin(g) -> (signed margin m, face corners (k, dim))``.
    """

    normals: np.ndarray
    heights: np.ndarray
    area: np.ndarray
    stable: np.ndarray
    sa: np.ndarray
    sb: np.ndarray
    sh: np.ndarray
    margin: object
    method: str
    error: float


def _shifted(h: _Hull3, delta: np.ndarray) -> _Hull3:
    """The same hull seen from a centre moved by ``delta``: only heights change."""
    return replace(h, X=h.X - delta, heights=h.heights - h.normals @ delta)


def _basins3(h: _Hull3, eps: float, samples: int | None):
    """(basin areas, roller, edge geometry, saddles, error) — or None when the traced areas
    do not add up and ``samples`` is None."""
    eg3 = _edge_geometry(h)
    W = _unit(h.X)
    roller = _Roller(h, eg3, W, eps)
    stable = roller.stable
    if not stable.any():
        raise StabilityError("no face of the hull is stable (degenerate hull)")
    sad = np.flatnonzero(eg3.saddle & (h.ea < h.eb))
    if samples is not None:
        return _sampled_basins(h, roller, samples), roller, eg3, sad, float("nan")
    if len(sad) == 0:  # one basin: the whole sphere
        area = np.where(stable, 4 * np.pi / np.count_nonzero(stable), 0.0)
        ok = np.count_nonzero(stable) == 1
    else:
        area, ok = _trace_basins(h, eg3, W, roller)
    error = abs(area.sum() - 4 * np.pi) / (4 * np.pi)
    if not ok or error > _AREA_CHECK or np.any(area[stable] <= 0):
        return None
    return area, roller, eg3, sad, float(error)


def _landscape3(X: np.ndarray, tol: float, samples: int) -> _Landscape:
    size = float(np.linalg.norm(np.ptp(X, axis=0)))
    eps = 1e-12 * size
    h0 = _build_hull3(X, eps)
    inside = float(h0.heights.min())
    if not inside > tol:
        where = "outside" if inside < -tol else "on the surface of"
        raise StabilityError(
            f"the centre of mass lies {where} the body's convex hull "
            f"(by {abs(inside):.3g} m), so the body cannot rest on any face: is the mesh "
            "open or inside out, or a density negative?")
    # A centre exactly above a vertex or an edge's end (symmetric meshes) is a degenerate
    # landscape whose traces may not close: look again from a centre nudged by a hair.
    method, found = "exact", None
    for nudge in _NUDGES:
        h = h0 if nudge == 0 else _shifted(h0, nudge * size * _NUDGE_DIRECTION)
        found = _basins3(h, eps, None)
        if found is not None:
            break
    if found is None:
        h, method = h0, "sampled"
        found = _basins3(h, eps, samples)
    area, roller, eg3, sad, error = found
    stable = roller.stable
    fa, fb = roller.sinks(h.ef[sad]), roller.sinks(h.eg[sad])
    if h is not h0:  # seen from the true centre, a nudged pose may sit on its face's edge:
        true = _Roller(h0, _edge_geometry(h0), _unit(h0.X), eps)  # roll it on from there
        try:
            landed = np.flatnonzero(area > 0)
            area = np.bincount(true.sinks(landed), weights=area[landed], minlength=len(area))
            fa, fb, stable = true.sinks(fa), true.sinks(fb), true.stable
        except StabilityError:
            pass  # the true centre's rolls are degenerate too: keep the nudged answer
    group, gnormals, gheights = _physical_faces(h0, tol)
    ng = len(gnormals)
    garea = np.bincount(group, weights=area, minlength=ng)
    gstable = np.bincount(group, weights=stable.astype(float), minlength=ng) > 0
    by_group = np.argsort(group[h0.ef], kind="stable")
    bounds = np.searchsorted(group[h0.ef][by_group], np.arange(ng + 1))

    def margin(gid: int) -> tuple[float, np.ndarray]:
        corners = np.unique(h0.ea[by_group[bounds[gid]:bounds[gid + 1]]])
        return _group_margin3(h0.X[corners], gnormals[gid])

    return _Landscape(gnormals, gheights, garea, gstable & (garea > 0), group[fa], group[fb],
                      eg3.sheight[sad], margin, method, error)


# ================================================================== the 2D hull
def _landscape2(X: np.ndarray, tol: float) -> _Landscape:
    """2D: hull edges are the poses; basins are arcs of the circle of directions."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(X)
    except QhullError as exc:
        raise GeometryError("the lamina is degenerate: its points span no area") from exc
    V = X[hull.vertices]  # counter-clockwise
    for _ in range(len(V)):  # drop corners lying on the line between their neighbours
        prev, nxt = np.roll(V, 1, axis=0), np.roll(V, -1, axis=0)
        d = nxt - prev
        off = np.abs(d[:, 0] * (V - prev)[:, 1] - d[:, 1] * (V - prev)[:, 0])
        off /= np.linalg.norm(d, axis=1)
        flat = off <= tol
        if not flat.any() or len(V) - flat.sum() < 3:
            break
        V = V[~(flat & ~np.roll(flat, 1))]  # the first of each run: neighbours change
    m = len(V)
    A, B = V, np.roll(V, -1, axis=0)
    D = B - A
    L = np.linalg.norm(D, axis=1)
    normals = np.stack((D[:, 1], -D[:, 0]), axis=1) / L[:, None]
    heights = _dot(A, normals)
    if not heights.min() > tol:
        raise StabilityError(
            "the centre of mass lies outside (or on) the lamina's convex hull: it cannot "
            "rest on any edge — is a density negative?")
    foot = heights[:, None] * normals
    along = _dot(foot - A, D) / L
    margins = np.minimum(along, L - along)
    stable = margins > tol
    # unstable edges tip over the end the foot lies beyond
    idx = np.arange(m)
    nxt = np.where(stable, idx, np.where(along >= L / 2, (idx + 1) % m, (idx - 1) % m))
    sink = _pointer_sinks(nxt)
    # vertex i lies between edge i-1 (normal angle a0) and edge i
    ang = np.arctan2(normals[:, 1], normals[:, 0])
    a0 = np.roll(ang, 1)
    width = np.mod(ang - a0, 2 * np.pi)
    into = np.mod(np.arctan2(V[:, 1], V[:, 0]) - a0, 2 * np.pi)
    is_max = into < width
    prev_edge = (idx - 1) % m
    arc = np.zeros(m)
    # a maximum splits its arc; otherwise the whole arc flows to its lower end
    np.add.at(arc, sink[prev_edge[is_max]], into[is_max])
    np.add.at(arc, sink[idx[is_max]], (width - into)[is_max])
    lower = np.where(heights[prev_edge] <= heights, prev_edge, idx)
    np.add.at(arc, sink[lower[~is_max]], width[~is_max])
    error = abs(arc.sum() - 2 * np.pi) / (2 * np.pi)

    def margin(gid: int) -> tuple[float, np.ndarray]:
        return float(margins[gid]), np.array([V[gid], V[(gid + 1) % m]])

    sad = np.flatnonzero(is_max)
    return _Landscape(normals, heights, arc, stable & (arc > 0), sink[prev_edge[sad]],
                      sink[sad], np.linalg.norm(V[sad], axis=1), margin, "exact", float(error))


# ================================================================= assembling
def _families(land: _Landscape, neutral_height: float) -> np.ndarray:
    """Per physical face, a family label: stable faces joined by saddles no higher than
    ``neutral_height`` above them share one."""
    n = len(land.normals)
    if not (neutral_height > 0 and len(land.sh)):
        return np.arange(n)
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    rise = land.sh - np.maximum(land.heights[land.sa], land.heights[land.sb])
    low = (land.sa != land.sb) & (rise <= neutral_height)
    graph = coo_matrix((np.ones(int(low.sum())), (land.sa[low], land.sb[low])), shape=(n, n))
    return connected_components(graph, directed=False)[1]


def _assemble(land: _Landscape, com: np.ndarray, mass: float, g: float,
              neutral_height: float, notes: list[str], X: np.ndarray | None = None) -> Poses:
    ids = np.flatnonzero(land.stable)
    family = _families(land, neutral_height)
    total = land.area[ids].sum()
    weight = mass * g
    roots, members_of = np.unique(family[ids], return_inverse=True)
    fam_a, fam_b = family[land.sa], family[land.sb]
    poses = []
    for k, root in enumerate(roots.tolist()):
        members = ids[members_of == k]
        p = float(land.area[members].sum() / total)
        rep = int(members[np.argmax(land.area[members])])
        neutral = len(members) > 1
        bowl = False
        if neutral:
            low = int(members[np.argmin(land.heights[members])])
            # The members as low as the lowest (within the sampling's ridges): spread along
            # a rolling surface, or clustered round the bottom of a bowl, which rocks back.
            level = members[land.heights[members] <= land.heights[low] + 4 * neutral_height]
            spread = np.degrees(np.arccos(np.clip(land.normals[level] @ land.normals[low], -1, 1)))
            bowl = X is not None and float(spread.max()) <= BOWL_SPREAD_DEG
            if bowl:
                rep, neutral = low, False
        cross = (fam_a != fam_b) & ((fam_a == root) | (fam_b == root))
        barrier = None
        if cross.any():
            barrier = float(weight * max(0.0, float(np.min(land.sh[cross])) - land.heights[rep]))
        margin, face = land.margin(rep)
        tilt = 0.0 if neutral else float(np.degrees(np.arctan2(max(margin, 0.0),
                                                               land.heights[rep])))
        if bowl:
            tilt = float(rocking(X, land.normals[rep], neutral_height).tilts_deg.min())
        poses.append(Pose(land.normals[rep].copy(), float(land.heights[rep]), p, tilt, barrier,
                          face + com, neutral, len(members)))
    poses.sort(key=lambda q: (-q.probability, q.com_height))
    neutral_poses = [q for q in poses if q.neutral]
    if neutral_poses:
        notes.append(f"{sum(q.members for q in neutral_poses)} hull faces of rolling surfaces "
                     f"were merged into {len(neutral_poses)} neutral pose(s)")
    rockers = [q for q in poses if q.members > 1 and not q.neutral]
    if rockers:
        notes.append(f"{sum(q.members for q in rockers)} hull faces at the bottom of curved bowls "
                     f"were merged into {len(rockers)} rocking pose(s); their critical tilt is "
                     "that of the rocker, to about a degree")
    if land.method == "sampled":
        notes.append("the basins could not be traced exactly (degenerate hull): probabilities "
                     f"come from rolling {FALLBACK_SAMPLES} directions downhill")
    return Poses(tuple(poses), mass, g, com.copy(), land.method, len(land.normals),
                 int(len(land.sh)), land.error, tuple(notes))


def poses_from_points(points, center_of_mass, *, mass: float = 1.0,
                      g: float = STANDARD_GRAVITY, tolerance: float | None = None,
                      neutral_height: float = 0.0, samples: int = FALLBACK_SAMPLES,
                      notes: tuple[str, ...] = ()) -> Poses:
    """Resting poses of the convex hull of ``points`` (n, 2 or 3) m, with its centre of mass
    at ``center_of_mass``.

    tolerance: faces coplanar within it (m) are one physical face; default 1e-6 of the
        points' size. Basins are traced on the exact hull either way.
    neutral_height: stable faces joined by saddles at most this much higher (m) are one
        neutral (rolling) pose; 0 merges nothing.

    A cube: six poses of 1/6.

    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> ps = poses_from_points(cube, [0.5, 0.5, 0.5])
    >>> len(ps), ps.method, bool(np.allclose(ps.probabilities, 1 / 6, rtol=0, atol=1e-12))
    (6, 'exact', True)
    """
    X = np.asarray(points, dtype=float)
    com = np.asarray(center_of_mass, dtype=float).reshape(-1)
    if X.ndim != 2 or X.shape[1] not in (2, 3) or com.shape != (X.shape[1],):
        raise GeometryError("poses need points (n, 2) or (n, 3) and a centre of the same size")
    if not (np.all(np.isfinite(X)) and np.all(np.isfinite(com))):
        raise GeometryError("a point or the centre of mass is not a finite number")
    if len(X) < X.shape[1] + 1:
        what = "a volume" if X.shape[1] == 3 else "an area"
        raise GeometryError(f"resting poses need points spanning {what}: at least "
                            f"{X.shape[1] + 1}, and this body has {len(X)}")
    size = float(np.linalg.norm(np.ptp(X, axis=0)))
    tol = 1e-6 * size if tolerance is None else float(tolerance)
    if not (size > 0 and tol > 0):
        raise GeometryError("the points have no extent, or the tolerance is not positive")
    X = X - com
    land = _landscape2(X, tol) if X.shape[1] == 2 else _landscape3(X, tol, samples)
    return _assemble(land, com, float(mass), float(g), float(neutral_height), list(notes),
                     X if neutral_height > 0 else None)


def resting_poses(body, *, g: float = STANDARD_GRAVITY, tolerance: float | None = None,
                  hull_tolerance: float | None = None, neutral_height: float | None = None,
                  props=None) -> Poses:
    """All stable resting poses of ``body`` and their probabilities.

    body: a solid (poses on faces of its hull) or a lamina (on edges of its hull, in its
        own plane).
    g: m/s², for the energy barriers.
    tolerance: faces coplanar within it are one physical face, m (default 1e-6 of the
        body's size).
    hull_tolerance: how closely curved surfaces are sampled, m (default 1e-4 of the size).
    neutral_height: poses joined by saddles at most this high above them are merged into
        one neutral (rolling) pose, m; default: for a body with curved surfaces, twice the
        hull tolerance (the ridges sampling leaves on a rolling surface); for a polytope, 0.

    Raises :class:`StabilityError` when the centre of mass is not strictly inside the
    hull (an open mesh) — it never hangs.

    >>> from plumbob.bodies.primitives import box
    >>> [round(p.probability, 4) for p in resting_poses(box(1, 1, 4))]
    [0.2406, 0.2406, 0.2406, 0.2406, 0.0187, 0.0187]
    """
    props = body.mass_properties() if props is None else props
    dim = body_dim(body, props)
    size = body_size(body)
    htol = 1e-4 * size if hull_tolerance is None else float(hull_tolerance)
    pts = hull_points(body, htol)
    if neutral_height is None:  # only sampled (curved) surfaces have rolling families
        neutral_height = 0.0 if is_polytope(body, size) else 2.0 * htol
    com = np.asarray(props.center_of_mass, dtype=float)
    if com.size < dim:
        com = np.pad(com, (0, dim - com.size))
    if pts.shape[1] != dim:
        pts = pts[:, :dim]
    return poses_from_points(pts, com[:dim], mass=props.mass, g=g, tolerance=tolerance,
                             neutral_height=float(neutral_height))
