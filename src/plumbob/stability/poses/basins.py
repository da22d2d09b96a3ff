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

from typing import NamedTuple

import numpy as np

from ...errors import StabilityError
from ...mesh.winding import solid_angle
from .hull import Hull3
from .rolling import Edges3, Roller, edge_geometry, step
from .vectors import cross, dot, fibonacci_sphere, unit

__all__ = ["Basins", "trace_basins", "sampled_basins", "basins3"]

_AREA_CHECK = 1e-7  # relative tolerance on the basins' total area (4π)
_FLAT = 1e-12  # |t| below this: the centre's foot is at the edge's end (a balanced vertex)


class Basins(NamedTuple):
    """The basins of a hull's faces.

    area: (F,) basin area per face, sr (0 for unstable faces).
    roller: the roll that found the stable faces and the basins' ends.
    edges: the hull's edge geometry.
    saddles: (S,) ids of the directed edges (one per pair) holding a saddle.
    error: |Σ area − 4π| / 4π (NaN for sampled basins).
    """

    area: np.ndarray
    roller: Roller
    edges: Edges3
    saddles: np.ndarray
    error: float


def trace_basins(h: Hull3, eg3: Edges3, W: np.ndarray, roller: Roller
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
    side = dot(cross(p, w0), h.normals[h.ef[edge]]) > 0
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
        done = ismax[va] | (dot(pa, w) >= 1.0 - 1e-24)  # at its maximum already
        if done.any():
            d = alive[done]
            area_l = solid_angle(nl[d], pa[done], w[done], unit=True)
            area_r = solid_angle(nr[d], w[done], pa[done], unit=True)
            np.add.at(area, left[d], area_l)
            np.add.at(area, right[d], area_r)
            alive, va, pa, w = alive[~done], va[~done], pa[~done], w[~done]
            if len(alive) == 0:
                break
        tang = unit(w - dot(w, pa)[:, None] * pa)
        limit = np.arccos(np.clip(dot(pa, w), -1.0, 1.0))
        e, q = step(h, eg3, va, pa, tang, limit, exclude[alive], near,
                    np.full(len(alive), -1))
        lost = e < 0
        if lost.any():  # passes through a corner, or numerically lost: end it at w
            ok = False
            d = alive[lost]
            np.add.at(area, left[d], solid_angle(nl[d], pa[lost], w[lost], unit=True))
            np.add.at(area, right[d], solid_angle(nr[d], w[lost], pa[lost], unit=True))
        go = ~lost
        d = alive[go]
        np.add.at(area, left[d], solid_angle(nl[d], pa[go], q[go], unit=True))
        np.add.at(area, right[d], solid_angle(nr[d], q[go], pa[go], unit=True))
        v[d], p[d], exclude[d] = h.eb[e[go]], q[go], h.und[e[go]]
        alive = d
    else:
        ok = False
    return np.mod(area, 4 * np.pi), ok


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


def basins3(h: Hull3, eps: float, samples: int | None) -> Basins | None:
    """The basins of every face of ``h`` (rolls resolved to ``eps``, m): traced exactly when
    ``samples`` is None — then None when the traced areas do not add up to 4π — else from
    rolling a Fibonacci lattice of ``samples`` directions."""
    eg3 = edge_geometry(h)
    W = unit(h.X)
    roller = Roller(h, eg3, W, eps)
    stable = roller.stable
    if not stable.any():
        raise StabilityError("no face of the hull is stable (degenerate hull)")
    sad = np.flatnonzero(eg3.saddle & (h.ea < h.eb))
    if samples is not None:
        return Basins(sampled_basins(h, roller, samples), roller, eg3, sad, float("nan"))
    if len(sad) == 0:  # one basin: the whole sphere
        area = np.where(stable, 4 * np.pi / np.count_nonzero(stable), 0.0)
        ok = np.count_nonzero(stable) == 1
    else:
        area, ok = trace_basins(h, eg3, W, roller)
    error = abs(area.sum() - 4 * np.pi) / (4 * np.pi)
    if not ok or error > _AREA_CHECK or np.any(area[stable] <= 0):
        return None
    return Basins(area, roller, eg3, sad, float(error))
