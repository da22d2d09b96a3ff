import numpy as np
import pytest
from conftest import rel
from hypothesis import given
from hypothesis import strategies as st

from plumbob.bodies import primitives as P
from plumbob.bodies.csg import union
from plumbob.errors import GeometryError
from plumbob.massprops import MassProperties, combine, point_mass, rotation_matrix


def test_two_particles_equation_15():
    system = combine([point_mass(1.0, [0, 0, 0]), point_mass(3.0, [4, 0, 0])])
    assert system.mass == 4.0
    np.testing.assert_allclose(system.center_of_mass, [3, 0, 0])
    # About the centre: 1·3² + 3·1² = 12 about y and z, 0 about x.
    np.testing.assert_allclose(system.inertia, np.diag([0, 12, 12]), atol=1e-12)


def test_hole_is_negative_mass():
    plate = P.rectangle(4, 2).mass_properties()
    hole = P.disc(0.5).translated([3, 1]).mass_properties()
    holed = plate - hole
    assert holed.mass == pytest.approx(8 - np.pi / 4, rel=1e-15)
    expected_x = (8 * 2 - np.pi / 4 * 3) / (8 - np.pi / 4)
    assert holed.center_of_mass[0] == pytest.approx(expected_x, rel=1e-14)
    assert (holed + hole).center_of_mass == pytest.approx(plate.center_of_mass, rel=1e-14)


def test_removing_everything_is_an_error():
    plate = P.rectangle(1, 1).mass_properties()
    with pytest.raises(GeometryError, match="no mass"):
        _ = plate - plate


def test_parallel_axes_rod_end():
    rod = P.box(2, 0.001, 0.001, density=1.0).mass_properties()
    m = rod.mass
    # thin rod about an end, axis z: m L²/3
    assert rod.moment_about_axis([0, 0.0005, 0.0005], [0, 0, 1]) == pytest.approx(
        m * 4 / 3, rel=1e-6
    )


def test_principal_axes_are_right_handed_and_diagonalise():
    props = P.box(1, 2, 3).transformed(rotation_matrix([1, 2, 3], 0.7)).mass_properties()
    axes = props.principal_axes
    assert np.linalg.det(axes) == pytest.approx(1.0)
    np.testing.assert_allclose(
        axes @ props.inertia @ axes.T,
        np.diag(props.principal_moments),
        atol=1e-12 * props.principal_moments.max(),
    )
    np.testing.assert_allclose(
        props.principal_moments, sorted([13 / 12 * 6, 10 / 12 * 6, 5 / 12 * 6]), rtol=1e-13
    )


def test_lamina_tensor_convention():
    # A 2 × 1 rectangle of unit density at the origin corner: ∫xy dA about the centre is 0,
    # so rotate by 30° and compare the off-diagonal with −∫xy dm computed by hand.
    rect = P.rectangle(2, 1).mass_properties()
    assert rect.inertia[0, 0] == pytest.approx(2 * 1 / 12)  # ∫y² dm
    assert rect.inertia[1, 1] == pytest.approx(2 * 4 / 12)  # ∫x² dm
    assert rect.inertia[2, 2] == pytest.approx(2 * 5 / 12)
    turned = rect.rotated(np.pi / 6)
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    ixx, iyy = 2 * 4 / 12, 2 * 1 / 12  # ∫x² and ∫y² in the body frame
    expected_xy = -(c * s * (ixx - iyy))  # −∫x'y' dm after the turn
    assert turned.inertia[0, 1] == pytest.approx(expected_xy, rel=1e-14)


def test_mirror_keeps_mass_and_moves_centre():
    props = P.triangle([0, 0], [3, 0], [0, 1]).mass_properties()
    mirrored = props.mirrored([1, 0, 0])
    assert mirrored.center_of_mass == pytest.approx([-1, 1 / 3])
    assert mirrored.inertia[0, 1] == pytest.approx(-props.inertia[0, 1])


def test_transform_needs_orthogonal_matrix():
    with pytest.raises(GeometryError, match="orthogonal"):
        P.box(1, 1, 1).mass_properties().transformed(np.diag([2.0, 1.0, 1.0]))


def test_immutable():
    props = point_mass(1.0, [0, 0, 0])
    with pytest.raises(ValueError):
        props.center_of_mass[0] = 3.0
    assert isinstance(props, MassProperties)


angles = st.floats(-np.pi, np.pi, allow_nan=False)
offsets = st.lists(st.floats(-1e3, 1e3, allow_nan=False), min_size=3, max_size=3)


@given(
    angles,
    st.lists(st.floats(-1, 1), min_size=3, max_size=3).filter(lambda v: np.linalg.norm(v) > 0.1),
    offsets,
)
def test_rigid_motions_commute_with_mass_properties(angle, axis, offset):
    """Moving the body then integrating = integrating then moving the result."""
    body = union(P.box(1, 2, 0.5), P.cylinder(0.3, 1).translated([0.5, 1, 0.5]))
    matrix = rotation_matrix(axis, angle)
    moved_first = body.transformed(matrix, np.array(offset)).mass_properties()
    moved_after = body.mass_properties().transformed(matrix, offset)
    assert moved_first.mass == pytest.approx(moved_after.mass, rel=1e-13)
    assert rel(moved_first.center_of_mass, moved_after.center_of_mass) < 1e-12
    assert rel(moved_first.inertia, moved_after.inertia) < 1e-12
