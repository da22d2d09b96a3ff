"""Physical faces: around each stable face of the exact hull, the faces a reader calls one.

The exact hull keeps faces apart that are coplanar only to within a hair — a flat
face of a float32 STL is a handful of triangles tilted by 10⁻⁷ rad, each its own
exact face. A pose rests on a *physical* face: for a stable exact face ``s``, the
exact faces reached from ``s`` through neighbours whose corners all lie within the
tolerance of ``s``'s own plane. Measuring every corner against the plane of ``s``
(not against a neighbour's) means a chain of slivers cannot bend a curved surface
into one face, and a larger tolerance only ever adds faces: the grouping is
monotone in the tolerance, so more tolerance never gives more poses.

:func:`physical_faces` grows every stable face's physical face at once (a
breadth-first flood over all of them together, one vectorised step per ring of
neighbours) and measures, per stable face, how far the foot of the centre of mass
lies inside its physical face. Everything is relative to the centre of mass, at
the origin.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...arrays import around, cross, dot, expand, stable_order, unique
from .hull import Hull3

__all__ = ["PhysicalFaces", "physical_faces"]

#: sinks × faces up to which :func:`physical_faces` flags the (sink, face) pairs it has
#: reached (one byte each) rather than keeping them sorted and searching them
SEEN_FLAGS = 1 << 24


class PhysicalFaces(NamedTuple):
    """The physical face of every stable exact face.

    sinks: (S,) the stable exact faces. owner, face: (K,) pairs — exact face ``face[k]``
    belongs to the physical face of ``sinks[owner[k]]`` (each sink owns itself), sorted by
    owner. margin: (S,) signed distance, m, from the foot of the centre of mass (square
    below it on the sink's plane) to the physical face's boundary, positive inside.
    same: (2, L) pairs of sink indices whose physical faces take in each other's sink.
    """

    sinks: np.ndarray
    owner: np.ndarray
    face: np.ndarray
    margin: np.ndarray
    same: np.ndarray
    boundary: np.ndarray  # (B,) edge ids on the boundary of a physical face
    boundary_owner: np.ndarray  # (B,) the sink index each boundary edge belongs to

    def corners(self, h: Hull3, k: int) -> np.ndarray:
        """The corners (m, relative to the centre) of sink ``k``'s physical face,
        counter-clockwise about its outward normal."""
        pts = h.X[unique(h.ea[self.boundary[self.boundary_owner == k]])]
        return pts[around(pts, h.normals[self.sinks[k]])]


class _FaceEdges:
    """The directed edges of given exact faces, as a stable sort of every edge by its left
    face would list them. A physical face reaches a handful of the hull's faces (an egg
    of 200,000 triangles: 35 stable faces, 9 lookups) and the sort of all 600,000 edges
    costs 10 ms: each lookup first scans the edges' faces (0.5 ms); when the scans have
    cost about what the sort would (``SCANS`` of them on a large hull, fewer on a small
    one, where a scan's fixed cost weighs more), the sort is made and used."""

    SCANS = 20

    def __init__(self, h: Hull3) -> None:
        self.h = h
        self.scans_left = int(self.SCANS * len(h.ef) / (len(h.ef) + 25_000))
        self.index: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    def of(self, faces: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Pairs (row into ``faces``, edge id) — each face's edges in ascending order —
        and each face's edge count, for exact face ids ``faces`` (repeats allowed)."""
        h = self.h
        if self.index is None and self.scans_left <= 0:
            order = stable_order(h.ef)
            count = np.bincount(h.ef, minlength=len(h.normals))
            self.index = order, np.cumsum(count) - count, count
        if self.index is not None:
            order, start, count = self.index
            rows, idx = expand(count[faces], start[faces])
            return rows, order[idx], count[faces]
        self.scans_left -= 1
        wanted = np.zeros(len(h.normals), dtype=bool)
        wanted[faces] = True
        edges = np.flatnonzero(wanted[h.ef])
        edges = edges[stable_order(h.ef[edges])]  # by face; ascending ids within each
        ranked = h.ef[edges]
        first = np.searchsorted(ranked, faces)
        count = np.searchsorted(ranked, faces, side="right") - first
        rows, idx = expand(count, first)
        return rows, edges[idx], count


def _distinct(keys: np.ndarray) -> np.ndarray:
    """The distinct values of an integer array, sorted (a sort, no hashing)."""
    keys = np.sort(keys)
    return keys[np.concatenate(([True], keys[1:] != keys[:-1]))] if len(keys) else keys


def _member(keys: np.ndarray, known: np.ndarray) -> np.ndarray:
    """Which of ``keys`` are in the sorted array ``known``."""
    pos = np.minimum(np.searchsorted(known, keys), max(len(known) - 1, 0))
    return (known[pos] == keys) if len(known) else np.zeros(len(keys), dtype=bool)


def _mean_corners(h: Hull3, rows: np.ndarray, edges: np.ndarray, count: np.ndarray
                  ) -> np.ndarray:
    """(k, 3) the mean corner of each of k faces, m, from their edges
    (:meth:`_FaceEdges.of`' ``rows``, ``edges``, ``count``): each face's corners summed
    in the order of its edges, as ``np.add.at`` over all edges would, for these faces
    alone."""
    corners = np.take(h.X, np.take(h.ea, edges), axis=0)
    total = np.stack([np.bincount(rows, weights=corners[:, k], minlength=len(count))
                      for k in range(3)], axis=1)
    return total / np.maximum(count, 1)[:, None]


def physical_faces(h: Hull3, sinks: np.ndarray, tol: float) -> PhysicalFaces:
    """The physical face of each of ``sinks`` (exact face ids): the exact faces reached
    through neighbours whose corners all lie within ``tol`` (m) of the sink's plane."""
    nF = len(h.normals)
    sinks = np.asarray(sinks, dtype=np.int64)
    n_s, h_s = h.normals[sinks], h.heights[sinks]
    edges_of = _FaceEdges(h).of
    owner = np.arange(len(sinks), dtype=np.int64)
    known = owner * nF + sinks  # sorted: owner-major keys of (owner, face)
    # which keys are known: a flag per key where there are few enough (no sort per ring)
    seen = np.zeros(len(sinks) * nF, dtype=bool) if len(sinks) * nF <= SEEN_FLAGS else None
    if seen is not None:
        seen[known] = True
    rings = [known]
    f_owner = owner
    rows, edge, _ = edges_of(sinks)  # the frontier's edges (then kept from each ring's)
    while len(f_owner):
        key = _distinct(f_owner[rows] * nF + h.eg[edge])
        key = key[~(seen[key] if seen is not None else _member(key, known))]
        o, g = key // nF, key % nF
        # a face's mean corner: its offset from a plane is the mean of its corners' offsets,
        # never more than the largest, so a face whose mean lies over 2·tol off is out
        # without looking at its corners (a cylinder's end cap, 4096 corners, next to 8192
        # side faces)
        rows, edge, count = edges_of(g)
        mean_corner = _mean_corners(h, rows, edge, count)
        near = (h_s[o] - dot(mean_corner, n_s[o]) <= 2 * tol) & (dot(h.normals[g], n_s[o]) > 0)
        key, o, g = key[near], o[near], g[near]
        kept = near[rows]  # the near faces' edges, in the same order
        rows, edge = (np.cumsum(near) - 1)[rows[kept]], edge[kept]
        corner = h.ea[edge]
        off = h_s[o[rows]] - dot(h.X[corner], n_s[o[rows]])  # ≥ 0: the hull is convex
        worst = np.zeros(len(o))
        np.maximum.at(worst, rows, off)
        ok = worst <= tol  # (facing the sink's way: ``near`` took only those)
        f_owner = o[ok]
        kept = ok[rows]  # the next frontier's edges: edges_of(g[ok]), in the same order
        rows, edge = (np.cumsum(ok) - 1)[rows[kept]], edge[kept]
        if seen is not None:
            seen[key[ok]] = True
            rings.append(key[ok])
        else:
            known = np.sort(np.concatenate((known, key[ok])))
    if seen is not None:  # the keys of every ring are new: one sort of them all
        known = np.sort(np.concatenate(rings))
    owner, face = known // nF, known % nF

    # the boundary: edges of a member face whose other side is not a member
    rows, edge, _ = edges_of(face)
    o = owner[rows]
    outside = ~(seen[o * nF + h.eg[edge]] if seen is not None
                else _member(o * nF + h.eg[edge], known))
    edge, o = edge[outside], o[outside]
    A, D = h.X[h.ea[edge]], h.X[h.eb[edge]] - h.X[h.ea[edge]]
    foot = (h_s[o])[:, None] * n_s[o]
    dist = dot(cross(D, foot - A), n_s[o]) / np.linalg.norm(D, axis=1)
    margin = np.full(len(sinks), np.inf)
    np.minimum.at(margin, o, dist)

    # sinks lying in one another's physical faces are one pose
    where = np.full(nF, -1, dtype=np.int64)
    where[sinks] = np.arange(len(sinks))
    other = where[face]
    pair = (other >= 0) & (other != owner)
    return PhysicalFaces(sinks, owner, face, margin, np.stack((owner[pair], other[pair])),
                         edge, o)
