"""Surface area and bounding boxes against closed forms, and invariant under rigid motions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from plumbob.bodies import primitives as P
from plumbob.bodies.measures import bounding_box, oriented_bounding_box, surface_area
from plumbob.errors import GeometryError

R, H = 0.3, 0.7
CURVED = [
    (P.sphere(R), 4 * math.pi * R ** 2),
    (P.cylinder(R, H), 2 * math.pi * R * (R + H)),
    (P.cone(R, H), math.pi * R * (R + math.hypot(R, H))),
    (P.torus(2 * R, R / 3), 4 * math.pi ** 2 * 2 * R * R / 3),
]


@pytest.mark.parametrize("segments", [16, 64, 256, 512])  # 512: a torus of 0.5M triangles
@pytest.mark.parametrize(("body", "true"), CURVED, ids=["sphere", "cylinder", "cone", "torus"])
def test_the_stated_bound_covers_the_faceting_of_curved_faces(body, true, segments):
    area = surface_area(body, segments)
    assert not area.exact
    assert abs(area.area / true - 1) <= area.relative_error


def test_polytopes_are_exact():
    """A 1 × 2 × 3 box: 2(2 + 3 + 6) = 22 m²; a box with a box hole adds the hole's walls."""
    assert surface_area(P.box(1, 2, 3)) .as_dict() == {
        "surface_area": pytest.approx(22.0, rel=1e-15), "surface_area_exact": True,
        "surface_area_relative_error": 0.0}
    import plumbob

    tube = plumbob.difference(P.box(2, 2, 1), P.box(1, 1, 3).translated([0.5, 0.5, -1]))
    area = surface_area(tube)
    assert area.exact and area.area == pytest.approx(2 * (4 - 1) + 4 * 2 + 4 * 1, rel=1e-12)


def test_a_lamina_has_no_surface_area():
    with pytest.raises(GeometryError, match="no surface area"):
        surface_area(P.rectangle(1, 2))


@settings(max_examples=25, deadline=None)
@given(angles=st.tuples(*[st.floats(-math.pi, math.pi)] * 3),
       offset=st.tuples(*[st.floats(-1e6, 1e6)] * 3))
def test_area_and_oriented_box_do_not_change_under_rigid_motions(angles, offset):
    """Far from the origin too: the sum is taken about a local origin."""
    body = P.box(1.0, 2.0, 3.0)
    moved = body.transformed(Rotation.from_euler("xyz", angles).as_matrix(), np.array(offset))
    assert surface_area(moved).area == pytest.approx(22.0, rel=1e-9)
    box = oriented_bounding_box(moved)
    assert sorted(box.extents) == pytest.approx([1.0, 2.0, 3.0], rel=1e-9)
    centre = moved.mass_properties().center_of_mass
    assert box.center == pytest.approx(centre, rel=1e-9, abs=1e-9 * (1 + np.abs(centre).max()))
    assert box.axes @ box.axes.T == pytest.approx(np.eye(3), abs=1e-12)


def test_axis_aligned_box_and_a_centred_box():
    """``box(..., centered=True)`` is the same box with its centre on the origin: the
    same inertia, the bounding box ±half its extents."""
    centred, corner = P.box(1, 2, 3, centered=True, density=5.0), P.box(1, 2, 3, density=5.0)
    a, b = centred.mass_properties(), corner.mass_properties()
    assert a.center_of_mass.tolist() == [0.0, 0.0, 0.0]
    assert a.inertia == pytest.approx(b.inertia, rel=1e-14)
    box = bounding_box(centred)
    assert box.lower.tolist() == [-0.5, -1.0, -1.5] and box.upper.tolist() == [0.5, 1.0, 1.5]
    assert box.volume == pytest.approx(6.0, rel=1e-15)
    ball = bounding_box(P.sphere(R).translated([1.0, 2.0, 3.0]))  # its poles, exactly
    assert ball.lower == pytest.approx(np.array([1.0, 2.0, 3.0]) - R, rel=1e-15)
    assert ball.upper == pytest.approx(np.array([1.0, 2.0, 3.0]) + R, rel=1e-15)
    ring = bounding_box(P.torus(2 * R, R / 3))
    assert ring.extents == pytest.approx([2 * (2 * R + R / 3)] * 2 + [2 * R / 3], rel=1e-14)


@pytest.mark.parametrize(("body", "support"), [
    (P.sphere(R), lambda u: R * np.ones(len(u))),
    (P.cylinder(R, H), lambda u: R * np.hypot(u[:, 0], u[:, 1]) + np.maximum(H * u[:, 2], 0)),
    (P.torus(2 * R, R / 3), lambda u: 2 * R * np.hypot(u[:, 0], u[:, 1]) + R / 3),
], ids=["sphere", "cylinder", "torus"])
@pytest.mark.parametrize("tolerance", [1e-3, 1e-4])
def test_hull_points_are_within_their_tolerance_of_the_body_in_every_direction(
        body, support, tolerance):
    """The promise of ``Body.hull_points``: no point of the body further than the
    tolerance outside the points' hull, so no support distance short by more (the
    closed-form support functions of the sphere, the cylinder on z = 0 and the torus)."""
    directions = np.random.default_rng(5).normal(size=(4000, 3))
    directions = np.vstack((directions, np.eye(3), -np.eye(3)))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    points = body.hull_points(tolerance)
    reach = (points @ directions.T).max(axis=0)
    assert (reach <= support(directions) + 1e-12).all()
    assert (support(directions) - reach).max() <= tolerance
