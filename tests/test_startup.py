"""Start-up: what a command loads, judged in a real ``python -m plumbob`` process.

A whole ``plumbob poses part.stl`` takes ~0.12 s, of which python and numpy are
~0.09 s: every module loaded that the command does not use shows in that budget
(numpy.ma alone ~10 ms, the MuJoCo drops room and the verdict ~5 ms, tomllib and
difflib ~6 ms). ``python -X importtime`` names every module a process imports, so
these tests read it from the very command a user runs.
"""

from __future__ import annotations

import gc
import os
import re
import subprocess
import sys

import numpy as np
import pytest
from _batch_corpus import write_stl
from conftest import ROOT
from hypothesis import given
from hypothesis import strategies as st

import plumbob.stability as stability
from plumbob.arrays import unique
from plumbob.bodies.primitives import box, pyramid

#: Never needed by a command on a mesh: other commands' libraries, plots, the
#: MuJoCo drops, the outline and quadrature code, numpy's masked arrays and series.
NEVER = ("scipy", "shapely", "trimesh", "mujoco", "matplotlib", "plotly", "numpy.ma", "shutil",
         "numpy.polynomial", "tomllib", "difflib", "plumbob.stability.drops",
         "plumbob.bodies.region", "plumbob.bodies.tiling", "plumbob.bodies.containment",
         "plumbob.bodies.csg", "plumbob.bodies.profiled", "plumbob.integrals.polygon",
         "plumbob.integrals.cells", "plumbob.integrals.rules", "plumbob.spec", "plumbob.energy",
         "plumbob.batch", "plumbob.export", "plumbob.balance", "plumbob.dynamics")


def _gridded_box(k: int) -> np.ndarray:
    """A unit cube, each face cut into k × k squares of two triangles (12 k² triangles)."""
    t = np.linspace(0.0, 1.0, k + 1)
    u, v = np.meshgrid(t[:-1], t[:-1], indexing="ij")
    d = 1.0 / k
    quads = np.stack([np.stack((u, v), -1), np.stack((u + d, v), -1),
                      np.stack((u + d, v + d), -1), np.stack((u, v + d), -1)], axis=2)
    squares = quads.reshape(-1, 4, 2)
    faces = []
    for axis in range(3):
        for side in (0.0, 1.0):
            corners = np.insert(squares, axis, side, axis=2)
            if (side == 1.0) == (axis == 1):  # wound outward
                corners = corners[:, ::-1]
            faces.append(corners[:, [0, 1, 2]])
            faces.append(corners[:, [0, 2, 3]])
    return np.concatenate(faces)


def _rotated(triangles: np.ndarray, seed: int) -> np.ndarray:
    q, r = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    q *= np.sign(np.diag(r))
    return triangles @ (q if np.linalg.det(q) > 0 else -q).T


@pytest.fixture(scope="module")
def meshes(tmp_path_factory) -> dict[str, str]:
    """A 1×2×3 box turned at random, and a 48-sided pyramid (many small faces)."""
    folder = tmp_path_factory.mktemp("startup")
    angles = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    ring = np.stack((np.cos(angles), np.sin(angles)), axis=1)
    bodies = {"box": _rotated(box(1, 2, 3).triangles, 3),
              "pyramid": _rotated(pyramid(ring, 0.8).triangles, 4),
              "upright": box(1, 2, 3).triangles,
              "large": _gridded_box(66)}  # past mesh.FULL_CHECK_LIMIT
    paths = {}
    for name, triangles in bodies.items():
        paths[name] = str(folder / f"{name}.stl")
        write_stl(paths[name], triangles)
    return paths


def imported(*cli_args: str, env: dict[str, str] | None = None) -> set[str]:
    """The modules a ``python -m plumbob`` process imports (it must succeed), in this
    process's environment or ``env``."""
    result = subprocess.run([sys.executable, "-X", "importtime", "-m", "plumbob", *cli_args],
                            capture_output=True, text=True, timeout=120,
                            env=dict(os.environ if env is None else env,
                                     PYTHONPATH=os.path.join(ROOT, "src")))
    assert result.returncode == 0, result.stderr[-2000:]
    names = set(re.findall(r"^import time:\s+\d+ \|\s+\d+ \|\s+(\S+)$", result.stderr, re.M))
    assert "numpy" in names and "plumbob.cli" in names  # the report was read
    return names


def _loaded(names: set[str], prefixes) -> list[str]:
    return sorted(n for n in names if any(n == p or n.startswith(p + ".") for p in prefixes))


@pytest.mark.parametrize("body", ["box", "pyramid"])
@pytest.mark.parametrize("extra", [(), ("--json",)])
def test_poses_on_a_mesh_loads_only_what_it_uses(meshes, body, extra):
    names = imported("poses", meshes[body], "--units", "mm", *extra)
    assert not _loaded(names, NEVER + ("plumbob.stability.verdict", "plumbob.report" if extra
                                       else "plumbob.stability.drops", "plumbob.materials",
                                       "plumbob.stability.support", "plumbob.bodies.cells",
                                       "plumbob.stability.rocking_result",
                                       "plumbob.stability.frame", "plumbob.stability.planar")), body
    assert "manifold3d" in names  # the hull: the one heavy library poses needs
    assert ("json" in names) == bool(extra)
    assert "threading" not in names  # blockwise starts threads only for large arrays


def test_poses_on_a_large_mesh_builds_no_topology(meshes):
    """A mesh past the full check's size whose edges pair: its check and weld need neither
    the topology (a sort of every edge) nor the repair and shell code."""
    from plumbob.mesh import FULL_CHECK_LIMIT

    assert len(_gridded_box(66)) > FULL_CHECK_LIMIT
    names = imported("poses", meshes["large"], "--units", "mm")
    assert not _loaded(names, NEVER + ("plumbob.mesh.topology", "plumbob.mesh.repair",
                                       "plumbob.mesh.shells", "json"))
    assert "plumbob.mesh.solid" in names


@pytest.mark.parametrize("extra", [(), ("--json",)])
def test_mass_of_a_mesh_loads_only_numpy(meshes, extra):
    names = imported("mass", meshes["pyramid"], "--units", "mm", *extra)
    assert not _loaded(names, NEVER + ("manifold3d", "plumbob.stability", "plumbob.materials")), \
        extra  # the material table's module: only a --material (check_density is arguments')


def test_check_of_a_mesh_loads_neither_poses_nor_drops(meshes):
    """A mesh standing on a face: the verdict alone. (Turned at random, the box touches the
    ground at a corner, and check says where it settles: that needs the poses.)"""
    names = imported("check", meshes["upright"], "--units", "mm")
    assert not _loaded(names, ("plumbob.stability.poses", "plumbob.stability.drops", "mujoco",
                               "matplotlib", "trimesh", "shapely", "tomllib", "scipy"))
    names = imported("check", meshes["box"], "--units", "mm")
    assert "plumbob.stability.poses.settling" in names
    assert not _loaded(names, ("plumbob.stability.drops", "mujoco", "matplotlib", "trimesh"))


def test_threadpoolctl_loads_only_to_limit_threads_the_environment_asked_for(meshes):
    """The command's entry point has BLAS start on one thread (nothing asked in the
    environment), so it need not load threadpoolctl (~2 ms) to limit it; asked for 8,
    it does."""
    from plumbob.__main__ import BLAS_VARIABLES

    clean = {k: v for k, v in os.environ.items() if k not in BLAS_VARIABLES}
    assert "threadpoolctl" not in imported("poses", meshes["box"], "--units", "mm", env=clean)
    asked = dict(clean, OPENBLAS_NUM_THREADS="8")
    assert "threadpoolctl" in imported("poses", meshes["box"], "--units", "mm", env=asked)


def test_stability_names_load_on_first_use():
    """``plumbob.stability`` shows its public names as before, each loaded when asked."""
    assert set(stability.__all__) <= set(dir(stability))
    from plumbob.stability.drops import drop_poses
    from plumbob.stability.poses import resting_poses
    from plumbob.stability.verdict import check

    assert stability.drop_poses is drop_poses and stability.check is check
    assert stability.resting_poses is resting_poses
    for name in stability.__all__:
        assert getattr(stability, name) is not None
    with pytest.raises(AttributeError, match="no attribute 'no_such_name'"):
        stability.no_such_name  # noqa: B018
    assert not hasattr(stability, "__wrapped__")


def test_the_entry_point_resumes_the_collector(monkeypatch, capsys):
    """The console script pauses garbage collection only while the modules load."""
    from plumbob.__main__ import entry

    monkeypatch.setattr(sys, "argv", ["plumbob", "--version"])
    try:
        with pytest.raises(SystemExit) as stop:
            entry()
        assert stop.value.code == 0 and capsys.readouterr().out.startswith("plumbob ")
        assert gc.isenabled()
    finally:
        gc.unfreeze()  # give this test process's objects back to the collector


def test_the_entry_point_leaves_what_is_alive_frozen_for_the_exit(meshes, monkeypatch, capsys):
    """A command that returned: what is alive is frozen (the interpreter's exit need not
    scan it), the collector still on (its youngest generation collected less often), the
    status the command's."""
    from plumbob.__main__ import YOUNG_OBJECTS, entry

    monkeypatch.setattr(sys, "argv", ["plumbob", "mass", meshes["box"], "--units", "mm"])
    gc.unfreeze()
    threshold = gc.get_threshold()
    try:
        assert entry() == 0 and "mass" in capsys.readouterr().out
        assert gc.isenabled() and gc.get_freeze_count() > 0
        assert not gc.get_objects(generation=2)  # every survivor frozen, none left to scan
        assert gc.get_threshold() == (YOUNG_OBJECTS, *threshold[1:])
    finally:
        gc.unfreeze()
        gc.set_threshold(*threshold)


@given(st.lists(st.integers(-5, 5), max_size=30))
def test_unique_is_numpys_unique(values):
    array = np.array(values, dtype=np.int64)
    expect = np.unique(array)
    got = unique(array)
    assert got.dtype == expect.dtype and got.tolist() == expect.tolist()


def _checked_meshes():
    """Triangle soups for check_solid, with whether its vertices can be reused."""
    cube = box(1.0, 1.0, 1.0).triangles
    flipped = cube.copy()
    flipped[3] = flipped[3, ::-1]
    nudged = cube.copy()  # one corner copy 1e-12 m off: welded (a near copy, not exact)
    corner = np.all(nudged == nudged[0, 0], axis=-1)
    nudged[np.flatnonzero(corner.any(axis=1))[0], np.argmax(corner.any(axis=0))] += 1e-12
    flat = np.array([[[3, 0, 0], [4, 0, 0], [3, 1, 0]], [[3, 0, 0], [3, 1, 0], [4, 0, 0]]],
                    dtype=float)  # a flat shell: dropped
    return [
        ("cube", cube, True),
        ("float32 cube", cube.astype(np.float32), True),
        ("inside out", cube[:, ::-1], True),
        ("one face flipped", flipped, True),
        ("two cubes apart", np.concatenate((cube, cube + 2.0)), True),
        ("a near copy welded", nudged, False),
        ("a flat shell dropped", np.concatenate((cube, flat)), False),
        ("overlapping cubes united", np.concatenate((cube, cube + 0.5)), False),
    ]


@pytest.mark.parametrize(("name", "triangles", "reused"), _checked_meshes(),
                         ids=[case[0] for case in _checked_meshes()])
def test_check_solid_vertices_are_those_a_body_would_weld(name, triangles, reused):
    """A mesh read from a file is welded once: check_solid hands its vertices and the
    triangles' index into them to the body only when they are exactly what welding the
    triangles it returns would give."""
    from plumbob.bodies.solid import MeshSolid
    from plumbob.mesh.solid import check_solid
    from plumbob.mesh.weld import merge_vertices

    checked = check_solid(triangles)
    assert (checked.vertices is not None) == reused, name
    assert (checked.index is not None) == reused, name
    expect, expect_index = merge_vertices(checked.triangles.reshape(-1, 3))
    body = MeshSolid(checked.triangles, checked=True, vertices=checked.vertices,
                     index=checked.index)
    got = body.hull_points()
    assert got.dtype == expect.dtype and np.array_equal(got, expect), name
    points, index = body.welded  # the check's weld, index and all, when it has one
    assert np.array_equal(points, expect) and index.dtype == np.int64, name
    assert np.array_equal(index, expect_index.reshape(-1, 3)), name
    moved = body.transformed(np.eye(3), np.array([1.0, 0.0, 0.0]))
    moved_expect = merge_vertices(moved.triangles.reshape(-1, 3))[0]  # not carried over
    assert np.array_equal(moved.hull_points(), moved_expect)


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("inside_out", [False, True])
def test_a_large_mesh_is_hashed_once(monkeypatch, dtype, inside_out):
    """A mesh past the full check's size: the check's edge pairing hashes the corners, and
    the body welds by those keys (float64 corners; float32 ones are hashed by their own
    bits, so the weld hashes again): the same vertices and index as a weld of its own."""
    from plumbob.bodies.solid import MeshSolid
    from plumbob.mesh import solid
    from plumbob.mesh.weld import merge_vertices, point_keys

    monkeypatch.setattr(solid, "FULL_CHECK_LIMIT", 10)
    triangles = _rotated(pyramid(np.stack((np.cos(np.arange(24) / 3.8),
                                           np.sin(np.arange(24) / 3.8)), axis=1), 0.8).triangles,
                         7).astype(dtype)
    checked = solid.check_solid(triangles[:, ::-1] if inside_out else triangles)
    assert checked.vertices is None and checked.notices[-1].startswith("shells: not checked")
    assert np.array_equal(checked.triangles, triangles)
    if dtype == np.float32:
        assert checked.keys is None
        return
    corners = checked.triangles.reshape(-1, 3)
    assert np.array_equal(checked.keys.reshape(-1), point_keys(corners.astype(float)))
    body = MeshSolid(checked.triangles, checked=True, keys=checked.keys)
    points, index = body.welded
    expect, expect_index = merge_vertices(corners)
    assert np.array_equal(points, expect) and np.array_equal(index.reshape(-1), expect_index)
    assert "_weld_keys" not in body.__dict__  # let go once welded
    wrong = np.zeros_like(checked.keys)  # keys that collide: caught, the exact weld instead
    points, index = MeshSolid(checked.triangles, checked=True, keys=wrong).welded
    assert len(points) == len(expect) and np.array_equal(points[index], checked.triangles)


def _arc_runs_by_labels(starts, ends, normals):
    """The grouping of the support's edges as it was computed before (a label per run,
    then np.unique of the labels, which loaded numpy.ma): the oracle for the split."""
    from plumbob.stability import verdict

    n = len(starts)
    lengths = np.linalg.norm(ends - starts, axis=1)
    short = lengths < verdict._ARC_EDGE_SHARE * lengths.sum()
    cos = np.einsum("ij,ij->i", normals, np.roll(normals, -1, axis=0))
    link = short & np.roll(short, -1) & (cos > np.cos(np.radians(verdict._ARC_TURN_DEG)))
    if link.all():
        return [np.arange(n)]
    order = (np.arange(n) + int(np.argmin(link)) + 1) % n
    labels = np.cumsum(~link[np.roll(order, 1)])
    split = []
    for run in [order[labels == label] for label in np.unique(labels)]:
        split += [run] if len(run) >= verdict._ARC_MIN_EDGES else [np.array([i]) for i in run]
    return split


@given(st.lists(st.one_of(st.just(0.01), st.floats(0.005, 1.5)), min_size=3, max_size=60))
def test_support_edges_group_into_the_same_arcs(gaps):
    """Round bases (many equal short edges) and broken ones: runs of short edges group
    into arcs exactly as before."""
    from plumbob.stability.verdict import _arc_runs

    angles = np.cumsum(gaps)
    angles = 2 * np.pi * angles / angles[-1]
    corners = np.stack((np.cos(angles), np.sin(angles)), axis=1)
    starts, ends = corners, np.roll(corners, -1, axis=0)
    d = ends - starts
    normals = np.stack((d[:, 1], -d[:, 0]), axis=1) / np.linalg.norm(d, axis=1)[:, None]
    got = _arc_runs(starts, ends, normals)
    expect = _arc_runs_by_labels(starts, ends, normals)
    assert [r.tolist() for r in got] == [r.tolist() for r in expect]


def _unique_by_stable_sort(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """merge_vertices' answer as it was computed before: np.unique of the keys with the
    first index of each (a stable sort) and the inverse."""
    from plumbob.mesh.weld import point_keys

    p = np.ascontiguousarray(points, dtype=float).reshape(-1, 3) + 0.0
    _, first, inverse = np.unique(point_keys(p), return_index=True, return_inverse=True)
    if not np.array_equal(p[first][inverse], p):
        return np.unique(p, axis=0, return_inverse=True)
    return p[first], inverse.reshape(-1)


@given(st.integers(0, 40), st.integers(0, 10**6), st.booleans())
def test_welding_by_an_unstable_sort_gives_the_same_vertices(n, seed, single):
    """Welding (every mesh read is welded) sorts its keys with numpy's fast unstable
    argsort: the vertices and the index of every corner are exactly as before."""
    from plumbob.mesh.weld import merge_vertices

    rng = np.random.default_rng(seed)
    distinct = rng.normal(size=(n, 3)).astype(np.float32 if single else float)
    distinct[rng.random((n, 3)) < 0.3] = -0.0  # signed zeros weld with zeros
    corners = distinct[rng.integers(0, max(n, 1), 3 * n)] if n else distinct
    vertices, index = merge_vertices(corners)
    expect_vertices, expect_index = _unique_by_stable_sort(corners)
    assert vertices.dtype == expect_vertices.dtype and index.dtype == expect_index.dtype
    assert np.array_equal(vertices, expect_vertices) and np.array_equal(index, expect_index)


@given(st.integers(0, 10**6), st.integers(1, 100), st.integers(1, 3000))
def test_unique_first_on_many_keys_is_numpys_unique(seed, tops, lows):
    """From RADIX_MIN keys the weld sorts by the keys' top 32 bits and then each run of
    different keys sharing them (up to 64 runs; more: all the keys at once): keys drawn
    from few top words and few low words (ties of the top bits everywhere, repeated keys)
    give np.unique's first indices and groups."""
    from plumbob.arrays import RADIX_MIN
    from plumbob.mesh.weld import unique_first

    rng = np.random.default_rng(seed)
    n = int(rng.integers(RADIX_MIN, 3 * RADIX_MIN))
    top = rng.integers(0, 1 << 32, tops, dtype=np.uint64)[rng.integers(0, tops, n)]
    low = rng.integers(0, 1 << 32, lows, dtype=np.uint64)[rng.integers(0, lows, n)]
    keys = (top << np.uint64(32)) | low
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    got_first, got_inverse = unique_first(keys)
    assert np.array_equal(got_first, first) and np.array_equal(got_inverse, inverse.reshape(-1))


def test_unique_first_on_hashes_with_a_few_ties_is_numpys_unique():
    """Hashes of 60,000 points, each used 3 to 8 times, two pairs of them made to share
    their top 32 bits: np.unique's first indices and groups."""
    from plumbob.arrays import stable_order
    from plumbob.mesh.weld import _ties_sorted, unique_first

    rng = np.random.default_rng(11)
    distinct = rng.integers(0, np.iinfo(np.uint64).max, 60_000, dtype=np.uint64)
    distinct[7] = (distinct[3] & np.uint64(0xFFFFFFFF00000000)) | np.uint64(5)
    distinct[9] = (distinct[8] & np.uint64(0xFFFFFFFF00000000)) | np.uint64(2**32 - 1)
    keys = np.repeat(distinct, rng.integers(3, 9, len(distinct)))[::-1].copy()
    rng.shuffle(keys)
    _, first, inverse = np.unique(keys, return_index=True, return_inverse=True)
    got_first, got_inverse = unique_first(keys)
    assert np.array_equal(got_first, first) and np.array_equal(got_inverse, inverse.reshape(-1))
    # the two runs are sorted where they lie: the stable order of the whole keys, no resort
    order = stable_order((keys >> np.uint64(32)).astype(np.int64))
    assert np.any(keys[order][1:] < keys[order][:-1])
    order, sk = _ties_sorted(keys, order, keys[order])
    assert np.array_equal(order, np.argsort(keys, kind="stable")) and np.array_equal(sk, keys[order])


@given(st.integers(0, 10**6), st.integers(0, 300), st.booleans())
def test_point_keys_are_splitmix_of_the_coordinates_bits(seed, n, single):
    """The weld's keys (mixed in place) are the splitmix64 rounds written out, so the
    vertices come in the same order: -0.0 hashed as 0.0, float32 by its own bits."""
    from plumbob.mesh.weld import point_keys

    def mix(z):
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
        return z ^ (z >> np.uint64(31))

    rng = np.random.default_rng(seed)
    p = rng.normal(size=(n, 3)).astype(np.float32 if single else float)
    p[rng.random((n, 3)) < 0.2] = -0.0
    q = p + p.dtype.type(0)
    with np.errstate(over="ignore"):
        if single:
            b = q.view(np.uint32)
            xy = (b[:, 0].astype(np.uint64) << np.uint64(32)) | b[:, 1]
            expect = mix(xy ^ b[:, 2] * np.uint64(0x9E3779B97F4A7C15))
        else:
            b = q.view(np.uint64)
            expect = mix(mix(mix(b[:, 0]) ^ b[:, 1]) ^ b[:, 2])
    assert np.array_equal(point_keys(p), expect)


def test_welding_survives_a_hash_collision(monkeypatch):
    from plumbob.mesh import weld

    corners = np.random.default_rng(5).normal(size=(8, 3))[[0, 1, 2, 1, 0, 7, 3, 3]]
    monkeypatch.setattr(weld, "point_keys", lambda p: np.zeros(len(p), dtype=np.uint64))
    vertices, index = weld.merge_vertices(corners)
    assert len(vertices) == 5 and np.array_equal(vertices[index], corners)
