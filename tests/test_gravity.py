"""The two values of g: the seed's 9.81, every default, and standard gravity gₙ."""

from __future__ import annotations

import inspect

import pytest

import plumbob
from plumbob import units
from plumbob.bodies.primitives import box


def test_standard_gravity_is_the_defined_value():
    assert units.STANDARD_GRAVITY == 9.80665  # CGPM 1901, exact by definition
    assert units.SEED_GRAVITY == 9.81


@pytest.mark.parametrize("function", [plumbob.check, plumbob.poses,
                                      plumbob.lift])
def test_every_default_g_is_the_seeds(function):
    assert inspect.signature(function).parameters["g"].default == units.SEED_GRAVITY


def test_g_scales_the_energy_to_topple():
    """Energies are linear in g: the standard value gives 9.80665 / 9.81 of the default's."""
    body = box(2, 2, 4, density=1000.0)
    seed = plumbob.check(body).energy_to_topple
    standard = plumbob.check(body, g=units.STANDARD_GRAVITY).energy_to_topple
    assert standard == pytest.approx(seed * 9.80665 / 9.81, rel=1e-12)
