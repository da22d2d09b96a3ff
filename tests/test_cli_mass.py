import json
import os
from fractions import Fraction as F

import numpy as np
import pytest
from conftest import SHAPES

from plumbob.cli import main

KEYS = {
    "kind",
    "mass",
    "center_of_mass",
    "inertia",
    "principal_moments",
    "principal_axes",
    "exact",
    "parts",
}


def run_json(capsys, *args):
    assert main(["mass", *args, "--json"]) == 0
    out = capsys.readouterr().out
    return json.loads(out)


def test_json_keys_for_a_lamina(capsys):
    data = run_json(capsys, os.path.join(SHAPES, "semicircle.toml"))
    assert KEYS <= set(data)
    assert data["kind"] == "lamina" and "area" in data and "volume" not in data
    assert len(data["center_of_mass"]) == 2
    assert np.array(data["inertia"]).shape == (3, 3)
    assert data["center_of_mass"][1] == pytest.approx(4 / (3 * np.pi), rel=1e-14)
    assert any("no density" in n for n in data["notes"])


def test_json_keys_for_a_solid_and_density_option(capsys):
    data = run_json(capsys, os.path.join(SHAPES, "stepped_cylinder.toml"), "--density", "2")
    assert data["kind"] == "solid" and "volume" in data
    assert data["mass"] == pytest.approx(2 * 20 * np.pi, rel=1e-14)
    assert "notes" not in data


def test_material_option(capsys):
    data = run_json(capsys, os.path.join(SHAPES, "stepped_cylinder.toml"), "--material", "steel")
    assert data["mass"] == pytest.approx(7850 * 20 * np.pi, rel=1e-14)


def test_text_report(capsys):
    assert main(["mass", os.path.join(SHAPES, "l_shape.toml")]) == 0
    out = capsys.readouterr().out
    assert "centre of mass" in out and "(0.833333, 0.833333)" in out


def test_particles_report(capsys):
    data = run_json(capsys, os.path.join(SHAPES, "earth_moon.toml"))
    assert data["kind"] == "particles" and data["parts"] == 2


@pytest.mark.parametrize(
    "args, message",
    [
        (["missing.toml"], "no such file"),
        (["shape.xyz"], "unknown file type"),
        (["bad_key.toml"], "unknown key"),
        (["unsafe.toml"], "unexpected character"),
        (["malformed.toml"], "ends too soon"),
        (["zero.toml"], "must be a positive"),
        (["ok.toml", "--density", "-1"], "--density must be a positive"),
        (["ok.toml", "--material", "kryptonite"], "unknown material"),
    ],
)
def test_bad_input_one_line_exit_2(tmp_path, capsys, args, message):
    specs = {
        "shape.xyz": "",
        "bad_key.toml": '[[part]]\ntype = "disc"\nradius = 1\ncolour = "red"\n',
        "unsafe.toml": '[[part]]\ntype = "disc"\nradius = "__import__(\'os\')"\n',
        "malformed.toml": '[[part]]\ntype = "disc"\nradius = "2 +"\n',
        "zero.toml": '[[part]]\ntype = "box"\nlength = 1\nwidth = 0\nheight = 1\n',
        "ok.toml": '[[part]]\ntype = "disc"\nradius = 1\n',
    }
    for name, text in specs.items():
        (tmp_path / name).write_text(text)
    path = str(tmp_path / args[0])
    code = main(["mass", path, *args[1:]])
    captured = capsys.readouterr()
    assert code == 2
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and message in lines[0] and "Traceback" not in captured.err


def test_zero_area_body_is_an_error(tmp_path, capsys):
    path = tmp_path / "flat.toml"
    path.write_text('[[part]]\ntype = "polygon"\nvertices = [[0, 0], [1, 1], [2, 2]]\n')
    assert main(["mass", str(path)]) == 2
    assert "no area" in capsys.readouterr().err


def test_usage_errors_exit_2(capsys):
    with pytest.raises(SystemExit) as info:
        main(["mass"])
    assert info.value.code == 2


def test_an_internal_error_is_one_line_and_status_3_never_1(monkeypatch, capsys):
    """A bug must not look like a failed requirement (1) or bad input (2) to a CI gate."""
    from plumbob import cli
    from plumbob.commands import mass

    def broken(args):
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(mass, "run", broken)
    monkeypatch.delenv("PLUMBOB_DEBUG", raising=False)
    parser = cli.build_parser("mass")
    monkeypatch.setattr(cli, "build_parser", lambda command=None: parser)
    parser.set_defaults(func=broken)
    status = cli.main(["mass", "shapes/block.toml"])
    err = capsys.readouterr().err
    assert status == cli.INTERNAL_ERROR == 3
    assert err.count("\n") == 1 and "ZeroDivisionError" in err and "Traceback" not in err


BRACKET = """
[shape]
name = "L-bracket"
kind = "solid"
[[part]]
type = "box"
length = 3
width = 0.5
height = 2
[[part]]
type = "box"
length = 0.5
width = 2.5
height = 2
[[part]]
op = "subtract"
type = "box"
length = 5
width = 2.5
height = 0.5
at = [-1, 0, 0.75]
"""


def test_an_l_bracket_of_boxes_is_reported_exact(capsys, tmp_path):
    """Two overlapping boxes minus a slot through both: no curve anywhere, so `exact` and
    the exact rational answer (volume 4.625, centre by inclusion and exclusion)."""
    spec = tmp_path / "bracket.toml"
    spec.write_text(BRACKET, encoding="utf-8")
    assert main(["mass", str(spec), "--density", "1"]) == 0
    out = capsys.readouterr().out
    assert "exact                   yes" in out and "segments per turn" not in out
    data = run_json(capsys, str(spec), "--density", "1")
    # legs 3 + 2.5 − their overlap 0.5, all 2 high, less a 0.5 slot: 5 · 1.5
    volume = F(3, 1) * F(1, 2) * 2 + F(1, 2) * F(5, 2) * 2 - F(1, 2) * F(1, 2) * 2
    volume *= F(3, 4)
    assert data["exact"] is True and data["relative_error"] < 1e-9
    assert data["volume"] == pytest.approx(float(volume), rel=1e-12)
    assert data["center_of_mass"][2] == pytest.approx(1.0, rel=1e-12)  # symmetric in z


def test_the_cabinet_carcass_is_exact_and_mirror_symmetric(capsys):
    """shapes/cabinet.toml: boxes minus boxes. Exact (round-off bounded, no facetings
    spoken of), symmetric about x = 0.3 so Ixy = Ixz = 0 to round-off."""
    assert main(["mass", os.path.join(SHAPES, "cabinet.toml")]) == 0
    out = capsys.readouterr().out
    assert "exact                   yes" in out and "segments per turn" not in out
    data = run_json(capsys, os.path.join(SHAPES, "cabinet.toml"))
    inertia = np.array(data["inertia"])
    assert data["exact"] is True and data["relative_error"] < 1e-8
    assert abs(inertia[0, 1]) <= 1e-14 * abs(inertia).max()
    assert abs(inertia[0, 2]) <= 1e-14 * abs(inertia).max()
    assert data["center_of_mass"][0] == pytest.approx(0.3, rel=1e-15)
    carcass = data["part_properties"][0]
    # 0.6 · 0.45 · 1.2 less the inside 0.564 · 0.432 · 1.164 (the front is open)
    volume = F(6, 10) * F(45, 100) * F(12, 10) - F(564, 1000) * F(432, 1000) * F(1164, 1000)
    assert carcass["volume"] == pytest.approx(float(volume), rel=1e-12)


def test_mass_reports_radii_area_box_and_the_inertia_about_a_point(tmp_path, capsys):
    """A 40 × 20 × 60 mm box with a corner at the origin, 1240 kg/m³: about that corner
    Ixx = m(b² + c²)/3 and Ixy = −m a b/4 (closed forms), the point given in mm like
    the file's coordinates; radii of gyration sqrt(I/m) about the centre; 8800 mm²."""
    import trimesh

    path = tmp_path / "box.stl"
    trimesh.creation.box(extents=(40, 20, 60)).apply_translation((20, 10, 30)).export(path)
    assert main(["mass", str(path), "--units", "mm", "--material", "pla", "--about", "0,0,0",
                 "--sizes", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    a, b, c = 0.04, 0.02, 0.06
    m = a * b * c * 1240
    about = np.array(out["inertia_about"]["inertia"])
    assert about[0, 0] == pytest.approx(m * (b * b + c * c) / 3, rel=1e-12)
    assert about[0, 1] == pytest.approx(-m * a * b / 4, rel=1e-12)
    assert about[1, 2] == pytest.approx(-m * b * c / 4, rel=1e-12)
    central = sorted([m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12])
    assert out["radii_of_gyration"] == pytest.approx(np.sqrt(np.array(central) / m), rel=1e-12)
    assert out["surface_area"] == pytest.approx(2 * (a * b + b * c + a * c), rel=1e-12)
    assert out["surface_area_exact"] is True
    assert out["bounding_box_lower"] == pytest.approx([0, 0, 0], abs=1e-15)
    assert out["bounding_box_upper"] == pytest.approx([a, b, c], rel=1e-12)
    assert main(["mass", str(path), "--units", "mm", "--about", "0,0,0", "--sizes"]) == 0
    text = capsys.readouterr().out
    assert "inertia (about (0, 0, 0) mm)" in text and "surface area" in text
    assert "8800 mm²" in text and "40 × 20 × 60 mm" in text
