"""Basins of attraction on the sphere of directions: how likely each face is.

A pose's probability is the area of its basin — the down directions that roll
into it — over 4π. Basins are bounded by the curves that flow into saddles;
:func:`trace_basins` traces them back uphill from every saddle, region by region,
to the maxima, and sums the exact signed spherical triangles fanned from each
basin's face normal over its boundary (all saddles advance at once).
:func:`sampled_basins` is the fallback for degenerate hulls: it rolls a
deterministic Fibonacci lattice of directions downhill. :func:`basins3` runs the
exact trace, checks that the areas add up to 4π, and says when they do not.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from ...arrays import cross, dot, fibonacci_sphere, unit
from ...errors import StabilityError
from ...mesh.winding import solid_angle
from .fans import FAN_CORNERS, Fans
from .hull import Hull3
from .rolling import Edges3, Roller, edge_geometry, step

__all__ = ["Basins", "trace_basins", "sampled_basins", "basins3"]

_AREA_CHECK = 1e-7  # relative tolerance on the basins' total area (4π)
_STRIP_AFTER = 8  # steps (at least) after which live traces also run ahead (:meth:`.Fans.climbs`)
_STRIP_FEW = 32  # ... when no more traces than this are alive
_STRIP_RETRY = 8  # steps before a trace whose run ahead failed tries again
_AHEAD_FEW = 2  # ... or when no more than this are alive (whatever _STRIP_FEW says)
_AHEAD_AFTER = 8  # steps (at least) after which those start
_FLAT = 1e-12  # |t| below this: the centre's foot is at the edge's end (a balanced vertex)


class Basins(NamedTuple):
    """The basins of a hull's faces.

    area: (F,) basin area per face, sr (0 for unstable faces).
    roller: the roll that found the stable faces and the basins' ends.
    edges: the hull's edge geometry.
    saddles: (S,) ids of the directed edges (one per pair) holding a saddle.
    error: |Σ area − 4π| / 4π (NaN for sampled basins).
    grouped: the areas of grouped faces are summed on the face standing for each group.
    """

    area: np.ndarray
    roller: Roller
    edges: Edges3
    saddles: np.ndarray
    error: float
    grouped: bool = False


def _crossing_face(h: Hull3, before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """The face two successively crossed directed edges share (−1: none, or no edge
    before): a separatrix circling it."""
    b = np.maximum(before, 0)
    f, g = h.ef[after], h.eg[after]
    share_f = (before >= 0) & ((h.ef[b] == f) | (h.eg[b] == f))
    share_g = (before >= 0) & ((h.ef[b] == g) | (h.eg[b] == g))
    return np.where(share_f, f, np.where(share_g, g, -1))


def standing_faces(roller: Roller, group: np.ndarray | None) -> np.ndarray:
    """(F,) the faces whose basins are traced: the stable ones, or with ``group`` (see
    :func:`trace_basins`) the one standing for each group."""
    if group is None:
        return roller.stable
    standing = np.zeros(len(roller.stable), dtype=bool)
    standing[group[roller.stable]] = True
    return standing


def trace_basins(h: Hull3, eg3: Edges3, W: np.ndarray, roller: Roller,
                 group: np.ndarray | None = None) -> tuple[np.ndarray, bool]:
    """Basin areas (per face, sr) from the separatrices traced back from every saddle.

    Every trace's path is kept as segments; each segment adds the signed spherical
    triangle from the left basin's face normal to the left basin and takes it from the
    right one, all summed in one pass at the end. Around a face of many corners the
    traces move in runs (:mod:`.fans`), one vectorised move per run; once the loop has
    run long with few traces alive, along crossings predicted in plain Python too.

    ``group`` (F,): per stable face, the face whose basin stands for its group (−1 for
    the others). Only the separatrices between groups are traced, each group's boundary
    fanned from its standing face's normal, and the group's whole area is put there: the
    saddles inside a rolling family (a capsule's 400 side faces) need no trace at all.
    """
    sad, f, g = _saddles_between(h, eg3, roller, group)
    if len(sad) == 0:  # no saddle between basins (groups): one of them is the whole sphere
        standing = standing_faces(roller, group)
        count = np.count_nonzero(standing)
        return np.where(standing, 4 * np.pi / count, 0.0), count == 1
    s = eg3.spoint[eg3.saddle_rows(sad)]
    # two traces per saddle: into the regions of both its ends
    v = np.concatenate((h.ea[sad], h.eb[sad]))
    p = np.concatenate((s, s))
    edge = np.concatenate((sad, sad))
    exclude = h.und[edge]
    f, g = np.concatenate((f, f)), np.concatenate((g, g))
    side = dot(cross(p, W[v]), h.normals[h.ef[edge]]) > 0
    left, right = np.where(side, f, g), np.where(side, g, f)
    near = eg3.t < -_FLAT  # arcs a region's flow leaves: traced back through them
    ismax = _maxima(h, near)
    fans = Fans(h, eg3, W, ismax, near)
    rings = fans.corner_count.max(initial=0) >= FAN_CORNERS
    last = np.full(len(v), -1, dtype=np.int64)  # the edge each trace crossed last
    no_fan = np.full(len(v), -1, dtype=np.int64)  # a face a run around has just failed on
    seg_trace, seg_from, seg_to = [], [], []  # the path segments, kept for the areas
    no_strip = np.full(len(v), -1, dtype=np.int64)  # the step a strip run may next start
    alive = np.arange(len(v))
    ok = True

    def take(t: int, moved) -> None:
        """Trace ``t`` runs along ``moved`` (a fan's or strip's path, last vertex, arc)."""
        path, v[t], last[t] = moved
        p[t], exclude[t] = path[-1], h.und[last[t]]
        seg_trace.append(np.full(len(path) - 1, t))
        seg_from.append(path[:-1])
        seg_to.append(path[1:])

    for count in range(len(h.X) + 8):
        if len(alive) == 0:
            break
        va, pa = v[alive], p.take(alive, axis=0)
        w = W.take(va, axis=0)
        wp = dot(pa, w)
        done = ismax[va] | (wp >= 1.0 - 1e-24)  # at its maximum already
        if np.count_nonzero(done):
            seg_trace.append(alive[done])
            seg_from.append(pa[done])
            seg_to.append(w[done])
            alive, va, pa, w, wp = alive[~done], va[~done], pa[~done], w[~done], wp[~done]
            if len(alive) == 0:
                break
        tang = unit(w - wp[:, None] * pa)
        limit = np.arccos(np.minimum(np.maximum(wp, -1.0), 1.0))  # np.clip, without its wrapper
        e, q = step(h, eg3, va, pa, tang, limit, exclude[alive], near, None)
        lost = e < 0  # passes through a corner, or numerically lost: end it at w
        ok = ok and not np.count_nonzero(lost)
        seg_trace.append(alive)
        seg_from.append(pa)
        seg_to.append(np.where(lost[:, None], w, q))
        go = ~lost
        d, e = alive[go], e[go]
        v[d], p[d], exclude[d] = h.eb[e], q[go], h.und[e]
        if rings:
            circling = _crossing_face(h, last[d], e)
            last[d] = e
            runs = (circling >= 0) & (circling != no_fan[d])
            runs &= fans.corner_count[np.maximum(circling, 0)] >= FAN_CORNERS
            for t, face in zip(d[runs].tolist(), circling[runs].tolist()):
                moved = fans.advance(int(v[t]), p[t], int(last[t]), face)
                if moved is None:
                    no_fan[t] = face
                    continue
                take(t, moved)
        else:  # no face of many corners to run around (an egg's hull)
            last[d] = e
            runs = np.zeros(len(d), dtype=bool)
        few = count >= _STRIP_AFTER and len(d) <= _STRIP_FEW
        lone = count >= _AHEAD_AFTER and len(d) <= _AHEAD_FEW
        if few or lone:
            # a few long traces, each step mostly overhead: their crossings predicted in
            # plain Python, all checked by one step (strips of thin regions, lone traces)
            for t, moved in fans.climbs(d[~runs & (no_strip[d] <= count)].tolist(), v, p, last):
                if moved is None:
                    no_strip[t] = count + _STRIP_RETRY
                    continue
                take(t, moved)
        alive = d
    else:
        ok = False
    trace = np.concatenate(seg_trace)
    a, b = np.concatenate(seg_from), np.concatenate(seg_to)
    nF = len(h.normals)
    area = np.bincount(left[trace], solid_angle(h.normals[left[trace]], a, b, unit=True),
                       minlength=nF)
    area -= np.bincount(right[trace], solid_angle(h.normals[right[trace]], a, b, unit=True),
                        minlength=nF)
    return np.mod(area, 4 * np.pi), ok


def _saddles_between(h: Hull3, eg3: Edges3, roller: Roller, group: np.ndarray | None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The saddle edges (one of each pair) between two basins (groups, with ``group``)
    and the stable faces (standing faces) the rolls from their two faces end on."""
    sad = _one_of_each(h, eg3)
    ends = roller.sinks(np.concatenate((h.ef[sad], h.eg[sad])))
    f, g = ends[:len(sad)], ends[len(sad):]
    if group is not None:
        f, g = group[f], group[g]
        between = f != g
        sad, f, g = sad[between], f[between], g[between]
    return sad, f, g


def _one_of_each(h: Hull3, eg3: Edges3) -> np.ndarray:
    """The saddle edges, one of each pair (``a < b``), ascending: from the saddle rows,
    not a pass over every edge."""
    saddles = eg3.saddles
    return saddles[np.take(h.ea, saddles) < np.take(h.eb, saddles)]


def _maxima(h: Hull3, near: np.ndarray) -> np.ndarray:
    """(n,) the points no region flows into: none of their out-edges is ``near`` (the
    edges are sorted by their start, ``h.start``)."""
    ismax = np.ones(len(h.X), dtype=bool)
    real = np.flatnonzero(h.degree)
    ismax[real] = ~np.logical_or.reduceat(near, h.start[real])
    return ismax


def sampled_basins(h: Hull3, roller: Roller, samples: int) -> np.ndarray:
    """Basin areas from rolling a Fibonacci lattice of directions downhill."""
    u = fibonacci_sphere(samples)
    area = np.zeros(len(h.normals))
    real = np.flatnonzero(h.degree > 0)
    for chunk in np.array_split(np.arange(samples), max(1, samples // 20000)):
        start = real[np.argmax(u[chunk] @ h.X[real].T, axis=1)]
        face = roller.roll(vertex=start, point=u[chunk])
        np.add.at(area, face[face >= 0], 4 * np.pi / samples)
    return area


def basins3(h: Hull3, eps: float, samples: int | None,
            grouping: Callable[[Hull3, Roller, Edges3, np.ndarray], np.ndarray] | None = None
            ) -> Basins | None:
    """The basins of every face of ``h`` (rolls resolved to ``eps``, m): traced exactly when
    ``samples`` is None — then None when the traced areas do not add up to 4π — else from
    rolling a Fibonacci lattice of ``samples`` directions.

    ``grouping(h, roller, edges, saddles)``, when given, says which stable faces are
    traced as one (:func:`trace_basins`' ``group``): their summed area is on the face
    standing for them, and the result's ``grouped`` is True."""
    eg3 = edge_geometry(h, eps)
    W = unit(h.X)
    roller = Roller(h, eg3, W, eps)
    stable = roller.stable
    if not stable.any():
        raise StabilityError("no face of the hull is stable (degenerate hull)")
    sad = _one_of_each(h, eg3)
    if samples is not None:
        return Basins(sampled_basins(h, roller, samples), roller, eg3, sad, float("nan"))
    group = grouping(h, roller, eg3, sad) if grouping is not None else None
    area, ok = trace_basins(h, eg3, W, roller, group)
    error = abs(area.sum() - 4 * np.pi) / (4 * np.pi)
    if not ok or error > _AREA_CHECK or np.any(area[standing_faces(roller, group)] <= 0):
        return None
    return Basins(area, roller, eg3, sad, float(error), group is not None)
