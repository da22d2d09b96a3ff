"""Separatrices around a many-cornered face, advanced in one vectorised move.

A finely tessellated round face (the cap of a cylinder, a coin's rim) is one point
``n_F`` on the sphere of directions, ringed by the thin regions of its corners. A
separatrix traced uphill near it (:mod:`.basins`) crosses those regions one after the
other — 2,500 steps around a 2,500-gon — and a loop of one vectorised step per
crossing spends its time in Python overhead, not arithmetic.

Each crossing is a central projection: in the region of corner ``v`` the trace moves
on great circles through ``w`` (the direction of ``v`` from the centre of mass), so
it meets the great circle with pole ``k`` at ``±(w (k·p) − p (k·w))``, a *linear*
map of the point ``p`` it came in at. The run of crossings around the face is
therefore a product of 3 × 3 matrices, and all its points follow at once from the
prefix products (a doubling scan, ``log₂`` rounds of batched matmuls).

The run is speculative: the trace may leave the ring anywhere, or reach a maximum.
Every predicted point is checked by the ordinary step (:func:`.rolling.step`), applied
to all of them together; the run is accepted up to the first point where the step
disagrees, and the ordinary loop carries on from there. So the answer is the
step-by-step answer; only the number of Python iterations changes. Runs grow
geometrically (64, 256, … crossings) so a ring left early costs little.

Along *strips* of thin regions of few corners (a tilted cylinder's side, where no
face has many corners) and for the last few traces, :meth:`Fans.climbs` predicts each
trace's crossings in plain Python (:func:`.ahead.climb`: which arc the great circle
toward ``w`` leaves a region by is a sign test at the arcs' ends, and the crossing
point the same linear map) and checks the runs of all of them by one ordinary step
over every predicted point, taken up to each one's first disagreement. On a box
united with a tilted cylinder (200k triangles) the trace fell from 0.16 s (228 table
strips, 303 runs, 255 loop steps) to about 0.04 s.
"""

from __future__ import annotations

import numpy as np

from ...arrays import around, dot, unit
from .ahead import Scalars, climb, scalars
from .hull import Hull3
from .rolling import Edges3, arc_sides, step

__all__ = ["FAN_CORNERS", "prefix_products", "Fans"]

FAN_CORNERS = 16  # faces with fewer corners are crossed by the ordinary step
_FIRST_RUN = 64  # crossings predicted in a first run; each further run is 4× longer
_STRIP_LONGEST = 4096  # crossings predicted along a strip at most
_AGREE = 1e-9  # predicted and stepped points further apart than this (rad) end the run


def prefix_products(M: np.ndarray) -> np.ndarray:
    """Inclusive prefix products ``Q[j] = M[j] @ M[j-1] @ … @ M[0]`` of (K, 3, 3)
    matrices, each scaled by a positive factor (projective maps: only directions count).

    >>> M = np.stack([np.diag([1.0, 2.0, 3.0]), np.diag([2.0, 2.0, 2.0]), np.eye(3)])
    >>> Q = prefix_products(M)
    >>> bool(np.allclose(Q[2] / Q[2, 0, 0], np.diag([1.0, 2.0, 3.0])))
    True
    """
    Q = M.copy()
    shift = 1
    while shift < len(Q):
        Q[shift:] = Q[shift:] @ Q[:-shift]
        Q /= np.abs(Q).max(axis=(1, 2), keepdims=True)
        shift *= 2
    return Q


class Fans:
    """Speculative runs of a separatrix around many-cornered faces of a hull.

    h, eg3: the hull and its edge geometry; W: (n, 3) unit directions of the hull
    points from the centre; ismax: (n,) points no region flows into (a trace ends
    there); near: (E,) the arcs a trace may cross (as in :func:`.basins.trace_basins`).
    """

    def __init__(self, h: Hull3, eg3: Edges3, W: np.ndarray, ismax: np.ndarray,
                 near: np.ndarray) -> None:
        self.h, self.eg3, self.W, self.ismax, self.near = h, eg3, W, ismax, near
        self.corner_count = np.bincount(h.ef, minlength=len(h.normals))
        self._rings: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self._scalars: Scalars | None = None

    def ring(self, face: int) -> tuple[np.ndarray, np.ndarray]:
        """The corners of ``face`` counter-clockwise about its normal, and the directed
        edges from each corner to the next (the face on their left)."""
        if face not in self._rings:
            h = self.h
            edges = np.flatnonzero(h.ef == face)
            edges = edges[around(h.X[h.ea[edges]], h.normals[face])]
            self._rings[face] = (h.ea[edges], edges)
        return self._rings[face]

    def chain(self, entered: int, face: int) -> tuple[np.ndarray, np.ndarray] | None:
        """After crossing the directed edge ``entered`` (into the region of its end), the
        corners met going on around ``face`` and the edges crossed from each; None when
        ``entered`` does not border ``face``."""
        h = self.h
        corners, edges = self.ring(face)
        m = len(corners)
        start = np.flatnonzero(corners == h.eb[entered])
        if len(start) == 0:
            return None
        i0 = int(start[0])
        j = np.arange(m - 1)
        if h.ef[entered] == face:  # the face on the left: on around it, counter-clockwise
            return corners[(i0 + j) % m], edges[(i0 + j) % m]
        if h.eg[entered] == face:  # on the right: clockwise, along the reversed edges
            return corners[(i0 - j) % m], h.twin[edges[(i0 - j - 1) % m]]
        return None

    def advance(self, v: int, p: np.ndarray, entered: int, face: int
                ) -> tuple[np.ndarray, int, int] | None:
        """Run a trace at corner ``v`` (point ``p``, come in over the directed edge
        ``entered``) on around ``face`` for as long as the ordinary step agrees.

        Returns the points it passed through (k + 1, 3), ``p`` first, the corner it is
        at and the edge it last crossed; None when not one crossing was predicted
        right.
        """
        found = self.chain(entered, face)
        if found is None:
            return None
        corners, edges = found
        # a trace ends at the first maximum it reaches (the step takes nothing from its
        # region): no prediction past it (a cap's ring, left at its highest corner). The
        # points before it are the same, bit for bit, however long the run's table
        top = np.flatnonzero(self.ismax[corners])
        if len(top):
            corners, edges = corners[:top[0]], edges[:top[0]]
        return self.run(p, entered, corners, edges) if len(corners) else None

    def climbs(self, traces: list[int], v: np.ndarray, p: np.ndarray, last: np.ndarray
               ) -> list[tuple[int, tuple[np.ndarray, int, int] | None]]:
        """Run the traces ``traces`` (at vertices ``v``, points ``p``, having crossed the
        directed edges ``last``; arrays over all traces) on along the crossings
        :func:`.ahead.climb` predicts for each in plain Python, all of them checked by one
        ordinary step (:func:`.rolling.step`) over every predicted point and taken up to
        each trace's first disagreement, as :meth:`run` takes one; 64, 256, … crossings
        at a time while every one is taken. Per trace, what :meth:`advance` returns."""
        h, eg3, W = self.h, self.eg3, self.W
        if self._scalars is None:
            self._scalars = scalars(h, eg3, W, self.near)
        sc = self._scalars
        paths: dict[int, list[np.ndarray]] = {t: [p[t][None, :]] for t in traces}
        at = {t: (int(v[t]), int(last[t]), p[t]) for t in traces}
        todo, size = list(traces), _FIRST_RUN
        while todo:
            chains, edges, points = [], [], []
            for t in todo:
                vt, lt, pt = at[t]
                ce, cp = climb(sc, vt, *pt.tolist(), sc.und[lt], size)
                if ce:
                    chains.append((t, len(ce)))
                    edges += ce
                    points += cp
            if not chains:
                break
            lengths = np.array([n for _, n in chains])
            offsets = np.cumsum(lengths) - lengths
            # (the list's type given: no element's type looked at, a third less time); each
            # region's vertex is its exit edge's start (not listed by the climb: one gather)
            ks = np.array(edges, dtype=np.intp)
            vs = h.ea[ks]
            q = np.fromiter(points, dtype=float, count=len(points)).reshape(-1, 3)
            starts = np.empty_like(q)
            starts[1:] = q[:-1]
            starts[offsets] = [at[t][2] for t, _ in chains]
            prev = np.empty_like(ks)
            prev[1:] = ks[:-1]
            prev[offsets] = [at[t][1] for t, _ in chains]
            w = W[vs]
            wp = dot(starts, w)
            tang = unit(w - wp[:, None] * starts)
            limit = np.arccos(np.clip(wp, -1.0, 1.0))
            e, q_step = step(h, eg3, vs, starts, tang, limit, h.und[prev], self.near, None)
            good = ((e == ks) & ~self.ismax[vs] & (wp < 1.0 - 1e-24)
                    & (np.linalg.norm(q_step - q, axis=1) <= _AGREE))
            first_bad = np.minimum.reduceat(np.where(good, len(vs), np.arange(len(vs))), offsets)
            take = np.minimum(first_bad - offsets, lengths)
            todo = []
            for (t, n), o, k in zip(chains, offsets.tolist(), take.tolist()):
                if k == 0:
                    continue
                end = o + k - 1
                paths[t].append(q[o:end])
                paths[t].append(q_step[end:end + 1])
                at[t] = (int(h.eb[ks[end]]), int(ks[end]), q_step[end])
                if k == n == size and size < _STRIP_LONGEST:
                    todo.append(t)
            size *= 4
        return [(t, (np.concatenate(paths[t]), at[t][0], at[t][1]) if len(paths[t]) > 1
                 else None) for t in traces]

    def run(self, p: np.ndarray, entered: int, corners: np.ndarray, crossed: np.ndarray
            ) -> tuple[np.ndarray, int, int] | None:
        """Run a trace at point ``p`` (come in over ``entered``) through the predicted
        ``corners``, crossing ``crossed``, for as long as the ordinary step agrees (see
        :meth:`advance`)."""
        h, eg3, W = self.h, self.eg3, self.W
        path = [p[None, :]]
        done = 0
        size = _FIRST_RUN
        while done < len(corners):
            vs, ks = corners[done:done + size], crossed[done:done + size]
            w, k = W[vs], eg3.pole[ks]
            M = w[:, :, None] * k[:, None, :]
            M -= dot(k, w)[:, None, None] * np.eye(3)
            q = (prefix_products(M) @ p)
            after_f, before_g = arc_sides(h, k, ks)
            q *= np.sign(dot(q, after_f + before_g))[:, None]
            q = unit(q)
            starts = np.concatenate((p[None, :], q[:-1]))
            prev = np.concatenate(([entered], ks[:-1]))
            wp = dot(starts, w)
            tang = unit(w - wp[:, None] * starts)
            limit = np.arccos(np.clip(wp, -1.0, 1.0))
            e, q_step = step(h, eg3, vs, starts, tang, limit, h.und[prev], self.near, None)
            good = ((e == ks) & ~self.ismax[vs] & (wp < 1.0 - 1e-24)
                    & (np.linalg.norm(q_step - q, axis=1) <= _AGREE))
            bad = np.flatnonzero(~good)
            take = int(bad[0]) if len(bad) else len(vs)
            if take == 0:
                break
            path.append(q[:take - 1])
            path.append(q_step[take - 1:take])
            p, entered = q_step[take - 1], int(ks[take - 1])
            done += take
            if take < len(vs):
                break
            size *= 4
        if done == 0:
            return None
        return np.concatenate(path), int(h.eb[entered]), entered
