"""A hull library's hull is used only when it holds every input point
(:mod:`plumbob.stability.poses.holds`): manifold3d's quickhull leaves grid points out."""

from __future__ import annotations

import manifold3d
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from plumbob.arrays import dot
from plumbob.stability.poses import holds as holds_module
from plumbob.stability.poses.convex import _manifold_hull, hull_mesh
from plumbob.stability.poses.holds import _degree, _vertex_copies, degenerate, holds
from plumbob.stability.poses.hull import build_hull3


def _grid_points(seed: int) -> np.ndarray:
    """The recipe of ``test_build_hull3_faces_are_the_plain_ones`` on a grid."""
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(int(rng.integers(8, 200)), 3))
    X = np.round(X * 2) / 2
    return X - X.mean(axis=0)


def test_the_grid_points_manifold3d_leaves_out_get_qhulls_hull():
    X = _grid_points(500044)
    eps = 1e-12 * float(np.ptp(X))
    wrong = manifold3d.Manifold.hull_points(X).volume()
    assert wrong == pytest.approx(51.25, rel=1e-12)  # the library's answer misses points
    assert _manifold_hull(X, eps) is None  # refused
    hm = hull_mesh(X, eps)
    assert float(np.dot(hm.offsets, hm.area)) / 3 == pytest.approx(53.5625, rel=1e-12)
    h = build_hull3(X, eps)
    assert float((X @ h.normals.T - h.heights).max()) <= 10 * eps


def _sphere_case(seed: int, n: int, near: int):
    """A hull of ``n`` points on a unit sphere (manifold3d's), and ``near`` points just
    inside it: on random triangles of it, drawn in towards the centre by 1e-6."""
    rng = np.random.default_rng(seed)
    S = rng.normal(size=(n, 3))
    S /= np.sqrt(dot(S, S))[:, None]
    hm = _manifold_hull(S, 1e-12)
    t = rng.integers(len(hm.tri), size=near)
    w = rng.dirichlet(np.ones(3), size=near)
    inside = np.einsum("kc,kcd->kd", w, hm.points[hm.tri[t]]) * (1 - 1e-6)
    return S, hm, inside


def _truth(X: np.ndarray, hm, tol: float) -> bool:
    return bool((X @ hm.normals.T - hm.offsets).max() <= tol)


@settings(max_examples=8, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans(), st.booleans())
def test_holds_is_every_point_under_every_plane(seed, out, walk):
    S, hm, near = _sphere_case(seed, 400, 3000)
    X = np.vstack((S, near))
    if out:  # one point just outside a random triangle's plane, far beyond round-off
        t = int(np.random.default_rng(seed).integers(len(hm.tri)))
        corner = hm.points[hm.tri[t]].mean(axis=0)
        X = np.vstack((X, corner + 1e-5 * hm.normals[t]))
    args = hm.points, hm.tri, hm.normals, hm.offsets, hm.twins, hm.area, 1e-7
    saved = holds_module.EXHAUSTIVE
    holds_module.EXHAUSTIVE = 0 if walk else saved  # located by walks, or compared
    try:
        assert holds(X, *args) is _truth(X, hm, 1e-7) is (not out)
    finally:
        holds_module.EXHAUSTIVE = saved


@pytest.mark.parametrize("near", [3000, 100])
@pytest.mark.parametrize("out", [False, True])
def test_holds_finds_the_points_to_locate_in_either_order(near, out):
    """The points left to walk are those outside the ball under every plane that are no
    vertex's copy, whichever test goes first: the ball where most points are not the
    hull's vertices (3,000 near its faces), the copies where most are (100). Points deep
    inside and one just outside a face: the walk must meet the outside one."""
    S, hm, inside = _sphere_case(5, 400, near)
    deep = np.random.default_rng(6).normal(size=(200, 3)) * 0.05
    X = np.vstack((S, inside, deep))
    if out:
        corner = hm.points[hm.tri[17]].mean(axis=0)
        X = np.vstack((X, corner + 1e-5 * hm.normals[17]))
    args = hm.points, hm.tri, hm.normals, hm.offsets, hm.twins, hm.area, 1e-7
    saved = holds_module.EXHAUSTIVE
    holds_module.EXHAUSTIVE = 0  # located by walks
    try:
        assert holds(X, *args) is _truth(X, hm, 1e-7) is (not out)
    finally:
        holds_module.EXHAUSTIVE = saved


def test_holds_leaves_undecided_what_it_cannot_afford():
    S, hm, near = _sphere_case(11, 400, 3000)
    args = hm.points, hm.tri, hm.normals, hm.offsets, hm.twins, hm.area, 1e-7
    saved = holds_module.EXHAUSTIVE, holds_module.WALKERS
    holds_module.EXHAUSTIVE, holds_module.WALKERS = 0, 100
    try:
        assert holds(np.vstack((S, near)), *args) is None
    finally:
        holds_module.EXHAUSTIVE, holds_module.WALKERS = saved


def test_holds_refuses_a_hull_that_leaves_out_a_vertex():
    S, hm, _ = _sphere_case(7, 300, 0)
    T = S[:-1]  # the hull of all but the last point: a point out, by up to its height
    part = _manifold_hull(T, 1e-12)
    args = part.points, part.tri, part.normals, part.offsets, part.twins, part.area, 1e-7
    assert holds(T, *args) and not holds(S, *args)


def test_degree_counts_the_windings_about_the_centre():
    _, hm, _ = _sphere_case(3, 200, 0)
    assert _degree(hm.points, hm.tri) == 1
    assert _degree(hm.points, np.vstack((hm.tri, hm.tri))) == 2  # wound twice


def test_degenerate_marks_coplanar_neighbours_and_slivers():
    cube = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    hm = hull_mesh(cube, 1e-12)  # each square face is two coplanar triangles
    assert degenerate(hm.area, hm.beyond, hm.points, 1e-12)
    _, sphere, _ = _sphere_case(5, 200, 0)
    assert not degenerate(sphere.area, sphere.beyond, sphere.points, 1e-12)


def _dense_cap(seed: int):
    """A hull of 400 points on a unit sphere and 1500 packed into a cap of about 2° at its
    pole (a tapered tip's many vertices in a small solid angle: one cube-map cell), and
    300 points just inside triangles of the cap."""
    rng = np.random.default_rng(seed)
    cap = rng.normal(size=(1500, 3)) * [0.03, 0.03, 0] + [0, 0, 1]
    S = np.vstack((rng.normal(size=(400, 3)), cap))
    S /= np.sqrt(dot(S, S))[:, None]
    hm = _manifold_hull(S, 1e-12)
    in_cap = np.flatnonzero(hm.points[hm.tri].mean(axis=1)[:, 2] > 0.999)
    t = rng.choice(in_cap, size=300)
    w = rng.dirichlet(np.ones(3), size=300)
    return S, hm, np.einsum("kc,kcd->kd", w, hm.points[hm.tri[t]]) * (1 - 1e-6)


@pytest.mark.parametrize("seed", [0, 1])
def test_walks_start_at_the_nearest_vertex_of_a_crowded_cell(seed):
    """Walks from the vertex nearest each point in direction end within 16 steps where
    walks from any vertex of the crowded cell need up to 256 (the answer is the same)."""
    S, hm, near = _dense_cap(seed)
    X = np.vstack((S, near))
    args = hm.points, hm.tri, hm.normals, hm.offsets, hm.twins, hm.area, 1e-7
    saved = holds_module.EXHAUSTIVE, holds_module.WALK_STEPS, holds_module.START_PAIRS
    holds_module.EXHAUSTIVE, holds_module.WALK_STEPS = 0, 16
    try:
        assert _truth(X, hm, 1e-7)
        assert holds(X, *args) is True
        beyond = hm.points[hm.tri[-1]].mean(axis=0) + 1e-5 * hm.normals[-1]
        assert holds(np.vstack((X, beyond)), *args) is False
        holds_module.START_PAIRS = -1  # any vertex of the cell: walks too long to decide
        assert holds(X, *args) is None
    finally:
        holds_module.EXHAUSTIVE, holds_module.WALK_STEPS, holds_module.START_PAIRS = saved


def _copies_looking_everywhere(X: np.ndarray, P: np.ndarray) -> np.ndarray:
    """The rows of X that ``_vertex_copies``' tables find when every row not yet found
    looks in every table (its own rule: only the rows that met a lost vertex's slot look
    again)."""
    found = np.zeros(len(X), dtype=bool)
    left = np.arange(len(P))
    for salt in range(4):
        if not len(left):
            break
        bits = max(4, int(len(left)).bit_length() + 2)
        table = {}
        for i in left:
            table[_slot(P[i], salt, bits)] = i  # the last write wins, as numpy's
        for r in np.flatnonzero(~found):
            j = table.get(_slot(X[r], salt, bits))
            found[r] = j is not None and bool(np.all(P[j] == X[r]))
        left = np.array([i for i in left if table[_slot(P[i], salt, bits)] != i], dtype=int)
    return found


def _slot(row: np.ndarray, salt: int, bits: int) -> int:
    """``_vertex_copies``' hash of one row, in Python integers."""
    b = [int(v) for v in np.asarray(row, dtype=np.float64).view(np.uint64)]
    m = (1 << 64) - 1
    h = (b[0] * (0x9E3779B97F4A7C15 ^ salt)) & m
    h ^= (b[1] * 0xC2B2AE3D27D4EB4F) & m
    h ^= b[2]
    h ^= h >> 29
    h = (h * 0xBF58476D1CE4E5B9) & m
    h ^= h >> 32
    return h & ((1 << bits) - 1)


@settings(max_examples=10, deadline=None)
@example(780, 677)  # a vertex lost its slot in all four tables
@given(st.integers(0, 2**32 - 1), st.integers(1, 700))
def test_vertex_copies_are_the_rows_equal_to_a_vertex(seed, n):
    """Only rows equal to a row of P are found (a signed zero equals zero; a row one ulp
    off is not a copy), and every one whose vertex found a slot in one of the four
    tables: the same as when every row looks in every table. A copy of a vertex that
    lost its slot in all four is not found (then it is located like any point)."""
    rng = np.random.default_rng(seed)
    P = np.round(rng.normal(size=(n, 3)), 2)  # rounded: rows that share coordinates
    P = P[np.unique(P, axis=0, return_index=True)[1]]
    pick = rng.integers(len(P), size=2 * n)
    X = np.vstack((P[pick], np.nextafter(P[pick[:n]], np.inf), -P[pick[:n]] * 0.0,
                   np.round(rng.normal(size=(n, 3)), 2)))
    X = X[rng.permutation(len(X))]
    rows = {tuple(p) for p in P.tolist()}
    truth = np.array([tuple(x) in rows for x in X.tolist()])
    found = _vertex_copies(X, P)
    assert not np.any(found & ~truth)
    assert len({tuple(x) for x in X[truth & ~found].tolist()}) <= 3  # of a few vertices
    assert found.tolist() == _copies_looking_everywhere(X, P).tolist()
