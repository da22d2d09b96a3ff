"""``str(result)`` is the report its command prints (issue 22): the library never prints,
but ``print(plumbob.check("part.stl", units="mm"))`` shows exactly what ``plumbob check
part.stl --units mm`` shows — the same function of ``report/`` writes both — and the
reprs give every number its unit."""

from __future__ import annotations

import pytest

import plumbob
from plumbob.bodies import primitives as P
from plumbob.cli import main
from plumbob.formats.writers import stl_bytes

OPTIONS = {"units": "mm", "material": "pla"}
FLAGS = ["--units", "mm", "--material", "pla"]


@pytest.fixture(scope="module")
def part(tmp_path_factory):
    """A 40 × 20 × 60 mm box, a corner at the origin, as an STL in mm (no unit inside)."""
    path = tmp_path_factory.mktemp("text") / "part.stl"
    path.write_bytes(stl_bytes(P.box(0.04, 0.02, 0.06).surface().triangles, "part", 1e-3))
    return str(path)


def _cli(capsys, *args) -> str:
    capsys.readouterr()
    assert main(list(args)) in (0, 1)
    return capsys.readouterr().out


def test_str_of_check_is_the_check_command_s_report(part, capsys):
    verdict = plumbob.check(part, require_tilt_deg=10, **OPTIONS)
    assert str(verdict) + "\n" == _cli(capsys, "check", part, *FLAGS, "--require-tilt", "10")
    assert "stability margin  10 mm" in str(verdict)  # the part's own units: mm and g
    assert "height of centre  0.03 m" in verdict.text("m,kg").splitlines()


def test_str_of_poses_lift_and_mass_properties_are_their_commands_reports(part, capsys):
    assert str(plumbob.poses(part, **OPTIONS)) + "\n" == _cli(capsys, "poses", part, *FLAGS)
    lift = plumbob.lift(part, **OPTIONS)
    assert str(lift) + "\n" == _cli(capsys, "lift", part, *FLAGS)
    assert "centre of mass above it  30 mm" in str(lift)
    props = plumbob.mass_properties(part, **OPTIONS)
    assert str(props) + "\n" == _cli(capsys, "mass", part, *FLAGS)
    assert "mass                    59.52 g" in str(props)


def test_a_result_of_a_body_reads_in_si_and_every_repr_has_units():
    block = P.box(1, 1, 4, density=1000.0)
    props = plumbob.mass_properties(block)
    assert str(props).splitlines()[3] == "mass                    4000 kg"
    assert repr(props) == ("MassProperties(dim=3, mass=4000 kg, volume=4 m³, center_of_mass="
                           "[0.5, 0.5, 2] m, principal_moments=[666.667, 5666.67, 5666.67] "
                           "kg·m², exact=True)")
    verdict = plumbob.check(block)
    assert str(verdict).startswith("plumbob check body (solid)\n")
    assert "margin=0.5 m" in repr(verdict) and "critical_tilt_deg=14.0362°" in repr(verdict)
    assert "mass=4000 kg" in repr(verdict) and "energy_to_topple=" in repr(verdict)
    lift = plumbob.lift(block, g=10.0)
    assert repr(lift) == ("LiftEnergy(mass=4000 kg, center_of_mass=[0.5, 0.5, 2] m, datum=0 m, "
                          "com_height=2 m, lift_energy=80000 J, g=10 m/s²)")
    assert "mass=4000 kg" in repr(plumbob.poses(block))
    assert repr(plumbob.poses(block)[0]).endswith(
        "com_height=0.5 m, critical_tilt_deg=45°, energy_barrier=8127 J)")
    # 4000 kg at 2 m high, ballast m at the floor: 8000 / (4000 + m) = 0.5 / tan 20°
    assert repr(plumbob.balance(block, require_tilt_deg=20)).startswith(
        "BalanceResult(ballast_mass=1823.52 kg, ballast_point=[0.5, 0.5, 0] m")
    plan = str(plumbob.balance(block, require_tilt_deg=20))  # balance's report, SI
    assert plan.startswith("plumbob balance body (solid)\n")
    assert "ballast  1823.52 kg centred at (0.5, 0.5, 0) m" in plan.splitlines()
    from plumbob.energy import crew_time

    assert repr(crew_time(1e6, 1e4, 3)).startswith("CrewTime(energy=1e+06 J, work_per_day=10000 J")


def test_load_options_need_a_file():
    with pytest.raises(plumbob.PlumbobError, match="units= reads a file"):
        plumbob.check(P.box(1, 1, 1), units="mm")
    with pytest.raises(plumbob.PlumbobError, match="not 'g'"):
        plumbob.mass_properties(P.box(1, 1, 1), g=3)


def test_round_off_is_not_shown_in_the_lift_report():
    """Issue 22: "ground datum −6.939e-18 m" is 0 (the JSON keeps every digit)."""
    import numpy as np

    from plumbob.energy import LiftEnergy

    lift = LiftEnergy(2.0, np.array([0.0, 0.0, 1.0]), -6.939e-18, 1.0, 19.62, 9.81)
    assert "ground datum             0 m" in str(lift).splitlines()
    assert lift.as_dict()["datum"] == -6.939e-18
