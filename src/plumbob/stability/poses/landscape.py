"""The height function's landscape: the candidate poses, their basins and saddles.

:func:`landscape3` runs the 3D pipeline — exact hull (:mod:`.hull`), rolls and
basins on it (:mod:`.rolling`, :mod:`.basins`), a nudged centre when the
landscape is degenerate (a centre exactly above a vertex or an edge's end, as
symmetric meshes have) — and then grows each stable face's physical face
(:mod:`.faces`): the faces coplanar with it within the tolerance. :func:`landscape2`
does the same one dimension down for a lamina: the hull's edges are the poses and
the basins are exact arcs of the circle of directions. Which candidates are one
rolling or rocking family is :mod:`.families`' question.

The result, a :class:`Landscape`, is all :mod:`.resting` needs to report poses.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np

from ...arrays import dot, pointer_sinks, unit
from ...errors import StabilityError
from ...tolerances import HULL_ROUND_OFF, size_of
from .basins import basins3
from .faces import physical_faces
from .hull import Hull3, build_hull3, shifted
from .rolling import Edges3, Roller, edge_geometry

__all__ = ["Landscape", "landscape3", "landscape2"]

_NUDGES = (0.0, 1e-9, 1e-7, 1e-5)  # relative moves of the centre for degenerate landscapes
_NUDGE_DIRECTION = np.array([0.5773, 0.2245, 0.7853]) / np.linalg.norm([0.5773, 0.2245, 0.7853])
# (a fixed, deterministic direction with no special relation to any axis)


class Landscape(NamedTuple):
    """The height function's landscape over the stable faces (3D) or edges (2D) of the
    exact hull: the candidate poses.

    normals, heights: (P, dim), (P,) per candidate: the outward unit normal of the
    stable face and the height of the centre of mass over it, m.
    area: (P,) the area of its basin (sr, or rad for a lamina); the basins of a rolling
    family's members are traced as one and summed on its representative (the others
    hold 0). face_area: (P,) the exact face's area, m² (its length for a lamina, m).
    margin: (P,) how far the foot of the centre lies inside the physical face, m.
    sa, sb, sh: saddles (maxima for a lamina) between the basins of candidates sa and
    sb (never equal), at height sh, m.
    same: (2, L) pairs of candidates on one physical face (the second lies within the
    tolerance of the first's plane, reached through such faces): one pose.
    corners: ``corners(p) -> (k, dim)`` the physical face's corners, m, relative to the
    centre of mass. points: the hull points relative to the centre of mass.
    faces: exact hull faces (3D) or hull edges (2D). hull: the exact hull the candidates
    are faces of (3D; None for a lamina), for rolls from any direction
    (:mod:`.settling`).
    """

    normals: np.ndarray
    heights: np.ndarray
    area: np.ndarray
    face_area: np.ndarray
    margin: np.ndarray
    sa: np.ndarray
    sb: np.ndarray
    sh: np.ndarray
    same: np.ndarray
    corners: Callable[[int], np.ndarray]
    points: np.ndarray
    faces: int
    method: str
    error: float
    hull: Hull3 | None = None


def _between(label: np.ndarray, fa: np.ndarray, fb: np.ndarray, sh: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Saddles between different candidates, as candidate ids."""
    a, b = label[fa], label[fb]
    keep = (a != b) & (a >= 0) & (b >= 0)
    return a[keep], b[keep], sh[keep]


def _saddle_ends(h: Hull3, roller: Roller, sad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The stable faces the rolls from both faces of each saddle edge ``sad`` end on, in
    one :meth:`~.rolling.Roller.sinks` call: one loop as long as the longest roll, not
    two."""
    ends = roller.sinks(np.concatenate((h.ef[sad], h.eg[sad])))
    return ends[:len(sad)], ends[len(sad):]


def _candidates(h: Hull3, sinks: np.ndarray, area: np.ndarray, fa: np.ndarray, fb: np.ndarray,
                sheight: np.ndarray, tol: float, method: str, error: float) -> Landscape:
    """The landscape over the stable faces ``sinks`` of ``h``, their basin areas ``area``,
    and the saddles (at heights ``sheight``) whose arcs roll down to ``fa`` and ``fb``."""
    pf = physical_faces(h, sinks, tol)
    label = np.full(len(h.normals), -1, dtype=np.int64)
    label[sinks] = np.arange(len(sinks))
    sa, sb, sh = _between(label, fa, fb, sheight)

    def corners(p: int) -> np.ndarray:
        return pf.corners(h, p)

    return Landscape(h.normals[sinks], h.heights[sinks], area, h.areas[sinks], pf.margin, sa,
                     sb, sh, pf.same, corners, h.X[h.degree > 0], len(h.normals), method, error)


def landscape3(X: np.ndarray, tol: float, samples: int,
               families_of: Callable[[Landscape], Any] | None = None,
               surface: np.ndarray | None = None) -> Landscape:
    """3D: the landscape over the physical faces of the hull of ``X`` (n, 3), m, relative
    to the centre of mass; faces coplanar within ``tol`` (m) of a stable face's plane are
    one. Basins are traced exactly, from a centre nudged by a hair when the landscape is
    degenerate, and from ``samples`` rolled directions when that fails too.

    ``families_of(landscape)`` (:func:`.families.families` with the caller's roll angle),
    when given, says before the trace which stable faces are one rolling family: only the
    boundaries between poses are then traced, and each rolling family's area is summed on
    its representative (first try only: a nudged centre traces every basin).
    ``surface`` (m, 3): the body's own triangles as indices into ``X``, taken for the hull
    when they bound a convex body (:func:`.convex.own_hull`)."""
    size = size_of(X)
    eps = HULL_ROUND_OFF * size
    h0 = build_hull3(X, eps, surface)  # surface: the body's own mesh, used if convex
    inside = float(h0.heights.min())
    if not inside > tol:
        where = "outside" if inside < -tol else "on the surface of"
        raise StabilityError(
            f"the centre of mass lies {where} the body's convex hull "
            f"(by {abs(inside):.3g} m), so the body cannot rest on any face: is the mesh "
            "open or inside out, or a density negative?")
    provisional: list[Landscape] = []

    def grouping(h: Hull3, roller: Roller, eg3: Edges3, sad: np.ndarray) -> np.ndarray:
        stable = np.flatnonzero(roller.stable)
        fa, fb = _saddle_ends(h, roller, sad)
        land = _candidates(h, stable, np.zeros(len(stable)), fa, fb,
                           eg3.sheight[eg3.saddle_rows(sad)], tol, "exact", 0.0)
        provisional.append(land)
        fam = families_of(land)
        group = np.full(len(h.normals), -1, dtype=np.int64)
        group[stable] = stable
        rolling = fam.kind[fam.label] == "rolling"
        group[stable[rolling]] = stable[fam.rep[fam.label[rolling]]]
        return group

    # A centre exactly above a vertex or an edge's end (symmetric meshes) is a degenerate
    # landscape whose traces may not close: look again from a centre nudged by a hair.
    method, found = "exact", None
    for nudge in _NUDGES:
        h = h0 if nudge == 0 else shifted(h0, nudge * size * _NUDGE_DIRECTION)
        try:
            found = basins3(h, eps, None, grouping if families_of and nudge == 0 else None)
        except StabilityError:  # a roll lost through a corner: degenerate too, nudge
            found = None
        if found is not None:
            break
    if found is None:
        h, method = h0, "sampled"
        found = basins3(h, eps, samples)
    area, roller, eg3, sad, error, grouped = found
    if grouped:  # h is h0: the provisional landscape is the landscape, with its areas
        stable = np.flatnonzero(roller.stable)
        return provisional[-1]._replace(area=area[stable], error=error, hull=h0)
    stable = roller.stable
    fa, fb = _saddle_ends(h, roller, sad)
    if h is not h0:  # seen from the true centre, a nudged pose may sit on its face's edge:
        true = Roller(h0, edge_geometry(h0, eps), unit(h0.X), eps)  # roll it on from there
        try:
            landed = np.flatnonzero(area > 0)
            area = np.bincount(true.sinks(landed), weights=area[landed], minlength=len(area))
            fa, fb, stable = true.sinks(fa), true.sinks(fb), true.stable
        except StabilityError:
            pass  # the true centre's rolls are degenerate too: keep the nudged answer
    sinks = np.flatnonzero(stable & (area > 0))
    land = _candidates(h0, sinks, area[sinks], fa, fb, eg3.sheight[eg3.saddle_rows(sad)], tol,
                       method, error)
    return land._replace(hull=h0)


def landscape2(X: np.ndarray, tol: float) -> Landscape:
    """2D: hull edges are the poses; basins are arcs of the circle of directions."""
    from ..planar import drop_collinear, planar_hull  # a lamina's only (~0.25 ms)

    V = drop_collinear(X[planar_hull(X)], tol)  # counter-clockwise
    m = len(V)
    A, B = V, np.roll(V, -1, axis=0)
    D = B - A
    L = np.linalg.norm(D, axis=1)
    normals = np.stack((D[:, 1], -D[:, 0]), axis=1) / L[:, None]
    heights = dot(A, normals)
    if not heights.min() > tol:
        raise StabilityError(
            "the centre of mass lies outside (or on) the lamina's convex hull: it cannot "
            "rest on any edge — is a density negative?")
    foot = heights[:, None] * normals
    along = dot(foot - A, D) / L
    margins = np.minimum(along, L - along)
    stable = margins > tol
    # unstable edges tip over the end the foot lies beyond
    idx = np.arange(m)
    nxt = np.where(stable, idx, np.where(along >= L / 2, (idx + 1) % m, (idx - 1) % m))
    sink = pointer_sinks(nxt)
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

    sad = np.flatnonzero(is_max)
    keep = stable & (arc > 0)
    label = np.full(m, -1, dtype=np.int64)
    label[keep] = np.arange(int(keep.sum()))
    sa, sb, sh = _between(label, sink[prev_edge[sad]], sink[sad], np.linalg.norm(V[sad], axis=1))
    ids = np.flatnonzero(keep)

    def corners(p: int) -> np.ndarray:
        g = ids[p]
        return np.array([V[g], V[(g + 1) % m]])

    return Landscape(normals[ids], heights[ids], arc[ids], L[ids], margins[ids], sa, sb, sh,
                     np.zeros((2, 0), dtype=np.int64), corners, V, m, "exact", float(error))
