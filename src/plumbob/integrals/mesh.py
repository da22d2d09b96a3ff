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

CHUNK = 1 << 17  # triangles per pass: ~30 MB of float64 temporaries


@dataclass(frozen=True, eq=False)
class VolumeMoments:
    """Signed volume moments about ``origin`` plus closure diagnostics.

    origin: (3,) m. m0: m³. m1: (3,) m⁴. m2: (3, 3) m⁵.
    vector_area: (3,) m², zero on a closed surface.
    area: total surface area, m².
    triangles: how many triangles were summed.
    """

    origin: np.ndarray
    m0: float
    m1: np.ndarray
    m2: np.ndarray
    vector_area: np.ndarray
    area: float
    triangles: int

    def __add__(self, other: VolumeMoments) -> VolumeMoments:
        shift = other.origin - self.origin
        m1 = other.m1 + other.m0 * shift
        m2 = (
            other.m2
            + np.outer(other.m1, shift)
            + np.outer(shift, other.m1)
            + other.m0 * np.outer(shift, shift)
        )
        return VolumeMoments(
            self.origin,
            self.m0 + other.m0,
            self.m1 + m1,
            self.m2 + m2,
            self.vector_area + other.vector_area,
            self.area + other.area,
            self.triangles + other.triangles,
        )


def _chunk_moments(tri: np.ndarray, origin: np.ndarray) -> np.ndarray:
    """Sums for one chunk (k, 3, 3) → flat array of 17 numbers."""
    a = tri[:, 0] - origin
    b = tri[:, 1] - origin
    c = tri[:, 2] - origin
    normal = np.cross(b - a, c - a)
    det = np.einsum("ij,ij->i", a, np.cross(b, c))  # 6 × signed tet volume
    s = a + b + c
    out = np.empty(17)
    out[0] = det.sum() / 6
    out[1:4] = det @ s / 24
    # ∫ r rᵀ over the tet (0, a, b, c) = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ), V = det/6
    w = det / 120
    q = np.einsum("k,ki,kj->ij", w, a, a)
    q += np.einsum("k,ki,kj->ij", w, b, b)
    q += np.einsum("k,ki,kj->ij", w, c, c)
    q += np.einsum("k,ki,kj->ij", w, s, s)
    out[4:13] = q.reshape(-1)
    out[13:16] = normal.sum(axis=0) / 2
    out[16] = np.sqrt(np.einsum("ij,ij->i", normal, normal)).sum() / 2
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
    for start in range(0, n, chunk):
        total += _chunk_moments(triangles[start : start + chunk].astype(float, copy=False), origin)
    m2 = total[4:13].reshape(3, 3)
    return VolumeMoments(
        origin,
        float(total[0]),
        total[1:4].copy(),
        (m2 + m2.T) / 2,
        total[13:16].copy(),
        float(total[16]),
        n,
    )
