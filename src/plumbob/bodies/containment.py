"""Point-in-body tests: which points lie in a plane region or in a closed triangle mesh.

Bodies answer :meth:`plumbob.bodies.base.Body.contains` with these kernels.
Every test takes a ``tolerance`` (m): a positive one grows the body by that much
(points on the boundary, or within ``tolerance`` of it, count as inside), a
negative one shrinks it (a point must lie that far inside), so a composite can
keep its holes' rims while removing their insides.

The mesh test takes the winding number of the surface about each point (the sum of
its triangles' signed solid angles over 4π; libigl's, exact, with a hierarchy of
bounding boxes so far triangles are summed in bulk — :func:`plumbob.mesh.winding_numbers`
is the same formula in numpy, point by triangle) and, for the tolerance, the exact
distance to the surface (:class:`plumbob.bodies.distance.SurfaceDistance`).
"""

from __future__ import annotations

import numpy as np

from .region import Region

__all__ = ["mesh_contains", "region_contains", "triangle_distances"]

_PAIRS = 1 << 16  # (point, triangle) pairs per pass: temporaries of a few MB


def region_contains(region: Region, points: np.ndarray, tolerance: float) -> np.ndarray:
    """Which points lie in a plane region, within ``tolerance``.

    Parameters
    ----------
    region : Region
        The exact region; its curved edges are flattened to a quarter of
        ``|tolerance|`` (at least 2.5e-10 of its size) for the test.
    points : ndarray, shape (m, 2)
        The points, m (only the first two columns are read).
    tolerance : float
        m. Positive or zero: points within it of the region count; negative:
        points must lie at least ``-tolerance`` inside.

    Returns
    -------
    ndarray of bool, shape (m,)

    Examples
    --------
    >>> from plumbob.bodies.primitives import rectangle_region
    >>> square = rectangle_region(1, 1)
    >>> region_contains(square, np.array([[0.5, 0.5], [1.0, 0.2], [1.1, 0.5]]), 0.0).tolist()
    [True, True, False]
    >>> region_contains(square, np.array([[1.0, 0.2], [0.99, 0.5]]), -0.05).tolist()
    [False, False]
    """
    import shapely

    tolerance = float(tolerance)
    flat = max(abs(tolerance), 1e-9 * region.size) / 4
    geometry = region.to_shapely(flat)
    where = shapely.points(np.asarray(points, dtype=float)[:, :2])
    if tolerance >= 0:
        return shapely.dwithin(geometry, where, tolerance)
    return shapely.contains_properly(geometry, where) & ~shapely.dwithin(
        geometry.boundary, where, -tolerance)


def _chunk(points: int) -> int:
    """Triangles per pass over ``points`` points: about ``_PAIRS`` pairs."""
    return max(1, _PAIRS // max(points, 1))


def _segment_distances(v: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Distances (m, k) to segments ``d`` (k, 3) from points at offsets ``v`` (m, k, 3)
    from the segments' starts."""
    dd = np.einsum("ki,ki->k", d, d)
    tau = np.clip(np.einsum("mki,ki->mk", v, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    off = v - tau[..., None] * d
    return np.sqrt(np.einsum("mki,mki->mk", off, off))


def triangle_distances(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """The distance from each point to the nearest of ``triangles`` (filled), m.

    Parameters
    ----------
    triangles : ndarray, shape (n, 3, 3)
        m; degenerate (zero-area) triangles count as their edges.
    points : ndarray, shape (m, 3)
        m.

    Returns
    -------
    ndarray, shape (m,)

    Examples
    --------
    >>> tri = np.array([[[0.0, 0, 0], [1, 0, 0], [0, 1, 0]]])
    >>> triangle_distances(tri, np.array([[0.2, 0.2, 3.0], [2.0, 0, 0], [0.1, 0.1, 0]]))
    array([3., 1., 0.])
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    best = np.full(len(points), np.inf)
    step = _chunk(len(points))
    for start in range(0, len(triangles), step):
        t = triangles[start:start + step].astype(float)
        a, b, c = t[:, 0], t[:, 1], t[:, 2]
        e0, e1 = b - a, c - a
        normal = np.cross(e0, e1)
        nn = np.einsum("ki,ki->k", normal, normal)
        safe = np.where(nn > 0, nn, 1.0)
        w = points[:, None, :] - a[None]
        s = np.einsum("mki,ki->mk", np.cross(w, e1[None]), normal) / safe
        u = np.einsum("mki,ki->mk", np.cross(e0[None], w), normal) / safe
        over = (nn > 0) & (s >= 0) & (u >= 0) & (s + u <= 1)
        plane = np.abs(np.einsum("mki,ki->mk", w, normal)) / np.sqrt(safe)
        edges = np.minimum(np.minimum(_segment_distances(w, e0), _segment_distances(w, e1)),
                           _segment_distances(points[:, None, :] - b[None], c - b))
        best = np.minimum(best, np.where(over, plane, edges).min(axis=1))
    return best


def mesh_contains(triangles: np.ndarray, points: np.ndarray, tolerance: float) -> np.ndarray:
    """Which points lie in the solid a closed, outward-wound mesh bounds, within ``tolerance``.

    Inside means a winding number above ½; the tolerance then adds the points
    within it of the surface (positive) or removes those nearer than ``-tolerance``
    (negative).

    Parameters
    ----------
    triangles : ndarray, shape (n, 3, 3)
        m.
    points : ndarray, shape (m, 3)
        m.
    tolerance : float
        m.

    Returns
    -------
    ndarray of bool, shape (m,)

    Examples
    --------
    >>> from plumbob.bodies.primitives import box
    >>> tri = box(1, 1, 1).triangles
    >>> pts = np.array([[0.5, 0.5, 0.5], [1.0, 1.0, 1.0], [0.5, 0.5, 1.5]])
    >>> mesh_contains(tri, pts, 1e-6).tolist()     # a corner is on the body
    [True, True, False]
    >>> mesh_contains(tri, pts, -0.1).tolist()
    [True, False, False]
    """
    import igl

    from .distance import SurfaceDistance

    points = np.asarray(points, dtype=float).reshape(-1, 3)
    triangles = np.asarray(triangles, dtype=float).reshape(-1, 3, 3)
    if not len(points) or not len(triangles):
        return np.zeros(len(points), dtype=bool)
    # a local origin, so the solid angles keep their digits far from the file's origin
    origin = triangles.reshape(-1, 3).min(axis=0)
    corners = np.ascontiguousarray((triangles - origin).reshape(-1, 3))
    faces = np.arange(len(corners), dtype=np.int64).reshape(-1, 3)
    inside = igl.winding_number(corners, faces, np.ascontiguousarray(points - origin)) > 0.5
    tolerance = float(tolerance)
    if tolerance > 0 and not inside.all():
        near = ~inside
        inside[near] = SurfaceDistance(triangles).distances(points[near]) <= tolerance
    elif tolerance < 0 and inside.any():
        inside[inside] = SurfaceDistance(triangles).distances(points[inside]) > -tolerance
    return inside
