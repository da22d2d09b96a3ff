"""Potential energy, pose changes, lift energy and crew time (the seed's section 2.4)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from plumbob.bodies.csg import Assembly
from plumbob.bodies.primitives import box, pyramid, rectangle
from plumbob.energy import (
    DAYS_PER_YEAR,
    crew_time,
    lift_energy,
    pose_energy_change,
    potential_energy,
    seed_work_per_day,
)
from plumbob.errors import ArgumentError, PlumbobError
from plumbob.massprops import point_mass, rotation_matrix

G = 9.81


def cheops():
    half = 115.0
    base = [(-half, -half), (half, -half), (half, half), (-half, half)]
    return pyramid(base, 147.0, density=2500.0)


def test_block_gains_3Mgh_2_from_lying_to_upright():
    """The seed's Exercise 17: a block h × h × 4h, centre 2h up upright and h/2 lying."""
    h = 1.0
    block = box(h, h, 4 * h, density=1000.0)
    m = 4000.0
    change = pose_energy_change(block, [1, 0, 0], [0, 0, -1])
    assert change.height_from == pytest.approx(h / 2)
    assert change.height_to == pytest.approx(2 * h)
    assert change.energy == pytest.approx(1.5 * m * G * h, rel=1e-14)
    back = pose_energy_change(block, [0, 0, -1], [0, 1, 0])
    assert back.energy == pytest.approx(-1.5 * m * G * h, rel=1e-14)


def test_pose_change_does_not_depend_on_where_the_body_is():
    block = box(1, 1, 4, density=2.0)
    turn = rotation_matrix([1, 1, 0], 0.7)
    moved = block.transformed(turn, np.array([5.0, -3.0, 100.0]))
    a = pose_energy_change(block, [1, 0, 0], [0, 0, -1])
    b = pose_energy_change(moved, turn @ [1, 0, 0], turn @ [0, 0, -1])
    assert b.energy == pytest.approx(a.energy, rel=1e-12)


def test_potential_energy_is_Mgh_of_the_centre():
    """Equation (23): the particles' Σ mᵢ g zᵢ is M g z_G."""
    parts = [point_mass(2.0, [0, 0, 1.0]), point_mass(3.0, [1, 0, 4.0])]
    total = parts[0] + parts[1]
    pe = potential_energy(total, g=G)
    assert pe.energy == pytest.approx(G * (2 * 1 + 3 * 4), rel=1e-14)
    assert potential_energy(total, datum=1.0, g=G).energy == pytest.approx(G * (2 * 0 + 3 * 3))
    assert pe.height == pytest.approx(14 / 5)


def test_a_lamina_measures_height_along_y():
    plate = rectangle(2.0, 3.0, density=5.0)  # 30 kg, centre 1.5 m up
    assert potential_energy(plate, g=10.0).energy == pytest.approx(450.0)
    assert lift_energy(plate, g=10.0).lift_energy == pytest.approx(450.0)


def test_great_pyramid_lift_energy_and_crew_time():
    """The seed's Exercise 20: M ≈ 6.48e9 kg, centre h/4 up, Mgh/4 ≈ 2.34e12 J;
    1000 men each lifting 1000 kg through 1 m a day: ≈ 2.4e5 days, ≈ 652 years."""
    lift = lift_energy(cheops())
    assert lift.mass == pytest.approx(230**2 * 147 / 3 * 2500, rel=1e-12)
    assert lift.mass == pytest.approx(6.48e9, rel=1e-3)
    assert lift.datum == pytest.approx(0.0, abs=1e-9)
    assert lift.com_height == pytest.approx(147 / 4, rel=1e-12)
    assert lift.lift_energy == pytest.approx(2.34e12, rel=2e-3)
    time = crew_time(lift.lift_energy, seed_work_per_day(), 1000)
    assert time.work_per_day == pytest.approx(1000 * G)
    assert time.crew_days == pytest.approx(2.4e5, rel=0.01)
    assert time.person_days == pytest.approx(1000 * time.crew_days)
    assert round(time.crew_years) == 652
    assert time.crew_years == pytest.approx(time.crew_days / DAYS_PER_YEAR)


def test_lift_datum_defaults_to_the_ground_the_body_stands_on():
    raised = box(2, 2, 10, density=1.0).translated([0, 0, 7.0])
    assert lift_energy(raised, g=10.0).lift_energy == pytest.approx(40 * 10 * 5)
    assert lift_energy(raised, g=10.0, datum=0.0).lift_energy == pytest.approx(40 * 10 * 12)


@given(st.floats(0.1, 100), st.floats(0.1, 100), st.floats(-50, 50))
def test_lift_energy_of_a_stack_is_the_sum_of_its_parts(m1, m2, shift):
    lower = box(1, 1, 1, density=m1)
    upper = box(1, 1, 1, density=m2).translated([0, 0, 1.0])
    stack = Assembly((lower, upper)).translated([0, 0, shift])
    expected = G * (m1 * 0.5 + m2 * 1.5)
    assert lift_energy(stack).lift_energy == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("kw", [{"g": 0.0}, {"g": -9.81}, {"g": float("nan")}])
def test_bad_gravity(kw):
    with pytest.raises(PlumbobError):
        lift_energy(box(1, 1, 1), **kw)


@pytest.mark.parametrize("args", [(1e6, 0.0, 10), (1e6, 100.0, 0), (1e6, 100.0, 2.5),
                                  (-1.0, 100.0, 1), (float("inf"), 100.0, 1)])
def test_bad_crew_time(args):
    with pytest.raises(PlumbobError):
        crew_time(*args)


def test_down_is_the_one_spelling_of_the_orientation_and_up_its_old_opposite():
    """``down`` as check and poses take it; ``up`` still read; the same heights either way."""
    block = box(2, 2, 10, density=1.0)
    tilted = np.array([1.0, -2.0, -3.0])
    assert lift_energy(block, down=tilted).lift_energy == pytest.approx(
        lift_energy(block, up=-tilted).lift_energy, rel=1e-12)
    assert lift_energy(block, down=[0, 0, -1]).lift_energy == lift_energy(block).lift_energy
    # a 40 kg block on its side (down = −x): its centre 1 m above the lowest point
    assert lift_energy(block, down=[-1, 0, 0], g=10.0).lift_energy == pytest.approx(400.0)
    props = block.mass_properties()
    assert potential_energy(props, down=[0, 0, -1], g=10.0).height == pytest.approx(5.0)
    with pytest.raises(ArgumentError, match="not both"):
        potential_energy(props, down=[0, 0, -1], up=[0, 0, 1])
