"""Welding a triangle soup: copies of a point become one vertex.

A soup (STL, a scene's meshes) repeats each vertex once per triangle that uses
it; topology needs shared vertices. Exact copies are found by hashing their bit
patterns (one pass, no sort of rows). Copies that a CAD exporter computed along
two paths may differ in their last bits (SolidWorks writes ``-6.1e-17`` for one
copy of ``0.0``): :func:`weld_near` merges points closer than a tolerance, with
a grid of cells and no Python loop over points. Welding only says which corners
are one vertex; a mesh's triangles keep their coordinates.
"""

from __future__ import annotations

import numpy as np

from ..arrays import RADIX_MIN, connected_components, stable_order, unique

__all__ = ["merge_vertices", "point_keys", "unique_first", "weld_near"]

#: a cell of the welding grid is this many tolerances wide (more than twice, so that two
#: points within the tolerance share a cell of at least one of the eight shifted grids)
CELL = 4.0


_GOLDEN = np.uint64(0x9E3779B97F4A7C15)

#: runs of keys alike in their top 32 bits sorted one by one, at most (more: a whole sort)
_FEW_RUNS = 64


_S30, _S27, _S31 = np.uint64(30), np.uint64(27), np.uint64(31)
_M1, _M2 = np.uint64(0xBF58476D1CE4E5B9), np.uint64(0x94D049BB133111EB)


def _mix(z: np.ndarray, scratch: np.ndarray) -> np.ndarray:
    """splitmix64's finaliser on ``z`` (uint64, wraps), in place (``scratch``: an array
    like it): every input bit reaches every output bit. In place, the three rounds of a
    float64 point's key make no temporaries: a fifth less time than ``z ^ (z >> 30)``."""
    np.right_shift(z, _S30, out=scratch)
    z ^= scratch
    z *= _M1
    np.right_shift(z, _S27, out=scratch)
    z ^= scratch
    z *= _M2
    np.right_shift(z, _S31, out=scratch)
    z ^= scratch
    return z


def point_keys(points: np.ndarray) -> np.ndarray:
    """A 64-bit hash (n,) of each point (n, 3) from its coordinates' bits: equal points get
    equal keys (``-0.0`` and ``0.0`` too); float32 points are hashed without conversion,
    two coordinates packed in one word and one mixing round (the fast STL path)."""
    p = np.asarray(points)
    if p.dtype != np.float32:
        p = p.astype(float, copy=False)
    p = p.reshape(-1, 3) + p.dtype.type(0)  # -0.0 → 0.0 (and a contiguous copy)
    with np.errstate(over="ignore"):
        if p.dtype == np.float32:
            b = p.view(np.uint32)
            xy = (b[:, 0].astype(np.uint64) << np.uint64(32)) | b[:, 1]
            xy ^= b[:, 2] * _GOLDEN
            return _mix(xy, np.empty_like(xy))
        b = p.view(np.uint64)
        # each coordinate mixed before the next joins: a product's top bit carries only its
        # factor's top bit, so `x ^ y * G` gave (x, y) and (-x, -y) one key (every
        # antipodal pair of a circle's points: all collisions, and the slow exact path)
        z = b[:, 0].copy()
        scratch = np.empty_like(z)
        _mix(z, scratch)
        z ^= b[:, 1]
        _mix(z, scratch)
        z ^= b[:, 2]
        return _mix(z, scratch)


def unique_first(keys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``np.unique(keys, return_index=True, return_inverse=True)[1:]`` for uint64 keys
    (hashes): the first index of each distinct key, in the order of the sorted keys, and
    each key's group.

    A stable argsort of the keys, made fast: one plain sort of words packing each key's
    top bits above its index, or from :data:`~plumbob.arrays.RADIX_MIN` keys a stable
    sort of their top 32 bits by 16-bit digits (two linear passes), after which the few
    runs of different keys that share their top bits (:func:`_ties_sorted`) are sorted by
    the whole key; should the sorted keys still come out of order, a stable
    ``np.argsort`` decides. 5–10× faster than the stable sort ``np.unique`` needs, same
    answer.

    >>> [a.tolist() for a in unique_first(np.array([7, 3, 7, 5, 3], dtype=np.uint64))]
    [[1, 3, 0], [2, 0, 2, 1, 0]]
    """
    keys = np.asarray(keys, dtype=np.uint64).reshape(-1)
    n = len(keys)
    if n >= RADIX_MIN:  # by the top 32 bits, two linear passes (arrays.stable_order)
        order = stable_order((keys >> np.uint64(32)).astype(np.int64))
        sk = keys[order]
        order, sk = _ties_sorted(keys, order, sk)
    else:
        bits = np.uint64(max(n - 1, 1).bit_length())
        packed = (keys >> bits) << bits
        packed |= np.arange(n, dtype=np.uint64)
        packed.sort()
        order = (packed & ((np.uint64(1) << bits) - np.uint64(1))).astype(np.intp)
        sk = keys[order]
    if np.any(sk[1:] < sk[:-1]):  # two keys alike in their top bits: sort them all
        order = np.argsort(keys, kind="stable")
        sk = keys[order]
    new = np.empty(n, dtype=bool)
    new[:1] = True
    np.not_equal(sk[1:], sk[:-1], out=new[1:])
    inverse = np.empty(n, dtype=np.intp)
    inverse[order] = np.cumsum(new) - 1
    return order[new], inverse


def _ties_sorted(keys: np.ndarray, order: np.ndarray,
                 sk: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A stable order of the keys' top 32 bits (``order``, ``sk`` the keys in it) made a
    stable order of the whole keys: each run of keys alike in their top bits that holds
    different keys is sorted on its own. Hashes of d distinct points share their top 32
    bits in about d² / 2³³ pairs (one pair in a 100,000-triangle mesh's 50,000 points, a
    quarter): a few small runs, where a third pass over every key would cost ~2 ms. Keys
    that are not such hashes, with many runs of ties, are sorted whole, stably."""
    top = sk >> np.uint64(32)
    ties = np.flatnonzero((top[1:] == top[:-1]) & (sk[1:] != sk[:-1]))
    starts = unique(np.searchsorted(top, top[ties]))  # (np.unique would load numpy.ma)
    if len(starts) > _FEW_RUNS:
        order = np.argsort(keys, kind="stable")
        return order, keys[order]
    for start in starts:
        stop = np.searchsorted(top, top[start], side="right")
        run = order[start:stop]
        run = run[np.argsort(keys[run], kind="stable")]
        order[start:stop] = run
        sk[start:stop] = keys[run]
    return order, sk


def merge_vertices(points: np.ndarray, tolerance: float = 0.0, *,
                   keys: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Distinct points and the index of each input point among them.

    Parameters
    ----------
    points : (n, 3) array_like
        Any float dtype; ``-0.0`` and ``0.0`` count as the same coordinate.
    tolerance : float
        m; 0 merges exact copies only. Above 0, points closer than it are merged too
        (:func:`weld_near`); each merged group keeps its first point's coordinates.
    keys : (n,) uint64 ndarray, optional
        ``point_keys`` of the points as float64, when the caller has them (a mesh check
        hashed them already: :func:`~plumbob.mesh.closure.paired_keys`); they decide the
        vertices' order, and a collision is caught as without them.

    Returns
    -------
    vertices : (V, 3) float64 ndarray
        The distinct points, in the order of their hashes (not of first use).
    index : (n,) int ndarray
        ``vertices[index]`` equals ``points`` (to within the welding distance).

    Examples
    --------
    >>> import numpy as np
    >>> vertices, index = merge_vertices([[0, 0, 0], [1, 0, 0], [-0.0, 0, 0]])
    >>> len(vertices), bool(index[0] == index[2]), bool(index[0] == index[1])
    (2, True, False)
    >>> np.array_equal(vertices[index], [[0, 0, 0], [1, 0, 0], [0, 0, 0]])
    True
    >>> len(merge_vertices([[0, 0, 0], [1, 0, 0], [-6.1e-17, 0, 0]], 1e-12)[0])
    2
    """
    p = np.ascontiguousarray(points, dtype=float).reshape(-1, 3)  # no copy of float64 rows
    first, inverse = unique_first(point_keys(p) if keys is None else keys.reshape(-1))
    unique = np.take(p, first, axis=0) + 0.0  # -0.0 → 0.0 (the keys hash them alike)
    # a hash collision (two points, one key): merge exactly instead (-0.0 == 0.0 here)
    if not np.array_equal(np.take(unique, inverse, axis=0), p):
        unique, inverse = np.unique(p + 0.0, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    if tolerance > 0 and len(unique) > 1:
        group = weld_near(unique, tolerance)
        _, keep, relabel = np.unique(group, return_index=True, return_inverse=True)
        unique, inverse = unique[keep], relabel.reshape(-1)[inverse]
    return unique, inverse


def weld_near(points: np.ndarray, tolerance: float) -> np.ndarray:
    """Group label (n,) of each point (n, 3): points closer than ``tolerance`` (m) share one.

    Points are binned in eight grids of cells :data:`CELL` tolerances wide, each
    shifted by half a cell along some axes; two points within the tolerance share
    a cell of at least one grid, and points sharing a cell are joined. Groups are
    the connected components, so a point may join one up to 7 tolerances away
    (a cell's diagonal): the tolerance is a scale far below any feature, not an
    exact radius. Labels are numbered by each group's first point.

    Examples
    --------
    >>> import numpy as np
    >>> weld_near(np.array([[0.0, 0, 0], [1e-9, 0, 0], [1.0, 0, 0], [2e-9, 1e-9, 0]]),
    ...           1e-8).tolist()
    [0, 0, 1, 0]
    """
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    n = len(p)
    if n < 2 or not tolerance > 0:
        return np.arange(n)
    scaled = (p - p.min(axis=0)) / (CELL * tolerance)
    u, v = [], []
    for shift in range(8):  # the eight grids, each a sort of the points
        offset = 0.5 * np.array([(shift >> axis) & 1 for axis in range(3)])
        q = np.floor(scaled + offset).astype(np.int64)
        order = np.lexsort(q.T[::-1])
        sq = q[order]
        new = np.r_[True, np.any(sq[1:] != sq[:-1], axis=1)]
        lead = order[np.flatnonzero(new)[np.cumsum(new) - 1]]
        joined = lead != order
        u.append(lead[joined])
        v.append(order[joined])
    return connected_components(n, np.concatenate(u), np.concatenate(v))
