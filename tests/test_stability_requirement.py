"""The Requirement value: checked once, the same verdict whichever way it is given."""

from __future__ import annotations

import math

import numpy as np
import pytest

from plumbob.bodies.primitives import box
from plumbob.errors import StabilityError
from plumbob.stability import check, resting_poses
from plumbob.stability.requirement import Requirement
from plumbob.stability.tipping import tipping_angle_deg


@pytest.mark.parametrize("changes, message", [
    (dict(g=0), "g must be"),
    (dict(tilt_deg=90), "a tilt must be between"),
    (dict(tilt_deg=float("nan")), "tilt_deg must be a finite"),
    (dict(friction=-0.1), "friction coefficient must be ≥ 0"),
    (dict(friction=float("inf")), "friction coefficient must be ≥ 0"),
    (dict(margin=-1), "margin must be"),
    (dict(require_tilt_deg=91), "require_tilt_deg must be from 0° to 90°"),
    (dict(down=[0, 0, 0, 1]), "down must be one vector"),
    (dict(loads=("push",)), "a load must be"),
])
def test_bad_requirements_are_refused_when_made(changes, message):
    with pytest.raises(StabilityError, match=message):
        Requirement(**changes)


def test_the_keywords_and_the_requirement_give_the_same_verdict():
    block = box(1, 1, 4, density=1000.0)
    keywords = check(block, [0, 0, -1], g=9.8, tilt_deg=5, toward_deg=30, friction=0.3,
                     require_tilt_deg=10, margin=0.4)
    req = Requirement([0, 0, -1], 9.8, 5, 30, 0.3, 0.4, 10)
    given = check(block, requirement=req)
    assert keywords.as_dict().keys() == given.as_dict().keys()
    assert given.passes is True and given.margin_passes is True and given.meets_requirement
    assert given.required_margin == 0.4 and given.g == 9.8 and given.friction == 0.3
    failing = check(block, margin=0.6)
    assert failing.margin_passes is False and failing.passes is None
    assert failing.meets_requirement is False
    with pytest.raises(StabilityError, match="not both"):
        check(block, [0, 0, -1], requirement=req)


def test_one_critical_tilt_for_the_verdict_and_the_poses():
    """atan(d/h) has one implementation: the verdict's critical tilt and the resting
    pose's agree to the last bit, and both equal the closed form."""
    block = box(1, 1, 4, density=1000.0)
    v = check(block)
    standing = next(p for p in resting_poses(block).poses if np.allclose(p.down, [0, 0, -1]))
    assert v.critical_tilt_deg == standing.critical_tilt_deg == tipping_angle_deg(0.5, 2.0)
    assert math.isclose(v.critical_tilt_deg, math.degrees(math.atan(0.25)), rel_tol=1e-15)
    assert [e.tipping_angle_deg for e in v.edges] == [v.critical_tilt_deg] * 4
