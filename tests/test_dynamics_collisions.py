"""Collisions: seed Examples 5–8 and Exercises 21–30, plus invariants (hypothesis)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from plumbob.dynamics.collisions import (
    ELASTIC_RTOL,
    bounce_heights,
    check_impact,
    collide,
    restitution_from_bounces,
)
from plumbob.errors import DynamicsError

INF = float("inf")


def unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


# ----------------------------------------------------------------- section 3
def test_example_5_railway_trucks_couple():
    r = collide(50_000, [2, 0], 30_000, [0, 0], e=0)
    np.testing.assert_allclose(r.v1_after, [1.25, 0])
    np.testing.assert_allclose(r.v2_after, [1.25, 0])


@pytest.mark.parametrize("big, small, u", [(80_000, 20_000, 3.0), (1.0, 1.0, 2.0)])
def test_exercise_21_engine_picks_up_truck(big, small, u):
    r = collide(big, u, small, 0.0, e=0)
    assert r.v1_after[0] == pytest.approx(big * u / (big + small), rel=1e-14)
    assert r.v2_after[0] == pytest.approx(big * u / (big + small), rel=1e-14)


def test_example_6_snooker_head_on_elastic():
    r = collide(0.16, [5, 0], 0.16, [0, 0], e=1)
    np.testing.assert_allclose(r.v1_after, [0, 0], atol=1e-15)
    np.testing.assert_allclose(r.v2_after, [5, 0])
    assert r.elastic


def test_exercise_22_trucks_not_elastic():
    r = collide(15_000, 4, 10_000, 0, e=0)
    assert r.v1_after[0] == pytest.approx(2.4) and r.v2_after[0] == pytest.approx(2.4)
    assert r.ke_before == pytest.approx(120_000)
    assert r.ke_after == pytest.approx(72_000)
    assert r.ke_loss == pytest.approx(48_000)
    assert not r.elastic


def test_example_7_black_ball_at_45_degrees():
    # The struck ball leaves along the common normal, here at π/4.
    u = 3.0
    r = collide(0.16, [u, 0], 0.16, [0, 0], normal=unit(math.pi / 4), e=1)
    np.testing.assert_allclose(r.v2_after, [u / 2, u / 2], rtol=1e-14)
    np.testing.assert_allclose(r.v1_after, [u / 2, -u / 2], rtol=1e-14)
    assert np.linalg.norm(r.v1_after) == pytest.approx(u / math.sqrt(2))
    assert np.linalg.norm(r.v2_after) == pytest.approx(u / math.sqrt(2))
    assert math.atan2(-r.v1_after[1], r.v1_after[0]) == pytest.approx(math.pi / 4)  # θ


def test_exercise_24_green_ball_at_60_degrees():
    u = 2.0
    r = collide(1.0, [u, 0], 1.0, [0, 0], normal=unit(math.pi / 3), e=1)
    np.testing.assert_allclose(r.v1_after, u * np.array([3 / 4, -math.sqrt(3) / 4]), rtol=1e-14)
    np.testing.assert_allclose(r.v2_after, u * np.array([1 / 4, math.sqrt(3) / 4]), rtol=1e-14)
    # The white ball leaves at θ = π/6 below its original line.
    assert math.atan2(-r.v1_after[1], r.v1_after[0]) == pytest.approx(math.pi / 6)


@pytest.mark.parametrize("m1, m2", [(1.0, 1.0), (2.0, 5.0), (0.3, 7.0)])
def test_exercise_25_perpendicular_particles_coalesce(m1, m2):
    u = 4.0
    r = collide(m1, [u, 0], m2, [0, u], e=0)  # head-on: normal along v1 − v2
    expected = np.array([m1 * u, m2 * u]) / (m1 + m2)
    np.testing.assert_allclose(r.v1_after, expected, rtol=1e-14)
    np.testing.assert_allclose(r.v2_after, expected, rtol=1e-14)
    assert r.ke_loss == pytest.approx(m1 * m2 * u * u / (m1 + m2), rel=1e-13)
    assert not r.elastic


def test_exercise_26_given_outcomes():
    a = check_impact(3, [2, 0], 3, [0, 0], [1, 1], [1, -1])
    assert (a.ke_before, a.ke_after, a.elastic, a.momentum_conserved) == (6.0, 6.0, True, True)
    b = check_impact(1, [2, 1], 3, [0, 1], [0.5, 1], [0.5, 1])
    assert (b.ke_before, b.ke_after, b.ke_loss) == (4.0, 2.5, 1.5)
    assert not b.elastic and b.momentum_conserved
    c = check_impact(1, [1, 0], 1, [0, 0], [1, 0], [1, 0])
    assert not c.momentum_conserved


# ----------------------------------------------------------------- section 4
@settings(max_examples=80, deadline=None)
@given(st.floats(0.01, 100), st.floats(0.01, 100), st.floats(-20, 20), st.floats(-20, 20),
       st.floats(0, 1))
def test_exercise_27_one_dimensional_formulas(m1, m2, x1, x2, e):
    assume(x1 - x2 > 1e-3)
    r = collide(m1, x1, m2, x2, e=e)
    big_x1 = ((m1 - e * m2) * x1 + m2 * (1 + e) * x2) / (m1 + m2)
    big_x2 = (m1 * (1 + e) * x1 + (m2 - e * m1) * x2) / (m1 + m2)
    assert r.v1_after[0] == pytest.approx(big_x1, rel=1e-12, abs=1e-12)
    assert r.v2_after[0] == pytest.approx(big_x2, rel=1e-12, abs=1e-12)


def test_exercise_27_b_and_c():
    r = collide(2.0, 5.0, 2.0, 0.0, e=1)       # (b): Example 6 again
    assert (r.v1_after[0], r.v2_after[0]) == (0.0, 5.0)
    r = collide(2.0, 5.0, 3.0, -1.0, e=0)      # (c): e = 0 ⇔ they move off together
    assert r.v1_after[0] == pytest.approx(r.v2_after[0], rel=1e-15)


@pytest.mark.parametrize("m1, m2, u, e", [(1, 1, 5, 0.5), (3, 0.2, 2, 0.9), (0.5, 4, 7, 0)])
def test_exercise_28_kinetic_energy_lost(m1, m2, u, e):
    r = collide(m1, [u, 0, 0], m2, [0, 0, 0], e=e)
    expected = m1 * m2 * (1 - e * e) * u * u / (2 * (m1 + m2))
    assert r.ke_loss == pytest.approx(expected, rel=1e-12)
    np.testing.assert_allclose(r.v1_after, [(m1 - e * m2) / (m1 + m2) * u, 0, 0], atol=1e-14)
    np.testing.assert_allclose(r.v2_after, [m1 * (1 + e) / (m1 + m2) * u, 0, 0])


@pytest.mark.parametrize("alpha", [0.0, 0.3, 1.0])
def test_example_8_golf_club(alpha):
    m, u = 0.046, 40.0
    v1 = [u * math.sin(alpha), u * math.cos(alpha)]
    r = collide(9 * m, v1, m, [0, 0], normal=[0, 1], e=0.8)
    c = u * math.cos(alpha)
    np.testing.assert_allclose(r.v1_after, [u * math.sin(alpha), 0.82 * c], rtol=1e-13,
                               atol=1e-12)
    np.testing.assert_allclose(r.v2_after, [0, 1.62 * c], atol=1e-12)
    assert r.ke_before == pytest.approx(4.5 * m * u * u)
    assert r.ke_loss == pytest.approx(0.162 * m * u * u * math.cos(alpha) ** 2, rel=1e-12)


def test_exercise_29_plastic_oblique():
    u = 2.0
    r = collide(1.0, u * unit(math.pi / 4), 1.0, [0, 0], normal=[1, 0], e=0)
    s = 1 / math.sqrt(2)
    np.testing.assert_allclose(r.v1_after, [u * s / 2, u * s], rtol=1e-14)
    np.testing.assert_allclose(r.v2_after, [u * s / 2, 0], atol=1e-15)


def test_exercise_30_bounces():
    e = restitution_from_bounces(1.0, 0.5, 2)
    assert e == pytest.approx(2 ** -0.25, rel=1e-15)
    assert round(e, 2) == 0.84
    np.testing.assert_allclose(bounce_heights(1.0, e, 2), [1.0, 2 ** -0.5, 0.5], rtol=1e-14)
    assert restitution_from_bounces(3.0, 3.0 * 0.36, 1) == pytest.approx(0.6)


def test_ball_dropped_on_floor_and_wall():
    # A fixed surface is infinite mass: the ball's normal velocity is reversed and scaled.
    r = collide(0.2, [0, -6], INF, [0, 0], normal=[0, -1], e=0.5)
    np.testing.assert_allclose(r.v1_after, [0, 3])
    np.testing.assert_array_equal(r.v2_after, [0, 0])
    assert r.wall and r.ke_before == pytest.approx(3.6) and r.ke_after == pytest.approx(0.9)
    np.testing.assert_allclose(r.momentum_after, [0, 0.6])
    # Oblique (seed Figure 37): the horizontal component is unchanged, Ẏ = −e ẏ.
    r = collide(1.0, [3, -4], INF, None, normal=[0, -2], e=0.25)
    np.testing.assert_allclose(r.v1_after, [3, 1])
    assert r.ke_after == pytest.approx(0.5 * (9 + 0.0625 * 16))
    # Head-on with a wall by default; e = 1 is elastic.
    r = collide(1.0, [2, 0, 0], INF, [0, 0, 0])
    np.testing.assert_allclose(r.v1_after, [-2, 0, 0])
    assert r.elastic and r.as_dict()["m2"] == "inf"


def test_moving_wall_energy_in_its_frame():
    # A wall moving at −1 m/s meets a ball at 2 m/s: in the wall's frame 3 → −3, so −4 m/s.
    r = collide(1.0, [2.0], INF, [-1.0], e=1)
    np.testing.assert_allclose(r.v1_after, [-4.0])
    assert r.ke_before == pytest.approx(4.5) and r.ke_after == pytest.approx(4.5) and r.elastic


# ---------------------------------------------------------------- invariants
vec = st.lists(st.floats(-30, 30), min_size=3, max_size=3)
masses = st.floats(1e-3, 1e3)


@settings(max_examples=200, deadline=None)
@given(masses, vec, masses, vec, vec, st.floats(0, 1))
def test_collision_invariants(m1, v1, m2, v2, normal, e):
    v1, v2, n = np.array(v1), np.array(v2), np.array(normal)
    assume(np.linalg.norm(n) > 1e-3)
    n = n / np.linalg.norm(n)
    if (v1 - v2) @ n < 0:
        n = -n
    assume((v1 - v2) @ n > 1e-6 * (1 + np.linalg.norm(v1) + np.linalg.norm(v2)))
    r = collide(m1, v1, m2, v2, normal=n, e=e)
    scale = m1 * np.abs(v1).max() + m2 * np.abs(v2).max() + 1e-300
    # momentum conserved
    np.testing.assert_allclose(r.momentum_after, r.momentum_before, rtol=0, atol=1e-12 * scale)
    np.testing.assert_allclose(m1 * r.v1_after + m2 * r.v2_after, m1 * v1 + m2 * v2,
                               rtol=0, atol=1e-12 * scale)
    # tangential components unchanged, normal relative velocity reversed and scaled by e
    t1, t2 = v1 - (v1 @ n) * n, v2 - (v2 @ n) * n
    np.testing.assert_allclose(r.v1_after - (r.v1_after @ n) * n, t1, atol=1e-12 * scale / m1)
    np.testing.assert_allclose(r.v2_after - (r.v2_after @ n) * n, t2, atol=1e-12 * scale / m2)
    closing = (v1 - v2) @ n
    assert (r.v1_after - r.v2_after) @ n == pytest.approx(-e * closing, rel=1e-9, abs=1e-9)
    # kinetic energy never increases; the loss is ½ μ (1 − e²) w²
    ke_scale = r.ke_before + 1e-300
    assert r.ke_after <= r.ke_before + 1e-12 * ke_scale
    mu = m1 * m2 / (m1 + m2)
    assert r.ke_loss == pytest.approx(0.5 * mu * (1 - e * e) * closing ** 2, rel=1e-6,
                                      abs=1e-10 * ke_scale)


@settings(max_examples=100, deadline=None)
@given(masses, vec, masses, vec)
def test_elastic_head_on_conserves_kinetic_energy(m1, v1, m2, v2):
    v1, v2 = np.array(v1), np.array(v2)
    assume(np.linalg.norm(v1 - v2) > 1e-3)
    r = collide(m1, v1, m2, v2, e=1)
    assert r.elastic
    assert abs(r.ke_after - r.ke_before) <= ELASTIC_RTOL * r.ke_before


@settings(max_examples=100, deadline=None)
@given(vec, st.floats(0, 2 * math.pi), st.floats(0.1, 10))
def test_exercise_23_equal_masses_elastic_right_angles(u, angle, m):
    # One ball at rest; any common normal with a closing speed.
    u = np.array(u)
    assume(np.linalg.norm(u) > 1e-2)
    n = np.array([math.cos(angle), math.sin(angle), 0.0])
    assume(u @ n > 1e-3 * np.linalg.norm(u))
    r = collide(m, u, m, [0, 0, 0], normal=n, e=1)
    big_u, big_v = r.v1_after, r.v2_after
    stationary = min(np.linalg.norm(big_u), np.linalg.norm(big_v)) < 1e-9 * np.linalg.norm(u)
    assert stationary or abs(big_u @ big_v) <= 1e-9 * (u @ u)


# ------------------------------------------------------------------- errors
@pytest.mark.parametrize("kwargs, message", [
    (dict(m1=-1, v1=[1, 0], m2=1, v2=[0, 0]), "must be positive"),
    (dict(m1=1, v1=[1, 0], m2=0, v2=[0, 0]), "must be positive"),
    (dict(m1=float("nan"), v1=[1, 0], m2=1, v2=[0, 0]), "must be positive"),
    (dict(m1=INF, v1=[1, 0], m2=1, v2=[0, 0]), "fixed surface"),
    (dict(m1=1, v1=[1, 0], m2=1, v2=[0, 0], e=1.5), r"\[0, 1\]"),
    (dict(m1=1, v1=[1, 0], m2=1, v2=[0, 0], e=-0.1), r"\[0, 1\]"),
    (dict(m1=1, v1=[1, 0], m2=1, v2=[0, 0], normal=[0, 0]), "zero vector"),
    (dict(m1=1, v1=[-1, 0], m2=1, v2=[0, 0], normal=[1, 0]), "not approaching"),
    (dict(m1=1, v1=[1, 0], m2=1, v2=[0, 0], normal=[0, 1]), "not approaching"),
    (dict(m1=1, v1=[1, 0], m2=1, v2=[1, 0]), "same velocity"),
    (dict(m1=1, v1=[1, 0], m2=1, v2=[0, 0, 0]), "same number"),
    (dict(m1=1, v1=[1, 0], m2=1, v2=[0, 0], normal=[1, 0, 0]), "components"),
    (dict(m1=1, v1=[1, 0, 0, 0], m2=1), "1, 2 or 3"),
    (dict(m1=1, v1=[float("inf"), 0], m2=1), "finite"),
])
def test_bad_input(kwargs, message):
    with pytest.raises(DynamicsError, match=message):
        collide(**kwargs)


@pytest.mark.parametrize("args", [(0, 0.5, 1), (1, 2, 1), (1, 0.5, 0), (1, -0.1, 1), (1, 0.5, 1.5)])
def test_bad_bounce_input(args):
    with pytest.raises(DynamicsError):
        restitution_from_bounces(*args)
