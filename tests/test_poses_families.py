"""Poses a person can use: physical faces that float32 noise never splits, rolling
families of tessellated surfaces of revolution, and monotone tolerances (issue 11)."""

import os

import numpy as np
import pytest
import trimesh
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.primitives import box
from plumbob.bodies.solid import MeshSolid
from plumbob.loading import read
from plumbob.stability import poses_from_points, resting_poses


def mesh_body(mesh: trimesh.Trimesh) -> MeshSolid:
    return MeshSolid(np.asarray(mesh.triangles, dtype=float))


def float32_stl(tmp_path, mesh: trimesh.Trimesh, name: str = "part.stl") -> str:
    """``mesh`` written by trimesh as a binary STL: float32 coordinates."""
    path = str(tmp_path / name)
    mesh.export(path)
    return path


def rigid(angles, offset) -> np.ndarray:
    T = trimesh.transformations.euler_matrix(*angles)
    T[:3, 3] = offset
    return T


# ------------------------------------------------------------ acceptance meshes
def test_a_64_sided_cylinder_rests_on_two_ends_or_rolls_on_its_side():
    ps = resting_poses(mesh_body(trimesh.creation.cylinder(0.5, 2.0, sections=64)))
    assert len(ps) == 3 and ps.probabilities.sum() == pytest.approx(1.0, abs=1e-12)
    side = [p for p in ps.poses if p.kind == "rolling"]
    ends = [p for p in ps.poses if p.kind == "face"]
    assert len(side) == 1 and len(ends) == 2 and side[0].members == 64
    assert np.allclose(np.abs(side[0].axis), [0, 0, 1], atol=1e-9)
    assert side[0].critical_tilt_deg == 0 and side[0].neutral
    # the side's probability is the sum of its 64 facets' (the exact basins, unmerged)
    exact = resting_poses(mesh_body(trimesh.creation.cylinder(0.5, 2.0, sections=64)),
                          roll_angle_deg=0)
    assert len(exact) == 66
    flat = [p.probability for p in exact.poses if abs(p.down[2]) < 1e-9]
    assert side[0].probability == pytest.approx(sum(flat), rel=1e-12)


def test_a_cone_rolls_round_its_apex_about_its_axis():
    ps = resting_poses(mesh_body(trimesh.creation.cone(1.0, 2.0, sections=48)))
    kinds = sorted(p.kind for p in ps.poses)
    assert kinds == ["face", "rolling"]
    rolling = [p for p in ps.poses if p.kind == "rolling"][0]
    assert np.allclose(np.abs(rolling.axis), [0, 0, 1], atol=1e-9)


def test_a_capsule_is_its_rolling_side_and_at_most_its_two_ends():
    ps = resting_poses(mesh_body(trimesh.creation.capsule(height=2.0, radius=0.5,
                                                          count=[32, 32])))
    rolling = [p for p in ps.poses if p.kind == "rolling"]
    assert len(rolling) == 1 and len(ps) <= 3
    assert np.allclose(np.abs(rolling[0].axis), [0, 0, 1], atol=1e-6)
    assert ps.probabilities.sum() == pytest.approx(1.0, abs=1e-12)


def test_a_tessellated_ball_is_one_rolling_pose_without_an_axis():
    ps = resting_poses(mesh_body(trimesh.creation.icosphere(subdivisions=4)))
    assert len(ps) == 1 and ps[0].kind == "rolling" and ps[0].axis is None
    assert ps[0].probability == 1.0 and ps[0].critical_tilt_deg == 0


@settings(max_examples=12, deadline=None)
@given(st.tuples(*[st.floats(-np.pi, np.pi)] * 3), st.tuples(*[st.floats(-50, 50)] * 3))
def test_a_rotated_1x2x3_box_stored_as_float32_has_exactly_six_poses(tmp_path_factory,
                                                                       angles, offset):
    mesh = trimesh.creation.box((1.0, 2.0, 3.0))
    mesh.apply_transform(rigid(angles, offset))
    path = float32_stl(tmp_path_factory.mktemp("box"), mesh)
    ps = resting_poses(read(path).body)
    assert len(ps) == 6 and all(p.kind == "face" for p in ps.poses)
    reference = resting_poses(box(1, 2, 3)).probabilities
    assert np.allclose(ps.probabilities, reference, atol=1e-6)


def test_quasi_static_values_of_a_cube_and_a_tetrahedron_stay():
    cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    assert np.allclose(poses_from_points(cube, [0.5] * 3).probabilities, 1 / 6, atol=1e-13)
    tetra = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    assert np.allclose(poses_from_points(tetra, [0, 0, 0]).probabilities, 0.25, atol=1e-13)


# ----------------------------------------------------------------- monotone
def irregular_prism(seed: int, n: int = 64) -> tuple[np.ndarray, np.ndarray]:
    """A 64-sided prism with irregular sides (angles and radii jittered) and a centre of
    mass off its axis: its sides merge into physical faces as the tolerance grows past
    their few-millimetre bends, and into families as the roll angle grows, a few at a
    time."""
    rng = np.random.default_rng(seed)
    k = (np.arange(n) + rng.uniform(-0.2, 0.2, n)) * 2 * np.pi / n
    r = 0.5 * (1 + rng.uniform(-1e-3, 1e-3, n))
    ring = np.stack((r * np.cos(k), r * np.sin(k)), axis=1)
    X = np.vstack([np.column_stack((ring, np.full(n, z))) for z in (-1.0, 1.0)])
    return X, rng.normal(size=3) * [0.02, 0.02, 0.1]


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.lists(st.floats(1e-8, 5e-2), min_size=2, max_size=6),
       st.sampled_from([0.0, 15.0]))
def test_more_tolerance_never_gives_more_poses(seed, tolerances, roll):
    X, com = irregular_prism(seed)
    counts = [len(poses_from_points(X, com, tolerance=t, roll_angle_deg=roll))
              for t in sorted(tolerances)]
    assert counts == sorted(counts, reverse=True)
    if roll == 0 and min(tolerances) < 1e-4 and max(tolerances) > 3e-2:
        assert counts[-1] * 3 <= counts[0]  # the test is not vacuous: sides do merge


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.lists(st.floats(0.0, 40.0), min_size=2, max_size=5),
       st.booleans())
def test_a_larger_roll_angle_never_gives_more_poses(seed, angles, prism):
    if prism:
        X, com = irregular_prism(seed)
    else:
        rng = np.random.default_rng(seed)
        X = rng.normal(size=(40, 3)) * [1.0, 0.8, 0.6]
        com = rng.dirichlet(np.full(40, 4.0)) @ X
    results = [poses_from_points(X, com, roll_angle_deg=a) for a in sorted(angles)]
    counts = [len(r) for r in results]
    assert counts == sorted(counts, reverse=True)
    for r in results:
        assert r.probabilities.sum() == pytest.approx(1.0, abs=1e-12)
    if prism and min(angles) == 0 and max(angles) > 20:
        assert counts[-1] * 4 <= counts[0]  # the test is not vacuous: the sides join


def test_float32_noise_never_splits_a_face(tmp_path):
    """A faceted body far from the origin, stored as float32: each flat face stays one
    pose (the exact hull sees each of its triangles apart, 1e-7 rad off)."""
    mesh = trimesh.creation.cylinder(0.5, 2.0, sections=10)  # a decagonal prism
    mesh.apply_transform(rigid((0.3, -1.2, 0.7), (300.0, -120.0, 45.0)))
    body = read(float32_stl(tmp_path, mesh)).body
    ps = resting_poses(body, roll_angle_deg=0)
    assert len(ps) == 12 and all(p.kind == "face" for p in ps.poses)
    # every side is its whole rectangle (not one of its two triangles), every end its
    # decagon, so the tilts are the exact prism's: atan(apothem·tan 18° / apothem) = 18°
    sides = [p for p in ps.poses if len(p.face) == 4]
    assert len(sides) == 10 and len([p for p in ps.poses if len(p.face) == 10]) == 2
    assert all(p.critical_tilt_deg == pytest.approx(18.0, abs=0.01) for p in sides)


def test_a_fine_sphere_is_fast_and_rolls():
    """Issue 10: a 360k-triangle sphere took over 120 s (a pose per facet); a fine ball
    is one rolling pose, and the work after the hull is linear-ish."""
    import time

    mesh = trimesh.creation.icosphere(subdivisions=6)  # 81 920 triangles
    body = mesh_body(mesh)
    start = time.perf_counter()
    ps = resting_poses(body)
    assert time.perf_counter() - start < 20.0  # seconds, on a loaded 2-core machine
    assert len(ps) == 1 and ps[0].kind == "rolling" and ps[0].members > 80_000


def _rocker_points(seed: int, flat: bool, n: int = 700) -> tuple[np.ndarray, np.ndarray]:
    """A lumpy rim of ``n`` points about a centre off their middle (or, ``flat``, points
    on a box's faces) and a random ``down``: the rocker's test inputs."""
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(n, 3))
    X /= np.linalg.norm(X, axis=1)[:, None]
    X = X * [1.0, 0.8, 0.6] + [0.0, 0.0, 0.15] + rng.normal(size=X.shape) * 0.01
    if flat:
        half, rows = np.array([1.0, 0.7, 0.4]), np.arange(len(X))
        axis = rng.integers(0, 3, len(X))
        X = rng.uniform(-1.0, 1.0, size=X.shape) * half
        X[rows, axis] = np.where(rng.random(len(X)) < 0.5, -1.0, 1.0) * half[axis]
        X += [0.05, -0.1, 0.1]
    down = rng.normal(size=3)
    return X, down / np.linalg.norm(down)


@settings(max_examples=8, deadline=None)
@given(st.integers(0, 10_000), st.floats(1e-5, 1e-1), st.booleans(), st.booleans())
def test_the_rockers_candidate_filter_drops_nothing(seed, eps, flat, binned):
    """rocking() sweeps only the points its exact filter keeps (those near the rim of the
    projected hull): the same heights and tilts as sweeping every point. ``flat``: a
    box's corners and the points of its faces, whose projections leave wide sectors of
    angle without a point and hold many points within eps of the support at once.
    ``binned``: the crest-angle bins' filter (else the intervals', as for few points)."""
    import plumbob.stability.rocking as rocking_module
    import plumbob.stability.sweep as sweep_module

    X, down = _rocker_points(seed, flat)  # a rim of some hundred points to keep
    threshold = sweep_module.BINNED
    try:
        sweep_module.BINNED = 0 if binned else 10**9
        fast = rocking_module.rocking(X, down, eps, azimuths=6)
    finally:
        sweep_module.BINNED = threshold
    keep = rocking_module._sweep_pairs
    try:  # every point at every angle of the sweep
        rocking_module._sweep_pairs = lambda a, B, alpha, eps, planes=None: [(
            np.repeat(np.arange(len(alpha)), len(a)), np.tile(np.arange(len(a)), len(alpha)))
        ] * len(B)
        slow = rocking_module.rocking(X, down, eps, azimuths=6)
    finally:
        rocking_module._sweep_pairs = keep
    # The same points reach the support, but through matrix products of other shapes
    # (BLAS picks its kernel and its order of summation by size), so each height
    # u·p, a sum of 3 products with |u| = 1, may differ by its round-off: at most
    # 3 ulps of the largest |p|₁ (Higham's γ₃), both ways.
    ulp = np.finfo(float).eps
    bound = 2 * 3 * ulp * float(np.abs(X).sum(axis=1).max())
    assert np.max(np.abs(fast.heights - slow.heights)) <= bound
    # A tilt is the arccos of u·c / |c|, c the mean of at most len(X) contact points
    # (each within eps of the support, so |c| >= the lowest height less eps): its cosine
    # may differ by γ_(len(X)+8) |p|max / |c|; then d(theta) = d(cos) / sin(theta), and
    # at most sqrt(2 d(cos)) near 0.
    reach = float(np.linalg.norm(X, axis=1).max())
    slack = (len(X) + 8) * ulp * reach / (float(slow.heights.min()) - eps)
    theta = np.radians(slow.tilts_deg)
    allowed = np.degrees(np.minimum(slack / np.maximum(np.sin(theta), 1e-300),
                                    np.sqrt(2 * slack)))
    assert np.all(np.abs(fast.tilts_deg - slow.tilts_deg) <= allowed)


@settings(max_examples=8, deadline=None)
@given(st.integers(0, 10_000), st.floats(1e-4, 1e-1), st.booleans(), st.integers(0, 600),
       st.floats(0.05, 2.0))
def test_each_ways_own_candidates_give_every_ways_pairs(seed, eps, flat, first, width):
    """candidate_pairs() with each way its own candidates (those its cone keeps, and
    some others) finds, at every angle of an arc, the contact interval_pairs() finds
    from every point for every way: the same points within eps of the support, summed
    in the same order (so the same θ, to the bit)."""
    from plumbob.stability.rocking import _contact_angles, _directions, _on_arcs
    from plumbob.stability.sweep import candidate_pairs, interval_pairs

    X, down = _rocker_points(seed, flat)
    rng = np.random.default_rng(seed)
    directions = _directions(down, 5)
    stop = min(720, first + 2 + int(width / 0.25))  # two angles at least, as swept
    arc = np.radians(np.arange(0.0, 180.0, 0.25))[first:stop]
    a, B = X @ down, directions @ X.T
    keep = _on_arcs(a, B, arc, eps + 1e-9 * float(np.abs(X).max()))
    keep |= rng.random(keep.shape) < 0.05  # candidates beyond a way's cone change nothing
    way, point = np.nonzero(keep)
    cuts = np.searchsorted(way, np.arange(len(directions) + 1))
    own = candidate_pairs(a[point], B[way, point], cuts, point, arc, eps)
    every = interval_pairs(a, B, arc, eps)
    _, theta_own = _contact_angles(X, down, directions, arc, eps, own)
    _, theta_every = _contact_angles(X, down, directions, arc, eps, every)
    assert np.array_equal(theta_own, theta_every)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.floats(1e-6, 1e-1), st.booleans(), st.integers(0, 700),
       st.floats(0.05, 125.0), st.floats(0.0, 2.0 * np.pi))
def test_one_ways_cut_keeps_the_cones_points(seed, eps, flat, first, width, azimuth):
    """_on_arc() finds a way's candidates among the points within _cone_cut() of the top
    along its arc's middle direction: exactly the points _on_arcs() keeps, in order, for
    arcs up to 120° wide (wider ones are _on_arcs' alone), on blobs and boxes' faces."""
    from plumbob.arrays import dot
    from plumbob.stability.rocking import _across, _cone_cut, _on_arc, _on_arcs

    X, down = _rocker_points(seed, flat)
    t1, t2 = _across(down)
    direction = np.cos(azimuth) * t1 + np.sin(azimuth) * t2
    stop = min(720, first + 2 + int(width / 0.25))
    arc = np.radians(np.arange(0.0, 180.0, 0.25))[first:stop]
    reach = eps + 1e-9 * float(np.abs(X).max())
    a, b = X @ down, X @ direction
    radius = float(np.sqrt(dot(X, X).max()))
    plain = np.flatnonzero(_on_arcs(a, b[None, :], arc, reach)[0])
    if _cone_cut(arc, reach, radius) is None:
        assert arc[-1] - arc[0] > np.radians(119.9)
        return
    assert np.array_equal(_on_arc(a, b, arc, reach, radius), plain)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.floats(1e-6, 1e-1), st.booleans(), st.floats(0.0, 1.2))
def test_the_cone_about_down_cut_keeps_its_points(seed, eps, flat, half):
    """_near_down() given the points' radius measures only the points within _cut() of
    the top along down, and keeps exactly the points it keeps measuring every one."""
    from plumbob.arrays import dot
    from plumbob.stability.rocking import _across, _near_down

    X, down = _rocker_points(seed, flat)
    reach = eps + 1e-9 * float(np.abs(X).max())
    a, across = X @ down, X @ _across(down).T
    radius = float(np.sqrt(dot(X, X).max()))
    assert np.array_equal(_near_down(a, across, half, reach, radius),
                          _near_down(a, across, half, reach))


@settings(max_examples=12, deadline=None)
@given(st.integers(0, 10_000), st.floats(1e-4, 1e-1), st.booleans(),
       st.sampled_from([np.inf, np.nan, 0.5, 1.5, 3.0, 15.0]))
def test_the_least_tilt_is_the_whole_sweeps(seed, eps, flat, cap):
    """least_tilt() sweeps a way only while it can still lower the least tilt, and only
    the points that can reach the support on its arcs (each way's own candidates,
    within one cone about down for many ways): min(cap, the whole sweep's least tilt)
    all the same, under a low cap (fewer first angles) or none."""
    import plumbob.stability.rocking as rocking_module

    X, down = _rocker_points(seed, flat)
    fast = rocking_module.least_tilt(X, down, eps, cap_deg=cap)
    whole = rocking_module.rocking(X, down, eps)
    expected = min(float(whole.tilts_deg.min()), cap)  # a NaN cap: no cap, as min() reads it
    # The same points reach the support at every angle swept; the contact's mean may be
    # summed in another order, so its cosine may differ by γ_(len(X)+8) |p|max / |c|
    # (as in the filter's test above), the tilt by that over sin(θ), or sqrt(2 d) at 0.
    ulp = np.finfo(float).eps
    slack = ((len(X) + 8) * ulp * float(np.linalg.norm(X, axis=1).max())
             / (float(whole.heights.min()) - eps))
    theta = np.radians(expected)
    allowed = np.degrees(min(slack / max(np.sin(theta), 1e-300), np.sqrt(2 * slack)))
    assert abs(fast - expected) <= allowed


def test_the_least_tilt_of_a_plane_rocker():
    """A lamina rocks two ways: least_tilt() is the least of rocking()'s two tilts."""
    from plumbob.stability.rocking import least_tilt, rocking

    t = np.linspace(0.0, 2 * np.pi, 400, endpoint=False)
    X = np.stack([1.3 * np.cos(t), np.sin(t) + 0.4 * np.cos(2 * t)], axis=1) - [0.1, 0.2]
    down = np.array([0.0, -1.0])
    whole = float(rocking(X, down, 1e-3).tilts_deg.min())
    assert 0.0 < whole < 90.0
    assert least_tilt(X, down, 1e-3) == pytest.approx(whole, rel=1e-12)
    assert least_tilt(X, down, 1e-3, cap_deg=whole / 2) == whole / 2


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 10_000), st.integers(1, 3000), st.integers(1, 60), st.booleans())
def test_group_max_is_numpys_maximum_at(seed, n, groups, ties):
    """The rocker's group maxima (a power sum picks the few values that can be largest)
    are np.maximum.at's, to the bit: negative values, ties, empty groups, values far
    below the largest."""
    from plumbob.stability.sweep import group_max

    rng = np.random.default_rng(seed)
    values = rng.normal(size=n) * 10.0 ** rng.integers(-3, 3, size=n)
    if ties:
        values = np.round(values, 1)
    key = rng.integers(0, groups, size=n)
    expected = np.full(groups, -np.inf)
    np.maximum.at(expected, key, values)
    assert np.array_equal(group_max(values, key, groups), expected)


def test_the_least_tilt_loads_no_more_of_numpy():
    """least_tilt() runs in `plumbob poses`, whose start-up is held to what it uses
    (tests/test_startup.py): sweeping every way on a lumpy rim leaves numpy.ma (which
    np.unique imports) unloaded, and the verdict's Rocking result (its frozen dataclass,
    in plumbob.stability.rocking_result) uncreated."""
    import subprocess
    import sys

    from conftest import ROOT

    code = ("import sys, numpy as np\n"
            "from plumbob.stability.rocking import least_tilt\n"
            "rng = np.random.default_rng(0)\n"
            "X = rng.normal(size=(700, 3))\n"
            "X /= np.linalg.norm(X, axis=1)[:, None]\n"
            "X = X * [1.0, 0.8, 0.6] + [0.0, 0.0, 0.15] + rng.normal(size=X.shape) * 0.05\n"
            "tilt = least_tilt(X, np.array([0.0, 0.0, -1.0]), 0.01)\n"
            "print(tilt, 'numpy.ma' in sys.modules,\n"
            "      'plumbob.stability.rocking_result' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=60, env=dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src")))
    assert out.returncode == 0, out.stderr
    tilt, loaded, result = out.stdout.split()
    assert 0.0 < float(tilt) < 90.0 and loaded == "False" and result == "False"
