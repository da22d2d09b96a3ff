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

from .sweep import sweep_pairs as _sweep_pairs
from .sweep import sweep_planes

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
    pairs = _sweep_pairs(points @ down, directions @ points.T, alpha, eps, sweep_planes(directions))
    heights = np.empty((len(directions), len(alpha)))
    tilts = np.empty(len(directions))
    for ways in _groups([len(at) for at, _ in pairs]):  # ways together, pairs bounded
        heights[ways], tilts[ways] = _sweep(points, down, directions[ways], alpha, eps,
                                            [pairs[k] for k in ways])
    return Rocking(down, directions, alpha, heights, tilts)


_PAIRS = 1 << 18  # (angle, point) pairs swept together, at most (bounds the temporaries)


def _groups(counts: list[int]) -> list[list[int]]:
    """Consecutive ways whose pairs add up to at most ``_PAIRS`` (one way at least)."""
    out: list[list[int]] = [[]]
    total = 0
    for k, count in enumerate(counts):
        if out[-1] and total + count > _PAIRS:
            out.append([])
            total = 0
        out[-1].append(k)
        total += count
    return out


def _sweep(points: np.ndarray, down: np.ndarray, directions: np.ndarray, alpha: np.ndarray,
           eps: float, pairs: list[tuple[np.ndarray, np.ndarray]]
           ) -> tuple[np.ndarray, np.ndarray]:
    """Heights (K, m) and tilts (K,) along ``directions`` (K, dim), every way at once
    from its (angle, point) pairs: the support at each angle, the contact (the mean of
    the points within ``eps`` of it) and the tilt the contact holds."""
    K, m, dim = len(directions), len(alpha), len(down)
    u = (np.cos(alpha)[None, :, None] * down
         + np.sin(alpha)[None, :, None] * directions[:, None, :]).reshape(K * m, dim)
    at = np.concatenate([k * m + a for k, (a, _) in enumerate(pairs)])
    j = np.concatenate([b for _, b in pairs])
    reach = np.einsum("pd,pd->p", u[at], points[j])
    top = np.full(K * m, -np.inf)
    np.maximum.at(top, at, reach)
    near = reach >= top[at] - eps
    at, j = at[near], j[near]
    contact = np.stack([np.bincount(at, weights=points[j, d], minlength=K * m)
                        for d in range(dim)], axis=1)
    contact /= np.bincount(at, minlength=K * m)[:, None]
    cosine = np.einsum("sd,sd->s", u, contact) / np.linalg.norm(contact, axis=1)
    theta = np.arccos(np.clip(cosine, -1.0, 1.0)).reshape(K, m)
    peak = np.maximum.accumulate(theta, axis=1)
    # A fall well below the best so far ends the branch; smaller dips are the ripple of
    # the sampled surface (a few degrees where the contact crosses the bottom).
    fell = (theta < peak - np.maximum(np.radians(3.0), 0.5 * peak)) & (alpha >= np.radians(5.0))
    end = np.where(fell.any(axis=1), np.argmax(fell, axis=1), m - 1)
    return top.reshape(K, m), np.degrees(peak[np.arange(K), end])
