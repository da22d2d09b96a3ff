"""Integration cells: batches of signed plane or solid pieces, each with exact quadrature rules.

A body of variable density is cut into *cells*: signed triangles or tetrahedra
(:class:`SimplexCells`), caps between a chord and a circular arc
(:class:`ArcCells`) or a cubic Bézier (:class:`BezierCells`), and products of
a plane cell with an interval — prisms, and turns about an axis
(:class:`ProductCells`). Each family gives, for a polynomial degree ``p``,
points and signed weights that integrate every polynomial of degree ``p`` in
the coordinates exactly (to rounding), and splits its cells into children that
tile them with the same sign, which is all the adaptive driver
(:mod:`plumbob.integrals.adaptive`) needs.

Cells hold coordinates relative to a local origin chosen near the body, so the
products stay exact far from the world origin. A family is a batch: every
method works on all of its cells at once, with no Python loop over cells.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

from .rules import arc_points_for_degree, gauss_legendre, points_for_degree, simplex_rule

__all__ = ["Cells", "SimplexCells", "ArcCells", "BezierCells", "ProductCells"]


class Cells(ABC):
    """A batch of integration cells of one kind, in coordinates relative to a local origin.

    The interface the driver integrates over: signed rules, splitting, corners.
    Every method acts on the whole batch at once.

    Attributes
    ----------
    dim : int
        2 for plane cells, 3 for solid ones.
    children : int
        How many pieces :meth:`split` cuts each cell into.
    """

    dim: int
    children: int

    @abstractmethod
    def __len__(self) -> int:
        """Number of cells in the batch."""

    @abstractmethod
    def rule(self, degree: int) -> tuple[np.ndarray, np.ndarray]:
        """Points and signed weights integrating polynomials of ``degree`` exactly on every cell.

        Parameters
        ----------
        degree : int
            Polynomial degree in the coordinates.

        Returns
        -------
        points : ndarray of shape (k, q, dim)
            Relative to the local origin, m.
        weights : ndarray of shape (k, q)
            Jacobians included (m² or m³), signed like the cell.
        """

    @abstractmethod
    def split(self) -> Cells:
        """Cut every cell into ``children`` pieces that tile it with the same sign.

        Returns
        -------
        Cells
            ``len(self) * children`` cells; child j of cell i is at ``i * children + j``.
        """

    @abstractmethod
    def take(self, index: slice | np.ndarray) -> Cells:
        """The cells at ``index`` (a slice, integer indices or a boolean mask), same kind."""

    @abstractmethod
    def corners(self) -> np.ndarray:
        """The cells' corner points (k, c, dim), relative to the local origin.

        The driver samples the density there: a jump clipping a corner can hide
        between every quadrature point, never from the corners.
        """

    def points_per_cell(self, degree: int) -> int:
        """How many points ``rule(degree)`` uses per cell (0 for an empty batch)."""
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

    The weight of a cell is signed by its orientation: counter-clockwise
    triangles and positively oriented tetrahedra count positive.

    Parameters
    ----------
    vertices : ndarray of shape (k, dim + 1, dim), or (k, dim, dim)
        Corners relative to the local origin, m. The short form leaves out a
        first vertex at the local origin (the signed tetrahedra of a closed mesh).

    Examples
    --------
    >>> tri = SimplexCells(np.array([[[0, 0], [1, 0], [0, 1]]], dtype=float))
    >>> points, weights = tri.rule(1)
    >>> points.shape, float(weights.sum())          # one point, the area 1/2
    ((1, 1, 2), 0.5)
    >>> kids = tri.split()
    >>> len(kids), float(kids.rule(0)[1].sum())      # four children, same area
    (4, 0.5)
    >>> float(SimplexCells(tri.vertices[:, ::-1]).rule(0)[1].sum())   # clockwise: negative
    -0.5
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

    Parameters
    ----------
    box : ndarray of shape (k, 2, 2)
        Parameter boxes ``[(u0, u1), (t0, t1)]`` within [0, 1]²; a whole cap is
        ``[[0, 1], [0, 1]]``, and :meth:`split` halves both ranges.
    centre : ndarray of shape (k, 2)
        The circles' centres, relative to the local origin, m.
    radius : ndarray of shape (k,)
        m.
    frame : ndarray of shape (k, 2, 2)
        Columns: the unit bisector of the arc and its normal.
    half_angle : ndarray of shape (k,)
        α, radians, in (0, π).
    sign : ndarray of shape (k,)
        +1 where the cap adds area, −1 where it removes it.

    Examples
    --------
    >>> half_disc = ArcCells(box=np.array([[[0.0, 1.0], [0.0, 1.0]]]), centre=np.zeros((1, 2)),
    ...     radius=np.ones(1), frame=np.eye(2)[None], half_angle=np.array([np.pi / 2]),
    ...     sign=np.ones(1))
    >>> round(float(half_disc.rule(0)[1].sum()), 14) == round(np.pi / 2, 14)
    True
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

    Parameters
    ----------
    box : ndarray of shape (k, 2, 2)
        Parameter boxes ``[(τ0, τ1), (t0, t1)]`` within [0, 1]², as for :class:`ArcCells`.
    controls : ndarray of shape (k, 4, 2)
        The four control points, relative to the local origin, m.
    frame : ndarray of shape (k, 2, 2)
        Columns: the unit vector across the chord and the unit vector along it.

    Examples
    --------
    A parabolic arch of height 1 over the chord (0, 0)–(1, 0) encloses 2/3;
    the loop (up the arch, back along the chord) runs clockwise, so it counts negative:

    >>> arch = BezierCells(box=np.array([[[0.0, 1.0], [0.0, 1.0]]]),
    ...     controls=np.array([[[0, 0], [1 / 3, 4 / 3], [2 / 3, 4 / 3], [1, 0]]]),
    ...     frame=np.array([[[0.0, 1.0], [-1.0, 0.0]]]))
    >>> round(float(arch.rule(0)[1].sum()), 12)
    -0.666666666667
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

    Parameters
    ----------
    base : Cells
        Plane cells in (x, y) for prisms, in (r, z) for turns, one per interval.
    interval : ndarray of shape (k, 2)
        The z range (m) or the angle range (radians) of each cell.
    axis : {"z", "phi"}
        Sweep along z (a prism) or turn about the z axis.
    periodic : bool
        The intervals are whole turns: the equally spaced rule in the angle,
        exact for trigonometric polynomials, replaces Gauss–Legendre.

    Examples
    --------
    A unit square at 1 ≤ r ≤ 2 turned once about z: a tube of volume 3π.

    >>> square = SimplexCells(np.array([[[1, 0], [2, 0], [2, 1]], [[1, 0], [2, 1], [1, 1]]], float))
    >>> tube = ProductCells(square, np.tile([0.0, 2 * np.pi], (2, 1)), "phi", periodic=True)
    >>> round(float(tube.rule(0)[1].sum() / np.pi), 14)
    3.0
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


