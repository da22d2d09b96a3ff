"""Convex hulls for the pose code, chosen by measurement: manifold3d first, qhull as fallback.

manifold3d's quickhull is the faster by one to three orders of magnitude on finely
tessellated meshes (qhull slows badly on the nearly co-circular points of a
tessellated circle), and manifold3d imports in milliseconds where ``scipy.spatial``
takes hundreds, which alone would be a large part of the start-up of ``plumbob
poses``: the figures are in ``docs/stability.md`` (*Speed*), measured by
``python bench/poses.py --hulls``. So
:func:`hull_triangles` asks manifold3d, checks its answer (a closed surface of
non-degenerate triangles, every edge convex to rounding error, a volume) and falls
back to qhull only when that check fails. A closed mesh that is its own hull (a
finely tessellated capsule: every point on the hull, quickhull's slowest case) needs
no hull at all: :func:`own_hull` proves it convex and takes its triangles.

manifold3d returns the hull's vertices as exact copies of input points
(``to_mesh64``), so the facet planes are planes through input points, as qhull's are.
Its quickhull leaves out points within its own epsilon (about 1e-7 of the size) of a
facet, an order of magnitude below the contact tolerance (1e-6 of the size) at which
faces are merged, so no pose can change.

On large inputs manifold3d builds the hull in parallel: the same triangles (through
the same points, in the same order) come back in another order, each starting at
another of its corners, from run to run. Each triangle is made to start at its least
point (:func:`_rotated`) and :func:`_normal_order` orders them by normal, equal
normals in ascending order of their points (:func:`_point_keys`; the order
:func:`_canonical` sorts them in): an order of the points' own. Every
cross product and every sum then runs the same way in every run, so the answers are
the same to the bit (they varied by round-off before, 1e-13 relative in a small
pose's probability).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ...arrays import cross, dot, lex_order, stable_order
from ...blockwise import blockwise
from ...errors import GeometryError
from ...mesh.winding import solid_angle
from ...tolerances import HULL_LEFT_OUT, size_of
from .holds import EXHAUSTIVE, degenerate, holds

__all__ = ["hull_triangles", "half_edge_twins", "twins_and_ends", "HullMesh", "hull_mesh", "own_hull",
           "corner_levels", "may_be_own_hull", "sample_triangles", "SOLID_ANGLE_CLOSURE"]

#: a surface proved convex by :func:`own_hull` subtends 4π from the centre to within this,
#: relative (one winding is 4π, two 8π: any other integer is far outside it)
SOLID_ANGLE_CLOSURE = 1e-9


class HullMesh(NamedTuple):
    """The convex hull as triangles, with what the checks measured on the way (so that
    :func:`~.hull.build_hull3` need not measure it again).

    points (m, 3), tri (F, 3), normals (F, 3), offsets (F,), twins (3F,): as
    :func:`hull_triangles` returns them. area: (F,) the triangles' areas. beyond: (3F,)
    per half-edge, the height of the far corner of the triangle across it over this
    triangle's plane (≤ 0 to rounding error on a convex hull). ends, end_twins,
    end_points: (3F,), (3F,), (2, 3F) the half-edges in ascending order of (from, to)
    points, the place of each one's twin in that order, and their points
    (:func:`twins_and_ends`). The corners' heights
    along their own triangle's normal are :func:`corner_levels`', measured where needed.
    """

    points: np.ndarray
    tri: np.ndarray
    normals: np.ndarray
    offsets: np.ndarray
    twins: np.ndarray
    area: np.ndarray
    beyond: np.ndarray
    ends: np.ndarray
    end_twins: np.ndarray
    end_points: np.ndarray


def _twins_by_search(tri: np.ndarray, n: int) -> np.ndarray | None:
    """:func:`half_edge_twins` by searching each reversed key among the sorted keys: the
    general answer, for the surfaces the pairing by undirected keys cannot settle."""
    frm = tri.ravel()
    to = tri[:, [1, 2, 0]].ravel()
    key = frm * n + to
    order = np.argsort(key, kind="stable")
    skey = key[order]
    if len(skey) > 1 and np.any(skey[1:] == skey[:-1]):
        return None  # an edge used twice in one direction: not a 2-manifold
    pos = np.minimum(np.searchsorted(skey, to * n + frm), len(skey) - 1)
    twin = order[pos]
    if not np.array_equal(key[twin], to * n + frm):
        return None
    return twin


def half_edge_twins(tri: np.ndarray, n: int) -> np.ndarray | None:
    """For the half-edges ``tri[t, k] → tri[t, (k + 1) % 3]`` (numbered ``3 t + k``), the
    reversed half-edge of each; None when the triangles are not a closed surface (an
    edge without exactly one reversed partner): :func:`twins_and_ends`' twins.

    >>> half_edge_twins(np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]), 4).tolist()
    [8, 11, 3, 2, 10, 6, 5, 9, 0, 7, 4, 1]
    """
    found = twins_and_ends(tri, n)
    return None if found is None else found[0]


def twins_and_ends(tri: np.ndarray, n: int
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None:
    """:func:`half_edge_twins` (3F,), the half-edges in ascending order of (from, to)
    (3F,: ``ends``), for the p-th of them the place of its twin in that order (3F,:
    ``twin[ends[p]] == ends[end_twins[p]]``) and its points (2, 3F: from, to), for the
    hull's edges (:func:`~.hull.build_hull3`); None when the triangles are not a closed
    surface.

    One stable sort of the directed keys (from, to), and one of that order by ``to``,
    which puts it in the order of (to, from): on a closed surface, whose directed edges
    are distinct and each reversed exactly once, the p-th half-edge by (to, from) is the
    reverse of the p-th by (from, to), as reversing maps one order onto the other.
    Checked: each pair must be reversed, else the surface is not closed (an edge used
    twice in one direction, or one without its reverse) and None, as
    :func:`_twins_by_search` finds. The second sort's keys are point numbers (one or
    two 16-bit passes), and the first one's order is the edges' order that
    :func:`~.hull.build_hull3` would otherwise sort again.

    >>> [a.tolist() for a in twins_and_ends(np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1],
    ...                                                [1, 3, 2]]), 4)]  # doctest: +NORMALIZE_WHITESPACE
    [[8, 11, 3, 2, 10, 6, 5, 9, 0, 7, 4, 1], [0, 3, 6, 8, 1, 9, 2, 11, 4, 5, 7, 10],
     [3, 6, 9, 0, 7, 10, 1, 4, 11, 2, 5, 8],
     [[0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3], [1, 2, 3, 0, 2, 3, 0, 1, 3, 0, 1, 2]]]
    """
    key = np.empty_like(tri)  # each half-edge's end, by column copies (a fancy gather of
    key[:, :2] = tri[:, 1:]  # the columns costs 3x) ...
    key[:, 2] = tri[:, 0]
    key = key.ravel()
    key += tri.ravel() * n  # ... and its key (from, to)
    ends = stable_order(key)
    key = key[ends]  # the directed keys in ascending order
    points = np.empty((2, len(key)), dtype=key.dtype)  # their points, in place
    a, b = points
    np.floor_divide(key, n, out=a)
    np.multiply(a, n, out=b)
    np.subtract(key, b, out=b)
    if len(ends) > 1 and np.any((a[1:] == a[:-1]) & (b[1:] == b[:-1])):
        return None  # an edge used twice in one direction: not a 2-manifold
    end_twins = stable_order(b)  # by (to, from): the reverse of each by (from, to)
    reverse = b * n  # the key of each one's reverse (0 <= a, b < n: one key, one pair)
    reverse += a
    if not np.array_equal(key[end_twins], reverse):
        return None  # an edge without its reverse
    twin = np.empty_like(ends)
    twin[ends] = ends[end_twins]
    return twin, ends, end_twins, points


def _normal_order(normals: np.ndarray, ties: np.ndarray | None = None) -> np.ndarray:
    """The triangles ordered by their normals rounded to 1e-9, largest x first, then y,
    then z, then as given: ``np.lexsort`` of the rounded components, as three stable
    integer sorts (:func:`~plumbob.arrays.lex_order`) instead of three float ones.

    ``np.round(x, 9)`` is ``rint(x · 1e9) / 1e9``, so the integers ``rint(x · 1e9)``
    (|·| ≤ 1e9) sort the same way.

    ``ties`` (F,) distinct integers, optional: equal rounded normals in ascending order
    of ``ties`` rather than as given (:func:`_point_keys`, a hull's triangles in the
    order of their points). Then x and y, 31 bits each, are one key sorted once, and
    only the triangles that tie on it (a split flat facet's) are sorted further.
    """
    def rounded(index: tuple | slice) -> np.ndarray:  # 0 ..= 2e9: descending components
        return (1e9 - np.rint(normals[index] * 1e9)).astype(np.int64)

    if ties is None:
        q = rounded(slice(None))
        return lex_order([q[:, 2], q[:, 1], q[:, 0]])
    key = rounded((slice(None), 0)) << 31
    key |= rounded((slice(None), 1))
    order = stable_order(key)  # by 16-bit digits, 2x np.argsort's speed; ties settled below
    ranked = key[order]
    same = ranked[1:] == ranked[:-1]
    if same.any():
        tied = np.flatnonzero(np.concatenate((same, [False])) | np.concatenate(([False], same)))
        run = np.cumsum(np.concatenate(([0], ~same)))[tied]  # ascending along ``tied``
        sub = order[tied]
        order[tied] = sub[np.lexsort((sub, ties[sub], rounded((sub, 2)), run))]
    return order


def _rotated(tri: np.ndarray) -> np.ndarray:
    """The triangles ``tri`` (F, 3) each starting at its least point, the winding kept.

    >>> _rotated(np.array([[5, 2, 7], [3, 1, 4]])).tolist()
    [[2, 7, 5], [1, 4, 3]]
    """
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    at_a = (a <= b) & (a <= c)  # np.argmin's choice: the first least corner
    at_b = ~at_a & (b <= c)
    out = np.empty_like(tri)
    np.minimum(np.minimum(a, b), c, out=out[:, 0])  # the least corner, where it is
    out[:, 1] = np.where(at_a, b, np.where(at_b, c, a))
    out[:, 2] = np.where(at_a, c, np.where(at_b, a, b))
    return out


def _canonical(tri: np.ndarray) -> np.ndarray:
    """The triangles ``tri`` (F, 3) each starting at its least point (the winding kept),
    in ascending order of (first, second, third) point: an order of the points' own,
    whatever order and starting corners the hull library chose.

    >>> _canonical(np.array([[5, 2, 7], [3, 1, 4], [2, 9, 6]])).tolist()
    [[1, 4, 3], [2, 7, 5], [2, 9, 6]]
    """
    tri = _rotated(tri)
    return np.take(tri, lex_order([tri[:, 2], tri[:, 1], tri[:, 0]]), axis=0)


_POINT_BITS = 21  # three point indices below 2²¹ pack into one int64 (:func:`_point_keys`)


def _point_keys(tri: np.ndarray, n: int) -> np.ndarray | None:
    """Per triangle of ``tri`` (:func:`_rotated`, indices below ``n``) one int64 in the
    order :func:`_canonical` sorts them by (first, second, third point), or None for
    ``n`` of 2²¹ points or more.

    >>> _point_keys(np.array([[1, 4, 3], [2, 7, 5]]), 10).tolist() == [
    ...     (1 << 42) + (4 << 21) + 3, (2 << 42) + (7 << 21) + 5]
    True
    """
    if n >= 1 << _POINT_BITS:
        return None
    key = tri[:, 0] << 2 * _POINT_BITS
    key |= tri[:, 1] << _POINT_BITS
    key |= tri[:, 2]
    return key


def _columns(P: np.ndarray) -> np.ndarray:
    """(3, n) the coordinates of the points ``P`` (n, 3), a row each: gathered by index,
    each gives a contiguous array, and the products below run on contiguous arrays (the
    same operations, in the same order, as on rows of corners: the same bits, in about
    half the time)."""
    return np.ascontiguousarray(np.asarray(P, dtype=np.float64).T)


def _dot_rows(Q: np.ndarray, idx: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``dot(P[idx], v[:, None, :])`` for ``Q = _columns(P)``, ``idx`` (k, 3), ``v`` (k, 3):
    each row's three points along that row's vector (x, then y, then z added)."""
    out = Q[0][idx] * v[:, 0:1]
    out += Q[1][idx] * v[:, 1:2]
    out += Q[2][idx] * v[:, 2:3]
    return out


def _planes(P: np.ndarray, tri: np.ndarray, solid_angles: bool = False
            ) -> tuple[np.ndarray, ...]:
    """Unit normals, offsets (the plane n·x = offset) and the lengths of the raw cross
    products (twice the areas) of the triangles ``tri`` through ``P``; with
    ``solid_angles``, also the solid angle each subtends from the origin. Block by
    block: the corners are never gathered for all triangles at once. The numbers are
    :func:`_corner_planes`', bit for bit (tested)."""
    if solid_angles:
        def corners(r: slice) -> tuple[np.ndarray, ...]:
            C = np.take(P, tri[r], axis=0)
            return (*_corner_planes(C), solid_angle(C[:, 0], C[:, 1], C[:, 2]))

        return blockwise(len(tri), corners)
    Q = _columns(P)

    def rows(r: slice) -> tuple[np.ndarray, ...]:
        t = tri[r].T
        (ax, bx, cx), (ay, by, cy), (az, bz, cz) = (Q[k][t] for k in range(3))
        ux, uy, uz = bx - ax, by - ay, bz - az
        vx, vy, vz = cx - ax, cy - ay, cz - az
        nx = uy * vz - uz * vy  # arrays.cross's formulas
        ny = uz * vx - ux * vz
        nz = ux * vy - uy * vx
        norm = nx * nx + ny * ny
        norm += nz * nz
        np.sqrt(norm, out=norm)
        with np.errstate(invalid="ignore", divide="ignore"):
            tx, ty, tz = nx / norm, ny / norm, nz / norm
        off = (ax + bx + cx) / 3 * tx
        off += (ay + by + cy) / 3 * ty
        off += (az + bz + cz) / 3 * tz
        return np.stack((tx, ty, tz), axis=1), off, norm

    return blockwise(len(tri), rows)


def _corner_planes(C: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`_planes` of triangles given by their corners ``C`` (F, 3, 3)."""
    cr = cross(C[:, 1] - C[:, 0], C[:, 2] - C[:, 0])
    norm = np.sqrt(dot(cr, cr))  # = np.linalg.norm(cr, axis=1), bit for bit
    with np.errstate(invalid="ignore", divide="ignore"):
        tn = cr / norm[:, None]
    off = dot((C[:, 0] + C[:, 1] + C[:, 2]) / 3, tn)  # = C.mean(axis=1), bit for bit
    return tn, off, norm


def corner_levels(P: np.ndarray, tri: np.ndarray, normals: np.ndarray,
                  face: np.ndarray | None = None) -> np.ndarray:
    """(F, 3) the heights of the corners of the triangles ``tri`` through ``P`` along
    ``normals`` (F, 3), one normal per triangle, or along ``normals[face]`` (``face``:
    (F,) a row of ``normals`` per triangle, gathered block by block): block by block."""
    Q = _columns(P)

    def rows(r: slice) -> tuple[np.ndarray]:
        return (_dot_rows(Q, tri[r], normals[r] if face is None
                          else normals.take(face[r], axis=0)),)

    return blockwise(len(tri), rows)[0]


def _beyond(P: np.ndarray, tri: np.ndarray, tn: np.ndarray, off: np.ndarray,
            twin: np.ndarray) -> np.ndarray:
    """(3F,) per half-edge, the height of the far corner of the triangle across it over
    this triangle's plane (≤ 0 to rounding error where the edge is convex)."""
    far = np.empty_like(tri)  # the corner of each half-edge's triangle across it, by
    far[:, 0] = tri[:, 2]  # column copies (a fancy gather of the columns costs 3x)
    far[:, 1:] = tri[:, :2]
    far = far.ravel()
    Q = _columns(P)

    def rows(r: slice) -> tuple[np.ndarray]:
        corners = np.take(far, twin[3 * r.start:3 * r.stop]).reshape(-1, 3)
        out = _dot_rows(Q, corners, tn[r])
        out -= off[r][:, None]
        return (out,)

    beyond, = blockwise(len(tri), rows)
    return beyond.ravel()


def _finish(P: np.ndarray, tri: np.ndarray, tn: np.ndarray, off: np.ndarray,
            area: np.ndarray, ties: np.ndarray | None = None) -> HullMesh | None:
    """The triangles in an order of their own geometry (by normal, then as given or by
    ``ties``: :func:`_normal_order`), not the hull library's — so faces, and poses of
    equal probability, come out in the same order from either library — with their
    twins and the heights across them; None when not closed."""
    order = _normal_order(tn, ties)
    tri, tn, off, area = (np.take(a, order, axis=0) for a in (tri, tn, off, area))
    found = twins_and_ends(tri, len(P))
    if found is None:
        return None
    beyond = _beyond(P, tri, tn, off, found[0])
    return HullMesh(P, tri, tn, off, found[0], area, beyond, *found[1:])


SAMPLE_TRIANGLES = 16  # triangles whose planes :func:`may_be_own_hull` tries
SAMPLE_POINTS = 4096  # points it tries against them
SAMPLE_PAIRS = 256  # pairs of consecutive triangles it tries against each other


def sample_triangles(tri: np.ndarray) -> np.ndarray:
    """The rows of ``tri`` (triangles as indices or as corners) that :func:`may_be_own_hull`
    tries: :data:`SAMPLE_TRIANGLES` spread evenly over the mesh, then
    :data:`SAMPLE_PAIRS` pairs of consecutive rows (``2 · SAMPLE_PAIRS`` rows), spread
    evenly too: a mesh's consecutive triangles mostly lie near each other."""
    m = len(tri)
    if m == 0:
        return tri[:0]
    first = (np.arange(SAMPLE_PAIRS) * max(m - 1, 0)) // SAMPLE_PAIRS
    pairs = np.stack((first, np.minimum(first + 1, max(m - 1, 0))), axis=1).ravel()
    return np.concatenate((tri[:: max(1, m // SAMPLE_TRIANGLES)][:SAMPLE_TRIANGLES],
                           tri[pairs]))


def _pairs_below(corners: np.ndarray, tn: np.ndarray, off: np.ndarray, eps: float) -> bool:
    """Whether the corners of each triangle ``corners[2i]``, ``corners[2i + 1]`` (k, 3, 3)
    lie at most ``eps`` above the other's plane (``tn``, ``off``: their planes), as on a
    convex surface every point lies under every face's plane."""
    above_a = dot(corners[1::2], tn[0::2, None, :]) - off[0::2, None]
    above_b = dot(corners[0::2], tn[1::2, None, :]) - off[1::2, None]
    with np.errstate(invalid="ignore"):
        return bool(np.all(above_a <= eps) and np.all(above_b <= eps))


def may_be_own_hull(P: np.ndarray, corners: np.ndarray, eps: float) -> bool:
    """A quick necessary condition for :func:`own_hull`: the triangles with ``corners``
    (:func:`sample_triangles` of the mesh, (k, 3, 3)) have the origin strictly inside
    their planes, no point of ``P`` (:data:`SAMPLE_POINTS` of them, spread evenly) lies
    more than ``eps`` outside the first :data:`SAMPLE_TRIANGLES`' planes, and the
    sampled pairs of consecutive triangles lie under each other's planes
    (:func:`_pairs_below`). A mesh that is not convex almost always fails it, in about a
    millisecond (the whole certificate takes tens on 100k triangles, more than the hull
    of such a mesh); a tessellated convex surface whose quads are split along concave diagonals (a
    lat-long egg) fails the pairs: their neighbours rise over their planes.
    """
    corners = np.asarray(corners, dtype=np.float64)
    tn, off, _ = _corner_planes(corners)
    spread = max(len(corners) - 2 * SAMPLE_PAIRS, 0)
    Q = P[:: max(1, len(P) // SAMPLE_POINTS)]
    with np.errstate(invalid="ignore"):
        return bool(np.all(off > eps) and np.all((Q @ tn[:spread].T).max(axis=0)
                                                 - off[:spread] <= eps)
                    and _pairs_below(corners[spread:], tn[spread:], off[spread:], eps))


def own_hull(P: np.ndarray, tri: np.ndarray, eps: float) -> HullMesh | None:
    """The closed surface ``tri`` (m, 3) through the points ``P`` (n, 3), relative to
    the centre of mass, as its own convex hull, when checks that prove it bounds a
    convex body with the centre strictly inside hold; otherwise None (then the hull of
    the points is computed). Every point must be a corner of a triangle (a point off
    the surface could lie outside it). Returns what :func:`hull_mesh` would for the
    hull of ``P``: triangles ordered by normal, outward, with their twins.

    The proof (``tri`` wound outward, the centre of mass at the origin); the planes and
    solid angles are measured in one pass, the twins only for a mesh that passes (1)
    and (4), so a mesh that is not convex costs little:

    1. *The origin strictly inside every triangle's plane*: every plane offset is above
       ``eps`` (a degenerate triangle, with no plane, fails). Each triangle then
       subtends a positive solid angle from the origin: the central projection onto
       the unit sphere keeps the orientation everywhere.
    2. *A closed 2-manifold*: every directed half-edge has exactly one reversed twin.
    3. *Every edge convex* to rounding error: the far corner of the triangle across
       each half-edge lies at most ``eps`` above this triangle's plane.
    4. *The solid angles add up to 4π* (:data:`SOLID_ANGLE_CLOSURE`): the projection
       of the closed surface has degree 1. As it keeps orientation, each point of the
       sphere has as many preimages as the degree counts (a vertex whose star wrapped
       around its ray k times would give nearby points k), so every ray from the
       origin meets the surface once: it is embedded and bounds a solid star-shaped
       about the origin.

    That solid is locally convex everywhere: inside a triangle, along an edge (3), and
    at a vertex, whose star is a simple fan (4) turning the same way at each edge (3),
    so its cone is convex. A closed connected locally convex set is convex
    (Tietze–Nakajima): the solid is the hull of the vertices and the triangles are
    the hull's. A mesh concave by less than ``eps`` (round-off, 1e-12 of the size)
    passes, as a hull library's answer is checked to the same ``eps``. Split or
    fanned flat faces (a cylinder's cap) are fine: exactly coplanar triangles become
    one face in :func:`~.hull.build_hull3` whichever way they are cut.

    >>> cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    >>> quads = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4],
    ...          [1, 5, 7, 3]]
    >>> tri = np.array([t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))])
    >>> len(own_hull(cube, tri, 1e-12).tri)
    12
    >>> own_hull(cube + [0, 0, 1.5], tri, 1e-12) is None  # the centre outside
    True
    """
    P = np.asarray(P, dtype=np.float64)
    tri = np.asarray(tri, dtype=np.int64)
    n, m = len(P), len(tri)
    if (P.ndim != 2 or P.shape[1] != 3 or tri.ndim != 2 or tri.shape[1] != 3 or m < 4
            or tri.min() < 0 or tri.max() >= n):
        return None  # not triangles through the points
    if not may_be_own_hull(P, np.take(P, sample_triangles(tri), axis=0), eps):
        return None  # not convex, found cheaply
    if np.count_nonzero(np.bincount(tri.ravel(), minlength=n)) != n:
        return None  # a point off the surface
    tn, off, norm, omega = _planes(P, tri, solid_angles=True)
    with np.errstate(invalid="ignore"):
        if not np.all(off > eps):  # NaN (a degenerate triangle) fails too
            return None  # (1)
    if not (np.all(omega > 0)
            and abs(float(omega.sum()) - 4 * math.pi) <= SOLID_ANGLE_CLOSURE * 4 * math.pi):
        return None  # (4) wound about the centre more than once, or not at all
    found = _finish(P, tri, tn, off, 0.5 * norm)  # its twins: None if not closed (2)
    if found is None or not float(found.beyond.max()) <= eps:
        return None  # (2), (3)
    return found


def _manifold_hull(X: np.ndarray, eps: float) -> HullMesh | None:
    """manifold3d's hull, or None when its answer fails the checks (then qhull decides)."""
    import manifold3d

    mesh = manifold3d.Manifold.hull_points(np.ascontiguousarray(X, dtype=np.float64)).to_mesh64()
    P = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    tri = _rotated(np.asarray(mesh.tri_verts, dtype=np.int64).reshape(-1, 3))
    ties = _point_keys(tri, len(P))  # the order of the points, settled with the normals'
    if ties is None:
        tri = _canonical(tri)  # more points than the keys hold: sorted by them first
    if len(tri) < 4 or len(P) < 4:
        return None
    tn, off, norm = _planes(P, tri)
    if not np.all(np.isfinite(tn)):
        return None  # a degenerate triangle has no plane
    found = _finish(P, tri, tn, off, 0.5 * norm, ties)
    if found is None:
        return None
    # summed in the triangles' own order (the library's varies from run to run)
    if not float(np.dot(found.offsets, found.area)) / 3 > eps * found.area.sum():
        return None  # no volume: flat points make a two-sided polygon, not a solid
    # every edge convex: the far corner of the triangle across it lies under this one's plane
    if np.max(found.beyond) > eps:
        return None
    # and no fold: on points of a grid manifold3d can leave a flat fin, two coplanar
    # triangles facing opposite ways across an edge (a convex solid has no such edge)
    flat = np.flatnonzero(np.abs(found.beyond) <= eps)
    if len(flat) and np.any(dot(found.normals[flat // 3],
                                found.normals[found.twins[flat] // 3]) < 0):
        return None
    if not _holds_input(X, found, eps, len(flat) > 0):
        return None  # a point left outside: quickhull went wrong on degenerate input
    return found


def _holds_input(X: np.ndarray, found: HullMesh, eps: float, flat: bool = False) -> bool:
    """Whether manifold3d's hull ``found`` is taken as the hull of ``X``: when it holds
    every point to within :data:`~plumbob.tolerances.HULL_LEFT_OUT` of the size.

    Its quickhull has returned closed polytopes, every edge convex, that leave points
    far out (a volume of 51.25 for qhull's 53.5625) on points of a grid: exactly
    coplanar and collinear points. :func:`.holds.holds` proves or refutes it — always
    for up to :data:`~.holds.EXHAUSTIVE` points × triangles, and on larger inputs whose
    hull shows exact coplanarity or collinearity (:func:`.holds.degenerate`) when few
    points are left to locate (a 200k-triangle egg: about 850 points, 20 ms of CPU
    beside a 300 ms hull). Where it does not decide — larger inputs without such marks, or
    walks that do not settle (a box united with a tilted cylinder: tens of thousands
    of points on the cylinder's straight sides, walks circling its flat caps) — the
    hull is taken on an observation, not a proof: no point left out in 4 000 random
    inputs without exact degeneracy, every miss seen on grid points
    (``docs/stability.md``, *Hull check*). qhull for such a box with cylinder at 200k
    triangles would add 1.4 s to a 0.5 s ``plumbob poses``. ``flat``: some edge is
    known flat (within ``eps``), the first of :func:`.holds.degenerate`'s marks."""
    if len(X) * len(found.tri) > EXHAUSTIVE and not (flat or degenerate(
            found.area, found.beyond, found.points, eps)):
        return True  # the observation
    proved = holds(X, found.points, found.tri, found.normals, found.offsets, found.twins,
                   found.area, HULL_LEFT_OUT * size_of(found.points))
    return proved is not False  # None: not decided, taken on the observation


def _qhull(X: np.ndarray) -> HullMesh:
    """scipy's qhull."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(X)
    except QhullError as exc:
        raise GeometryError("the body is flat or degenerate: its points span no volume, so "
                            "it has no resting poses as a solid") from exc
    tri = hull.simplices.astype(np.int64).copy()
    eq = hull.equations
    scale = np.linalg.norm(eq[:, :3], axis=1)
    tn = eq[:, :3] / scale[:, None]
    off = -eq[:, 3] / scale
    flip = dot(cross(X[tri[:, 1]] - X[tri[:, 0]], X[tri[:, 2]] - X[tri[:, 0]]), tn) < 0
    tri[flip] = tri[flip][:, [0, 2, 1]]
    C = np.take(X, tri, axis=0)
    cr = cross(C[:, 1] - C[:, 0], C[:, 2] - C[:, 0])
    found = _finish(X, tri, tn, off, 0.5 * np.sqrt(dot(cr, cr)))
    if found is None:
        raise GeometryError("the convex hull is not a closed surface (qhull failure)")
    return found


def hull_mesh(X: np.ndarray, eps: float, surface: np.ndarray | None = None) -> HullMesh:
    """:func:`hull_triangles` with what its checks measured (a :class:`HullMesh`)."""
    if surface is not None:
        found = own_hull(X, surface, eps)
        if found is not None:
            return found
    found = _manifold_hull(X, eps)
    return found if found is not None else _qhull(X)


def hull_triangles(X: np.ndarray, eps: float, surface: np.ndarray | None = None
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The convex hull of ``X`` (n, 3) as triangles.

    ``surface`` (m, 3), optional: triangles of a closed, outward surface through the
    points (indices into ``X``, every point used), ``X`` relative to a point strictly
    inside. When :func:`own_hull` proves it bounds a convex body (a mesh
    that is its own hull), they are the hull and no hull is computed; otherwise the
    hull of the points is, as without it.

    Returns ``(P, tri, normals, offsets, twins)``: points (m, 3) that ``tri`` (F, 3)
    indexes, wound counter-clockwise seen from outside, each triangle's outward unit
    normal and plane offset (n·x = offset), and for each half-edge ``3 t + k`` (from
    ``tri[t, k]`` to ``tri[t, (k + 1) % 3]``) its reversed twin. ``eps`` (m) is the
    rounding error within which an edge may look concave. The triangles come in an
    order of their own geometry (by normal), whichever library made them.

    Raises GeometryError when the points span no volume.

    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> P, tri, normals, offsets, twins = hull_triangles(cube, 1e-12)
    >>> len(tri), sorted(set(np.round(offsets, 12).tolist()))
    (12, [0.0, 1.0])
    """
    found = hull_mesh(X, eps, surface)
    return found.points, found.tri, found.normals, found.offsets, found.twins
