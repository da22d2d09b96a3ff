"""Applied loads against hand calculations: moments about the tipping edge, the factor
of safety against overturning, the worst points, and bad input."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.bodies.csg import Assembly
from plumbob.bodies.primitives import box, rectangle
from plumbob.cli import main
from plumbob.errors import StabilityError
from plumbob.loading import read
from plumbob.loads import Force, Hang, Press, Push
from plumbob.stability import check

G = 9.81
REL = 1e-9
# the box: 1 m along x, 0.5 m along y, 2 m high, 100 kg; weight W, centre 0.5 m from the x
# edges and 0.25 m from the y edges
L, B, H, M = 1.0, 0.5, 2.0, 100.0
W = M * G


def block(offset=(0.0, 0.0, 0.0)):
    return box(L, B, H, density=M / (L * B * H)).translated(offset)


def _status(argv) -> int:
    """The exit status of the command line (argparse's refusals exit)."""
    try:
        return main(argv)
    except SystemExit as exit:
        return int(exit.code)


def close(a, b, rel=REL):
    return math.isclose(a, b, rel_tol=rel, abs_tol=rel * max(abs(b), 1.0))


@pytest.mark.parametrize("offset", [(0.0, 0.0, 0.0), (1e4, -3e3, 250.0)])
@pytest.mark.parametrize("height", [0.4, 1.0, 1.7, 2.0])
def test_a_push_at_a_height_topples_it_above_w_d_over_f(offset, height):
    """Pushed along +x with F at height h, it tips over the edge x = L when F h > W d,
    d = L/2: the factor of safety W d / (F h); the same far from the origin."""
    force = 300.0
    o = np.array(offset)
    v = check(block(offset), loads=[Force([force, 0, 0], o + [0, B / 2, height])])
    lv = v.loaded
    assert np.allclose(lv.edge_normal, [1, 0, 0])
    assert close(lv.resisting_moment, W * L / 2)
    assert close(lv.overturning_moment, force * height)
    assert close(lv.overturning_safety_factor, W * (L / 2) / (force * height))
    assert close(lv.overturning_safety_factor, lv.resisting_moment / lv.overturning_moment)
    threshold = W * (L / 2) / force  # 1.635 m
    assert lv.verdict == ("stands" if height < threshold else "topples")
    assert lv.stands is (height < threshold)


def test_the_threshold_height_itself_is_the_balance():
    force = 300.0
    h = W * (L / 2) / force
    lv = check(block(), loads=[Force([force, 0, 0], [0, B / 2, h])]).loaded
    assert close(lv.overturning_safety_factor, 1.0) and lv.verdict == "neutral"
    assert close(lv.load_factor, 1.0)


def test_a_weight_hung_beyond_its_front():
    """m kg hung e beyond the edge x = L: overturning m g e, resisting W L/2."""
    m, e = 20.0, 0.3
    lv = check(block(), loads=[Hang(m, [L + e, B / 2, 1.0])]).loaded
    assert close(lv.overturning_moment, m * G * e)
    assert close(lv.resisting_moment, W * L / 2)
    assert close(lv.overturning_safety_factor, W * L / 2 / (m * G * e))
    assert lv.moments[1].outside and any("outside the body" in n for n in lv.notes)
    heavy = check(block(), loads=[Hang(200.0, [L + e, B / 2, 1.0])]).loaded
    assert heavy.verdict == "topples" and close(heavy.overturning_safety_factor,
                                                W * L / 2 / (200 * G * e))


def test_a_push_and_a_hung_weight_at_once():
    f, h, m, e = 150.0, 1.2, 30.0, 0.2
    v = check(block(), loads=[Force([f, 0, 0], [0, 0.1, h]), Hang(m, [L + e, 0.4, 0.5])])
    lv = v.loaded
    assert close(lv.overturning_moment, f * h + m * G * e)
    assert close(lv.resisting_moment, W * L / 2)
    assert close(lv.overturning_safety_factor, W * L / 2 / (f * h + m * G * e))
    assert [r.kind for r in lv.moments] == ["weight", "force", "hang"]
    assert close(sum(r.moment for r in lv.moments),
                 lv.overturning_moment - lv.resisting_moment)
    assert close(lv.normal_force, W + m * G) and close(lv.tangential_force, f)
    assert v.meets_requirement is lv.stands


def test_loads_from_a_spec_in_its_own_unit(tmp_path):
    spec = tmp_path / "pushed.toml"
    spec.write_text("""
[shape]
units = "cm"
[[part]]
type = "box"
length = 100
width = 50
height = 200
density = 100
[[load]]
name = "lean"
force = [300, 0, 0]
at = [0, 25, 120]
[[load]]
mass = 20
at = [130, 25, 100]
""")
    reading = read(str(spec))
    assert [type(x).__name__ for x in reading.loads] == ["Force", "Hang"]
    lv = check(reading.body, loads=reading.loads).loaded
    assert close(lv.overturning_moment, 300 * 1.2 + 20 * G * 0.3)
    assert close(lv.overturning_safety_factor, W * 0.5 / (300 * 1.2 + 20 * G * 0.3))
    assert lv.moments[1].name == "lean"


def test_the_worst_push_and_press_are_found_exactly():
    """A push of F no higher than h0 goes at h0 over the narrow way (d = B/2); with no limit
    at the top. A press on a shelf reaching e beyond the base's edge gives F e."""
    f = 100.0
    lv = check(block(), loads=[Push(f, 1.5)]).loaded
    assert close(lv.overturning_moment, f * 1.5) and close(lv.resisting_moment, W * B / 2)
    assert abs(abs(lv.edge_normal[1]) - 1) < 1e-12 and close(lv.moments[1].at[2], 1.5)
    top = check(block(), loads=[Push(f)]).loaded
    assert close(top.overturning_moment, f * H)
    shelf = box(0.6, B, 0.05, density=100.0).translated([L, 0, 1.0])  # 0.6 m beyond x = L
    body = Assembly((block(), shelf))
    v = check(body, loads=[Press(200.0)])
    lv = v.loaded
    assert np.allclose(lv.edge_normal, [1, 0, 0])
    assert close(lv.moments[1].moment, 200.0 * 0.6) and close(lv.moments[1].at[0], L + 0.6)
    wm = v.mass * G * (v.center_of_mass[0] - L)
    assert close(lv.moments[0].moment, wm)


@settings(max_examples=40, deadline=None)
@given(fx=st.floats(-500, 500), fy=st.floats(-500, 500), fz=st.floats(-400, 400),
       x=st.floats(0, L), y=st.floats(0, B), z=st.floats(0, H))
def test_the_factor_is_resisting_over_overturning_and_decides(fx, fy, fz, x, y, z):
    lv = check(block(), loads=[Force([fx, fy, fz], [x, y, z])]).loaded
    if lv.verdict == "lifts":
        return
    if lv.overturning_safety_factor is None:  # nothing overturns (or too little to divide by)
        assert lv.overturning_moment < 1e-300 * lv.resisting_moment + 1e-300 and lv.stands
        return
    assert close(lv.overturning_safety_factor, lv.resisting_moment / lv.overturning_moment)
    if lv.overturning_safety_factor > 1 + 1e-6:
        assert lv.verdict == "stands"
    elif lv.overturning_safety_factor < 1 - 1e-6:
        assert lv.verdict == "topples"


def test_a_tilted_floor_leans_the_weight_and_the_hung_mass():
    """Floor tilted θ toward +x: about the edge x = L the weight's moment is
    W (h sinθ − d cosθ), a hung mass's m g (z sinθ + e cosθ)."""
    theta, m, e, z = 5.0, 10.0, 0.1, 1.5
    t = math.radians(theta)
    lv = check(block(), tilt_deg=theta, toward_deg=0, loads=[Hang(m, [L + e, B / 2, z])]).loaded
    assert np.allclose(lv.edge_normal, [1, 0, 0]) and np.allclose(lv.tilt_direction, [1, 0, 0])
    assert close(lv.moments[0].moment, W * (H / 2 * math.sin(t) - L / 2 * math.cos(t)))
    assert close(lv.moments[1].moment, m * G * (z * math.sin(t) + e * math.cos(t)))


def test_with_friction_it_slides_before_it_tips():
    f, h = 300.0, 1.0
    low = check(block(), friction=0.2, loads=[Force([f, 0, 0], [0, B / 2, h])]).loaded
    assert low.slides and low.slides_first and low.verdict == "slides"
    grip = check(block(), friction=0.8, loads=[Force([f, 0, 0], [0, B / 2, h])]).loaded
    assert not grip.slides and not grip.slides_first and grip.verdict == "stands"


def test_a_lamina_takes_loads_in_its_plane():
    plate = rectangle(1.0, 2.0, density=50.0)  # 100 kg
    lv = check(plate, loads=[Force([300, 0], [0, 1.0])]).loaded
    assert close(lv.overturning_moment, 300.0) and close(lv.resisting_moment, W * 0.5)
    with pytest.raises(StabilityError, match="given in 3D but the body is a lamina"):
        check(plate, loads=[Force([300, 0, 0], [0, 1.0, 0])])


@pytest.mark.parametrize("option, value, words", [
    ("--force", "1,2,nan@0,0,0", "finite"),
    ("--force", "1,2,inf@0,0,0", "finite"),
    ("--force", "1,2,3@0,0", "3 components but the point 2"),
    ("--force", "1,2,3@0,0,0,0", "expected 2 or 3 numbers"),
    ("--force", "1,2,3", "an @ before the point"),
    ("--hang", "-1@0,0,0", "≥ 0 kg"),
    ("--hang", "5", "an @ before the point"),
    ("--force", "1,2@0,0", "given in 2D but the body is a solid"),
])
def test_bad_loads_are_one_line_and_status_2(capsys, option, value, words):
    path = os.path.join(os.path.dirname(__file__), "..", "shapes", "cabinet.toml")
    assert _status(["check", path, f"{option}={value}"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and words in err and "Traceback" not in err


@pytest.mark.parametrize("table, words", [
    ("force = [1, 0, 0]\nmass = 2\nat = [0, 0, 0]", "not force and mass"),
    ("mass = -2\nat = [0, 0, 0]", "≥ 0 kg"),
    ("force = [1, 0, 0]", "needs at ="),
    ("force = [1, 0, 0]\nat = [0, 0]", "expected 3 components"),
    ("force = [1, 0, 0]\nat = [0, 0, 0]\ncolour = 1", "unknown key 'colour'"),
])
def test_bad_load_tables_name_the_table(tmp_path, capsys, table, words):
    spec = tmp_path / "bad.toml"
    spec.write_text(f'[[part]]\ntype = "box"\nlength = 1\nwidth = 1\nheight = 1\n'
                    f"[[load]]\n{table}\n")
    assert _status(["check", str(spec)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "load[1]" in err and words in err


def test_check_json_and_exit_status_under_loads(capsys):
    path = os.path.join(os.path.dirname(__file__), "..", "shapes", "cabinet.toml")
    import json

    assert main(["check", path, "--json", "--hang=1@0.3,-0.05,1.0"]) == 0
    out = json.loads(capsys.readouterr().out)
    ul = out["under_loads"]
    assert ul["verdict"] == "stands" and ul["overturning_safety_factor"] > 1
    assert close(ul["overturning_safety_factor"], ul["resisting_moment"] / ul["overturning_moment"])
    assert main(["check", path, "--json", "--hang=100@0.3,-0.3,1.0"]) == 1
    assert json.loads(capsys.readouterr().out)["under_loads"]["verdict"] == "topples"


def test_the_picture_draws_the_loads_and_the_critical_edge():
    pytest.importorskip("matplotlib")
    v = check(block(), loads=[Force([300, 0, 0], [0, B / 2, 1.7]), Hang(10.0, [L + 0.2, B / 2, 1])])
    fig = v.plot(body=block())
    edges = [line for ax in fig.axes for line in ax.get_lines() if line.get_gid() == "critical edge"]
    assert len(edges) == 1 and np.allclose(edges[0].get_xdata(), [L, L])
    texts = " ".join(t.get_text() for ax in fig.axes for t in ax.texts)
    assert "force: 300 N, 510 N·m" in texts and "under the loads: topples" in fig._suptitle.get_text()
