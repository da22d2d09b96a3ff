"""Exact volume moments of closed triangle meshes by the divergence theorem, uniform or graded.

Each triangle ``(a, b, c)`` and a local origin ``o`` span a signed tetrahedron;
the signed tetrahedra of a closed, outward-oriented surface sum to the solid
(several shells add; a void is an inward shell and subtracts). Products are
formed in coordinates relative to ``o`` — chosen near the mesh — so results
stay exact far from the world origin, and triangles are processed in chunks of
:data:`CHUNK` so memory stays bounded and the temporaries stay in cache.

Two kernels share that one chunk loop (:class:`_Tetrahedra`):

* :func:`triangle_soup_moments` — uniform density, closed-form tetrahedron
  moments: ``m0`` volume (m³), ``m1`` (3,) ``∫ r dV`` (m⁴), ``m2`` (3, 3)
  ``∫ r rᵀ dV`` (m⁵) about ``o``;
* :func:`mesh_field_moments` — a polynomial density field, by the collapsed
  tetrahedron rule of :mod:`plumbob.integrals.rules` (exact), returning a
  :class:`~plumbob.integrals.adaptive.FieldIntegral`.

The surface's vector area ``Σ (b−a)×(c−a)/2`` vanishes on a closed surface;
both kernels return it with the total area, so callers can tell an open mesh,
whose "volume" would depend on ``o``.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

if TYPE_CHECKING:
    from .adaptive import FieldIntegral

__all__ = ["VolumeMoments", "triangle_soup_moments", "mesh_field_moments", "CHUNK"]

CHUNK = 1 << 12  # triangles per pass: the temporaries (~1 MB) stay in cache


class VolumeMoments(NamedTuple):
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


class _Tetrahedra:
    """The one chunk loop of the mesh kernels: the signed tetrahedra (o, a, b, c), chunk by chunk.

    Iterating yields, per chunk of at most ``chunk`` triangles:

    * ``triangles`` (k, 3, 3), the chunk as given (world coordinates, its dtype);
    * ``corners`` (4, 3, k) float64, component-major: ``corners[i, j]`` is
      coordinate j of corner i relative to the origin, contiguous over the
      chunk; ``corners[3]`` is scratch the kernel may overwrite;
    * ``normal`` (3, k): ``n = (b − a) × (c − a)``, twice the vector area;
    * ``det`` (k,): ``a · (b × c) = a · n``, six times the signed volume.

    The buffers are reused from chunk to chunk: a kernel must finish with a
    chunk before asking for the next. On the way the loop sums what every
    kernel reports, the surface's ``vector_area`` (3,), its ``area`` and the
    enclosed ``volume``.
    """

    def __init__(self, triangles: np.ndarray, origin: np.ndarray, chunk: int = CHUNK) -> None:
        self.triangles = triangles
        self.origin = origin
        self.chunk = max(1, int(chunk))
        self.vector_area = np.zeros(3)
        self.area = 0.0
        self.volume = 0.0

    def __iter__(self) -> Iterator[tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
        triangles, origin, chunk = self.triangles, self.origin, self.chunk
        width = min(chunk, len(triangles))
        corner_buffer = np.empty((4, 3, width))
        edge_buffer = np.empty((2, 3, width))
        normal_buffer = np.empty((3, width))
        det_buffer = np.empty(width)
        for start in range(0, len(triangles), chunk):
            tri = triangles[start:start + chunk]
            k = len(tri)
            corners = corner_buffer[:, :, :k]
            np.subtract(tri.transpose(1, 2, 0), origin[None, :, None], out=corners[:3])
            a, b, c = corners[0], corners[1], corners[2]
            u, v = edge_buffer[0, :, :k], edge_buffer[1, :, :k]
            np.subtract(b, a, out=u)
            np.subtract(c, a, out=v)
            n = normal_buffer[:, :k]
            np.multiply(u[1], v[2], out=n[0])
            n[0] -= u[2] * v[1]
            np.multiply(u[2], v[0], out=n[1])
            n[1] -= u[0] * v[2]
            np.multiply(u[0], v[1], out=n[2])
            n[2] -= u[1] * v[0]
            det = det_buffer[:k]
            np.multiply(a[0], n[0], out=det)
            det += a[1] * n[1]
            det += a[2] * n[2]
            self.volume += det.sum() / 6
            self.vector_area += n.sum(axis=1) / 2
            np.multiply(n, n, out=u)
            self.area += np.sqrt(u.sum(axis=0)).sum() / 2
            yield tri, corners, n, det


def _as_triangles(triangles: np.ndarray) -> np.ndarray:
    triangles = np.asarray(triangles)
    if triangles.ndim != 3 or triangles.shape[1:] != (3, 3):
        raise ValueError("triangles must have shape (n, 3, 3)")
    return triangles


def triangle_soup_moments(
    triangles: np.ndarray, origin: np.ndarray | None = None, chunk: int = CHUNK
) -> VolumeMoments:
    """Return the volume moments of the solid bounded by a closed triangle mesh.

    With a, b, c the corners relative to the origin and s = a + b + c, the
    tetrahedron (0, a, b, c) of signed volume V has ``∫ r dV = V s / 4`` and
    ``∫ r rᵀ dV = V/20 (a aᵀ + b bᵀ + c cᵀ + s sᵀ)``; the last is one small
    matrix product over the stacked corners.

    Parameters
    ----------
    triangles : array_like of shape (n, 3, 3)
        Corners in m, any float dtype, wound counter-clockwise seen from
        outside (outward normals).
    origin : array_like of shape (3,), optional
        The local origin; defaults to the mean of the first triangles' vertices.
    chunk : int, default CHUNK
        Triangles per pass (a memory / speed trade-off; the sums do not depend on it
        beyond rounding).

    Returns
    -------
    VolumeMoments
        Volume, first and second moments about ``origin``, the surface's vector
        area and area, and the bounding box.

    Raises
    ------
    ValueError
        If ``triangles`` does not have shape (n, 3, 3).

    Examples
    --------
    >>> tet = np.array([[[0, 0, 0], [0, 1, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
    ...     [[0, 0, 0], [0, 0, 1], [0, 1, 0]], [[1, 0, 0], [0, 1, 0], [0, 0, 1]]], float)
    >>> m = triangle_soup_moments(tet)
    >>> round(m.m0 * 6, 12), np.round(m.origin + m.m1 / m.m0, 12).tolist()
    (1.0, [0.25, 0.25, 0.25])
    >>> triangle_soup_moments(tet[:3]).vector_area.tolist()   # open: a face is missing
    [-0.5, -0.5, -0.5]
    >>> triangle_soup_moments(np.zeros((0, 3, 3))).m0   # an empty mesh has no volume
    0.0
    """
    triangles = _as_triangles(triangles)
    n = len(triangles)
    if origin is None:
        origin = (
            triangles[: min(n, 1024)].reshape(-1, 3).mean(axis=0, dtype=float) if n else np.zeros(3)
        )
    origin = np.asarray(origin, dtype=float)
    total = np.zeros(12)  # m1 (3), m2 (9)
    lower, upper = np.full(3, np.inf), np.full(3, -np.inf)
    tetrahedra = _Tetrahedra(triangles, origin, chunk)
    for _, corners, _, det in tetrahedra:
        a, b, c, s = corners
        np.add(a, b, out=s)
        s += c
        total[:3] += s @ det / 24
        stacked = corners.transpose(1, 0, 2).reshape(3, -1)
        weights = np.tile(det, 4)
        total[3:] += ((stacked * weights) @ stacked.T).reshape(-1) / 120
        np.minimum(lower, corners[:3].min(axis=(0, 2)), out=lower)
        np.maximum(upper, corners[:3].max(axis=(0, 2)), out=upper)
    m2 = total[3:].reshape(3, 3)
    return VolumeMoments(
        origin, float(tetrahedra.volume), total[:3].copy(), (m2 + m2.T) / 2,
        tetrahedra.vector_area, float(tetrahedra.area), n, lower + origin, upper + origin,
    )


def mesh_field_moments(
    triangles: np.ndarray,
    density: Callable[[np.ndarray], np.ndarray],
    origin: np.ndarray,
    degree: int,
    *,
    chunk: int = CHUNK,
) -> FieldIntegral:
    """Return the exact moments of a polynomial density field over a closed triangle mesh.

    The fast path of :func:`~plumbob.integrals.adaptive.integrate_field` for the
    signed tetrahedra ``(origin, a, b, c)`` of a triangle soup: the points of
    the collapsed rule of degree ``degree + 2`` are formed chunk by chunk,
    component-major, by small matrix products. In the same pass it sums the
    surface's vector area and area (the closure check) and samples the density
    at every corner.

    Parameters
    ----------
    triangles : array_like of shape (n, 3, 3)
        Corners in m, wound counter-clockwise seen from outside.
    density : callable
        Maps world points (m, 3), m, to densities (m,), kg/m³.
    origin : array_like of shape (3,)
        Local origin near the mesh, m; the moments are about it.
    degree : int
        The density's polynomial degree.
    chunk : int, default CHUNK
        Triangles per pass.

    Returns
    -------
    FieldIntegral
        ``exact`` moments about ``origin``; ``vector_area`` and ``surface_area``
        for the closure check; ``bad_points``/``bad_values`` and
        ``corner_points``/``corner_values`` keep the worst negative or
        non-finite samples at quadrature points and at vertices.

    Raises
    ------
    ValueError
        If ``triangles`` does not have shape (n, 3, 3), or ``density`` does not
        return one value per point.

    Examples
    --------
    ρ = 1 + x over the unit tetrahedron: mass 1/6 + 1/24 = 5/24, x̄ = 7/25.

    >>> tet = np.array([[[0, 0, 0], [0, 1, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
    ...     [[0, 0, 0], [0, 0, 1], [0, 1, 0]], [[1, 0, 0], [0, 1, 0], [0, 0, 1]]], float)
    >>> r = mesh_field_moments(tet, lambda p: 1 + p[:, 0], np.zeros(3), 1)
    >>> round(r.mass * 24, 12), round(float(r.first[0] / r.mass), 12), r.exact
    (5.0, 0.28, True)
    >>> r = mesh_field_moments(tet, lambda p: p[:, 0] - 0.5, np.zeros(3), 1)
    >>> float(r.corner_values.min())   # negative at the vertices off x = 1
    -0.5
    >>> mesh_field_moments(np.zeros((0, 3, 3)), lambda p: p[:, 0], np.zeros(3), 1).mass
    0.0
    """
    triangles = _as_triangles(triangles)
    origin = np.asarray(origin, dtype=float)
    # density fields only: `plumbob mass part.stl` need not load the quadrature rooms
    from .adaptive import FieldIntegral, InvalidSamples, sample_density
    from .rules import tetrahedron_rule

    bary, w = tetrahedron_rule(int(degree) + 2)
    lam = np.ascontiguousarray(bary[:, 1:])  # (q, 3): weights of a, b, c (the apex is 0)
    q = len(w)
    bad, corners_bad = InvalidSamples(3), InvalidSamples(3)
    sums = np.zeros(10)  # mass, first (3), second (6: xx yy zz xy xz yz)
    evaluations = 0
    buffer = np.empty((2, 3, q, min(chunk, len(triangles))))
    tetrahedra = _Tetrahedra(triangles, origin, chunk)
    for t, corners, _, det in tetrahedra:
        k = len(t)
        # Quadrature points, component-major: (3, q, k) = λ (q, 3) @ corners (3, k) per component.
        local, world = buffer[0, :, :, :k], buffer[1, :, :, :k]
        for j in range(3):
            np.matmul(lam, corners[:3, j, :], out=local[j])
            np.add(local[j], origin[j], out=world[j])
        flat = local.reshape(3, q * k)
        values = sample_density(density, world.reshape(3, q * k).T, bad).reshape(q, k)
        corner_values = sample_density(density, t.reshape(-1, 3), corners_bad)
        evaluations += values.size + corner_values.size
        values *= det
        values *= w[:, None]
        wr = values.reshape(-1)
        weighted = flat * wr
        sums[0] += wr.sum()
        sums[1:4] += weighted.sum(axis=1)
        m2 = weighted @ flat.T
        sums[4:10] += m2[[0, 1, 2, 0, 0, 1], [0, 1, 2, 1, 2, 2]]
    s = sums
    second = np.array([[s[4], s[7], s[8]], [s[7], s[5], s[9]], [s[8], s[9], s[6]]])
    total = np.concatenate(([tetrahedra.volume, s[0]], s[1:4], second.reshape(-1)))
    return FieldIntegral.from_sums(
        origin, total, bad, exact=True, error=0.0, converged=True, evaluations=evaluations,
        cells=len(triangles), vector_area=tetrahedra.vector_area,
        surface_area=float(tetrahedra.area), corner_points=corners_bad.points,
        corner_values=corners_bad.values)
