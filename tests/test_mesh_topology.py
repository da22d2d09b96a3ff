"""Mesh topology: vertex welding, connected components, winding, shells, boundary."""

import os
import sys

import numpy as np
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
