"""Exact volume moments of closed triangle meshes by the divergence theorem.

Each triangle ``(a, b, c)`` and a local origin ``o`` span a signed tetrahedron;
the signed tetrahedra of a closed, outward-oriented surface sum to the solid
(several shells add; a void is an inward shell and subtracts). Products are
formed in coordinates relative to ``o`` — chosen near the mesh — so results
stay exact far from the world origin, and triangles are processed in chunks so
memory stays bounded.

Moments about ``o``: ``m0`` volume (m³), ``m1`` (3,) ``∫ r dV`` (m⁴),
``m2`` (3, 3) ``∫ r rᵀ dV`` (m⁵).

The surface's vector area ``Σ (b−a)×(c−a)/2`` and its first moment vanish on
a closed surface; they are returned so callers can tell an open mesh, whose
"volume" would depend on ``o``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["VolumeMoments", "triangle_soup_moments", "CHUNK"]

CHUNK = 1 << 12  # triangles per pass: the temporaries (~1 MB) stay in cache


@dataclass(frozen=True, eq=False)
class VolumeMoments:
    """Signed volume moments about ``origin`` plus closure diagnostics.

    origin: (3,) m. m0: m³. m1: (3,) m⁴. m2: (3, 3) m⁵.
    vector_area: (3,) m², zero on a closed surface.
    area: total surface area, m².
    lower, upper: (3,) m, the bounding box of the vertices.
    triangles: how many triangles were summed.
    """

    origin: np.ndarray
    m0: float
    m1: np.ndarray
    m2: np.ndarray
    vector_area: np.ndarray
    area: float
    triangles: int
    lower: np.ndarray
    upper: np.ndarray


def _chunk_moments(tri: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """Sums for one chunk (k, 3, 3) → flat array of 23 numbers (the last six are
    the chunk's bounding box relative to the origin).

    With a, b, c the corners relative to the origin, u = b − a, v = c − a and
    n = u × v (twice the triangle's vector area), the tetrahedron (0, a, b, c)
    has 6V = a · (b × c) = a · n. Its integrals: ``∫ r dV = V (a+b+c)/4`` and
    ``∫ r rᵀ dV = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ)`` with s = a + b + c; the
    last is one small matrix product over the stacked corners.
    """
    # component-major copy: corners[i, j] is coordinate j of corner i, contiguous over triangles
    corners = np.empty((4, 3, len(tri)))
    np.subtract(tri.transpose(1, 2, 0), origin[None, :, None], out=corners[:3])
    a, b, c = corners[0], corners[1], corners[2]
    u = b - a
    v = c - a
    n = np.empty_like(u)
    np.multiply(u[1], v[2], out=n[0])
    n[0] -= u[2] * v[1]
    np.multiply(u[2], v[0], out=n[1])
    n[1] -= u[0] * v[2]
    np.multiply(u[0], v[1], out=n[2])
    n[2] -= u[1] * v[0]
    det = a[0] * n[0]
    det += a[1] * n[1]
    det += a[2] * n[2]
    np.add(a, b, out=corners[3])
    corners[3] += c
    out = np.empty(23)
    out[0] = det.sum() / 6
    out[1:4] = corners[3] @ det / 24
    stacked = corners.transpose(1, 0, 2).reshape(3, -1)
    weights = np.tile(det, 4)
    out[4:13] = ((stacked * weights) @ stacked.T).reshape(-1) / 120
    out[13:16] = n.sum(axis=1) / 2
    np.multiply(n, n, out=u)
    out[16] = np.sqrt(u.sum(axis=0)).sum() / 2
    lows = corners[:3].min(axis=(0, 2))
    highs = corners[:3].max(axis=(0, 2))
    out[17:20] = lows
    out[20:23] = highs
    return out


def triangle_soup_moments(
    triangles: np.ndarray, origin: np.ndarray | None = None, chunk: int = CHUNK
) -> VolumeMoments:
    """Volume moments of the solid bounded by ``triangles`` (n, 3, 3), any float dtype.

    Triangles must be wound counter-clockwise seen from outside (outward normals).
    ``origin`` defaults to the mean of the first triangles' vertices.

    >>> tet = np.array([[[0, 0, 0], [0, 1, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
    ...     [[0, 0, 0], [0, 0, 1], [0, 1, 0]], [[1, 0, 0], [0, 1, 0], [0, 0, 1]]], float)
    >>> m = triangle_soup_moments(tet)
    >>> round(m.m0 * 6, 12), np.round(m.origin + m.m1 / m.m0, 12).tolist()
    (1.0, [0.25, 0.25, 0.25])
    >>> triangle_soup_moments(np.zeros((0, 3, 3))).m0   # an empty mesh has no volume
    0.0
    """
    triangles = np.asarray(triangles)
    if triangles.ndim != 3 or triangles.shape[1:] != (3, 3):
        raise ValueError("triangles must have shape (n, 3, 3)")
    n = len(triangles)
    if origin is None:
        origin = (
            triangles[: min(n, 1024)].reshape(-1, 3).mean(axis=0, dtype=float) if n else np.zeros(3)
        )
    origin = np.asarray(origin, dtype=float)
    total = np.zeros(17)
    lower, upper = np.full(3, np.inf), np.full(3, -np.inf)
    for start in range(0, n, chunk):
        sums = _chunk_moments(triangles[start : start + chunk], origin)
        total += sums[:17]
        np.minimum(lower, sums[17:20], out=lower)
        np.maximum(upper, sums[20:23], out=upper)
    m2 = total[4:13].reshape(3, 3)
    return VolumeMoments(
        origin, float(total[0]), total[1:4].copy(), (m2 + m2.T) / 2, total[13:16].copy(),
        float(total[16]), n, lower + origin, upper + origin,
    )
