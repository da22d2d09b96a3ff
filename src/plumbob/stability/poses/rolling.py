"""The quasi-static roll downhill on the Gauss map of an exact hull.

On the sphere of down directions, each hull face is a point (its normal), each
edge an arc between its two faces' normals, and each vertex ``v`` owns a
spherical polygon on which the body pivots about ``v``: directions move along
great circles away from ``w = (v − c)/|v − c|``. :func:`edge_geometry` computes,
per directed edge, the arc's pole, where the centre's foot falls along the edge
and whether the arc holds a saddle. :class:`Roller` decides which faces are
stable and follows any start — a face, or a direction inside a vertex's region —
downhill to the stable face it ends on, all starts at once.

The basin tracer (:mod:`.basins`) walks the same regions uphill, with the same
arc-crossing step :func:`step`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import StabilityError
from .hull import Hull3
from .vectors import cross, dot, expand, group_first, unique, unit

__all__ = ["Edges3", "edge_geometry", "first_least_sorted", "step", "Roller"]

_THETA_EPS = 1e-12  # rad: intersections closer than this to a trace's start are its own arc
_RELAXED = 1e-4  # how far outside an arc (sine of the angle) a trace may still cross it
_CORNER = 5e-19  # 1 − cos of the angle (1e-9 rad) within which a roll is at an arc's end


@dataclass(frozen=True)
class Edges3:
    """Per directed edge: geometry for the Gauss-map flow."""

    pole: np.ndarray  # (E, 3) unit edge direction: the arc n_F → n_G turns about it
    t: np.ndarray  # (E,) foot of c on the edge's line, as a fraction from a to b
    saddle: np.ndarray  # (E,) bool: the arc holds a saddle
    spoint: np.ndarray  # (E, 3) unit direction from c square to the edge line
    sheight: np.ndarray  # (E,) |c to the edge line|, m
    after_f: np.ndarray  # (E, 3) pole × n_F: q·after_f ≥ 0 when q lies past n_F on the arc
    before_g: np.ndarray  # (E, 3) n_G × pole: q·before_g ≥ 0 when q lies before n_G
    toward_f: np.ndarray  # (E, 3) spoint × pole: q·toward_f > 0 when q lies on n_F's side


def edge_geometry(h: Hull3) -> Edges3:
    """The Gauss-map arc of every directed edge of ``h``, and whether it holds a saddle:
    the direction from the centre square to the edge's line lies on the arc and the
    foot lies strictly inside the edge."""
    A, D, L2 = h.edge_start, h.edge_vector, h.edge_length2
    t = dot(A, D)
    np.negative(t, out=t)
    t /= L2  # -(A·D) / |D|²
    pole = D / np.sqrt(L2)[:, None]
    s = t[:, None] * D
    s += A  # the foot A + t D ...
    sheight = np.sqrt(dot(s, s))  # = np.linalg.norm(s, axis=1), bit for bit
    s /= sheight[:, None]  # ... and its direction
    after_f = cross(pole, h.left_normal)
    # the reversed edge's pole is −pole (exactly) and its faces are swapped, so its
    # after_f is this edge's n_G × pole, bit for bit
    before_g = np.take(after_f, h.twin, axis=0)
    odd = np.take(h.ef, h.twin) != h.eg  # an edge a degenerate hull has twice: no mirror
    if odd.any():
        before_g[odd] = cross(h.normals[h.eg[odd]], pole[odd])
    in_arc = (dot(s, after_f) >= 0) & (dot(s, before_g) >= 0)
    saddle = (t > 0) & (t < 1) & in_arc
    return Edges3(pole, t, saddle, s, sheight, after_f, before_g, cross(s, pole))


def _arc_hits(h: Hull3, eg3: Edges3, rows: np.ndarray, cand: np.ndarray, p: np.ndarray,
              tang: np.ndarray, limit: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where the great circle ``cos θ p + sin θ tang`` (θ > 0) first meets each candidate arc.

    rows: trace of each candidate; cand: directed edge id; p, tang: per trace.
    Returns θ (inf when the great circle is not met before ``limit``), how far outside
    the arc the meeting point lies (0 inside; sines of angles) and the meeting points.
    """
    k = eg3.pole[cand]
    pr, tr = p[rows], tang[rows]
    a, b = dot(pr, k), dot(tr, k)
    theta = np.arctan2(-a, b)
    theta = np.where(theta <= _THETA_EPS, theta + np.pi, theta)
    q = np.cos(theta)[:, None] * pr + np.sin(theta)[:, None] * tr
    miss = np.maximum(0.0, -np.minimum(dot(q, eg3.after_f[cand]), dot(q, eg3.before_g[cand])))
    ok = (theta > _THETA_EPS) & (theta <= limit[rows] + 1e-12)
    return np.where(ok, theta, np.inf), miss, q


def first_least_sorted(rows: np.ndarray, values: np.ndarray, n: int) -> np.ndarray:
    """For group keys ``rows`` in ascending order: per group ``0..n-1`` the index (into
    ``rows``) of its least value, the first on ties; −1 for a group with no members or
    only infinite values. Segment reductions over the sorted keys, not ``ufunc.at``.

    >>> first_least_sorted(np.array([0, 0, 2, 2]), np.array([3.0, 1.0, np.inf, 5.0]), 3).tolist()
    [1, -1, 3]
    """
    out = np.full(n, -1, dtype=np.int64)
    if len(rows) == 0:
        return out
    starts = np.flatnonzero(np.concatenate(([True], rows[1:] != rows[:-1])))
    least = np.minimum.reduceat(values, starts)
    segment = np.repeat(np.arange(len(starts)), np.diff(np.append(starts, len(rows))))
    at = np.where(values == least[segment], np.arange(len(rows)), len(rows))
    first = np.minimum.reduceat(at, starts)
    finite = np.isfinite(least)
    out[rows[starts[finite]]] = first[finite]
    return out


def step(h: Hull3, eg3: Edges3, v: np.ndarray, p: np.ndarray, tang: np.ndarray,
          limit: np.ndarray, exclude: np.ndarray, want: np.ndarray, face: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray]:
    """For traces at vertices ``v`` from points ``p`` along ``tang``: the first arc of
    the vertex's region met, among out-edges selected by the mask ``want`` (per edge),
    leaving out the undirected edge ``exclude`` and the arcs ending at the face ``face``
    (≥ 0 for a trace starting at that face's normal, a corner of the region);
    returns (edge id or −1, meeting point)."""
    rows, cand = expand(h.degree[v], h.start[v])
    fr = face[rows]
    keep = want[cand] & (h.und[cand] != exclude[rows])
    keep &= (fr < 0) | ((h.ef[cand] != fr) & (h.eg[cand] != fr))
    rows, cand = rows[keep], cand[keep]
    theta, miss, q = _arc_hits(h, eg3, rows, cand, p, tang, limit)
    # the first arc met inside; failing that (a point a rounding error outside its
    # region), the arc met least far outside
    met = np.isfinite(theta)
    score = np.where(miss <= 1e-12, theta, np.where(met & (miss <= _RELAXED), 10.0 + miss, np.inf))
    best = first_least_sorted(rows, score, len(v))
    found = best >= 0
    if not found.any():
        return np.full(len(v), -1, dtype=np.int64), unit(p)
    b = np.maximum(best, 0)
    edge = np.where(found, cand[b], -1)
    point = np.where(found[:, None], q[b], p)
    return edge, unit(point)


class Roller:
    """The quasi-static roll downhill: which faces are stable, and where anything ends.

    h: the hull; eg3: its edge geometry; W: (n, 3) unit directions from the centre to
    the hull points; tol: how far (m) inside its face the centre's foot must lie for
    the face to be stable.

    stable: (F,) the faces that are minima. lands: (F,) where a roll from each face
    ends rolling over edges alone (a stable face, or a face that pivots about a
    corner). :meth:`sinks` and :meth:`roll` follow rolls to their stable faces.
    """

    def __init__(self, h: Hull3, eg3: Edges3, W: np.ndarray, tol: float) -> None:
        self.h, self.eg3, self.W, self.tol = h, eg3, W, tol
        nF = len(h.normals)
        A, D, n = h.edge_start, h.edge_vector, h.left_normal
        self.length = np.sqrt(h.edge_length2)
        self.foot = np.take(h.heights, h.ef)[:, None] * n
        rel = self.foot - A
        s = dot(cross(D, rel), n) / self.length  # signed, positive inside
        self.margin = np.full(nF, np.inf)
        np.minimum.at(self.margin, h.ef, s)
        self.stable = self.margin > tol
        self._memo = np.where(self.stable, np.arange(nF), -1)  # sinks found so far
        # an unstable face tips over the point of its boundary nearest the foot
        L = self.length
        tau = np.clip(dot(rel, D) / (L * L), 0.0, 1.0)
        off = tau[:, None] * D
        off += A
        off -= self.foot  # A + tau D − foot
        dist = np.sqrt(dot(off, off))  # = np.linalg.norm(off, axis=1), bit for bit
        tip = group_first(h.ef, dist, nF)
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
            p = unit(np.asarray(point, dtype=float).copy())
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
            tang = unit(dot(w, pa)[:, None] * pa - w)
            edge, q = step(h, eg3, va, pa, tang, np.full(len(rolling), np.pi),
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
            towards_f = np.where(eg3.saddle[e], dot(q, eg3.toward_f[e]) > 0,
                                 h.heights[fa] <= h.heights[ga])
            slid = rolling[sliding]
            cur[slid] = np.where(towards_f, fa, ga)[sliding]
            in_region[slid] = False
            crossing = ~lost & ~sliding
            # a crossing at the arc's very end lands on that face's normal: the body now
            # rests on the face (a symmetric body rolls exactly through it)
            on_f = crossing & (1.0 - dot(q, h.normals[fa]) <= _CORNER)
            on_g = crossing & ~on_f & (1.0 - dot(q, h.normals[ga]) <= _CORNER)
            landed = on_f | on_g
            cur[rolling[landed]] = np.where(on_f, fa, ga)[landed]
            in_region[rolling[landed]] = False
            crossing &= ~landed
            cr = rolling[crossing]
            v[cr], p[cr], exclude[cr] = h.eb[e[crossing]], q[crossing], h.und[e[crossing]]
            start_face[rolling[~lost]] = -1
        raise StabilityError("the resting poses could not be resolved: a roll never ends "
                             "(a degenerate hull?)")

    def sinks(self, faces: np.ndarray) -> np.ndarray:
        """The stable face each of ``faces`` ends up on (remembered once rolled)."""
        faces = np.asarray(faces, dtype=np.int64)
        todo = unique(faces[self._memo[faces] < 0])
        if len(todo):
            out = self.roll(face=todo)
            if np.any(out < 0):
                raise StabilityError("a roll from a face of the hull was lost "
                                     "(degenerate hull)")
            self._memo[todo] = out
        return self._memo[faces]


