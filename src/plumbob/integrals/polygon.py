"""Exact area moments of plane regions by Green's theorem.

A region's boundary is made of rings; each ring is a polygon through its
vertices (the *chords*) whose edges may bulge into circular arcs or cubic
Bézier curves. By Green's theorem the moments of the region are the moments of
the chord polygon plus, for every curved edge, the moments of the small loop
"curve out, chord back" — a signed circular segment, or a Bézier cap.

All kernels take coordinates *relative to a local origin* chosen by the caller
(near the region) and return moment tensors about that origin:

* ``m0``: area, m²
* ``m1``: shape (2,), ``∫ r dA``, m³
* ``m2``: shape (2, 2), ``∫ r rᵀ dA``, m⁴
* ``m3``: shape (2, 2, 2), ``∫ r⊗r⊗r dA``, m⁵ (only where asked; solids of
  revolution need it)

Areas are signed: counter-clockwise rings count positive, clockwise negative.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "AreaMoments",
    "polygon_moments",
    "rings_moments",
    "arc_cap_moments",
    "cubic_cap_moments",
    "bulge_arc_geometry",
]


@dataclass(frozen=True, eq=False)
class AreaMoments:
    """Signed moments of a plane region about a local origin (see module docstring)."""

    m0: float
    m1: np.ndarray
    m2: np.ndarray
    m3: np.ndarray | None = None

    def __add__(self, other: AreaMoments) -> AreaMoments:
        m3 = None if self.m3 is None or other.m3 is None else self.m3 + other.m3
        return AreaMoments(self.m0 + other.m0, self.m1 + other.m1, self.m2 + other.m2, m3)

    def __neg__(self) -> AreaMoments:
        return AreaMoments(-self.m0, -self.m1, -self.m2, None if self.m3 is None else -self.m3)

    @staticmethod
    def zero(degree: int = 2) -> AreaMoments:
        return AreaMoments(
            0.0, np.zeros(2), np.zeros((2, 2)), np.zeros((2, 2, 2)) if degree >= 3 else None
        )


def _simplex_tensors(measure: np.ndarray, vertices: list[np.ndarray], degree: int):
    """Moment tensors of simplices (one vertex at the origin is implied when
    ``vertices`` has only ``dim`` entries) from the complete-homogeneous formula
    ``∫_T ℓ(r)^n = |T| n! m! / (n+m)! h_n(ℓ(v_0), …, ℓ(v_m))``.

    ``measure`` (k,) is the signed size, each vertex array is (k, dim).
    Returns (m0, m1, m2, m3) summed over the k simplices.
    """
    m = vertices[0].shape[1]
    s = sum(vertices)
    m0 = measure.sum()
    m1 = measure @ s / (m + 1)
    # h_2 = (S S^T + Q) / 2, scale 2! m! / (m+2)!
    w2 = measure / ((m + 1) * (m + 2))
    q = sum(np.einsum("k,ki,kj->ij", w2, v, v) for v in vertices)
    m2 = q + np.einsum("k,ki,kj->ij", w2, s, s)
    m3 = None
    if degree >= 3:
        # h_3 = (S⊗S⊗S + 3 sym(S⊗Q) + 2 C) / 6, scale 3! m! / (m+3)!
        w3 = measure / ((m + 1) * (m + 2) * (m + 3))
        sss = np.einsum("k,ki,kj,kl->ijl", w3, s, s, s)
        c = sum(np.einsum("k,ki,kj,kl->ijl", w3, v, v, v) for v in vertices)
        sq = sum(np.einsum("k,ki,kj,kl->ijl", w3, s, v, v) for v in vertices)
        sym_sq = sq + sq.transpose(1, 0, 2) + sq.transpose(1, 2, 0)
        m3 = sss + sym_sq + 2 * c
    return float(m0), m1, m2, m3


def polygon_moments(vertices: np.ndarray, origin: np.ndarray, degree: int = 2) -> AreaMoments:
    """Signed moments of the polygon through ``vertices`` (n, 2), closed implicitly.

    The polygon is fanned into triangles from ``origin``; every product is formed
    in coordinates relative to it, so results stay exact far from (0, 0).

    >>> square = np.array([[0, 0], [2, 0], [2, 1], [0, 1]], dtype=float)
    >>> m = polygon_moments(square, np.zeros(2))
    >>> m.m0, m.m1.tolist()
    (2.0, [2.0, 1.0])
    >>> polygon_moments(square[:2], np.zeros(2)).m0   # a degenerate ring has no area
    0.0
    """
    v = np.asarray(vertices, dtype=float)
    if len(v) < 3:
        return AreaMoments.zero(degree)
    if degree >= 3:
        a = v - origin
        b = np.roll(a, -1, axis=0)
        cross = a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]
        m0, m1, m2, m3 = _simplex_tensors(cross / 2, [a, b], 3)
        return AreaMoments(m0, m1, m2, m3)
    return _polygon_moments_2(v, np.asarray(origin, dtype=float))


def rings_moments(rings: list[np.ndarray], origin: np.ndarray, degree: int = 2) -> AreaMoments:
    """The summed signed moments of many straight-edged rings (each (n_i, 2), closed
    implicitly) about ``origin``, in one vectorised pass: a drawing of 100,000 holes is
    one fan of edges, not 100,000 calls of :func:`polygon_moments`.

    >>> square = np.array([[0, 0], [2, 0], [2, 1], [0, 1]], dtype=float)
    >>> hole = square[::-1] * 0.5 + 0.25
    >>> m = rings_moments([square, hole, square[:2]], np.zeros(2))
    >>> m.m0, m.m0 == (polygon_moments(square, np.zeros(2)) + polygon_moments(hole, np.zeros(2))).m0
    (1.5, True)
    """
    rings = [r for r in rings if len(r) >= 3]  # a degenerate ring has no area
    if not rings:
        return AreaMoments.zero(degree)
    lengths = np.fromiter((len(r) for r in rings), dtype=np.int64, count=len(rings))
    a = np.concatenate(rings).astype(float, copy=False) - np.asarray(origin, dtype=float)
    following = np.arange(1, len(a) + 1)
    ends = np.cumsum(lengths) - 1
    following[ends] = ends - lengths + 1  # each ring's last edge closes to its first vertex
    b = a[following]
    cross = a[:, 0] * b[:, 1] - b[:, 0] * a[:, 1]
    m0, m1, m2, m3 = _simplex_tensors(cross / 2, [a, b], degree)
    return AreaMoments(m0, m1, m2, m3)


_CHUNK = 1 << 14  # vertices per pass: the temporaries stay in cache


def _polygon_moments_2(v: np.ndarray, origin: np.ndarray) -> AreaMoments:
    """Degree ≤ 2, the hot path: the simplex formula expanded by hand, summed in
    cache-sized chunks with in-place temporaries.

    Per edge (x0, y0) → (x1, y1), with c = x0 y1 − x1 y0:
    ``A = Σc/2``, ``∫x = Σc(x0+x1)/6``, ``∫x² = Σc(x0² + x0x1 + x1²)/12``,
    ``∫xy = Σc(x0(2y0+y1) + x1(y0+2y1))/24``.
    """
    n = len(v)
    sums = np.zeros(6)
    for start in range(0, n, _CHUNK):
        stop = min(n, start + _CHUNK)
        block = v[start : stop + 1] if stop < n else np.vstack((v[start:stop], v[:1]))
        local = block - origin
        x, y = local[:, 0], local[:, 1]
        x0, x1, y0, y1 = x[:-1], x[1:], y[:-1], y[1:]
        cross = x0 * y1
        cross -= x1 * y0
        sx = x0 + x1
        sy = y0 + y1
        qxx = x0 * sx
        qxx += x1 * x1
        qyy = y0 * sy
        qyy += y1 * y1
        qxy = y0 + sy
        qxy *= x0
        tail = y1 + sy
        tail *= x1
        qxy += tail
        sums += (cross.sum(), cross @ sx, cross @ sy, cross @ qxx, cross @ qyy, cross @ qxy)
    sxy = sums[5] / 24
    return AreaMoments(
        float(sums[0] / 2),
        sums[1:3] / 6,
        np.array([[sums[3] / 12, sxy], [sxy, sums[4] / 12]]),
    )


def bulge_arc_geometry(p0: np.ndarray, p1: np.ndarray, bulge: np.ndarray):
    """Circle of each arc given by chord ends (k, 2) and DXF bulge ``tan(sweep/4)``.

    A positive bulge turns counter-clockwise from ``p0`` to ``p1``. Returns
    ``(centre (k, 2), radius (k,), half_angle (k,), bisector (k, 2))`` where the
    bisector is the unit vector from the centre to the arc's midpoint.
    """
    chord = p1 - p0
    length = np.hypot(chord[:, 0], chord[:, 1])
    direction = chord / length[:, None]
    left = np.stack((-direction[:, 1], direction[:, 0]), axis=1)
    half_angle = 2 * np.arctan(np.abs(bulge))
    radius = length / (2 * np.sin(half_angle))
    sagitta = bulge * length / 2
    arc_mid = (p0 + p1) / 2 - left * sagitta[:, None]
    bisector = -left * np.sign(bulge)[:, None]
    centre = arc_mid - bisector * radius[:, None]
    return centre, radius, half_angle, bisector


def _rotate_shift(m0, m1, m2, m3, rotation, shift):
    """Tensors (k-batched) turned by ``rotation`` (k, 2, 2) then moved by ``shift`` (k, 2)."""
    m1 = np.einsum("kia,ka->ki", rotation, m1)
    m2 = np.einsum("kia,kjb,kab->kij", rotation, rotation, m2)
    if m3 is not None:
        m3 = np.einsum("kia,kjb,klc,kabc->kijl", rotation, rotation, rotation, m3)
        t = shift
        m2t = np.einsum("kij,kl->kijl", m2, t)
        m1tt = np.einsum("ki,kj,kl->kijl", m1, t, t)
        m3 = (
            m3
            + m2t
            + m2t.transpose(0, 1, 3, 2)
            + m2t.transpose(0, 3, 1, 2)
            + m1tt
            + m1tt.transpose(0, 2, 1, 3)
            + m1tt.transpose(0, 2, 3, 1)
            + m0[:, None, None, None] * np.einsum("ki,kj,kl->kijl", t, t, t)
        )
    m1t = np.einsum("ki,kj->kij", m1, shift)
    m2 = (
        m2
        + m1t
        + m1t.transpose(0, 2, 1)
        + m0[:, None, None] * np.einsum("ki,kj->kij", shift, shift)
    )
    m1 = m1 + m0[:, None] * shift
    return m0, m1, m2, m3


def _x_minus_sin(x: np.ndarray) -> np.ndarray:
    """``x − sin x`` to full relative precision, also for small ``x`` (a Taylor series).

    >>> float(_x_minus_sin(np.array(1e-4)) / (1e-12 / 6))
    0.9999999995000001
    """
    x = np.asarray(x, dtype=float)
    direct = x - np.sin(x)
    x2 = x * x
    term, series = x * x2 / 6, np.zeros_like(x)
    for k in range(1, 12):  # |x| < 1: the twelfth term is below 1e-20 of the first
        series = series + term
        term = -term * x2 / ((2 * k + 2) * (2 * k + 3))
    return np.where(np.abs(x) < 1.0, series, direct)


def arc_cap_moments(
    p0: np.ndarray, p1: np.ndarray, bulge: np.ndarray, origin: np.ndarray, degree: int = 2
) -> AreaMoments:
    """Signed moments of the circular segments between chords p0→p1 (k, 2) and their arcs.

    Each segment counts positive for a positive bulge (the loop "arc out, chord
    back" then runs counter-clockwise). Closed forms in the segment's own frame —
    centre at the origin, bisector along x — are turned and moved into place.

    >>> m = arc_cap_moments(np.array([[1.0, 0.0]]), np.array([[-1.0, 0.0]]), np.array([1.0]),
    ...                     np.zeros(2))
    >>> bool(np.isclose(m.m1[1] / m.m0, 4 / (3 * np.pi), rtol=1e-15))
    True
    """
    bulge = np.asarray(bulge, dtype=float)
    if bulge.size == 0:
        return AreaMoments.zero(degree)
    p0 = np.asarray(p0, dtype=float) - origin
    p1 = np.asarray(p1, dtype=float) - origin
    centre, r, alpha, u = bulge_arc_geometry(p0, p1, bulge)
    s, c = np.sin(alpha), np.cos(alpha)
    r2 = r * r
    # Sector |φ| ≤ α minus the signed triangle (0, r e^{iα}, r e^{-iα}).
    tri = r2 * s * c
    # Written without the cancellation of sector − triangle, which loses every digit
    # of a nearly straight arc: α − s c = (2α − sin 2α)/2 and the x moment is 2r³s³/3.
    m0 = r2 * _x_minus_sin(2 * alpha) / 2
    mx = 2 * r2 * r * s**3 / 3
    m1 = np.stack((mx, np.zeros_like(mx)), axis=1)
    r4 = r2 * r2
    mxx = r4 / 4 * (alpha + s * c) - tri * r2 * c * c / 2
    myy = r4 / 4 * (alpha - s * c) - tri * r2 * s * s / 6
    m2 = np.zeros((len(bulge), 2, 2))
    m2[:, 0, 0] = mxx
    m2[:, 1, 1] = myy
    m3 = None
    if degree >= 3:
        r5 = r4 * r
        m3 = np.zeros((len(bulge), 2, 2, 2))
        # Triangle third moments: (T/10) h_3 over vertices {0, A, B}.
        xxx = r5 / 5 * (2 * s - 2 * s**3 / 3) - tri * r * r2 * c**3 * 2 / 5
        xyy = r5 / 5 * (2 * s**3 / 3) - tri * r * r2 * c * s * s * 2 / 15
        m3[:, 0, 0, 0] = xxx
        m3[:, 0, 1, 1] = m3[:, 1, 0, 1] = m3[:, 1, 1, 0] = xyy
    rotation = np.stack((u, np.stack((-u[:, 1], u[:, 0]), axis=1)), axis=2)
    m0, m1, m2, m3 = _rotate_shift(m0, m1, m2, m3, rotation, centre)
    sign = np.sign(bulge)
    return AreaMoments(
        float(sign @ m0),
        np.einsum("k,ki->i", sign, m1),
        np.einsum("k,kij->ij", sign, m2),
        None if m3 is None else np.einsum("k,kijl->ijl", sign, m3),
    )


_GAUSS_NODES, _GAUSS_WEIGHTS = np.polynomial.legendre.leggauss(8)
_T = (_GAUSS_NODES + 1) / 2
_W = _GAUSS_WEIGHTS / 2


def cubic_cap_moments(controls: np.ndarray, origin: np.ndarray, degree: int = 2) -> AreaMoments:
    """Signed moments of the loops "cubic Bézier out, chord back" for controls (k, 4, 2).

    Green's theorem ``∫ x^p y^q dA = ∮ x^(p+1) y^q / (p+1) dy`` has a polynomial
    integrand of degree at most 14 along a cubic, so 8-point Gauss–Legendre is
    exact (to rounding).
    """
    ctrl = np.asarray(controls, dtype=float) - origin
    if len(ctrl) == 0:
        return AreaMoments.zero(degree)
    t = _T[None, :, None]
    b0, b1, b2, b3 = (ctrl[:, i][:, None, :] for i in range(4))
    mt = 1 - t
    curve = mt**3 * b0 + 3 * mt**2 * t * b1 + 3 * mt * t**2 * b2 + t**3 * b3
    dcurve = 3 * (mt**2 * (b1 - b0) + 2 * mt * t * (b2 - b1) + t**2 * (b3 - b2))
    line = (1 - t) * b3 + t * b0
    dline = (b0 - b3) * np.ones_like(t)
    points = np.concatenate((curve, line), axis=1)
    tangents = np.concatenate((dcurve, dline), axis=1)
    weights = np.concatenate((_W, _W))
    x, y, dy = points[..., 0], points[..., 1], tangents[..., 1] * weights

    def moment(p: int, q: int) -> float:
        return float(np.sum(x ** (p + 1) * y**q * dy) / (p + 1))

    m1 = np.array([moment(1, 0), moment(0, 1)])
    sxy = moment(1, 1)
    m2 = np.array([[moment(2, 0), sxy], [sxy, moment(0, 2)]])
    m3 = None
    if degree >= 3:
        m3 = np.empty((2, 2, 2))
        for i in range(2):
            for j in range(2):
                for k in range(2):
                    nx = (i == 0) + (j == 0) + (k == 0)
                    m3[i, j, k] = moment(nx, 3 - nx)
    return AreaMoments(moment(0, 0), m1, m2, m3)
