"""The lamina's planar hull (stability/planar.py) against scipy's qhull, and the
start-up of ``plumbob poses`` on a lamina (no scipy)."""

from __future__ import annotations

import os

import numpy as np
import pytest
from conftest import ROOT
from hypothesis import example, given, settings
from hypothesis import strategies as st
from scipy.spatial import ConvexHull
from test_startup import imported

from plumbob.errors import GeometryError
from plumbob.stability.planar import planar_hull


def signed_area(P: np.ndarray) -> float:
    """Shoelace, about the first corner (exact far from the origin too)."""
    P = P - P[0]
    return 0.5 * float(np.sum(P[:, 0] * np.roll(P[:, 1], -1) - np.roll(P[:, 0], -1) * P[:, 1]))


def clouds():
    rng = np.random.default_rng(7)
    for n in (3, 10, 200, 5000):
        yield "normal", rng.normal(size=(n, 2)) * [3.0, 0.5]
    t = rng.uniform(0, 2 * np.pi, 500)
    yield "circle", np.c_[np.cos(t), np.sin(t)]
    yield "grid", rng.integers(0, 5, size=(300, 2)).astype(float)  # ties and collinear runs
    yield "far", rng.normal(size=(300, 2)) + 1e6


@pytest.mark.parametrize("name, X", list(clouds()), ids=[c[0] + str(len(c[1])) for c in clouds()])
def test_planar_hull_is_qhulls(name, X):
    corners = planar_hull(X)
    qh = ConvexHull(X - X[0])  # qhull's volume is about the origin: local coordinates
    P = X[corners]
    assert signed_area(P) > 0  # counter-clockwise
    assert signed_area(P) == pytest.approx(qh.volume, rel=1e-12)
    assert set(map(tuple, P)) == set(map(tuple, X[qh.vertices]))  # the same input points
    assert len(set(corners.tolist())) == len(corners)


def test_degenerate_points_are_refused():
    for X in ([[0, 0], [1, 1]], [[0, 0], [1, 1], [2, 2], [3, 3]], [[1, 2]] * 5):
        with pytest.raises(GeometryError, match="span no area"):
            planar_hull(np.array(X, dtype=float))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.integers(-6, 6), st.integers(-6, 6)), min_size=3, max_size=60),
       st.floats(0, 2 * np.pi), st.floats(-1e3, 1e3))
# rows of collinear points turned: round-off put a point of the row "outside" an edge
# past whose end it lay, and the hull folded back along the row (a random run found it)
@example([(0, 0), (0, 1), (1, 1), (-2, 1), (4, 1)], 2.908203125, 0.0)
@example([(6, 6), (3, 3), (4, 4), (-1, -1), (2, 2), (1, 1), (6, 5), (-5, -5), (-6, -6)],
         3.2861226487291444, 0.0)
def test_hull_moves_with_the_points(raw, angle, shift):
    """Rotating and shifting the points moves the hull with them: same area, and every
    point inside or on it."""
    X = np.array(raw, dtype=float)
    if abs(np.linalg.matrix_rank(X[1:] - X[0])) < 2:
        with pytest.raises(GeometryError):
            planar_hull(X)
        return
    c, s = np.cos(angle), np.sin(angle)
    Y = X @ np.array([[c, s], [-s, c]]) + shift
    a, b = signed_area(X[planar_hull(X)]), signed_area(Y[planar_hull(Y)])
    assert b == pytest.approx(a, rel=1e-9)
    P = Y[planar_hull(Y)]
    d = np.roll(P, -1, axis=0) - P
    cross = d[:, 0][:, None] * (Y[:, 1] - P[:, 1][:, None]) - d[:, 1][:, None] * (
        Y[:, 0] - P[:, 0][:, None])
    assert cross.min() >= -1e-9 * (1 + abs(shift)) ** 2


def test_lamina_poses_import_no_scipy():
    names = imported("poses", os.path.join(ROOT, "shapes", "l_shape.toml"))
    assert not [n for n in names if n.split(".")[0] == "scipy"]
