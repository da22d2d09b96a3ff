"""ParticleSystem: centre of mass (seed Exercises 3, 11, 12), momentum and kinetic energy."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.particles import ParticleSystem
from plumbob.errors import GeometryError


def test_exercise_3_earth_moon_center_of_mass_below_the_surface():
    # Masses kg, distance km (the seed works in kilometres).
    system = ParticleSystem([5.97e24, 7.34e22], [[0.0, 0.0], [3.84e5, 0.0]])
    x = system.center_of_mass[0]
    assert x == pytest.approx(4660, abs=10)          # seed: ≈ 4660 km from the centre
    radius = 1.27e4 / 2
    assert radius - x == pytest.approx(1690, abs=10)  # seed: ≈ 1690 km below the surface


@pytest.mark.parametrize("xs, expected", [
    ([0, 4, 6], 10 / 3),          # Exercise 11(a)
    ([0, 1, 4, 5, 6], 16 / 5),    # Exercise 11(b)
    ([-2, 0, 2, 4], 1.0),         # Exercise 12(a)
])
def test_exercises_11_12_equal_masses_on_the_x_axis(xs, expected):
    system = ParticleSystem([2.5] * len(xs), [[x, 0.0] for x in xs])
    np.testing.assert_allclose(system.center_of_mass, [expected, 0.0], rtol=1e-15, atol=1e-15)


def test_exercise_12b_equilateral_triangle():
    system = ParticleSystem([1.0] * 3, [[0, 0], [2, 0], [1, math.sqrt(3)]])
    np.testing.assert_allclose(system.center_of_mass, [1.0, 1 / math.sqrt(3)], rtol=1e-15)


def test_example_5_momentum_and_center_velocity():
    trucks = ParticleSystem([50_000, 30_000], [[0, 0], [20, 0]], [[2, 0], [0, 0]])
    np.testing.assert_array_equal(trucks.momentum, [100_000, 0])
    # After coupling both move at v_G = 1.25 m/s: the momentum is M v_G.
    np.testing.assert_allclose(trucks.velocity_of_center, [1.25, 0], rtol=1e-15)


def test_exercise_6_center_of_mass_velocity():
    # A at rest at the origin, B at x = 3 moving away at 6 m/s: v_G = 3 m/s.
    pair = ParticleSystem([1.0, 1.0], [[0.0, 0.0], [3.0, 0.0]], [[0.0, 0.0], [6.0, 0.0]])
    np.testing.assert_allclose(pair.velocity_of_center, [3.0, 0.0])
    x_g = pair.center_of_mass[0] + pair.velocity_of_center[0] * 0.5
    assert x_g == pytest.approx(3.0)  # so A is at 3 when B is back at 3


def test_exercise_26_kinetic_energies():
    before = ParticleSystem([3, 3], [[0, 0], [1, 0]], [[2, 0], [0, 0]])
    after = ParticleSystem([3, 3], [[0, 0], [1, 0]], [[1, 1], [1, -1]])
    assert before.kinetic_energy == 6.0 and after.kinetic_energy == 6.0  # (a) elastic
    before = ParticleSystem([1, 3], [[0, 0], [1, 0]], [[2, 1], [0, 1]])
    after = ParticleSystem([1, 3], [[0, 0], [1, 0]], [[0.5, 1], [0.5, 1]])
    assert before.kinetic_energy == 4.0 and after.kinetic_energy == 2.5   # (b) 1.5 J lost


def test_coalesced_pair_has_no_relative_kinetic_energy():
    pair = ParticleSystem([1.0, 4.0], [[0, 0, 0], [1, 2, 3]], [[1, 2, 3], [1, 2, 3]])
    assert pair.kinetic_energy_relative == pytest.approx(0.0, abs=1e-15)
    assert pair.kinetic_energy == pytest.approx(0.5 * 5 * 14)


def test_system_at_rest_and_existing_api():
    system = ParticleSystem([1.0, 3.0], [[0, 0], [4, 0]])
    np.testing.assert_array_equal(system.momentum, [0, 0])
    assert system.kinetic_energy == 0.0 and system.kinetic_energy_relative == 0.0
    props = system.mass_properties()
    assert props.mass == 4.0
    np.testing.assert_allclose(props.center_of_mass, [3.0, 0.0])
    with pytest.raises(GeometryError):
        ParticleSystem([1.0, -1.0], [[0, 0], [1, 0]])


finite = st.floats(-50, 50, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(0.01, 100), finite, finite, finite), min_size=1, max_size=8))
def test_koenig_decomposition_and_momentum(rows):
    masses = [r[0] for r in rows]
    velocities = [[r[1], r[2], r[3]] for r in rows]
    system = ParticleSystem(masses, np.zeros((len(rows), 3)), velocities)
    np.testing.assert_allclose(system.momentum, system.total_mass * system.velocity_of_center,
                               rtol=1e-12, atol=1e-9)
    vg = system.velocity_of_center
    total = 0.5 * system.total_mass * float(vg @ vg) + system.kinetic_energy_relative
    assert total == pytest.approx(system.kinetic_energy, rel=1e-9, abs=1e-9)
    assert system.kinetic_energy_relative <= system.kinetic_energy * (1 + 1e-12) + 1e-12
