"""A lone roll's next crossings, predicted in plain Python floats.

A roll downhill over a finely tessellated smooth surface (an egg's side) crosses the
thin regions of hundreds of vertices one after another, and :meth:`.rolling.Roller.roll`
advances each roll one region per vectorised step: with one or two rolls alive, each
step is numpy's per-call overhead (about 0.2 ms), not arithmetic. :func:`predict`
walks ahead of one roll with the step's own formulas (:func:`.rolling.step`) on Python
floats, a few microseconds a candidate arc; the roller then checks the whole run with
one vectorised step over all the predicted points and takes it up to the first
disagreement, so every decision is the step's own (as the fan and strip runs of
:mod:`.fans` are checked). The prediction stops wherever the roll does anything but
cross into the next region (it slides along an arc, lands on a face, or meets an arc
only within the step's relaxed tolerance): the roller's loop takes those steps.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .hull import Hull3

__all__ = ["predict"]

_THETA_EPS = 1e-12  # as rolling._THETA_EPS: intersections this close are the start's own arc
_CORNER = 5e-19  # as rolling._CORNER: a crossing this close to an arc's end lands on its face


_RELAXED_SCORE = 10.0  # step scores an arc met only within its relaxed tolerance 10 + miss


def predict(h: Hull3, eg3: Any, W: np.ndarray, far: np.ndarray, v: int, p: np.ndarray,
            exclude: int, longest: int, ismax: np.ndarray | None = None
            ) -> tuple[list[int], list[int], list[list[float]]]:
    """Up to ``longest`` crossings of a roll at vertex ``v``, at the unit point ``p``,
    having last crossed the undirected edge ``exclude`` (``eg3``: the hull's
    :class:`~.rolling.Edges3`; ``W``: the unit directions of its points; ``far``: the
    arcs a roll may cross): the vertices whose regions it crosses (``v`` first), the
    directed edge it leaves each by, and the unit point where.

    Each move is :func:`.rolling.step` with ``limit`` π, as :meth:`.rolling.Roller.roll`
    takes it: from ``p`` along the great circle away from ``W[v]``, the first arc met
    (least angle θ, the first on ties) at ``cos θ p + sin θ t``. The walk stops before a
    move that meets no arc cleanly (only outside it by more than 1e-12), slides (the
    arc holds the centre's foot: ``t < 1``) or lands on a face's normal.

    With ``ismax`` (per point: nothing flows into it) the walk is a separatrix's, traced
    uphill as :func:`.basins.trace_basins` steps it (``far``: the arcs it may cross):
    toward ``W[v]``, no further than ``W[v]`` itself, and it stops at a maximum; it
    never slides nor lands.
    """
    start, degree, und, ef, eg, eb = h.start, h.degree, h.und, h.ef, h.eg, h.eb
    normals, pole, foot = h.normals, eg3.pole, eg3.t
    px, py, pz = (float(x) for x in p)
    verts: list[int] = []
    edges: list[int] = []
    points: list[list[float]] = []
    for _ in range(longest):
        s, d = int(start[v]), int(degree[v])
        wx, wy, wz = W[v].tolist()
        wp = wx * px + wy * py + wz * pz
        limit = math.pi
        if ismax is None:
            tx, ty, tz = wp * px - wx, wp * py - wy, wp * pz - wz
        else:
            if ismax[v] or wp >= 1.0 - 1e-24:
                break  # at its maximum: the trace ends there
            tx, ty, tz = wx - wp * px, wy - wp * py, wz - wp * pz
            limit = math.acos(min(1.0, max(-1.0, wp)))
        norm = math.sqrt(tx * tx + ty * ty + tz * tz)
        if norm > 0:
            tx, ty, tz = tx / norm, ty / norm, tz / norm
        best, best_score, best_q = -1, math.inf, (0.0, 0.0, 0.0)
        ks = pole[s:s + d].tolist()
        fs = normals[ef[s:s + d]].tolist()
        gs = normals[eg[s:s + d]].tolist()
        for i, (c_far, c_und) in enumerate(zip(far[s:s + d].tolist(), und[s:s + d].tolist())):
            if not c_far or c_und == exclude:
                continue
            kx, ky, kz = ks[i]
            theta = math.atan2(-(px * kx + py * ky + pz * kz), tx * kx + ty * ky + tz * kz)
            if theta <= _THETA_EPS:
                theta += math.pi
            if not (theta > _THETA_EPS and theta <= limit + 1e-12):
                continue  # not met on this side of the antipode: infinite score
            c, sn = math.cos(theta), math.sin(theta)
            qx, qy, qz = c * px + sn * tx, c * py + sn * ty, c * pz + sn * tz
            fx, fy, fz = fs[i]
            gx, gy, gz = gs[i]
            after_f = (qx * (ky * fz - kz * fy) + qy * (kz * fx - kx * fz)
                       + qz * (kx * fy - ky * fx))
            before_g = (qx * (gy * kz - gz * ky) + qy * (gz * kx - gx * kz)
                        + qz * (gx * ky - gy * kx))
            miss = max(0.0, -min(after_f, before_g))
            score = theta if miss <= 1e-12 else _RELAXED_SCORE + miss
            if score < best_score:
                best, best_score, best_q = s + i, score, (qx, qy, qz)
        if best < 0 or best_score >= _RELAXED_SCORE:
            break  # met only loosely, or not at all
        if ismax is None and float(foot[best]) < 1:
            break  # the roll slides along the arc
        qx, qy, qz = best_q
        norm = math.sqrt(qx * qx + qy * qy + qz * qz)
        qx, qy, qz = qx / norm, qy / norm, qz / norm
        nf, ng = normals[ef[best]].tolist(), normals[eg[best]].tolist()
        if ismax is None and (1.0 - (qx * nf[0] + qy * nf[1] + qz * nf[2]) <= _CORNER
                              or 1.0 - (qx * ng[0] + qy * ng[1] + qz * ng[2]) <= _CORNER):
            break  # lands on a face: the roller's loop takes it there
        verts.append(v)
        edges.append(best)
        points.append([qx, qy, qz])
        v, exclude = int(eb[best]), int(und[best])
        px, py, pz = qx, qy, qz
    return verts, edges, points
