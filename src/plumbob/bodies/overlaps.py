"""Which parts may overlap, without testing all pairs: bounding boxes and a sweep.

A spec of 600 disjoint spheres must not build 600 faceted spheres and 180,000
boolean intersections to learn that nothing overlaps. Each body's bounding box
comes from its hull points (exact for polytopes, sampled within 1e-4 of the size
for curves) widened by a margin larger than that sampling, so two bodies whose
boxes do not meet cannot overlap. A sort-and-sweep along x then lists the pairs
whose boxes meet: O(n log n + k) for k such pairs. Only those pairs need the
faceted geometry (:mod:`plumbob.bodies.csg`), and parts that overlap nothing
compose exactly.

The same boxes give the local origin of a boolean far from the world origin: the
facets are built and united near 0 and the result is moved back, so a boolean at
1e6 m has the error (and the stated bound) it has at the origin.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import GeometryError
from ..limits import MAX_SEGMENTS, check_count
from .base import Body

__all__ = ["Facets", "bounding_boxes", "boxes_meet", "candidate_pairs", "connected_groups", "local_origin"]

#: how much a box is widened, relative to its diagonal: well above the hull points'
#: sampling tolerance (1e-4 of the size), so a curved body never pokes out of its box
BOX_MARGIN = 1e-3


def bounding_boxes(bodies: Sequence[Body]) -> np.ndarray:
    """(n, 2, dim) m: each body's lower and upper corner, widened by :data:`BOX_MARGIN`
    of its diagonal, so the body lies inside its box.

    >>> from plumbob.bodies.primitives import box
    >>> bounding_boxes([box(1, 2, 3)]).round(3).tolist()
    [[[-0.004, -0.004, -0.004], [1.004, 2.004, 3.004]]]
    """
    out = []
    for body in bodies:
        points = np.asarray(body.hull_points(), dtype=float)
        low, high = points.min(axis=0), points.max(axis=0)
        margin = BOX_MARGIN * _length(high - low) + np.finfo(float).eps * float(
            np.max(np.abs(points)))
        out.append((low - margin, high + margin))
    return np.array(out, dtype=float)


def boxes_meet(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether boxes ``a`` and ``b`` (each (2, dim)) share a point."""
    return bool(np.all(a[0] <= b[1]) and np.all(b[0] <= a[1]))


def candidate_pairs(boxes: np.ndarray) -> np.ndarray:
    """(k, 2) the index pairs i < j whose boxes meet, by sort and sweep along x.

    >>> boxes = np.array([[[0, 0], [1, 1]], [[5, 5], [6, 6]], [[0.5, 0.5], [2, 2]]])
    >>> candidate_pairs(boxes).tolist()
    [[0, 2]]
    """
    n = len(boxes)
    if n < 2:
        return np.zeros((0, 2), dtype=np.int64)
    order = np.argsort(boxes[:, 0, 0], kind="stable")
    low = boxes[order, 0, :]
    high = boxes[order, 1, :]
    # for each box, the boxes after it in x order that start before it ends
    ends = np.searchsorted(low[:, 0], high[:, 0], side="right")
    found = []
    for i in range(n - 1):  # one step per part, each vectorised over its candidates
        if ends[i] <= i + 1:
            continue
        others = np.arange(i + 1, ends[i])
        meet = np.all((low[others] <= high[i]) & (low[i] <= high[others]), axis=1)
        if meet.any():
            hits = order[others[meet]]
            found.append(np.stack((np.minimum(order[i], hits), np.maximum(order[i], hits)), 1))
    if not found:
        return np.zeros((0, 2), dtype=np.int64)
    pairs = np.concatenate(found)
    return pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]


def connected_groups(n: int, pairs: Sequence[tuple[int, int]]) -> list[list[int]]:
    """The indices 0..n-1 grouped by the ``pairs`` that join them (each group sorted,
    groups in order of their first index).

    >>> connected_groups(5, [(0, 3), (3, 4)])
    [[0, 3, 4], [1], [2]]
    """
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i, j in pairs:
        a, b = root(int(i)), root(int(j))
        if a != b:
            parent[max(a, b)] = min(a, b)
    groups: dict[int, list[int]] = {}
    for i in range(n):
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def local_origin(boxes: np.ndarray) -> np.ndarray | None:
    """Where to put the origin for a boolean of bodies in ``boxes``: the centre of
    their common box when it lies further from the origin than the box's own
    diagonal (far enough for the coordinates' size to cost digits), else None.

    >>> local_origin(np.array([[[1e6, 0, 0], [1e6 + 2, 1, 1]]])).tolist()
    [1000001.0, 0.5, 0.5]
    >>> local_origin(np.array([[[0, 0], [2, 1]]])) is None
    True
    """
    low, high = boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)
    centre = low / 2 + high / 2  # not (low + high) / 2, which overflows near 1.8e308
    if _length(centre) > _length(high - low):
        return centre
    return None


def _length(vector: np.ndarray) -> float:
    """The Euclidean length of ``vector``, without overflow for coordinates past 1e154
    (whose squares a plain norm would turn into inf)."""
    largest = float(np.max(np.abs(vector)))
    if largest == 0 or not np.isfinite(largest):
        return largest
    return largest * float(np.linalg.norm(vector / largest))


class Facets:
    """The bodies' faceted shapes (shapely or manifold3d), made on first use — only
    the parts whose boxes meet another's are ever faceted — each placed relative
    to ``origin`` (None: where it is)."""

    def __init__(self, bodies: Sequence[Body], segments: int, origin: np.ndarray | None):
        # a sphere faceted at n segments per turn has about n²/2 triangles
        segments = check_count("segments per turn", segments, MAX_SEGMENTS,
                               hint="plumbob.limits.MAX_SEGMENTS")
        if segments < 8:
            raise GeometryError(f"a faceted boolean needs at least 8 segments per turn, not "
                                f"{segments}")
        self.bodies, self.segments, self.origin = bodies, segments, origin
        self.made: dict[int, object] = {}

    def __getitem__(self, index: int):
        index = int(index)
        if index not in self.made:
            body = self.bodies[index]
            if self.origin is not None:
                body = body.translated(-self.origin)
            self.made[index] = body.to_geometry(self.segments)
        return self.made[index]
