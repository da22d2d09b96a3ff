"""The bounding-box sweep that lists which parts may overlap: against all pairs."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from plumbob.bodies import primitives as P
from plumbob.bodies.overlaps import bounding_boxes, candidate_pairs, connected_groups, local_origin


def _all_pairs(boxes):
    n = len(boxes)
    return sorted((i, j) for i in range(n) for j in range(i + 1, n)
                  if np.all(boxes[i, 0] <= boxes[j, 1]) and np.all(boxes[j, 0] <= boxes[i, 1]))


@given(st.lists(st.tuples(st.integers(-20, 20), st.integers(-20, 20), st.integers(-20, 20),
                          st.integers(0, 6), st.integers(0, 6), st.integers(0, 6)),
                min_size=0, max_size=40))
def test_sweep_finds_exactly_the_pairs_whose_boxes_meet(rows):
    boxes = np.array([[[x, y, z], [x + a, y + b, z + c]] for x, y, z, a, b, c in rows],
                     dtype=float).reshape(-1, 2, 3)
    assert [tuple(p) for p in candidate_pairs(boxes).tolist()] == _all_pairs(boxes)


@pytest.mark.parametrize("body", [P.sphere(1.0), P.torus(2.0, 0.5), P.cylinder(1.0, 3.0),
                                  P.disc(2.0), P.semicircle(1.0)])
def test_a_curved_body_lies_inside_its_box(body):
    """The box from sampled hull points, widened, holds the true extreme points."""
    turned = body.transformed(np.linalg.qr(np.arange(body.dim**2).reshape(body.dim, -1)
                                           + np.eye(body.dim))[0])
    box = bounding_boxes([turned])[0]
    fine = turned.hull_points(1e-6 * turned.size)  # 100 times finer than the box's samples
    assert np.all(fine >= box[0]) and np.all(fine <= box[1])


def test_groups_join_through_chains():
    assert connected_groups(6, [(4, 5), (0, 2), (2, 4)]) == [[0, 2, 4, 5], [1], [3]]


def test_local_origin_only_far_away():
    near = np.array([[[0.0, 0, 0], [1, 1, 1]], [[2.0, 0, 0], [3, 1, 1]]])
    assert local_origin(near) is None
    assert local_origin(near + 1e6) == pytest.approx([1e6 + 1.5, 1e6 + 0.5, 1e6 + 0.5])
