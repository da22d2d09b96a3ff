"""check's readable report: the weakest edges, round bases as arcs, by how much a body
topples, and by how much a design check is missed — against closed forms."""

import json
import os

import numpy as np
import pytest
from conftest import SHAPES

from plumbob.bodies.csg import union
from plumbob.bodies.primitives import cylinder
from plumbob.cli import main
from plumbob.stability import check

A = np.sqrt(3) / 2
H = np.sqrt(3) * A


def run(capsys, *args, status=0):
    assert main(list(args)) == status
    return capsys.readouterr().out


def test_shortfall_of_a_failed_design_check(capsys):
    out = run(capsys, "check", os.path.join(SHAPES, "sculpture.toml"), "--require-tilt", "10",
              status=1)
    critical = np.degrees(np.arctan((4 * A / 21) / (19 * H / 21)))
    assert f"FAIL (critical tilt {critical:.4g}°, {10 - critical:.4g}° short of 10°)" in out
    data = json.loads(run(capsys, "check", os.path.join(SHAPES, "sculpture.toml"),
                          "--require-tilt", "10", "--json", status=1))
    assert data["shortfall_deg"] == pytest.approx(10 - critical, rel=1e-9)
    passed = json.loads(run(capsys, "check", os.path.join(SHAPES, "sculpture.toml"),
                            "--require-tilt", "5", "--json"))
    assert passed["passes"] is True and "shortfall_deg" not in passed


def _overhang_spec(tmp_path) -> str:
    """A 1 m cube foot under a 4 × 1 × 1 m beam reaching to x = 4: the centre is at
    x = (0.5 + 4·2)/5 = 1.7, 0.7 m beyond the foot's edge x = 1, at height 1.3 m."""
    path = tmp_path / "overhang.toml"
    path.write_text('[shape]\nkind = "solid"\ndensity = 1\n'
                    '[[part]]\ntype = "cube"\nside = 1\n'
                    '[[part]]\ntype = "box"\nlength = 4\nwidth = 1\nheight = 1\nat = [0, 0, 1]\n',
                    encoding="utf-8")
    return str(path)


def test_a_toppling_body_says_by_how_much(tmp_path, capsys):
    spec = _overhang_spec(tmp_path)
    over = np.degrees(np.arctan(0.7 / 1.3))
    out = run(capsys, "check", spec, "--require-tilt", "10", status=1)
    assert "the centre of mass is 0.7 m beyond the support" in out
    assert f"none: it is over by {over:.4g}°" in out
    assert f"FAIL (it topples, over by {over:.4g}°: {10 + over:.4g}° short of 10°)" in out
    assert "critical tilt     -" not in out
    data = json.loads(run(capsys, "check", spec, "--json"))
    assert data["verdict"] == "topples"
    assert data["overhang"] == pytest.approx(0.7, rel=1e-12)
    assert data["over_by_deg"] == pytest.approx(over, rel=1e-12)


def test_a_round_base_is_one_arc(tmp_path, capsys):
    path = tmp_path / "drum.toml"
    path.write_text('[shape]\nkind = "solid"\n[[part]]\ntype = "cylinder"\nradius = 1\n'
                    'height = 2\n', encoding="utf-8")
    out = run(capsys, "check", str(path))
    v = check(cylinder(1, 2))
    assert f"the whole round rim ({len(v.edges)} edges)" in out
    assert len(v.edges) > 100 and out.count("\n(") == 0


def test_two_legs_are_two_sides_and_two_arcs():
    legs = union(cylinder(0.1, 1), cylinder(0.1, 1).translated([1, 0, 0]))
    v = check(legs)
    groups = v.edge_groups()
    assert sorted(g.kind for g in groups) == ["arc", "arc", "edge", "edge"]
    assert sum(g.count for g in groups) == len(v.edges)
    # the weakest: a straight side, 0.1 m from the centre's foot, atan(0.1/0.5)
    assert groups[0].kind == "edge"
    assert groups[0].tipping_angle_deg == pytest.approx(np.degrees(np.arctan(0.2)), rel=1e-9)
    assert min(g.distance for g in groups) == pytest.approx(v.margin)


def test_only_the_weakest_edges_unless_all(tmp_path, capsys):
    """A 12-sided prism: 12 edges (none short enough to be an arc), four listed."""
    path = tmp_path / "prism.toml"
    path.write_text('[shape]\nkind = "solid"\n[[part]]\ntype = "extrude"\nheight = 3\n'
                    '[part.profile]\ntype = "regular_polygon"\nsides = 12\nradius = 1\n',
                    encoding="utf-8")
    out = run(capsys, "check", str(path))
    assert "weakest tipping edges" in out and "… and 8 more (8 edges" in out
    table = out.split("weakest tipping edges")[1].splitlines()[1:5]
    assert len(table) == 4 and all(line.startswith("(") for line in table)
    full = run(capsys, "check", str(path), "--all-edges")
    assert "… and" not in full
    rows = full.split("tipping over")[1].strip().splitlines()[1:]
    assert len([row for row in rows if row.startswith("(")]) == 12
    data = json.loads(run(capsys, "check", str(path), "--json"))
    assert len(data["edges"]) == 12
