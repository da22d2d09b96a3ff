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

from typing import TYPE_CHECKING

import numpy as np

from ..arrays import dot
from ..lazy import lazy_exports
from .sweep import candidate_pairs, sweep_planes
from .sweep import sweep_pairs as _sweep_pairs

if TYPE_CHECKING:
    from .rocking_result import Rocking

__all__ = ["Rocking", "least_tilt", "rocking"]

#: the result of :func:`rocking` (and its probe angle) live in :mod:`.rocking_result`,
#: loaded on first use: resting poses ask only :func:`least_tilt`
__getattr__, __dir__ = lazy_exports(__name__, {"Rocking": "plumbob.stability.rocking_result",
                                               "PROBE_DEG": "plumbob.stability.rocking_result"},
                                    __all__)

ROLL_STEP_DEG = 0.25


def rocking(points: np.ndarray, down: np.ndarray, eps: float, azimuths: int = 24) -> Rocking:
    """Turn the contact direction away from ``down`` along ``azimuths`` ways (2 in a
    plane) over points (n, dim) given relative to the centre of mass, sampled to within
    ``eps`` m. The contact P(u) is the mean of the points within ``eps`` of the support
    plane, which follows a smooth surface far more closely than any single sample."""
    down = np.asarray(down, dtype=float)
    directions = _directions(down, azimuths)
    alpha = _angles()
    pairs = _sweep_pairs(points @ down, directions @ points.T, alpha, eps, sweep_planes(directions))
    heights = np.empty((len(directions), len(alpha)))
    tilts = np.empty(len(directions))
    for ways in _groups([len(at) for at, _ in pairs]):  # ways together, pairs bounded
        heights[ways], tilts[ways] = _sweep(points, down, directions[ways], alpha, eps,
                                            [pairs[k] for k in ways])
    from .rocking_result import Rocking

    return Rocking(down, directions, alpha, heights, tilts)


def _directions(down: np.ndarray, azimuths: int) -> np.ndarray:
    """The ways the contact direction is turned: ``azimuths`` unit vectors perpendicular
    to ``down`` (3D), or the two of a plane."""
    if len(down) == 3:
        t1, t2 = _across(down)
        phi = 2 * np.pi * np.arange(azimuths) / azimuths
        return np.cos(phi)[:, None] * t1 + np.sin(phi)[:, None] * t2
    return np.array([[-down[1], down[0]], [down[1], -down[0]]])


def _across(down: np.ndarray) -> np.ndarray:
    """Two orthonormal directions (2, 3) perpendicular to ``down`` (unit, 3D): the
    ways' directions are combinations of them."""
    helper = np.eye(3)[np.argmin(np.abs(down))]
    t1 = np.cross(down, helper)
    t1 /= np.linalg.norm(t1)
    return np.stack((t1, np.cross(down, t1)))


def _angles() -> np.ndarray:
    """The angles α the contact direction is turned through, radians."""
    return np.radians(np.arange(0.0, 180.0, ROLL_STEP_DEG))


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
    top, theta = _contact_angles(points, down, directions, alpha, eps, pairs)
    peak, end, _ = _ends(theta, alpha, np.full(len(directions), -np.inf))
    K, m = theta.shape
    end = np.where(end < 0, m - 1, end)
    return top, np.degrees(peak[np.arange(K), end])


def _contact_angles(points: np.ndarray, down: np.ndarray, directions: np.ndarray,
                    alpha: np.ndarray, eps: float, pairs: list[tuple[np.ndarray, np.ndarray]],
                    columns: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Heights (K, m), m, and the angle θ (K, m), radians, between each contact direction
    and its contact, from each way's (angle, point) pairs. ``columns``: the points'
    coordinates as contiguous rows (dim, n), when the caller has them (a copy of every
    point's coordinates per call otherwise: most of a few-way sweep's cost)."""
    K, m, dim = len(directions), len(alpha), len(down)
    u = (np.cos(alpha)[None, :, None] * down
         + np.sin(alpha)[None, :, None] * directions[:, None, :]).reshape(K * m, dim)
    at = np.concatenate([k * m + a for k, (a, _) in enumerate(pairs)])
    j = np.concatenate([b for _, b in pairs])
    # u·p coordinate by coordinate, each gathered from its own contiguous column: a
    # gather of whole rows and einsum over 3 terms cost some 5 times as much
    u_at = np.ascontiguousarray(u.T)
    p_at = np.ascontiguousarray(points.T) if columns is None else columns
    reach = u_at[0][at] * p_at[0][j]
    for d in range(1, dim):
        reach += u_at[d][at] * p_at[d][j]
    top = np.full(K * m, -np.inf)
    np.maximum.at(top, at, reach)
    near = reach >= top[at] - eps
    at, j = at[near], j[near]
    contact = np.stack([np.bincount(at, weights=p_at[d][j], minlength=K * m)
                        for d in range(dim)], axis=1)
    contact /= np.bincount(at, minlength=K * m)[:, None]
    # |contact| as sqrt(dot): np.linalg.norm's numbers, bit for bit, without its wrapper
    cosine = np.einsum("sd,sd->s", u, contact) / np.sqrt(dot(contact, contact))
    theta = np.arccos(np.clip(cosine, -1.0, 1.0)).reshape(K, m)
    return top.reshape(K, m), theta


def _ends(theta: np.ndarray, alpha: np.ndarray, before: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The running peak of θ (K, m) over the angles ``alpha`` (m,), each way's peak
    ``before`` them (K,) included, where each way's branch ends (the first angle of a
    fall, −1 where none) and its tilt there, degrees (NaN where none)."""
    peak = np.maximum(np.maximum.accumulate(theta, axis=1), before[:, None])
    # A fall well below the best so far ends the branch; smaller dips are the ripple of
    # the sampled surface (a few degrees where the contact crosses the bottom).
    fell = (theta < peak - np.maximum(np.radians(3.0), 0.5 * peak)) & (alpha >= np.radians(5.0))
    end = np.where(fell.any(axis=1), np.argmax(fell, axis=1), -1)
    tilt = np.where(end >= 0, np.degrees(peak[np.arange(len(theta)), np.maximum(end, 0)]),
                    np.nan)
    return peak, end, tilt


_FIRST = 32  # angles every way is swept through before the least tilt is sought
_FIRST_UNDER_A_LOW_CAP = (2.0, 8)  # or, where the cap is below 2°, through these
_LEAST_BLOCK = 128  # angles the way of least peak is swept on by, at a time
_BLOCK = 32  # and the others (blocks tuned on the 100k-200k replays: 64, 128, 64 and
# 16 under a low cap cost a third more)
# The interval filter's passes for a way's own candidates: its cone has already kept only
# the points near its arc, so a coarse pass would keep nearly all; one pass by 8 angles
# (dense, over the candidates) costs ~10 % less than (64, 8) over the 200k replays, with
# the same pairs swept
_LEVELS = (8,)


def least_tilt(points: np.ndarray, down: np.ndarray, eps: float, cap_deg: float = np.inf,
               azimuths: int = 24) -> float:
    """``min(cap_deg, rocking(points, down, eps, azimuths).tilts_deg.min())``, degrees:
    the steepest tilt the rocker holds whichever way it is tilted, found without
    sweeping every way through every angle.

    A way's tilt is the peak of its θ up to where its branch ends, so its peak so far
    is a lower bound of it: once that reaches the least tilt found yet (or
    ``cap_deg``), the way cannot lower the answer and is swept no further. Every way is
    swept through the first :data:`_FIRST` angles (fewer under a low cap, where
    most often every way's peak passes the cap within a few degrees, and those few
    degrees' cone holds a few points); then, over and over, the way of
    least peak is swept on to its end (most often near the least tilt) or until its
    peak passes the least tilt so far, and the other ways still below it by a block.
    Each sweep takes only the points that can come within ``eps`` of the support on
    each way's arc (:func:`_on_arcs`; for many ways at once, among those that can on
    the one cone about down that holds their arcs, :func:`_near_down`), each way its
    own (:func:`~plumbob.stability.sweep.candidate_pairs`). The angles a way is swept
    through give the θ the whole sweep gives there (the same points reach the
    support; the contact's sum may be taken in another order: round-off), so the
    answer is the whole sweep's.
    """
    down = np.asarray(down, dtype=float)
    directions = _directions(down, azimuths)
    alpha = _angles()
    K, m = len(directions), len(alpha)
    a = points @ down
    # The points' coordinates across down (a basis of the ways' directions): the cone
    # about down measures distances across it from these. Along a way, every point's
    # (a row of B) is computed once that way is swept alone or with one other.
    across = points @ _across(down).T if len(down) == 3 else None
    B = np.empty((K, len(points)))
    has_row = np.zeros(K, dtype=bool)
    columns = np.ascontiguousarray(points.T)  # for every sweep's contacts

    def rows(ways: np.ndarray) -> np.ndarray:
        new = ways[~has_row[ways]]
        if len(new):
            B[new], has_row[new] = directions[new] @ points.T, True
        if len(ways) == 1:  # one way's row, not a copy of it
            return B[int(ways[0]):int(ways[0]) + 1]
        return B[ways]

    scale = float(np.max(np.abs(points))) if len(points) else 0.0
    radius = float(np.sqrt(dot(points, points).max())) if len(points) else 0.0
    bound = float(cap_deg) if cap_deg < np.inf else np.inf  # NaN: no cap
    peak = np.full(K, -np.inf)
    at = np.zeros(K, dtype=np.int64)  # each way has been swept through the angles before
    ended = np.zeros(K, dtype=bool)

    def sweep(ways: np.ndarray, stop: int) -> None:
        """Sweep ``ways`` (all at one angle) on to the angle before ``stop``."""
        nonlocal bound
        first = int(at[ways[0]])
        arc = alpha[first:stop]
        reach = eps + 1e-9 * scale
        if len(ways) > 2 and across is not None:
            # the ways' arcs all lie in one cone about down: one pass over the points (in
            # space) keeps those that can reach the support there, each way's cone then
            # looks at those alone
            some = _near_down(a, across, float(arc[-1]), reach, radius)
            a_ways, B_ways = a[some], directions[ways] @ points[some].T
        else:
            some, a_ways, B_ways = None, a, rows(ways)
        if some is None and _cone_cut(arc, reach, radius) is not None:
            # one or two ways over every point: each way's few candidates found from a
            # cut along its arc's middle direction first (the same points, in order)
            found = [_on_arc(a, B_ways[k], arc, reach, radius) for k in range(len(ways))]
            way = np.repeat(np.arange(len(ways)), [len(f) for f in found])
            point = np.concatenate(found)
        else:
            way, point = np.nonzero(_on_arcs(a_ways, B_ways, arc, reach))
        cuts = np.searchsorted(way, np.arange(len(ways) + 1))
        pairs = candidate_pairs(a_ways[point], B_ways[way, point], cuts,
                                point if some is None else some[point], arc, eps, _LEVELS)
        _, theta = _contact_angles(points, down, directions[ways], arc, eps, pairs, columns)
        running, end, tilt = _ends(theta, arc, peak[ways])
        peak[ways], at[ways] = running[:, -1], stop
        if stop == m:  # a branch that never fell ends at the last angle
            tilt = np.where(end < 0, np.degrees(running[:, -1]), tilt)
        done = ~np.isnan(tilt)
        ended[ways[done]] = True
        if done.any():
            bound = min(bound, float(tilt[done].min()))

    def live() -> np.ndarray:
        return np.flatnonzero(~ended & ~(np.degrees(peak) >= bound))

    low, few = _FIRST_UNDER_A_LOW_CAP
    sweep(np.arange(K), min(few if bound < low else _FIRST, m))
    while len(ways := live()):
        least = ways[np.argmin(peak[ways])]
        while not ended[least] and not np.degrees(peak[least]) >= bound:
            sweep(np.array([least]), min(int(at[least]) + _LEAST_BLOCK, m))
        for start in sorted(set(at[ways := live()].tolist())):  # the others, where they are
            group = ways[at[ways] == start]
            sweep(group, min(int(start) + _BLOCK, m))
    return bound


def _on_arcs(a: np.ndarray, B: np.ndarray, arc: np.ndarray, reach: float) -> np.ndarray:
    """Which points (ways, n) can come within ``reach`` of the support along each way's
    arc of contact directions ``cos α down + sin α direction`` (α in ``arc``, a
    direction per row of ``B``: the points' coordinates along it; ``a`` along
    ``down``).

    An arc of half-width A about its middle direction c lies in the cone of directions
    within A of c. If q is the support point of c, every direction u of the cone has
    support at least u·q, so a point p comes within ``reach`` of it only if
    u·(p − q) ≥ −reach for some u in the cone: with v = p − q (v·c ≤ 0, its angle
    from c is past 90° ≥ A), (v·c) cos A + |v × c| sin A ≥ −reach. The support point of
    every direction passes the test, and on a smooth surface few others do. An arc's
    directions lie in its way's plane, where u·v is u·v' with v' the part of v in the
    plane: the test holds with |v' × c|, no more than |v × c|, one coordinate of v'.
    For many ways at once, the points are first narrowed by the one cone about down
    that holds all their arcs (:func:`_near_down`)."""
    mid = 0.5 * (arc[0] + arc[-1])
    half = 0.5 * (arc[-1] - arc[0])
    along = np.cos(mid) * a + np.sin(mid) * B  # (ways, n): each point along each c
    across = np.cos(mid) * B - np.sin(mid) * a  # and across it, in the way's plane
    top = np.argmax(along, axis=1)
    rows = np.arange(len(B))
    depth = along - along[rows, top][:, None]  # v·c ≤ 0
    side = np.abs(across - across[rows, top][:, None])  # |v' × c|
    return depth * np.cos(half) + side * np.sin(half) >= -reach


def _cut(half: float, reach: float, radius: float) -> float | None:
    """How far below the top of the points along a cone's axis c (half-width ``half``)
    a point can lie and still pass the cone's test (:func:`_on_arcs`, :func:`_near_down`;
    None for a cone wider than 60° each way, where the cut would keep nearly all): with
    depth = (v·c) ≤ 0 and side ≤ 2 ``radius`` (both points within ``radius`` of the
    origin), depth cos A + side sin A ≥ −reach needs depth ≥ −(reach + 2 radius sin A) /
    cos A; widened by 1e-9 of the radius, far past the rounding of the terms (some 1e-16
    of it)."""
    if not np.cos(half) >= 0.5:
        return None
    return float((reach + 2.0 * radius * np.sin(half)) / np.cos(half) + 1e-9 * radius)


def _cone_cut(arc: np.ndarray, reach: float, radius: float) -> float | None:
    """:func:`_cut` for the cone about the middle direction of ``arc`` (its half-width)."""
    return _cut(0.5 * (arc[-1] - arc[0]), reach, radius)


def _on_arc(a: np.ndarray, b: np.ndarray, arc: np.ndarray, reach: float, radius: float
            ) -> np.ndarray:
    """``np.flatnonzero(_on_arcs(a, b[None, :], arc, reach)[0])`` for one way (``b``: the
    points' coordinates along its direction; ``radius``: no point is further from the
    origin), with the test's numbers, bit for bit, computed only for the points within
    :func:`_cone_cut` of the top along the arc's middle direction (the others fail it):
    on an egg's 99,000 hull points a third of the passes over them."""
    mid = 0.5 * (arc[0] + arc[-1])
    half = 0.5 * (arc[-1] - arc[0])
    along = np.cos(mid) * a + np.sin(mid) * b  # as _on_arcs computes it, row by row
    top = int(np.argmax(along))
    near = (along >= along[top] - _cone_cut(arc, reach, radius)).nonzero()[0]
    across = np.cos(mid) * b[near] - np.sin(mid) * a[near]
    depth = along[near] - along[top]
    side = np.abs(across - (np.cos(mid) * b[top] - np.sin(mid) * a[top]))
    return near[depth * np.cos(half) + side * np.sin(half) >= -reach]


def _near_down(a: np.ndarray, across: np.ndarray, half: float, reach: float,
               radius: float | None = None) -> np.ndarray:
    """Indices of the points that can come within ``reach`` of the support for some
    direction within ``half`` (radians, up to π) of down: :func:`_on_arcs`'s test for
    the one cone about down that holds every way's arc of a block (one test for all the
    ways, in space, where a cone each costs a pass over the points each). With φ the
    angle of v from down (past 90°), the test reads |v| cos(φ − half) ≥ −reach: exact
    where φ > half, and passed where φ ≤ half (the cosine is then not negative), so it
    holds for a cone wider than 90° too. ``a``: the points' coordinates along down;
    ``across`` (n, 2): along two orthonormal directions across it, from which |v × c|
    is taken (not from |v|² − (v·c)², which cancels near c). ``radius``, when given: no
    point lies further from the origin, and only the points within :func:`_cut` of the
    top along down are measured (the others fail the test; the same indices)."""
    top = int(np.argmax(a))
    cut = _cut(half, reach, radius) if radius is not None else None
    if cut is not None:  # the test, bit for bit, on the points within the cut alone
        near = (a >= a[top] - cut).nonzero()[0]
        depth = a[near] - a[top]
        side = np.hypot(across[near, 0] - across[top, 0], across[near, 1] - across[top, 1])
        return near[depth * np.cos(half) + side * np.sin(half) >= -reach]
    depth = a - a[top]  # v·c ≤ 0
    side = np.hypot(across[:, 0] - across[top, 0], across[:, 1] - across[top, 1])
    return np.flatnonzero(depth * np.cos(half) + side * np.sin(half) >= -reach)
