"""--explain: the calculation sheet follows the seed's worked solutions (Unit 19)."""

from __future__ import annotations

import math
import os
import re

from conftest import SHAPES

from plumbob.cli import main
from plumbob.loading import read
from plumbob.loads import Force
from plumbob.report import sheet_html, sheet_markdown
from plumbob.stability import check
from plumbob.stability.sheet import calculation_sheet


def sheet(name: str, **options):
    body = read(os.path.join(SHAPES, f"{name}.toml")).body
    v = check(body, **options)
    return calculation_sheet(body, v, name), v


def test_the_l_shape_is_example_3():
    """Example 3: the rectangle 2m at (a, a/2), the square m at (a/2, 3a/2), r_G = 5a/6 (i+j)."""
    s, _ = sheet("l_shape")
    rows = {p.name: p for p in s.parts}
    assert math.isclose(rows["rectangle"].mass, 2 * rows["square"].mass, rel_tol=1e-12)
    assert list(rows["rectangle"].center) == [1.0, 0.5]
    assert list(rows["square"].center) == [0.5, 1.5]
    assert all(math.isclose(c, 5 / 6, rel_tol=1e-12) for c in s.center_of_mass)
    text = sheet_markdown(s)
    assert "equation (15)" in text and "(0.833333, 0.833333)" in text and "it stands" in text


def test_the_sculpture_is_exercise_14():
    """r_G = (−4a/21, 19h/21), left of O, over the base: it will not topple."""
    a = math.sqrt(3) / 2
    h = math.sqrt(3) * a
    s, v = sheet("sculpture")
    assert math.isclose(s.center_of_mass[0], -4 * a / 21, rel_tol=1e-12)
    assert math.isclose(s.center_of_mass[1], 19 * h / 21, rel_tol=1e-12)
    assert v.verdict == "stands" and s.overturning_safety_factor is None
    # the critical edge is O, the base's right-hand end; the weight resists with W·4a/21
    assert abs(s.edge_start[0]) < 1e-12
    assert math.isclose(s.resisting_moment, v.mass * v.g * 4 * a / 21, rel_tol=1e-9)
    assert "it stands" in sheet_markdown(s)


def test_the_stepped_cylinder_is_exercise_19():
    """r_G = 14a/5 i, to the right of P (x = 2a), the leftmost point of contact: d = 4a/5."""
    s, v = sheet("stepped_cylinder")
    assert math.isclose(s.center_of_mass[0], 14 / 5, rel_tol=1e-12)
    end_p = [e for e in v.edges if e.normal[0] < -0.5]
    assert len(end_p) == 1 and math.isclose(end_p[0].start[0], 2.0, rel_tol=1e-12)
    assert math.isclose(end_p[0].distance, 4 / 5, rel_tol=1e-9)
    assert re.search(r"\| \(2, 0, -3\)–\(2, 0, -3\) \| \(-1, 0, 0\) \| 0\.8 \|", sheet_markdown(s))


def test_the_pyramid_is_exercise_20():
    """M ≈ 6.48e9 kg, G at h/4, and M g h/4 ≈ 2.34e12 J to lift its stones."""
    s, _ = sheet("pyramid_cheops")
    assert math.isclose(s.mass, 230 ** 2 * 147 / 3 * 2500, rel_tol=1e-12)
    assert math.isclose(s.center_of_mass[2], 147 / 4, rel_tol=1e-12)
    assert math.isclose(s.lift_energy, s.mass * 9.81 * 147 / 4, rel_tol=1e-12)
    assert round(s.lift_energy / 1e12, 2) == 2.34
    assert "2.33624e+12 J" in sheet_markdown(s)


def test_loads_on_the_sheet_match_the_check():
    s, v = sheet("block", loads=[Force([2000, 0, 0], [0, 0.5, 3.0])])
    lv = v.loaded
    assert s.overturning_safety_factor == lv.overturning_safety_factor
    assert math.isclose(sum(p.moment for p in s.parts), lv.moments[0].moment, rel_tol=1e-12)
    assert "Factor of safety against overturning R / O" in sheet_markdown(s)


def test_explain_on_the_command_line(capsys, tmp_path):
    path = os.path.join(SHAPES, "l_shape.toml")
    assert main(["check", path, "--explain"]) == 0
    assert "# Calculation sheet" in capsys.readouterr().out
    out = tmp_path / "sheet.html"
    assert main(["check", path, "--explain", str(out)]) == 0
    text = out.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>") and "<table>" in text
    assert main(["check", path, "--explain", str(tmp_path / "sheet.txt")]) == 2
    assert "--explain writes a .md or .html" in capsys.readouterr().err
    assert sheet_html(sheet("l_shape")[0]).count("<h2>") == 4
