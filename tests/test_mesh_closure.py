"""The one closure rule (plumbob.mesh.closure) and welding (plumbob.mesh.weld): copies
that differ by round-off weld, holes are loops of unshared edges that span an area,
T-junction slits span none, and an open MeshSolid cannot be built."""

import os
import sys

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "bad_inputs"))
from make_bad_inputs import cube  # noqa: E402

from plumbob import mesh  # noqa: E402
from plumbob.bodies.solid import MeshSolid  # noqa: E402
from plumbob.errors import GeometryError  # noqa: E402
from plumbob.mesh.closure import edges_pair, holes, require_closed  # noqa: E402
from plumbob.mesh.topology import mesh_topology  # noqa: E402
from plumbob.mesh.weld import merge_vertices, point_keys, weld_near  # noqa: E402
from plumbob.tolerances import WELD  # noqa: E402


def outward(tri: np.ndarray, centre) -> np.ndarray:
    """Each triangle of a convex body turned to face away from ``centre``."""
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    inward = np.einsum("ij,ij->i", normal, tri.mean(axis=1) - centre) < 0
    tri = tri.copy()
    tri[inward] = tri[inward][:, ::-1]
    return tri


def tube(k: int = 24, height: float = 3.0) -> np.ndarray:
    """An open tube around the z-axis (no ends): its faces' area vectors cancel."""
    a = 2 * np.pi * np.arange(k) / k
    lo = np.stack((np.cos(a), np.sin(a), 0 * a), axis=1)
    hi = lo + [0, 0, height]
    nxt = np.roll(np.arange(k), -1)
    return np.concatenate((np.stack((lo, lo[nxt], hi[nxt]), 1), np.stack((lo, hi[nxt], hi), 1)))


def sleeve() -> np.ndarray:
    """A unit cube without its top and bottom."""
    tri = cube()
    return tri[np.ptp(tri[:, :, 2], axis=1) > 0]


def stacked_by_t_junctions() -> np.ndarray:
    """A 1 × 1 × 2 box made of two open boxes that share no edge: the lower one's top rim
    runs whole, the upper one's bottom rim is split at each side's middle. They close only
    together, through T-junctions."""
    lower = sleeve()
    lower = np.concatenate((lower, cube()[np.all(cube()[:, :, 2] == 0, axis=1)]))
    corners = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float)
    walls = []
    for i in range(4):  # per side wall of the upper box
        bl, br = np.append(corners[i], 1.0), np.append(corners[(i + 1) % 4], 1.0)
        tl, tr, m = bl + [0, 0, 1], br + [0, 0, 1], (bl + br) / 2
        walls += [(bl, m, tl), (m, tr, tl), (m, br, tr)]
    top = cube(offset=(0, 0, 1))
    upper = np.concatenate((np.array(walls), top[np.all(top[:, :, 2] == 2, axis=1)]))
    return outward(np.concatenate((lower, upper)), np.array([0.5, 0.5, 1.0]))


# ------------------------------------------------------------------ welding
def test_round_off_copies_weld_only_with_a_tolerance():
    points = np.array([[0.0, 1, 1], [-6.12e-17, 1, 1], [1, 1, 1]])
    assert len(merge_vertices(points)[0]) == 3
    vertices, index = merge_vertices(points, 1e-12)
    assert len(vertices) == 2 and index[0] == index[1] != index[2]


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_signed_zeros_hash_alike(dtype):
    keys = point_keys(np.array([[0.0, -0.0, 1.0], [-0.0, 0.0, 1.0]], dtype=dtype))
    assert keys[0] == keys[1]


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 40), st.integers(0, 2**32 - 1), st.floats(1e-12, 1e-3))
def test_points_within_the_tolerance_always_weld_and_far_ones_never(n, seed, tolerance):
    rng = np.random.default_rng(seed)
    # originals on a grid 20 tolerances apart: far from each other
    originals = rng.choice(10**6, size=(n, 3), replace=False) * 20 * tolerance
    offset = rng.normal(size=(n, 3))
    offset *= (0.99 * tolerance * rng.random(n) / np.linalg.norm(offset, axis=1))[:, None]
    group = weld_near(np.concatenate((originals, originals + offset)), tolerance)
    assert np.array_equal(group[:n], group[n:])  # each copy with its original
    assert len(np.unique(group)) == len(np.unique(originals, axis=0))


def test_topology_welds_only_boundary_copies_and_reports_them():
    tri = cube(2).copy()
    tri[tri == 0.0] = -6.12e-17 * (np.arange(tri.size).reshape(tri.shape)[tri == 0.0] % 2)
    exact = mesh_topology(tri)
    assert len(exact.boundary) > 0
    welded = mesh_topology(tri, 1e-9)
    assert len(welded.boundary) == 0 and welded.shells == 1
    assert welded.welded > 0 and 0 < welded.weld_distance < 1e-16


def test_check_solid_says_what_it_welded_and_measures_the_input():
    tri = cube(3).copy()
    tri[tri == 1.0] = 1.0 + 2.2e-16 * (np.arange(tri.size).reshape(tri.shape)[tri == 1.0] % 2)
    checked = mesh.check_solid(tri)
    (notice,) = [n for n in checked.notices if n.startswith("weld: merged")]
    assert "not identical" in notice and f"{WELD:g} of the size" in notice
    assert MeshSolid(checked.triangles, checked=True).mass_properties().volume == \
        pytest.approx(1.0, rel=1e-14)


def test_a_real_crack_is_not_welded():
    tri = cube(2).copy()
    tri[(tri[:, :, 0] > 0.75).all(axis=1) & (tri[..., 1] == 0.5).any(axis=1)] += [0, 1e-3, 0]
    with pytest.raises(GeometryError, match="is open"):
        mesh.check_solid(tri)


# ------------------------------------------------------------------ the rule
def test_edges_pair_certifies_closed_consistent_surfaces():
    tri = cube(3)
    rng = np.random.default_rng(1)
    shuffled = tri[rng.permutation(len(tri))][:, [1, 2, 0]]
    assert edges_pair(tri) and edges_pair(shuffled) and edges_pair(tri.astype(np.float32))
    assert not edges_pair(tri[1:])
    flipped = tri.copy()
    flipped[0] = flipped[0, ::-1]
    assert not edges_pair(flipped)


@pytest.mark.parametrize("make, loops, edges", [(tube, 2, 48), (sleeve, 2, 8)])
def test_open_surfaces_whose_area_vectors_cancel_are_open(make, loops, edges):
    tri = make()
    summary = mesh.surface_summary(tri)
    assert summary.closed  # the old test alone would pass them
    found = holes(mesh_topology(tri), summary.area)
    assert (found.loops, found.edges, found.slits) == (loops, edges, 0)
    message = f"is open: {edges} boundary edges ({loops} holes)"
    with pytest.raises(GeometryError, match=message.replace("(", r"\(").replace(")", r"\)")):
        require_closed(tri)
    with pytest.raises(GeometryError, match="is open"):
        mesh.check_solid(tri)
    with pytest.raises(GeometryError, match="is open"):
        MeshSolid(tri)


def test_big_open_tube_is_refused_on_the_cheap_path_too(monkeypatch):
    monkeypatch.setattr(mesh.solid, "FULL_CHECK_LIMIT", 10)
    with pytest.raises(GeometryError, match="2 holes"):
        mesh.check_solid(tube())


def test_shells_that_close_only_through_t_junctions_are_one_solid():
    tri = stacked_by_t_junctions()
    topo = mesh_topology(tri)
    assert topo.shells == 2 and len(topo.boundary) == 12
    found = holes(topo, mesh.surface_summary(tri).area)
    assert found.loops == 0 and found.slits == 12
    checked = mesh.check_solid(tri)
    assert any("T-junctions" in n for n in checked.notices)
    props = MeshSolid(checked.triangles, checked=True).mass_properties()
    assert props.volume == pytest.approx(2.0, rel=1e-14)
    np.testing.assert_allclose(props.center_of_mass, [0.5, 0.5, 1.0], rtol=1e-14)
    require_closed(tri)
    assert MeshSolid(tri).mass_properties().volume == pytest.approx(2.0, rel=1e-14)


def test_closed_mesh_solid_checks_once_and_keeps_its_moments():
    body = MeshSolid(cube(2))
    assert body.checked and body.moments is not None
    moved = body.translated([1, 2, 3])
    assert moved.checked and moved.mass_properties().volume == pytest.approx(1.0)


def test_a_mesh_solid_needs_real_triangles():
    with pytest.raises(GeometryError, match="array of real numbers"):
        MeshSolid(cube().astype(complex))
    with pytest.raises(GeometryError, match="array of real numbers"):
        MeshSolid(cube()[:, :2])
    whole = MeshSolid(np.rint(cube(2) * 2).astype(int))  # whole numbers are coordinates too
    assert whole.mass_properties().volume == pytest.approx(8.0)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_point_keys_separate_mirrored_points(dtype):
    """A circle's points come in antipodal pairs and a box's in mirror images: each
    distinct point must get its own key (a collision is still merged exactly, but by a
    slow fallback: this is what kept welding a tessellated cylinder at 0.3 s)."""
    from plumbob.mesh.weld import point_keys

    q = np.random.default_rng(5).normal(size=(20_000, 3))
    mirrored = np.concatenate([q, -q, q * [1, -1, 1], q * [-1, 1, 1], q * [1, 1, -1]])
    keys = point_keys(mirrored.astype(dtype))
    assert len(np.unique(keys)) == len(mirrored)
