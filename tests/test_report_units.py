"""``--report-units``: the text report of mass, check and lift in other length and mass
units; the JSON stays SI. Each converted number is checked against the SI JSON."""

from __future__ import annotations

import json
import math
import os
import re

import pytest

from plumbob.cli import main
from plumbob.errors import ArgumentError
from plumbob.report import ReportUnits

NUMBER = r"(-?[\d.]+(?:e[+-]?\d+)?)"


def _run(capsys, *args: str) -> str:
    assert main(list(args)) == 0
    return capsys.readouterr().out


def _row(text: str, label: str) -> str:
    return next(line for line in text.splitlines() if line.startswith(label))


def _numbers(text: str) -> list[float]:
    return [float(x) for x in re.findall(NUMBER, text)]


@pytest.fixture
def mace(shapes_dir):
    return os.path.join(shapes_dir, "mace_assembly.toml")


def test_mass_in_mm_and_g_is_the_si_report_scaled(capsys, mace):
    si = json.loads(_run(capsys, "mass", mace, "--json"))
    text = _run(capsys, "mass", mace, "--report-units", "mm,g")
    assert _numbers(_row(text, "mass"))[0] == pytest.approx(si["mass"] * 1e3, rel=1e-5)
    assert "g" == _row(text, "mass").split()[-1]
    assert _numbers(_row(text, "volume"))[0] == pytest.approx(si["volume"] * 1e9, rel=1e-5)
    assert _row(text, "volume").endswith("mm³")
    assert _row(text, "mean density").endswith("g/mm³")
    assert _numbers(_row(text, "mean density"))[0] == pytest.approx(
        si["mass"] * 1e3 / (si["volume"] * 1e9), rel=1e-5)
    assert _numbers(_row(text, "centre of mass")) == pytest.approx(
        [c * 1e3 for c in si["center_of_mass"]], rel=1e-5, abs=1e-9)
    assert _numbers(_row(text, "principal moments"))[:3] == pytest.approx(
        [m * 1e9 for m in si["principal_moments"]], rel=1e-5)
    assert _row(text, "principal moments").endswith("g·mm²")
    head = _row(text, "head")
    assert _numbers(head)[0] == pytest.approx(si["part_properties"][1]["mass"] * 1e3, rel=1e-5)


def test_one_unit_changes_only_its_quantity(capsys, shapes_dir):
    block = os.path.join(shapes_dir, "block.toml")
    text = _run(capsys, "mass", block, "--report-units", "t")
    assert _row(text, "mass").split()[-2:] == ["4", "t"]
    assert _row(text, "centre of mass").endswith("(0.5, 0.5, 2) m")


def test_lift_and_check_in_other_units(capsys, shapes_dir):
    block = os.path.join(shapes_dir, "block.toml")
    lift = _run(capsys, "lift", block, "--report-units", "in,lb")
    assert _numbers(_row(lift, "centre of mass above it"))[0] == pytest.approx(2 / 0.0254)
    assert _numbers(_row(lift, "mass"))[0] == pytest.approx(4000 / 0.45359237, rel=1e-5)
    assert _row(lift, "lift energy").endswith(" J")  # energies stay in joules
    check = _run(capsys, "check", block, "--report-units", "mm")
    assert _row(check, "height of centre").endswith("2000 mm")
    assert _row(check, "stability margin").endswith("500 mm")
    assert "distance mm" in check


def test_the_default_report_is_si(capsys, shapes_dir):
    block = os.path.join(shapes_dir, "block.toml")
    assert _row(_run(capsys, "check", block), "height of centre").endswith("2 m")


@pytest.mark.parametrize("command", ["mass", "check", "lift"])
def test_report_units_with_json_is_an_error_not_ignored(capsys, shapes_dir, command):
    block = os.path.join(shapes_dir, "block.toml")
    assert main([command, block, "--json", "--report-units", "mm"]) == 2
    assert "JSON is always in SI" in capsys.readouterr().err


@pytest.mark.parametrize("text", ["furlong", "mm,cm", "g,kg", "", "mm,,g"])
def test_bad_report_units_are_refused(text):
    with pytest.raises(ArgumentError):
        ReportUnits.parse(text)


def test_parse_order_does_not_matter():
    assert ReportUnits.parse("g,mm") == ReportUnits.parse("mm,g") == ReportUnits("mm", "g")


@pytest.fixture
def box_mm(tmp_path):
    """A 40 × 20 × 60 mm box with a corner at the origin, as an STL (no unit inside)."""
    import trimesh

    path = tmp_path / "box.stl"
    trimesh.creation.box(extents=(40, 20, 60)).apply_translation((20, 10, 30)).export(path)
    return str(path)


@pytest.mark.parametrize("spelling", ["mm", "MM", "millimetre", "Millimeter", " millimetres "])
def test_a_part_read_in_mm_reports_in_mm_and_g(capsys, box_mm, spelling):
    """48 cm³ of PLA (1240 kg/m³) is 59.52 g; its centre (20, 10, 30) mm; the JSON SI."""
    text = _run(capsys, "mass", box_mm, "--units", spelling, "--material", "pla")
    assert _row(text, "mass").split()[1:] == ["59.52", "g"]
    assert _row(text, "centre of mass").endswith("(20, 10, 30) mm")
    assert "g·mm²" in _row(text, "inertia")
    si = json.loads(_run(capsys, "mass", box_mm, "--units", spelling, "--material", "pla",
                         "--json"))
    assert si["mass"] == pytest.approx(0.05952, rel=1e-12)
    assert si["center_of_mass"] == pytest.approx([0.02, 0.01, 0.03], rel=1e-12)
    check = _run(capsys, "check", box_mm, "--units", spelling, "--material", "pla")
    assert _row(check, "stability margin").split()[-2:] == ["10", "mm"]
    lift = _run(capsys, "lift", box_mm, "--units", spelling, "--material", "pla")
    assert _row(lift, "centre of mass above it").split()[-2:] == ["30", "mm"]


def test_inches_report_in_inches_and_pounds_unless_asked_otherwise(capsys, box_mm):
    """The same numbers read as inches: 48 000 in³ of PLA is 48 000 × 0.0254³ × 1240 kg."""
    kg = 48_000 * 0.0254 ** 3 * 1240
    text = _run(capsys, "mass", box_mm, "--units", '"', "--material", "pla")
    assert _numbers(_row(text, "mass"))[0] == pytest.approx(kg / 0.45359237, rel=1e-5)
    assert _row(text, "mass").endswith("lb")
    text = _run(capsys, "mass", box_mm, "--units", "inch", "--material", "pla",
                "--report-units", "m,kg")
    assert _numbers(_row(text, "mass"))[0] == pytest.approx(kg, rel=1e-5)


def test_a_part_in_metres_or_of_unknown_unit_stays_si(capsys, shapes_dir):
    text = _run(capsys, "mass", os.path.join(shapes_dir, "block.toml"))
    assert _row(text, "mass").endswith("kg")


def test_an_unknown_unit_is_one_line_naming_the_choices(capsys, box_mm):
    with pytest.raises(SystemExit) as exit_status:
        main(["mass", box_mm, "--units", "furlong"])
    assert exit_status.value.code == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "furlong" in err and "mm" in err



def test_balance_reads_in_mm_and_g_for_a_mm_part_and_its_json_stays_si(capsys, box_mm):
    """A 40 × 20 × 60 mm box of PLA tilted to 25°: the ballast plan's text in mm and g,
    each number the SI JSON's scaled."""
    args = ["balance", box_mm, "--units", "mm", "--material", "pla", "--require-tilt", "25"]
    si = json.loads(_run(capsys, *args, "--json"))
    text = _run(capsys, *args)
    before = _row(text, "before")
    assert "margin 10 mm" in before and before.endswith("(20, 10, 30) mm")
    ballast = _row(text, "ballast ")
    assert ballast.split()[2] == "g" and not re.search(r"\bm\b|kg", ballast)
    assert _numbers(ballast) == pytest.approx(
        [si["ballast"]["mass"] * 1e3] + [c * 1e3 for c in si["ballast"]["center_of_mass"]],
        rel=1e-5, abs=1e-9)
    after = _row(text, "after")
    assert after.endswith(f"mass {si['after']['mass'] * 1e3:.6g} g")
    assert _numbers(after.split("centre of mass")[1])[:3] == pytest.approx(
        [c * 1e3 for c in si["after"]["center_of_mass"]], rel=1e-5)
    # the JSON is SI: the box's centre height 30 mm → tilt 25° needs tan(25°)·h = 10 mm
    assert si["after"]["com_height"] == pytest.approx(0.01 / math.tan(math.radians(25)),
                                                      rel=1e-6)


def test_the_ballast_shape_line_follows_the_report_units():
    """The formatter alone (a plan with a steel cube): volumes in mm³, densities in
    g/mm³, sides in mm; SI by default."""
    from dataclasses import replace

    from plumbob.balance.result import balance
    from plumbob.bodies.primitives import box
    from plumbob.report.balance import balance_text

    r = balance(box(0.04, 0.02, 0.06, density=1240.0), require_tilt_deg=25)
    side = (r.ballast_mass / 7850) ** (1 / 3)
    r = replace(r, ballast_material="steel", ballast_density=7850.0,
                ballast_volume=r.ballast_mass / 7850, ballast_shape="box",
                ballast_dimensions=(side,))
    mm = _row(balance_text(r, "b", "solid", [], 0.06, ReportUnits("mm", "g")), "ballast shape")
    assert mm.startswith("ballast shape  steel (0.00785 g/mm³), ")
    assert _numbers(mm)[1:] == pytest.approx([r.ballast_volume * 1e9, side * 1e3], rel=1e-3)
    assert mm.endswith("mm, fits inside") and "mm³:" in mm
    si = _row(balance_text(r, "b", "solid", [], 0.06), "ballast shape")
    assert "(7850 kg/m³)" in si and "m³:" in si and si.endswith(" m, fits inside")
