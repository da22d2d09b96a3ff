"""The check picture tells the truth at a glance: a rose for every kind of support, the
side view across the weakest way, one frame per figure, nothing covering anything, and
every part of an assembly told apart. Checked by what is drawn and where (artists and
their data, rendered boxes of text), not by pixels."""

import itertools
import os

import matplotlib
import numpy as np
import pytest
from conftest import SHAPES

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.text import Annotation, Text  # noqa: E402

import plumbob  # noqa: E402
from plumbob.bodies import primitives as P  # noqa: E402
from plumbob.bodies.csg import Assembly  # noqa: E402
from plumbob.plot import plot_check  # noqa: E402
from plumbob.plot.rose import rose_samples  # noqa: E402
from plumbob.stability import check, resting_poses  # noqa: E402


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _shape(name: str):
    return plumbob.load(os.path.join(SHAPES, f"{name}.toml"))


# ------------------------------------------------------------------ rendered boxes
def _drawn(fig) -> list[tuple[str, object, bool]]:
    """(name, window box, is words) of every text, legend, marked point and the weakest
    way's arrow that is drawn."""
    fig.canvas.draw()
    fig.canvas.draw()  # constrained layout settles on the second pass
    renderer = fig.canvas.get_renderer()
    items = []

    def add(name, artist, words=True):
        if artist is None or not artist.get_visible():
            return
        if isinstance(artist, Text) and not artist.get_text().strip():
            return
        box = (Text.get_window_extent(artist, renderer) if isinstance(artist, Annotation)
               else artist.get_window_extent(renderer))  # an annotation's words, not its arrow
        if box.width > 0 and box.height > 0:
            items.append((name, box, words))

    add("suptitle", fig._suptitle)
    for t in fig.texts:
        if t is not fig._suptitle:
            add(f"figure text {t.get_text()[:30]!r}", t)
    for i, ax in enumerate(fig.axes):
        tag = f"panel {i}"
        add(f"{tag} title", ax.title)
        for axis in [ax.xaxis, ax.yaxis] + ([ax.zaxis] if hasattr(ax, "zaxis") else []):
            add(f"{tag} {axis.axis_name} label", axis.label)
            lo, hi = sorted(axis.get_view_interval())
            for tick in axis.get_major_ticks():
                if lo - 1e-9 * (hi - lo) <= tick.get_loc() <= hi + 1e-9 * (hi - lo):
                    for label in (tick.label1, tick.label2):
                        add(f"{tag} tick {label.get_text()!r}", label)
        for t in ax.texts:
            add(f"{tag} text {t.get_text()!r}", t)
            if t.get_gid() == "weakest way":
                items.append((f"{tag} arrow", t.arrow_patch.get_window_extent(renderer), False))
        add(f"{tag} legend", ax.get_legend())
        for line in ax.lines:
            if line.get_gid() in ("foot", "centre of mass", "critical"):
                add(f"{tag} {line.get_gid()} marker", line, words=False)
    return items


def _covered(fig) -> list[tuple[str, str]]:
    """Pairs of drawn things that overlap, at least one of them words."""
    pad = 0.5  # pixels: boxes that only touch do not cover
    out = []
    for (a, p, wa), (b, q, wb) in itertools.combinations(_drawn(fig), 2):
        if (wa or wb) and (p.x0 + pad < q.x1 - pad and q.x0 + pad < p.x1 - pad
                           and p.y0 + pad < q.y1 - pad and q.y0 + pad < p.y1 - pad):
            out.append((a, b))
    return out


def _cut_off(fig) -> list[str]:
    page = fig.bbox
    return [name for name, box, words in _drawn(fig) if words and (
        box.x0 < page.x0 - 0.5 or box.y0 < page.y0 - 0.5 or box.x1 > page.x1 + 0.5
        or box.y1 > page.y1 + 0.5)]


CASES = [("cabinet", {}), ("cabinet", {"require_tilt_deg": 10}), ("stepped_cylinder", {}),
         ("mace_assembly", {}), ("block", {"down": [1, 0, -1]}), ("sculpture", {}),
         ("pyramid_cheops", {"pose": 2}), ("triangle", {})]


@pytest.mark.parametrize(("name", "options"), CASES,
                         ids=[f"{n}-{'-'.join(map(str, o.values())) or 'default'}"
                              for n, o in CASES])
def test_nothing_covers_anything(name, options):
    body = _shape(name)
    options = dict(options)
    if "pose" in options:
        options["down"] = resting_poses(body)[options.pop("pose") - 1].down
    fig = plot_check(check(body, **options), body, path=f"{name}.toml")
    assert _covered(fig) == []
    assert _cut_off(fig) == []


def test_the_overlap_test_sees_an_overlap():
    """The measure itself: two words drawn on one spot are caught."""
    fig = plot_check(check(P.box(1, 1, 4)), P.box(1, 1, 4))
    plan = fig.axes[2]
    plan.text(0.5, 0.5, "over the foot", transform=plan.transData, fontsize="large")
    (foot,) = [ln for ln in plan.lines if ln.get_gid() == "foot"]
    x, y = foot.get_xydata()[0]
    plan.text(x, y, "on the foot", ha="center", va="center")
    assert any("on the foot" in a or "on the foot" in b for a, b in _covered(fig))


# ------------------------------------------------------------------ the rose
def test_the_rose_of_a_line_contact_is_its_tipping_over_the_ends():
    """The stepped cylinder (a = 1) on its side touches along x from 2 to 4 under its centre
    at x = 2.8, height 3: tilted toward φ from +x it tips over the far end at
    atan(1.2 / (3 cos φ)) (toward −x, atan(0.8 / (3 |cos φ|))); straight across it only
    rolls (90°). The report's 14.9° and 21.8° are the rose's extremes along x."""
    v = check(_shape("stepped_cylinder"))
    angles, tilts = rose_samples(v)
    cos = np.cos(angles)
    with np.errstate(divide="ignore"):
        reach = np.where(cos > 0, 1.2 / cos, np.where(cos < 0, 0.8 / -cos, np.inf))
    expected = np.degrees(np.arctan2(reach, 3.0))
    np.testing.assert_allclose(tilts, expected, rtol=0, atol=1e-9)
    assert tilts[0] == pytest.approx(21.801409486351815, abs=1e-9)
    assert tilts[180] == pytest.approx(14.931417178137552, abs=1e-9)
    fig = plot_check(v, _shape("stepped_cylinder"))
    rose = fig.axes[3]
    (line,) = [ln for ln in rose.lines if ln.get_label() == "critical tilt by direction"]
    np.testing.assert_allclose(line.get_ydata(), expected, atol=1e-9)
    labels = [t.get_text() for t in rose.get_legend().get_texts()]
    assert "rolls across its line at any tilt" in labels


def test_the_rose_of_a_point_contact():
    """A ball rolls every way (0° all round, and the legend says so); a hemisphere on its
    dome rocks back: its rose is the rocker's tilt each way (about 22.5°), the same all round
    (a body of revolution)."""
    ball = check(P.sphere(1.0))
    _, tilts = rose_samples(ball)
    assert np.all(tilts == 0.0)
    rose = plot_check(ball, P.sphere(1.0)).axes[3]
    assert "rolls every way at any tilt" in [t.get_text() for t in rose.get_legend().get_texts()]
    dome = check(P.hemisphere(1.0), [0, 0, 1])
    _, tilts = rose_samples(dome)
    assert dome.verdict == "stands" and tilts.min() > 15.0
    assert np.ptp(tilts) < 2.0  # the rocker's tilt, sampled in 24 ways


# ------------------------------------------------------------------ the side view
def test_the_side_view_looks_across_the_weakest_way():
    """The cabinet is weakest toward −y (its open drawer): the side view runs along −y,
    says so on its axis, and shows the drawer's overhang beyond the support as far as the
    body reaches that way."""
    body = _shape("cabinet")
    v = check(body)
    assert np.allclose(v.critical_direction, [0, -1, 0], atol=1e-12)
    side = plot_check(v, body).axes[1]
    assert "toward −y" in side.get_xlabel() and "toward −y" in side.get_title()
    drawn = np.concatenate([c.get_paths()[k].vertices for c in side.collections
                            if c.get_gid() == "body" for k in range(len(c.get_paths()))])
    reach = body.hull_points() @ v.critical_direction
    assert drawn[:, 0].max() == pytest.approx(reach.max(), abs=1e-9)
    assert drawn[:, 0].min() == pytest.approx(reach.min(), abs=1e-9)
    support = v.support.polygon @ v.critical_direction
    assert drawn[:, 0].max() > support.max() + 0.2  # the drawer, 0.3 m out, is in view


# ------------------------------------------------------------------ one frame
def test_one_frame_per_figure_in_a_pose():
    """The 1 × 1 × 4 block in its second pose, on a long side: every panel, the rose's
    directions and G in the title are in the placed pose's e1, e2, up."""
    body = _shape("block")
    pose = resting_poses(body)[1]
    v = check(body, pose.down)
    fig = plot_check(v, body)
    rows = np.vstack((v.support.frame.axes, -v.down))
    g = rows @ v.center_of_mass
    title = fig._suptitle.get_text()
    assert "G (e1, e2, up) (" + ", ".join(f"{c:.4g}" for c in g) + ") m" in title
    ax3d, side, plan, rose = fig.axes
    assert "e1, e2, up" in ax3d.get_title()
    assert side.get_ylabel() == "up, m"
    assert (plan.get_xlabel(), plan.get_ylabel()) == ("e1, m", "e2, m")
    ticks = [t.get_text() for t in rose.get_xticklabels()]
    assert ticks == ["toward +e1", "+e2", "−e1", "−e2"]
    assert not any(c in "".join(ticks) for c in "xyz")
    # the default orientation is the body's own frame, named so
    upright = plot_check(check(body), body)
    assert [t.get_text() for t in upright.axes[3].get_xticklabels()] == [
        "toward +x", "+y", "−x", "−y"]


# ------------------------------------------------------------------ assemblies
def test_parts_of_one_material_are_told_apart():
    """Two oak legs and an oak top: three colours, one legend entry per part (named)."""
    oak = 750.0
    legs = [P.box(0.1, 0.1, 1.0, density=oak, name="leg").translated([x, 0, 0])
            for x in (0.0, 0.9)]
    top = P.box(1.0, 0.3, 0.1, density=oak, name="top").translated([0, -0.1, 1.0])
    body = Assembly((legs[0], legs[1], top), name="bench")
    side = plot_check(check(body), body).axes[1]
    colours = [tuple(np.round(c.get_facecolor()[0], 6)) for c in side.collections
               if c.get_gid() == "body"]
    assert len(colours) == 3 and len(set(colours)) == 3
    entries = [t.get_text() for t in side.get_legend().get_texts()]
    parts = [e for e in entries if "kg/m³" in e]
    assert parts == ["leg 1 (750 kg/m³)", "leg 2 (750 kg/m³)", "top (750 kg/m³)"]
