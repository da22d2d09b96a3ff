"""The target rows against plumbob's own verdict: the tilt rows vanish at the critical
tilt, the margin rows at the margin, and adding a particle moves the centre exactly as
the linear condition says."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from plumbob.balance import target_for
from plumbob.bodies.csg import Assembly
from plumbob.bodies.particles import ParticleSystem
from plumbob.bodies.primitives import box, cylinder, polygon, pyramid
from plumbob.errors import StabilityError
from plumbob.loading import read
from plumbob.stability import check

BODIES = {
    "block": lambda: box(1, 1, 4, density=1000.0),
    "lying block": lambda: box(1, 1, 4).translated([0.3, -0.2, 0.1]),
    "cylinder": lambda: cylinder(0.4, 1.5),
    "pyramid": lambda: pyramid([[0, 0], [2, 0], [1.5, 1], [-0.2, 1.2]], 1.3, apex=[1.9, 1.1]),
    "sculpture (lamina)": lambda: read("shapes/sculpture.toml").body,
}


@pytest.mark.parametrize("name", sorted(BODIES))
def test_tilt_rows_vanish_at_the_critical_tilt(name):
    body = BODIES[name]()
    v = check(body)
    assert v.verdict == "stands"
    t = target_for(body, require_tilt_deg=v.critical_tilt_deg)
    slack = t.slack(v.center_of_mass)
    size = body.size
    assert slack.min() == pytest.approx(0.0, abs=1e-9 * size)
    assert set(t.kinds) == {"tilt"}
    # a little more tilt is not met, a little less is
    more = target_for(body, require_tilt_deg=v.critical_tilt_deg + 0.01)
    less = target_for(body, require_tilt_deg=v.critical_tilt_deg - 0.01)
    assert not more.met_by(v.center_of_mass) and less.met_by(v.center_of_mass)


@pytest.mark.parametrize("name", sorted(BODIES))
def test_margin_rows_vanish_at_the_margin(name):
    body = BODIES[name]()
    v = check(body)
    t = target_for(body, margin=v.margin)
    assert t.slack(v.center_of_mass).min() == pytest.approx(0.0, abs=1e-9 * body.size)
    # margin 0: the rows are the edge distances themselves
    zero = target_for(body)
    np.testing.assert_allclose(np.sort(zero.slack(v.center_of_mass)),
                               np.sort(v.support.edge_distances), atol=1e-12 * body.size)


def test_both_targets_stack_rows():
    t = target_for(box(1, 1, 4), margin=0.1, require_tilt_deg=float(np.degrees(0.1)))
    assert t.normals.shape == (8, 3) and t.kinds.count("margin") == 4


@given(st.floats(0.05, 0.95), st.floats(0.05, 0.95), st.floats(0.1, 3.9),
       st.floats(1.0, 5000.0), st.floats(0.0, 0.4))
def test_linear_condition_matches_the_check_with_a_particle(x, y, z, m, theta):
    """M·slack(c) + m·slack(p) has the sign of the combined body's own tilt margin."""
    body = box(1, 1, 4, density=1000.0)
    props = body.mass_properties()
    t = target_for(body, require_tilt_deg=float(np.degrees(theta)))
    p = np.array([x, y, z])
    combined_slack = props.mass * t.slack(props.center_of_mass) + m * t.slack(p)
    both = Assembly((body, ParticleSystem([m], [p])))
    v = check(both)
    tan_critical = np.tan(np.radians(v.critical_tilt_deg))
    # row-wise: d_e − tanθ·h at the combined centre, times the total mass
    expected = (props.mass + m) * (np.sort(v.support.edge_distances)[0]
                                    - np.tan(theta) * v.com_height)
    assert combined_slack.min() == pytest.approx(expected, abs=1e-9 * (props.mass + m))
    assert (combined_slack.min() >= 0) == (tan_critical >= np.tan(theta) - 1e-12)


def test_a_point_support_has_no_target():
    with pytest.raises(StabilityError, match="single point"):
        target_for(box(1, 1, 4), down=[0.1, 0.2, -1])


def test_bad_target_values():
    with pytest.raises(StabilityError, match="margin"):
        target_for(box(1, 1, 1), margin=-1)
    with pytest.raises(StabilityError, match="tilt"):
        target_for(box(1, 1, 1), require_tilt_deg=float(np.degrees(2.0)))


def test_lamina_rows_are_in_its_plane():
    body = polygon([[0, 0], [2, 0], [2, 1], [0, 1]])
    t = target_for(body, margin=0.25)
    assert t.normals.shape == (2, 2)
    assert t.slack(np.array([1.0, 0.5])).tolist() == pytest.approx([0.75, 0.75])


@pytest.mark.parametrize("toward_deg", [0, 40, 100, 200, 300])
def test_tilt_toward_one_way_matches_the_slope_check(toward_deg):
    """Toward one direction the rows vanish at the slope check's tipping angle."""
    body = BODIES["pyramid"]()
    slope = check(body, tilt_deg=1, toward_deg=toward_deg).slope
    limit = np.radians(slope.tipping_angle_deg)
    t = target_for(body, require_tilt_deg=float(np.degrees(limit)), toward=slope.direction)
    tilt_rows = np.array([k == "tilt" for k in t.kinds])
    c = body.mass_properties().center_of_mass
    assert t.slack(c)[tilt_rows].min() == pytest.approx(0.0, abs=1e-12 * body.size)
    assert t.slack(c)[~tilt_rows].min() > 0  # and it stands on level ground
    steeper = float(np.degrees(limit + 1e-4))
    assert not target_for(body, require_tilt_deg=steeper, toward=slope.direction).met_by(c)


def test_a_target_no_ballast_can_reach_is_a_failed_requirement(capsys, shapes_dir):
    """docs/cli.md: exit status 1 when `balance` is not met (a design target the means
    given cannot reach), 2 only for bad input; one line, nothing on standard output."""
    import os

    from plumbob.cli import main

    path = os.path.join(shapes_dir, "block.toml")
    status = main(["balance", path, "--require-tilt", "89", "--ballast-material", "steel"])
    out, err = capsys.readouterr()
    lines = [line for line in err.splitlines() if not line.startswith("plumbob: note")]
    assert status == 1 and out == "" and len(lines) == 1
    assert "no ballast inside the body meets the target" in lines[0]
    assert main(["balance", path, "--require-tilt", "10", "--ballast-material", "unobtainium"]
                ) == 2  # bad input stays 2
