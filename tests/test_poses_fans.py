"""Runs of a separatrix around a many-cornered face (stability/poses/fans.py): the same
basin areas as the step-by-step trace, in far fewer Python steps."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.stability.poses import basins
from plumbob.stability.poses.fans import prefix_products
from plumbob.stability.poses.hull import build_hull3

manifold3d = pytest.importorskip("manifold3d", reason="the test meshes are built by manifold3d")


def boss_points(segments: int, offset: tuple[float, float], height: float = 10.0,
                radius: float = 8.0) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and centre of mass of a 40 × 30 × 20 box with a cylinder boss of
    ``segments`` sides standing ``height`` above it, its axis at ``offset`` (x, y) from
    the box's."""
    m3 = manifold3d.Manifold
    body = m3.cube([40, 30, 20], center=True) + m3.cylinder(
        10 + height, radius, radius, segments).translate([offset[0], offset[1], 0])
    return solid_points(body)


def solid_points(body) -> tuple[np.ndarray, np.ndarray]:
    """A manifold's vertices and its centre of mass (uniform density), the latter by the
    divergence theorem over its triangles."""
    mesh = body.to_mesh()
    X = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    a, b, c = (X[np.asarray(mesh.tri_verts)[:, k]] for k in range(3))
    six_v = np.einsum("ij,ij->i", a, np.cross(b, c))
    return X, (six_v[:, None] * (a + b + c)).sum(axis=0) / (4 * six_v.sum())


def traced(X: np.ndarray, center: np.ndarray, monkeypatch, fans: bool, strips: bool | None = None
           ) -> tuple[np.ndarray, int]:
    """Basin areas of the hull of ``X`` about ``center``, and the number of Python-level
    steps the trace took; ``fans`` False forces the step-by-step trace (no runs around
    rings, nor along strips unless ``strips`` says so)."""
    strips = fans if strips is None else strips
    calls = []
    real = basins.step

    def counting(*args):
        calls.append(1)
        return real(*args)

    with monkeypatch.context() as patch:
        patch.setattr(basins, "step", counting)
        if not fans:
            patch.setattr(basins, "FAN_CORNERS", 10**9)
        if not strips:
            patch.setattr(basins, "_STRIP_AFTER", 10**9)
        X = X - center
        size = float(np.linalg.norm(np.ptp(X, axis=0)))
        found = basins.basins3(build_hull3(X, 1e-12 * size), 1e-12 * size, None)
    assert found is not None, "the exact trace failed"
    return found.area, len(calls)


def test_prefix_products_are_the_running_products():
    rng = np.random.default_rng(1)
    M = rng.normal(size=(37, 3, 3))
    Q = prefix_products(M)
    running = np.eye(3)
    for j in range(len(M)):
        running = M[j] @ running
        scale = Q[j].ravel() @ running.ravel() / (Q[j].ravel() @ Q[j].ravel())
        assert scale > 0  # scaled by a positive factor only: directions keep their sign
        assert np.allclose(Q[j] * scale, running, rtol=1e-10, atol=1e-12 * np.abs(running).max())


@pytest.mark.parametrize("segments", [48, 400, 2000])
def test_boss_cap_runs_agree_with_single_steps(segments, monkeypatch):
    X, center = boss_points(segments, (5.0, 0.0))
    with_fans, steps = traced(X, center, monkeypatch, fans=True)
    single, single_steps = traced(X, center, monkeypatch, fans=False)
    assert np.allclose(with_fans, single, rtol=0, atol=1e-13 * 4 * np.pi)
    assert abs(with_fans.sum() - 4 * np.pi) <= 1e-12 * 4 * np.pi
    if segments >= 400:  # the traces round the cap's ring in runs, not one step a corner
        assert single_steps > segments / 4
        assert steps < single_steps / 10


def test_coin_both_rims(monkeypatch):
    """A short cylinder off centre of mass (a point mass sets the centre): both caps are
    rings, and every saddle's trace runs around one."""
    m3 = manifold3d.Manifold
    X, _ = solid_points(m3.cylinder(3, 20, 20, 1500))
    center = np.array([4.0, 1.0, 1.1])  # off the axis and below mid-height
    with_fans, steps = traced(X, center, monkeypatch, fans=True)
    single, single_steps = traced(X, center, monkeypatch, fans=False)
    assert np.allclose(with_fans, single, rtol=0, atol=1e-13 * 4 * np.pi)
    assert steps < single_steps


@settings(max_examples=12, deadline=None)
@given(st.integers(24, 300), st.floats(-9.0, 9.0), st.floats(-5.0, 5.0), st.floats(2.0, 30.0))
def test_runs_agree_with_single_steps_anywhere(segments, x, y, height):
    X, center = boss_points(segments, (x, y), height)
    with pytest.MonkeyPatch.context() as monkeypatch:  # no function fixture under given
        with_fans, _ = traced(X, center, monkeypatch, fans=True)
        single, _ = traced(X, center, monkeypatch, fans=False)
    assert np.allclose(with_fans, single, rtol=0, atol=1e-12 * 4 * np.pi)


def tilted_cylinder_points(segments: int, tilt: float, turn: float, offset: tuple[float, float]
                           ) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and centre of mass of a 40 × 30 × 20 box united with a Ø14 cylinder through
    it, tilted ``tilt`` degrees from the vertical (bench/_shapes.py's smooth mesh): its
    side is a strip of thin faces, not a ring."""
    m3 = manifold3d.Manifold
    cylinder = (m3.cylinder(44, 7, 7, segments, center=True)
                .rotate([tilt, 0, turn]).translate([offset[0], offset[1], 6]))
    return solid_points(m3.cube([40, 30, 20], center=True) + cylinder)


def test_strip_runs_agree_with_single_steps(monkeypatch):
    """Along the tilted cylinder's side the separatrices cross thin regions of few
    corners: runs along the predicted strip, checked by the ordinary step, take most of
    the steps out and leave the areas as they were."""
    X, center = tilted_cylinder_points(600, 27.0, 40.0, (2.0, -1.0))
    with_strips, steps = traced(X, center, monkeypatch, fans=True)
    rings_only, ring_steps = traced(X, center, monkeypatch, fans=True, strips=False)
    single, _ = traced(X, center, monkeypatch, fans=False)
    assert np.allclose(with_strips, single, rtol=0, atol=1e-13 * 4 * np.pi)
    assert np.allclose(rings_only, single, rtol=0, atol=1e-13 * 4 * np.pi)
    assert abs(with_strips.sum() - 4 * np.pi) <= 1e-12 * 4 * np.pi
    assert ring_steps > 150  # the strip: the rings' runs never start on it
    assert steps < ring_steps / 3


@settings(max_examples=8, deadline=None)
@given(st.integers(40, 400), st.floats(5.0, 60.0), st.floats(0.0, 360.0),
       st.floats(-6.0, 6.0), st.floats(-6.0, 6.0))
def test_strip_runs_agree_anywhere(segments, tilt, turn, x, y):
    X, center = tilted_cylinder_points(segments, tilt, turn, (x, y))
    with pytest.MonkeyPatch.context() as monkeypatch:  # no function fixture under given
        with_strips, _ = traced(X, center, monkeypatch, fans=True)
        single, _ = traced(X, center, monkeypatch, fans=False)
    assert np.allclose(with_strips, single, rtol=0, atol=1e-12 * 4 * np.pi)
