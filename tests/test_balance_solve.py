"""check --solve-for: the smallest change of one spec parameter, against closed forms;
loading.read's parameter overrides."""

import json
import os

import numpy as np
import pytest
from conftest import SHAPES

from plumbob.balance.solve import solve_parameter
from plumbob.cli import main
from plumbob.errors import PlumbobError, SpecError, StabilityError
from plumbob.loading import read
from plumbob.stability import check

A = np.sqrt(3) / 2
H = np.sqrt(3) * A
SCULPTURE = os.path.join(SHAPES, "sculpture.toml")


def _foot_closed_form(tilt_deg: float) -> float:
    """The sculpture's base reaching f beyond O adds the triangle (0,0), (f,0), (a,h):
    area f·h/2, centroid ((f + a)/3, h/3). Its critical tilt over the edge at x = f is
    reached when f·A(f) − Mx(f) − tan θ·My(f) = 0 — a quadratic in f."""
    area0 = 7 * A * H / 2  # 3½ triangles of side 2a
    x0, y0 = -4 * A / 21, 19 * H / 21
    t = np.tan(np.radians(tilt_deg))
    # f(A0 + f h/2) − A0 x0 − (f h/2)(f + a)/3 − t(A0 y0 + f h²/6) = 0
    coefficients = [H / 2 - H / 6, area0 - H * A / 6 - t * H * H / 6, -area0 * x0 - t * area0 * y0]
    roots = np.roots(coefficients)
    return float(min(r.real for r in roots if r.real > 0 and abs(r.imag) < 1e-12))


def test_wider_base_for_the_sculpture(capsys):
    assert main(["check", SCULPTURE, "--require-tilt", "10", "--solve-for", "foot",
                 "--json"]) == 1  # the sculpture as given still fails
    data = json.loads(capsys.readouterr().out)
    solution = data["solution"]
    assert solution["name"] == "foot" and solution["start"] == 0
    assert solution["value"] == pytest.approx(_foot_closed_form(10), rel=1e-9)
    assert solution["achieved"] >= 10
    body = read(SCULPTURE, parameters={"foot": solution["value"]}).body
    assert check(body, require_tilt_deg=10).passes
    narrower = read(SCULPTURE, parameters={"foot": 0.999 * solution["value"]}).body
    assert not check(narrower, require_tilt_deg=10).passes


def test_margin_of_the_block(capsys):
    """The block's margin is h/2: a margin of 0.6 m needs h = 1.2."""
    assert main(["check", os.path.join(SHAPES, "block.toml"), "--margin", "0.6",
                 "--solve-for", "h"]) == 1
    out = capsys.readouterr().out
    assert "stability margin at least 0.6 m: FAIL (0.1 m short)" in out
    assert "h that meets it: 1 → 1.2 (+0.2)" in out


def test_already_met_is_no_change(capsys):
    assert main(["check", os.path.join(SHAPES, "block.toml"), "--require-tilt", "5",
                 "--solve-for", "h", "--json"]) == 0
    solution = json.loads(capsys.readouterr().out)["solution"]
    assert solution["change"] == 0 and solution["value"] == 1


def test_cabinet_drawer(capsys):
    """Pulled out less, the drawer passes; the answer is a root: a little more fails."""
    path = os.path.join(SHAPES, "cabinet.toml")
    assert main(["check", path, "--require-tilt", "10", "--solve-for", "drawer_open",
                 "--json"]) == 1
    solution = json.loads(capsys.readouterr().out)["solution"]
    assert 0 < solution["value"] < 0.3
    assert check(read(path, parameters={"drawer_open": solution["value"]}).body,
                 require_tilt_deg=10).passes
    assert not check(read(path, parameters={"drawer_open": solution["value"] + 1e-4}).body,
                     require_tilt_deg=10).passes


def test_scale_invariant_parameter_has_no_answer():
    """Scaling the block scales its margin and its height alike: its tilt never changes."""
    with pytest.raises(StabilityError, match="stays short"):
        solve_parameter("h", 1.0, lambda h: float(np.degrees(np.arctan(0.25))), 20.0)


def test_an_invalid_value_ends_a_side():
    def measure(w):
        if w <= 0:
            raise SpecError("width must be positive")
        return 1 / w

    solution = solve_parameter("w", 1.0, measure, 4.0)
    assert solution.value == pytest.approx(0.25, rel=1e-9) and solution.achieved >= 4.0


def test_parameters_override_and_recompute():
    body = read(SCULPTURE, parameters={"a": 1.0}).body
    # h follows a: the sculpture scales by 1/a0, its centre with it
    assert body.mass_properties().center_of_mass == pytest.approx(
        [-4 / 21, 19 * np.sqrt(3) / 21], rel=1e-12)
    with pytest.raises(PlumbobError, match="no parameter 'b' to set; known: a, h, foot"):
        read(SCULPTURE, parameters={"b": 1.0})
    with pytest.raises(PlumbobError, match="apply only to a TOML spec"):
        read(os.path.join(SHAPES, "..", "docs", "models", "missing.stl"), parameters={"a": 1})
