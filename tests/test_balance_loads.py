"""balance under loads and --standard: the least ballast, checked by the check's own
factor of safety, against hand calculations."""

from __future__ import annotations

import json
import math
import os

from conftest import SHAPES

from plumbob.balance.loaded import balance_standard, balance_under_loads
from plumbob.bodies.primitives import box
from plumbob.cli import main
from plumbob.loads import Force
from plumbob.stability.requirement import Requirement

G = 9.81


def test_the_least_ballast_under_a_push():
    """A 100 kg box 1 × 0.5 × 2 m pushed along +x with 600 N at 1.5 m: the ballast goes at
    the back (d = 1 m from the tipping edge): m g · 1 + W · 0.5 = 900 N·m."""
    body = box(1, 0.5, 2, density=100.0)
    r = balance_under_loads(body, Requirement(loads=(Force([600, 0, 0], [0, 0.25, 1.5]),)))
    want = (900 - 100 * G * 0.5) / G
    assert math.isclose(r.ballast.added_mass, want, rel_tol=1e-4)  # the planner's LP tolerance
    assert abs(r.ballast.ballast_point[0]) < 1e-9
    assert r.passes and r.after.loaded.overturning_safety_factor >= 1
    assert r.before.loaded.verdict == "topples"


def test_balance_standard_makes_a_column_pass_iec62368():
    """The 30 kg column 0.2 × 0.2 × 1.8 m fails IEC 62368-1; its tilt test needs the least
    ballast (the force test's push grows with the weight)."""
    col = box(0.2, 0.2, 1.8, density=30 / (0.2 * 0.2 * 1.8))
    r = balance_standard(col, "iec62368-1")
    assert r.passes and r.after.critical_tilt_deg >= 10 - 1e-9
    # the text report says which test the ballast is for (it was an internal error)
    from plumbob.report.balance import loaded_text

    text = loaded_text(r, "column", "solid", [], 1.8, None, "iec62368-1")
    assert text.endswith("\n\n(iec62368-1: its tilt test needs the least ballast)")


def test_balance_command_with_loads(capsys):
    path = os.path.join(SHAPES, "block.toml")
    assert main(["balance", path, "--force=20000,0,0@0,0.5,3", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["passes"] and out["after"]["under_loads"]["overturning_safety_factor"] >= 1
    assert out["before"]["under_loads"]["verdict"] == "topples"


def test_solve_for_the_widest_foot_under_a_push(tmp_path, capsys):
    """A box w × 1 × 2 m of 100 kg/m³ pushed along +x with 300 N at 1.5 m stands when
    W w/2 ≥ 450 N·m, W = 200 g w: w = √(450 / (100 g))."""
    spec = tmp_path / "wide.toml"
    spec.write_text('[parameters]\nw = 0.4\n[[part]]\ntype = "box"\nlength = "w"\nwidth = 1\n'
                    'height = 2\ndensity = 100\n[[load]]\nforce = [300, 0, 0]\nat = [0, 0.5, 1.5]\n')
    assert main(["check", str(spec), "--solve-for", "w", "--json"]) == 1  # fails as it is
    out = json.loads(capsys.readouterr().out)
    sol = out["solution"]
    assert sol["measure"] == "overturning_safety_factor"
    assert math.isclose(sol["value"], math.sqrt(450 / (100 * G)), rel_tol=1e-6)
