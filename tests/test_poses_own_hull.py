"""A closed mesh that is its own convex hull (stability/poses/convex.py::own_hull): the
certificate holds on convex meshes and gives the poses the computed hull gives; it fails
on meshes that are not convex, immersed or wound twice, and then nothing changes."""

from __future__ import annotations

import math

import manifold3d
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation

from plumbob.bodies.solid import MeshSolid
from plumbob.errors import GeometryError, StabilityError
from plumbob.mesh.weld import merge_vertices
from plumbob.mesh.winding import solid_angle
from plumbob.stability.poses import convex, poses_from_points, resting_poses

M3 = manifold3d.Manifold


def welded(body: M3, float32: bool = False) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A manifold's surface as welded vertices, triangles indexing them (outward) and its
    centre of mass (uniform density, by the divergence theorem), as a file would give
    them; ``float32`` rounds the coordinates first (a binary STL)."""
    mesh = body.to_mesh64()
    soup = np.asarray(mesh.vert_properties, dtype=float)[:, :3][
        np.asarray(mesh.tri_verts, dtype=np.int64).reshape(-1, 3)]
    if float32:
        soup = soup.astype(np.float32).astype(float)
    V, index = merge_vertices(soup.reshape(-1, 3))
    F = index.reshape(-1, 3)
    a, b, c = (V[F[:, k]] for k in range(3))
    six_v = np.einsum("ij,ij->i", a, np.cross(b, c))
    return V, F, (six_v[:, None] * (a + b + c)).sum(axis=0) / (4 * six_v.sum())


def certified(V: np.ndarray, F: np.ndarray, com: np.ndarray) -> bool:
    X = V - com
    return convex.own_hull(X, F, 1e-12 * float(np.linalg.norm(np.ptp(X, axis=0)))) is not None


def direction(p) -> np.ndarray:
    """What names a pose: its face's normal, or a rolling family's axis (its ``down`` is
    one of its lowest faces, equally low by symmetry: which one, the last bits decide)."""
    return p.axis if p.kind == "rolling" and p.axis is not None else p.down


def canonical(poses) -> list:
    """The poses in an order of their own: poses of equal probability (symmetric faces)
    come in the order their last bits give, which either hull may flip."""
    return sorted(poses, key=lambda p: (-round(p.probability, 9), p.kind,
                                        *np.round(direction(p), 9).tolist()))


def assert_same_poses(a, b) -> None:
    assert len(a) == len(b) and a.hull_faces == b.hull_faces and a.method == b.method
    assert np.allclose(a.probabilities, b.probabilities, rtol=0, atol=1e-12)
    for p, q in zip(canonical(a), canonical(b)):
        assert p.kind == q.kind and p.members == q.members
        assert p.probability == pytest.approx(q.probability, rel=0, abs=1e-12)
        assert np.allclose(direction(p), direction(q), rtol=0, atol=1e-12)
        assert p.com_height == pytest.approx(q.com_height, rel=1e-12)


def both_ways(V, F, com, monkeypatch, roll_angle_deg: float = 0.0):
    """The poses with the mesh given, and with the own hull refused (the hull computed);
    by default every stable face a pose of its own (no rolling families), the strictest
    comparison."""
    own = poses_from_points(V, com, surface=F, roll_angle_deg=roll_angle_deg)
    with monkeypatch.context() as m:
        m.setattr(convex, "own_hull", lambda *args: None)
        hull = poses_from_points(V, com, surface=F, roll_angle_deg=roll_angle_deg)
    return own, hull


@pytest.fixture(params=[True, False], ids=["prechecked", "full certificate"])
def precheck(request, monkeypatch) -> bool:
    """Every refusal twice: as it happens (a sampled check first, which catches most), and
    with that check waved through, so that the full certificate must refuse alone."""
    if not request.param:
        monkeypatch.setattr(convex, "may_be_own_hull", lambda *args: True)
    return request.param


def capsule(segments: int = 48) -> M3:
    ball = M3.sphere(0.5, segments)
    return M3.batch_hull([ball, ball.translate([0.0, 0.0, 1.5])])


def polytope(seed: int) -> M3:
    return M3.hull_points(np.random.default_rng(seed).normal(size=(40, 3)) * [1.0, 2.0, 0.7])


CONVEX = {
    "capsule": capsule,
    "box": lambda: M3.cube([1.0, 2.0, 3.0]),
    "refined box": lambda: M3.cube([1.0, 2.0, 3.0], center=True).refine(3),
    "cylinder": lambda: M3.cylinder(2.0, 0.6, 0.6, 64),
    "polytope": lambda: polytope(1),
    "rotated polytope": lambda: polytope(2).rotate([17.0, -33.0, 71.0]),
}


@pytest.mark.parametrize("float32", [False, True], ids=["float64", "float32"])
@pytest.mark.parametrize("name", list(CONVEX))
def test_a_convex_mesh_is_its_own_hull(name, float32, monkeypatch):
    V, F, com = welded(CONVEX[name](), float32)
    assert certified(V, F, com)
    own, hull = both_ways(V, F, com, monkeypatch)
    assert_same_poses(own, hull)
    assert_same_poses(*both_ways(V, F, com, monkeypatch, 15.0))  # with rolling families
    # and no hull was computed on the way
    monkeypatch.setattr(convex, "_manifold_hull", lambda *args: pytest.fail("hull computed"))
    assert_same_poses(poses_from_points(V, com, surface=F, roll_angle_deg=0.0), own)


def test_a_mesh_body_passes_its_own_triangles(monkeypatch):
    """resting_poses of a MeshSolid: the welded mesh is the hull, the poses the same."""
    V, F, _ = welded(capsule(32).rotate([10.0, 20.0, 30.0]))
    body = MeshSolid(V[F])
    with monkeypatch.context() as m:
        m.setattr(convex, "own_hull", lambda *args: None)
        hull = resting_poses(body)
    monkeypatch.setattr(convex, "_manifold_hull", lambda *args: pytest.fail("hull computed"))
    assert_same_poses(resting_poses(MeshSolid(V[F])), hull)
    assert [p.kind for p in hull] == ["rolling"]  # the capsule rolls (its ends are round)


def test_a_mesh_body_that_is_plainly_not_convex_is_not_welded_again(monkeypatch):
    """A mesh read with its vertices welded already (a reader's check did it) and not
    convex: a sample of its planes says so, and it is not welded a second time."""
    V, F, _ = welded(l_block())
    body = MeshSolid(V[F], vertices=V.copy())
    own = resting_poses(body)
    assert "welded" not in body.__dict__
    monkeypatch.setattr(convex, "own_hull", lambda *args: None)
    assert_same_poses(own, resting_poses(MeshSolid(V[F])))


def l_block() -> M3:
    return M3.cube([3.0, 1.0, 1.0]) + M3.cube([1.0, 1.0, 3.0])


def boss() -> M3:
    """tests/test_poses_fans.py's box with a cylinder boss."""
    return M3.cube([40, 30, 20], center=True) + M3.cylinder(20, 8, 8, 48).translate([5, 3, 0])


def torus() -> M3:
    return M3.revolve(manifold3d.CrossSection.circle(0.3, 24).translate([1.0, 0.0]), 48)


def dimpled() -> M3:
    """A refined box with the middle vertex of its top face pushed in by 1e-6 of its size."""
    body = M3.cube([2.0, 2.0, 2.0], center=True).refine(2)
    size = math.sqrt(12.0)
    return body.warp(lambda p: (p[0], p[1], p[2] - 1e-6 * size
                                if p[2] > 0.999 and abs(p[0]) + abs(p[1]) < 1e-9 else p[2]))


@pytest.mark.parametrize("make", [l_block, boss, torus, dimpled],
                         ids=["L-block", "boss", "torus", "dimpled box"])
def test_a_mesh_that_is_not_convex_changes_nothing(make, monkeypatch, precheck):
    V, F, com = welded(make())
    assert not certified(V, F, com)
    own, hull = both_ways(V, F, com, monkeypatch)
    assert_same_poses(own, hull)
    assert_same_poses(own, poses_from_points(V, com, roll_angle_deg=0.0))
    if precheck and make is not dimpled:  # refused at once, by the sampled check
        X = V - com
        assert not convex.may_be_own_hull(X, X[convex.sample_triangles(F)], 1e-12)


def test_the_dimple_is_really_there():
    """The dimpled box above is what it says: one vertex moved inward by 1e-6 of the
    size, inside the hull of the box's eight corners."""
    V, F, com = welded(dimpled())
    top = np.flatnonzero((np.abs(V[:, 0]) + np.abs(V[:, 1]) < 1e-9) & (V[:, 2] > 0.99))
    assert len(top) == 1 and V[top[0], 2] == pytest.approx(1 - 1e-6 * math.sqrt(12), abs=1e-15)
    assert ConvexHull(V).vertices.size == 8  # the hull: the box's corners only


TETRA_FACES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
TETRA = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])


@pytest.mark.parametrize("centre", [[1.0, 1.0, 1.0], [0.2, 0.2, 0.0], [0.0, 0.0, 0.0]],
                         ids=["outside", "on a face", "at a corner"])
def test_a_centre_not_strictly_inside_is_refused(centre, precheck):
    X = TETRA - centre
    assert convex.own_hull(X, TETRA_FACES, 1e-12) is None
    with pytest.raises(StabilityError, match="outside|surface"):
        poses_from_points(TETRA, centre, surface=TETRA_FACES)


def test_a_tetrahedron_with_the_centre_inside_is_certified():
    centre = TETRA.mean(axis=0)
    assert convex.own_hull(TETRA - centre, TETRA_FACES, 1e-12) is not None
    assert np.allclose(poses_from_points(TETRA, centre, surface=TETRA_FACES).probabilities,
                       poses_from_points(TETRA, centre).probabilities, rtol=0, atol=1e-13)


def twice_wound() -> tuple[np.ndarray, np.ndarray]:
    """A bipyramid over a pentagram: a closed 2-manifold (a sphere: its equator is one
    cycle of five vertices), every triangle facing away from the origin and every edge
    convex, yet its central projection covers the sphere twice (an immersed surface)."""
    t = 2 * np.pi * np.arange(5) / 5
    V = np.concatenate((np.c_[np.cos(t), np.sin(t), np.zeros(5)], [[0, 0, 1], [0, 0, -1]]))
    ring = np.array([0, 2, 4, 1, 3])  # the pentagram's order: 144° a step
    nxt = np.roll(ring, -1)
    F = np.concatenate((np.c_[ring, nxt, np.full(5, 5)], np.c_[nxt, ring, np.full(5, 6)]))
    return V, F


def test_a_surface_wound_twice_is_refused_by_its_solid_angle(precheck):
    V, F = twice_wound()
    C = V[F]
    omega = solid_angle(C[:, 0], C[:, 1], C[:, 2])
    assert np.all(omega > 0) and omega.sum() == pytest.approx(8 * np.pi, rel=1e-12)
    # the other checks pass: closed, the origin inside every plane, every edge convex
    twin = convex.half_edge_twins(F, len(V))
    tn, off, _ = convex._planes(V, F)
    assert twin is not None and off.min() > 0.1
    assert convex._beyond(V, F, tn, off, twin).max() < 0
    assert convex.own_hull(V, F, 1e-12) is None
    # the poses are the pentagonal bipyramid's, the hull of the points
    assert_same_poses(poses_from_points(V, [0, 0, 0], surface=F), poses_from_points(V, [0, 0, 0]))


def test_a_point_off_the_surface_is_refused(precheck):
    """Every point must be a corner: one outside the mesh makes its hull bigger."""
    centre = TETRA.mean(axis=0)
    X = np.concatenate((TETRA, [[2.0, 2.0, 2.0]])) - centre
    assert convex.own_hull(X, TETRA_FACES, 1e-12) is None
    ps = poses_from_points(X + centre, centre, surface=TETRA_FACES)
    assert_same_poses(ps, poses_from_points(X + centre, centre))


def test_an_open_or_inside_out_surface_is_refused(precheck):
    centre = TETRA.mean(axis=0)
    assert convex.own_hull(TETRA - centre, TETRA_FACES[:, ::-1], 1e-12) is None
    assert convex.own_hull(TETRA - centre, np.r_[TETRA_FACES[:3], TETRA_FACES[:1]], 1e-12) is None


def test_a_t_junction_is_refused(precheck):
    """A face split at the midpoint of an edge its neighbour keeps whole: the solid
    angles still add up to 4π and every edge that pairs is convex, but the surface is
    not a closed 2-manifold."""
    centre = TETRA.mean(axis=0)
    X = np.concatenate((TETRA, [(TETRA[1] + TETRA[2]) / 2])) - centre
    F = np.concatenate((TETRA_FACES[:3], [[1, 4, 3], [4, 2, 3]]))
    C = X[F]
    assert solid_angle(C[:, 0], C[:, 1], C[:, 2]).sum() == pytest.approx(4 * np.pi, rel=1e-12)
    assert convex.half_edge_twins(F, len(X)) is None
    assert convex.own_hull(X, F, 1e-12) is None


@pytest.mark.parametrize("surface, phrase", [
    (np.zeros((4, 2), dtype=int), "integer indices"),
    (np.zeros((4, 3)), "integer indices"),
    (TETRA_FACES + 1, "index points 0 … 3"),
    (TETRA_FACES - 1, "index points 0 … 3"),
])
def test_a_surface_that_is_no_triangles_is_a_geometry_error(surface, phrase):
    with pytest.raises(GeometryError, match=phrase):
        poses_from_points(TETRA, TETRA.mean(axis=0), surface=surface)


def test_a_lamina_ignores_the_surface():
    square = np.array([[0.0, 0], [1, 0], [1, 1], [0, 1]])
    ps = poses_from_points(square, [0.5, 0.5], surface=np.array([[0, 1, 2], [0, 2, 3]]))
    assert np.allclose(ps.probabilities, 0.25, rtol=0, atol=1e-13)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(6, 60))
def test_random_convex_hulls_rotated_are_certified(seed, n):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(n, 3)) * rng.uniform(0.2, 3.0, size=3)
    body = M3.hull_points(Rotation.random(random_state=rng).apply(X))
    assume(body.volume() > 1e-3)
    V, F, com = welded(body)
    assert certified(V, F, com)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(8, 60), st.floats(0.0, 0.5))
def test_a_vertex_pushed_inside_the_others_hull_is_refused(seed, n, depth):
    """Pushed toward the centre until it lies inside the hull of the other points, a
    vertex can be no corner of a convex body: the certificate must fail."""
    rng = np.random.default_rng(seed)
    V, F, com = welded(M3.hull_points(rng.normal(size=(n, 3))))
    k = int(rng.integers(len(V)))
    V = V.copy()
    V[k] = com + depth * (V[k] - com)
    eq = ConvexHull(np.delete(V, k, axis=0)).equations  # outward unit normals, offsets
    assume(float((eq[:, :3] @ V[k] + eq[:, 3]).max()) < -1e-9)  # well inside the others
    assert not certified(V, F, com)
    with pytest.MonkeyPatch.context() as m:  # the full certificate alone refuses it too
        m.setattr(convex, "may_be_own_hull", lambda *args: True)
        assert not certified(V, F, com)


def test_a_convex_surface_split_along_concave_diagonals_is_refused_at_once():
    """An ellipsoid on a lat-long grid with twisted longitudes: every quad bends, and
    each is split along its concave diagonal, so the mesh is not its own hull though
    every point is on the hull. The sampled pairs of consecutive triangles see it alone
    (each rises over the other's plane), and the full certificate refuses it too."""
    theta = np.linspace(0, np.pi, 26)[1:-1]
    t, p = np.meshgrid(theta, np.linspace(0, 2 * np.pi, 48, endpoint=False), indexing="ij")
    p = p + 0.8 * t
    V = np.stack((np.sin(t) * np.cos(p), 0.6 * np.sin(t) * np.sin(p), 0.8 * np.cos(t)), -1)
    idx = np.arange(V.shape[0] * V.shape[1]).reshape(V.shape[:2])
    a, b = idx[:-1], idx[1:]
    a2, b2 = np.roll(a, -1, axis=1), np.roll(b, -1, axis=1)
    ring = np.roll(idx, -1, axis=1)
    F = np.concatenate([np.stack((a, b, b2), -1).reshape(-1, 3),
                        np.stack((a, b2, a2), -1).reshape(-1, 3),
                        np.stack((np.full(48, idx.size), idx[0], ring[0]), 1),
                        np.stack((np.full(48, idx.size + 1), ring[-1], idx[-1]), 1)])
    X = np.vstack((V.reshape(-1, 3), [[0.0, 0.0, 0.8], [0.0, 0.0, -0.8]]))
    assert len(ConvexHull(X).vertices) == len(X)  # every point on the hull: only the cut
    corners = X[convex.sample_triangles(F)]
    pairs = corners[-2 * convex.SAMPLE_PAIRS:]
    tn, off, _ = convex._corner_planes(pairs)
    assert not convex._pairs_below(pairs, tn, off, 1e-12)
    assert not convex.may_be_own_hull(X, corners, 1e-12)
    with pytest.MonkeyPatch.context() as m:  # the full certificate refuses it alone
        m.setattr(convex, "may_be_own_hull", lambda *args: True)
        assert convex.own_hull(X, F, 1e-12) is None
