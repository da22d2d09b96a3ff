"""`plumbob balance --wall` with ballast, and with `--target-pose auto` (issue 23).

Small convex bodies keep these fast: a convex mesh's inward offset is exact (every face
plane moved in), so no level set is taken.

* A prism leaning out over its base (30 × 20 mm, its top shifted 36 mm along x, 40 mm
  up) topples by 3 mm; the best any carve with 2 mm walls reaches is a margin of about
  1.3 mm. Asked for 3 mm, hollowing alone refuses and offers ballast; with
  ``--ballast-material`` the best carve is taken and the least ballast makes up the
  rest, checked against the ballast plumbob finds for the carved file read back.
* A wedge (legs 40 and 30 mm, 60 mm long) asked for a margin of 23 mm with 2 mm walls:
  in its most probable pose (on its 40 × 60 face, margin 22.7 mm as it is) a carve does
  it; in the others no carve reaches 23 mm. ``--target-pose auto`` takes that pose,
  empties what ``--target-pose 1`` empties, and the written file stands that way up.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from plumbob.formats.writers import stl_bytes

MM = 1e-3
RHO = 1200.0


def _convex_stl(path, corners_mm) -> None:
    """The convex hull of the corners (mm), wound outward, written as a binary STL in mm."""
    from scipy.spatial import ConvexHull

    points = np.asarray(corners_mm, dtype=float) * MM
    hull = ConvexHull(points)
    tri = points[hull.simplices]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    flip = np.einsum("ij,ij->i", normal, tri.mean(axis=1) - points.mean(axis=0)) < 0
    tri[flip] = tri[flip][:, ::-1]
    path.write_bytes(stl_bytes(tri, path.stem, MM))


def _run(capsys, *argv) -> tuple[int, dict | None, str]:
    from plumbob.cli import main

    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, (json.loads(out) if status == 0 and "--json" in argv else None), err


@pytest.fixture(scope="module")
def leaning(tmp_path_factory):
    folder = tmp_path_factory.mktemp("leaning")
    path = folder / "leaning.stl"
    _convex_stl(path, [[0, 0, 0], [30, 0, 0], [30, 20, 0], [0, 20, 0],
                       [36, 0, 40], [66, 0, 40], [66, 20, 40], [36, 20, 40]])
    return path


def test_wall_with_ballast_carves_the_best_and_ballasts_the_rest(leaning, tmp_path, capsys):
    from plumbob import read
    from plumbob.balance.result import balance

    common = ["balance", str(leaning), "--units", "mm", "--density", str(RHO), "--wall", "2mm",
              "--margin", "3mm", "--out", str(tmp_path / "carved.stl")]
    # hollowing alone: refused, the bound stated and ballast offered
    status, _, err = _run(capsys, *common)
    assert status == 1 and not (tmp_path / "carved.stl").exists()  # a target not met
    found = re.search(r"with 2 mm walls reaches is a margin of ([0-9.]+) mm", err)
    assert found, err
    assert "--ballast-material" in err
    bound = float(found.group(1)) * MM
    assert 0 < bound < 3 * MM
    # with ballast: the best carve, then the least steel
    status, out, _ = _run(capsys, *common, "--ballast-material", "steel", "--json")
    assert status == 0 and out["passes"]
    carve = out["hollow"]
    assert not carve["target_met"] and carve["removed_mass"] > 0
    # the carve taken is the best one: its margin, measured on the file, is the bound
    assert carve["margin"] == pytest.approx(carve["bound"]["value"], rel=1e-6)
    assert carve["bound"]["value"] == pytest.approx(bound, rel=5e-3)  # the message's 3 digits
    ballast = out["ballast"]
    assert ballast["material"] == "steel" and ballast["mass"] > 0
    assert ballast["volume"] * ballast["density"] == pytest.approx(ballast["mass"], rel=1e-12)
    assert out["after"]["margin"] >= 3 * MM
    # the same ballast as plumbob finds for the carved file on its own
    carved = read(str(tmp_path / "carved.stl"), units="mm").body.with_default_density(RHO)
    alone = balance(carved, margin=3 * MM, material="steel", density=ballast["density"])
    assert alone.ballast_mass == pytest.approx(ballast["mass"], rel=1e-9)


def test_target_pose_auto_with_a_wall_takes_the_pose_a_carve_can_make_stand(tmp_path, capsys):
    wedge = tmp_path / "wedge.stl"
    _convex_stl(wedge, [[0, 0, 0], [40, 0, 0], [0, 0, 30], [0, 60, 0], [40, 60, 0],
                        [0, 60, 30]])
    common = ["balance", str(wedge), "--units", "mm", "--density", str(RHO), "--wall", "2mm",
              "--margin", "23mm", "--json"]
    status, out, _ = _run(capsys, *common, "--target-pose", "auto", "--out",
                          str(tmp_path / "auto.stl"))
    assert status == 0
    tried = out["poses_tried"]
    assert len(tried) >= 2
    costs = [np.inf if t["cost"] is None else t["cost"] for t in tried]
    chosen = int(np.argmin(costs))
    assert out["pose"] == tried[chosen]["pose"] and np.isfinite(costs[chosen]) and costs[chosen] > 0
    # the others: no carve reaches 23 mm there, and the bound each states is below it
    for t, cost in zip(tried, costs):
        if not np.isfinite(cost):
            found = re.search(r"reaches is a margin of ([0-9.]+) mm", t["needs"])
            assert found and float(found.group(1)) < 23, t["needs"]
    # the chosen pose asked for by number empties the same, and its file stands that way up
    status, alone, _ = _run(capsys, *common, "--target-pose", str(out["pose"]), "--out",
                            str(tmp_path / "alone.stl"))
    assert status == 0
    assert alone["hollow"]["removed_mass"] == pytest.approx(out["hollow"]["removed_mass"],
                                                            rel=1e-12)
    # the plan's cost against the file's (its float32 corners): within the file's round-off
    assert out["hollow"]["removed_mass"] == pytest.approx(costs[chosen], rel=1e-6)
    down = ",".join(f"{v:.17g}" for v in out["target"]["down"])
    status, check, _ = _run(capsys, "check", str(tmp_path / "auto.stl"), "--units", "mm",
                            "--density", str(RHO), "--down", down, "--margin", "23mm", "--json")
    assert status == 0 and check["verdict"] == "stands" and check["margin"] >= 23 * MM
