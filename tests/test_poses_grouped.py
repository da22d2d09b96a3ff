"""Tracing only the boundaries between poses (stability/poses/landscape.py and basins.py):
a rolling family's basins are traced as one, and the poses are those of the trace of
every basin."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from test_poses_fans import solid_points

from plumbob.stability.poses import basins, landscape, poses_from_points

manifold3d = pytest.importorskip("manifold3d", reason="the test meshes are built by manifold3d")
m3 = manifold3d.Manifold


def capsule(segments: int):
    return m3.cylinder(3.0, 1.0, 1.0, segments) + m3.sphere(1.0, segments) + m3.sphere(
        1.0, segments).translate([0, 0, 3.0])


def poses_both_ways(X: np.ndarray, center: np.ndarray, monkeypatch) -> tuple:
    """The poses with rolling families traced as one, and with every basin traced, and
    how many trace steps each took."""
    steps = []
    real = basins.step

    def counting(*args):
        steps.append(1)
        return real(*args)

    monkeypatch.setattr(basins, "step", counting)
    grouped = poses_from_points(X, center)
    grouped_steps = len(steps)
    every = landscape.landscape3
    monkeypatch.setattr(landscape, "landscape3",
                        lambda X, tol, samples, families_of=None, surface=None:
                        every(X, tol, samples, None, surface))
    from plumbob.stability.poses import resting

    monkeypatch.setattr(resting, "landscape3", landscape.landscape3)
    steps.clear()
    single = poses_from_points(X, center)
    return grouped, grouped_steps, single, len(steps)


def same_poses(a, b) -> None:
    """The same poses; the probabilities to round-off: the two ways sum the spherical
    triangles of different boundaries (a family's outline, or every member's), and
    their round-off reaches a few 1e-12 on a 47-gon frustum."""
    assert [p.kind for p in a] == [p.kind for p in b]
    assert np.allclose(a.probabilities, b.probabilities, rtol=0, atol=1e-10)
    for p, q in zip(a, b):
        assert p.members == q.members and p.com_height == pytest.approx(q.com_height, rel=1e-12)
        assert p.critical_tilt_deg == pytest.approx(q.critical_tilt_deg, rel=1e-9, abs=1e-12)


def test_a_capsule_is_traced_not_at_all(monkeypatch):
    X, center = solid_points(capsule(96))
    grouped, grouped_steps, single, single_steps = poses_both_ways(X, center, monkeypatch)
    assert [p.kind for p in grouped] == ["rolling"] and grouped.probabilities[0] == 1.0
    same_poses(grouped, single)
    assert grouped_steps == 0 < single_steps


@pytest.mark.parametrize("shape", ["cylinder", "cone", "frustum_off_centre", "box_and_rod"])
def test_rolling_families_traced_as_one_give_the_same_poses(shape, monkeypatch):
    body = {"cylinder": m3.cylinder(4.0, 1.0, 1.0, 64),
            "cone": m3.cylinder(3.0, 1.0, 0.0, 80),
            "frustum_off_centre": m3.cylinder(2.0, 1.5, 0.7, 72).translate([0.3, 0, 0]),
            "box_and_rod": m3.cube([2, 2, 2], center=True)
            + m3.cylinder(6.0, 0.4, 0.4, 48).rotate([90, 0, 0]).translate([0, 3, 0])}[shape]
    X, center = solid_points(body)
    grouped, grouped_steps, single, single_steps = poses_both_ways(X, center, monkeypatch)
    assert "rolling" in [p.kind for p in grouped] or shape == "box_and_rod"
    same_poses(grouped, single)
    assert grouped_steps <= single_steps
    assert sum(grouped.probabilities) == pytest.approx(1.0, abs=1e-12)


@settings(max_examples=10, deadline=None)
@given(st.integers(24, 120), st.floats(0.5, 4.0), st.floats(0.0, 1.0), st.floats(-0.4, 0.4))
@example(47, 1.2734375, 0.404296875, 0.0)  # the probabilities differ by 3e-12 (round-off)
def test_traced_as_one_anywhere(segments, height, top, shift):
    """Frusta of any proportions, centre of mass moved off the axis by a point mass."""
    X, center = solid_points(m3.cylinder(height, 1.0, top, segments))
    center = center + [shift, 0.0, 0.0]
    with pytest.MonkeyPatch.context() as monkeypatch:  # no function fixture under given
        grouped, _, single, _ = poses_both_ways(X, center, monkeypatch)
    same_poses(grouped, single)
