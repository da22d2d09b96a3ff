"""Mesh topology: vertex welding, connected components, winding, shells, boundary."""

import os
import sys

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import cube  # noqa: E402

from plumbob.mesh import connected_components, mesh_topology  # noqa: E402


@given(st.integers(1, 60), st.lists(st.tuples(st.integers(0, 59), st.integers(0, 59)),
                                    max_size=80))
def test_connected_components_match_scipy(n, edges):
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components as scipy_components

    edges = [(u % n, v % n) for u, v in edges]
    u = np.array([e[0] for e in edges], dtype=np.int64)
    v = np.array([e[1] for e in edges], dtype=np.int64)
    ours = connected_components(n, u, v)
    graph = coo_matrix((np.ones(len(u)), (u, v)), shape=(n, n))
    count, theirs = scipy_components(graph, directed=False)
    assert ours.max() + 1 == count
    # the same partition: labels correspond one to one
    pairs = set(zip(ours.tolist(), theirs.tolist()))
    assert len(pairs) == count
    # numbered in the order of each component's smallest node
    assert np.array_equal(np.unique(ours, return_index=True)[1], np.sort(
        np.unique(ours, return_index=True)[1])) and ours[0] == 0


def test_topology_of_a_cube():
    topo = mesh_topology(cube(2).astype(np.float32))
    assert len(topo.vertices) == 26  # 8 corners, 12 edge midpoints, 6 face centres
    assert topo.shells == 1 and topo.orientable
    assert len(topo.boundary) == 0 and topo.nonmanifold == 0 and not topo.flip.any()


def test_signed_zero_merges():
    tri = cube()
    tri[tri == 0] = -0.0  # the same points, negative zeros
    tri[:6][tri[:6] == 0] = 0.0
    assert len(mesh_topology(tri).vertices) == 8


def _pairs(triangles):
    """The face pairs sharing an edge, and whether they run it the same way."""
    from plumbob.mesh.topology import _pair_edges
    from plumbob.mesh.weld import merge_vertices

    vertices, index = merge_vertices(triangles.reshape(-1, 3))
    p = _pair_edges(index.reshape(-1, 3).astype(np.int64), len(vertices))
    at = p.starts[p.counts == 2]
    h1, h2 = p.order[at], p.order[at + 1]
    return p.owner[h1], p.owner[h2], p.half[h1, 0] == p.half[h2, 0]


def test_a_consistently_wound_mesh_skips_the_winding_components():
    """mesh_topology turns nothing without building the two-node graph when no shared
    edge runs the same way in both faces: what that graph's rule gives there too."""
    from plumbob.mesh.topology import _winding

    tri = np.concatenate((cube(3), cube(2) + 5.0))  # two shells
    f1, f2, same = _pairs(tri)
    assert not same.any()
    flip, orientable = _winding(len(tri), f1, f2, same)
    assert orientable and not flip.any()
    turned = tri.copy()
    turned[[3, 40]] = turned[[3, 40], ::-1]
    topo = mesh_topology(turned)
    assert topo.flip.nonzero()[0].tolist() == [3, 40] and topo.orientable


@pytest.mark.parametrize("n", [2048, 5001])
@pytest.mark.parametrize("span", [1, 2**16 - 1, 2**16, 2**32 + 7, 2**48 - 1, 2**48, 2**62,
                                  2**63 - 8])
def test_sorts_by_digits_are_stable_argsorts(n, span):
    """From RADIX_MIN keys stable_order sorts by 16-bit digits and unique_first by the top
    48 bits: the same orders as numpy's stable argsort and unique, keys alike in their
    top bits included."""
    from plumbob.arrays import RADIX_MIN, stable_order
    from plumbob.mesh.weld import unique_first

    assert n >= RADIX_MIN
    rng = np.random.default_rng(span % 1000 + n)
    keys = rng.integers(-3, span, n, dtype=np.int64)
    assert np.array_equal(stable_order(keys), np.argsort(keys, kind="stable"))
    hashes = rng.integers(0, 2**64 - 1, max(n // 7, 1), dtype=np.uint64, endpoint=True)
    for words in (hashes, (hashes >> np.uint64(20)) << np.uint64(20)):  # ties in the top bits
        words = words[rng.integers(0, len(words), n)] | rng.integers(0, 3, n).astype(np.uint64)
        _, first, inverse = np.unique(words, return_index=True, return_inverse=True)
        mine = unique_first(words)
        assert np.array_equal(mine[0], first) and np.array_equal(mine[1], inverse.reshape(-1))
