"""Rocking and rolling on curved surfaces, from the support function.

A body resting with contact direction u (the outward normal where it touches the
plane) has its centre of mass at height h(u) = max over its points p of (p − c)·u.
Where it rests on a curved surface — a point or a line of contact — the static
margin is zero, and what happens next depends on curvature:

* h rises whichever way u turns: the bottom of a bowl, it **rocks back**
  (a hemisphere on its dome, a weighted ball);
* h stays level one way: it **rolls** (a cylinder on its side, a uniform ball);
* h falls some way: it **topples** (an egg balanced on its end).

On a plane tilted by θ a rocker rolls until the point it touches, P(u), lies
straight below the centre of mass, so θ(u) = angle(u, P(u)); it holds while θ(u)
can still rise as u turns, and rolls away past the first maximum. For a ball
whose centre of mass lies d from the centre of its radius-R surface, asin(d/R).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Rocking", "rocking"]

ROLL_STEP_DEG = 0.25
PROBE_DEG = 8.0  # how far u turns to judge curvature: past the sampling's ripple


@dataclass(frozen=True)
class Rocking:
    """How a body resting on a curved surface responds to being turned.

    directions: (k, dim) unit vectors perpendicular to ``down`` (body frame): the
        ways the contact direction is turned.
    alpha: (m,) how far it is turned, radians.
    heights: (k, m) height of the centre of mass, m, with contact direction
        u = cos α · down + sin α · direction.
    tilts_deg: (k,) the tilt of the plane, degrees, each way, before the rocker's
        equilibrium ends.
    """

    down: np.ndarray
    directions: np.ndarray
    alpha: np.ndarray
    heights: np.ndarray
    tilts_deg: np.ndarray

    @property
    def rest_height(self) -> float:
        """Height of the centre of mass at rest, m."""
        return float(self.heights[:, 0].min())

    def rise(self, probe_deg: float = PROBE_DEG) -> np.ndarray:
        """(k,) how much the centre of mass rises, m, when turned ``probe_deg`` each way."""
        i = int(np.argmin(np.abs(self.alpha - np.radians(probe_deg))))
        return self.heights[:, i] - self.heights[:, 0]

    def kind(self, noise: float) -> str:
        """``"stands"`` (rocks back), ``"topples"`` or ``"neutral"`` (rolls), judging rises
        against ``noise`` (m, the sampling's error in heights)."""
        rise = self.rise()
        if np.all(rise > noise):
            return "stands"
        if np.any(rise < -noise):
            return "topples"
        return "neutral"

    def barrier(self) -> float:
        """Least rise of the centre of mass, m, that rolls it out of its bowl (over the
        highest point of the way it rolls, in the easiest direction)."""
        return float((self.heights.max(axis=1) - self.heights[:, 0]).min())


_LEVELS = (64, 8)  # angle steps per interval in the exact filter's two passes


def _intervals(m: int, coarse: int) -> tuple[np.ndarray, np.ndarray]:
    """Indices of the first and last angle of each interval of ``coarse`` steps over
    ``m`` angles (the last interval ends at the last angle)."""
    ends = np.arange(0, m, coarse)
    if ends[-1] != m - 1:
        ends = np.append(ends, m - 1)
    return ends[:-1], ends[1:]


def _expand(first: np.ndarray, count: np.ndarray) -> np.ndarray:
    """``first[i], first[i] + 1, …, first[i] + count[i] − 1`` for every i, concatenated."""
    total = int(count.sum())
    starts = np.cumsum(count) - count
    return np.repeat(first - starts, count) + np.arange(total)


def _keep(a: np.ndarray, b: np.ndarray, polar: tuple[np.ndarray, np.ndarray],
          alpha: np.ndarray, eps: float, lo: np.ndarray, hi: np.ndarray, k: np.ndarray,
          j: np.ndarray) -> np.ndarray:
    """Which pairs (interval k, point j) pass the exact filter: the point's best reach
    over the interval ``alpha[lo[k]] … alpha[hi[k]]`` is not below the support's worst
    there, less ``eps``. Every interval's pairs must hold every point that supports
    somewhere on it (true of all points, and kept true by the filter). ``polar``: each
    point's distance from the origin and the angle of its crest, in [0, 2π)."""
    r, crest = polar
    lo_a, hi_a = alpha[lo], alpha[hi]
    aj, bj = a[j], b[j]
    reach_lo = np.cos(lo_a)[k] * aj + np.sin(lo_a)[k] * bj
    reach_hi = np.cos(hi_a)[k] * aj + np.sin(hi_a)[k] * bj
    best = np.maximum(reach_lo, reach_hi)
    cj = crest[j]
    inside = (cj >= lo_a[k]) & (cj <= hi_a[k])
    best[inside] = r[j[inside]]
    # the support at each interval's start, and the lowest it reaches over the interval
    top = np.full(len(lo), -np.inf)
    np.maximum.at(top, k, reach_lo)
    s = np.empty(len(lo), dtype=np.int64)
    at_top = np.flatnonzero(reach_lo == top[k])
    s[k[at_top]] = at_top  # a pair supporting each interval's start (any of ties)
    worst = np.minimum(reach_lo[s], reach_hi[s])
    trough = np.mod(cj[s] + np.pi, 2 * np.pi)
    worst = np.where((trough >= lo_a) & (trough <= hi_a), -r[j[s]], worst)
    return best >= worst[k] - eps


def _sweep_pairs(a: np.ndarray, b: np.ndarray, alpha: np.ndarray, eps: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """(angle index, point index) pairs holding, at every angle of the sweep, every point
    whose reach ``a cos α + b sin α`` comes within ``eps`` of the support there (the
    points projected to ``(a, b)`` in the plane of the sweep).

    Exact (no pair that matters is dropped): a fixed point's reach is a sinusoid, whose
    extremes over an interval of angles are at its ends or its crest (trough) inside
    it, and the support is at least the reach of the point supporting an interval's
    start. The filter runs interval by interval, coarse then fine, each pass on the
    pairs the last one kept: on a smooth surface an interval's own candidates are the
    few points near the part of the rim it sweeps, where one candidate list for the
    whole sweep would hold the whole rim at every angle.
    """
    m = len(alpha)
    r, crest = np.hypot(a, b), np.mod(np.arctan2(b, a), 2 * np.pi)
    # the first pass over every point at once: the reach at each interval's two ends
    lo, hi = _intervals(m, _LEVELS[0])
    ends = alpha[np.append(lo, hi[-1])]
    reach = np.cos(ends)[:, None] * a + np.sin(ends)[:, None] * b
    best = np.maximum(reach[:-1], reach[1:])
    inside = np.searchsorted(ends, crest, side="right") - 1
    inside[crest == ends[-1]] = len(lo) - 1
    has = np.flatnonzero((inside >= 0) & (inside < len(lo)))
    best[inside[has], has] = r[has]
    s = np.argmax(reach[:-1], axis=1)  # the support at each interval's start
    rows = np.arange(len(lo))
    worst = np.minimum(reach[:-1][rows, s], reach[1:][rows, s])
    trough = np.mod(crest[s] + np.pi, 2 * np.pi)
    worst = np.where((trough >= alpha[lo]) & (trough <= alpha[hi]), -r[s], worst)
    k, j = np.nonzero(best >= (worst - eps)[:, None])
    for level, coarse in enumerate(_LEVELS[1:], start=1):
        # each kept interval's pairs, split into the finer intervals inside it
        per = _LEVELS[level - 1] // coarse
        lo, hi = _intervals(m, coarse)
        count = np.minimum((k + 1) * per, len(lo)) - k * per
        j = np.repeat(j, count)
        k = _expand(k * per, count)
        keep = _keep(a, b, (r, crest), alpha, eps, lo, hi, k, j)
        k, j = k[keep], j[keep]
    stop = np.where(k == len(lo) - 1, m, hi[k])  # the last interval holds the last angle
    count = stop - lo[k]
    return _expand(lo[k], count), np.repeat(j, count)


def rocking(points: np.ndarray, down: np.ndarray, eps: float, azimuths: int = 24) -> Rocking:
    """Turn the contact direction away from ``down`` along ``azimuths`` ways (2 in a
    plane) over points (n, dim) given relative to the centre of mass, sampled to within
    ``eps`` m. The contact P(u) is the mean of the points within ``eps`` of the support
    plane, which follows a smooth surface far more closely than any single sample."""
    down = np.asarray(down, dtype=float)
    dim = len(down)
    if dim == 3:
        helper = np.eye(3)[np.argmin(np.abs(down))]
        t1 = np.cross(down, helper)
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(down, t1)
        phi = 2 * np.pi * np.arange(azimuths) / azimuths
        directions = np.cos(phi)[:, None] * t1 + np.sin(phi)[:, None] * t2
    else:
        directions = np.array([[-down[1], down[0]], [down[1], -down[0]]])
    alpha = np.radians(np.arange(0.0, 180.0, ROLL_STEP_DEG))
    heights = np.empty((len(directions), len(alpha)))
    tilts = np.empty(len(directions))
    for k, direction in enumerate(directions):  # a few dozen ways, each vectorised
        u = np.cos(alpha)[:, None] * down + np.sin(alpha)[:, None] * direction
        at, j = _sweep_pairs(points @ down, points @ direction, alpha, eps)
        reach = np.einsum("pd,pd->p", u[at], points[j])
        top = np.full(len(alpha), -np.inf)
        np.maximum.at(top, at, reach)
        heights[k] = top
        near = reach >= top[at] - eps
        at, j = at[near], j[near]
        contact = np.stack([np.bincount(at, weights=points[j, d], minlength=len(alpha))
                            for d in range(dim)], axis=1)
        contact /= np.bincount(at, minlength=len(alpha))[:, None]
        cosine = np.einsum("sd,sd->s", u, contact) / np.linalg.norm(contact, axis=1)
        theta = np.arccos(np.clip(cosine, -1.0, 1.0))
        peak = np.maximum.accumulate(theta)
        # A fall well below the best so far ends the branch; smaller dips are the
        # ripple of the sampled surface (a few degrees where the contact crosses the
        # bottom).
        fell = (theta < peak - np.maximum(np.radians(3.0), 0.5 * peak)) & (alpha >= np.radians(5.0))
        end = int(np.argmax(fell)) if fell.any() else len(alpha) - 1
        tilts[k] = np.degrees(peak[end])
    return Rocking(down, directions, alpha, heights, tilts)
