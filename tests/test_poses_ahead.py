"""Rolls run ahead (stability/poses/ahead.py, ``Roller.ahead``): the moves the last few
rolls make (across regions, over faces and corners), predicted in plain Python and checked
by one vectorised step, end every roll on the face the step-by-step roll ends on, in far
fewer Python steps."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from plumbob.arrays import unit
from plumbob.stability.poses import rolling
from plumbob.stability.poses.hull import build_hull3

manifold3d = pytest.importorskip("manifold3d", reason="the test meshes are built by manifold3d")


def solid_points(body) -> tuple[np.ndarray, np.ndarray]:
    """A manifold's vertices and its centre of mass (uniform density)."""
    mesh = body.to_mesh64()
    X = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    a, b, c = (X[np.asarray(mesh.tri_verts, dtype=np.int64).reshape(-1, 3)[:, k]]
               for k in range(3))
    six_v = np.einsum("ij,ij->i", a, np.cross(b, c))
    return X, (six_v[:, None] * (a + b + c)).sum(axis=0) / (4 * six_v.sum())


def lumpy(segments: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """A smooth lumpy blob (a warped sphere): its rolls cross hundreds of thin regions."""
    rng = np.random.default_rng(seed)
    k = unit(rng.normal(size=(3, 3)))
    amp = rng.uniform(0.05, 0.15, 3)

    def warp(p):
        d = np.asarray(p) / np.linalg.norm(p)
        r = 1.0 + float(np.sum(amp * np.cos(3.0 * np.arccos(np.clip(k @ d, -1, 1)))))
        return tuple(d * r * np.array([1.0, 0.8, 0.6]))

    return solid_points(manifold3d.Manifold.sphere(1.0, segments).warp(warp))


def tilted_cylinder(segments: int, tilt: float, turn: float) -> tuple[np.ndarray, np.ndarray]:
    """A box united with a tilted cylinder (bench/_shapes.py's smooth mesh)."""
    m3 = manifold3d.Manifold
    cylinder = m3.cylinder(44, 7, 7, segments, center=True).rotate([tilt, 0, turn])
    return solid_points(m3.cube([40, 30, 20], center=True) + cylinder.translate([2, -1, 6]))


def rolled(X: np.ndarray, center: np.ndarray, faces: int, runs: bool, seed: int = 0
           ) -> tuple[np.ndarray, int]:
    """Where rolls from ``faces`` faces of the hull (spread by ``seed``) end, and how many
    vectorised steps the loop took: with runs ahead for every roll in a region (however
    many), or none."""
    X = X - center
    eps = 1e-12 * float(np.linalg.norm(np.ptp(X, axis=0)))
    h = build_hull3(X, eps)
    roller = rolling.Roller(h, rolling.edge_geometry(h, eps), unit(h.X), eps)
    start = np.random.default_rng(seed).choice(len(h.normals), faces, replace=False)
    calls, inside = [], []
    real_step, real_ahead = rolling.step, rolling.Roller.ahead

    def counting(*args):
        calls.append(not inside)  # the loop's own steps, not a run's checks
        return real_step(*args)

    def ahead(self, *args):
        inside.append(1)
        try:
            return real_ahead(self, *args)
        finally:
            inside.pop()

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(rolling, "step", counting)
        patch.setattr(rolling.Roller, "ahead", ahead)
        patch.setattr(rolling, "_RUN_FEW", 10**9 if runs else 0)
        ends = roller.roll(face=start)
    return ends, sum(calls)


@pytest.mark.parametrize("make", [lambda: lumpy(160, 1), lambda: tilted_cylinder(600, 27.0, 40.0)],
                         ids=["lumpy blob", "box + tilted cylinder"])
def test_runs_end_where_single_steps_end(make):
    X, center = make()
    ahead, steps = rolled(X, center, 40, runs=True)
    single, single_steps = rolled(X, center, 40, runs=False)
    assert np.all(single >= 0) and np.array_equal(ahead, single)
    assert single_steps > 30 and steps < single_steps / 2  # long rolls, run ahead


@settings(max_examples=6, deadline=None)
@given(st.integers(40, 400), st.floats(5.0, 60.0), st.floats(0.0, 360.0), st.integers(0, 99))
def test_runs_end_where_single_steps_end_anywhere(segments, tilt, turn, seed):
    X, center = tilted_cylinder(segments, tilt, turn)
    ahead, _ = rolled(X, center, 20, runs=True, seed=seed)
    single, _ = rolled(X, center, 20, runs=False, seed=seed)
    assert np.array_equal(ahead, single)


def traced(X: np.ndarray, center: np.ndarray, ahead: bool) -> tuple[np.ndarray, int]:
    """Basin areas of the hull of ``X`` about ``center`` and the trace's loop steps, with
    the last few separatrices run ahead (Fans.climbs) or not (fans as they are)."""
    from plumbob.stability.poses import basins

    X = X - center
    eps = 1e-12 * float(np.linalg.norm(np.ptp(X, axis=0)))
    calls = []
    real = basins.step

    def counting(*args):
        calls.append(1)
        return real(*args)

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(basins, "step", counting)
        patch.setattr(basins, "_AHEAD_FEW", basins._AHEAD_FEW if ahead else -1)
        patch.setattr(basins, "_STRIP_FEW", basins._STRIP_FEW if ahead else -1)
        found = basins.basins3(build_hull3(X, eps), eps, None)
    assert found is not None, "the exact trace failed"
    return found.area, len(calls)


@pytest.mark.parametrize("make", [lambda: lumpy(160, 2), lambda: tilted_cylinder(600, 45.0, 200.0)],
                         ids=["lumpy blob", "box + tilted cylinder"])
def test_lone_separatrices_run_ahead_to_the_same_areas(make):
    """One or two separatrices left: their crossings predicted in plain Python and checked
    by the ordinary step (Fans.climbs), the same basin areas to round-off."""
    X, center = make()
    ahead, steps = traced(X, center, ahead=True)
    single, single_steps = traced(X, center, ahead=False)
    assert np.allclose(ahead, single, rtol=0, atol=1e-13 * 4 * np.pi)
    assert abs(ahead.sum() - 4 * np.pi) <= 1e-12 * 4 * np.pi
    assert steps < single_steps


def test_the_sign_test_predicts_the_steps_crossings():
    """ahead.climb's exit (the one arc whose ends lie on opposite sides of the great
    circle toward w) and its crossing point (the linear map of the point it came in at)
    are the ordinary step's own, crossing after crossing, on every separatrix of a lumpy
    blob: the runs ahead are checked by the step, but a predictor that seldom agreed
    would make them useless."""
    from plumbob.arrays import dot
    from plumbob.stability.poses.ahead import climb, scalars

    X, center = lumpy(120, 3)
    X = X - center
    eps = 1e-12 * float(np.linalg.norm(np.ptp(X, axis=0)))
    h = build_hull3(X, eps)
    eg3 = rolling.edge_geometry(h, eps)
    W = unit(h.X)
    near = eg3.t < -1e-12
    sad = eg3.saddles[h.ea[eg3.saddles] < h.eb[eg3.saddles]]
    s = scalars(h, eg3, W, near)
    crossings = 0
    for start in (h.ea[sad], h.eb[sad]):
        for v0, edge, p0 in zip(start.tolist(), sad.tolist(), eg3.spoint[eg3.saddle_rows(sad)]):
            edges, points = climb(s, v0, *p0.tolist(), int(h.und[edge]), 400)
            if not edges:
                continue
            q = np.array(points).reshape(-1, 3)
            starts = np.concatenate((p0[None, :], q[:-1]))
            vs = h.ea[np.array(edges)]  # each region's vertex: its exit edge's start
            assert vs[0] == v0 and np.array_equal(vs[1:], h.eb[np.array(edges[:-1])])
            w = W[vs]
            wp = dot(starts, w)
            before = np.concatenate(([h.und[edge]], h.und[np.array(edges[:-1], dtype=np.int64)]))
            e, stepped = rolling.step(h, eg3, vs, starts, unit(w - wp[:, None] * starts),
                                      np.arccos(np.clip(wp, -1.0, 1.0)), before, near,
                                      np.full(len(vs), -1))
            assert np.array_equal(e, edges)
            assert np.abs(stepped - q).max() <= 1e-12
            crossings += len(edges)
    assert crossings > 20 * len(sad)  # long separatrices, all of them predicted
