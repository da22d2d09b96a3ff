"""Resting poses: closed forms, an independent Monte-Carlo descent, invariants, bad input."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_stability_support import SCULPTURE, A, H

import plumbob.stability.poses.basins as basins_module
import plumbob.stability.poses.faces as faces_module
from plumbob.bodies.primitives import box, cylinder, polygon, pyramid, rectangle, sphere
from plumbob.bodies.solid import MeshSolid
from plumbob.errors import GeometryError, PlumbobError, StabilityError
from plumbob.massprops import rotation_matrix
from plumbob.mesh import solid_angle
from plumbob.stability import check, poses_from_points, resting_poses
from plumbob.stability.poses.basins import basins3, sampled_basins
from plumbob.stability.poses.faces import physical_faces
from plumbob.stability.poses.hull import build_hull3
from plumbob.stability.poses.landscape import landscape2

G = 9.81
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
TETRA = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=float)


# ------------------------------------------------------------ independent references
def monte_carlo_descent(points, com, n=3000, seed=0):
    """Independent quasi-static descent of h(u) = max (v − c)·u from random directions:
    steepest (min-norm) subgradient steps over the one or two points in contact, with
    shrinking steps. Returns the final directions (n, 3)."""
    rng = np.random.default_rng(seed)
    Y = np.asarray(points, float) - com
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1)[:, None]
    rows = np.arange(n)
    for eta, steps in ((1e-2, 400), (2e-3, 300), (4e-4, 200)):
        for _ in range(steps):
            s = u @ Y.T
            top = np.argpartition(-s, 1, axis=1)[:, :2]
            first = np.where(s[rows, top[:, 0]] >= s[rows, top[:, 1]], top[:, 0], top[:, 1])
            second = np.where(first == top[:, 0], top[:, 1], top[:, 0])
            gi = Y[first] - s[rows, first][:, None] * u
            gj = Y[second] - s[rows, second][:, None] * u
            band = s[rows, first] - s[rows, second] <= 2 * eta * np.linalg.norm(
                Y[first] - Y[second], axis=1)
            dg = gi - gj
            lam = np.clip(-np.einsum("ij,ij->i", gj, dg)
                          / np.maximum(np.einsum("ij,ij->i", dg, dg), 1e-300), 0, 1)
            d = np.where(band[:, None], gj + lam[:, None] * dg, gi)
            dn = np.linalg.norm(d, axis=1)[:, None]
            u = u - eta * d / np.where(dn > 0, dn, 1)
            u /= np.linalg.norm(u, axis=1)[:, None]
    return u


def lhuilier_fan(centre, ring):
    """Area of a spherical polygon star-shaped about ``centre``: L'Huilier's theorem on the
    triangles (centre, ring[i], ring[i+1]) — side lengths only, no signed formula."""
    total = 0.0
    for p, q in zip(ring, np.roll(ring, -1, axis=0)):
        a = np.arccos(np.clip(p @ q, -1, 1))
        b = np.arccos(np.clip(centre @ q, -1, 1))
        c = np.arccos(np.clip(centre @ p, -1, 1))
        s = (a + b + c) / 2
        t = np.tan(s / 2) * np.tan((s - a) / 2) * np.tan((s - b) / 2) * np.tan((s - c) / 2)
        total += 4 * np.arctan(np.sqrt(max(t, 0.0)))
    return total


def box_face_probability(half, axis):
    """The +axis face of a box with half-sizes ``half``: its basin is bounded by the great
    arcs from its four edges' saddles (square to each edge) to its four corners' maxima."""
    i, j, k = axis, (axis + 1) % 3, (axis + 2) % 3
    ring = []
    for sj, sk in ((1, 1), (1, 0), (1, -1), (0, -1), (-1, -1), (-1, 0), (-1, 1), (0, 1)):
        v = np.zeros(3)
        v[i], v[j], v[k] = half[i], sj * half[j], sk * half[k]
        ring.append(v / np.linalg.norm(v))
    centre = np.zeros(3)
    centre[i] = 1.0
    return lhuilier_fan(centre, np.array(ring)) / (4 * np.pi)


def foot_inside(pose, com) -> bool:
    """Independent check that a pose is truly stable: the foot lies inside its face."""
    n = pose.down
    face = pose.face - com
    foot = (face[0] @ n) * n
    e1 = np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(n, e1)
    q = np.stack(((face - foot) @ e1, (face - foot) @ e2), axis=1)
    d = np.roll(q, -1, axis=0) - q
    cross = d[:, 0] * (-q[:, 1]) - d[:, 1] * (-q[:, 0])
    return bool(np.all(cross > 0) or np.all(cross < 0))


def random_body(seed, n=10):
    """Random points and a centre of mass strictly inside their hull (a convex combination)."""
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(n, 3)) * [1.0, 0.7, 0.45]
    com = rng.dirichlet(np.full(n, 4.0)) @ X
    return X, com


# ------------------------------------------------------------------- closed forms
def test_cube_six_poses_of_one_sixth():
    ps = poses_from_points(CUBE, [0.5, 0.5, 0.5], mass=2.0)
    assert ps.method == "exact" and len(ps) == 6
    assert np.allclose(ps.probabilities, 1 / 6, rtol=0, atol=1e-13)
    for p in ps.poses:
        assert p.com_height == pytest.approx(0.5)
        assert p.critical_tilt_deg == pytest.approx(45.0)
        assert p.energy_barrier == pytest.approx(2.0 * G * (np.sqrt(0.5) - 0.5))
        assert len(p.face) == 4
    assert sorted(map(tuple, np.array([p.down for p in ps.poses]).round(12))) == sorted(
        map(tuple, np.vstack((np.eye(3), -np.eye(3)))))


def test_regular_tetrahedron_four_poses_of_one_quarter():
    ps = poses_from_points(TETRA, [0, 0, 0])
    assert len(ps) == 4 and np.allclose(ps.probabilities, 0.25, rtol=0, atol=1e-13)
    # foot at the face's centre: inradius of the face over inradius of the solid: atan √2
    assert all(p.critical_tilt_deg == pytest.approx(np.degrees(np.arctan(np.sqrt(2))))
               for p in ps.poses)


@pytest.mark.parametrize("size", [(1, 2, 3), (1, 1, 4), (0.3, 2, 2.5)])
def test_boxes_against_an_independent_spherical_area(size):
    ps = resting_poses(box(*size))
    half = np.array(size) / 2
    for p in ps.poses:
        axis = int(np.argmax(np.abs(p.down)))
        assert p.probability == pytest.approx(box_face_probability(half, axis), abs=1e-12)
    assert len(ps) == 6


def test_rectangle_lamina_closed_form():
    """A w × h lamina: each long side's basin is the arc between its corners' directions."""
    ps = resting_poses(rectangle(3.0, 1.0))
    assert len(ps) == 4 and ps.method == "exact"
    long_sides = [p for p in ps.poses if abs(p.down[1]) > 0.5]
    assert all(p.probability == pytest.approx(np.arctan(3.0) / np.pi, abs=1e-13)
               for p in long_sides)
    assert sum(ps.probabilities) == pytest.approx(1.0, abs=1e-14)


def test_sculpture_poses_include_the_seeds():
    ps = resting_poses(polygon(SCULPTURE))
    assert len(ps) == 3
    base = [p for p in ps.poses if np.allclose(p.down, [0, -1])]
    assert len(base) == 1
    assert base[0].com_height == pytest.approx(19 * H / 21)
    assert base[0].critical_tilt_deg == pytest.approx(np.degrees(np.arctan(4 * A / (19 * H))))
    # leaving it over the edge at O costs what the verdict says it costs to topple
    v = check(polygon(SCULPTURE))
    assert base[0].energy_barrier == pytest.approx(v.energy_to_topple, rel=1e-12)


def test_pose_tilts_agree_with_the_verdict():
    body = pyramid([(0, 0), (3.0, -0.4), (2.6, 2.2), (0.3, 1.7)], 2.5, apex=(1.9, 0.7))
    for p in resting_poses(body).poses:
        v = check(body, p.down)
        assert v.verdict == "stands"
        assert v.critical_tilt_deg == pytest.approx(p.critical_tilt_deg, rel=1e-9)
        assert v.com_height == pytest.approx(p.com_height, rel=1e-12)


# ----------------------------------------------------------- Monte-Carlo check
@pytest.mark.parametrize("seed", [3, 11])
def test_against_an_independent_monte_carlo_descent(seed):
    X, com = random_body(seed)
    ps = poses_from_points(X, com, roll_angle_deg=0)  # the exact basins: no families
    assert ps.method == "exact"
    u = monte_carlo_descent(X, com)
    downs = np.array([p.down for p in ps.poses])
    landed = np.argmax(u @ downs.T, axis=1)
    assert np.all(np.einsum("ij,ij->i", u, downs[landed]) > np.cos(0.01))  # all converged
    frequency = np.bincount(landed, minlength=len(downs)) / len(u)
    sigma = np.sqrt(ps.probabilities * (1 - ps.probabilities) / len(u))
    assert np.all(np.abs(frequency - ps.probabilities) <= 4.5 * sigma + 1e-3)


def test_box_against_monte_carlo():
    size = np.array([1.0, 2.0, 3.0])
    X = CUBE * size
    ps = poses_from_points(X, size / 2)
    u = monte_carlo_descent(X, size / 2, seed=5)
    downs = np.array([p.down for p in ps.poses])
    frequency = np.bincount(np.argmax(u @ downs.T, axis=1), minlength=6) / len(u)
    assert np.allclose(frequency, ps.probabilities, atol=0.03)


# -------------------------------------------------------------------- invariants
seeds = st.integers(0, 10_000)


@settings(max_examples=40)
@given(seeds, st.integers(5, 40))
def test_probabilities_sum_to_one_and_every_pose_is_truly_stable(seed, n):
    X, com = random_body(seed, n)
    ps = poses_from_points(X, com)
    assert np.all(np.isfinite(ps.probabilities)) and np.all(ps.probabilities > 0)
    assert ps.probabilities.sum() == pytest.approx(1.0, abs=1e-12)
    assert ps.method == "exact" and ps.area_error < 1e-9
    assert np.all(np.diff(ps.probabilities) <= 0)  # most probable first
    for p in ps.poses:
        assert foot_inside(p, com)
        assert p.critical_tilt_deg > 0


@settings(max_examples=25)
@given(seeds, st.tuples(*[st.floats(-np.pi, np.pi)] * 3), st.tuples(*[st.floats(-20, 20)] * 3))
def test_rigid_motions_turn_the_poses_with_the_body(seed, angles, offset):
    X, com = random_body(seed, 14)
    turn = (rotation_matrix([1, 0, 0], angles[0]) @ rotation_matrix([0, 1, 0], angles[1])
            @ rotation_matrix([0, 0, 1], angles[2]))
    before = poses_from_points(X, com)
    after = poses_from_points(X @ turn.T + offset, turn @ com + offset)
    assert len(after) == len(before)
    for p in before.poses:
        match = [q for q in after.poses if np.allclose(q.down, turn @ p.down, atol=1e-8)]
        assert len(match) == 1
        assert match[0].probability == pytest.approx(p.probability, abs=1e-10)
        assert match[0].com_height == pytest.approx(p.com_height, rel=1e-10)


@settings(max_examples=15)
@given(seeds, st.floats(1e-3, 1e6))
def test_mass_changes_barriers_not_poses(seed, mass):
    X, com = random_body(seed)
    light = poses_from_points(X, com, mass=1.0)
    heavy = poses_from_points(X, com, mass=mass)
    assert np.array_equal(light.probabilities, heavy.probabilities)
    for p, q in zip(light.poses, heavy.poses):
        assert np.array_equal(p.down, q.down)
        if p.energy_barrier is not None:
            assert q.energy_barrier == pytest.approx(mass * p.energy_barrier, rel=1e-12)


# --------------------------------------------------------------- faces and slivers
def subdivided_box_mesh(size, n, noise=0.0, seed=0):
    """A box whose faces are n × n grids of triangles (float coordinates jittered)."""
    rng = np.random.default_rng(seed)
    tris = []
    t = np.linspace(0, 1, n + 1)
    for axis in range(3):
        for side in (0, 1):
            i, j = (axis + 1) % 3, (axis + 2) % 3
            for a in range(n):
                for b in range(n):
                    quad = []
                    for da, db in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = np.zeros(3)
                        p[axis], p[i], p[j] = side, t[a + da], t[b + db]
                        quad.append(p * size)
                    q = np.array(quad)
                    if side == 0:
                        q = q[::-1]
                    tris += [q[[0, 1, 2]], q[[0, 2, 3]]]
    tris = np.array(tris)
    verts, inverse = np.unique(tris.reshape(-1, 3), axis=0, return_inverse=True)
    verts = verts + noise * rng.uniform(-1, 1, verts.shape)
    return verts[inverse.reshape(-1, 3)]


def test_coplanar_triangles_make_one_physical_face():
    tris = subdivided_box_mesh(np.array([1.0, 2.0, 3.0]), 4, noise=1e-9)
    body = MeshSolid(tris)
    ps = resting_poses(body)
    assert len(ps) == 6
    reference = resting_poses(box(1, 2, 3)).probabilities
    assert np.allclose(sorted(ps.probabilities), sorted(reference), atol=1e-6)


def test_slivers_do_not_lose_probability():
    """A box whose top is a fan of hundreds of sliver triangles (as STL exports make)."""
    k = 300
    x = np.linspace(0, 1, k + 1)
    rim = np.vstack(([[0, 0, 1]], np.stack((x, np.zeros_like(x), np.ones_like(x)), 1),
                     [[1, 1, 1], [0, 1, 1]]))
    X = np.vstack((rim, CUBE))
    ps = poses_from_points(X, [0.5, 0.5, 0.5])
    assert len(ps) == 6 and np.allclose(ps.probabilities, 1 / 6, atol=1e-12)


def test_the_sampled_fallback_agrees(monkeypatch):
    X, com = random_body(7, 25)
    exact = poses_from_points(X, com)
    monkeypatch.setattr(basins_module, "_AREA_CHECK", -1.0)  # refuse the traced areas
    sampled = poses_from_points(X, com, samples=40_000)
    assert sampled.method == "sampled" and any("could not be traced" in n for n in sampled.notes)
    assert np.allclose(sampled.probabilities, exact.probabilities, atol=0.01)
    assert sampled.probabilities.sum() == pytest.approx(1.0)


# ------------------------------------------------------------------ curved bodies
def test_cylinder_two_ends_and_one_rolling_pose():
    ps = resting_poses(cylinder(1.0, 2.0))
    assert len(ps) == 3 and ps.probabilities.sum() == pytest.approx(1.0)
    ends = [p for p in ps.poses if abs(p.down[2]) > 0.99]
    side = [p for p in ps.poses if abs(p.down[2]) < 1e-9]
    assert len(ends) == 2 and len(side) == 1
    assert side[0].neutral and side[0].critical_tilt_deg == 0 and side[0].members > 10
    assert ends[0].probability == pytest.approx(ends[1].probability, rel=1e-9)
    assert all(p.critical_tilt_deg == pytest.approx(45.0, abs=0.05) for p in ends)
    assert any("rolling" in n for n in ps.notes)


def test_sphere_has_one_neutral_pose():
    ps = resting_poses(sphere(1.0))
    assert len(ps) == 1 and ps.poses[0].probability == 1.0 and ps.poses[0].neutral
    assert ps.poses[0].energy_barrier is None


def test_polytopes_are_never_merged_into_neutral_poses():
    ps = resting_poses(box(1.0, 1.0, 1.0 + 1e-5))  # nearly a cube: six poses stay six
    assert len(ps) == 6 and not any(p.neutral for p in ps.poses)


# ------------------------------------------------------------------------ bad input
def test_centre_outside_the_hull_is_a_clear_error_not_a_hang():
    with pytest.raises(StabilityError, match="outside the body's convex hull"):
        poses_from_points(CUBE, [0.5, 0.5, 1.5])
    with pytest.raises(StabilityError, match="on the surface of"):
        poses_from_points(CUBE, [0.5, 0.5, 1.0])
    with pytest.raises(StabilityError, match="outside"):
        poses_from_points(CUBE[:, :2][[0, 2, 4, 6]], [3.0, 0.5])


def test_an_open_mesh_is_a_clear_error():
    tris = subdivided_box_mesh(np.array([1.0, 1.0, 1.0]), 1)[:-1]  # one triangle missing
    with pytest.raises(PlumbobError, match="not closed|is open"):
        resting_poses(MeshSolid(tris))


@pytest.mark.parametrize("points", [np.zeros((5, 3)), CUBE[:4], np.eye(3)])
def test_degenerate_point_sets(points):
    with pytest.raises(GeometryError):
        poses_from_points(points, points.mean(axis=0))


def blob_mesh(n_lat=31, n_lon=60, seed=1):
    """A closed, bumpy, non-symmetric blob on a latitude-longitude grid."""
    rng = np.random.default_rng(seed)
    theta = np.linspace(0, np.pi, n_lat + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, n_lon, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    d = np.stack((np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)), axis=-1)
    r = np.ones_like(t)
    for _ in range(5):
        k = rng.normal(size=3)
        k /= np.linalg.norm(k)
        r += 0.1 * np.cos(rng.integers(2, 5) * np.arccos(np.clip(d @ k, -1, 1)))
    verts = np.vstack(((d * r[..., None] * [1.0, 0.75, 0.55]).reshape(-1, 3),
                       [[0, 0, 0.55], [0, 0, -0.55]]))
    idx = np.arange(len(theta) * len(phi)).reshape(len(theta), len(phi))
    a, b = idx[:-1], idx[1:]
    a2, b2 = np.roll(a, -1, axis=1), np.roll(b, -1, axis=1)
    top, bottom = len(verts) - 2, len(verts) - 1
    faces = np.concatenate((np.stack((a, b, b2), -1).reshape(-1, 3),
                            np.stack((a, b2, a2), -1).reshape(-1, 3),
                            np.stack((np.full(len(phi), top), idx[0], np.roll(idx[0], -1)), 1),
                            np.stack((np.full(len(phi), bottom), np.roll(idx[-1], -1), idx[-1]),
                                     1)))
    return verts[faces]


def test_every_pose_of_a_fine_mesh_stands_where_it_rests():
    """Regression: a fine mesh's vertices just below a face must not pass for a curved
    surface when the verdict re-measures edges near the foot."""
    body = MeshSolid(blob_mesh(), density=1000.0)
    ps = resting_poses(body)
    assert ps.method == "exact" and len(ps) > 3
    for p in ps.poses:
        v = check(body, p.down)
        assert v.verdict == "stands" and v.support.kind == "polygon"
        if p.kind == "face":  # a rocker's tilt is its bowl's, not its lowest face's
            assert v.critical_tilt_deg == pytest.approx(p.critical_tilt_deg, rel=1e-6, abs=1e-9)
        else:
            # at least the lowest face's tilt: equal to it (to round-off) when the bowl's
            # edge is that face's
            assert p.kind == "rocking"
            assert p.critical_tilt_deg >= v.critical_tilt_deg * (1 - 1e-12)


def test_a_bowl_rocks_back_and_a_cylinder_rolls():
    """Sampled curved surfaces: the bottom of a bowl is a stable pose whose critical tilt is
    where the rocker's equilibrium ends (asin(d/R) for a ball whose centre of mass is d from
    the centre of its radius-R surface); a cylinder's side is one neutral, rolling pose."""
    from plumbob.bodies.primitives import cylinder, hemisphere

    dome = [p for p in resting_poses(hemisphere(1.0)) if p.down[2] > 0.9]
    assert len(dome) == 1 and not dome[0].neutral
    assert dome[0].com_height == pytest.approx(1 - 3 / 8, abs=1e-3)
    assert dome[0].critical_tilt_deg == pytest.approx(np.degrees(np.arcsin(3 / 8)), abs=1.0)
    side = [p for p in resting_poses(cylinder(0.5, 2.0)) if abs(p.down[2]) < 0.1]
    assert len(side) == 1 and side[0].neutral and side[0].critical_tilt_deg == 0.0


def test_a_weighted_ball_has_one_self_righting_pose():
    from plumbob.bodies.csg import difference, union
    from plumbob.bodies.primitives import sphere

    shell = difference(sphere(1.0, density=100.0), sphere(0.3).translated([0, 0, -0.5]))
    # the ballast a hair smaller than its cavity: coincident spheres cost the boolean seconds
    ball = union(shell, sphere(0.2999, density=10_000.0).translated([0, 0, -0.5]))
    d = -ball.mass_properties().center_of_mass[2]
    poses = resting_poses(ball)
    assert len(poses) == 1 and not poses[0].neutral
    assert poses[0].probability == pytest.approx(1.0)
    assert np.degrees(np.arccos(-poses[0].down[2])) < 2.0
    assert poses[0].critical_tilt_deg == pytest.approx(np.degrees(np.arcsin(d)), abs=1.0)


# -------------------------------------------------------- the pieces, one at a time
def test_a_cubes_hull_has_six_faces_and_paired_edges():
    h = build_hull3(CUBE - 0.5, 1e-12)
    assert len(h.normals) == 6 and len(h.ea) == 24  # qhull's 12 triangles merged in pairs
    assert np.allclose(h.heights, 0.5) and np.allclose(h.areas, 1.0)
    assert np.array_equal(h.ea[h.twin], h.eb) and np.array_equal(h.eb[h.twin], h.ea)
    assert np.array_equal(h.ef[h.twin], h.eg) and np.array_equal(h.und, h.und[h.twin])
    assert np.array_equal(h.degree, np.full(8, 3))
    assert sorted(map(tuple, h.normals.round(12))) == sorted(
        map(tuple, np.vstack((np.eye(3), -np.eye(3)))))


def test_physical_faces_merge_what_is_coplanar_within_the_tolerance():
    """A cube whose top is bent by 1e-9 m along a diagonal: two exact faces there, one
    physical face at a tolerance of 1e-6 m, and still two at 1e-12 m."""
    X = CUBE - 0.5
    X[7, 2] += 1e-9
    h = build_hull3(X, 1e-14)
    assert len(h.normals) == 7
    tops = np.flatnonzero(h.normals[:, 2] > 0.5)
    assert len(tops) == 2
    pf = physical_faces(h, tops, 1e-6)
    assert sorted(pf.face[pf.owner == 0].tolist()) == sorted(tops.tolist())
    assert pf.same.shape[1] == 2  # each takes in the other
    assert np.all(pf.margin > 0.49)  # the foot lies half a side inside the whole top
    assert len(pf.corners(h, 0)) == 4
    tight = physical_faces(h, tops, 1e-12)
    assert np.array_equal(tight.face, tops) and tight.same.shape[1] == 0


def test_each_face_of_a_regular_tetrahedron_has_a_quarter_of_the_sphere():
    h = build_hull3(TETRA, 1e-12)
    found = basins3(h, 1e-12, None)
    assert found is not None and found.roller.stable.all()
    assert np.allclose(found.area / (4 * np.pi), 0.25, rtol=0, atol=1e-14)
    assert len(found.saddles) == 6 and found.error < 1e-14
    sampled = sampled_basins(h, found.roller, 20_000)
    assert sampled.sum() == pytest.approx(4 * np.pi)
    assert np.allclose(sampled / (4 * np.pi), 0.25, atol=2e-3)


def test_the_roller_lands_every_face_on_a_stable_one():
    X, com = random_body(3, 40)
    h = build_hull3(X - com, 1e-12)
    roller = basins3(h, 1e-12, None).roller
    sinks = roller.sinks(np.arange(len(h.normals)))
    assert roller.stable[sinks].all()
    assert np.array_equal(sinks[roller.stable], np.flatnonzero(roller.stable))


def test_a_square_laminas_landscape_is_four_quarter_arcs():
    land = landscape2(CUBE[[0, 2, 6, 4], :2] - 0.5, 1e-9)
    assert len(land.area) == 4 and np.allclose(land.area, np.pi / 2, rtol=0, atol=1e-15)
    assert len(land.sh) == 4 and np.allclose(land.sh, np.sqrt(0.5))
    assert np.allclose(land.margin, 0.5) and land.corners(0).shape == (2, 2)


def test_the_spherical_triangle_of_an_octant():
    x, y, z = np.eye(3)
    assert solid_angle(x, y, z) == pytest.approx(np.pi / 2)
    assert solid_angle(x, z, y) == pytest.approx(-np.pi / 2)


# ------------------------------------------------------------------ the result
def test_as_dict_is_the_json_of_the_command():
    ps = poses_from_points(CUBE, [0.5, 0.5, 0.5], mass=2.0)
    out = ps.as_dict()
    assert list(out) == ["mass", "center_of_mass", "g", "method", "hull_faces", "poses"]
    assert out["mass"] == 2.0 and out["hull_faces"] == 6 and len(out["poses"]) == 6
    assert list(out["poses"][0]) == ["down", "com_height", "probability", "critical_tilt_deg",
                                      "energy_barrier", "kind", "neutral", "members", "axis",
                                      "face", "transform"]
    assert out["poses"][0]["probability"] == ps[0].probability
    with_notes = resting_poses(cylinder(1.0, 2.0)).as_dict()
    assert list(with_notes)[-1] == "notes" and any("rolling" in n for n in with_notes["notes"])


def test_reprs_are_one_short_line():
    ps = resting_poses(cylinder(1.0, 2.0))
    text = repr(ps)
    assert text.startswith("Poses(3 pose(s), probabilities=(") and "method='exact'" in text
    assert "\n" not in text and len(text) < 200
    side = repr(ps[0])
    assert side.startswith("Pose(probability=") and "rolling about (0, 0, 1)" in side
    assert len(side) < 200
    assert "face=" not in side and "array" not in side  # no array dump


def test_a_pose_by_its_rank():
    """``Poses.ranked(k)`` is the k-th most probable (1-based, as --pose takes it); a rank
    out of range names what was asked."""
    from plumbob.stability.poses import resting_poses

    poses = resting_poses(box(1, 2, 3, density=1.0))
    assert poses.ranked(1) is poses[0] and poses.ranked(len(poses)) is poses[-1]
    with pytest.raises(StabilityError, match="--pose must be between 1 and 6"):
        poses.ranked(7, "--pose")
    with pytest.raises(StabilityError):
        poses.ranked(0)


def _physical_faces_by_search(h, sinks, tol):
    """Each sink's physical face by a plain breadth-first search: from a face, on to
    each neighbour across an edge that faces the sink's way and whose corners all lie
    within ``tol`` of the sink's plane."""
    corners = [np.unique(h.ea[h.ef == f]) for f in range(len(h.normals))]
    pairs = []
    for k, s in enumerate(sinks):
        n, d = h.normals[s], h.heights[s]
        reached, todo = {int(s)}, [int(s)]
        while todo:
            f = todo.pop()
            for g in h.eg[h.ef == f].tolist():
                if g not in reached and h.normals[g] @ n > 0 and \
                        np.all(d - h.X[corners[g]] @ n <= tol):
                    reached.add(g)
                    todo.append(g)
        pairs += [(k, g) for g in sorted(reached)]
    return np.array(pairs).T


@pytest.mark.parametrize("seen_flags", [1 << 24, 0])
def test_physical_faces_are_the_faces_a_plain_search_reaches(seen_flags, monkeypatch):
    """Boxes with finely tessellated, slightly rippled sides (hundreds of exact faces, a
    few sinks): the physical faces, by the flags of the (sink, face) pairs reached or by
    their sorted keys, are the ones a plain search reaches, at every tolerance."""
    monkeypatch.setattr(faces_module, "SEEN_FLAGS", seen_flags)
    rng = np.random.default_rng(7)
    t = np.linspace(-1.0, 1.0, 7)
    u, v = (a.ravel() for a in np.meshgrid(t, t))
    w = 1 + 1e-6 * (2 - u * u - v * v) + 1e-8 * rng.standard_normal(len(u))  # bulged
    sides = [np.stack(p, axis=1) for s in (-w, w) for p in ((u, v, s), (u, s, v), (s, u, v))]
    h = build_hull3(np.concatenate(sides) * [1.0, 0.8, 0.6], 1e-14)
    assert len(h.normals) > 300
    sinks = np.arange(0, len(h.normals), 29)
    for tol in (1e-9, 1e-6, 3e-6, 1e-5, 1e-3):
        pf = physical_faces(h, sinks, tol)
        want = _physical_faces_by_search(h, sinks, tol)
        assert np.array_equal(np.stack((pf.owner, pf.face)), want), tol
        assert pf.boundary_owner.tolist() == sorted(pf.boundary_owner.tolist())
