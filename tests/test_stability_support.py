"""Support polygons: contact with the plane, ground frames, degenerate supports."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from plumbob.bodies.csg import union
from plumbob.bodies.particles import ParticleSystem
from plumbob.bodies.primitives import box, cylinder, disc, polygon, pyramid, sphere
from plumbob.errors import StabilityError
from plumbob.massprops import point_mass, rotation_matrix
from plumbob.stability.support import ground_frame, support_polygon, unit_vector

A = np.sqrt(3) / 2  # the seed's sculpture, Exercise 14
H = 1.5
SCULPTURE = [(-2 * A, 0), (0, 0), (A, H), (A, 2 * H), (0, 2 * H), (-A, H)]

unit3 = st.tuples(*[st.floats(-1, 1)] * 3).filter(lambda v: np.linalg.norm(v) > 0.1)


def stepped_cylinder(a: float = 1.0):
    """The seed's Exercise 19: radius a on x in [0, 2a], radius 3a on x in [2a, 4a]."""
    turn = rotation_matrix([0, 1, 0], np.pi / 2)
    small = cylinder(a, 2 * a).transformed(turn)
    large = cylinder(3 * a, 2 * a).transformed(turn, np.array([2 * a, 0.0, 0.0]))
    return union(small, large)


@given(unit3)
def test_ground_frame_is_orthonormal_right_handed_and_deterministic(v):
    down = unit_vector(v, 3)
    frame = ground_frame(down)
    basis = np.vstack((frame.axes, -down))
    assert np.allclose(basis @ basis.T, np.eye(3), atol=1e-12)
    assert np.linalg.det(basis) == pytest.approx(1.0)
    assert np.array_equal(ground_frame(down).axes, frame.axes)


def test_ground_frame_for_the_default_downs():
    assert np.array_equal(ground_frame(np.array([0.0, 0.0, -1.0])).axes, [[1, 0, 0], [0, 1, 0]])
    assert np.array_equal(ground_frame(np.array([0.0, -1.0])).axes, [[1, 0]])
    # tilt directions: 90° from +x toward +y
    assert np.allclose(ground_frame(np.array([0.0, 0.0, -1.0])).direction(90), [0, 1, 0])


def test_box_on_end_stands_on_its_base():
    s = support_polygon(box(1, 1, 4))
    assert s.kind == "polygon" and s.com_height == pytest.approx(2.0)
    assert sorted(map(tuple, s.polygon.round(12))) == [(0, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0)]
    assert np.allclose(s.edge_distances, 0.5)
    assert np.allclose(s.plane_point, [0.5, 0.5, 0.0])


def test_sculpture_lamina_support_is_its_base_interval():
    s = support_polygon(polygon(SCULPTURE))
    assert s.kind == "segment" and s.dim == 2
    assert np.allclose(sorted(s.polygon[:, 0]), [-2 * A, 0.0])
    assert np.allclose(s.polygon[:, 1], 0.0)
    assert s.com_height == pytest.approx(19 * H / 21)


def test_cylinder_on_its_side_touches_along_a_line():
    turn = rotation_matrix([0, 1, 0], np.pi / 2)  # axis along +x
    s = support_polygon(cylinder(1.0, 2.0).transformed(turn))
    assert s.kind == "segment"
    ends = s.polygon[np.argsort(s.polygon[:, 0])]
    assert np.allclose(ends, [[0, 0, -1], [2, 0, -1]], atol=1e-9)


def test_stepped_cylinder_touches_along_the_large_cylinder():
    s = support_polygon(stepped_cylinder())
    assert s.kind == "segment"
    assert np.allclose(sorted(s.polygon[:, 0]), [2.0, 4.0])
    assert np.allclose(s.polygon[:, 1:], [[0, -3], [0, -3]], atol=1e-9)


@pytest.mark.parametrize("down", [[0, 0, -1], [0.3, -0.4, -0.5]])
def test_a_sphere_touches_at_one_point(down):
    s = support_polygon(sphere(1.0), down)
    assert s.kind == "point"
    assert np.allclose(s.polygon[0], unit_vector(down, 3), atol=1e-9)


def test_a_disc_lamina_touches_at_one_point():
    s = support_polygon(disc(2.0))
    assert s.kind == "point" and np.allclose(s.polygon[0], [0, -2], atol=1e-9)


def test_tolerance_decides_what_touches():
    tipped = box(1, 1, 4).transformed(rotation_matrix([1, 0, 0], 1e-7))  # one edge 1e-7 up
    assert support_polygon(tipped).kind == "polygon"  # default 1e-6 of the size: all four corners
    assert support_polygon(tipped, tolerance=1e-9).kind == "segment"  # only the lower edge


def test_a_pyramid_balanced_on_its_apex_touches_at_a_point():
    s = support_polygon(pyramid([(0, 0), (2, 0), (2, 2), (0, 2)], 3.0), [0, 0, 1])
    assert s.kind == "point" and np.allclose(s.polygon[0], [1, 1, 3])


def test_particles_stand_on_their_lowest_points():
    ps = ParticleSystem([1.0, 1.0, 1.0, 1.0], [[0, 0, 0], [2, 0, 0], [0, 2, 0], [0.5, 0.5, 3]])
    s = support_polygon(ps)
    assert s.kind == "polygon" and len(s.vertices) == 3


def test_an_assembly_of_a_solid_and_a_lamina_stands_as_a_solid():
    from plumbob.bodies.csg import Assembly
    from plumbob.bodies.primitives import rectangle

    plate = rectangle(3, 1, density=1.0)  # in z = 0, beside the cube's base
    s = support_polygon(Assembly((box(1, 1, 1, density=1.0), plate)))
    assert s.kind == "polygon" and s.dim == 3
    assert np.allclose(np.ptp(s.polygon, axis=0), [3, 1, 0])


def test_a_body_lying_flat_has_nothing_to_stand_on():
    pair = ParticleSystem([1.0, 2.0], [[0, 0, 0], [1, 0, 0]])
    with pytest.raises(StabilityError, match="lies flat"):
        support_polygon(pair)
    assert support_polygon(pair, [1, 0, 0]).kind == "point"  # on its end: it falls


def test_a_centre_of_mass_below_the_plane_is_an_error():
    body = box(1, 1, 1)
    wrong = point_mass(1.0, [0.5, 0.5, -2.0])
    with pytest.raises(StabilityError, match="not above the plane"):
        support_polygon(body, props=wrong)


@pytest.mark.parametrize("down", [[0, 0, 0], [np.nan, 0, 1], [1, 2]])
def test_bad_down_directions(down):
    with pytest.raises(StabilityError):
        support_polygon(box(1, 1, 1), down)


def test_a_lamina_down_must_lie_in_its_plane():
    with pytest.raises(StabilityError, match="own plane"):
        support_polygon(polygon(SCULPTURE), [0, -1, 1])
    assert support_polygon(polygon(SCULPTURE), [0, -1, 0]).kind == "segment"


def test_the_support_carries_the_body_size_whatever_the_tolerance():
    """Reports scale their round-off by ``support.size``, never by a tolerance turned back
    into a size (wrong whenever ``--tolerance`` is given)."""
    from plumbob.stability.support import body_size

    body = box(1, 2, 4)
    for tolerance in (None, 1e-3):
        s = support_polygon(body, tolerance=tolerance)
        assert s.size == body_size(body)
    assert support_polygon(body, tolerance=1e-3).tolerance == 1e-3


def test_a_union_of_curved_parts_touches_the_plane_where_its_parts_do():
    """Two overlapping unit spheres, 1 m apart: the union is faceted for its volume, but
    it touches a plane below it at the two spheres' own poles (not on the facets' flat
    caps), and, its cross-section about the line through them being a circle, it rolls
    freely about that line: a segment of contact and a neutral verdict. Turned and moved,
    it keeps its exact contact."""
    from plumbob import check

    pair = union(sphere(1.0, density=1.0), sphere(1.0, density=1.0).translated([1, 0, 0]))
    assert not pair.mass_properties().exact  # faceted: its volume is extrapolated
    assert np.array_equal(pair.support_points(np.array([0, 0, -1.0]), 1e-9),
                          [[0, 0, -1], [1, 0, -1]])
    verdict = check(pair)
    assert verdict.support.kind == "segment" and verdict.verdict == "neutral"
    assert verdict.critical_tilt_deg == 0 and abs(verdict.margin) <= 1e-12
    turn = rotation_matrix([0, 0, 1], np.radians(30))
    moved = pair.transformed(turn, [5.0, -2.0, 3.0])
    lowest = moved.support_points(np.array([0, 0, -1.0]), 1e-9)
    expected = (turn @ np.array([[0, 0, -1], [1, 0, -1]]).T).T + [5.0, -2.0, 3.0]
    assert np.allclose(np.sort(lowest, axis=0), np.sort(expected, axis=0), rtol=0, atol=1e-14)
