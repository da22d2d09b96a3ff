"""Standards as bundles: IEC 62368-1 passes a squat cabinet and fails a tall column
(against hand calculations); ASTM F2057 on the shipped cabinet reports each drawer."""

from __future__ import annotations

import json
import math
import os

import pytest
from conftest import SHAPES

from plumbob.bodies.primitives import box
from plumbob.cli import main
from plumbob.errors import StabilityError
from plumbob.loading import read
from plumbob.stability.standards import PRESETS, run_standard

G = 9.81


def solid(lx, ly, lz, mass):
    return box(lx, ly, lz, density=mass / (lx * ly * lz))


def test_iec62368_passes_a_squat_cabinet():
    r = run_standard(solid(0.8, 0.5, 0.6, 40.0), "iec62368-1")
    assert r.passes and [t.name for t in r.tests] == ["tilt", "force"]
    tilt, force = r.tests
    assert math.isclose(tilt.margin, math.degrees(math.atan(0.25 / 0.3)) - 10, rel_tol=1e-12)
    # push 0.13 W (< 250 N) at the top (0.6 m), over the narrow way (d = 0.25 m); the press
    # (min(0.5 W, 100 N)) acts at the edge itself: no moment
    w = 40 * G
    want = w * 0.25 / (0.13 * w * 0.6)
    assert math.isclose(force.overturning_safety_factor, want, rel_tol=1e-9)


def test_iec62368_fails_a_tall_slender_column():
    r = run_standard(solid(0.2, 0.2, 1.8, 30.0), "iec62368-1")
    assert not r.passes and not any(t.passes for t in r.tests)
    w = 30 * G
    # the worst push is at the 1.5 m limit, not the 1.8 m top
    want = w * 0.1 / (0.13 * w * 1.5)
    assert math.isclose(r.tests[1].overturning_safety_factor, want, rel_tol=1e-9)
    assert math.isclose(r.tests[1].point[2], 1.5, rel_tol=1e-12)
    assert r.tests[0].margin < 0


def test_the_caps_in_newtons_apply_to_heavy_units():
    """A 500 kg cabinet: 13 % of its weight is 638 N, capped at 250 N."""
    r = run_standard(solid(1.0, 0.6, 2.0, 500.0), "iec62368-1")
    w = 500 * G
    assert math.isclose(r.tests[1].overturning_safety_factor, w * 0.3 / (250 * 1.5),
                        rel_tol=1e-9)


def test_a_display_needs_the_8_6_5_force_too():
    # passes the tilt test but not 20 % of its weight at 1.5 m
    r = run_standard(solid(0.5, 0.4, 1.5, 20.0), "iec62368-1-display")
    names = {t.name: t for t in r.tests}
    assert names["tilt"].passes and not names["display"].passes and not r.passes


def test_astm_f2057_on_the_cabinet_reports_each_drawer(capsys):
    path = os.path.join(SHAPES, "cabinet.toml")
    reading = read(path)
    assert [e.name for e in reading.extendables] == ["drawer"]
    r = run_standard(reading.body, "astm-f2057", extendables=reading.extendables)
    assert [t.case for t in r.tests] == ["drawer"] and r.edition == "F2057-23"
    assert not r.passes and r.tests[0].verdict == "topples"
    assert main(["check", path, "--standard", "astm-f2057", "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    std = out["standard"]
    assert std["edition"] == "F2057-23" and "not a certification" in std["disclaimer"]
    assert std["tests"][0]["case"] == "drawer" and std["passes"] is False


def test_a_spec_without_extendables_is_told_what_to_add():
    with pytest.raises(StabilityError, match=r"\[\[extendable\]\]"):
        run_standard(solid(1, 1, 1, 10.0), "astm-f2057")
    with pytest.raises(StabilityError, match="unknown standard"):
        run_standard(solid(1, 1, 1, 10.0), "en-14749")


def test_every_preset_is_cited_in_the_docs():
    text = open(os.path.join(SHAPES, "..", "docs", "standards.md"), encoding="utf-8").read()
    for name, preset in PRESETS.items():
        assert f"`{name}`" in text and preset.edition in text


def test_check_exit_status_follows_the_bundle(capsys, tmp_path):
    spec = tmp_path / "column.toml"
    spec.write_text('[[part]]\ntype = "box"\nlength = 0.2\nwidth = 0.2\nheight = 1.8\n'
                    "density = 416.67\n")
    assert main(["check", str(spec), "--standard", "iec62368-1"]) == 1
    text = capsys.readouterr().out
    assert "FAIL  tilt" in text and "3rd edition (2018)" in text and "not a certification" in text


def test_batch_adds_a_column_per_test_and_the_loads(tmp_path):
    import csv
    import shutil

    for name in ("block.toml", "cabinet.toml"):
        shutil.copy(os.path.join(SHAPES, name), tmp_path / name)
    out = tmp_path / "rows.csv"
    assert main(["batch", str(tmp_path), "--out", str(out), "--hang", "5@0.2,0.2,0.5",
                 "--standard", "iec62368-1", "--jobs", "1", "--quiet"]) == 0
    rows = {os.path.basename(r["path"]): r for r in csv.DictReader(open(out, encoding="utf-8"))}
    assert rows["block.toml"]["standard_passes"] == "True"
    assert rows["cabinet.toml"]["standard_passes"] == "False"
    for r in rows.values():
        assert {"std_tilt_passes", "std_tilt_margin", "std_force_passes", "std_force_margin",
                "load_verdict", "overturning_safety_factor"} <= set(r)
    single = run_standard(read(os.path.join(SHAPES, "cabinet.toml")).body, "iec62368-1")
    assert math.isclose(float(rows["cabinet.toml"]["std_tilt_margin"]), single.tests[0].margin,
                        rel_tol=1e-12)


def test_the_html_report_shows_the_load_case_and_the_standard(tmp_path):
    pytest.importorskip("plotly")
    out = tmp_path / "cabinet.html"
    path = os.path.join(SHAPES, "cabinet.toml")
    assert main(["report", path, "-o", str(out), "--hang", "10@0.3,-0.3,1",
                 "--standard", "iec62368-1"]) == 0
    page = out.read_text(encoding="utf-8")
    assert "Under the applied loads" in page and "factor of safety" in page
    assert "Standard: iec62368-1" in page and "3rd edition (2018)" in page
    assert "not a certification" in page
