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

from typing import NamedTuple

import numpy as np

from ...arrays import cross, dot, expand, group_first, unique, unit
from ...blockwise import blockwise
from ...errors import StabilityError
from .ahead import Scalars, Tables, roam, scalars
from .hull import Hull3

__all__ = ["Edges3", "arc_sides", "edge_geometry", "first_least_sorted", "step", "Roller"]

_THETA_EPS = 1e-12  # rad: intersections closer than this to a trace's start are its own arc
_RELAXED = 1e-4  # how far outside an arc (sine of the angle) a trace may still cross it
_CORNER = 5e-19  # 1 − cos of the angle (1e-9 rad) within which a roll is at an arc's end
_RUN_AFTER = 4  # loop steps after which rolls in regions also run ahead (:meth:`Roller.ahead`)
_RUN_FEW = 32  # ... when no more rolls than this are in regions
_RUN_FIRST = 32  # crossings predicted in a first run; each further one is 4× longer
_RUN_LONGEST = 2048  # crossings predicted in one run at most
_RUN_RETRY = 8  # loop steps before a roll whose run failed tries again
_AGREE = 1e-9  # predicted and stepped points further apart than this (rad) end a run


class Edges3(NamedTuple):
    """Per directed edge of a hull: the Gauss-map arc the flow crosses, and where the
    centre's foot on the edge's left face lies against the edge (for the roll).

    Only what every edge needs is kept for every edge. The saddle's direction and
    height are kept for the saddle edges (``saddles``), the rows the traces and rolls
    ask them for; the arc's ends are made for the edges a step tries
    (:func:`arc_sides`).
    """

    pole: np.ndarray  # (E, 3) unit edge direction: the arc n_F → n_G turns about it
    t: np.ndarray  # (E,) foot of c on the edge's line, as a fraction from a to b
    saddle: np.ndarray  # (E,) bool: the arc holds a saddle
    inset: np.ndarray  # (E,) how far the foot of c on face F lies inside this edge, m
    tip_distance: np.ndarray  # (E,) from that foot to the nearest point of the edge, m
    # that nearest point, ``along`` the edge from a (m) of ``length``, as the roll asks it
    # (within ``tol`` of an end a face pivots about that corner): only at a face's tip
    # edge, so only the answers are kept, not two more arrays of every edge's distances
    tip_inside: np.ndarray  # (E,) bool: tol < along < length − tol
    tip_at_a: np.ndarray  # (E,) bool: along ≤ tol
    saddles: np.ndarray  # (S,) the directed edges holding a saddle, ascending
    spoint: np.ndarray  # (S, 3) unit direction from c square to the edge line
    sheight: np.ndarray  # (S,) |c to the edge line|, m
    toward_f: np.ndarray  # (S, 3) spoint × pole: q·toward_f > 0 when q lies on n_F's side
    tol: float  # m: the roll's tolerance ``tip_inside`` and ``tip_at_a`` were measured with

    def saddle_rows(self, edges: np.ndarray) -> np.ndarray:
        """The rows of ``spoint``, ``sheight`` and ``toward_f`` for the saddle edges
        ``edges``."""
        return np.searchsorted(self.saddles, edges)

    def toward_f_at(self, edges: np.ndarray) -> np.ndarray:
        """(k, 3) ``toward_f`` of ``edges``; zero rows for edges holding no saddle."""
        if len(self.saddles) == 0:
            return np.zeros((len(edges), 3))
        rows = np.minimum(self.saddle_rows(edges), len(self.saddles) - 1)
        found = self.saddles.take(rows) == edges
        return np.where(found[:, None], self.toward_f.take(rows, axis=0), 0.0)


def arc_sides(h: Hull3, pole: np.ndarray, edges: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For directed edges ``edges`` with poles ``pole`` (k, 3): ``after_f = pole × n_F``
    (q·after_f ≥ 0 when q lies past n_F on the arc) and ``before_g = n_G × pole``
    (q·before_g ≥ 0 when q lies before n_G)."""
    return _sides(pole, np.take(h.normals, np.take(h.ef, edges), axis=0),
                  np.take(h.normals, np.take(h.eg, edges), axis=0))


def _sides(pole: np.ndarray, n_f: np.ndarray, n_g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`arc_sides` from the arcs' poles and their faces' normals."""
    return cross(pole, n_f), cross(n_g, pole)


def _foot_direction(A: np.ndarray, D: np.ndarray, t: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """The unit direction from the centre square to the lines ``A + t D`` (k, 3), at
    their feet ``t``, and its length (m)."""
    s = t[:, None] * D
    s += A  # the foot A + t D ...
    height = np.sqrt(dot(s, s))  # = np.linalg.norm(s, axis=1), bit for bit
    s /= height[:, None]  # ... and its direction
    return s, height


def edge_geometry(h: Hull3, tol: float) -> Edges3:
    """The Gauss-map arc of every directed edge of ``h``, whether it holds a saddle (the
    direction from the centre square to the edge's line lies on the arc and the foot
    lies strictly inside the edge), and the foot of the centre on the edge's left face
    against the edge, its nearest point judged within ``tol`` (m: the roll's, as
    :class:`Roller` is given it) of the edge's ends. Row by row, in blocks
    (:func:`~plumbob.blockwise.blockwise`)."""
    X, N, H = h.X, h.normals, h.heights
    ea, eb, ef, eg = h.ea, h.eb, h.ef, h.eg
    # coordinate columns: contiguous gathers and arithmetic on contiguous arrays, the
    # row formulas' operations in the same order (dot: (x + y) + z; cross: the same
    # differences of products), so the same bits
    Xc, Nc = np.ascontiguousarray(X.T), np.ascontiguousarray(N.T)

    def rows(r: slice) -> tuple[np.ndarray, ...]:
        ia, ib, jf = ea[r], eb[r], ef[r]
        a0, a1, a2 = (np.take(Xc[k], ia) for k in range(3))
        d0, d1, d2 = (np.take(Xc[k], ib) for k in range(3))
        d0 -= a0
        d1 -= a1
        d2 -= a2
        L2 = d0 * d0
        L2 += d1 * d1
        L2 += d2 * d2  # dot(D, D)
        t = a0 * d0
        t += a1 * d1
        t += a2 * d2
        np.negative(t, out=t)
        t /= L2  # -(A·D) / |D|²
        L = np.sqrt(L2)
        pole = np.empty((len(t), 3))
        np.divide(d0, L, out=pole[:, 0])
        np.divide(d1, L, out=pole[:, 1])
        np.divide(d2, L, out=pole[:, 2])
        # a saddle needs the foot strictly inside the edge (a few % of a smooth hull's
        # edges): the arc test only for those rows, the same numbers row by row
        inside = np.flatnonzero((t > 0) & (t < 1))
        saddle = np.zeros(len(t), dtype=bool)
        if len(inside):
            A = np.stack([np.take(c, inside) for c in (a0, a1, a2)], axis=1)
            D = np.stack([np.take(c, inside) for c in (d0, d1, d2)], axis=1)
            s, _ = _foot_direction(A, D, np.take(t, inside))
            edges = np.arange(r.start, r.stop)[inside]
            after_f, before_g = _sides(np.take(pole, inside, axis=0),
                                       np.take(N, np.take(ef, edges), axis=0),
                                       np.take(N, np.take(eg, edges), axis=0))
            saddle[inside] = (dot(s, after_f) >= 0) & (dot(s, before_g) >= 0)
        n0, n1, n2 = (np.take(Nc[k], jf) for k in range(3))
        # the centre's foot on face F (height × normal): how far inside this edge, and
        # its nearest point on the edge; rel = foot − A
        hf = np.take(H, jf)
        f0, f1, f2 = hf * n0, hf * n1, hf * n2
        r0, r1, r2 = f0 - a0, f1 - a1, f2 - a2
        # inset = (D × rel)·n / L, signed, positive inside
        inset = d1 * r2
        inset -= d2 * r1
        inset *= n0
        c = d2 * r0
        c -= d0 * r2
        c *= n1
        inset += c
        c = d0 * r1
        c -= d1 * r0
        c *= n2
        inset += c
        inset /= L
        tau = r0 * d0
        tau += r1 * d1
        tau += r2 * d2
        tau /= L2
        np.clip(tau, 0.0, 1.0, out=tau)
        # A + tau D − foot, component by component
        o = tau * d0
        o += a0
        o -= f0
        dist = o * o
        o = tau * d1
        o += a1
        o -= f1
        o *= o
        dist += o
        o = tau * d2
        o += a2
        o -= f2
        o *= o
        dist += o
        tip_distance = np.sqrt(dist)  # = np.linalg.norm(off, axis=1), bit for bit
        along = tau * L
        tip_inside = along > tol
        tip_inside &= along < L - tol
        return pole, t, saddle, inset, tip_distance, tip_inside, along <= tol

    pole, t, saddle, inset, tip, tip_inside, tip_at_a = blockwise(len(ea), rows)
    saddles = np.flatnonzero(saddle)
    A = np.take(X, np.take(ea, saddles), axis=0)
    D = np.take(X, np.take(eb, saddles), axis=0)
    D -= A
    s, height = _foot_direction(A, D, np.take(t, saddles))
    toward_f = cross(s, np.take(pole, saddles, axis=0))
    return Edges3(pole, t, saddle, inset, tip, tip_inside, tip_at_a, saddles, s, height,
                  toward_f, float(tol))


def _arc_hits(h: Hull3, eg3: Edges3, rows: np.ndarray, cand: np.ndarray, p: np.ndarray,
              tang: np.ndarray, limit: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Where the great circle ``cos θ p + sin θ tang`` (θ > 0) first meets each candidate arc.

    rows: trace of each candidate; cand: directed edge id; p, tang: per trace.
    Returns θ (inf when the great circle is not met before ``limit``), how far outside
    the arc the meeting point lies (0 inside; sines of angles) and the meeting points.
    """
    # rows gathered with ndarray.take (fancy indexing of rows costs about 3x as much,
    # and np.take's wrapper twice the method on a step's few hundred rows)
    k = eg3.pole.take(cand, axis=0)
    pr, tr = p.take(rows, axis=0), tang.take(rows, axis=0)
    a, b = dot(pr, k), dot(tr, k)
    theta = np.arctan2(-a, b)
    theta = np.where(theta <= _THETA_EPS, theta + np.pi, theta)
    q = np.cos(theta)[:, None] * pr + np.sin(theta)[:, None] * tr
    # q·after_f = q·(k × n_F) = n_F·(q × k) and q·before_g = q·(n_G × k) = −n_G·(q × k):
    # one cross product for both sides
    qk = cross(q, k)
    inside_f = dot(qk, h.normals.take(h.ef[cand], axis=0))
    inside_g = dot(qk, h.normals.take(h.eg[cand], axis=0))
    miss = np.maximum(0.0, -np.minimum(inside_f, -inside_g))
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
    if n == 1:  # one group (a lone trace): argmin is the first least, NaN and inf are none
        first = int(np.argmin(values))
        if np.isfinite(values[first]):
            out[0] = first
        return out
    new = np.concatenate(([True], rows[1:] != rows[:-1]))
    starts = new.nonzero()[0]  # the methods: np.flatnonzero's and np.cumsum's wrappers
    least = np.minimum.reduceat(values, starts)  # cost as much as the work on a few rows
    segment = new.cumsum() - 1
    at = np.where(values == least[segment], np.arange(len(rows)), len(rows))
    first = np.minimum.reduceat(at, starts)
    finite = np.isfinite(least)
    out[rows[starts[finite]]] = first[finite]
    return out


def step(h: Hull3, eg3: Edges3, v: np.ndarray, p: np.ndarray, tang: np.ndarray,
          limit: np.ndarray, exclude: np.ndarray, want: np.ndarray, face: np.ndarray | None
          ) -> tuple[np.ndarray, np.ndarray]:
    """For traces at vertices ``v`` from points ``p`` along ``tang``: the first arc of
    the vertex's region met, among out-edges selected by the mask ``want`` (per edge),
    leaving out the undirected edge ``exclude`` and the arcs ending at the face ``face``
    (≥ 0 for a trace starting at that face's normal, a corner of the region; None:
    none does); returns (edge id or −1, meeting point)."""
    rows, cand = expand(h.degree[v], h.start[v])
    keep = want[cand] & (h.und[cand] != exclude[rows])
    if face is not None and face.max(initial=-1) >= 0:  # some start at a face's normal
        fr = face[rows]
        keep &= (fr < 0) | ((h.ef[cand] != fr) & (h.eg[cand] != fr))
    rows, cand = rows[keep], cand[keep]
    theta, miss, q = _arc_hits(h, eg3, rows, cand, p, tang, limit)
    # the first arc met inside; failing that (a point a rounding error outside its
    # region), the arc met least far outside
    met = np.isfinite(theta)
    score = np.where(miss <= 1e-12, theta, np.where(met & (miss <= _RELAXED), 10.0 + miss, np.inf))
    best = first_least_sorted(rows, score, len(v))
    found = best >= 0
    if not np.count_nonzero(found):
        return np.full(len(v), -1, dtype=np.int64), unit(p)
    b = np.maximum(best, 0)
    edge = np.where(found, cand[b], -1)
    point = np.where(found[:, None], q.take(b, axis=0), p)
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
        self.margin = np.full(nF, np.inf)
        np.minimum.at(self.margin, h.ef, eg3.inset)
        self.stable = self.margin > tol
        self._memo = np.where(self.stable, np.arange(nF), -1)  # sinks found so far
        self._scalars: Scalars | None = None  # for runs ahead (:meth:`ahead`)
        self._tables: Tables | None = None
        # an unstable face tips over the point of its boundary nearest the foot
        tip = group_first(h.ef, eg3.tip_distance, nF)
        self.tip_edge = tip
        if eg3.tol != tol:
            raise ValueError(f"edge geometry measured to {eg3.tol} m, not the roll's {tol} m")
        self.pivots = ~self.stable & ~eg3.tip_inside[tip]
        self._tip_at_a = eg3.tip_at_a[tip]  # a pivot's corner: the tip edge's start, else its end
        # rolls over edges chain faces: jump along them to a stable face or a pivot (the
        # chains' ends, which point to themselves); only the faces that roll over an edge
        # (a few % of a smooth hull's) jump, each until it points at an end
        move = np.flatnonzero(~(self.stable | self.pivots))
        over = np.arange(nF)
        over[move] = h.eg[tip[move]]
        for _ in range(64):
            if len(move) == 0:
                break
            nxt = over[move]
            jumped = over[nxt]
            over[move] = jumped
            move = move[jumped != nxt]
        else:
            raise StabilityError("the resting poses could not be resolved: rolling over "
                                 "edges never ends (a degenerate hull?)")
        self.lands = over

    def pivot_vertex(self, faces: np.ndarray) -> np.ndarray:
        """The corner each of the pivoting ``faces`` tips over (the end of its tip edge
        nearest the centre's foot)."""
        tip = self.tip_edge[faces]
        return np.where(self._tip_at_a[faces], self.h.ea[tip], self.h.eb[tip])

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
        no_run = np.zeros(k, dtype=np.int64)  # the loop step a run ahead may next start
        for count in range(4 * len(h.normals) + 16):
            at_face = (alive & ~in_region).nonzero()[0]
            if len(at_face):
                f = self.lands[cur[at_face]]  # over edges, as far as that goes
                done = self.stable[f]
                result[at_face[done]] = f[done]
                alive[at_face[done]] = False
                piv, f = at_face[~done], f[~done]  # over a corner: pivot about it
                v[piv] = self.pivot_vertex(f)
                p[piv] = h.normals[f]
                start_face[piv] = f
                exclude[piv] = -1
                in_region[piv] = True
            rolling = (alive & in_region).nonzero()[0]
            if len(rolling) == 0:
                if not np.count_nonzero(alive):
                    return result
                continue
            va, pa = v[rolling], p[rolling]
            w = self.W.take(va, axis=0)
            tang = unit(dot(w, pa)[:, None] * pa - w)
            edge, q = step(h, eg3, va, pa, tang, np.full(len(rolling), np.pi),
                            exclude[rolling], far, start_face[rolling])
            lost = edge < 0
            from_face = start_face[rolling]
            # lost leaving a corner along its own arc: over the face's nearest edge
            rescue = lost & (from_face >= 0)
            if np.count_nonzero(rescue):
                cur[rolling[rescue]] = h.eg[self.tip_edge[from_face[rescue]]]
                in_region[rolling[rescue]] = False
            gone = lost & (from_face < 0)
            alive[rolling[gone]] = False
            e = np.maximum(edge, 0)
            sliding = ~lost & (eg3.t[e] < 1)
            # on a sliding arc: to the side of its saddle, or to its lower end
            fa, ga = h.ef[e], h.eg[e]
            towards_f = np.where(eg3.saddle[e],
                                 dot(q, eg3.toward_f_at(e)) > 0,
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
            if count >= _RUN_AFTER and len(rolling) <= _RUN_FEW:
                # a few long rolls, each step mostly overhead: run them ahead
                ready = rolling[alive[rolling] & (no_run[rolling] <= count)]
                cur[ready[in_region[ready]]] = -1
                for t, moved in self.ahead(ready.tolist(), cur, v, p, exclude, start_face, far):
                    if moved is None:
                        no_run[t] = count + _RUN_RETRY
                        continue
                    cur[t], v[t], p[t], exclude[t] = moved
                    in_region[t] = moved[0] < 0
                    start_face[t] = -1
        raise StabilityError("the resting poses could not be resolved: a roll never ends "
                             "(a degenerate hull?)")

    def ahead(self, rolls: list[int], cur: np.ndarray, v: np.ndarray, p: np.ndarray,
              exclude: np.ndarray, start_face: np.ndarray, far: np.ndarray
              ) -> list[tuple[int, tuple[int, int, np.ndarray, int] | None]]:
        """The rolls ``rolls`` — at the faces ``cur`` (≥ 0), else in the regions of ``v`` at
        ``p``, having last crossed the undirected edges ``exclude``, come from the faces
        ``start_face`` (arrays over all rolls; ``far``: the arcs a roll may cross) — run on
        for as long as :func:`step` agrees with the moves :func:`.ahead.roam` predicts:
        every predicted region move of all of them is stepped at once, and each run is
        taken up to the first move where the step leaves by another arc, meets it more
        than 1e-9 rad from the prediction, or goes on differently (slides to the other
        face, lands or not). Runs of 32, 128, … moves while every one is taken. Per roll,
        its new (face, vertex, point, excluded edge) as the loop would have left it after
        those moves — a face ≥ 0 to go on from there, else a region — or None when not
        one move was taken."""
        h, eg3, W = self.h, self.eg3, self.W
        if self._scalars is None:
            self._scalars = scalars(h, eg3, W, far)
            saddles = eg3.saddles.tolist()

            def flat(a: np.ndarray) -> memoryview:
                return memoryview(np.ascontiguousarray(a).reshape(-1))

            self._tables = Tables(flat(self.lands), flat(self.stable), flat(self.tip_edge),
                                  flat(self._tip_at_a), flat(h.heights), flat(eg3.saddle),
                                  flat(eg3.toward_f), dict(zip(saddles, range(len(saddles)))))
        sc, tables = self._scalars, self._tables
        at = {r: (int(cur[r]), int(v[r]), p[r], int(exclude[r]), int(start_face[r]))
              for r in rolls}
        moved: dict[int, tuple[int, int, np.ndarray, int]] = {}
        todo, size = list(rolls), _RUN_FIRST
        while todo:
            chains: list[tuple[int, int]] = []
            V, P, X, SF, E, Q, ends = [], [], [], [], [], [], []
            for r in todo:
                cr, vr, pr, xr, fr = at[r]
                found = roam(sc, tables, cr, vr, *pr.tolist(), xr, fr, size)
                if found[4]:
                    chains.append((r, len(found[4])))
                    for into, part in zip((V, P, X, SF, E, Q, ends), found):
                        into += part
            if not chains:
                break
            lengths = np.array([n for _, n in chains])
            offsets = np.cumsum(lengths) - lengths
            vs, es, outcome = np.array(V), np.array(E), np.array(ends)
            starts = np.array(P).reshape(-1, 3)
            predicted = np.array(Q).reshape(-1, 3)
            w = W[vs]
            tang = unit(dot(w, starts)[:, None] * starts - w)
            e, q = step(h, eg3, vs, starts, tang, np.full(len(vs), np.pi), np.array(X), far,
                        np.array(SF))
            good = (e == es) & (np.sqrt(dot(q - predicted, q - predicted)) <= _AGREE)
            # what the loop does after each of those steps: slide, land, or cross
            fa, ga = h.ef[es], h.eg[es]
            sliding = eg3.t[es] < 1
            towards_f = np.where(eg3.saddle[es], dot(q, eg3.toward_f_at(es)) > 0,
                                 h.heights[fa] <= h.heights[ga])
            on_f = 1.0 - dot(q, h.normals[fa]) <= _CORNER
            on_g = 1.0 - dot(q, h.normals[ga]) <= _CORNER
            went = np.where(sliding, np.where(towards_f, fa, ga),
                            np.where(on_f, fa, np.where(on_g, ga, -1)))
            good &= went == outcome
            first_bad = np.minimum.reduceat(np.where(good, len(vs), np.arange(len(vs))), offsets)
            take = np.minimum(first_bad - offsets, lengths)
            todo = []
            for (r, n), o, k in zip(chains, offsets.tolist(), take.tolist()):
                if k == 0:
                    continue
                last = o + k - 1
                face = int(went[last])
                edge = int(es[last])
                if face < 0:  # crossed into the next region
                    moved[r] = (-1, int(h.eb[edge]), q[last], int(h.und[edge]))
                else:  # on a face: the loop goes on from there
                    moved[r] = (face, 0, q[last], -1)
                at[r] = (*moved[r], -1)
                if k == n == size and size < _RUN_LONGEST:
                    todo.append(r)
            size *= 4
        return [(r, moved.get(r)) for r in rolls]

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


