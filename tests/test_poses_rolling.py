"""The roll on the Gauss map (stability/poses/rolling.py): its segment minimum, and rolls
that pass exactly through a face's normal (symmetric bodies)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_poses_fans import boss_points

from plumbob import blockwise
from plumbob.arrays import cross, dot, group_first, unit
from plumbob.stability.poses import basins, poses_from_points
from plumbob.stability.poses.hull import build_hull3
from plumbob.stability.poses.rolling import Roller, edge_geometry, first_least_sorted


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


def _row_geometry(h):
    """The edge geometry by the row formulas (whole rows, no blocks, no columns)."""
    A, D = h.X[h.ea], h.X[h.eb] - h.X[h.ea]
    L2 = dot(D, D)
    t = -dot(A, D) / L2
    L = np.sqrt(L2)
    n = h.normals[h.ef]
    foot = h.heights[h.ef][:, None] * n
    rel = foot - A
    inset = dot(cross(D, rel), n) / L
    tau = np.clip(dot(rel, D) / L2, 0.0, 1.0)
    off = tau[:, None] * D + A - foot
    along, tol = tau * L, 1e-9  # the roller's below
    return (D / L[:, None], t, inset, np.sqrt(dot(off, off)), (along > tol) & (along < L - tol),
            along <= tol)


@pytest.mark.parametrize("seed", [0, 1])
def test_edge_geometry_and_roller_are_the_row_formulas_bit_for_bit(seed, monkeypatch):
    """The columns edge_geometry computes on (in blocks, in threads) give the row formulas'
    bits, and the roller's chains over edges (jumped only where a face rolls over an edge)
    end where jumping every face ends."""
    monkeypatch.setattr(blockwise, "BLOCK_ROWS", 1000)  # several blocks, in threads
    monkeypatch.setattr(blockwise, "MIN_THREADED_ROWS", 2000)
    rng = np.random.default_rng(seed)
    u = unit(rng.normal(size=(1500, 3)))  # an egg-like ellipsoid: every point a vertex
    X = u * [1.0, 0.7, 0.5] * (1 + 0.1 * u[:, :1]) + [0.1, -0.05, 0.02]
    h = build_hull3(X, 1e-12 * 4)
    eg3 = edge_geometry(h, 1e-9)
    assert len(h.ea) > 4 * blockwise.BLOCK_ROWS and eg3.saddle.any()
    for got, want in zip((eg3.pole, eg3.t, eg3.inset, eg3.tip_distance, eg3.tip_inside,
                          eg3.tip_at_a), _row_geometry(h)):
        assert np.array_equal(got, want)
    roller = Roller(h, eg3, unit(h.X), 1e-9)
    over = np.where(roller.stable | roller.pivots, np.arange(len(h.normals)),
                    h.eg[roller.tip_edge])
    while not np.array_equal(over[over], over):
        over = over[over]
    assert np.array_equal(roller.lands, over)
    assert (roller.lands != np.arange(len(h.normals))).any()  # some roll over edges


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
