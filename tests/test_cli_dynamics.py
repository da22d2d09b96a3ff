"""``plumbob simulate`` and ``plumbob collide`` through ``plumbob.cli.main``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from plumbob.cli import main

SHAPES = Path(__file__).resolve().parents[1] / "shapes"


def run_cli(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv: str) -> dict:
    code, out, err = run_cli(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


# ------------------------------------------------------------------ collide
def test_collide_example_6_text(capsys):
    code, out, _ = run_cli(capsys, "collide", "--m1", "0.16", "--v1", "5,0", "--m2", "0.16",
                           "--v2", "0,0")
    assert code == 0
    assert "(5, 0) → (0, 0) m/s" in out and "(0, 0) → (5, 0) m/s" in out
    assert "elastic (no kinetic energy lost)" in out


def test_collide_json_keys_and_golf_club(capsys):
    alpha, u = 0.4, 30.0
    v1 = f"{u * math.sin(alpha)!r},{u * math.cos(alpha)!r}"
    data = run_json(capsys, "collide", "--m1", "9", "--v1", v1, "--m2", "1", "--v2", "0,0",
                    "--normal", "0,1", "--e", "0.8")
    for key in ("v1_after", "v2_after", "ke_before", "ke_after", "ke_loss", "elastic",
                "momentum_before", "momentum_after"):
        assert key in data
    c = u * math.cos(alpha)
    np.testing.assert_allclose(data["v1_after"], [u * math.sin(alpha), 0.82 * c])
    np.testing.assert_allclose(data["v2_after"], [0, 1.62 * c], atol=1e-12)
    assert data["ke_loss"] == pytest.approx(0.162 * u * u * math.cos(alpha) ** 2)
    assert data["elastic"] is False
    np.testing.assert_allclose(data["momentum_after"], data["momentum_before"])


def test_collide_default_normal_is_head_on_and_coalescing(capsys):
    # Exercise 25 with m1 = 1, m2 = 3, u = 2: V = u (m1, m2)/(m1 + m2).
    data = run_json(capsys, "collide", "--m1", "1", "--v1", "2,0", "--m2", "3", "--v2", "0,2",
                    "--e", "0")
    np.testing.assert_allclose(data["v1_after"], [0.5, 1.5])
    np.testing.assert_allclose(data["v2_after"], [0.5, 1.5])
    np.testing.assert_allclose(data["normal"], [1 / math.sqrt(2), -1 / math.sqrt(2)])
    assert data["ke_loss"] == pytest.approx(1 * 3 * 4 / 4)


def test_collide_wall_with_negative_components(capsys):
    data = run_json(capsys, "collide", "--m1", "0.5", "--v1", "-3,4", "--m2", "inf",
                    "--normal", "-1,0", "--e", "0.5")
    np.testing.assert_allclose(data["v1_after"], [1.5, 4.0])
    np.testing.assert_allclose(data["v2_after"], [0.0, 0.0])
    assert data["m2"] == "inf"
    assert data["ke_loss"] == pytest.approx(0.5 * 0.5 * 9 * (1 - 0.25))
    # --v2 defaults to rest; 1-D and 3-D vectors work.
    data = run_json(capsys, "collide", "--m1", "2", "--v1", "3", "--m2", "1")
    assert data["v1_after"] == pytest.approx([1.0]) and data["v2_after"] == pytest.approx([4.0])
    data = run_json(capsys, "collide", "--m1", "1", "--v1", "0,0,-2", "--m2", "inf",
                    "--e", "0.5")
    assert data["v1_after"] == pytest.approx([0, 0, 1.0])


@pytest.mark.parametrize("argv, message", [
    (["--m1", "-1", "--v1", "1,0", "--m2", "1"], "must be positive"),
    (["--m1", "0", "--v1", "1,0", "--m2", "1"], "must be positive"),
    (["--m1", "1", "--v1", "1,0", "--m2", "-2"], "must be positive"),
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--e", "1.2"], "[0, 1]"),
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--e", "-0.5"], "[0, 1]"),
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--normal", "0,0"], "zero vector"),
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--normal", "-1,0"], "no collision"),
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--v2", "2,0", "--normal", "1,0"],
     "no collision"),  # body 2 ahead and faster: they separate
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--v2", "1,0"], "same velocity"),
    (["--m1", "1", "--v1", "1,x", "--m2", "1"], "must be a number"),
    (["--m1", "1", "--v1", "1,2,3,4", "--m2", "1"], "1 to 3"),
    (["--m1", "heavy", "--v1", "1,0", "--m2", "1"], "must be a number"),
    (["--m1", "inf", "--v1", "1,0", "--m2", "1"], "fixed surface"),
    (["--m1", "1", "--v1", "1,0", "--m2", "1", "--v2", "0,0,0"], "same number"),
])
def test_collide_bad_input_one_line_exit_2(capsys, argv, message):
    code, out, err = run_cli(capsys, "collide", *argv)
    assert code == 2
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("plumbob: ")
    assert message in err
    assert "Traceback" not in err


# ----------------------------------------------------------------- simulate
def test_simulate_mace_json(capsys):
    data = run_json(capsys, "simulate", str(SHAPES / "mace_throw.toml"), "--until", "1.6",
                    "--samples", "17")
    for key in ("times", "positions", "center_of_mass", "momentum"):
        assert key in data
    t = np.array(data["times"])
    assert len(t) == 17 and t[-1] == 1.6
    parabola = np.column_stack([2.0 * t, 8.0 * t - 0.5 * 9.81 * t * t])
    np.testing.assert_allclose(data["center_of_mass"], parabola, atol=1e-6)
    np.testing.assert_allclose(np.array(data["momentum"])[:, 0], 4.0)
    assert np.array(data["positions"]).shape == (17, 2, 2)
    assert data["names"] == ["A", "B"] and data["total_mass"] == 2.0


def test_simulate_spring_pair_text(capsys):
    code, out, err = run_cli(capsys, "simulate", str(SHAPES / "spring_pair.toml"),
                             "--until", "2", "--samples", "5")
    assert code == 0, err
    assert "Seed Example 2" in out
    assert "centre of mass" in out and "(0, 0) → (5, 0) m" in out   # x_G = P t²/(4m) = 5
    assert "(0, 0) → (20, 0) kg·m/s" in out                          # P t
    assert out.count("\n") > 10


@pytest.mark.parametrize("argv, message", [
    (["missing.toml", "--until", "1"], "no such file"),
    (["{mace}", "--until", "0"], "--until must be a positive"),
    (["{mace}", "--until", "soon"], "--until must be a number"),
    (["{mace}", "--until", "1", "--samples", "1"], "--samples"),
    (["{bad}", "--until", "1"], "every mass must be positive"),
    (["{nonsense}", "--until", "1"], "unknown key"),
])
def test_simulate_bad_input_one_line_exit_2(capsys, tmp_path, argv, message):
    bad = tmp_path / "bad.toml"
    bad.write_text('[[particle]]\nmass = -2\nposition = [0, 0]\n')
    nonsense = tmp_path / "nonsense.toml"
    nonsense.write_text('wind = 3\n[[particle]]\nmass = 2\nposition = [0, 0]\n')
    paths = {"mace": str(SHAPES / "mace_throw.toml"), "bad": str(bad), "nonsense": str(nonsense)}
    argv = [a.format(**paths) for a in argv]
    code, out, err = run_cli(capsys, "simulate", *argv)
    assert code == 2
    assert out == ""
    assert err.count("\n") == 1 and err.startswith("plumbob: ")
    assert message in err
    assert "Traceback" not in err
