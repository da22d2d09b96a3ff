"""The fast paths of the pose hull pipeline give the answers of the plain ones they replace:
the triangle order by integer ranks is ``np.lexsort`` of the rounded normals, twins by one
sort of undirected keys are twins by search (closed or not), the weld's one-sort unique is
``np.unique``'s, and ``build_hull3``'s faces and edges are those of a plain construction."""

from __future__ import annotations

import numpy as np
from hypothesis import example, given, settings
from hypothesis import strategies as st

from plumbob.arrays import cross, dot, expand, lex_order, row_max, row_min, stable_order, unit
from plumbob.mesh.weld import merge_vertices, unique_first
from plumbob.stability.poses.convex import (
    _normal_order,
    _twins_by_search,
    half_edge_twins,
    hull_mesh,
)
from plumbob.stability.poses.hull import build_hull3
from plumbob.stability.poses.rolling import arc_sides, edge_geometry


def _unit_rows(rng: np.random.Generator, n: int, quantum: float) -> np.ndarray:
    """Unit vectors, many repeated and many sharing components to 1e-9 (ties)."""
    v = rng.normal(size=(n, 3))
    if quantum:
        v = np.round(v / quantum) * quantum
    v[rng.random(n) < 0.3] = [0.0, 0.0, 1.0]
    v[rng.random(n) < 0.1] = [0.0, 0.0, -1.0]
    v[rng.random(n) < 0.1, :2] = 0.0  # x and y equal, z of either sign
    v[~np.any(v != 0, axis=1)] = [1.0, 0.0, 0.0]
    v /= np.linalg.norm(v, axis=1)[:, None]
    v[rng.random(n) < 0.05] *= -1.0  # exact negatives, signed zeros
    return v


@given(st.integers(0, 2**32 - 1), st.integers(1, 400), st.sampled_from([0.0, 0.5, 1e-9]))
def test_normal_order_is_the_lexsort_of_rounded_normals(seed, n, quantum):
    tn = _unit_rows(np.random.default_rng(seed), n, quantum)
    key = np.round(tn, 9)
    want = np.lexsort((-key[:, 2], -key[:, 1], -key[:, 0]))
    assert np.array_equal(_normal_order(tn), want)


@given(st.integers(0, 2**32 - 1), st.integers(1, 400), st.sampled_from([0.0, 0.5, 1e-9]))
def test_normal_order_with_ties_is_the_lexsort_of_rounded_normals_then_ties(seed, n, quantum):
    """Equal rounded normals in ascending order of ``ties`` (a hull's triangles by their
    points): one sort of x and y packed, the ties settled apart."""
    rng = np.random.default_rng(seed)
    tn = _unit_rows(rng, n, quantum)
    ties = rng.permutation(n).astype(np.int64) * 3 + 1
    key = np.round(tn, 9)
    want = np.lexsort((ties, -key[:, 2], -key[:, 1], -key[:, 0]))
    assert np.array_equal(_normal_order(tn, ties), want)


@given(st.integers(0, 2**32 - 1), st.integers(4, 60))
def test_manifold_hull_order_is_by_normal_then_canonical(seed, n):
    """The hull's triangles as sorting them by their points first (:func:`_canonical`),
    then stably by normal, would leave them: the points' own order whatever order the
    library gave, without the first sort."""
    import manifold3d

    from plumbob.stability.poses.convex import _canonical, _planes, _rotated

    X = np.random.default_rng(seed).normal(size=(n, 3))
    X[: n // 2, 2] = 0.0  # a flat facet: many equal normals
    hm = hull_mesh(X - X.mean(axis=0), 1e-12)
    mesh = manifold3d.Manifold.hull_points(X - X.mean(axis=0)).to_mesh64()
    tri = _canonical(np.asarray(mesh.tri_verts, dtype=np.int64).reshape(-1, 3))
    tn = _planes(np.asarray(mesh.vert_properties)[:, :3], tri)[0]
    assert np.array_equal(hm.tri, tri[_normal_order(tn)])
    assert np.array_equal(_rotated(tri), tri)


def _closed_surface(rng: np.random.Generator, n: int) -> np.ndarray:
    """A random convex hull's triangles (a closed 2-manifold, wound outward), vertices
    renumbered."""
    from scipy.spatial import ConvexHull

    X = rng.normal(size=(n, 3))
    hull = ConvexHull(X)
    tri = hull.simplices.copy()
    a, b, c = (X[tri[:, k]] for k in range(3))
    inward = np.einsum("ij,ij->i", np.cross(b - a, c - a), hull.equations[:, :3]) < 0
    tri[inward] = tri[inward][:, ::-1]
    perm = rng.permutation(len(X))
    return perm[tri][rng.permutation(len(tri))]


@given(st.integers(0, 2**32 - 1), st.integers(4, 60))
def test_twins_by_undirected_keys_are_twins_by_search(seed, n):
    rng = np.random.default_rng(seed)
    tri = _closed_surface(rng, n)
    twin = half_edge_twins(tri, n)
    assert twin is not None and np.array_equal(twin, _twins_by_search(tri, n))
    frm, to = tri.ravel(), tri[:, [1, 2, 0]].ravel()
    assert np.array_equal(frm[twin], to) and np.array_equal(twin[twin], np.arange(len(twin)))


@given(st.integers(0, 2**32 - 1), st.integers(4, 40),
       st.sampled_from(["drop", "flip", "duplicate", "loop", "random"]))
def test_twins_of_broken_surfaces_agree_with_search(seed, n, how):
    """Whatever the triangles, the fast twins are the searched ones (None alike)."""
    rng = np.random.default_rng(seed)
    tri = _closed_surface(rng, n)
    k = int(rng.integers(len(tri)))
    if how == "drop":
        tri = np.delete(tri, k, axis=0)
    elif how == "flip":
        tri[k] = tri[k, ::-1]
    elif how == "duplicate":
        tri = np.concatenate((tri, tri[k:k + 1]))
    elif how == "loop":
        tri[k, 1] = tri[k, 0]
    else:
        tri = rng.integers(0, 5, size=(int(rng.integers(1, 8)), 3))
        n = 5
    fast, slow = half_edge_twins(tri, n), _twins_by_search(tri, n)
    assert (fast is None) == (slow is None)
    if fast is not None:
        assert np.array_equal(fast, slow)


@given(st.integers(0, 2**32 - 1), st.integers(0, 500), st.integers(1, 50))
def test_unique_first_is_numpys_unique(seed, n, spread):
    rng = np.random.default_rng(seed)
    keys = rng.integers(0, 2**64 - 1, spread, dtype=np.uint64, endpoint=True)[
        rng.integers(0, spread, n)]
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    mine = unique_first(keys)
    assert np.array_equal(mine[0], first) and np.array_equal(mine[1], inverse.reshape(-1))


def test_merge_vertices_matches_the_exact_merge():
    rng = np.random.default_rng(7)
    pts = rng.normal(size=(300, 3))[rng.integers(0, 300, 2000)]
    pts[rng.random(len(pts)) < 0.1] *= -0.0  # signed zeros... and plain sign flips
    vertices, index = merge_vertices(pts)
    assert np.array_equal(vertices[index], pts + 0.0)
    assert len(vertices) == len(np.unique(pts + 0.0, axis=0))


def _plain_faces(X: np.ndarray, eps: float) -> tuple[np.ndarray, np.ndarray]:
    """Faces and heights the slow way: triangles joined across edges whose far corners lie
    within eps of both planes (and slivers to the triangle across their longest edge),
    areas summed, the largest corner height per face."""
    from plumbob.arrays import connected_components

    hm = hull_mesh(X, eps)
    P, tri, tn, off, twin = hm.points, hm.tri, hm.normals, hm.offsets, hm.twins
    i = np.repeat(np.arange(len(tri)), 3)
    j = twin // 3
    dij = np.abs(np.einsum("kvc,kc->kv", P[tri[j]], tn[i]) - off[i][:, None]).max(axis=1)
    dji = np.abs(np.einsum("kvc,kc->kv", P[tri[i]], tn[j]) - off[j][:, None]).max(axis=1)
    same = (dij <= eps) & (dji <= eps) & (np.einsum("ij,ij->i", tn[i], tn[j]) > 0)
    i, j = i[same], j[same]
    # a sliver (its corners on one line, within eps) has no plane: it is one face with
    # the triangle across its longest edge
    slivers = []
    for t, corners in enumerate(P[tri]):
        lengths = [np.linalg.norm(corners[(k + 1) % 3] - corners[k]) for k in range(3)]
        k = int(np.argmax(lengths))
        if 2 * hm.area[t] <= eps * lengths[k]:
            slivers.append((t, twin[3 * t + k] // 3))
    if slivers:
        i = np.concatenate((i, [a for a, _ in slivers]))
        j = np.concatenate((j, [b for _, b in slivers]))
    comp = connected_components(len(tri), i, j)
    return comp, np.bincount(comp, weights=hm.area)


@given(st.integers(0, 2**32 - 1), st.booleans())
@example(151370, True)  # its hull holds a sliver: three grid points on one line
@example(28872, True)  # manifold3d's hull holds a flat fin (a fold): qhull's is taken
@example(500044, True)  # manifold3d's hull leaves grid points 0.87 out (qhull decides)
@example(571, True)  # the same, another way
@example(1329, True)  # the same, a third way
def test_build_hull3_faces_are_the_plain_ones(seed, grid):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(int(rng.integers(8, 200)), 3))
    if grid:  # many coplanar triangles: merged faces with corners on their edges
        X = np.round(X * 2) / 2
    X = X - X.mean(axis=0)
    eps = 1e-12 * float(np.ptp(X))
    h = build_hull3(X, eps)
    comp, areas = _plain_faces(X, eps)
    assert np.allclose(np.sort(h.areas), np.sort(areas), rtol=1e-12, atol=0)
    # edges: sorted by (start, end), twins reversed, faces on both sides, and every
    # face's height that of its corners
    assert np.all((np.diff(h.ea) > 0) | ((np.diff(h.ea) == 0) & (np.diff(h.eb) > 0)))
    assert np.array_equal(h.ea[h.twin], h.eb) and np.array_equal(h.eb[h.twin], h.ea)
    assert np.array_equal(h.ef[h.twin], h.eg) and np.all(h.ef != h.eg)
    assert np.array_equal(h.und, np.minimum(np.arange(len(h.ea)), h.twin))
    top = np.full(len(h.normals), -np.inf)
    np.maximum.at(top, h.ef, dot(h.X[h.ea], h.normals[h.ef]))
    assert np.array_equal(top, h.heights)
    assert np.array_equal(np.bincount(h.ea, minlength=len(h.X)), h.degree)
    # every input point under every face's plane
    assert (X @ h.normals.T - h.heights).max() <= 10 * eps


@given(st.integers(0, 2**32 - 1), st.integers(0, 50), st.integers(1, 5))
def test_row_max_and_min_are_numpys(seed, n, k):
    a = np.random.default_rng(seed).normal(size=(n, k))
    a[a > 1.5] = np.nan  # NaN propagates alike
    assert np.array_equal(row_max(a), a.max(axis=1), equal_nan=True)
    assert np.array_equal(row_min(a), a.min(axis=1), equal_nan=True)


@given(st.integers(0, 2**32 - 1), st.integers(0, 300),
       st.sampled_from([1, 3, 1000, 2**31, 2**62]))
def test_stable_order_is_a_stable_argsort(seed, n, spread):
    keys = np.random.default_rng(seed).integers(-spread, spread, n, dtype=np.int64)
    assert np.array_equal(stable_order(keys), np.argsort(keys, kind="stable"))


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2048, 6000), st.sampled_from([1, 2, 3]),
       st.integers(0, 9))
def test_stable_order_partitions_a_small_top_digit(seed, n, words, top):
    """Keys whose top 16-bit digit takes a few values (sorted by a partition per value,
    from RADIX_MIN keys) or more (a counting sort): numpy's stable argsort, ties kept in
    order; the keys shifted off zero too."""
    rng = np.random.default_rng(seed)
    span = (top << (16 * words)) + int(rng.integers(0, 1 << (16 * words)))
    keys = rng.integers(0, span, n, dtype=np.int64, endpoint=True)
    keys[rng.integers(0, n, n // 4)] = span  # the top value, and many ties
    for shifted in (keys, keys - 12345):
        assert np.array_equal(stable_order(shifted), np.argsort(shifted, kind="stable"))


@given(st.integers(0, 2**32 - 1), st.integers(0, 200), st.integers(1, 4))
def test_lex_order_is_lexsort(seed, n, k):
    rng = np.random.default_rng(seed)
    keys = [rng.integers(-3, 3, n) for _ in range(k)]
    assert np.array_equal(lex_order(keys), np.lexsort(keys))


@given(st.integers(0, 2**32 - 1), st.integers(0, 400), st.sampled_from([0, 20, 40, 60]))
def test_unique_first_with_keys_alike_in_their_top_bits(seed, n, low):
    """Keys differing only in their low bits (below the packed index) still come out in
    full order."""
    rng = np.random.default_rng(seed)
    keys = (rng.integers(0, 4, n).astype(np.uint64) << np.uint64(low)) | rng.integers(
        0, 8, n).astype(np.uint64)
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    mine = unique_first(keys)
    assert np.array_equal(mine[0], first) and np.array_equal(mine[1], inverse.reshape(-1))


@given(st.integers(0, 2**32 - 1), st.integers(0, 30), st.integers(1, 4),
       st.sampled_from([1e-200, 1e-5, 1.0, 1e150]))
def test_dot_and_unit_are_the_plain_formulas(seed, n, dim, scale):
    """``dot`` adds the products in component order and ``unit`` divides by
    ``np.linalg.norm``: the same numbers to the bit, whatever the magnitudes."""
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, dim)) * scale
    b = rng.normal(size=(n, dim))
    a[rng.random(n) < 0.2] = 0.0  # zero rows stay zero
    plain = a[:, 0] * b[:, 0]
    for k in range(1, dim):
        plain = plain + a[:, k] * b[:, k]
    with np.errstate(over="ignore"):
        assert np.array_equal(dot(a, b), plain)
        norm = np.linalg.norm(a, axis=-1, keepdims=True)
        assert np.array_equal(unit(a), a / np.where(norm > 0, norm, 1.0))


@given(st.lists(st.tuples(st.integers(0, 4), st.integers(0, 50)), max_size=20))
def test_expand_lists_every_row_range(rows):
    counts = np.array([c for c, _ in rows], dtype=np.int64)
    starts = np.array([s for _, s in rows], dtype=np.int64)
    row, item = expand(counts, starts)
    want = [(i, s + k) for i, (c, s) in enumerate(rows) for k in range(c)]
    assert list(zip(row.tolist(), item.tolist())) == want


@given(st.integers(0, 2**32 - 1), st.booleans())
@example(39368, True)  # a grid hull with an edge twice: its twin is not its mirror (CI found it)
def test_edge_geometry_is_the_plain_formulas(seed, grid):
    """Every field of the edge geometry as the plain per-edge formulas give it, bit for
    bit (computed block by block, the saddle rows' directions in a pass of their own)."""
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(int(rng.integers(8, 150)), 3))
    if grid:
        X = np.round(X * 2) / 2
    X = X - X.mean(axis=0) - 0.01
    h = build_hull3(X, 1e-12 * float(np.ptp(X)))
    tol = float(rng.uniform(0.0, 0.3))  # a roll's tolerance, m: as wide as a third of an edge
    e = edge_geometry(h, tol)
    A = h.X[h.ea]
    D = h.X[h.eb] - A
    L2 = dot(D, D)
    t = -dot(A, D) / L2
    pole = D / np.sqrt(L2)[:, None]
    p = A + t[:, None] * D
    height = np.linalg.norm(p, axis=1)
    s = p / height[:, None]
    after_f, before_g = cross(pole, h.normals[h.ef]), cross(h.normals[h.eg], pole)
    n = h.normals[h.ef]
    foot = h.heights[h.ef][:, None] * n
    L = np.sqrt(L2)
    inset = dot(cross(D, foot - A), n) / L
    tau = np.clip(dot(foot - A, D) / L2, 0.0, 1.0)
    tip = np.linalg.norm(A + tau[:, None] * D - foot, axis=1)
    saddle = (t > 0) & (t < 1) & (dot(s, after_f) >= 0) & (dot(s, before_g) >= 0)
    rows = np.flatnonzero(saddle)
    mine_after, mine_before = arc_sides(h, e.pole, np.arange(len(h.ea)))
    for mine, plain in [(e.t, t), (e.pole, pole), (e.saddle, saddle), (mine_after, after_f),
                        (mine_before, before_g), (e.inset, inset), (e.tip_distance, tip),
                        (e.tip_inside, (tau * L > tol) & (tau * L < L - tol)),
                        (e.tip_at_a, tau * L <= tol), (e.saddles, rows), (e.spoint, s[rows]),
                        (e.sheight, height[rows]), (e.toward_f, cross(s, pole)[rows])]:
        assert np.array_equal(mine, plain)


@given(st.integers(0, 2**32 - 1), st.booleans())
def test_the_hull_is_the_same_to_the_bit_whatever_order_manifold3d_returns(seed, grid):
    """manifold3d's parallel quickhull returns the same triangles in another order, each
    starting at another corner, from run to run on large inputs: the hull plumbob builds
    from them (and so every pose) is the same to the bit however they come."""
    import types

    import manifold3d

    rng = np.random.default_rng(seed)
    X = rng.normal(size=(int(rng.integers(8, 200)), 3))
    if grid:
        X = np.round(X * 2) / 2  # coplanar triangles: ties in the order by normal
    X = X - X.mean(axis=0) - 0.01
    eps = 1e-12 * float(np.ptp(X))
    mesh = manifold3d.Manifold.hull_points(np.ascontiguousarray(X)).to_mesh64()
    P = np.asarray(mesh.vert_properties, dtype=np.float64)[:, :3]
    tri = np.asarray(mesh.tri_verts, dtype=np.int64).reshape(-1, 3)

    def shuffled_hull(points):
        rows = rng.permutation(len(tri))
        turn = rng.integers(0, 3, len(tri))
        again = np.take_along_axis(tri[rows], (turn[rows, None] + np.arange(3)) % 3, axis=1)
        return types.SimpleNamespace(to_mesh64=lambda: types.SimpleNamespace(
            vert_properties=P, tri_verts=again.astype(np.uint32)))

    want = build_hull3(X, eps)
    original = manifold3d.Manifold.hull_points
    manifold3d.Manifold.hull_points = staticmethod(shuffled_hull)
    try:
        got = build_hull3(X, eps)
    finally:
        manifold3d.Manifold.hull_points = original
    for mine, plain in zip(got, want):
        assert np.array_equal(mine, plain)


@given(st.integers(0, 2**32 - 1), st.integers(0, 60), st.integers(1, 6))
def test_rotated_starts_each_triangle_at_its_first_least_point(seed, n, spread):
    """``_rotated`` is the rotation ``np.argmin`` picks (ties too: the first least)."""
    from plumbob.stability.poses.convex import _rotated

    tri = np.random.default_rng(seed).integers(0, spread, size=(n, 3))
    start = np.argmin(tri, axis=1) if n else np.zeros(0, dtype=int)
    want = np.take_along_axis(tri, (start[:, None] + np.arange(3)) % 3, axis=1)
    assert np.array_equal(_rotated(tri), want)


@given(st.integers(0, 2**32 - 1), st.integers(0, 300), st.floats(1e-3, 1e6))
def test_planes_levels_and_heights_across_are_the_row_formulas(seed, m, scale):
    """The planes, the corners' levels and the heights across each half-edge, computed
    on coordinate columns, are the row formulas' numbers to the bit (a triangle with a
    repeated corner too: NaN alike)."""
    from plumbob.stability.poses.convex import _beyond, _corner_planes, _planes, corner_levels

    rng = np.random.default_rng(seed)
    P = rng.normal(size=(40, 3)) * scale + rng.normal(size=3) * scale * 10
    tri = rng.integers(0, 40, size=(m, 3))
    C = P[tri]
    with np.errstate(invalid="ignore", divide="ignore"):
        want = _corner_planes(C)
    for mine, plain in zip(_planes(P, tri), want):
        np.testing.assert_array_equal(mine, plain)
    normals = rng.normal(size=(m, 3))
    np.testing.assert_array_equal(corner_levels(P, tri, normals),
                                  dot(C, normals[:, None, :]))
    twin = rng.integers(0, 3 * m, size=3 * m) if m else np.zeros(0, dtype=int)
    offsets = rng.normal(size=m)
    far = P[tri[:, [2, 0, 1]].ravel()[twin]].reshape(-1, 3, 3)
    np.testing.assert_array_equal(_beyond(P, tri, normals, offsets, twin),
                                  (dot(far, normals[:, None, :]) - offsets[:, None]).ravel())
