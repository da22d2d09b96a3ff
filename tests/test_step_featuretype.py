"""A real CAD file: trimesh's ``featuretype.STEP`` (SolidWorks 2013, inches) against the
STL SolidWorks exported of the same part (``featuretype.STL``, trimesh's test models).

The B-rep's volume, centre and inertia must agree with the STL's (trimesh's mass
properties) to within what the STL's faceting allows: each STL triangle lies within
its measured chord deviation ``d`` of the B-rep, so the solids differ by at most
``Σ area·d`` in volume (and that weighted by the distance from the centre, or its
square, in first and second moments). The STEP's own stated error must be far
tighter than that."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("OCP", reason="the plumbob[cad] extra (cadquery-ocp-novtk)")

from plumbob.formats import step as S  # noqa: E402
from plumbob.formats import step_worker  # noqa: E402

DATA = Path(__file__).parent / "data" / "trimesh_models"
STEP, STL = DATA / "featuretype.STEP", DATA / "featuretype.STL"
INCH = 0.0254


def test_the_solidworks_file_declares_inches_despite_its_metre_conversion_bases():
    # SolidWorks defines its inch as 0.0254 of an SI metre unit of its own: the
    # coordinates are in the unit the representation context names, the inch
    assert S.step_unit(str(STEP)) == "in"


@pytest.fixture(scope="module")
def both():
    trimesh = pytest.importorskip("trimesh")
    result = step_worker.read(str(STEP), S.DEVIATION)  # the child's reader, in this process
    assert "parts" in result, result
    step = S._reading(str(STEP), result["parts"], 1e-3, (), "in").body  # OpenCASCADE: mm
    stl = trimesh.load(str(STL), process=True)
    stl.apply_scale(INCH)
    return step, stl


def _distances(points: np.ndarray, triangles: np.ndarray, reach: float) -> np.ndarray:
    """The distance from each point (n, 3) to the nearest triangle (m, 3, 3), exact where
    it is under ``reach``, else inf: a grid of cells ``2 reach`` wide lists every triangle
    whose box widened by ``reach`` meets each cell, so a point's own cell lists every
    triangle within ``reach`` of it."""
    from plumbob.bodies.distance import point_triangle_distances

    side = 2 * reach
    origin = np.minimum(points.min(axis=0), triangles.min(axis=(0, 1))) - reach
    lo = np.floor((triangles.min(axis=1) - reach - origin) / side).astype(np.int64)
    hi = np.floor((triangles.max(axis=1) + reach - origin) / side).astype(np.int64)
    span = hi - lo + 1
    count = span.prod(axis=1)
    owner = np.repeat(np.arange(len(triangles)), count)
    k = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    sx, sy = span[owner, 0], span[owner, 1]
    cells = np.stack([lo[owner, 0] + k % sx, lo[owner, 1] + k // sx % sy,
                      lo[owner, 2] + k // (sx * sy)], axis=1)
    wide = int(max(cells.max(), 1)) + 2

    def key(ijk):
        return (ijk[:, 0] * wide + ijk[:, 1]) * wide + ijk[:, 2]

    cell_key = key(cells)
    order = np.argsort(cell_key, kind="stable")
    cell_key, owner = cell_key[order], owner[order]
    point_key = key(np.floor((points - origin) / side).astype(np.int64))
    first = np.searchsorted(cell_key, point_key, "left")
    n = np.searchsorted(cell_key, point_key, "right") - first
    which = np.repeat(np.arange(len(points)), n)
    candidate = owner[np.repeat(first, n) + np.arange(n.sum()) - np.repeat(np.cumsum(n) - n, n)]
    best = np.full(len(points), np.inf)
    np.minimum.at(best, which, point_triangle_distances(points[which], triangles[candidate]))
    return np.where(best <= reach, best, np.inf)


def _chord_deviations(stl, step) -> np.ndarray:
    """Each STL triangle's distance from the B-rep (m): the largest over its centre and
    edge midpoints (where a chord sags most) of the distance to the B-rep's
    tessellation, plus that tessellation's own deviation from the B-rep."""
    tri = np.asarray(stl.triangles)
    points = np.concatenate([tri.mean(axis=1)[:, None], (tri + np.roll(tri, -1, axis=1)) / 2],
                            axis=1)  # (n, 4, 3)
    d = _distances(points.reshape(-1, 3), np.asarray(step.triangles), 0.02 * INCH)
    return d.reshape(len(tri), 4).max(axis=1) + step.deviation


def test_the_brep_agrees_with_the_stl_export_to_the_stl_faceting(both):
    step, stl = both
    props = step.mass_properties()  # no density given: 1 kg/m³, so mass = volume
    d = _chord_deviations(stl, step)
    area = stl.area_faces
    c = props.center_of_mass
    reach = np.linalg.norm(np.asarray(stl.triangles) - c, axis=2).max(axis=1) + d
    volume_bound = float(np.sum(area * d))  # m³
    moment_bound = float(np.sum(area * d * reach))  # m⁴, first moment about c
    second_bound = float(np.sum(area * d * reach**2))  # m⁵
    # the faceting: SolidWorks' chords sag up to ~0.009 in from its arcs
    assert 0.001 * INCH < d.max() < 0.02 * INCH
    assert abs(stl.volume - props.volume) <= volume_bound
    shift = np.linalg.norm(stl.center_mass - c)
    assert shift <= moment_bound / stl.volume
    inertia = np.asarray(stl.moment_inertia)  # trimesh: unit density, about its centre
    assert np.abs(inertia - props.inertia).max() <= second_bound + 2 * stl.volume * shift**2
    # the bounds are not vacuous: the differences are a sizeable part of them
    assert abs(stl.volume - props.volume) > 0.05 * volume_bound
    # the STEP's answer is far tighter than the STL's: its stated bound, and the
    # faceting's effect it is free of
    assert props.relative_error * props.volume < 1e-4 * volume_bound
    assert props.relative_error < 1e-6 * abs(stl.volume / props.volume - 1)


def test_the_tessellation_for_shape_questions_is_closed_and_near_the_stl(both):
    step, stl = both
    tess = np.asarray(step.triangles)
    # plumbob's own tessellation is far finer than SolidWorks' STL
    assert step.deviation < 0.001 * INCH
    lo, hi = tess.reshape(-1, 3).min(axis=0), tess.reshape(-1, 3).max(axis=0)
    assert np.allclose(lo, stl.bounds[0], atol=step.deviation * 2)
    assert np.allclose(hi, stl.bounds[1], atol=step.deviation * 2)
