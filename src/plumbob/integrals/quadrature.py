"""Quadrature for density fields: simplex rules from Gauss–Jacobi points, curved cells, adaptivity.

A body of variable density ρ is cut into *cells*: signed triangles or
tetrahedra, caps between a chord and a circular arc or a cubic Bézier, and
products of a plane cell with an interval (prisms, and turns about an axis).
Each cell family gives, for a polynomial degree ``p``, points and signed
weights that integrate every polynomial of degree ``p`` in the coordinates
exactly (to rounding). The driver :func:`integrate_field` sums

* ``∫ ρ dV`` (mass), ``∫ ρ r dV`` and ``∫ ρ r rᵀ dV`` about a local origin,
* ``∫ 1 dV`` (the measure: area or volume),

in one pass when ρ is a polynomial of known degree ``d`` (rule degree ``d + 2``),
and adaptively otherwise.

Simplex rules (:func:`triangle_rule`, :func:`tetrahedron_rule`) are the collapsed
(Duffy / Stroud conical product) rules: the square or cube is mapped onto the
simplex, the Jacobian ``(1 − ξ)^k`` is absorbed in a Gauss–Jacobi weight, so
``n`` points per direction integrate degree ``2n − 1`` exactly, for any ``n``.

Adaptive integration (ρ not a polynomial): each cell is integrated with two
rules of ``n`` and ``n + 1`` points per direction; the difference is the cell's
error estimate for the lower rule, and the higher one is kept. While raising
``n`` shrinks the total estimate at least fourfold, ``n`` is raised (smooth
fields converge geometrically); after that, the cells whose estimate exceeds
their share of the tolerance (proportional to their size) are split in two
along every direction, until the total estimate is below the tolerance or the
evaluation budget is spent. The reported error is the sum of the cells' estimates.

A jump that only clips a cell's corner can fall between every Gauss point of
both rules, which then agree. So the field is also sampled at every cell's
corners: a corner value outside the range of the cell's quadrature samples by
more than that range marks the cell, and it is charged ``3 |size| × excess``
(a bound on what the corner can hide). Smooth fields are not marked; steps are
charged honestly, which makes their estimates pessimistic (in the tests, 10²–10³
times the true error).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

__all__ = [
    "gauss_legendre",
    "gauss_jacobi",
    "triangle_rule",
    "tetrahedron_rule",
    "simplex_rule",
    "points_for_degree",
    "arc_points_for_degree",
    "Cells",
    "SimplexCells",
    "ArcCells",
    "BezierCells",
    "ProductCells",
    "FieldIntegral",
    "integrate_field",
    "mesh_field_moments",
    "CHUNK_POINTS",
    "MAX_EVALUATIONS",
]

CHUNK_POINTS = 1 << 20  # quadrature points per pass: ~100 MB of float64 temporaries
MAX_EVALUATIONS = 20_000_000  # default budget of density evaluations for adaptive integration
_KEEP_BAD = 64  # invalid density samples kept for the caller to report


# ------------------------------------------------------------------ 1D rules
def _frozen(*arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    for a in arrays:
        a.setflags(write=False)
    return arrays


@lru_cache(maxsize=64)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n``-point Gauss–Legendre rule on [0, 1]: nodes (n,), weights (n,) summing to 1.

    Exact for polynomials of degree ``2n − 1``.

    >>> x, w = gauss_legendre(2)
    >>> round(float(w @ x**3), 15)
    0.25
    """
    from scipy.special import roots_legendre

    if n < 1:
        raise ValueError("a Gauss rule needs at least one point")
    x, w = roots_legendre(n)
    return _frozen((x + 1) / 2, w / 2)


@lru_cache(maxsize=64)
def gauss_jacobi(n: int, alpha: int) -> tuple[np.ndarray, np.ndarray]:
    """``n``-point Gauss–Jacobi rule on [0, 1] for the weight ``(1 − x)^alpha``.

    ``Σ w f(x) = ∫₀¹ (1 − x)^alpha f(x) dx`` for polynomials f of degree ``2n − 1``.

    >>> x, w = gauss_jacobi(1, 1)
    >>> float(w.sum()), round(float(x[0]), 15)   # ∫(1−x) = 1/2, centre 1/3
    (0.5, 0.333333333333333)
    """
    from scipy.special import roots_jacobi

    if n < 1:
        raise ValueError("a Gauss rule needs at least one point")
    x, w = roots_jacobi(n, alpha, 0.0)
    return _frozen((x + 1) / 2, w / 2 ** (alpha + 1))


def points_for_degree(degree: int) -> int:
    """Gauss points per direction for exactness up to polynomial ``degree``: ``2n − 1 ≥ degree``."""
    return max(1, int(degree) // 2 + 1)


# ------------------------------------------------------------------ simplex rules
@lru_cache(maxsize=64)
def triangle_rule(degree: int) -> tuple[np.ndarray, np.ndarray]:
    """Collapsed Gauss–Jacobi rule on the triangle (0,0), (1,0), (0,1), exact to ``degree``.

    Returns barycentric coordinates (q, 3) — weights of the vertices in order —
    and weights (q,) summing to the triangle's area 1/2; ``q = n²`` with
    ``n = degree // 2 + 1``. The map ``u = ξ, v = η (1 − ξ)`` has Jacobian
    ``1 − ξ``, taken by a Gauss–Jacobi (α = 1) rule in ξ; η is Gauss–Legendre.

    >>> bary, w = triangle_rule(2)
    >>> bary.shape, round(float(w.sum()), 15)
    ((4, 3), 0.5)
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
    """Collapsed Gauss–Jacobi rule on the tetrahedron (0,0,0), e₁, e₂, e₃, exact to ``degree``.

    Returns barycentric coordinates (q, 4) and weights (q,) summing to 1/6;
    ``q = n³``. The map ``u = ξ, v = η (1 − ξ), w = ζ (1 − ξ)(1 − η)`` has
    Jacobian ``(1 − ξ)² (1 − η)``: Gauss–Jacobi α = 2 in ξ, α = 1 in η, Legendre in ζ.

    >>> bary, w = tetrahedron_rule(1)
    >>> bary.shape, round(float(w.sum() * 6), 15)
    ((1, 4), 1.0)
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
    """:func:`triangle_rule` (``dim`` 2) or :func:`tetrahedron_rule` (``dim`` 3)."""
    if dim == 2:
        return triangle_rule(int(degree))
    if dim == 3:
        return tetrahedron_rule(int(degree))
    raise ValueError("simplex rules exist for dim 2 and 3")


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
    kappa = (degree + 2) * half_angle_millirad / 1000
    n = points_for_degree(degree + 2)
    while _gauss_remainder_log10(n, kappa) > -20 and n < 200:
        n += 1
    return n


def arc_points_for_degree(degree: int, half_angle: float) -> int:
    """Gauss–Legendre points in the angle for an arc of ``half_angle`` (radians).

    A polynomial of ``degree`` in x, y times the arc's Jacobian is a
    trigonometric polynomial of degree ``degree + 2`` in the angle θ; Gauss's
    remainder for ``e^{ikθ}``, ``|k| ≤ degree + 2``, on an interval of half-width
    ``half_angle`` is bounded below 1e-20 (relative to the sum of the Fourier
    coefficients' sizes), i.e. far below rounding.

    >>> arc_points_for_degree(2, np.pi / 8) >= points_for_degree(4)
    True
    """
    return _arc_points(int(degree), int(math.ceil(half_angle * 1000)))


# ------------------------------------------------------------------ cells
class Cells(ABC):
    """A batch of integration cells of one kind, in coordinates relative to a local origin.

    ``rule(degree)`` gives points (k, q, dim) m and signed weights (k, q) (m² or
    m³, Jacobians included) integrating polynomials of ``degree`` exactly over
    every cell; ``split()`` cuts every cell into ``children`` pieces (child j
    of cell i at ``i * children + j``) that tile it with the same sign.
    """

    dim: int
    children: int

    @abstractmethod
    def __len__(self) -> int: ...

    @abstractmethod
    def rule(self, degree: int) -> tuple[np.ndarray, np.ndarray]: ...

    @abstractmethod
    def split(self) -> Cells: ...

    @abstractmethod
    def take(self, index: slice | np.ndarray) -> Cells: ...

    @abstractmethod
    def corners(self) -> np.ndarray:
        """The cells' corner points (k, c, dim), relative to the local origin."""

    def points_per_cell(self, degree: int) -> int:
        """How many points ``rule(degree)`` uses per cell."""
        return self.take(slice(0, 1)).rule(degree)[1].shape[1] if len(self) else 0


def _det(edges: np.ndarray) -> np.ndarray:
    """Determinants of (k, d, d) edge matrices (rows are edge vectors), d = 2 or 3."""
    if edges.shape[-1] == 2:
        return edges[:, 0, 0] * edges[:, 1, 1] - edges[:, 0, 1] * edges[:, 1, 0]
    a, b, c = edges[:, 0], edges[:, 1], edges[:, 2]
    return np.einsum("ij,ij->i", a, np.cross(b, c))


@dataclass(frozen=True, eq=False)
class SimplexCells(Cells):
    """Signed triangles (dim 2) or tetrahedra (dim 3).

    vertices: (k, dim + 1, dim), or (k, dim, dim) for simplices whose first
    vertex is the local origin (the signed tetrahedra of a closed mesh). The
    weight of a cell is signed by its orientation: counter-clockwise triangles
    and positively oriented tetrahedra count positive.
    """

    vertices: np.ndarray

    @property
    def dim(self) -> int:  # type: ignore[override]
        return self.vertices.shape[2]

    @property
    def children(self) -> int:  # type: ignore[override]
        return 4 if self.dim == 2 else 8

    @property
    def apex_at_origin(self) -> bool:
        return self.vertices.shape[1] == self.dim

    def __len__(self) -> int:
        return len(self.vertices)

    def take(self, index: slice | np.ndarray) -> SimplexCells:
        return SimplexCells(self.vertices[index])

    def corners(self) -> np.ndarray:
        return self._full()

    def _full(self) -> np.ndarray:
        v = np.asarray(self.vertices, dtype=float)
        if self.apex_at_origin:
            v = np.concatenate((np.zeros((len(v), 1, self.dim)), v), axis=1)
        return v

    def rule(self, degree: int) -> tuple[np.ndarray, np.ndarray]:
        bary, w = simplex_rule(self.dim, degree)
        v = np.asarray(self.vertices, dtype=float)
        if self.apex_at_origin:
            points = np.matmul(bary[:, 1:], v)  # (k, q, dim)
            jac = _det(v)
        else:
            points = np.matmul(bary, v)
            jac = _det(v[:, 1:] - v[:, :1])
        return points, jac[:, None] * w[None, :]

    def split(self) -> SimplexCells:
        v = self._full()
        if self.dim == 2:
            m01, m12 = (v[:, 0] + v[:, 1]) / 2, (v[:, 1] + v[:, 2]) / 2
            m02 = (v[:, 0] + v[:, 2]) / 2
            kids = [(v[:, 0], m01, m02), (m01, v[:, 1], m12), (m02, m12, v[:, 2]), (m01, m12, m02)]
        else:
            p = [v[:, i] for i in range(4)]
            m = {(i, j): (p[i] + p[j]) / 2 for i in range(4) for j in range(i + 1, 4)}
            kids = [
                (p[0], m[0, 1], m[0, 2], m[0, 3]), (m[0, 1], p[1], m[1, 2], m[1, 3]),
                (m[0, 2], m[1, 2], p[2], m[2, 3]), (m[0, 3], m[1, 3], m[2, 3], p[3]),
                (m[0, 2], m[1, 3], m[0, 1], m[1, 2]), (m[0, 2], m[1, 3], m[1, 2], m[2, 3]),
                (m[0, 2], m[1, 3], m[2, 3], m[0, 3]), (m[0, 2], m[1, 3], m[0, 3], m[0, 1]),
            ]
        out = np.stack([np.stack(k, axis=1) for k in kids], axis=1)  # (k, c, d+1, d)
        out = out.reshape(-1, self.dim + 1, self.dim)
        # Every child keeps its parent's orientation, so the signed pieces tile it.
        parent = np.repeat(np.sign(_det(v[:, 1:] - v[:, :1])), self.children)
        flip = np.sign(_det(out[:, 1:] - out[:, :1])) != parent
        out[flip, -2:] = out[flip, -2:][:, ::-1]
        return SimplexCells(out)


@dataclass(frozen=True, eq=False)
class _BoxCells(Cells):
    """Cells that are images of parameter boxes ``[a0, a1] × [b0, b1]`` ⊂ [0, 1]²."""

    box: np.ndarray  # (k, 2, 2): rows (u0, u1), (t0, t1)

    dim = 2
    children = 4

    def __len__(self) -> int:
        return len(self.box)

    def _data(self) -> dict[str, np.ndarray]:
        raise NotImplementedError

    def _with(self, index, box: np.ndarray) -> _BoxCells:
        fields = {k: v[index] for k, v in self._data().items()}
        return type(self)(box=box, **fields)

    def take(self, index: slice | np.ndarray) -> _BoxCells:
        return self._with(index, self.box[index])

    def split(self) -> _BoxCells:
        b = self.box
        u0, u1, t0, t1 = b[:, 0, 0], b[:, 0, 1], b[:, 1, 0], b[:, 1, 1]
        um, tm = (u0 + u1) / 2, (t0 + t1) / 2
        kids = [((u0, um), (t0, tm)), ((u0, um), (tm, t1)),
                ((um, u1), (t0, tm)), ((um, u1), (tm, t1))]
        box = np.stack([np.stack([np.stack(r, axis=1) for r in kid], axis=1) for kid in kids],
                       axis=1)
        index = np.repeat(np.arange(len(b)), 4)
        return self._with(index, box.reshape(-1, 2, 2))

    def _map(self, u: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Points (k, q, 2) and signed Jacobians (k, q) at parameters u, t (k, q)."""
        raise NotImplementedError

    def corners(self) -> np.ndarray:
        b = self.box
        u = b[:, 0][:, [0, 0, 1, 1]]
        t = b[:, 1][:, [0, 1, 0, 1]]
        return self._map(u, t)[0]

    def _params(self, nu: int, nt: int):
        """Gauss points in the boxes: u (k, q), t (k, q) and the box-weight (k, q)."""
        xu, wu = gauss_legendre(nu)
        xt, wt = gauss_legendre(nt)
        b = self.box
        du = (b[:, 0, 1] - b[:, 0, 0])[:, None]
        dt = (b[:, 1, 1] - b[:, 1, 0])[:, None]
        u = b[:, 0, 0][:, None] + du * np.repeat(xu, nt)[None, :]
        t = b[:, 1, 0][:, None] + dt * np.tile(xt, nu)[None, :]
        w = du * dt * np.outer(wu, wt).reshape(1, -1)
        return u, t, w


@dataclass(frozen=True, eq=False)
class ArcCells(_BoxCells):
    """Caps between a chord and a circular arc, in the arc's own frame.

    Frame: origin at the circle's centre, x along the arc's bisector, so the
    arc is θ ∈ [−α, α] at radius r and the chord is the line x = r cos α.
    By Green's theorem ``∬ f dA = ∮ F dy`` with ``F = ∫_{x_ref}^{x} f``: the
    cap is swept by segments at height ``y = r sin θ`` from ``x = x_ref`` to the
    arc, parameters ``u ∈ [0, 1] → θ = α (2u − 1)`` and ``t ∈ [0, 1]`` along
    the segment, Jacobian ``2α · r cos θ · (r cos θ − x_ref)``.
    ``x_ref = max(r cos α, 0)``: for caps larger than a half disc the chord
    term, the rectangle ``[r cos α, 0] × [−r sin α, r sin α]``, is integrated
    separately (as two triangles) so every point lies inside the cap.

    centre (k, 2) local, radius (k,), frame (k, 2, 2) columns (bisector,
    normal), half_angle (k,), sign (k,) ±1 (the cap adds or removes area).
    """

    centre: np.ndarray = None  # type: ignore[assignment]
    radius: np.ndarray = None  # type: ignore[assignment]
    frame: np.ndarray = None  # type: ignore[assignment]
    half_angle: np.ndarray = None  # type: ignore[assignment]
    sign: np.ndarray = None  # type: ignore[assignment]

    def _data(self) -> dict[str, np.ndarray]:
        return {"centre": self.centre, "radius": self.radius, "frame": self.frame,
                "half_angle": self.half_angle, "sign": self.sign}

    def rule(self, degree: int) -> tuple[np.ndarray, np.ndarray]:
        width = self.box[:, 0, 1] - self.box[:, 0, 0]
        nu = arc_points_for_degree(degree, float(np.max(self.half_angle * width, initial=0.0)))
        u, t, w = self._params(nu, points_for_degree(degree))
        points, jac = self._map(u, t)
        return points, jac * w

    def _map(self, u: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        alpha = self.half_angle[:, None]
        r = self.radius[:, None]
        x_ref = np.maximum(r * np.cos(alpha), 0.0)
        theta = alpha * (2 * u - 1)
        cos, sin = np.cos(theta), np.sin(theta)
        x = x_ref + t * (r * cos - x_ref)
        y = r * sin
        jac = 2 * alpha * r * cos * (r * cos - x_ref)
        local = np.stack((x, y), axis=-1)
        points = self.centre[:, None, :] + np.einsum("kij,kqj->kqi", self.frame, local)
        return points, self.sign[:, None] * jac


@dataclass(frozen=True, eq=False)
class BezierCells(_BoxCells):
    """Signed loops "cubic Bézier out, chord back", swept perpendicular to the chord.

    In a frame with origin at the first end and y along the chord, Green's
    theorem with ``F = ∫₀^x f`` leaves only the curve: parameters ``u`` (the
    curve's τ) and ``t`` along the segment from the chord to the curve point,
    Jacobian ``X(τ) Y′(τ)``. For a polynomial f of degree p the integrand has
    degree ``3p + 5`` in τ and p in t, so the rule is exact.

    controls: (k, 4, 2) local; frame (k, 2, 2) columns (across, along the chord).
    """

    controls: np.ndarray = None  # type: ignore[assignment]
    frame: np.ndarray = None  # type: ignore[assignment]

    def _data(self) -> dict[str, np.ndarray]:
        return {"controls": self.controls, "frame": self.frame}

    def rule(self, degree: int) -> tuple[np.ndarray, np.ndarray]:
        u, t, w = self._params(points_for_degree(3 * degree + 5), points_for_degree(degree))
        points, jac = self._map(u, t)
        return points, jac * w

    def _map(self, u: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        p0 = self.controls[:, 0]
        c = np.einsum("kij,kni->knj", self.frame, self.controls - p0[:, None])  # frame coords
        tau = u[..., None]
        mt = 1 - tau
        b0, b1, b2, b3 = (c[:, i][:, None, :] for i in range(4))
        curve = mt**3 * b0 + 3 * mt**2 * tau * b1 + 3 * mt * tau**2 * b2 + tau**3 * b3
        deriv = 3 * (mt**2 * (b1 - b0) + 2 * mt * tau * (b2 - b1) + tau**2 * (b3 - b2))
        x = t * curve[..., 0]
        y = curve[..., 1]
        jac = curve[..., 0] * deriv[..., 1]
        points = p0[:, None, :] + np.einsum("kij,kqj->kqi", self.frame, np.stack((x, y), axis=-1))
        return points, jac


@dataclass(frozen=True, eq=False)
class ProductCells(Cells):
    """Plane cells swept along an interval: prisms (``axis="z"``) or turns about z (``"phi"``).

    base: plane cells in (x, y) for prisms, in (r, z) for turns.
    interval: (k, 2) the z range (m) or the angle range (radians).
    periodic: the intervals are whole turns (then the equally spaced rule,
    exact for trigonometric polynomials, is used in the angle).

    For a turn the point is ``(r cos φ, r sin φ, z)`` and the Jacobian r, so the
    plane rule is asked for one degree more.
    """

    base: Cells
    interval: np.ndarray
    axis: str = "z"
    periodic: bool = False

    dim = 3

    @property
    def children(self) -> int:  # type: ignore[override]
        return 2 * self.base.children

    def __len__(self) -> int:
        return len(self.interval)

    def take(self, index: slice | np.ndarray) -> ProductCells:
        return ProductCells(self.base.take(index), self.interval[index], self.axis, self.periodic)

    def split(self) -> ProductCells:
        base = self.base.split()
        iv = np.repeat(self.interval, self.base.children, axis=0)
        mid = iv.mean(axis=1)
        halves = np.stack((np.stack((iv[:, 0], mid), axis=1),
                           np.stack((mid, iv[:, 1]), axis=1)), axis=1)
        index = np.repeat(np.arange(len(base)), 2)
        return ProductCells(base.take(index), halves.reshape(-1, 2), self.axis, False)

    def corners(self) -> np.ndarray:
        base = self.base.corners()  # (k, c, 2)
        k, c = base.shape[:2]
        u = np.repeat(base[..., 0], 2, axis=1)
        v = np.repeat(base[..., 1], 2, axis=1)
        along = np.tile(self.interval, (1, c))
        if self.axis == "phi":
            return np.stack((u * np.cos(along), u * np.sin(along), v), axis=-1)
        return np.stack((u, v, along), axis=-1)

    def rule(self, degree: int) -> tuple[np.ndarray, np.ndarray]:
        turn = self.axis == "phi"
        p2, w2 = self.base.rule(degree + 1 if turn else degree)
        if turn and self.periodic:
            n = degree + 1  # equally spaced: exact for trigonometric degree ≤ n − 1
            s, ws = (np.arange(n) + 0.5) / n, np.full(n, 1.0 / n)
        else:
            s, ws = gauss_legendre(points_for_degree(degree))
        a, b = self.interval[:, :1], self.interval[:, 1:]
        along = a + (b - a) * s[None, :]  # (k, n)
        wl = (b - a) * ws[None, :]
        k, q2, n = len(self), p2.shape[1], len(s)
        w = (w2[:, :, None] * wl[:, None, :]).reshape(k, q2 * n)
        u, v = p2[..., 0][:, :, None], p2[..., 1][:, :, None]
        along = along[:, None, :]
        if turn:
            pts = (u * np.cos(along), u * np.sin(along), np.broadcast_to(v, (k, q2, n)))
            w = w * np.broadcast_to(u, (k, q2, n)).reshape(k, -1)
        else:
            pts = (np.broadcast_to(u, (k, q2, n)), np.broadcast_to(v, (k, q2, n)),
                   np.broadcast_to(along, (k, q2, n)))
        return np.stack(pts, axis=-1).reshape(k, q2 * n, 3), w


# ------------------------------------------------------------------ the driver
@dataclass(frozen=True, eq=False)
class FieldIntegral:
    """Moments of a density field over cells, about ``origin``.

    origin: (d,) m. mass: ∫ρ (kg). first: (d,) ∫ρ r (kg·m). second: (d, d)
    ∫ρ r rᵀ (kg·m²). measure: ∫1, area (m²) or volume (m³).
    exact: the rule was exact for the field's polynomial degree.
    error: estimated absolute error, in kg (moments scaled by the body's size),
    0 when exact. converged: the error is within the tolerance.
    evaluations: density evaluations spent. cells: cells in the final partition.
    bad_points (m, d) world coordinates and bad_values (m,): samples where the
    density was negative or not finite (at most a few, the worst first).
    """

    origin: np.ndarray
    mass: float
    first: np.ndarray
    second: np.ndarray
    measure: float
    exact: bool
    error: float
    converged: bool
    evaluations: int
    cells: int
    bad_points: np.ndarray
    bad_values: np.ndarray
    vector_area: np.ndarray | None = None
    surface_area: float = 0.0
    corner_points: np.ndarray | None = None
    corner_values: np.ndarray | None = None


class _Bad:
    """Keeps a few of the worst invalid samples seen."""

    def __init__(self, dim: int) -> None:
        self.points = np.zeros((0, dim))
        self.values = np.zeros(0)

    def add(self, points: np.ndarray, values: np.ndarray) -> None:
        ok = np.isfinite(values) & (values >= 0)
        if ok.all():
            return
        bad = ~ok
        pts = np.concatenate((self.points, points[bad]))
        vals = np.concatenate((self.values, values[bad]))
        # Non-finite first, then most negative.
        key = np.where(np.isfinite(vals), vals, -np.inf)
        order = np.argsort(key, kind="stable")[:_KEEP_BAD]
        self.points, self.values = pts[order], vals[order]


def _evaluate(density: Callable[[np.ndarray], np.ndarray], points: np.ndarray,
              origin: np.ndarray, bad: _Bad) -> np.ndarray:
    k, q, d = points.shape
    world = points.reshape(-1, d) + origin
    values = np.asarray(density(world), dtype=float).reshape(-1)
    if values.shape != (k * q,):
        raise ValueError("a density field must return one value per point, "
                         f"got shape {values.shape}")
    if values.size and not (values.min() >= 0 and np.isfinite(values.sum())):
        bad.add(world, values)
    return values.reshape(k, q)


def _cell_sums(points: np.ndarray, weights: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Per-cell [∫1, ∫ρ, ∫ρ r (d), ∫ρ r rᵀ (d²)] → (k, 2 + d + d²)."""
    k, q, d = points.shape
    wr = weights * values
    out = np.empty((k, 2 + d + d * d))
    out[:, 0] = weights.sum(axis=1)
    out[:, 1] = wr.sum(axis=1)
    pw = points * wr[..., None]
    out[:, 2:2 + d] = pw.sum(axis=1)
    out[:, 2 + d:] = np.matmul(pw.transpose(0, 2, 1), points).reshape(k, d * d)
    return out


def _total_sums(points: np.ndarray, weights: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Sums over all cells (the fast path: one matrix product)."""
    k, q, d = points.shape
    flat = points.reshape(-1, d)
    wr = (weights * values).reshape(-1)
    out = np.empty(2 + d + d * d)
    out[0] = weights.sum()
    out[1] = wr.sum()
    pw = flat * wr[:, None]
    out[2:2 + d] = pw.sum(axis=0)
    out[2 + d:] = (pw.T @ flat).reshape(-1)
    return out


def _chunks(cells: Cells, per_cell: int):
    step = max(1, CHUNK_POINTS // max(per_cell, 1))
    for start in range(0, len(cells), step):
        yield cells.take(slice(start, start + step))


def _sweep(cells: Sequence[Cells], degree: int, density, origin, bad: _Bad, per_cell: bool):
    """Rule of ``degree`` over every family.

    Returns (totals (s,) or, per family, (sums (k, s), sample min (k,), sample max (k,))),
    and the number of evaluations.
    """
    d = len(origin)
    size = 2 + d + d * d
    totals = np.zeros(size)
    parts = []
    evaluations = 0
    for family in cells:
        if not len(family):
            parts.append((np.zeros((0, size)), np.zeros(0), np.zeros(0)))
            continue
        q = family.points_per_cell(degree)
        rows, lows, highs = [], [], []
        for chunk in _chunks(family, q):
            pts, w = chunk.rule(degree)
            values = _evaluate(density, pts, origin, bad)
            evaluations += values.size
            if per_cell:
                rows.append(_cell_sums(pts, w, values))
                lows.append(values.min(axis=1))
                highs.append(values.max(axis=1))
            else:
                totals += _total_sums(pts, w, values)
        if per_cell:
            parts.append((np.concatenate(rows), np.concatenate(lows), np.concatenate(highs)))
    return (parts if per_cell else totals), evaluations


def _corner_ranges(cells: Sequence[Cells], density, origin, bad: _Bad):
    """Per family: the density's (min, max) over each cell's corners, and evaluations."""
    out, evaluations = [], 0
    for family in cells:
        lows, highs = [], []
        c = family.corners().shape[1] if len(family) else 1
        for chunk in _chunks(family, c):
            values = _evaluate(density, chunk.corners(), origin, bad)
            evaluations += values.size
            lows.append(values.min(axis=1))
            highs.append(values.max(axis=1))
        out.append((np.concatenate(lows) if lows else np.zeros(0),
                    np.concatenate(highs) if highs else np.zeros(0)))
    return out, evaluations


def _blind_spots(sums: np.ndarray, lo: tuple, hi: tuple, corners: tuple) -> np.ndarray:
    """Error bound (kg) for cells whose corners see values their quadrature points miss.

    A jump that only clips a cell's corner can fall between every Gauss point of
    both rules, so the two agree; the corners see it. A corner value outside
    the samples' range by more than that range marks such a cell, and its error
    is bounded by ``|cell size| × excess`` (a smooth field's corners stay
    within about one range of its samples).
    """
    smin = np.minimum(lo[1], hi[1])
    smax = np.maximum(lo[2], hi[2])
    excess = np.maximum(np.maximum(corners[1] - smax, smin - corners[0]), 0.0)
    spread = smax - smin
    scale = np.maximum(np.abs(smax), np.abs(smin))
    flagged = excess > spread + 1e-9 * scale
    return np.where(flagged, 3 * np.abs(sums[:, 0]) * excess, 0.0)


def _norm(diff: np.ndarray, d: int, size: float) -> np.ndarray:
    """Errors in kg from differences of per-cell sums (k, s): mass + moments / size^k."""
    return (np.abs(diff[:, 1]) + np.abs(diff[:, 2:2 + d]).sum(axis=1) / size
            + np.abs(diff[:, 2 + d:]).sum(axis=1) / size**2)


def _result(origin, sums, exact, error, converged, evaluations, cells, bad: _Bad) -> FieldIntegral:
    d = len(origin)
    second = sums[2 + d:].reshape(d, d)
    return FieldIntegral(
        origin=np.asarray(origin, dtype=float), mass=float(sums[1]), first=sums[2:2 + d].copy(),
        second=(second + second.T) / 2, measure=float(sums[0]), exact=exact, error=float(error),
        converged=converged, evaluations=int(evaluations), cells=int(cells),
        bad_points=bad.points, bad_values=bad.values)


def integrate_field(
    cells: Sequence[Cells],
    density: Callable[[np.ndarray], np.ndarray],
    origin: np.ndarray,
    degree: int | None,
    *,
    tolerance: float = 1e-10,
    size: float = 1.0,
    max_evaluations: int = MAX_EVALUATIONS,
) -> FieldIntegral:
    """∫ρ, ∫ρ r and ∫ρ r rᵀ over signed ``cells`` (coordinates relative to ``origin``).

    ``density`` maps world points (n, d) m to (n,) kg/m^d. With ``degree`` (the
    field's polynomial degree) one pass of a rule of degree ``degree + 2`` is
    exact. Without it the integral is adaptive (see the module docstring) to a
    relative ``tolerance`` of the mass, moments measured against ``size`` (m),
    spending at most ``max_evaluations`` density evaluations.

    >>> tri = SimplexCells(np.array([[[0, 0], [1, 0], [0, 1]]], dtype=float))
    >>> r = integrate_field([tri], lambda p: 1 + p[:, 0], np.zeros(2), 1)
    >>> round(r.mass, 15), r.exact            # ∫(1 + x) over the triangle = 1/2 + 1/6
    (0.666666666666667, True)
    >>> r = integrate_field([tri], lambda p: np.exp(p[:, 0]), np.zeros(2), None)
    >>> abs(r.mass - (np.e - 2)) <= r.error, r.exact
    (True, False)
    """
    origin = np.asarray(origin, dtype=float)
    d = len(origin)
    bad = _Bad(d)
    ncells = sum(len(c) for c in cells)
    if degree is not None:
        sums, evaluations = _sweep(cells, int(degree) + 2, density, origin, bad, per_cell=False)
        return _result(origin, sums, True, 0.0, True, evaluations, ncells, bad)

    size = float(size) if size > 0 else 1.0
    families = [c for c in cells if len(c)]

    def cost(fams: Sequence[Cells], n: int) -> int:
        return sum(len(f) * (f.points_per_cell(2 * n - 1) + f.points_per_cell(2 * n + 1))
                   for f in fams)

    # Start as high as the budget allows (3 points per direction, down to 1).
    n = next((m for m in (3, 2) if cost(families, m) <= max_evaluations / 4), 1)
    lo_parts, spent = _sweep(families, 2 * n - 1, density, origin, bad, per_cell=True)
    corner_parts, ev = _corner_ranges(families, density, origin, bad)
    spent += ev
    done = np.zeros(2 + d + d * d)
    done_error = 0.0
    done_cells = 0
    total_measure = None
    previous = math.inf
    p_phase = True
    while True:
        hi_parts, ev = _sweep(families, 2 * n + 1, density, origin, bad, per_cell=True)
        spent += ev
        errors = [_norm(h[0] - lo[0], d, size) + _blind_spots(h[0], lo, h, c)
                  for h, lo, c in zip(hi_parts, lo_parts, corner_parts)]
        total = done + sum((h[0].sum(axis=0) for h in hi_parts), np.zeros_like(done))
        error = done_error + sum(float(e.sum()) for e in errors)
        target = tolerance * abs(total[1])
        active = sum(len(f) for f in families)
        if total_measure is None:
            total_measure = sum(float(np.abs(h[0][:, 0]).sum()) for h in hi_parts) or 1.0
        if error <= target or not active:
            return _result(origin, total, False, error, error <= target, spent,
                           done_cells + active, bad)
        if (p_phase and error < previous / 4 and n < 8
                and spent + cost(families, n + 1) <= max_evaluations / 2):
            previous = error
            n += 1
            lo_parts = hi_parts
            continue
        p_phase = False
        # h-phase: accept cells within their share of the tolerance, split the rest.
        kept = []
        for family, h, e in zip(families, hi_parts, errors):
            share = 0.5 * target * np.abs(h[0][:, 0]) / total_measure
            refine = e > share
            done += h[0][~refine].sum(axis=0)
            done_error += float(e[~refine].sum())
            done_cells += int((~refine).sum())
            if refine.any():
                kept.append(family.take(np.flatnonzero(refine)).split())
        if spent + cost(kept, n) > max_evaluations:
            return _result(origin, total, False, error, False, spent, done_cells + active, bad)
        families = kept
        lo_parts, ev = _sweep(families, 2 * n - 1, density, origin, bad, per_cell=True)
        spent += ev
        corner_parts, ev = _corner_ranges(families, density, origin, bad)
        spent += ev


MESH_CHUNK = 1 << 12  # triangles per pass of the mesh kernel: temporaries stay in cache


def mesh_field_moments(
    triangles: np.ndarray,
    density: Callable[[np.ndarray], np.ndarray],
    origin: np.ndarray,
    degree: int,
    *,
    chunk: int = MESH_CHUNK,
) -> FieldIntegral:
    """Exact moments of a polynomial density (``degree``) over a closed mesh (n, 3, 3), m.

    The fast path of :func:`integrate_field` for the signed tetrahedra
    ``(origin, a, b, c)`` of a triangle soup: component-major, cache-sized
    chunks, the points of the collapsed rule of degree ``degree + 2`` formed by
    small matrix products. In the same pass it sums the surface's vector area
    and area (closure check) and samples the density at every corner
    (``corner_points``/``corner_values`` keep the worst invalid ones).

    >>> from plumbob.bodies.primitives import box
    >>> r = mesh_field_moments(box(1, 1, 1).triangles, lambda p: 1 + p[:, 0], np.zeros(3), 1)
    >>> round(r.mass, 15), round(float(r.first[0] / r.mass), 15)   # ∫(1 + x) = 3/2, x̄ = 5/9
    (1.5, 0.555555555555556)
    """
    triangles = np.asarray(triangles)
    origin = np.asarray(origin, dtype=float)
    bary, w = tetrahedron_rule(int(degree) + 2)
    lam = np.ascontiguousarray(bary[:, 1:])  # (q, 3): weights of a, b, c (the apex is 0)
    q = len(w)
    bad, corners_bad = _Bad(3), _Bad(3)
    sums = np.zeros(11)  # measure, mass, first (3), second (6: xx yy zz xy xz yz)
    vector = np.zeros(3)
    area = 0.0
    evaluations = 0
    buffer = np.empty((2, 3, q, min(chunk, len(triangles))))
    corners = np.empty((3, 3, min(chunk, len(triangles))))
    for start in range(0, len(triangles), chunk):
        t = triangles[start:start + chunk]
        k = len(t)
        # (3 corners, 3 components, k), local coordinates
        c = corners[:, :, :k]
        np.subtract(t.transpose(1, 2, 0), origin[None, :, None], out=c)  # contiguous
        a, b, cc = c[0], c[1], c[2]
        e1, e2 = b - a, cc - a
        nx = e1[1] * e2[2] - e1[2] * e2[1]
        ny = e1[2] * e2[0] - e1[0] * e2[2]
        nz = e1[0] * e2[1] - e1[1] * e2[0]
        vector += (nx.sum(), ny.sum(), nz.sum())
        area += float(np.sqrt(nx * nx + ny * ny + nz * nz).sum())
        det = a[0] * nx + a[1] * ny + a[2] * nz  # a·(b×c) = a·((b−a)×(c−a))
        # Quadrature points, component-major: (3, q, k) = λ (q, 3) @ corners (3, k) per component.
        local, world = buffer[0, :, :, :k], buffer[1, :, :, :k]
        for j in range(3):
            np.matmul(lam, c[:, j, :], out=local[j])
            np.add(local[j], origin[j], out=world[j])
        flat = local.reshape(3, q * k)
        points = world.reshape(3, q * k).T
        values = np.asarray(density(points), dtype=float).reshape(q, k)
        corner_points = t.reshape(-1, 3)
        corner_values = np.asarray(density(corner_points), dtype=float)
        evaluations += values.size + corner_values.size
        if not (values.min() >= 0 and np.isfinite(values.sum())):
            bad.add(points, values.reshape(-1))
        if not (corner_values.min() >= 0 and np.isfinite(corner_values.sum())):
            corners_bad.add(np.asarray(corner_points, dtype=float), corner_values)
        values *= det
        values *= w[:, None]
        wr = values.reshape(-1)
        weighted = flat * wr
        sums[0] += det.sum() / 6
        sums[1] += wr.sum()
        sums[2:5] += weighted.sum(axis=1)
        m2 = weighted @ flat.T
        sums[5:11] += m2[[0, 1, 2, 0, 0, 1], [0, 1, 2, 1, 2, 2]]
    s = sums
    second = np.array([[s[5], s[8], s[9]], [s[8], s[6], s[10]], [s[9], s[10], s[7]]])
    total = np.concatenate(([s[0], s[1]], s[2:5], second.reshape(-1)))
    result = _result(origin, total, True, 0.0, True, evaluations, len(triangles), bad)
    from dataclasses import replace

    return replace(result, vector_area=vector / 2, surface_area=area / 2,
                   corner_points=corners_bad.points, corner_values=corners_bad.values)
