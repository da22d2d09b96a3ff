"""Quadrature rules: Gauss–Legendre and Gauss–Jacobi on [0, 1], and collapsed simplex rules.

Every rule here is exact for polynomials up to a stated degree, for any degree:
``n`` Gauss points integrate degree ``2n − 1``. The simplex rules
(:func:`triangle_rule`, :func:`tetrahedron_rule`) are the collapsed (Duffy /
Stroud conical product) rules: the square or cube is mapped onto the simplex
and the Jacobian ``(1 − ξ)^k`` is absorbed in a Gauss–Jacobi weight, so no
table of hand-tuned rules caps the degree.

Rules are cached and returned read-only, so callers share them freely.
:func:`arc_points_for_degree` sizes the angular rule of a circular arc, whose
integrands are trigonometric rather than polynomial.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

__all__ = [
    "gauss_legendre",
    "gauss_jacobi",
    "points_for_degree",
    "triangle_rule",
    "tetrahedron_rule",
    "simplex_rule",
    "arc_points_for_degree",
]


def _frozen(*arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    """Mark cached rules read-only: a caller writing into one would corrupt every later use."""
    for a in arrays:
        a.setflags(write=False)
    return arrays


# ------------------------------------------------------------------ 1D rules
@lru_cache(maxsize=64)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the ``n``-point Gauss–Legendre rule on [0, 1].

    Exact for polynomials of degree ``2n − 1``.

    Parameters
    ----------
    n : int
        Number of points, at least 1.

    Returns
    -------
    nodes : ndarray of shape (n,)
        Points in (0, 1), increasing.
    weights : ndarray of shape (n,)
        Positive weights summing to 1 (the interval's length). Both arrays are
        read-only and shared between calls.

    Raises
    ------
    ValueError
        If ``n < 1``.

    Examples
    --------
    >>> x, w = gauss_legendre(2)
    >>> round(float(w @ x**3), 15)   # ∫₀¹ x³ dx, exact with two points
    0.25
    >>> gauss_legendre(1)            # the midpoint rule
    (array([0.5]), array([1.]))
    >>> gauss_legendre(0)
    Traceback (most recent call last):
    ...
    ValueError: a Gauss rule needs at least one point
    """
    from scipy.special import roots_legendre

    if n < 1:
        raise ValueError("a Gauss rule needs at least one point")
    x, w = roots_legendre(n)
    return _frozen((x + 1) / 2, w / 2)


@lru_cache(maxsize=64)
def gauss_jacobi(n: int, alpha: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the ``n``-point Gauss–Jacobi rule on [0, 1] for the weight ``(1 − x)^alpha``.

    ``Σ w f(x) = ∫₀¹ (1 − x)^alpha f(x) dx`` for polynomials f of degree
    ``2n − 1``: the weight is how the simplex rules absorb their Jacobian.

    Parameters
    ----------
    n : int
        Number of points, at least 1.
    alpha : int
        Power of ``(1 − x)`` in the weight (0 gives :func:`gauss_legendre`).

    Returns
    -------
    nodes : ndarray of shape (n,)
        Points in (0, 1).
    weights : ndarray of shape (n,)
        Positive weights summing to ``1 / (alpha + 1)``. Read-only, shared.

    Raises
    ------
    ValueError
        If ``n < 1``, as for :func:`gauss_legendre`.

    Examples
    --------
    >>> x, w = gauss_jacobi(1, 1)
    >>> float(w.sum()), round(float(x[0]), 15)   # ∫(1−x) = 1/2, centre 1/3
    (0.5, 0.333333333333333)
    >>> x, w = gauss_jacobi(3, 2)
    >>> round(float(w @ x**5 * 2520), 12)        # ∫₀¹ (1−x)² x⁵ dx = 5! 2! / 8! = 1/168
    15.0
    """
    from scipy.special import roots_jacobi

    if n < 1:
        raise ValueError("a Gauss rule needs at least one point")
    x, w = roots_jacobi(n, alpha, 0.0)
    return _frozen((x + 1) / 2, w / 2 ** (alpha + 1))


def points_for_degree(degree: int) -> int:
    """Return the Gauss points per direction that make a rule exact up to ``degree``.

    The smallest ``n`` with ``2n − 1 ≥ degree``.

    Parameters
    ----------
    degree : int
        Polynomial degree to integrate exactly; negative degrees count as 0.

    Returns
    -------
    int
        Points per direction, at least 1.

    Examples
    --------
    >>> points_for_degree(3), points_for_degree(4)
    (2, 3)
    >>> points_for_degree(0), points_for_degree(-2)   # a constant still needs one point
    (1, 1)
    """
    return max(1, int(degree) // 2 + 1)


# ------------------------------------------------------------------ simplex rules
@lru_cache(maxsize=64)
def triangle_rule(degree: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the collapsed Gauss–Jacobi rule on the triangle (0,0), (1,0), (0,1).

    The map ``u = ξ, v = η (1 − ξ)`` has Jacobian ``1 − ξ``, taken by a
    Gauss–Jacobi (α = 1) rule in ξ; η is Gauss–Legendre. With
    ``n = degree // 2 + 1`` points per direction the rule has ``n²`` points,
    all inside the triangle, with positive weights.

    Parameters
    ----------
    degree : int
        Every polynomial of this degree in (u, v) is integrated exactly.

    Returns
    -------
    barycentric : ndarray of shape (q, 3)
        Weights of the three vertices, in order, at each point.
    weights : ndarray of shape (q,)
        Summing to the triangle's area 1/2. Both arrays are read-only, shared.

    Examples
    --------
    >>> bary, w = triangle_rule(2)
    >>> bary.shape, round(float(w.sum()), 15)
    ((4, 3), 0.5)
    >>> bary, w = triangle_rule(0)       # one point: the centroid
    >>> np.round(bary, 15).tolist(), float(w[0])
    ([[0.333333333333333, 0.333333333333333, 0.333333333333333]], 0.5)
    """
    n = points_for_degree(degree)
    xi, wx = gauss_jacobi(n, 1)
    eta, we = gauss_legendre(n)
    u = np.repeat(xi, n)
    v = np.tile(eta, n) * (1 - u)
    w = np.outer(wx, we).reshape(-1)
    bary = np.stack((1 - u - v, u, v), axis=1)
    return _frozen(bary, w)


@lru_cache(maxsize=64)
def tetrahedron_rule(degree: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the collapsed Gauss–Jacobi rule on the tetrahedron (0,0,0), e₁, e₂, e₃.

    The map ``u = ξ, v = η (1 − ξ), w = ζ (1 − ξ)(1 − η)`` has Jacobian
    ``(1 − ξ)² (1 − η)``: Gauss–Jacobi α = 2 in ξ, α = 1 in η, Legendre in ζ;
    ``n³`` points with ``n = degree // 2 + 1``.

    Parameters
    ----------
    degree : int
        Every polynomial of this degree in (u, v, w) is integrated exactly.

    Returns
    -------
    barycentric : ndarray of shape (q, 4)
        Weights of the four vertices, in order, at each point.
    weights : ndarray of shape (q,)
        Summing to the tetrahedron's volume 1/6. Read-only, shared.

    Examples
    --------
    >>> bary, w = tetrahedron_rule(1)
    >>> bary.shape, round(float(w.sum() * 6), 15)
    ((1, 4), 1.0)
    >>> bary, w = tetrahedron_rule(3)
    >>> round(float(w @ bary[:, 1] ** 3 * 120), 12)   # ∫ u³ = 3! / 6! = 1/120
    1.0
    """
    n = points_for_degree(degree)
    xi, wx = gauss_jacobi(n, 2)
    eta, we = gauss_jacobi(n, 1)
    zeta, wz = gauss_legendre(n)
    a, b, c = (g.reshape(-1) for g in np.meshgrid(xi, eta, zeta, indexing="ij"))
    u = a
    v = b * (1 - a)
    t = c * (1 - a) * (1 - b)
    w = np.einsum("i,j,k->ijk", wx, we, wz).reshape(-1)
    bary = np.stack((1 - u - v - t, u, v, t), axis=1)
    return _frozen(bary, w)


def simplex_rule(dim: int, degree: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the collapsed rule on the unit simplex of dimension ``dim``.

    Parameters
    ----------
    dim : int
        2 for :func:`triangle_rule`, 3 for :func:`tetrahedron_rule`.
    degree : int
        Polynomial degree integrated exactly.

    Returns
    -------
    barycentric : ndarray of shape (q, dim + 1)
    weights : ndarray of shape (q,)
        Summing to the simplex's measure ``1 / dim!``.

    Raises
    ------
    ValueError
        If ``dim`` is neither 2 nor 3.

    Examples
    --------
    >>> simplex_rule(3, 2)[0].shape
    (8, 4)
    >>> simplex_rule(1, 2)
    Traceback (most recent call last):
    ...
    ValueError: simplex rules exist for dim 2 and 3
    """
    if dim == 2:
        return triangle_rule(int(degree))
    if dim == 3:
        return tetrahedron_rule(int(degree))
    raise ValueError("simplex rules exist for dim 2 and 3")


# ------------------------------------------------------------------ arcs
def _gauss_remainder_log10(n: int, kappa: float) -> float:
    """log10 of the Gauss–Legendre remainder bound on [−1, 1] for ``e^{iκs}``:
    ``2^{2n+1} (n!)^4 / ((2n+1) ((2n)!)^3) · κ^{2n}``."""
    if kappa <= 0:
        return -math.inf
    lg = (2 * n + 1) * math.log(2) + 4 * math.lgamma(n + 1) - math.log(2 * n + 1) \
        - 3 * math.lgamma(2 * n + 1) + 2 * n * math.log(kappa)
    return lg / math.log(10)


@lru_cache(maxsize=256)
def _arc_points(degree: int, half_angle_millirad: int) -> int:
    """Cached on the angle rounded up to a milliradian, so nearby arcs share one answer."""
    kappa = (degree + 2) * half_angle_millirad / 1000
    n = points_for_degree(degree + 2)
    while _gauss_remainder_log10(n, kappa) > -20 and n < 200:
        n += 1
    return n


def arc_points_for_degree(degree: int, half_angle: float) -> int:
    """Return the Gauss–Legendre points in the angle that integrate over an arc to rounding.

    A polynomial of ``degree`` in x, y times the arc's Jacobian is a
    trigonometric polynomial of degree ``degree + 2`` in the angle θ; Gauss's
    remainder for ``e^{ikθ}``, ``|k| ≤ degree + 2``, on an interval of
    half-width ``half_angle`` is bounded below 1e-20 (relative to the sum of the
    Fourier coefficients' sizes), i.e. far below rounding.

    Parameters
    ----------
    degree : int
        Polynomial degree of the integrand in x, y.
    half_angle : float
        Half the arc's opening angle, radians.

    Returns
    -------
    int
        Points in the angle: never fewer than a polynomial of degree
        ``degree + 2`` needs, at most 200.

    Examples
    --------
    >>> arc_points_for_degree(2, np.pi / 8) >= points_for_degree(4)
    True
    >>> arc_points_for_degree(8, np.pi) > arc_points_for_degree(8, 0.1)
    True
    >>> arc_points_for_degree(2, 0.0) == points_for_degree(4)   # no arc: the polynomial count
    True
    """
    return _arc_points(int(degree), int(math.ceil(half_angle * 1000)))
