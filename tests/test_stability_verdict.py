"""Verdicts, margins, tipping angles and energies, slopes, friction and tilt tests."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_stability_support import SCULPTURE, A, H, stepped_cylinder

from plumbob.bodies.csg import Composite
from plumbob.bodies.primitives import box, cylinder, polygon, pyramid, rectangle, sphere
from plumbob.errors import StabilityError
from plumbob.massprops import rotation_matrix
from plumbob.stability import check

G = 9.81


def test_box_on_end_closed_forms():
    """1 m × 1 m × 4 m standing on end: tilt atan(0.5/2), energy Mg(√4.25 − 2)."""
    v = check(box(1, 1, 4, density=1000.0))
    m = 4000.0
    assert v.verdict == "stands" and v.stands
    assert v.margin == pytest.approx(0.5)
    assert v.com_height == pytest.approx(2.0)
    assert v.critical_tilt_deg == pytest.approx(np.degrees(np.arctan(0.25)), rel=1e-12)
    assert v.critical_tilt_deg == pytest.approx(14.036, abs=1e-3)
    assert v.energy_to_topple == pytest.approx(m * G * (np.sqrt(4.25) - 2), rel=1e-12)
    assert abs(v.critical_direction[2]) < 1e-15 and np.linalg.norm(v.critical_direction) == \
        pytest.approx(1)
    assert len(v.edges) == 4
    assert all(e.tipping_angle_deg == pytest.approx(v.critical_tilt_deg) for e in v.edges)


def test_box_lying_down():
    v = check(box(1, 1, 4), [1, 0, 0])
    assert v.com_height == pytest.approx(0.5)
    assert v.margin == pytest.approx(0.5)
    assert v.critical_tilt_deg == pytest.approx(45.0)


def test_sculpture_stands_with_its_centre_4a_21_inside_the_edge_at_O():
    """The seed's Exercise 14: centre (−4a/21, 19h/21), O at the origin."""
    v = check(polygon(SCULPTURE))
    assert v.verdict == "stands"
    assert v.margin == pytest.approx(4 * A / 21, rel=1e-12)
    assert v.margin == pytest.approx(0.165, abs=5e-4)
    assert v.com_height == pytest.approx(19 * H / 21, rel=1e-12)
    assert v.critical_tilt_deg == pytest.approx(np.degrees(np.arctan((4 * A) / (19 * H))))
    assert v.critical_tilt_deg == pytest.approx(6.93, abs=5e-3)
    assert np.allclose(v.critical_direction, [1, 0])  # toward O
    assert np.allclose(sorted(v.support.polygon[:, 0]), [-2 * A, 0])


def test_l_shape_lamina():
    """The seed's Example 3: centre (5a/6, 5a/6) over a base of 2a."""
    l_shape = polygon([(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)])
    v = check(l_shape)
    assert v.margin == pytest.approx(5 / 6)
    assert np.allclose(v.critical_direction, [-1, 0])
    assert v.critical_tilt_deg == pytest.approx(45.0)


def test_stepped_cylinder_stands_along_its_axis_and_is_neutral_to_rolling():
    """The seed's Exercise 19: centre at 14a/5 > 2a, over the contact line x in [2a, 4a]."""
    v = check(stepped_cylinder())
    assert v.verdict == "neutral"
    assert v.com_height == pytest.approx(3.0)
    assert v.center_of_mass[0] == pytest.approx(14 / 5)
    assert abs(v.margin) <= v.support.tolerance
    axial = {round(float(e.normal[0])): e for e in v.edges if abs(e.normal[0]) > 0.5}
    assert axial[-1].distance == pytest.approx(14 / 5 - 2)  # beyond P, the leftmost contact
    assert axial[1].distance == pytest.approx(4 - 14 / 5)
    assert axial[-1].tipping_angle_deg == pytest.approx(np.degrees(np.arctan(0.8 / 3)))
    rolling = [e for e in v.edges if abs(e.normal[1]) > 0.5]
    assert len(rolling) == 2 and all(abs(e.distance) <= v.support.tolerance for e in rolling)
    assert abs(v.critical_direction[1]) == pytest.approx(1)  # it rolls sideways


def test_a_sphere_is_neutral():
    v = check(sphere(1.0, density=2.0))
    assert v.verdict == "neutral" and v.critical_tilt_deg == 0 and v.energy_to_topple == 0


def test_cylinder_upright_tips_at_45_degrees():
    v = check(cylinder(1.0, 2.0))
    assert v.verdict == "stands"
    assert v.critical_tilt_deg == pytest.approx(45.0, abs=1e-3)  # a sampled rim: within 1e-6


def leaning_block():
    """A thin plate with a heavy block above it overhanging its edge."""
    plate = box(1, 1, 0.1, density=100.0)
    block = box(3, 1, 1, density=1000.0).translated([0.5, 0.0, 0.1])
    return Composite((plate, block), (1.0, 1.0))


def test_a_body_whose_centre_is_beyond_its_base_topples():
    body = leaning_block()
    com = body.mass_properties().center_of_mass
    v = check(body)
    assert v.verdict == "topples" and not v.stands
    assert v.margin == pytest.approx(-(com[0] - 1.0))
    assert np.allclose(v.critical_direction, [1, 0, 0])
    assert v.critical_tilt_deg < 0 and v.energy_to_topple == 0


def test_a_box_balanced_on_its_edge_is_neutral():
    turn = rotation_matrix([0, 1, 0], np.pi / 4)
    v = check(box(1, 1, 1).transformed(turn))
    assert v.verdict == "neutral" and v.support.kind == "segment"


def test_tilted_plane():
    body = box(1, 1, 4)
    assert check(body, tilt_deg=10, toward_deg=0).slope.topples is False
    s = check(body, tilt_deg=15, toward_deg=0).slope
    assert s.topples and s.verdict == "topples"
    assert s.tipping_angle_deg == pytest.approx(np.degrees(np.arctan(0.25)))
    assert np.allclose(s.direction, [1, 0, 0])
    diagonal = check(body, tilt_deg=15, toward_deg=45).slope  # toward a corner: further
    assert not diagonal.topples
    assert diagonal.tipping_angle_deg == pytest.approx(np.degrees(np.arctan(np.sqrt(0.5) / 2)))
    worst = check(body, tilt_deg=15).slope  # no direction: the worst one
    assert worst.topples


def test_friction_slide_or_topple():
    body = box(1, 1, 4)  # tips when tan θ > 0.25
    assert check(body, friction=0.2).slides_first is True
    assert check(body, friction=0.3).slides_first is False
    s = check(body, tilt_deg=12, toward_deg=0, friction=0.2).slope
    assert s.slides and not s.topples and s.verdict == "slides" and s.slides_first
    assert check(body, tilt_deg=12, toward_deg=0, friction=0.3).slope.slides is False


def test_require_tilt_checks_every_direction():
    body = box(1, 1, 4)
    assert check(body, require_tilt_deg=10).passes is True
    assert check(body, require_tilt_deg=15).passes is False
    # the worst direction of a long footprint is across it
    v = check(box(4, 1, 1), require_tilt_deg=40)
    assert v.passes is True and v.critical_tilt_deg == pytest.approx(45.0)
    assert check(box(4, 1, 1), require_tilt_deg=46).passes is False
    assert check(sphere(1.0), require_tilt_deg=1).passes is False  # it rolls away


def test_lamina_tilts_only_within_its_plane():
    lamina = rectangle(2, 1)
    assert check(lamina, tilt_deg=10, toward_deg=180).slope.direction.tolist() == [-1, 0]
    with pytest.raises(StabilityError, match="own plane"):
        check(lamina, tilt_deg=10, toward_deg=90)


@pytest.mark.parametrize("kw", [{"tilt_deg": 95}, {"tilt_deg": -1}, {"friction": -0.1}])
def test_bad_slope_arguments(kw):
    with pytest.raises(StabilityError):
        check(box(1, 1, 1), **kw)


def irregular_pyramid():
    base = [(0, 0), (3.0, -0.4), (2.6, 2.2), (0.3, 1.7)]
    return pyramid(base, 2.5, apex=(1.9, 0.7), density=3.0)


angles = st.floats(-np.pi, np.pi)


@settings(max_examples=25)
@given(st.tuples(angles, angles, angles), st.tuples(*[st.floats(-50, 50)] * 3))
def test_rigid_motions_change_nothing(angles3, offset):
    body = irregular_pyramid()
    turn = (rotation_matrix([1, 0, 0], angles3[0]) @ rotation_matrix([0, 1, 0], angles3[1])
            @ rotation_matrix([0, 0, 1], angles3[2]))
    moved = body.transformed(turn, np.array(offset))
    before = check(body)
    after = check(moved, turn @ np.array([0.0, 0.0, -1.0]))
    assert after.verdict == before.verdict == "stands"
    assert after.margin == pytest.approx(before.margin, rel=1e-9)
    assert after.critical_tilt_deg == pytest.approx(before.critical_tilt_deg, rel=1e-9)
    assert after.energy_to_topple == pytest.approx(before.energy_to_topple, rel=1e-8)
    assert np.allclose(after.critical_direction, turn @ before.critical_direction, atol=1e-9)
    assert sorted(e.distance for e in after.edges) == pytest.approx(
        sorted(e.distance for e in before.edges), rel=1e-9)


@settings(max_examples=15)
@given(st.floats(0.01, 1e4))
def test_density_scales_energies_only(density):
    light = check(irregular_pyramid())
    heavy = check(pyramid([(0, 0), (3.0, -0.4), (2.6, 2.2), (0.3, 1.7)], 2.5, apex=(1.9, 0.7),
                          density=density))
    assert heavy.margin == pytest.approx(light.margin, rel=1e-12)
    assert heavy.critical_tilt_deg == pytest.approx(light.critical_tilt_deg, rel=1e-12)
    assert heavy.energy_to_topple == pytest.approx(light.energy_to_topple * density / 3.0,
                                                   rel=1e-9)


def test_tipping_energy_is_the_rise_of_the_centre_of_mass():
    """Messuri and Klein: tipping over an edge raises the centre from h to √(d² + h²)."""
    v = check(irregular_pyramid(), g=2.0)
    for e in v.edges:
        rise = np.hypot(e.distance, v.com_height) - v.com_height
        assert e.energy == pytest.approx(v.mass * 2.0 * rise, rel=1e-10)


def test_curved_contact_is_judged_by_curvature():
    """Over a point of contact: a hemisphere on its dome rocks back, a ball rolls, a cone
    on its tip falls."""
    from plumbob.bodies.primitives import cone, hemisphere, sphere

    dome = check(hemisphere(1.0, density=1.0), down=[0, 0, 1])
    assert dome.verdict == "stands" and dome.margin == pytest.approx(0, abs=1e-6)
    assert dome.critical_tilt_deg == pytest.approx(np.degrees(np.arcsin(3 / 8)), abs=1.0)
    # rolled over the rim: the centre rises from 5/8 to the rim's farthest reach √(1 + (3/8)²)
    rise = np.hypot(1, 3 / 8) - 5 / 8
    assert dome.energy_to_topple == pytest.approx(dome.mass * 9.81 * rise, rel=0.02)
    assert check(hemisphere(1.0), down=[0, 0, 1], require_tilt_deg=10).passes
    assert not check(hemisphere(1.0), down=[0, 0, 1], require_tilt_deg=30).passes
    slope = check(hemisphere(1.0), down=[0, 0, 1], tilt_deg=30, toward_deg=45).slope
    assert slope.topples
    assert check(sphere(1.0)).verdict == "neutral"
    assert check(cone(0.5, 2.0), down=[0, 0, 1]).verdict == "topples"
