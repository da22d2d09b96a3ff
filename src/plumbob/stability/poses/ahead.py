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
from typing import Any, NamedTuple

import numpy as np

from .hull import Hull3

__all__ = ["Scalars", "climb", "predict", "scalars"]

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


class Scalars(NamedTuple):
    """A hull's arrays as flat memoryviews: single entries read as Python numbers at list
    speed, with nothing converted up front (``tolist`` of an egg's 600k edges would cost
    more than the whole walk)."""

    W: memoryview  # (3n,) unit directions of the points
    N: memoryview  # (3F,) face normals
    K: memoryview  # (3E,) arc poles
    start: memoryview
    degree: memoryview
    ef: memoryview
    eg: memoryview
    eb: memoryview
    und: memoryview
    near: memoryview  # (E,) the arcs a walk may cross
    ismax: memoryview  # (n,) the points a walk ends at


def scalars(h: Hull3, eg3: Any, W: np.ndarray, near: np.ndarray, ismax: np.ndarray) -> Scalars:
    """:class:`Scalars` of a hull ``h``, its edge geometry ``eg3``, the unit directions
    ``W`` of its points, the arcs ``near`` a walk crosses and its maxima ``ismax``."""

    def flat(a: np.ndarray) -> memoryview:
        return memoryview(np.ascontiguousarray(a).reshape(-1))

    return Scalars(flat(W), flat(h.normals), flat(eg3.pole), flat(h.start), flat(h.degree),
                   flat(h.ef), flat(h.eg), flat(h.eb), flat(h.und), flat(near), flat(ismax))


def climb(s: Scalars, v: int, px: float, py: float, pz: float, exclude: int, longest: int
          ) -> tuple[list[int], list[int], list[float]]:
    """Up to ``longest`` crossings of a separatrix traced uphill from the unit point ``p``
    in the region of ``v``, having last crossed the undirected edge ``exclude``: the
    vertices whose regions it crosses (``v`` first), the directed edge it leaves each by,
    and the points where, flat (x, y, z per crossing).

    The region of ``v`` is a convex spherical polygon and the trace runs on the great
    circle from ``p`` toward ``w = W[v]``: that circle meets the boundary twice, at ``p``
    and where it leaves, so the exit is the one arc (among ``near`` ones, other than
    ``exclude``) whose ends lie on opposite sides of the circle's plane — a sign test of
    ``(p × w)·n`` at its two faces' normals, no angle computed. The crossing point is the
    projective map ``w (k·p) − p (k·w)`` of ``p`` (``k`` the arc's pole), signed to lie
    ahead. The walk stops at a maximum (``ismax``, or ``w`` reached), where no arc or more
    than one is straddled (a corner), and where the arc would be met beyond ``w``: what
    the step decides there is the loop's (:func:`.rolling.step` checks every crossing
    predicted here)."""
    W, N, K, start, degree = s.W, s.N, s.K, s.start, s.degree
    ef, eg, eb, und, near, ismax = s.ef, s.eg, s.eb, s.und, s.near, s.ismax
    verts: list[int] = []
    edges: list[int] = []
    points: list[float] = []
    for _ in range(longest):
        if ismax[v]:
            break
        i = 3 * v
        wx, wy, wz = W[i], W[i + 1], W[i + 2]
        if wx * px + wy * py + wz * pz >= 1.0 - 1e-24:
            break
        cx, cy, cz = py * wz - pz * wy, pz * wx - px * wz, px * wy - py * wx  # p × w
        found = -1
        first = start[v]
        for j in range(first, first + degree[v]):
            if not near[j] or und[j] == exclude:
                continue
            f, g = 3 * ef[j], 3 * eg[j]
            sf = cx * N[f] + cy * N[f + 1] + cz * N[f + 2]
            sg = cx * N[g] + cy * N[g + 1] + cz * N[g + 2]
            if (sf > 0.0 and sg < 0.0) or (sf < 0.0 and sg > 0.0):
                if found >= 0:
                    found = -2
                    break
                found = j
        if found < 0:
            break
        k = 3 * found
        kx, ky, kz = K[k], K[k + 1], K[k + 2]
        kp = kx * px + ky * py + kz * pz
        kw = kx * wx + ky * wy + kz * wz
        if kp < 0.0:
            kp, kw = -kp, -kw
        if kw > 0.0 or kp == 0.0:  # met beyond w (or not at all): the trace's maximum first
            break
        qx, qy, qz = wx * kp - px * kw, wy * kp - py * kw, wz * kp - pz * kw
        norm = math.sqrt(qx * qx + qy * qy + qz * qz)
        px, py, pz = qx / norm, qy / norm, qz / norm
        verts.append(v)
        edges.append(found)
        points += (px, py, pz)
        v, exclude = eb[found], und[found]
    return verts, edges, points
