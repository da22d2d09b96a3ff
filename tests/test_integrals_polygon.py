import numpy as np
import pytest
import shapely
from conftest import rel, star_polygon
from hypothesis import given
from hypothesis import strategies as st

from plumbob.bodies import primitives as P
from plumbob.bodies.region import Region, Ring
from plumbob.integrals.polygon import (
    arc_cap_moments,
    cubic_cap_moments,
    polygon_moments,
    rings_moments,
)


def shapely_moments(vertices):
    poly = shapely.Polygon(vertices)
    return poly.area, np.array(poly.centroid.coords[0])


@given(st.integers(4, 60), st.integers(0, 2**32 - 1))
def test_polygon_area_and_centroid_match_shapely(n, seed):
    v = star_polygon(np.random.default_rng(seed), n)
    m = polygon_moments(v, v.mean(axis=0))
    area, centroid = shapely_moments(v)
    assert m.m0 == pytest.approx(area, rel=1e-12)
    assert rel(v.mean(axis=0) + m.m1 / m.m0, centroid) < 1e-12


def test_second_moments_of_rectangle_closed_form():
    v = np.array([[0, 0], [3, 0], [3, 2], [0, 2]], dtype=float)
    m = polygon_moments(v, np.zeros(2))
    assert m.m2[0, 0] == pytest.approx(3**3 * 2 / 3)  # ∫x² dA = b³h/3
    assert m.m2[1, 1] == pytest.approx(3 * 2**3 / 3)
    assert m.m2[0, 1] == pytest.approx(3**2 * 2**2 / 4)


def test_far_from_origin_stays_exact():
    """Centred second moments of a unit square 1e8 away: exact, where naive sums lose all digits."""
    square = P.rectangle(1, 1).translated([1e8, -3e8]).mass_properties()
    assert square.inertia[0, 0] == pytest.approx(1 / 12, rel=1e-12)
    assert square.inertia[0, 1] == pytest.approx(0, abs=1e-12)
    naive = polygon_moments(np.array([[0, 0], [1, 0], [1, 1], [0, 1.0]]) + [1e8, -3e8], np.zeros(2))
    with np.errstate(all="ignore"):
        naive_central = naive.m2[0, 0] - naive.m1[0] ** 2 / naive.m0
    assert not np.isclose(naive_central, 1 / 12, rtol=1e-3)  # the trap the local origin avoids


def test_degree_three_moments_by_subdivision():
    """∫x³, ∫x²y, … of a triangle match a fine midpoint rule on its subdivision."""
    v = np.array([[0.2, 0.1], [1.5, 0.3], [0.4, 1.7]])
    m = polygon_moments(v, np.zeros(2), degree=3)
    # Reference: the simplex formula is exact; check against 4-level refinement sums of a
    # 6-point degree-4 rule (Strang–Fix) — independent of the closed form.
    pts = np.array(
        [
            [0.445948490915965, 0.445948490915965],
            [0.445948490915965, 0.108103018168070],
            [0.108103018168070, 0.445948490915965],
            [0.091576213509771, 0.091576213509771],
            [0.091576213509771, 0.816847572980459],
            [0.816847572980459, 0.091576213509771],
        ]
    )
    w = np.array([0.223381589678011] * 3 + [0.109951743655322] * 3) / 2
    e1, e2 = v[1] - v[0], v[2] - v[0]
    area = 0.5 * abs(e1[0] * e2[1] - e1[1] * e2[0])
    q = v[0] + pts[:, :1] * (v[1] - v[0]) + pts[:, 1:] * (v[2] - v[0])
    ref = np.einsum("k,ki,kj,kl->ijl", w * 2 * area, q, q, q)
    assert rel(m.m3, ref) < 1e-9
    assert rel(m.m2, np.einsum("k,ki,kj->ij", w * 2 * area, q, q)) < 1e-9


def test_semicircle_centre_is_exactly_4a_over_3pi():
    for a in (1.0, 0.37, 250.0):
        props = P.semicircle(a).mass_properties()
        assert props.area == pytest.approx(np.pi * a * a / 2, rel=1e-15)
        assert props.center_of_mass[1] == pytest.approx(4 * a / (3 * np.pi), rel=1e-14)
        assert props.center_of_mass[0] == pytest.approx(0, abs=1e-15 * a)


@pytest.mark.parametrize("angle", [0.01, 0.5, np.pi / 2, 2.0, 3.0, 2 * np.pi - 0.1])
def test_sector_and_segment_closed_forms(angle):
    r = 1.7
    alpha = angle / 2
    sector = P.sector(r, angle).mass_properties()
    assert sector.area == pytest.approx(r * r * alpha, rel=1e-13)
    assert sector.center_of_mass[0] == pytest.approx(2 * r * np.sin(alpha) / (3 * alpha), rel=1e-13)
    segment = P.circular_segment(r, angle).mass_properties()
    seg_area = r * r * (alpha - np.sin(alpha) * np.cos(alpha))
    assert segment.area == pytest.approx(seg_area, rel=1e-10)
    expected = 4 * r * np.sin(alpha) ** 3 / (3 * (2 * alpha - np.sin(2 * alpha)))
    assert segment.center_of_mass[0] == pytest.approx(expected, rel=1e-8)


def test_disc_and_annulus_inertia():
    r = 2.0
    disc = P.disc(r).mass_properties()
    assert disc.inertia[2, 2] == pytest.approx(disc.mass * r * r / 2, rel=1e-14)
    ring = P.annulus(1.0, 2.0).mass_properties()
    assert ring.area == pytest.approx(3 * np.pi, rel=1e-14)
    assert ring.inertia[2, 2] == pytest.approx(ring.mass * (1 + 4) / 2, rel=1e-14)


def test_arc_caps_converge_to_flattened_polygons():
    ring = Ring(np.array([[0, 0], [2, 0], [2, 1], [0, 1.0]]), bulges=np.array([0.3, -0.2, 0, 0.5]))
    region = Region((ring,))
    exact = region.moments(np.zeros(2), degree=3)
    fine = region.to_shapely(1e-9)
    assert exact.m0 == pytest.approx(fine.area, rel=1e-8)
    assert rel(exact.m1 / exact.m0, np.array(fine.centroid.coords[0])) < 1e-8


def test_cubic_bezier_exact_against_dense_polygon():
    controls = np.array([[[0, 0], [1, -1], [2, -1], [3, 0]]], dtype=float)
    m = cubic_cap_moments(controls, np.zeros(2), degree=3)
    t = np.linspace(0, 1, 200001)[:, None]
    b0, b1, b2, b3 = controls[0]
    curve = (1 - t) ** 3 * b0 + 3 * (1 - t) ** 2 * t * b1 + 3 * (1 - t) * t**2 * b2 + t**3 * b3
    area, centroid = shapely_moments(curve)
    # Out along the curve below the chord, back along the chord: counter-clockwise, positive.
    assert m.m0 == pytest.approx(area, rel=1e-9)
    assert rel(m.m1 / m.m0, centroid) < 1e-9
    # Closed form: x = 3t, y = −3t(1−t), so the area is ∫ 3t(1−t) · 3 dt = 3/2 and the
    # centroid's depth is ∫ (3t(1−t))²/2 · 3 dt / (3/2) = 3/10.
    assert m.m0 == pytest.approx(1.5, rel=1e-14)
    assert m.m1[1] / m.m0 == pytest.approx(-0.3, rel=1e-14)


def test_arc_cap_sign_follows_bulge():
    p0, p1 = np.array([[1.0, 0.0]]), np.array([[-1.0, 0.0]])
    up = arc_cap_moments(p0, p1, np.array([1.0]), np.zeros(2))
    down = arc_cap_moments(p0, p1, np.array([-1.0]), np.zeros(2))
    assert up.m0 == pytest.approx(np.pi / 2) and down.m0 == pytest.approx(-np.pi / 2)


@given(st.integers(0, 2**32 - 1), st.floats(-np.pi, np.pi))
def test_region_rigid_motion(seed, angle):
    rng = np.random.default_rng(seed)
    ring = Ring(star_polygon(rng, 7), bulges=rng.uniform(-0.3, 0.3, 7))
    region = Region((ring,))
    c, s = np.cos(angle), np.sin(angle)
    turned = region.transformed(np.array([[c, -s], [s, c]]), [5.0, -2.0])
    a, b = region.moments(np.zeros(2)), turned.moments(np.array([5.0, -2.0]))
    assert b.m0 == pytest.approx(a.m0, rel=1e-12)
    mirrored = region.transformed(np.diag([1.0, -1.0]))
    assert mirrored.moments().m0 == pytest.approx(a.m0, rel=1e-12)


@pytest.mark.parametrize("degree", [2, 3])
@pytest.mark.parametrize("far", [0.0, 1e6])
def test_rings_moments_is_the_sum_of_polygon_moments(degree, far):
    """The one-pass sum over many rings (a drawing's holes) equals ring-by-ring sums,
    also far from the origin, and a degenerate ring adds nothing."""
    rng = np.random.default_rng(11)
    rings = [star_polygon(rng, int(rng.integers(3, 12)), centre=rng.normal(size=2) * 5 + far)
             for _ in range(40)]
    rings = [r if k % 3 else r[::-1] for k, r in enumerate(rings)]  # holes wind the other way
    origin = rings[0][0]
    one = rings_moments(rings + [rings[0][:2]], origin, degree)
    each = polygon_moments(rings[0], origin, degree)
    for ring in rings[1:]:
        each = each + polygon_moments(ring, origin, degree)
    scale = max(abs(each.m0), 1.0)
    assert abs(one.m0 - each.m0) <= 1e-12 * scale
    np.testing.assert_allclose(one.m1, each.m1, rtol=1e-12, atol=1e-12 * np.abs(each.m1).max())
    np.testing.assert_allclose(one.m2, each.m2, rtol=1e-12, atol=1e-12 * np.abs(each.m2).max())
    if degree == 3:
        np.testing.assert_allclose(one.m3, each.m3, rtol=1e-11, atol=1e-12 * np.abs(each.m3).max())
