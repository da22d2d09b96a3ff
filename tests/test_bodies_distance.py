"""Exact distances from points to a mesh's surface (bodies/distance.SurfaceDistance, the
AABB tree behind the level-set offsets and the hollowing walls), against brute force:
every triangle measured (Ericson's closest point, point_triangle_distances), and against
trimesh's closest points."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.distance import SurfaceDistance, point_triangle_distances


def _brute(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    return point_triangle_distances(points[:, None, :], triangles[None]).min(axis=1)


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**31 - 1), far=st.sampled_from([0.0, 1e3, -5e4]),
       scale=st.sampled_from([1e-3, 1.0]))
def test_the_distance_is_the_least_over_every_triangle(seed, far, scale):
    """A soup of random triangles (slivers and large ones among them), far from the
    origin or not: the tree's distance is the least of all, to the round-off of the
    coordinates' size, and its nearest point is at that distance."""
    rng = np.random.default_rng(seed)
    triangles = rng.normal(size=(40, 3, 3)) * scale * rng.uniform(0.01, 1, (40, 1, 1))
    triangles += rng.normal(size=(40, 1, 3)) * scale + far
    points = rng.normal(size=(60, 3)) * 2 * scale + far
    distance, nearest = SurfaceDistance(triangles).query(points)
    # relative to the coordinates' size: far from the origin both carry its round-off
    slack = 1e-12 * (abs(far) + scale)
    assert np.allclose(distance, _brute(points - far, triangles - far), rtol=1e-9, atol=slack)
    assert np.allclose(np.linalg.norm(points - nearest, axis=1), distance, rtol=1e-9, atol=slack)


def test_a_closed_mesh_against_brute_force_and_trimesh():
    """Points inside and outside a faceted ball: the least over every triangle; trimesh's
    closest points (a candidate search of its own) are never nearer, and agree but for
    the few points where its candidates miss the nearest triangle (3 of these 300, by up
    to 23 µm on a 20 mm ball)."""
    import trimesh

    mesh = trimesh.creation.icosphere(subdivisions=3, radius=0.02)
    points = np.random.default_rng(1).uniform(-0.03, 0.03, (300, 3))
    distance = SurfaceDistance(mesh.triangles).distances(points)
    assert np.allclose(distance, _brute(points, mesh.triangles), rtol=0, atol=1e-15)
    _, theirs, _ = trimesh.proximity.closest_point(mesh, points)
    assert np.all(distance <= theirs + 1e-15)
    assert np.mean(np.abs(distance - theirs) <= 1e-12) >= 0.95
