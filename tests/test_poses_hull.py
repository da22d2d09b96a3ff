"""The hull behind the poses (stability/poses/convex.py): manifold3d's quickhull checked
against scipy's qhull, the numpy planar hull against qhull's, the fallback, and the
start-up of ``plumbob poses`` (no scipy import)."""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest
from conftest import ROOT
from scipy.spatial import ConvexHull

from plumbob.bodies.primitives import box
from plumbob.errors import GeometryError
from plumbob.stability.poses import convex, poses_from_points
from plumbob.stability.poses.convex import half_edge_twins, hull_triangles


def hull_volume(P: np.ndarray, tri: np.ndarray) -> float:
    """Divergence theorem over the triangles."""
    a, b, c = P[tri[:, 0]], P[tri[:, 1]], P[tri[:, 2]]
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6)


@pytest.mark.parametrize("seed", range(6))
def test_quickhull_is_qhulls_hull(seed):
    rng = np.random.default_rng(seed)
    X = rng.normal(size=(400, 3)) * [1.0, 2.0, 0.5]
    if seed % 2:  # rounded to a grid: many coplanar and duplicate points
        X = np.round(X * 4) / 4
    P, tri, normals, offsets, twins = hull_triangles(X, 1e-12 * np.ptp(X))
    qh = ConvexHull(X)
    assert hull_volume(P, tri) == pytest.approx(qh.volume, rel=1e-12)
    assert np.array_equal(twins, half_edge_twins(tri, len(P)))  # closed, and paired right
    # every input point under every facet plane, to rounding error
    assert (X @ normals.T - offsets).max() <= 1e-12 * np.ptp(X)
    # the corners are qhull's vertices (points on an edge or inside a face are not)
    mine = {tuple(p) for p in P[np.unique(tri)]}
    assert {tuple(p) for p in X[qh.vertices]} <= mine


def test_the_qhull_fallback_gives_the_same_poses(monkeypatch):
    rng = np.random.default_rng(3)
    X = rng.normal(size=(60, 3))
    com = X.mean(axis=0)
    fast = poses_from_points(X, com)
    monkeypatch.setattr(convex, "_manifold_hull", lambda X, eps: None)
    slow = poses_from_points(X, com)
    assert np.allclose(fast.probabilities, slow.probabilities, rtol=0, atol=1e-12)
    assert fast.hull_faces == slow.hull_faces


def test_flat_points_are_a_geometry_error():
    flat = np.random.default_rng(0).normal(size=(20, 3)) * [1, 1, 0]
    with pytest.raises(GeometryError, match="flat"):
        hull_triangles(flat, 1e-12)


def test_a_fine_float32_circle_needs_no_qhull(monkeypatch):
    """A 20 000-sided prism stored as float32: qhull takes seconds on its nearly
    co-circular points; the quickhull answer passes its checks."""
    def refuse(X):
        raise AssertionError("qhull was asked")

    monkeypatch.setattr(convex, "_qhull", refuse)
    t = np.linspace(0, 2 * np.pi, 20_000, endpoint=False)
    ring = np.stack((np.cos(t), np.sin(t)), axis=1) * 0.008
    X = np.concatenate((np.c_[ring, np.zeros(len(t))], np.c_[ring, np.full(len(t), 0.03)]))
    X = X.astype(np.float32).astype(float)
    P, tri, *_ = hull_triangles(X - X.mean(axis=0), 1e-12 * 0.03)
    assert hull_volume(P, tri) == pytest.approx(np.pi * 0.008 ** 2 * 0.03, rel=1e-6)




def test_poses_start_up_imports_no_scipy(tmp_path):
    body = box(1, 2, 3)
    records = np.zeros(len(body.triangles), dtype=[("n", "<f4", 3), ("t", "<f4", (3, 3)),
                                                    ("a", "<u2")])
    records["t"] = body.triangles
    path = tmp_path / "box.stl"
    with open(path, "wb") as handle:
        handle.write(b"box".ljust(80) + np.uint32(len(records)).tobytes())
        records.tofile(handle)
    code = ("import sys; from plumbob.cli import main; "
            f"status = main(['poses', {str(path)!r}, '--units', 'm']); "
            "print(status, sorted(m for m in sys.modules if m.split('.')[0] == 'scipy'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env=dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src")),
                         check=True).stdout
    assert out.strip().splitlines()[-1] == "0 []"
