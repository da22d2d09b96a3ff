"""Rolls and separatrices run ahead: their next crossings predicted in plain Python floats.

A roll downhill over a finely tessellated smooth surface (an egg's side) crosses the
thin regions of hundreds of vertices one after another, and a separatrix traced uphill
(:mod:`.basins`) as many; a loop of one vectorised step per crossing
(:func:`.rolling.step`) spends its time in numpy's per-call overhead (about 0.2 ms a
step), not arithmetic, once few walks are left. :func:`climb` (uphill) and
:func:`descend` (downhill) walk ahead of one in plain Python floats, about 2 µs a
crossing: a region is a convex spherical polygon and the walk runs on the great circle
through ``w``, so the arc it leaves by is the one whose ends lie on opposite sides of
that circle's plane (one sign test per candidate arc, no angle), and the crossing
point is a linear map of the point it came in at. The caller then checks all the
predicted crossings of all its walks with one vectorised step over the predicted
points and takes each run up to its first disagreement, so every decision is the
step's own. A prediction stops wherever the walk does anything but cross into the
next region (it slides along an arc, lands on a face, reaches its maximum, or meets a
corner): the loop takes those steps.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from .hull import Hull3

__all__ = ["Scalars", "Tables", "climb", "roam", "scalars"]

_CORNER = 5e-19  # as rolling._CORNER: a crossing this close to an arc's end lands on its face


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
    ea: memoryview
    eb: memoryview
    und: memoryview
    crosses: memoryview  # (E,) the arcs a walk may cross
    t: memoryview  # (E,) where the centre's foot lies along each edge (Edges3.t)


def scalars(h: Hull3, eg3: Any, W: np.ndarray, crosses: np.ndarray) -> Scalars:
    """:class:`Scalars` of a hull ``h``, its edge geometry ``eg3``, the unit directions
    ``W`` of its points and the arcs ``crosses`` a walk may cross."""

    def flat(a: np.ndarray) -> memoryview:
        return memoryview(np.ascontiguousarray(a).reshape(-1))

    return Scalars(flat(W), flat(h.normals), flat(eg3.pole), flat(h.start), flat(h.degree),
                   flat(h.ef), flat(h.eg), flat(h.ea), flat(h.eb), flat(h.und), flat(crosses),
                   flat(eg3.t))


def climb(s: Scalars, v: int, px: float, py: float, pz: float, exclude: int, longest: int
          ) -> tuple[list[int], list[float]]:
    """Up to ``longest`` crossings of a separatrix traced uphill from the unit point ``p``
    in the region of ``v``, having last crossed the undirected edge ``exclude``: the
    directed edge it leaves each region by (an out-edge of the region's vertex, so the
    vertices are their ``ea``, ``v`` first), and the points where, flat (x, y, z per
    crossing).

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
    ef, eg, eb, und, near = s.ef, s.eg, s.eb, s.und, s.crosses
    edges: list[int] = []
    points: list[float] = []
    for _ in range(longest):
        i = 3 * v
        wx, wy, wz = W[i], W[i + 1], W[i + 2]
        if wx * px + wy * py + wz * pz >= 1.0 - 1e-24:
            break
        cx, cy, cz = py * wz - pz * wy, pz * wx - px * wz, px * wy - py * wx  # p × w
        found = -1
        first = start[v]
        for j in range(first, first + degree[v]):  # none at a maximum (nothing flows in)
            if not near[j] or und[j] == exclude:
                continue
            f = 3 * ef[j]
            sf = cx * N[f] + cy * N[f + 1] + cz * N[f + 2]
            g = 3 * eg[j]
            sg = cx * N[g] + cy * N[g + 1] + cz * N[g + 2]
            if (sf > 0.0 and sg < 0.0) or (sf < 0.0 and sg > 0.0):
                found = j  # the one arc straddled (past the entry): a tie is the check's
                break
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
        edges.append(found)
        points += (px, py, pz)
        v, exclude = eb[found], und[found]
    return edges, points


class Tables(NamedTuple):
    """What a roll does at a face and on a sliding arc (:class:`.rolling.Roller`'s tables),
    as flat memoryviews (see :class:`Scalars`)."""

    lands: memoryview  # (F,) where a roll from each face ends over edges alone
    stable: memoryview  # (F,) the stable faces
    tip_edge: memoryview  # (F,) the edge an unstable face tips over
    tip_at_a: memoryview  # (F,) a pivot's corner is its tip edge's start (else its end)
    heights: memoryview  # (F,) the centre's height over each face
    saddle: memoryview  # (E,) the arcs holding a saddle
    toward_f: memoryview  # (3S,) per saddle row, spoint × pole
    saddle_row: dict[int, int]  # saddle edge -> its row


def roam(s: Scalars, r: Tables, cur: int, v: int, px: float, py: float, pz: float,
         exclude: int, start_face: int, longest: int
         ) -> tuple[list[int], list[float], list[int], list[int], list[int], list[float],
                    list[int]]:
    """Up to ``longest`` region moves of a roll downhill (:meth:`.rolling.Roller.roll`),
    predicted in plain Python: from the face ``cur`` (≥ 0), or else from the unit point
    ``p`` in the region of ``v`` (having last crossed the undirected edge ``exclude``,
    come from the face ``start_face`` when ≥ 0), on over edges and corners as the roller
    moves: a face hands the roll to the face its rolls over edges land on, an unstable
    one pivots about its tip's corner, starting at its normal; a region move leaves by
    the arc the great circle away from ``w`` straddles (as :func:`climb` finds it, the
    arcs ``s.crosses`` that do not end at the start face), crossing it into the next
    region, or onto a face when it slides along an arc holding the centre's foot
    (``t < 1``: to its saddle's side, or its lower end) or crosses within 1e-9 rad of an
    arc's end. Stops at a stable face, or where no arc (or a corner) is straddled.

    Per move: the vertex, start point (flat), excluded edge, start face, the edge it
    leaves by, the point where (flat), and the face it ends on (−1: into the next
    region)."""
    W, N, K, start, degree = s.W, s.N, s.K, s.start, s.degree
    ef, eg, eb, und, far, foot = s.ef, s.eg, s.eb, s.und, s.crosses, s.t
    lands, stable, tip_edge, tip_at_a = r.lands, r.stable, r.tip_edge, r.tip_at_a
    ea = s.ea
    V: list[int] = []
    P: list[float] = []
    X: list[int] = []
    SF: list[int] = []
    E: list[int] = []
    Q: list[float] = []
    ends: list[int] = []
    for _ in range(longest):
        if cur >= 0:  # at a face: over edges, then about its tip's corner
            f = lands[cur]
            if stable[f]:
                break
            tip = tip_edge[f]
            v = ea[tip] if tip_at_a[f] else eb[tip]
            i = 3 * f
            px, py, pz = N[i], N[i + 1], N[i + 2]
            start_face, exclude, cur = f, -1, -1
        i = 3 * v
        wx, wy, wz = W[i], W[i + 1], W[i + 2]
        cx, cy, cz = py * wz - pz * wy, pz * wx - px * wz, px * wy - py * wx  # p × w
        found, f, g = -1, 0, 0
        first = start[v]
        for j in range(first, first + degree[v]):
            if not far[j] or und[j] == exclude:
                continue
            f, g = ef[j], eg[j]
            if f == start_face or g == start_face:
                continue
            f, g = 3 * f, 3 * g
            sf = cx * N[f] + cy * N[f + 1] + cz * N[f + 2]
            sg = cx * N[g] + cy * N[g + 1] + cz * N[g + 2]
            if (sf > 0.0 and sg < 0.0) or (sf < 0.0 and sg > 0.0):
                found = j
                break
        if found < 0:
            break
        k = 3 * found
        kx, ky, kz = K[k], K[k + 1], K[k + 2]
        kp = kx * px + ky * py + kz * pz
        kw = kx * wx + ky * wy + kz * wz
        if kp > 0.0:  # the side behind w: its coefficient negative
            kp, kw = -kp, -kw
        if kp == 0.0:
            break
        qx, qy, qz = wx * kp - px * kw, wy * kp - py * kw, wz * kp - pz * kw
        norm = math.sqrt(qx * qx + qy * qy + qz * qz)
        qx, qy, qz = qx / norm, qy / norm, qz / norm
        V.append(v)
        P += (px, py, pz)
        X.append(exclude)
        SF.append(start_face)
        E.append(found)
        Q += (qx, qy, qz)
        if foot[found] < 1.0:  # slides along the arc: to its saddle's side, or its lower end
            row = r.saddle_row.get(found) if r.saddle[found] else None
            if row is not None:
                t3 = 3 * row
                to_f = qx * r.toward_f[t3] + qy * r.toward_f[t3 + 1] + qz * r.toward_f[t3 + 2] > 0
            else:
                to_f = r.heights[ef[found]] <= r.heights[eg[found]]
            cur = ef[found] if to_f else eg[found]
        elif 1.0 - (qx * N[f] + qy * N[f + 1] + qz * N[f + 2]) <= _CORNER:
            cur = ef[found]  # lands on a face's normal
        elif 1.0 - (qx * N[g] + qy * N[g + 1] + qz * N[g + 2]) <= _CORNER:
            cur = eg[found]
        else:
            cur = -1
            v, exclude, start_face = eb[found], und[found], -1
            px, py, pz = qx, qy, qz
        ends.append(cur)
    return V, P, X, SF, E, Q, ends
