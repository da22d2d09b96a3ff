"""Closed forms to 1e-13: every primitive against its textbook formula."""

import numpy as np
import pytest

from plumbob.bodies import primitives as P
from plumbob.bodies.region import Region
from plumbob.errors import GeometryError

RTOL = 1e-13


def check(props, mass, com, diag):
    assert props.mass == pytest.approx(mass, rel=RTOL)
    np.testing.assert_allclose(
        props.center_of_mass, com, rtol=RTOL, atol=RTOL * max(1, np.abs(com).max())
    )
    np.testing.assert_allclose(np.diag(props.inertia), diag, rtol=RTOL)
    off = props.inertia - np.diag(np.diag(props.inertia))
    assert np.abs(off).max() <= RTOL * np.abs(diag).max()


def test_sphere():
    r, rho = 1.3, 7.0
    m = 4 / 3 * np.pi * r**3 * rho
    check(P.sphere(r, density=rho).mass_properties(), m, [0, 0, 0], [0.4 * m * r * r] * 3)


def test_hemisphere_centre_3r_over_8():
    r = 2.0
    m = 2 / 3 * np.pi * r**3
    i_axis = 0.4 * m * r * r
    i_base = 0.4 * m * r * r - m * (3 * r / 8) ** 2  # about the centre of mass
    check(P.hemisphere(r).mass_properties(), m, [0, 0, 3 * r / 8], [i_base, i_base, i_axis])


def test_cone_centre_h_over_4():
    r, h = 0.7, 2.5
    m = np.pi * r * r * h / 3
    i_axis = 0.3 * m * r * r
    i_perp = m * (3 * r * r / 20 + 3 * h * h / 80)
    check(P.cone(r, h).mass_properties(), m, [0, 0, h / 4], [i_perp, i_perp, i_axis])


def test_frustum():
    r0, r1, h = 2.0, 1.0, 3.0
    m = np.pi * h / 3 * (r0 * r0 + r0 * r1 + r1 * r1)
    z = h / 4 * (r0 * r0 + 2 * r0 * r1 + 3 * r1 * r1) / (r0 * r0 + r0 * r1 + r1 * r1)
    i_axis = 3 * m / 10 * (r0**5 - r1**5) / (r0**3 - r1**3)
    props = P.frustum(r0, r1, h).mass_properties()
    assert props.mass == pytest.approx(m, rel=RTOL)
    assert props.center_of_mass[2] == pytest.approx(z, rel=RTOL)
    assert props.inertia[2, 2] == pytest.approx(i_axis, rel=RTOL)


def test_cylinder():
    r, h = 0.5, 3.0
    m = np.pi * r * r * h
    i_perp = m * (3 * r * r + h * h) / 12
    check(P.cylinder(r, h).mass_properties(), m, [0, 0, h / 2], [i_perp, i_perp, m * r * r / 2])


def test_torus_by_pappus():
    big, small = 3.0, 0.8
    m = 2 * np.pi**2 * big * small**2
    i_axis = m * (big**2 + 0.75 * small**2)
    i_diam = m * (big**2 / 2 + 5 / 8 * small**2)
    check(P.torus(big, small).mass_properties(), m, [0, 0, 0], [i_diam, i_diam, i_axis])


def test_turned_part_is_exact_sum_of_cylinders():
    """A stepped profile revolved equals the two cylinders it is made of (Pappus vs parts)."""
    profile = P.polygon([[0, 0], [1, 0], [1, 2], [3, 2], [3, 4], [0, 4]])
    turned = P.revolve(profile).mass_properties()
    parts = (
        P.cylinder(1, 2).mass_properties()
        + P.cylinder(3, 2).translated([0, 0, 2]).mass_properties()
    )
    assert turned.mass == pytest.approx(parts.mass, rel=RTOL)
    np.testing.assert_allclose(turned.center_of_mass, parts.center_of_mass, atol=RTOL * 4)
    np.testing.assert_allclose(
        turned.inertia, parts.inertia, rtol=RTOL, atol=RTOL * parts.inertia.max()
    )


def test_revolved_arc_profile_is_a_sphere_with_a_hole():
    """A half-disc with a square notch turned about its diameter: sphere minus cylinder."""
    r, a = 1.0, 0.25
    half_disc = P.sphere(r).profile
    sphere = P.revolve(half_disc).mass_properties()
    assert sphere.volume == pytest.approx(4 / 3 * np.pi, rel=RTOL)
    notch = P.rectangle(a, 2 * a).translated([0, -a])
    body = P.revolve(
        Region(half_disc.rings + (notch.region.rings[0].reversed(),))
    ).mass_properties()
    assert body.volume == pytest.approx(4 / 3 * np.pi - np.pi * a * a * 2 * a, rel=RTOL)


def test_box_and_prism():
    a, b, c = 1.0, 2.0, 3.0
    m = a * b * c
    check(
        P.box(a, b, c).mass_properties(),
        m,
        [a / 2, b / 2, c / 2],
        [m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12],
    )
    prism = P.prism(P.rectangle(a, b), c).mass_properties()
    np.testing.assert_allclose(prism.inertia, P.box(a, b, c).mass_properties().inertia, rtol=RTOL)


def test_prism_of_disc_is_cylinder():
    disc_prism = P.prism(P.disc(0.5), 3.0).mass_properties()
    cyl = P.cylinder(0.5, 3.0).mass_properties()
    assert disc_prism.mass == pytest.approx(cyl.mass, rel=RTOL)
    np.testing.assert_allclose(disc_prism.inertia, cyl.inertia, rtol=RTOL)


def test_square_pyramid():
    s, h = 230.0, 147.0
    props = P.pyramid(
        s / 2 * np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]), h, density=2500
    ).mass_properties()
    m = 2500 * s * s * h / 3
    assert props.mass == pytest.approx(m, rel=RTOL)
    assert props.center_of_mass[2] == pytest.approx(h / 4, rel=RTOL)
    i_axis = m * s * s / 10
    i_perp = m * (s * s / 20 + 3 * h * h / 80)
    np.testing.assert_allclose(np.diag(props.inertia), [i_perp, i_perp, i_axis], rtol=RTOL)


def test_regular_polygon_approaches_disc_and_matches_formula():
    n, r = 12, 1.0
    props = P.regular_polygon(n, r).mass_properties()
    area = n * r * r * np.sin(2 * np.pi / n) / 2
    assert props.area == pytest.approx(area, rel=RTOL)
    # polar moment of a regular n-gon: A r² (2 + cos(2π/n)) / 6
    assert props.inertia[2, 2] == pytest.approx(
        area * r * r * (2 + np.cos(2 * np.pi / n)) / 6, rel=RTOL
    )


def test_triangle_centre_one_third_of_height():
    props = P.triangle([-1, 0], [1, 0], [0, 3]).mass_properties()
    assert props.center_of_mass == pytest.approx([0, 1.0], abs=1e-15)
    assert props.inertia[0, 0] == pytest.approx(3 * 3**2 / 18, rel=RTOL)  # b h³/36 · ρ


@pytest.mark.parametrize(
    "make",
    [
        lambda: P.disc(0),
        lambda: P.box(1, -1, 1),
        lambda: P.cone(1, 0),
        lambda: P.annulus(2, 1),
        lambda: P.polygon([[0, 0], [1, 1], [2, 2]]),
        lambda: P.regular_polygon(2, 1),
        lambda: P.tetrahedron([0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]),
        lambda: P.torus(1, 2),
        lambda: P.sphere(float("nan")),
    ],
)
def test_degenerate_primitives_are_errors(make):
    with pytest.raises(GeometryError):
        make()


@pytest.mark.parametrize(
    "body, down, count",
    [
        (P.sphere(1.0), [0, 0, -1.0], 1),  # a point, not a cap of samples
        (P.sphere(1.0), [0.6, 0, -0.8], 1),
        (P.disc(1.0), [0, -1.0], 1),
        (P.semicircle(1.0), [0.6, 0.8], 1),
    ],
)
def test_curved_contact_is_the_true_point(body, down, count):
    pts = body.support_points(np.array(down), 1e-6)
    assert len(pts) == count
    np.testing.assert_allclose(pts[0], np.array(down) * (1.0 if len(down) == 3 else 1.0), atol=1e-12)


def test_cylinder_on_its_side_touches_along_a_line():
    pts = P.cylinder(0.5, 2.0).support_points(np.array([1.0, 0, 0]), 1e-6)
    assert np.allclose(pts[:, 0], 0.5) and np.allclose(pts[:, 1], 0)
    assert pts[:, 2].min() == pytest.approx(0) and pts[:, 2].max() == pytest.approx(2)
