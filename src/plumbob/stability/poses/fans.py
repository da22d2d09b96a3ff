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

The same runs go along *strips* of thin regions of few corners (a tilted cylinder's
side, where no face has many corners): there the edge sequence is predicted by a
table, per arc a trace may cross, of the arc a trace entering the next region from
the arc's middle leaves by (one step over all such arcs, :meth:`Fans.strip`), and
checked the same way. On a box united with a tilted cylinder (182k triangles) the
loop's 1,555 steps fell to about 230.
"""

from __future__ import annotations

import numpy as np

from ...arrays import around, dot, unit
from .ahead import predict
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
        self._exit_table: tuple[list[int], list[int]] | None = None

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
        return self.run(p, entered, *found)

    def strip_chain(self, entered: int, longest: int) -> tuple[np.ndarray, np.ndarray] | None:
        """After crossing the directed edge ``entered``, the corners and edges the trace is
        predicted to meet next, each exit the one a trace from the middle of its entry arc
        takes (:meth:`_exits`); at most ``longest``; None when none is predicted."""
        exits, eb = self._exits()
        corners, crossed = [], []
        k = entered
        for _ in range(longest):
            nxt = exits[k]
            if nxt < 0:
                break
            corners.append(eb[k])
            crossed.append(nxt)
            k = nxt
        if not crossed:
            return None
        return np.array(corners, dtype=np.int64), np.array(crossed, dtype=np.int64)

    def _exits(self) -> tuple[list[int], list[int]]:
        """(E,) per directed edge a trace may cross, the edge a trace entering the region
        of its end from the middle of its arc leaves by (−1: none, or not such an edge):
        the prediction a strip of thin regions (a cylinder's side) is run along with;
        and (E,) the edges' ends."""
        if self._exit_table is None:
            h, W = self.h, self.W
            k = np.flatnonzero(self.near)
            v = h.eb[k]
            p = unit(h.normals[h.ef[k]] + h.normals[h.eg[k]])
            w = W[v]
            wp = dot(p, w)
            tang = unit(w - wp[:, None] * p)
            limit = np.arccos(np.clip(wp, -1.0, 1.0))
            e, _ = step(h, self.eg3, v, p, tang, limit, h.und[k], self.near,
                        np.full(len(k), -1))
            table = np.full(len(h.ea), -1, dtype=np.int64)
            table[k] = np.where(self.ismax[v], -1, e)
            # as lists: the chains follow them one crossing at a time
            self._exit_table = (table.tolist(), h.eb.tolist())
        return self._exit_table

    def ahead_chain(self, v: int, p: np.ndarray, entered: int, longest: int
                    ) -> tuple[np.ndarray, np.ndarray] | None:
        """As :meth:`strip_chain`, the crossings a trace at ``v`` (at ``p``, having crossed
        ``entered``) is predicted to make, stepped one by one in plain Python floats
        (:func:`.ahead.predict`) instead of read from a table built for every arc."""
        h = self.h
        corners, crossed, _ = predict(h, self.eg3, self.W, self.near, v, p,
                                      int(h.und[entered]), longest, self.ismax)
        if not crossed:
            return None
        return np.array(corners, dtype=np.int64), np.array(crossed, dtype=np.int64)

    def strip(self, v: int, p: np.ndarray, entered: int, table: bool = True,
              ahead: bool = False) -> tuple[np.ndarray, int, int] | None:
        """As :meth:`advance`, along the predicted exits (:meth:`strip_chain`, with
        ``table``) or, where those are not taken, with ``ahead``, along the crossings
        :meth:`ahead_chain` predicts; 64, 256, … crossings at a time while every one is
        taken."""
        paths = []
        size = _FIRST_RUN
        while True:
            found, moved = self.strip_chain(entered, size) if table else None, None
            if found is not None and found[0][0] == v:
                moved = self.run(p, entered, *found)
            if moved is None and ahead:
                found = self.ahead_chain(v, p, entered, size)
                moved = None if found is None else self.run(p, entered, *found)
            if moved is None:
                break
            path, v, entered = moved
            paths.append(path if not paths else path[1:])
            p = path[-1]
            if len(path) - 1 < len(found[1]) or size >= _STRIP_LONGEST:
                break
            size *= 4
        if not paths:
            return None
        return np.concatenate(paths), v, entered

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
            e, q_step = step(h, eg3, vs, starts, tang, limit, h.und[prev], self.near,
                             np.full(len(vs), -1))
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
