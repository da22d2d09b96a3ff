"""Welding a triangle soup: exact copies of a point become one vertex.

A soup (STL, a scene's meshes) repeats each vertex once per triangle that uses
it; topology needs shared vertices. Points are hashed by their bit patterns
(one pass, no sort of rows), so only exact copies merge: nothing is snapped,
and the geometry is kept bit for bit.
"""

from __future__ import annotations

import numpy as np

__all__ = ["merge_vertices"]


def _mix(z: np.ndarray) -> np.ndarray:
    """splitmix64's finaliser: every input bit reaches every output bit (uint64, wraps)."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def merge_vertices(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Distinct points and the index of each input point among them.

    Parameters
    ----------
    points : (n, 3) array_like
        Any float dtype; ``-0.0`` and ``0.0`` count as the same coordinate.

    Returns
    -------
    vertices : (V, 3) float64 ndarray
        The distinct points, in the order of their hashes (not of first use).
    index : (n,) int ndarray
        ``vertices[index]`` equals ``points``.

    Examples
    --------
    >>> import numpy as np
    >>> vertices, index = merge_vertices([[0, 0, 0], [1, 0, 0], [-0.0, 0, 0]])
    >>> len(vertices), bool(index[0] == index[2]), bool(index[0] == index[1])
    (2, True, False)
    >>> np.array_equal(vertices[index], [[0, 0, 0], [1, 0, 0], [0, 0, 0]])
    True
    """
    p = np.ascontiguousarray(points, dtype=float).reshape(-1, 3) + 0.0  # -0.0 → 0.0
    bits = p.view(np.uint64)
    key = _mix(_mix(_mix(bits[:, 0]) ^ bits[:, 1]) ^ bits[:, 2])
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    unique = p[first]
    if not np.array_equal(unique[inverse], p):  # a hash collision: merge exactly instead
        unique, inverse = np.unique(p, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1)
