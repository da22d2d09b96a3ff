"""The roll on the Gauss map (stability/poses/rolling.py): its segment minimum, and rolls
that pass exactly through a face's normal (symmetric bodies)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_poses_fans import boss_points

from plumbob.arrays import group_first
from plumbob.stability.poses import basins, poses_from_points
from plumbob.stability.poses.hull import build_hull3
from plumbob.stability.poses.rolling import first_least_sorted


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 6), st.sampled_from([0.0, 1.0, 2.5, -1.0, np.inf])),
                max_size=40))
def test_first_least_sorted_is_group_first(pairs):
    pairs.sort(key=lambda kv: kv[0])
    rows = np.array([k for k, _ in pairs], dtype=np.int64)
    values = np.array([v for _, v in pairs], dtype=float)
    got = first_least_sorted(rows, values, 7)
    want = group_first(rows, values, 7) if len(rows) else np.full(7, -1)
    # group_first gives an all-infinite group its first member; here such a group has none
    finite = np.array([np.isfinite(values[rows == g]).any() for g in range(7)])
    assert np.array_equal(got, np.where(finite, want, -1))
    lone = values[rows == 0]  # one group alone (a lone trace: its own path)
    got = first_least_sorted(np.zeros(len(lone), dtype=np.int64), lone, 1)
    assert np.array_equal(got, first_least_sorted(np.zeros(len(lone), dtype=np.int64),
                                                  lone, 2)[:1])


def test_a_roll_through_a_face_normal_lands_on_that_face():
    """A box with a low boss on its symmetry plane: slanted faces pivot about corners whose
    rolls run exactly through the boss cap's normal. They used to be lost there (every
    nudge of the centre too), and the poses failed as a 'degenerate hull'."""
    X, center = boss_points(116, (0.0, 0.5), 2.0)
    poses = poses_from_points(X, center)
    assert poses.method == "exact" and len(poses) == 6
    X = X - center
    size = float(np.linalg.norm(np.ptp(X, axis=0)))
    hull = build_hull3(X, 1e-12 * size)
    exact = basins.basins3(hull, 1e-12 * size, None)
    sampled = basins.basins3(hull, 1e-12 * size, 400_000)
    assert exact is not None
    assert np.allclose(exact.area, sampled.area, rtol=0, atol=2e-3 * 4 * np.pi)
    assert exact.area.sum() == pytest.approx(4 * np.pi, rel=1e-12)
