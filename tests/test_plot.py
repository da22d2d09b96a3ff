"""Pictures: what is drawn is where the numbers say (not just that a file appears)."""

import json
import os
import subprocess
import sys

import matplotlib
import numpy as np
import pytest
from conftest import ROOT, SHAPES

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import plumbob  # noqa: E402
from plumbob.bodies import primitives as P  # noqa: E402
from plumbob.cli import main  # noqa: E402
from plumbob.plot import plot_body, plot_check, plot_lift, plot_poses, tilt_rose  # noqa: E402
from plumbob.plot.geometry import decimate, drawing  # noqa: E402
from plumbob.plot.style import SI  # noqa: E402
from plumbob.stability import check, resting_poses  # noqa: E402

A = np.sqrt(3) / 2  # the sculpture's a; h = √3 a = 1.5
H = 1.5


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _by_gid(ax, gid):
    return [a for a in ax.get_children() if a.get_gid() == gid]


def _stl(tmp_path, body, name="part.stl"):
    import trimesh

    tri = np.asarray(body.triangles, dtype=float)
    mesh = trimesh.Trimesh(tri.reshape(-1, 3), np.arange(len(tri) * 3).reshape(-1, 3))
    path = tmp_path / name
    mesh.export(path)
    return str(path)


# ------------------------------------------------------------------ start-up
def test_commands_without_plot_do_not_import_matplotlib():
    shape = os.path.join(SHAPES, "block.toml")
    code = (
        "import sys, io, contextlib; from plumbob.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        f"    for c in ('mass', 'check', 'poses', 'lift'): main([c, {shape!r}, '--json'])\n"
        "sys.stderr.write(repr([m for m in ('matplotlib', 'plotly') if m in sys.modules]))"
    )
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert result.returncode == 0, result.stderr
    assert result.stderr.strip().endswith("[]"), result.stderr


# ---------------------------------------------------------- the sculpture
def test_sculpture_check_draws_section_centre_base_and_tipping_point(tmp_path, capsys):
    path = os.path.join(SHAPES, "sculpture.toml")
    out = tmp_path / "s.png"
    assert main(["check", path, "--plot", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    body = plumbob.load(path)
    fig = plot_check(check(body), body)
    ax = fig.axes[0]
    (com,) = _by_gid(ax, "centre of mass")
    np.testing.assert_allclose(com.get_xydata()[0], [-4 * A / 21, 19 * H / 21], atol=1e-12)
    (base,) = _by_gid(ax, "support")
    np.testing.assert_allclose(sorted(base.get_xydata()[:, 0]), [-2 * A, 0.0], atol=1e-12)
    np.testing.assert_allclose(base.get_xydata()[:, 1], 0.0, atol=1e-12)
    tips = np.array([t.get_xydata()[0] for t in _by_gid(ax, "tipping point")])
    assert np.any(np.all(np.abs(tips) < 1e-12, axis=1))  # O, the right-hand end of the base
    texts = [t.get_text() for t in ax.texts]
    assert "tips here at 6.93°" in texts
    assert any(a.get_gid() == "body" for a in ax.patches)  # the cross-section itself


def test_lamina_holes_are_holes():
    fig = plot_body(P.annulus(0.5, 1.0))
    ax = fig.axes[0]
    fig.canvas.draw()
    pixels = np.asarray(fig.canvas.buffer_rgba())

    def colour(x, y):
        px, py = ax.transData.transform((x, y))
        return pixels[int(round(pixels.shape[0] - py)), int(round(px)), :3]

    assert np.all(colour(0.3, 0.1) == 255)  # the hole is paper white
    assert not np.all(colour(0.75, 0.0) == 255)  # the ring is filled


# ------------------------------------------------------------------ solids
def test_solid_check_marks_centre_and_support_polygon():
    body = P.box(2.0, 1.0, 4.0, density=1000.0).translated([0.3, -0.2, 0.0])
    v = check(body, require_tilt_deg=10)
    fig = plot_check(v, body)
    ax3d, side, plan, rose = fig.axes
    (com3,) = _by_gid(ax3d, "centre of mass")
    np.testing.assert_allclose(np.ravel(com3.get_data_3d()), v.center_of_mass, atol=1e-12)
    # the side view looks across the weakest way: its horizontal axis runs along it
    (com_side,) = _by_gid(side, "centre of mass")
    along = v.center_of_mass @ v.critical_direction
    np.testing.assert_allclose(com_side.get_xydata()[0], [along, v.center_of_mass[2]],
                               atol=1e-12)
    (polygon,) = _by_gid(plan, "support polygon")
    drawn = polygon.get_xy()[:-1]
    expected = v.support.polygon[:, :2]
    assert len(drawn) == len(expected) == 4
    assert {tuple(np.round(p, 9)) for p in drawn} == {tuple(np.round(p, 9)) for p in expected}
    (foot,) = _by_gid(plan, "foot")
    np.testing.assert_allclose(foot.get_xydata()[0], v.center_of_mass[:2], atol=1e-12)
    assert foot.get_color() == "#1a7f37"  # stands comfortably: green
    assert _by_gid(rose, "required tilt")


def test_tilt_rose_follows_the_verdict():
    v = check(P.box(1.0, 1.0, 4.0))
    fig = tilt_rose(v)
    (line,) = [ln for ln in fig.axes[0].lines if ln.get_label() == "critical tilt by direction"]
    theta, r = line.get_data()
    k = int(np.argmin(np.abs(theta - 0.0)))
    assert r[k] == pytest.approx(np.degrees(np.arctan(0.5 / 2.0)))
    assert r.min() == pytest.approx(v.critical_tilt_deg)


def test_toppling_is_red_and_amber_below_required():
    leaning = P.polygon([[0, 0], [1, 0], [3, 2], [2, 2]])
    v = check(leaning)
    assert v.verdict == "topples"
    (foot,) = _by_gid(plot_check(v, leaning).axes[0], "foot")
    assert foot.get_color() == "#c62828"
    v = check(plumbob.load(os.path.join(SHAPES, "sculpture.toml")), require_tilt_deg=10)
    (foot,) = _by_gid(plot_check(v).axes[0], "foot")
    assert foot.get_color() == "#f0b400"


def test_assembly_parts_are_coloured_by_material_with_a_legend():
    body = plumbob.load(os.path.join(SHAPES, "mace_assembly.toml"))
    fig = plot_body(body)
    texts = [t.get_text() for t in fig.axes[1].get_legend().get_texts()]
    assert any(t.startswith("shaft (760") for t in texts)
    assert any(t.startswith("head (7850") for t in texts)


# ------------------------------------------------------------------- poses
@pytest.mark.parametrize("with_body", [True, False])
def test_gallery_has_one_panel_per_pose(with_body):
    body = P.box(1.0, 2.0, 3.0)
    poses = resting_poses(body)
    fig = plot_poses(poses, body if with_body else None)
    panels = [a for a in fig.axes if a.get_gid() == "pose"]
    assert len(panels) == len(poses) == 6
    assert panels[0].get_title().startswith(f"#1  p = {poses[0].probability:.3f}")


def test_lamina_gallery_and_result_methods():
    body = plumbob.load(os.path.join(SHAPES, "l_shape.toml"))
    poses = resting_poses(body)
    fig = poses.plot(body=body)
    assert len([a for a in fig.axes if a.get_gid() == "pose"]) == len(poses)
    assert poses._repr_png_()[:4] == b"\x89PNG"
    v = check(body)
    assert v._repr_png_()[:4] == b"\x89PNG"
    fig, ax = plt.subplots()
    assert body.plot(ax=ax) is fig
    assert v.plot(ax=ax, body=body) is fig


# -------------------------------------------------------------------- files
def test_plot_on_every_command_and_format(tmp_path, capsys):
    stl = _stl(tmp_path, P.box(0.02, 0.03, 0.05))
    for command, name in (("mass", "m.svg"), ("check", "c.svg"), ("poses", "p.png"),
                          ("lift", "l.pdf")):
        target = tmp_path / name
        assert main([command, stl, "--plot", str(target)]) == 0, command
        head = target.read_bytes()[:64]
        assert {"svg": b"<?xml", "png": b"\x89PNG", "pdf": b"%PDF"}[name[-3:]] in head
    assert not [f for f in os.listdir(tmp_path) if f.startswith(".plumbob-")]


def test_plot_leaves_json_unchanged(tmp_path, capsys):
    path = os.path.join(SHAPES, "sculpture.toml")
    main(["check", path, "--json"])
    plain = json.loads(capsys.readouterr().out)
    main(["check", path, "--json", "--plot", str(tmp_path / "s.png")])
    assert json.loads(capsys.readouterr().out) == plain


def test_bad_plot_targets(tmp_path, capsys):
    path = os.path.join(SHAPES, "block.toml")
    with pytest.raises(SystemExit) as exit_:
        main(["check", path, "--plot", str(tmp_path / "s.txt")])  # refused before any work
    assert exit_.value.code == 2
    assert "PNG, SVG or PDF" in capsys.readouterr().err
    assert main(["check", path, "--plot", str(tmp_path / "missing" / "s.png")]) == 2
    assert "cannot write" in capsys.readouterr().err


def test_failed_drawing_leaves_no_file(tmp_path, monkeypatch, capsys):
    from matplotlib.figure import Figure

    def broken(self, *args, **kwargs):
        kwargs = args[0] if args else None
        kwargs.write(b"partial")
        raise OSError("disk full")

    monkeypatch.setattr(Figure, "savefig", broken)
    target = tmp_path / "s.png"
    assert main(["mass", os.path.join(SHAPES, "block.toml"), "--plot", str(target)]) == 2
    assert os.listdir(tmp_path) == []


def test_lift_picture_marks_datum_and_centre():
    from plumbob.energy import lift_energy

    body = plumbob.load(os.path.join(SHAPES, "pyramid_cheops.toml"))
    lift = lift_energy(body)
    fig = plot_lift(lift, body)
    ax = fig.axes[0]
    (com,) = _by_gid(ax, "centre of mass")
    assert com.get_xydata()[0][1] == pytest.approx(lift.datum + lift.com_height)
    (datum,) = _by_gid(ax, "datum")
    assert datum.get_ydata()[0] == pytest.approx(lift.datum)


# --------------------------------------------------------------- decimation
def test_decimation_keeps_the_shape_and_says_so():
    import trimesh

    sphere = trimesh.creation.icosphere(subdivisions=6)  # 81,920 triangles
    tri = sphere.vertices[sphere.faces]
    small = decimate(tri, 5000)
    assert 500 < len(small) <= 5000
    np.testing.assert_allclose(small.reshape(-1, 3).min(axis=0), -1, atol=0.05)
    np.testing.assert_allclose(small.reshape(-1, 3).max(axis=0), 1, atol=0.05)
    d = drawing(plumbob.MeshSolid(tri), 5000)
    assert d.decimated and "81,920" in d.note


# ------------------------------------------------------------------- report
def _external_resources(page: str) -> list[str]:
    """Every script, style sheet, image or frame the page would fetch."""
    from html.parser import HTMLParser

    found = []

    class Parser(HTMLParser):
        def handle_starttag(self, tag, attrs):
            for name, value in attrs:
                if name in ("src", "href") and value and not value.startswith(("data:", "#")):
                    found.append(f"{tag} {name}={value}")

    Parser().feed(page)
    return found


def test_report_page_is_self_contained(tmp_path, capsys):
    out = tmp_path / "r.html"
    assert main(["report", os.path.join(SHAPES, "stepped_cylinder.toml"), "-o", str(out),
                 "--require-tilt", "10"]) == 0
    page = out.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>")
    assert _external_resources(page) == []
    assert page.count("Plotly.newPlot") >= 2  # the 3-D view and the tilt rose
    for section in ("Mass properties", "Stability on level ground", "Resting poses",
                    "centre of mass G", "support polygon", "data:image/png;base64,"):
        assert section in page, section


def test_report_on_a_lamina_and_a_mesh(tmp_path, capsys):
    out = tmp_path / "l.html"
    assert main(["report", os.path.join(SHAPES, "sculpture.toml"), "-o", str(out)]) == 0
    assert "Resting poses (3)" in out.read_text(encoding="utf-8")
    capsys.readouterr()
    stl = _stl(tmp_path, P.box(1.0, 2.0, 3.0))
    assert main(["report", stl, "-o", str(tmp_path / "m.html"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["report"].endswith("m.html")


def _headline(page: str) -> str:
    import re

    found = re.findall(r'<span class="verdict" id="headline" style="background:([^;]*);[^"]*">'
                       r"([^<]*)</span>", page)
    assert len(found) == 1, found
    return found[0]


def test_a_failed_requirement_is_the_report_headline(tmp_path, capsys):
    """The seed's block stands with a critical tilt of 14.04°: asked for 40° the page's
    first words are FAIL, in the topples colour, with both tilts; for half its tilt, PASS."""
    from plumbob.plot.style import STATUS_COLOURS

    stepped = os.path.join(SHAPES, "block.toml")
    assert main(["check", stepped, "--json"]) == 0
    tilt = json.loads(capsys.readouterr().out)["critical_tilt_deg"]
    out = tmp_path / "r.html"
    capsys.readouterr()
    assert main(["report", stepped, "-o", str(out), "--require-tilt", "40"]) == 0
    colour, text = _headline(out.read_text(encoding="utf-8"))
    assert tilt < 40
    assert text.startswith("FAIL: required tilt 40° not met") and f"{tilt:.4g}°" in text
    assert colour == STATUS_COLOURS["topples"]
    assert main(["report", stepped, "-o", str(out), "--require-tilt", f"{tilt * 0.5:.3g}"]) == 0
    colour, text = _headline(out.read_text(encoding="utf-8"))
    assert text.startswith("PASS: stands") and colour == STATUS_COLOURS["stands"]


def test_the_report_page_shows_a_mm_part_in_mm_and_g_and_an_assemblys_parts(tmp_path, capsys):
    """A 40 × 20 × 60 mm PLA box read in mm: 59.52 g, centre (20, 10, 30) mm, the 3-D
    view's axes in mm; the cabinet's three parts each with their mass and centre."""
    import trimesh

    box = tmp_path / "box.stl"
    trimesh.creation.box(extents=(40, 20, 60)).apply_translation((20, 10, 30)).export(box)
    out = tmp_path / "box.html"
    assert main(["report", str(box), "--units", "mm", "--material", "pla", "-o", str(out)]) == 0
    page = out.read_text(encoding="utf-8")
    assert "<th>mass</th><td>59.52 g</td>" in page
    assert "<th>centre of mass</th><td>(20, 10, 30) mm</td>" in page
    assert '"text":"x, mm"' in page.replace(" ", "").replace('"text":"x,mm"', '"text":"x, mm"')
    cabinet = os.path.join(SHAPES, "cabinet.toml")
    capsys.readouterr()
    assert main(["mass", cabinet, "--json"]) == 0
    parts = json.loads(capsys.readouterr().out)["part_properties"]
    assert main(["report", cabinet, "-o", str(out)]) == 0
    page = out.read_text(encoding="utf-8")
    assert f"<h2>Parts ({len(parts)})</h2>" in page
    for part in parts:
        assert f"<tr><td>{part['name']}</td><td>{part['kind']}</td>" in page
        assert f"<td>{part['mass']:.6g}</td>" in page


def test_the_report_gallery_captions_are_as_large_as_the_tables_text(monkeypatch):
    """The pose captions, in pixels of the PNG shown at its own size, are no smaller
    than the tables' 16 px; the page shows the image unscaled up to its width."""
    from plumbob.plot import files, html
    from plumbob.stability.poses import resting_poses

    drawn = []
    real = files.png_bytes

    def keep(fig, dpi=100):
        drawn.append((fig, dpi, [ax.title.get_fontsize() for ax in fig.axes
                                 if ax.get_gid() == "pose"]))
        return real(fig, dpi)

    monkeypatch.setattr(files, "png_bytes", keep)
    body = P.box(1.0, 2.0, 3.0)
    html._poses_html(resting_poses(body), body, SI)
    (_, dpi, sizes), = drawn
    assert sizes and min(sizes) * dpi / 72 >= html.TABLE_FONT_PX - 1e-9


def test_the_report_rose_marks_the_weakest_direction_and_names_the_axes(tmp_path, capsys):
    """The cabinet tips forward (−y) first: the rose's marker sits at −90° (e1 = +x,
    e2 = +y on level ground) with its tilt, and the angular axis says toward +x."""
    out = tmp_path / "c.html"
    assert main(["report", os.path.join(SHAPES, "cabinet.toml"), "-o", str(out)]) == 0
    page = out.read_text(encoding="utf-8")
    assert '"ticktext":["toward +x","\\u2212x","+y","\\u2212y"]' in page
    capsys.readouterr()
    assert main(["check", os.path.join(SHAPES, "cabinet.toml"), "--json"]) == 0
    tilt = json.loads(capsys.readouterr().out)["critical_tilt_deg"]
    assert f'"weakest {tilt:.3g}\\u00b0"' in page
    assert '"theta":[-90.0]' in page
