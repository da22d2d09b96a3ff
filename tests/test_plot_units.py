"""``--plot`` labels a picture in the text report's units (issue 22): a part drawn in mm
reads in mm, g and g·mm² in its pictures too, and ``--report-units`` changes them. Tested
by what is drawn — every text artist's string and the tick labels — not by pixels."""

from __future__ import annotations

import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from plumbob.bodies import primitives as P  # noqa: E402
from plumbob.energy import lift_energy  # noqa: E402
from plumbob.plot import plot_body, plot_check, plot_lift, plot_poses  # noqa: E402
from plumbob.report import ReportUnits  # noqa: E402
from plumbob.stability import check, resting_poses  # noqa: E402

MM = ReportUnits("mm", "g")
NUMBER = r"-?[\d.]+(?:e[+-]?\d+)?"


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def part():
    """A 40 × 20 × 60 mm box of PLA (1240 kg/m³), a corner at the origin: 59.52 g, G at
    (20, 10, 30) mm, margin 10 mm; principal moments 9920, 19840, 25792 g·mm²."""
    return P.box(0.04, 0.02, 0.06, density=1240.0)


def _strings(fig) -> list[str]:
    """Every string drawn: titles, labels, legends, annotations (tick labels are made when
    the figure is drawn: their formatters are asked instead)."""
    return [a.get_text() for a in fig.findobj(Text) if a.get_text().strip()]


def _lengths_in_metres(strings) -> list[str]:
    """Strings that give a length (a number, then m) or a mass in kg: none in a mm part's
    picture."""
    return [s for s in strings if re.search(rf"{NUMBER}\)? m\b(?!²)|\bkg\b|, m$", s)]


def test_the_check_picture_of_a_mm_part_reads_in_mm(part):
    fig = plot_check(check(part), part, units=MM)
    strings = _strings(fig)
    assert not _lengths_in_metres(strings), _lengths_in_metres(strings)
    summary = fig._suptitle.get_text()
    assert "margin 10 mm" in summary and "height of G 30 mm" in summary
    assert "G (20, 10, 30) mm" in summary
    assert "foot of G: stands, margin 10 mm" in strings
    assert "along the weakest way, toward −y →, mm" in strings and "z, mm" in strings
    plan = fig.axes[2]
    assert plan.get_xlabel() == "x, mm"
    # the ticks read in mm: the tick at 0.03 m is labelled 30 (without drawing the figure)
    assert plan.xaxis.get_major_formatter()(0.03, 0) == "30"
    assert fig.axes[1].yaxis.get_major_formatter()(0.06, 0) == "60"
    assert any("axes x, y, z, mm" in s for s in strings)


def test_the_check_picture_is_si_by_default(part):
    strings = _strings(plot_check(check(part), part))
    assert "foot of G: stands, margin 0.01 m" in strings
    assert "x, m" in strings


def test_the_mass_picture_gives_mass_and_inertia_in_g_and_g_mm2(part):
    strings = _strings(plot_body(part, units=MM))
    caption = next(s for s in strings if s.startswith("G = "))
    assert caption == ("G = (20, 10, 30) mm, mass 59.52 g, principal moments "
                       "(9920, 19840, 25792) g·mm²")
    assert not _lengths_in_metres(strings)
    assert {"x, mm", "z, mm", "y, mm"} <= set(strings)
    si = _strings(plot_body(part))
    caption = next(s for s in si if s.startswith("G = "))
    numbers = [float(x) for x in re.findall(NUMBER, caption.split("moments")[1])]
    assert numbers == pytest.approx([9.92e-6, 1.984e-5, 2.5792e-5], rel=1e-6)
    assert caption.endswith("kg·m²")


def test_the_pose_gallery_gives_each_height_of_g_in_mm(part):
    poses = resting_poses(part)
    fig = plot_poses(poses, units=MM)
    titles = [ax.get_title() for ax in fig.axes if ax.get_gid() == "pose"]
    heights = sorted({float(re.search(rf"G at ({NUMBER}) mm", t).group(1)) for t in titles})
    assert heights == pytest.approx([10, 20, 30])  # half of each side it can stand on
    assert not _lengths_in_metres(_strings(fig))


def test_the_lift_picture_gives_datum_height_and_mass_in_the_report_units(part):
    lift = lift_energy(part)
    strings = _strings(plot_lift(lift, part, units=MM))
    assert "ground datum, 0 mm" in strings and "z_G − datum = 30 mm" in strings
    assert any(s.endswith("(mass 59.52 g)") for s in strings)
    assert not _lengths_in_metres(strings)


def test_plot_on_the_command_line_follows_the_part_units_and_report_units(tmp_path, capsys,
                                                                          part):
    """The CLI passes the text report's units: natural (mm for --units mm), or asked."""
    from plumbob.cli import main
    from plumbob.formats.writers import stl_bytes
    from plumbob.plot import files

    stl = tmp_path / "box.stl"
    stl.write_bytes(stl_bytes(part.surface().triangles, "box", 1e-3))  # in mm, no unit inside
    drawn = {}

    def keep(fig, path, dpi=150):
        drawn[path] = _strings(fig)

    original = files.save_figure
    files.save_figure = keep
    try:
        for units in ([], ["--report-units", "in,lb"]):
            out = str(tmp_path / f"lift{len(units)}.png")
            assert main(["lift", str(stl), "--units", "mm", "--material", "pla", "--plot", out,
                         *units]) == 0
    finally:
        files.save_figure = original
    capsys.readouterr()
    assert "z_G − datum = 30 mm" in drawn[str(tmp_path / "lift0.png")]
    inches = drawn[str(tmp_path / "lift2.png")]
    assert f"z_G − datum = {0.03 / 0.0254:.4g} in" in inches
    assert any(s.endswith(f"(mass {0.05952 / 0.45359237:.4g} lb)") for s in inches)
    assert np.isclose(0.03 / 0.0254, 1.181, rtol=1e-3)



@pytest.mark.parametrize("picture", ["check in mm", "mass of an assembly", "lift in mm"])
def test_nothing_covers_anything_in_mm_pictures_and_the_mass_and_lift_pictures(part, picture):
    """The overlap measure of test_plot_check_truth on what it did not cover: a mm part's
    check picture (longer labels, scaled ticks) and the mass and lift pictures (legend,
    caption, the centre's label)."""
    from conftest import SHAPES
    from test_plot_check_truth import _covered, _cut_off

    import plumbob

    if picture == "check in mm":
        fig = plot_check(check(part), part, units=MM)
    elif picture == "mass of an assembly":
        fig = plot_body(plumbob.load(f"{SHAPES}/mace_assembly.toml"))
    else:
        fig = plot_lift(lift_energy(part), part, units=MM)
    assert _covered(fig) == [] and _cut_off(fig) == []


def test_an_inch_part_has_its_ticks_at_round_inches(part):
    """Ticks at round numbers of the unit drawn in, not at round metres relabelled
    (0.787402 in): the ticks of the plan and the side view step by 1, 2, 2.5 or 5 times a
    power of ten inches, from a multiple of the step, and the 3-D view's labels are
    short."""
    inch = ReportUnits("in", "lb")
    fig = plot_check(check(part), part, units=inch)
    for ax in (fig.axes[1], fig.axes[2]):
        for axis in (ax.xaxis, ax.yaxis):
            values = np.array(axis.get_major_locator()()) / 0.0254
            step = float(np.diff(values).mean())
            mantissa = step / 10 ** np.floor(np.log10(step))
            assert len(values) >= 3 and min(abs(mantissa - m) for m in (1, 2, 2.5, 5)) < 1e-9
            assert np.allclose(values / step, np.round(values / step)), values
    labels = [fig.axes[0].xaxis.get_major_formatter()(v, 0)
              for v in fig.axes[0].xaxis.get_major_locator()()]
    assert all(len(label) <= 5 for label in labels), labels
