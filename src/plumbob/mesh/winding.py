"""Solid angles and winding numbers: which points a surface wraps, and how often.

The signed solid angle a triangle subtends at a point is Van Oosterom and
Strackee's closed form, ``Ω = 2 atan2(a·(b×c), |a||b||c| + (a·b)|c| + (a·c)|b| +
(b·c)|a|)`` with a, b, c the corners seen from the point; it is stable for
small and nearly flat triangles (no arccos). Summed over a closed, outward
surface and divided by 4π it is the winding number: 1 inside, 0 outside, the
nesting depth where shells nest. This module holds the one copy of the formula.
"""

from __future__ import annotations

import numpy as np

from ..arrays import cross

__all__ = ["solid_angle", "solid_angles", "winding_numbers"]

#: corner vectors formed per pass of :func:`winding_numbers` (points × triangles)
WINDING_BLOCK = 2_000_000


def _dot(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", x, y)


def solid_angle(a: np.ndarray, b: np.ndarray, c: np.ndarray, *, unit: bool = False) -> np.ndarray:
    """Signed solid angle (sr) of the triangles with corners ``a, b, c`` (…, 3) seen from 0.

    Positive when ``a → b → c`` turns counter-clockwise seen from the origin's
    far side (the origin is behind an outward face). ``unit``: the vectors are
    unit vectors (the area of a spherical triangle), so their lengths are taken
    as exactly 1.

    Examples
    --------
    >>> import numpy as np
    >>> e = np.eye(3)
    >>> float(solid_angle(e[0], e[1], e[2]) / (4 * np.pi))  # one octant of the sphere
    0.125
    >>> float(solid_angle(e[0], e[2], e[1], unit=True) / (4 * np.pi))  # the other way round
    -0.125
    """
    if unit:
        num = _dot(a, cross(b, c))
        den = 1.0 + _dot(a, b) + _dot(b, c) + _dot(c, a)
        return 2.0 * np.arctan2(num, den)
    la, lb, lc = (np.sqrt(_dot(x, x)) for x in (a, b, c))
    det = _dot(a, cross(b, c))
    den = la * lb * lc + _dot(a, b) * lc + _dot(a, c) * lb + _dot(b, c) * la
    return 2 * np.arctan2(det, den)


def solid_angles(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """Signed solid angle (k, m), sr, that each triangle (m, 3, 3) subtends at each point (k, 3).

    Examples
    --------
    >>> import numpy as np
    >>> tri = np.array([[[1.0, 0, 0], [0, 1, 0], [0, 0, 1]]])
    >>> omega = solid_angles(np.array([[0.0, 0, 0], [1, 1, 1]]), tri)
    >>> omega.shape, float(omega[0, 0] / (4 * np.pi))
    ((2, 1), 0.125)
    """
    points = np.asarray(points, dtype=float)
    corners = np.asarray(triangles)[None] - points[:, None, None]
    return solid_angle(corners[:, :, 0], corners[:, :, 1], corners[:, :, 2])


def winding_numbers(points: np.ndarray, triangles: np.ndarray, labels: np.ndarray | None = None,
                    groups: int = 1) -> np.ndarray:
    """Winding number (k, groups) of each point (k, 3) about each group of triangles (n, 3, 3).

    1 inside a closed outward-wound surface, 0 outside, ½ on a face, the nesting
    depth where shells nest; fractional near the holes of an open one.
    ``labels`` (n,) puts each triangle in a group ``0..groups-1`` (a shell);
    None puts them all in one. Points and triangles are taken in blocks so the
    temporaries stay near :data:`WINDING_BLOCK` corner vectors whatever their
    numbers; triangles of any float dtype are converted a block at a time.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = v[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]
    >>> w = winding_numbers(np.array([[0.1, 0.1, 0.1], [1.0, 1.0, 1.0]]), tetra)
    >>> np.round(w, 12).ravel().tolist()
    [1.0, 0.0]
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    k, n = len(points), len(triangles)
    total = np.zeros((k, groups))
    point_step = min(max(k, 1), max(1, WINDING_BLOCK // 64))
    step = max(1, WINDING_BLOCK // point_step)
    for s in range(0, n, step):  # blocks of triangles
        block = np.asarray(triangles[s:s + step], dtype=float)
        member = None
        if labels is not None and groups > 1:
            member = (np.asarray(labels[s:s + step])[:, None] == np.arange(groups)).astype(float)
        for p in range(0, k, point_step):  # blocks of points
            omega = solid_angles(points[p:p + point_step], block)
            if member is None:
                total[p:p + point_step, 0] += omega.sum(axis=1)
            else:
                total[p:p + point_step] += omega @ member
    return total / (4 * np.pi)
