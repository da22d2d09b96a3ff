"""The check, poses and lift commands: JSON keys, the seed's answers, exit statuses."""

import json
import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import ROOT, SHAPES

from plumbob.cli import main

A = np.sqrt(3) / 2


def shape(name: str) -> str:
    return os.path.join(SHAPES, name)


def run_json(capsys, *args, status=0):
    assert main([*args, "--json"]) == status
    captured = capsys.readouterr()
    return json.loads(captured.out)


CHECK_KEYS = {"verdict", "stands", "margin", "critical_tilt_deg", "critical_direction",
              "energy_to_topple", "com_height", "center_of_mass", "support_polygon"}


def test_check_sculpture(capsys):
    data = run_json(capsys, "check", shape("sculpture.toml"))
    assert CHECK_KEYS <= set(data)
    assert data["kind"] == "lamina" and data["verdict"] == "stands" and data["stands"] is True
    assert data["margin"] == pytest.approx(4 * A / 21, rel=1e-9)
    assert data["critical_tilt_deg"] == pytest.approx(6.93, abs=5e-3)
    assert data["critical_direction"] == pytest.approx([1, 0])
    assert np.allclose(sorted(np.array(data["support_polygon"])[:, 0]), [-2 * A, 0])
    assert "slides_first" not in data and "passes" not in data


def test_check_stepped_cylinder_is_neutral_and_stands_along_its_axis(capsys):
    data = run_json(capsys, "check", shape("stepped_cylinder.toml"))
    assert data["verdict"] == "neutral" and data["stands"] is False
    assert data["com_height"] == pytest.approx(3.0)
    axial = sorted(e["distance"] for e in data["edges"] if abs(e["normal"][0]) > 0.5)
    assert axial == pytest.approx([0.8, 1.2])


def test_check_block_tilt_friction_and_design_check(capsys):
    block = shape("block.toml")
    data = run_json(capsys, "check", block, "--require-tilt", "10", "--friction", "0.2")
    assert data["passes"] is True and data["slides_first"] is True
    assert data["critical_tilt_deg"] == pytest.approx(np.degrees(np.arctan(0.25)))
    assert data["energy_to_topple"] == pytest.approx(4000 * 9.81 * (np.sqrt(4.25) - 2))
    failing = run_json(capsys, "check", block, "--require-tilt", "15", status=1)
    assert failing["passes"] is False
    slope = run_json(capsys, "check", block, "--tilt", "15", "--toward", "90")["slope"]
    assert slope["topples"] is True and slope["direction"] == pytest.approx([0, 1, 0])
    assert slope["tipping_angle_deg"] == pytest.approx(np.degrees(np.arctan(0.25)))


def test_check_other_downs_and_poses(capsys):
    lying = run_json(capsys, "check", shape("block.toml"), "--down=1,0,0")
    assert lying["com_height"] == pytest.approx(0.5) and lying["down"] == [1, 0, 0]
    first = run_json(capsys, "check", shape("block.toml"), "--pose", "1")
    assert first["com_height"] == pytest.approx(0.5) and first["stands"]
    light = run_json(capsys, "check", shape("block.toml"), "--g", "1.62")
    assert light["energy_to_topple"] == pytest.approx(4000 * 1.62 * (np.sqrt(4.25) - 2))


def test_check_text_report(capsys):
    assert main(["check", shape("sculpture.toml"), "--require-tilt", "5"]) == 0
    out = capsys.readouterr().out
    assert "stands" in out and "6.93°" in out and "PASS" in out


def test_poses_json(capsys):
    data = run_json(capsys, "poses", shape("block.toml"))
    poses = data["poses"]
    assert len(poses) == 6 and data["method"] == "exact"
    assert sum(p["probability"] for p in poses) == pytest.approx(1.0, abs=1e-12)
    assert [p["probability"] for p in poses] == sorted((p["probability"] for p in poses),
                                                      reverse=True)
    for p in poses:
        assert {"down", "com_height", "probability", "critical_tilt_deg",
                "energy_barrier"} <= set(p)
        assert np.linalg.norm(p["down"]) == pytest.approx(1.0)
    upright = [p for p in poses if p["down"] == pytest.approx([0, 0, -1])][0]
    assert upright["com_height"] == pytest.approx(2.0)
    assert upright["energy_barrier"] == pytest.approx(4000 * 9.81 * (np.sqrt(4.25) - 2))


def test_poses_of_a_lamina_and_the_text_report(capsys):
    data = run_json(capsys, "poses", shape("sculpture.toml"))
    assert len(data["poses"]) == 3
    assert main(["poses", shape("stepped_cylinder.toml")]) == 0
    out = capsys.readouterr().out
    assert "rolls" in out and "probability" in out


def test_lift_pyramid_and_crew(capsys):
    data = run_json(capsys, "lift", shape("pyramid_cheops.toml"), "--crew", "1000",
                    "--work-per-day", str(1000 * 9.81))
    assert data["mass"] == pytest.approx(6.48e9, rel=1e-3)
    assert data["com_height"] == pytest.approx(147 / 4)
    assert data["lift_energy"] == pytest.approx(2.34e12, rel=2e-3)
    assert data["crew_days"] == pytest.approx(2.4e5, rel=0.01)
    assert round(data["crew_years"]) == 652
    assert data["person_days"] == pytest.approx(1000 * data["crew_days"])
    plain = run_json(capsys, "lift", shape("block.toml"))
    assert plain["lift_energy"] == pytest.approx(4000 * 9.81 * 2)
    assert "crew_days" not in plain
    raised = run_json(capsys, "lift", shape("block.toml"), "--datum", "-1")
    assert raised["com_height"] == pytest.approx(3.0)


def test_lift_text_report_with_the_seeds_day_of_work(capsys):
    assert main(["lift", shape("pyramid_cheops.toml"), "--crew", "1000"]) == 0
    out = capsys.readouterr().out
    assert "652" in out and "9810 J" in out


@pytest.mark.parametrize("args", [
    ["check", "block.toml", "--down", "0,0,0"],
    ["check", "block.toml", "--down", "1,2,3,4"],
    ["check", "block.toml", "--pose", "99"],
    ["check", "block.toml", "--toward", "30"],
    ["check", "block.toml", "--tilt", "95"],
    ["check", "sculpture.toml", "--tilt", "5", "--toward", "90"],
    ["check", "block.toml", "--friction", "-1"],
    ["lift", "block.toml", "--crew", "0"],
    ["lift", "block.toml", "--work-per-day", "0"],
    ["poses", "no_such_file.toml"],
])
def test_bad_input_is_one_line_and_status_2(capsys, args):
    path = shape(args[1])
    with pytest.raises(SystemExit) as exit_info:
        status = main([args[0], path, *args[2:]])
        raise SystemExit(status)
    assert exit_info.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("plumbob:") and "\n" not in err


def write_open_cube_stl(path):
    corners = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    faces = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
             (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7)]  # (1, 7, 5) missing
    lines = ["solid open"]
    for f in faces:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += [f"vertex {x} {y} {z}" for x, y, z in corners[list(f)]]
        lines += ["endloop", "endfacet"]
    lines.append("endsolid open")
    path.write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize("command", ["poses", "check"])
def test_an_open_mesh_gets_a_clear_error_never_a_hang(tmp_path, command):
    stl = tmp_path / "open.stl"
    write_open_cube_stl(stl)
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    result = subprocess.run([sys.executable, "-m", "plumbob.cli", command, str(stl)],
                            capture_output=True, text=True, env=env, timeout=60)
    assert result.returncode == 2
    assert "open" in result.stderr or "closed" in result.stderr


def test_cli_startup_stays_light():
    """The stability commands are registered at start-up: they must not load scipy."""
    code = ("import sys; from plumbob.cli import build_parser; build_parser(); "
            "print([m for m in ('scipy', 'shapely', 'manifold3d', 'trimesh') "
            "if m in sys.modules])")
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            env=env, timeout=60)
    assert result.stdout.strip() == "[]", result.stderr
