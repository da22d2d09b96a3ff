"""Mesh checks: topology, winding, shells (voids, islands, overlaps), repair, sizes, units."""

import os
import sys

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import cube  # noqa: E402

from plumbob.errors import GeometryError  # noqa: E402
from plumbob.io import validate  # noqa: E402
from plumbob.io.validate import (  # noqa: E402
    check_extent,
    check_solid,
    connected_components,
    mesh_topology,
    units_scale,
)


def notices_with(notices, text):
    return [n for n in notices if text in n]


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


@given(st.integers(0, 5000), st.integers(0, 2**32 - 1))
def test_block_bounds_match_a_plain_reduction(n, seed):
    points = np.random.default_rng(seed).normal(size=(n, 3)).astype(np.float32)
    lo, hi = validate.block_bounds(points)
    if n:
        assert np.array_equal(lo, points.min(axis=0)) and np.array_equal(hi, points.max(axis=0))
    else:
        assert np.all(lo == np.inf) and np.all(hi == -np.inf)
    if n > 1:
        points[n // 2, 1] = np.nan
        assert np.isnan(validate.block_bounds(points)[0][1])


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


def test_hidden_winding_error_is_found_on_small_meshes():
    # Top and bottom faces turned: their vector areas cancel, so the cheap test passes.
    tri = cube().copy()
    z_faces = np.isclose(tri[:, :, 2], tri[:, :1, 2]).all(axis=1)
    tri[z_faces] = tri[z_faces][:, ::-1]
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(1.0, rel=1e-15)
    assert notices_with(notices, "4 of 12 triangles were wound against their neighbours")


def test_void_is_kept_and_not_called_an_overlap():
    hollow = np.concatenate((cube(size=2.0), cube(size=1.0, offset=(0.5, 0.5, 0.5))[:, ::-1]))
    body, notices = check_solid(hollow)
    assert body.mass_properties().volume == pytest.approx(7.0, rel=1e-15)
    assert notices == ()


def test_ball_in_a_void_in_a_ball():
    tri = np.concatenate((cube(size=3.0), cube(size=2.0, offset=(0.5,) * 3)[:, ::-1],
                          cube(size=1.0, offset=(1.0,) * 3)))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(27 - 8 + 1, rel=1e-15)
    assert notices == ()


def test_hollow_cube_inside_out_is_turned_as_a_whole():
    hollow = np.concatenate((cube(size=2.0), cube(size=1.0, offset=(0.5, 0.5, 0.5))[:, ::-1]))
    body, notices = check_solid(hollow[:, ::-1])
    assert body.mass_properties().volume == pytest.approx(7.0, rel=1e-15)
    assert notices_with(notices, "inside out")


def test_one_of_two_separate_shells_inside_out():
    tri = np.concatenate((cube(), cube(offset=(3, 0, 0))[:, ::-1]))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(2.0, rel=1e-15)
    assert notices_with(notices, "1 of 2 shells pointed inward")


def test_touching_shells_are_not_an_overlap():
    tri = np.concatenate((cube(), cube(offset=(1, 0, 0))))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(2.0, rel=1e-15)
    assert not notices_with(notices, "overlap")


def test_nested_duplicate_shells_are_united():
    tri = np.concatenate((cube(size=2.0), cube(size=1.0, offset=(0.5, 0.5, 0.5))))
    body, notices = check_solid(tri)
    props = body.mass_properties()
    assert props.volume == pytest.approx(8.0, rel=1e-12)
    assert props.center_of_mass == pytest.approx([1.0, 1.0, 1.0], rel=1e-12)
    assert notices_with(notices, "2 shells overlap; united with manifold3d (volume 9 → 8 m³)")


def test_t_junctions_close_geometrically():
    # The top face is cut into three triangles at the midpoint of one of its edges; the
    # neighbouring side face keeps that edge whole.
    tri = cube()
    top = np.isclose(tri[:, :, 2], 1.0).all(axis=1)
    m = [0.5, 0.0, 1.0]
    fan = np.array([[[0, 0, 1], m, [0, 1, 1]], [m, [1, 1, 1], [0, 1, 1]],
                    [m, [1, 0, 1], [1, 1, 1]]], dtype=float)
    tri = np.concatenate((tri[~top], fan))
    body, notices = check_solid(tri)
    assert body.mass_properties().volume == pytest.approx(1.0, rel=1e-15)
    assert notices_with(notices, "edges are not shared by two triangles (T-junctions?)")


def test_mobius_strip_is_not_orientable():
    n = 12
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    centre = np.stack((np.cos(t), np.sin(t), np.zeros(n)), axis=1)
    half = 0.3 * np.stack((np.cos(t / 2) * np.cos(t), np.cos(t / 2) * np.sin(t), np.sin(t / 2)), 1)
    a, b = centre + half, centre - half
    nxt = np.roll(np.arange(n), -1)
    a1, b1 = a[nxt], b[nxt]
    a1[-1], b1[-1] = b[0], a[0]  # the half twist
    tri = np.concatenate((np.stack((a, b, a1), 1), np.stack((b, b1, a1), 1)))
    with pytest.raises(GeometryError, match="non-orientable"):
        check_solid(tri)


def test_big_meshes_take_the_cheap_path(monkeypatch):
    monkeypatch.setattr(validate, "FULL_CHECK_LIMIT", 0)
    body, notices = check_solid(cube(2)[:, ::-1].astype(np.float32))
    assert body.triangles.dtype == np.float32
    assert body.mass_properties().volume == pytest.approx(1.0, rel=1e-7)
    assert notices_with(notices, "inside out") and notices_with(notices, "not checked for overlap")
    with pytest.raises(GeometryError, match="3 boundary edges"):  # failing the cheap test
        check_solid(cube(2)[1:])


def test_repair_closes_a_non_planar_hole_and_reports_it():
    # An octahedron without one face: the hole is a triangle, closed by a fan.
    v = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    tri = v[np.array(faces)]
    fine = np.concatenate([_subdivide(t) for t in tri])  # 8 × 16 triangles
    body, notices = check_solid(fine[1:], repair=True)
    assert body.mass_properties().volume == pytest.approx(4 / 3, rel=1e-14)
    assert notices_with(notices, "repair: closed 1 hole (3 boundary edges)")


def _subdivide(t: np.ndarray, k: int = 4) -> np.ndarray:
    """A triangle cut into k² similar triangles (same orientation)."""
    out = []
    p = lambda i, j: t[0] + (t[1] - t[0]) * i / k + (t[2] - t[0]) * j / k  # noqa: E731
    for i in range(k):
        for j in range(k - i):
            out.append([p(i, j), p(i + 1, j), p(i, j + 1)])
            if i + j < k - 1:
                out.append([p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)])
    return np.array(out)


def test_extent_and_units():
    assert check_extent(np.zeros(3), np.ones(3), path=None) == ()
    assert "2000 m across" in check_extent(np.zeros(2), np.array([2000.0, 0]), path=None)[0]
    assert "only 1e-06 m" in check_extent(np.zeros(2), np.array([1e-6, 0]), path=None)[0]
    with pytest.raises(GeometryError, match="far beyond"):
        check_extent(np.zeros(3), np.array([0, 0, 2e9]), path="x.stl")
    assert units_scale(None) == (1.0, (validate.UNITS_ASSUMED,))
    assert units_scale("in") == (0.0254, ())
    assert units_scale(None, "millimeter", 1e-3)[0] == 1e-3
