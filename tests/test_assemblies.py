"""Assemblies of parts in different materials, and the issue's two example specs.

Equation (15): the combined centre of mass is the mass-weighted mean of the
parts' centres.
"""

from __future__ import annotations

import importlib.util
import json
import os

import numpy as np
import pytest
from conftest import SHAPES, rel
from hypothesis import given
from hypothesis import strategies as st

from plumbob.bodies import primitives as prim
from plumbob.bodies.csg import Assembly
from plumbob.bodies.density_field import DensityField
from plumbob.bodies.graded import GradedLamina, with_density_field
from plumbob.cli import main
from plumbob.loading import read
from plumbob.materials import density_of

GRADED_PLATE = os.path.join(SHAPES, "graded_plate.toml")
MACE = os.path.join(SHAPES, "mace_assembly.toml")


def mace_closed_form() -> tuple[float, float, float]:
    """(head mass, shaft mass, z_G) of the mace, from the materials table."""
    head = density_of("steel") * 4 / 3 * np.pi * 0.05**3
    shaft = density_of("oak") * np.pi * 0.01**2 * 1.0
    return head, shaft, (head * 1.05 + shaft * 0.5) / (head + shaft)


# ------------------------------------------------------------------ equation (15)


@given(st.lists(st.tuples(st.floats(1, 20000), st.floats(-10, 10), st.floats(-10, 10),
                          st.floats(-10, 10)), min_size=1, max_size=5))
def test_assembly_centre_is_the_mass_weighted_mean(parts):
    bodies = [prim.sphere(0.3, density=rho).translated([x, y, z]) for rho, x, y, z in parts]
    asm = Assembly(tuple(bodies))
    each = asm.part_properties()
    masses = np.array([p.mass for p in each])
    centres = np.array([p.center_of_mass for p in each])
    total = asm.mass_properties()
    assert total.mass == pytest.approx(masses.sum(), rel=1e-14)
    assert rel(total.center_of_mass, masses @ centres / masses.sum(), scale=20) <= 1e-13
    assert total.parts == len(parts)


def test_assembly_of_graded_and_uniform_parts_follows_equation_15():
    plate = with_density_field(prim.box(1, 1, 0.1), DensityField.from_expression("1 + x"))
    ball = prim.sphere(0.2, density=density_of("lead")).translated([2, 0, 0])
    asm = Assembly((plate, ball))
    p, b = plate.mass_properties(), ball.mass_properties()
    assert p.mass == pytest.approx(0.15, rel=1e-14)  # ∫(1 + x) over 1 × 1 × 0.1
    total = asm.mass_properties()
    want = (p.mass * p.center_of_mass + b.mass * b.center_of_mass) / (p.mass + b.mass)
    assert rel(total.center_of_mass, want, scale=2) <= 1e-14


def test_two_halves_of_one_body_equal_the_body():
    rho = density_of("granite")
    whole = prim.box(2, 1, 1, density=rho).mass_properties()
    halves = Assembly((prim.box(1, 1, 1, density=rho),
                       prim.box(1, 1, 1, density=rho).translated([1, 0, 0]))).mass_properties()
    assert halves.mass == pytest.approx(whole.mass, rel=1e-14)
    assert rel(halves.center_of_mass, whole.center_of_mass, scale=2) <= 1e-14
    assert rel(halves.inertia, whole.inertia) <= 1e-13


def test_two_graded_halves_equal_the_graded_body():
    field = DensityField.from_expression("1 + x + y^2")
    whole = with_density_field(prim.disc(1), field).mass_properties()
    top = prim.semicircle(1)
    bottom = prim.semicircle(1).transformed(np.diag([1.0, -1.0]))
    halves = with_density_field(Assembly((top, bottom)), field).mass_properties()
    assert whole.exact and halves.exact
    assert halves.mass == pytest.approx(whole.mass, rel=1e-13)
    assert rel(halves.center_of_mass, whole.center_of_mass, scale=1) <= 1e-13
    assert rel(halves.inertia, whole.inertia) <= 1e-13


# ------------------------------------------------------------------ the example specs


def test_graded_plate_spec():
    body = read(GRADED_PLATE).body
    assert isinstance(body, GradedLamina)
    props = body.mass_properties()
    assert props.exact
    assert props.mass == pytest.approx(1.5, rel=1e-15)
    np.testing.assert_allclose(props.center_of_mass, [5 / 9, 0.5], rtol=1e-15)


def test_mace_assembly_spec():
    body = read(MACE).body
    assert body.kind == "assembly"
    head, shaft, zg = mace_closed_form()
    parts = {p.name: p.mass_properties() for p in body.parts}
    assert parts["head"].mass == pytest.approx(head, rel=1e-14)
    assert parts["shaft"].mass == pytest.approx(shaft, rel=1e-14)
    np.testing.assert_allclose(parts["head"].center_of_mass, [0, 0, 1.05], atol=1e-15)
    np.testing.assert_allclose(parts["shaft"].center_of_mass, [0, 0, 0.5], atol=1e-15)
    props = body.mass_properties()
    assert props.mass == pytest.approx(head + shaft, rel=1e-14)
    np.testing.assert_allclose(props.center_of_mass, [0, 0, zg], rtol=1e-14, atol=1e-15)
    assert zg == pytest.approx(1.019805, abs=1e-6)  # the number written in the spec


def test_mass_command_on_the_assembly(capsys):
    assert main(["mass", MACE, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    head, shaft, zg = mace_closed_form()
    assert data["mass"] == pytest.approx(head + shaft, rel=1e-12)
    assert data["center_of_mass"][2] == pytest.approx(zg, rel=1e-12)


def test_mass_command_on_the_graded_plate(capsys):
    assert main(["mass", GRADED_PLATE, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["center_of_mass"] == pytest.approx([5 / 9, 0.5], rel=1e-14)
    assert data["exact"] is True


# The stability and energy commands belong to other engineers and may land after this
# file. Until a command's module exists its test is an expected failure, clearly marked
# (it is not skipped): the lead runs these once `check`, `poses` and `lift` are in.
def _command(name: str):
    missing = importlib.util.find_spec(f"plumbob.commands.{name}") is None
    return pytest.param(name, marks=pytest.mark.xfail(
        missing, reason=f"plumbob {name} is not written yet: run again when it lands",
        strict=True))


@pytest.mark.parametrize("command", [_command("check"), _command("poses"), _command("lift")])
@pytest.mark.parametrize("spec", [MACE, GRADED_PLATE])
def test_every_command_works_on_an_assembly(command, spec, capsys):
    assert main([command, spec, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert isinstance(data, dict) and data
