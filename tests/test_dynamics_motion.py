"""Particle systems in motion: closed forms, conservation laws, constraints, specs."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.particles import ParticleSystem
from plumbob.dynamics import (
    Link,
    MotionModel,
    Spring,
    simulate,
    spring_pair_pull,
)
from plumbob.errors import DynamicsError, InputFileError, SpecError
from plumbob.spec import load_simulation, parse_simulation

SHAPES = Path(__file__).resolve().parents[1] / "shapes"
G = 9.81


def run_spec(name: str, until: float, samples: int = 101):
    spec = load_simulation(SHAPES / name)
    return spec, simulate(spec.model, until, samples, **spec.options)


# ------------------------------------------------------------ shipped specs
def test_spring_pair_matches_example_2_closed_form():
    spec, run = run_spec("spring_pair.toml", 5.0)
    assert spec.model.names == ("A", "B")
    xa, xb, xg = spring_pair_pull(2.0, 50.0, 1.0, 10.0, run.times)
    np.testing.assert_allclose(run.positions[:, 0, 0], xa, rtol=0, atol=1e-7)
    np.testing.assert_allclose(run.positions[:, 1, 0], xb, rtol=0, atol=1e-7)
    np.testing.assert_allclose(run.center_of_mass[:, 0], xg, rtol=0, atol=1e-12)
    np.testing.assert_allclose(run.positions[:, :, 1], 0.0, atol=1e-15)
    # F = M a_G: the pull alone accelerates G at P/(2m); dP/dt = P.
    np.testing.assert_allclose(run.center_of_mass_acceleration, [[2.5, 0.0]] * len(run.times),
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(run.momentum[:, 0], 10.0 * run.times, rtol=1e-10, atol=1e-12)
    assert run.newton_residual < 1e-12


def test_mace_center_of_mass_follows_the_parabola_and_the_ends_loop():
    _, run = run_spec("mace_throw.toml", 1.6, 161)
    t = run.times[:, None]
    parabola = np.array([2.0, 8.0]) * t + 0.5 * np.array([0.0, -G]) * t * t
    np.testing.assert_allclose(run.center_of_mass, parabola, rtol=0, atol=1e-6)
    # The rod turns uniformly about G at 12 rad/s (no torque about G from gravity).
    turn = np.column_stack([np.cos(12.0 * run.times), np.sin(12.0 * run.times)])
    np.testing.assert_allclose(run.positions[:, 0], parabola - 0.3 * turn, rtol=0, atol=1e-6)
    np.testing.assert_allclose(run.positions[:, 1], parabola + 0.9 * turn, rtol=0, atol=1e-6)
    lengths = np.linalg.norm(run.positions[:, 1] - run.positions[:, 0], axis=1)
    np.testing.assert_allclose(lengths, 1.2, rtol=1e-8)
    assert run.max_constraint_error < 1e-8
    # dP/dt = M g, and the ends do loop: B's height is not monotonic on the way up.
    np.testing.assert_allclose(run.momentum, [4.0, 16.0] + 2.0 * np.array([0, -G]) * t,
                               rtol=1e-10, atol=1e-9)
    rising = run.times < 8.0 / G
    assert np.any(np.diff(run.positions[rising, 1, 1]) < 0)
    # Energy: translational + rotational + potential is constant.
    energy = run.kinetic_energy + 2.0 * G * run.center_of_mass[:, 1]
    np.testing.assert_allclose(energy, energy[0], rtol=1e-8)


# ------------------------------------------------------------ conservation
@settings(max_examples=8, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(2, 5), st.sampled_from([2, 3]))
def test_momentum_conserved_without_external_force(seed, n, dim):
    rng = np.random.default_rng(seed)
    masses = rng.uniform(0.1, 5.0, n)
    positions = rng.uniform(-2.0, 2.0, (n, dim))
    velocities = rng.uniform(-3.0, 3.0, (n, dim))
    springs = tuple(Spring(i, (i + 1) % n, float(rng.uniform(1, 30)), float(rng.uniform(0, 2)))
                    for i in range(n - 1 if n == 2 else n))
    system = ParticleSystem(masses, positions, velocities)
    run = simulate(MotionModel(system, springs=springs), 2.0, samples=21)
    scale = float(masses @ np.linalg.norm(velocities, axis=1))
    assert np.max(np.abs(run.momentum - system.momentum)) <= 1e-9 * scale
    np.testing.assert_allclose(run.center_of_mass,
                               system.center_of_mass + np.outer(run.times,
                                                                system.velocity_of_center),
                               rtol=0, atol=1e-9 * (1 + np.abs(positions).max()))
    assert run.newton_residual < 1e-12


def test_spinning_rigid_triangle_in_3d():
    side = 1.0
    positions = np.array([[0, 0, 0], [side, 0, 0], [side / 2, side * math.sqrt(3) / 2, 0]])
    masses = np.array([1.0, 2.0, 3.0])
    center = masses @ positions / masses.sum()
    omega = np.array([0.0, 0.0, 5.0])
    velocities = np.array([0.5, -0.2, 0.1]) + np.cross(omega, positions - center)
    system = ParticleSystem(masses, positions, velocities)
    links = (Link(0, 1, side), Link(1, 2, side), Link(2, 0, side))
    run = simulate(MotionModel(system, links=links), 3.0, samples=31)
    np.testing.assert_allclose(run.momentum, np.broadcast_to(system.momentum, (31, 3)),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(run.kinetic_energy, system.kinetic_energy, rtol=1e-8)
    for i, j in ((0, 1), (1, 2), (2, 0)):
        lengths = np.linalg.norm(run.positions[:, i] - run.positions[:, j], axis=1)
        np.testing.assert_allclose(lengths, side, rtol=1e-8)


# ------------------------------------------------------------------ friction
def test_block_slides_to_rest():
    block = ParticleSystem([2.0], [[0.0, 0.0]], [[3.0, 4.0]])
    run = simulate(MotionModel(block, friction=0.5, surface_gravity=G), 2.0, samples=41)
    stop = 5.0 / (0.5 * G)                         # |v0| / (μ g)
    distance = 25.0 / (2 * 0.5 * G)                # |v0|² / (2 μ g)
    np.testing.assert_allclose(run.positions[-1, 0], [0.6 * distance, 0.8 * distance],
                               rtol=1e-6)
    sliding = run.times < stop - 0.05
    np.testing.assert_allclose(run.external_force[sliding], np.broadcast_to(
        [-0.5 * 2.0 * G * 0.6, -0.5 * 2.0 * G * 0.8], (sliding.sum(), 2)), rtol=1e-9)
    assert np.linalg.norm(run.velocities[-1, 0]) < 1e-5


def test_exercise_4_rod_on_a_rough_incline():
    # Down-slope axis x: gravity g sin α along x, the surface pressing with g cos α.
    alpha, mu = math.radians(30), 0.2
    pair = ParticleSystem([1.0, 3.0], [[0.0, 0.0], [0.8, 0.0]], [[0.5, 0.0], [0.5, 0.0]])
    model = MotionModel(pair, links=(Link(0, 1, 0.8),), gravity=[G * math.sin(alpha), 0.0],
                        friction=mu, surface_gravity=G * math.cos(alpha))
    run = simulate(model, 1.0, samples=11)
    a = G * (math.sin(alpha) - mu * math.cos(alpha))
    np.testing.assert_allclose(run.center_of_mass_acceleration[:, 0], a, rtol=1e-9)
    np.testing.assert_allclose(run.velocities[-1, :, 0], 0.5 + a, rtol=1e-8)


# ------------------------------------------------------------------- strings
def test_slack_string_snaps_taut():
    # B moves towards and past A at 1 m/s; the 1 m string is slack until B is 1 m
    # beyond A (t = 2), then jerks both to the common velocity −0.5 m/s (momentum kept).
    pair = ParticleSystem([1.0, 1.0], [[0.0, 0.0], [1.0, 0.0]], [[0.0, 0.0], [-1.0, 0.0]])
    run = simulate(MotionModel(pair, links=(Link(0, 1, 1.0, "string"),)), 3.0, samples=31)
    assert len(run.string_jerks) == 1 and run.string_jerks[0][0] == pytest.approx(2.0, abs=1e-6)
    before = run.times < 2.0 - 1e-9
    np.testing.assert_allclose(run.positions[before, 0, 0], 0.0, atol=1e-12)
    np.testing.assert_allclose(run.positions[before, 1, 0], 1.0 - run.times[before], atol=1e-9)
    after = run.times > 2.0
    np.testing.assert_allclose(run.positions[after, 0, 0], -0.5 * (run.times[after] - 2.0),
                               atol=1e-6)
    np.testing.assert_allclose(run.momentum[:, 0], -1.0, rtol=1e-12)
    assert run.kinetic_energy[-1] == pytest.approx(0.25)      # half lost, as for e = 0


def test_string_does_not_push():
    pair = ParticleSystem([1.0, 1.0], [[0.0, 0.0], [1.0, 0.0]])
    model = MotionModel(pair, links=(Link(0, 1, 1.0, "string"),), forces=[[2.0, 0.0], [0, 0]])
    run = simulate(model, 0.5, samples=6)
    np.testing.assert_allclose(run.positions[-1], [[0.25, 0.0], [1.0, 0.0]], atol=1e-12)


# -------------------------------------------------------------------- errors
def pair(velocities=None):
    return ParticleSystem([1.0, 1.0], [[0.0, 0.0], [1.0, 0.0]], velocities)


@pytest.mark.parametrize("make, message", [
    (lambda: MotionModel(pair(), links=(Link(0, 1, 2.0),)), "start 1 m apart"),
    (lambda: MotionModel(pair(), links=(Link(0, 1, 0.5, "string"),)), "start 1 m apart"),
    (lambda: MotionModel(pair([[0, 0], [1, 0]]), links=(Link(0, 1, 1.0),)), "stretch"),
    (lambda: MotionModel(pair([[0, 0], [1, 0]]), links=(Link(0, 1, 1.0, "string"),)), "stretch"),
    (lambda: MotionModel(pair(), links=(Link(0, 1, 1.0, "chain"),)), "'rod' or a 'string'"),
    (lambda: MotionModel(pair(), springs=(Spring(0, 0, 1.0, 1.0),)), "two different"),
    (lambda: MotionModel(pair(), springs=(Spring(0, 2, 1.0, 1.0),)), "only 2 particles"),
    (lambda: MotionModel(pair(), springs=(Spring(0, 1, -1.0, 1.0),)), "positive stiffness"),
    (lambda: MotionModel(pair(), friction=0.3), "supporting surface"),
    (lambda: MotionModel(pair(), gravity=[0, 0, -9.81]), "gravity"),
    (lambda: MotionModel(pair(), forces=[[1, 0]]), "one vector"),
    (lambda: simulate(MotionModel(pair()), 0.0), "positive"),
    (lambda: simulate(MotionModel(pair()), float("nan")), "positive"),
    (lambda: simulate(MotionModel(pair()), 1.0, samples=1), "at least 2"),
])
def test_bad_models(make, message):
    with pytest.raises(DynamicsError, match=message):
        make()


def test_compressed_taut_string_is_allowed():
    # Ends approaching: the string simply goes slack.
    run = simulate(MotionModel(pair([[0, 0], [-1, 0]]), links=(Link(0, 1, 1.0, "string"),)),
                   0.5, samples=3)
    np.testing.assert_allclose(run.positions[-1, 1], [0.5, 0.0])


# --------------------------------------------------------------------- specs
def spec(**extra) -> dict:
    base = {"particle": [{"name": "A", "mass": 1.0, "position": [0.0, 0.0]},
                         {"name": "B", "mass": 2.0, "position": [1.0, 0.0]}]}
    base.update(extra)
    return base


def test_spec_expressions_defaults_and_options():
    loaded = parse_simulation(spec(
        parameters={"k": 10, "k2": "2*k"},
        spring=[{"between": ["A", "B"], "stiffness": "k2"}],
        rod=[{"between": ["A", "B"]}],
        surface={"friction": 0.25},
        solver={"rtol": 1e-8, "method": "Radau"},
    ))
    model = loaded.model
    assert model.springs == (Spring(0, 1, 20.0, 1.0),)    # natural length: initial distance
    assert model.links == (Link(0, 1, 1.0, "rod"),)
    assert model.surface_gravity == G
    np.testing.assert_array_equal(model.friction, [0.25, 0.25])
    assert loaded.options == {"rtol": 1e-8, "method": "Radau"}


@pytest.mark.parametrize("data, error, message", [
    (spec(colour="red"), SpecError, "unknown key 'colour'"),
    ({"particle": []}, SpecError, "at least one"),
    ({"particle": [{"mass": 1.0}]}, SpecError, "needs a mass"),
    ({"particle": [{"mass": -1.0, "position": [0, 0]}]}, DynamicsError, "positive"),
    ({"particle": [{"mass": True, "position": [0, 0]}]}, SpecError, "number"),
    ({"particle": [{"mass": "2*q", "position": [0, 0]}]}, SpecError, "unknown name"),
    ({"particle": [{"mass": 1, "position": [0, 0]}, {"mass": 1, "position": [0, 0, 1]}]},
     SpecError, "components"),
    (spec(spring=[{"between": ["A", "C"], "stiffness": 1}]), SpecError, "not defined"),
    (spec(spring=[{"between": ["A", "B"]}]), SpecError, "stiffness"),
    (spec(rod=[{"between": ["A", "A"]}]), DynamicsError, "itself"),
    (spec(rod=[{"between": ["A", "B"], "length": 3}]), DynamicsError, "start 1 m apart"),
    (spec(kind="lamina"), SpecError, "not a simulation"),
    (spec(solver={"method": "Euler"}), SpecError, "method"),
    (spec(gravity=[0, 0, -9.81]), SpecError, "components"),
])
def test_bad_specs(data, error, message):
    with pytest.raises(error, match=message):
        parse_simulation(data, "bad.toml")


def test_spec_files(tmp_path):
    with pytest.raises(InputFileError, match="no such file"):
        load_simulation(tmp_path / "missing.toml")
    broken = tmp_path / "broken.toml"
    broken.write_text("[[particle]\nmass = 1\n")
    with pytest.raises(SpecError, match="not valid TOML"):
        load_simulation(broken)
    bad = tmp_path / "bad.toml"
    bad.write_text('[[particle]]\nmass = 0\nposition = [0, 0]\n')
    with pytest.raises(DynamicsError) as info:
        load_simulation(bad)
    assert str(bad) in str(info.value)
