"""Which points come near the support as the contact direction sweeps a plane: the
exact candidate filters of the rocker's sweep (:mod:`.rocking`).

Points ``p`` are projected to ``(a, b)`` in the plane of a sweep; at angle α a point
reaches ``a cos α + b sin α``, and the support is the greatest reach. The sweep needs,
at each of its angles, every point within ``eps`` of the support, and those pairs
alone are worth computing in full. Two filters find a superset of them, exactly (no
pair that matters is dropped): by intervals of angles (:func:`interval_pairs`, for
few points) and by bins of the points' crest angles (:func:`sweep_pairs`).
"""

from __future__ import annotations

import numpy as np

from ..arrays import expand

__all__ = ["BINNED", "candidate_pairs", "group_max", "interval_pairs", "sweep_pairs", "sweep_planes"]

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


def interval_pairs(a: np.ndarray, B: np.ndarray, alpha: np.ndarray, eps: float
                   ) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per row ``b`` of ``B`` (K, n): (angle index, point index) pairs holding, at every
    angle of the sweep, every point whose reach ``a cos α + b sin α`` comes within
    ``eps`` of the support there (the points projected to ``(a, b)`` in the plane of
    the sweep): :func:`candidate_pairs` with every point a candidate of every row."""
    K, n = B.shape
    return candidate_pairs(np.tile(a, K), B.ravel(), np.arange(K + 1) * n,
                           np.tile(np.arange(n), K), alpha, eps)


def candidate_pairs(a: np.ndarray, b: np.ndarray, bounds: np.ndarray, point: np.ndarray,
                    alpha: np.ndarray, eps: float, levels: tuple[int, ...] = _LEVELS
                    ) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per direction q, from its candidates ``a[bounds[q]:bounds[q + 1]]``,
    ``b[…]`` (the points ``point[…]``, which must hold every point that supports
    somewhere on the sweep, each once): (angle index, point) pairs holding, at every
    angle of the sweep, every candidate whose reach ``a cos α + b sin α`` comes within
    ``eps`` of the support there. Each direction has at least one candidate.

    Exact (no pair that matters is dropped): a fixed point's reach is a sinusoid, whose
    extremes over an interval of angles are at its ends or its crest (trough) inside
    it, and the support is at least the reach of the point supporting an interval's
    start. The filter runs interval by interval, coarse then fine, each pass on the
    pairs the last one kept: on a smooth surface an interval's own candidates are the
    few points near the part of the rim it sweeps, where one candidate list for the
    whole sweep would hold the whole rim at every angle. Every direction's sweep runs
    in the same passes (its candidates are a run of one flat array, its intervals are
    intervals ``q I …``), each direction's pairs in the order of its own sweep, at each
    angle in the order of its candidates (so a sum over them is taken in that order).
    """
    K, m = len(bounds) - 1, len(alpha)
    owner = np.repeat(np.arange(K), np.diff(bounds))
    r, crest = np.hypot(a, b), np.mod(np.arctan2(b, a), 2 * np.pi)
    # the first pass over every point at once: the reach at each interval's two ends
    lo, hi = _intervals(m, levels[0])
    count = len(lo)
    ends = alpha[np.append(lo, hi[-1])]
    reach = np.cos(ends)[:, None] * a + np.sin(ends)[:, None] * b
    best = np.maximum(reach[:-1], reach[1:])
    inside = np.searchsorted(ends, crest, side="right") - 1
    inside[crest == ends[-1]] = count - 1
    has = np.flatnonzero((inside >= 0) & (inside < count))
    best[inside[has], has] = r[has]
    # the support at each interval's start, per direction (its first candidate of
    # greatest reach: flat ids), and the least it reaches
    start = reach[:-1]
    top = np.maximum.reduceat(start, bounds[:-1], axis=1)  # (intervals, K)
    first = np.where(start == top[:, owner], np.arange(len(a)), len(a))
    s = np.minimum.reduceat(first, bounds[:-1], axis=1)
    rows = np.arange(count)[:, None]
    worst = np.minimum(reach[:-1][rows, s], reach[1:][rows, s])
    trough = np.mod(crest[s] + np.pi, 2 * np.pi)
    in_lo = (trough >= alpha[lo][:, None]) & (trough <= alpha[hi][:, None])
    worst = np.where(in_lo, -r[s], worst)
    near = best >= (worst - eps)[:, owner]
    j, k = np.nonzero(near.T)  # each direction's pairs together (its candidates are a run)
    q = owner[j]
    for level, coarse in enumerate(levels[1:], start=1):
        # each kept interval's pairs, split into the finer intervals inside it
        per = levels[level - 1] // coarse
        lo, hi = _intervals(m, coarse)
        count = len(lo)
        split = np.minimum((k + 1) * per, count) - k * per
        j, q = np.repeat(j, split), np.repeat(q, split)
        k = _expand(k * per, split)
        keep = _keep(a, b, (r, crest), alpha, eps, np.tile(lo, K), np.tile(hi, K),
                     q * count + k, j)
        k, j, q = k[keep], j[keep], q[keep]
    stop = np.where(k == len(lo) - 1, m, hi[k])  # the last interval holds the last angle
    span = stop - lo[k]
    angle, points = _expand(lo[k], span), np.repeat(point[j], span)
    cuts = np.searchsorted(np.repeat(q, span), np.arange(K + 1))
    return [(angle[cuts[d]:cuts[d + 1]], points[cuts[d]:cuts[d + 1]]) for d in range(K)]


BINNED = 5_000  # from this many points on, the crest-angle bins' filter
_MANY = 20_000  # past this many points, narrower windows pay for more passes
_CHUNK = 1_000_000  # points × planes filtered together (bounds the temporaries)
_FINE = 4  # finer bins per bin for the farthest points that bound the support
_GROUP = 32  # finer bins whose farthest point finds where the support is
_AROUND = 1  # groups either side of that where the support is sought
_EVERY = 4  # the support point is sought at every so many angles


def sweep_planes(directions: np.ndarray) -> list[tuple[int, int]]:
    """The sweep directions as planes of sweeps: (k, k2) where direction k2 is opposite
    to k (to round-off: its sweep is the other half of the same plane), (k, −1) where
    none is."""
    K = len(directions)
    half = K // 2
    if K % 2 == 0 and K and np.allclose(directions[half:], -directions[:half], rtol=0.0,
                                        atol=1e-12):
        return [(k, k + half) for k in range(half)]
    return [(k, -1) for k in range(K)]


def group_max(r: np.ndarray, key: np.ndarray, groups: int) -> np.ndarray:
    """The largest of ``r`` in each group of ``key`` (−inf for an empty group), exactly
    as ``np.maximum.at`` finds it.

    ``np.maximum.at`` over every point is slow; a power sum is not. The 1024-th root of
    the sum of (r / r_max)^1024 over a group lies between its largest value and that
    times count^(1/1024) (< 1.007 for up to a thousand points), so only the points
    within that factor of it can be the largest: ``np.maximum.at`` runs on those few.
    Values below 0.6 r_max count as 0.6 r_max (no subnormal numbers): a group whose
    bound is that floor has all its points looked at."""
    top = float(r.max()) if len(r) else 0.0
    if not top > 0:
        out = np.full(groups, -np.inf)
        np.maximum.at(out, key, r)
        return out
    x = np.maximum(r * (1.0 / top), 0.6)
    for _ in range(10):
        x *= x
    count = np.bincount(key, minlength=groups)
    bound = top * np.bincount(key, weights=x, minlength=groups) ** (1.0 / 1024)
    least = bound * np.maximum(count, 1) ** (-1.0 / 1024) * (1 - 1e-12)
    least[bound <= 0.6 * top * np.maximum(count, 1) ** (1.0 / 1024) * (1 + 1e-12)] = -np.inf
    some = np.flatnonzero(r >= least[key])
    out = np.full(groups, -np.inf)
    np.maximum.at(out, key[some], r[some])
    return out


def _support_below(x: np.ndarray, y: np.ndarray, far: np.ndarray, cos_t: np.ndarray,
                   sin_t: np.ndarray) -> np.ndarray:
    """At most the support function of the points (x, y) at the angles (cos_t, sin_t),
    and close to it: ``x``, ``y``, ``far`` (F,) are the farthest point of each of F
    bins of their angle about the origin (``far`` −inf for an empty bin, F a multiple
    of ``_GROUP``).

    At every ``_EVERY``-th angle, the best reach (in single precision: it only chooses)
    of the farthest points of groups of ``_GROUP`` bins finds the group nearest the
    support, and the best of every bin's point in that group and the next ones the
    support point. Each angle's bound is the better reach of the support points of the
    two such angles about it (on a smooth rim the support point moves little)."""
    groups = len(far) // _GROUP
    within = np.argmax(far.reshape(groups, _GROUP), axis=1) + _GROUP * np.arange(groups)
    some = np.flatnonzero(np.isfinite(far[within]))
    c, s = cos_t[::_EVERY], sin_t[::_EVERY]
    reach = np.outer(c.astype(np.float32), x[within[some]].astype(np.float32))
    reach += np.outer(s.astype(np.float32), y[within[some]].astype(np.float32))
    best = some[np.argmax(reach, axis=1)]  # the group nearest the support
    offsets = np.arange(-_AROUND * _GROUP, (_AROUND + 1) * _GROUP)
    at = (best[:, None] * _GROUP + offsets) % len(far)
    reach = c[:, None] * x[at] + s[:, None] * y[at]
    reach[np.isinf(far[at])] = -np.inf
    point = at[np.arange(len(at)), np.argmax(reach, axis=1)]  # its support point
    nearest = np.arange(len(cos_t)) // _EVERY
    low = np.full(len(cos_t), -np.inf)
    for k in (point[nearest], point[(nearest + 1) % len(point)]):
        np.maximum(low, cos_t * x[k] + sin_t * y[k], out=low)
    return low


def _distances(limit: int, fine: int) -> list[tuple[int, int]]:
    """(d, w): the angular distances (in bins) tried, ``d .. d + w − 1`` at once: one by
    one up to ``fine``, then in blocks of 4 to 2 ``fine``, of 16 to 256 and of 64 (each
    block judged by its least level and its nearest distance)."""
    out, d = [], 0
    for w, upto in ((1, fine), (4, 2 * fine), (16, 256), (64, limit)):
        while d < min(upto, limit):
            out.append((d, w))
            d += w
    return out


def _farthest(a: np.ndarray, Bc: np.ndarray, step: float, bins: int
              ) -> tuple[np.ndarray, ...]:
    """The points' radii (P, n) in each plane of ``Bc`` (rows: their coordinates along
    its direction, ``a`` along down), the bins of their crest angles (P, n), each bin's
    farthest radius (P, bins), and the same of ``_FINE`` finer bins with the index of
    the point (into the flattened (P, n)) that reaches it (−1 for an empty bin)."""
    P, n = Bc.shape
    r = np.sqrt(a * a + Bc * Bc)
    crest = np.arctan2(Bc, a)
    crest[crest < 0] += 2 * np.pi
    fine = np.minimum((crest * (_FINE / step)).astype(np.int64), _FINE * bins - 1)
    del crest
    key = (fine + (np.arange(P) * (_FINE * bins))[:, None]).ravel()
    far_fine = group_max(r.ravel(), key, P * _FINE * bins)
    at = np.flatnonzero(r.ravel() >= far_fine[key])
    champion = np.full(P * _FINE * bins, -1, dtype=np.int64)
    champion[key[at]] = at
    far = far_fine.reshape(P, bins, _FINE).max(axis=2)
    return r, fine // _FINE, far, far_fine.reshape(P, -1), champion.reshape(P, -1)


def _windows(level: np.ndarray, far: np.ndarray, cos_d: np.ndarray, fine: int
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per bin (P, bins) of crest angles: the least radius a point of it needs to come
    within eps of the support at some angle (``level``: the support's lower bound less
    eps, inf where not swept), and its window each side, (2, P, bins): the angles
    b − d (left) and b + 1 + d (right) for d from ``first`` to ``last``, the distances
    its farthest point (``far``) may reach. A bin is done at the distance past which
    its farthest point reaches no angle of its plane. Distances up to ``fine`` are tried
    one by one (narrower windows), farther ones in blocks (fewer passes)."""
    P, bins = level.shape
    floor = np.full(P * bins, np.inf)
    first = np.full((2, P * bins), bins, dtype=np.int64)
    last = np.full((2, P * bins), -1, dtype=np.int64)
    least_in = level.min(axis=1)
    far = far.ravel()
    active = np.flatnonzero(far >= np.repeat(least_in, bins))
    least_over = {1: level.ravel()}  # the least level over w angles from each on
    for d, w in _distances(len(cos_d), fine):
        if cos_d[d] <= 0:
            break
        active = active[far[active] * cos_d[d] >= least_in[active // bins]]
        if len(active) == 0:
            break  # no point reaches any angle this far from its crest
        if w not in least_over:  # from the least over w / 4 angles (1, 4, 16, 64)
            x = least_over[w // 4].reshape(P, bins)
            for shift in (w // 4, w // 2):
                x = np.minimum(x, np.roll(x, -shift, axis=1))
            least_over[w] = x.ravel()
        row, b = np.divmod(active, bins)
        row *= bins
        # both sides at once: the angles b − d − w + 1 … (left) and b + 1 + d … (right)
        at = np.concatenate((b - (d + w - 1), b + 1 + d)) % bins
        need = least_over[w][np.concatenate((row, row)) + at] / cos_d[d]
        floor[active] = np.minimum(floor[active], np.minimum(need[:len(b)], need[len(b):]))
        hit = need <= np.concatenate((far[active], far[active]))
        side = hit.reshape(2, -1)
        for k in (0, 1):
            h = active[side[k]]
            first[k][h] = np.minimum(first[k][h], d)
            last[k][h] = d + w - 1
    return floor.reshape(P, bins), first.reshape(2, P, bins), last.reshape(2, P, bins)


def sweep_pairs(a: np.ndarray, B: np.ndarray, alpha: np.ndarray, eps: float,
                 planes: list[tuple[int, int]] | None = None
                 ) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per row ``b`` of ``B``: (angle index, point index) pairs holding, at every angle of
    the sweep ``alpha`` (regular steps from 0, less than π), every point whose reach
    ``a cos α + b sin α`` comes within ``eps`` of the support there (the points
    projected to ``(a, b)`` in the plane of the sweep).

    Exact (no pair that matters is dropped), by bounds that only ever keep more. Two
    opposite directions sweep the two halves of one plane, taken together. The points
    are binned by their crest angle (one bin per step of the sweep); a point of radius
    r whose crest lies an angle d (less one bin, for rounding) from α reaches at most
    r cos d there, while the support is at least ``L(α)``, the best reach of the
    farthest points of finer bins about the support (:func:`_support_below`). So a
    bin's points can come near the support only at the angles where its farthest
    point's bound reaches ``L − eps`` (a short window on a smooth rim), and a point
    only if its radius reaches the least of ``(L − eps) / cos d`` over all angles (a
    thin band along the rim). Each point left is tried at each angle of its bin's
    window: on a smooth surface, the few points near the part of the rim each angle
    sweeps, found in a few passes over the points. Below ``BINNED`` points the
    interval filter (:func:`interval_pairs`) runs instead: its passes over all the
    points cost less there than the bins' fixed work over every angle.
    """
    m, n, K = len(alpha), len(a), len(B)
    step = float(alpha[1] - alpha[0]) if m > 1 else np.pi
    bins = max(int(round(2 * np.pi / step)), 2 * m)  # a crest past the last: in it
    scale = float(np.max(np.abs(a))) + float(np.max(np.abs(B))) if n else 0.0
    slack = 1e-9 * scale  # round-off of the bounds: far above it, far below eps
    # each bin's angle: the sweep's angles, the second half mirrored (−α)
    theta = np.arange(bins) * step
    cos_t, sin_t = np.cos(theta), np.sin(theta)
    cos_t[:m], sin_t[:m] = np.cos(alpha), np.sin(alpha)
    mirror = bins - np.arange(1, m)
    cos_t[mirror], sin_t[mirror] = np.cos(alpha[1:]), -np.sin(alpha[1:])
    # cos of the angular distance d between an angle and a bin's crests, less one bin
    # (a crest rounded into the next bin); d = 0 is the bin's own two ends
    cos_d = np.cos(np.maximum(np.arange(bins // 4 + 1) - 1, 0) * step)
    if n < BINNED:  # few points: the interval filter's fewer passes cost less
        return interval_pairs(a, np.asarray(B), alpha, eps)
    out: list[tuple[np.ndarray, np.ndarray]] = [(np.zeros(0, np.int64),) * 2] * K
    planes = [(k, -1) for k in range(K)] if planes is None else planes
    size = max(1, _CHUNK // n)
    for first in range(0, len(planes), size):
        chunk = planes[first:first + size]
        P = len(chunk)
        Bc = B[[k for k, _ in chunk]]
        r, bin_, far, far_fine, champion = _farthest(a, Bc, step, bins)
        low = np.empty((P, bins))
        for p in range(P):
            c = np.maximum(champion[p], 0)
            low[p] = _support_below(a[c % n], Bc.ravel()[c], far_fine[p], cos_t, sin_t)
        level = low - eps - slack
        swept = np.zeros((P, bins), dtype=bool)
        swept[:, :m] = True
        swept[[p for p, (_, k2) in enumerate(chunk) if k2 >= 0], bins - m + 1:] = True
        level[~swept] = np.inf
        least = float(level[swept].min())
        if not least > 0:  # the support comes within eps of the centre: every pair
            for k, k2 in chunk:
                for kk in (k, k2)[:1 + (k2 >= 0)]:
                    out[kk] = (np.repeat(np.arange(m), n), np.tile(np.arange(n), m))
            continue
        floor, first, last = _windows(level, far, cos_d, 64 if n > _MANY else 16)
        for p, (k, k2) in enumerate(chunk):
            j = np.flatnonzero(r[p] >= floor[p, bin_[p]] - slack)
            b = bin_[p, j]
            f, g = first[:, p, b], last[:, p, b]
            lo = np.concatenate((b - g[0], b + 1 + f[1]))
            count = np.maximum(np.concatenate((g[0] - f[0], g[1] - f[1])) + 1, 0)
            rows, i = expand(count, lo)
            j = np.concatenate((j, j))[rows]
            i %= bins
            keep = cos_t[i] * a[j] + sin_t[i] * Bc[p, j] >= level[p, i] - slack
            i, j = i[keep], j[keep]
            first_half = i < m
            out[k] = (i[first_half], j[first_half])
            if k2 >= 0:  # the other half, and the angle 0 both share
                other = ~first_half | (i == 0)
                out[k2] = ((bins - i[other]) % bins, j[other])
    return out
