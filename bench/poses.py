"""Benchmark: resting poses, plumbob against trimesh's ``compute_stable_poses``.

Both run in one process on the same closed, non-symmetric meshes (a bumpy
"potato" of 10 000 and 100 000 triangles, and a smooth convex-ish blob of
100 000, whose hull has nearly as many faces as the mesh) with the same centre
of mass, and the ratios of their times are printed. The acceptance target of
issue 3 is at least 50× at 100k faces, with probabilities summing to 1 and no
reported pose that is not truly stable.

Both libraries compute the convex hull with qhull; its time is printed too, as
it bounds the ratio any pose code built on qhull can reach.

Note that the two libraries answer different models: trimesh's probabilities
are the solid angles subtended by hull triangles, passed down a toppling graph;
plumbob's are the basins of the quasi-static descent of Baktash et al. (2025). The
poses themselves (stable faces) should agree, up to trimesh counting coplanar
triangles separately.

Run: ``python bench/poses.py [--repeat R] [--quick]``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def potato(n_lat: int, n_lon: int, *, seed: int = 1, bump: float = 0.12):
    """A closed, outward-wound, non-symmetric blob on a latitude-longitude grid:
    ``2 · n_lon · (n_lat − 1)`` triangles. Returns (vertices (n, 3), faces (m, 3))."""
    rng = np.random.default_rng(seed)
    theta = np.linspace(0, np.pi, n_lat + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, n_lon, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    d = np.stack((np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)), axis=-1)
    r = np.ones_like(t)
    for _ in range(6):
        k = rng.normal(size=3)
        k /= np.linalg.norm(k)
        lobes = rng.integers(2, 6)
        r += bump * rng.uniform(0.3, 1.0) * np.cos(
            lobes * np.arccos(np.clip(d @ k, -1, 1)) + rng.uniform(0, 2 * np.pi))
    radii = np.array([1.0, 0.75, 0.55])
    verts = np.vstack(((d * r[..., None] * radii).reshape(-1, 3),
                       [[0, 0, radii[2]], [0, 0, -radii[2]]]))
    top, bottom = len(verts) - 2, len(verts) - 1
    idx = np.arange(len(theta) * len(phi)).reshape(len(theta), len(phi))
    a, b = idx[:-1], idx[1:]
    a2, b2 = np.roll(a, -1, axis=1), np.roll(b, -1, axis=1)
    faces = [np.stack((a, b, b2), -1).reshape(-1, 3), np.stack((a, b2, a2), -1).reshape(-1, 3),
             np.stack((np.full(len(phi), top), idx[0], np.roll(idx[0], -1)), 1),
             np.stack((np.full(len(phi), bottom), np.roll(idx[-1], -1), idx[-1]), 1)]
    return verts, np.concatenate(faces)


def timed(fn, repeat: int):
    """(best wall time, best CPU time, result) over ``repeat`` runs, s."""
    wall = cpu = np.inf
    result = None
    for _ in range(repeat):
        w, c = time.perf_counter(), time.process_time()
        result = fn()
        wall = min(wall, time.perf_counter() - w)
        cpu = min(cpu, time.process_time() - c)
    return wall, cpu, result


def truly_stable(body, down) -> bool:
    """Independent of the pose code: plumbob's toppling verdict on that face."""
    from plumbob.stability import check

    return check(body, down).verdict == "stands"


def run_case(name: str, verts: np.ndarray, faces: np.ndarray, repeat: int) -> dict:
    import trimesh
    from scipy.spatial import ConvexHull

    from plumbob.bodies.solid import MeshSolid
    from plumbob.stability import poses_from_points

    body = MeshSolid(verts[faces], density=1000.0)
    com = body.mass_properties().center_of_mass
    mesh = trimesh.Trimesh(verts, faces, process=False)

    qh_wall, qh_cpu, _ = timed(lambda: ConvexHull(verts - com), repeat)
    our_wall, our_cpu, ours = timed(lambda: poses_from_points(verts, com), repeat)
    tm_wall, tm_cpu, (transforms, tm_probs) = timed(
        lambda: trimesh.poses.compute_stable_poses(mesh, center_mass=com), 1)

    our_ok = all(truly_stable(body, p.down) for p in ours.poses)
    tm_downs = [t[:3, :3].T @ np.array([0.0, 0.0, -1.0]) for t in transforms]
    tm_unstable = sum(not truly_stable(body, d) for d in tm_downs)
    tm_nan = int(np.count_nonzero(~np.isfinite(tm_probs)))
    print(f"\n{name}: {len(faces):,} triangles, {ours.hull_faces:,} hull faces")
    print(f"  qhull alone (shared floor)   {qh_wall:8.3f} s wall  {qh_cpu:8.3f} s CPU")
    print(f"  plumbob poses                {our_wall:8.3f} s wall  {our_cpu:8.3f} s CPU   "
          f"{len(ours)} poses, sum {ours.probabilities.sum():.15f}, {ours.method}, "
          f"all truly stable: {our_ok}")
    print(f"  trimesh compute_stable_poses {tm_wall:8.3f} s wall  {tm_cpu:8.3f} s CPU   "
          f"{len(tm_probs)} poses, sum {np.nansum(tm_probs):.15f}, {tm_nan} NaN, "
          f"{tm_unstable} not truly stable")
    beyond = tm_cpu / max(our_cpu - qh_cpu, 1e-9)
    print(f"  ratio trimesh / plumbob      {tm_wall / our_wall:8.1f}× wall "
          f"{tm_cpu / our_cpu:8.1f}× CPU   (plumbob beyond qhull: {beyond:.0f}× CPU)")
    return {"faces": len(faces), "ratio": tm_cpu / our_cpu,
            "ok": our_ok and abs(ours.probabilities.sum() - 1) < 1e-12}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="best of R runs for plumbob")
    parser.add_argument("--quick", action="store_true", help="only the 10k-face mesh")
    args = parser.parse_args(argv)

    from plumbob.stability import poses_from_points

    warm, _ = potato(11, 20)  # imports and first calls out of the timings
    poses_from_points(warm, warm.mean(axis=0))
    cases = [("bumpy potato", *potato(51, 100))]
    if not args.quick:
        cases += [("bumpy potato", *potato(201, 250)),
                  ("smooth blob", *potato(201, 250, seed=5, bump=0.02))]
    results = [run_case(name, v, f, args.repeat) for name, v, f in cases]
    big = [r for r in results if r["faces"] >= 100_000]
    if big:
        worst = min(r["ratio"] for r in big)
        print(f"\nat 100k faces: {worst:.1f}× faster (CPU) — target 50×: "
              f"{'met' if worst >= 50 else 'not met'}")
    return 0 if all(r["ok"] for r in results) else 1


if __name__ == "__main__":
    raise SystemExit(main())
