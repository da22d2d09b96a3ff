"""Two-particle systems of the seed's section 1 (closed forms, and the simulation agreeing)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from plumbob.bodies.particles import ParticleSystem
from plumbob.dynamics import (
    Link,
    MotionModel,
    Spring,
    VibratingMolecule,
    center_of_mass_acceleration,
    mace_balance_point,
    max_pull_before_break,
    partner_position,
    pulley_lift,
    rigid_pair,
    simulate,
    spring_pair_pull,
)
from plumbob.errors import DynamicsError

G = 9.81


# ---------------------------------------------------------------------- lift
def test_exercise_1_lift_numbers():
    lift = pulley_lift(1000, 1065)
    assert lift.acceleration == pytest.approx(65 * G / 2065, rel=1e-15)
    assert round(lift.acceleration, 2) == 0.31
    assert round(lift.speed_after(100), 1) == 7.9
    assert lift.speed_after(100) == pytest.approx(math.sqrt(2 * 65 * G / 2065 * 100))


def test_exercise_1_tension_and_pulley_reaction():
    m1, m2, g = 3.0, 5.0, 9.8
    lift = pulley_lift(m1, m2, g)
    assert lift.acceleration == pytest.approx((m2 - m1) * g / (m1 + m2))
    assert lift.tension == pytest.approx(2 * m1 * m2 * g / (m1 + m2))
    assert lift.pulley_reaction == pytest.approx(4 * m1 * m2 * g / (m1 + m2))
    # Newton's second law for each particle (equations 1 and 2), lift moving down.
    assert m2 * g - lift.tension == pytest.approx(m2 * lift.acceleration)
    assert m1 * g - lift.tension == pytest.approx(-m1 * lift.acceleration)
    assert lift.pulley_reaction < (m1 + m2) * g
    assert lift.time_to(4.0) == pytest.approx(math.sqrt(2 * 4.0 / lift.acceleration))


def test_lift_balanced_and_reversed():
    balanced = pulley_lift(10, 10)
    assert balanced.acceleration == 0 and balanced.tension == pytest.approx(10 * G)
    with pytest.raises(DynamicsError, match="never moves"):
        balanced.time_to(1.0)
    assert pulley_lift(12, 10).acceleration < 0  # the lift rises
    with pytest.raises(DynamicsError, match="positive"):
        pulley_lift(0, 10)


# ---------------------------------------------------------------------- mace
@pytest.mark.parametrize("m1, m2, length", [(3.0, 1.0, 1.2), (1.0, 1.0, 2.0), (10.0, 0.1, 0.9)])
def test_mace_balance_point_is_the_center_of_mass(m1, m2, length):
    b = mace_balance_point(m1, m2, length)
    assert b.from_head / b.from_tail == pytest.approx(m2 / m1)     # equation (5)
    assert b.from_head + b.from_tail == pytest.approx(length)
    mace = ParticleSystem([m1, m2], [[0.0, 0.0], [length, 0.0]])
    assert mace.center_of_mass[0] == pytest.approx(b.from_head, rel=1e-14)


# ------------------------------------------------------------------ molecule
def test_nitrogen_molecule_closed_form_and_simulation():
    # N₂: two 14.007 u atoms, bond stiffness ≈ 2295 N/m, bond length 1.098e-10 m.
    m = 14.007 * 1.66053907e-27
    mol = VibratingMolecule(m, m, 2295.0, 1.098e-10)
    assert mol.angular_frequency == pytest.approx(math.sqrt(2 * 2295.0 / m))
    x1, x2, v1, v2 = 0.0, 1.108e-10, 480.0, 520.0
    pair = ParticleSystem([m, m], [[x1, 0.0], [x2, 0.0]], [[v1, 0.0], [v2, 0.0]])
    model = MotionModel(pair, springs=(Spring(0, 1, 2295.0, 1.098e-10),))
    run = simulate(model, 3 * mol.period, samples=61)
    a, b, g = mol.positions(run.times, x1, x2, v1, v2)
    amplitude = 1e-12
    np.testing.assert_allclose(run.positions[:, 0, 0], a, rtol=0, atol=1e-6 * amplitude)
    np.testing.assert_allclose(run.positions[:, 1, 0], b, rtol=0, atol=1e-6 * amplitude)
    # G moves uniformly at (v1 + v2)/2 whatever the vibration (Newton's first law).
    np.testing.assert_allclose(run.center_of_mass[:, 0], g, rtol=1e-12)
    np.testing.assert_allclose(run.center_of_mass_velocity[:, 0], 500.0, rtol=1e-12)
    # After a whole number of periods the bond length is back where it started.
    assert run.positions[-1, 1, 0] - run.positions[-1, 0, 0] == pytest.approx(x2 - x1,
                                                                               rel=1e-9)


def test_unequal_molecule_frequency():
    mol = VibratingMolecule(1.0, 3.0, 6.0, 1.0)
    assert mol.angular_frequency == pytest.approx(math.sqrt(6.0 * 4.0 / 3.0))
    assert mol.period == pytest.approx(2 * math.pi / math.sqrt(8.0))
    with pytest.raises(DynamicsError):
        VibratingMolecule(1.0, -1.0, 6.0, 1.0)


# ---------------------------------------------------------------- example 2
def test_example_2_closed_form_satisfies_the_seed():
    m, k, length, p = 2.0, 50.0, 1.0, 10.0
    l0, w = length / 2, math.sqrt(2 * k / m)
    t = np.linspace(0, 3, 301)
    xa, xb, xg = spring_pair_pull(m, k, length, p, t)
    np.testing.assert_allclose((xa + xb) / 2, xg, atol=1e-15)                 # G midway
    np.testing.assert_allclose(xg, p * t * t / (4 * m))                      # (a)
    d = (xb - xa) / 2
    np.testing.assert_allclose(d, l0 + p / (4 * k) * (1 - np.cos(w * t)))     # (c)
    # (b): m d̈ + 2k d = 2k l0 + P/2, checked with a central difference.
    h = t[1] - t[0]
    d_dd = (d[2:] - 2 * d[1:-1] + d[:-2]) / h ** 2
    np.testing.assert_allclose(m * d_dd + 2 * k * d[1:-1], 2 * k * l0 + p / 2, rtol=2e-3)


# ------------------------------------------------------- pairs moving as one
def test_exercise_8_string_breaking_pull():
    assert max_pull_before_break(50, 50, 10) == 20.0
    # The simulated taut string carries half the pull: a 20 N pull gives 10 N tension.
    pair = ParticleSystem([50.0, 50.0], [[0.0, 0.0], [1.0, 0.0]], names=("A", "B"))
    model = MotionModel(pair, links=(Link(0, 1, 1.0, "string"),), forces=[[0, 0], [20.0, 0]],
                        surface_gravity=G)
    run = simulate(model, 2.0, samples=21)
    accel = run.center_of_mass_acceleration[:, 0]
    np.testing.assert_allclose(accel, 0.2, rtol=1e-9)
    tension = 50.0 * (run.velocities[-1, 0, 0] / 2.0)  # m_A a_A, A moves only by the string
    assert tension == pytest.approx(10.0, rel=1e-8)
    assert run.max_constraint_error < 1e-8


def test_exercise_10_pair_on_a_track():
    pair = rigid_pair(1.0, 4.0, 20.0)
    assert (pair.acceleration, pair.internal_force) == (4.0, 16.0)
    # The same with a rod in the simulation.
    system = ParticleSystem([4.0, 1.0], [[0.0, 0.0], [0.5, 0.0]])
    model = MotionModel(system, links=(Link(0, 1, 0.5),), forces=[[0, 0], [20.0, 0]])
    # The checks ask for 1e-9: the solver's tolerance must be finer than that, since the
    # rod's drift (about 8 rtol in length) comes back as velocity through the stabilisation.
    run = simulate(model, 1.0, samples=11, rtol=1e-11)
    np.testing.assert_allclose(run.velocities[-1, :, 0], [4.0, 4.0], rtol=1e-9)
    np.testing.assert_allclose(run.positions[-1, :, 0], [2.0, 2.5], rtol=1e-9)


def test_exercise_9_friction_on_a_wire():
    a = center_of_mass_acceleration([3.0, 0.5], [[-0.4 * 3.0 * G], [-0.4 * 0.5 * G]])
    np.testing.assert_allclose(a, [-0.4 * G])
    # Simulated with a spring between them (internal forces do not matter).
    system = ParticleSystem([3.0, 0.5], [[0.0, 0.0], [1.0, 0.0]], [[2.0, 0.0], [1.5, 0.0]])
    model = MotionModel(system, springs=(Spring(0, 1, 40.0, 1.0),), friction=0.4,
                        surface_gravity=G)
    run = simulate(model, 0.3, samples=31)
    assert np.all(run.velocities[:, :, 0] > 0)     # both still moving forwards
    np.testing.assert_allclose(run.center_of_mass_acceleration[:, 0], -0.4 * G, rtol=1e-9)
    np.testing.assert_allclose(run.center_of_mass_velocity[:, 0],
                               (3.0 * 2.0 + 0.5 * 1.5) / 3.5 - 0.4 * G * run.times, rtol=1e-8)


def test_exercise_6_where_is_a():
    # G starts at 1.5 and moves at 3 m/s; at t = 0.5 it is at 3, and so is B: A is at 3.
    x_g = 1.5 + 3.0 * 0.5
    np.testing.assert_allclose(partner_position(x_g, 1.0, 3.0, 1.0), [3.0])
    np.testing.assert_allclose(partner_position([1.0, 2.0], 2.0, [0.0, 0.0], 1.0), [3.0, 6.0])
    with pytest.raises(DynamicsError):
        partner_position([1.0, 2.0], 2.0, [0.0], 1.0)
