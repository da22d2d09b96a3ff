"""Hollowing leaning figurines (issue 23): each target's time, and how close to the bound.

Target: with 2 mm walls, figurines of 10k to 200k triangles, every target up to 95 % of
the best margin any carve reaches met, each ``plumbob balance`` in under 60 s on 2 cores,
the margin checked on the written file; a target beyond the bound refused with the bound
stated, within 5 % of an independent one (tests/_voxel_bound.py: 0.5 mm voxels, scipy's
distance transform, every plane carve — no plumbob code), printed as a ratio.

Each target is one whole process, as a user runs it::

    plumbob balance fig.stl --units mm --density 1200 --wall 2mm --margin M --out carved.stl

timed by its wall clock and by its processor time (user + system). The 60 s target is
judged on the processor time: on a machine that other jobs share (this project's has two
cores and often ten busy jobs) the wall clock measures the queue, and a process alone on
two cores takes no longer than its processor time. For the 95 % target the written files are then checked
with trimesh, as the tests do: closed, the wall kept at points sampled on the void (their
distance to the figurine's surface, and inside it), and the same mass properties.

The figurines are tests/_figurines.py's (a capsule leaning out of a plinth, a bent arm,
an off-centre head), their faceting chosen for the triangle count.

Run: ``PYTHONPATH=src python bench/hollow.py [--sizes 10000,50000] [--smoke]`` (``--smoke``:
one small figurine, coarse voxels, every step run once and nothing judged).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests"))

from _figurines import figurine_triangles  # noqa: E402
from _voxel_bound import voxel_bound  # noqa: E402

WALL_MM = 2.0
RHO = 1200.0
PITCH = 0.5e-3
#: triangles (about) -> (kind, seed, segments)
CASES = {10_000: ("capsule", 1, 150), 50_000: ("head", 2, 245), 100_000: ("arm", 1, 376),
         200_000: ("capsule", 2, 735)}
SMOKE = ("capsule", 1, 24)


def _plumbob(argv: list[str]) -> tuple[subprocess.CompletedProcess, float, float]:
    """Run ``python -m plumbob ARGV``; (the process, wall s, processor s)."""
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "plumbob", *argv], env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return done, wall, cpu


def _files_ok(source: np.ndarray, carved: str, void: str, samples: int) -> tuple[bool, float]:
    """trimesh's view of the written files: (closed, wall kept and same mass properties;
    the least distance found from the void to the figurine's surface, mm)."""
    import trimesh

    carved_mesh, void_mesh = trimesh.load(carved), trimesh.load(void)
    closed = all(m.is_watertight and m.is_winding_consistent and m.is_volume
                 for m in (carved_mesh, void_mesh))
    outer = trimesh.Trimesh(**trimesh.triangles.to_kwargs(source / 1e-3))
    points, _ = trimesh.sample.sample_surface(void_mesh, samples, seed=5)
    points = np.concatenate((points, void_mesh.vertices[:: max(1, len(void_mesh.vertices)
                                                              // (samples // 4))]))
    _, distance, _ = trimesh.proximity.closest_point(outer, points)
    wall = bool(outer.contains(points).all() and distance.min() >= WALL_MM - 1e-4)
    # the mass from plumbob's own reading of the file, against trimesh's
    from plumbob import read

    mass = read(carved, units="mm").body.with_default_density(RHO).mass_properties().mass
    carved_mesh.apply_scale(1e-3)
    carved_mesh.density = RHO
    same = abs(mass - carved_mesh.mass) <= 1e-9 * carved_mesh.mass
    return closed and wall and same, float(distance.min())


def run(size: int, case: tuple, folder: str, pitch: float, samples: int, judge: bool) -> bool:
    from plumbob.formats.writers import stl_bytes

    kind, seed, segments = case
    triangles = figurine_triangles(kind, seed, 1.0, segments)
    path = os.path.join(folder, f"{kind}{seed}.stl")
    with open(path, "wb") as handle:
        handle.write(stl_bytes(triangles, kind, 1e-3))
    clock = time.perf_counter()
    independent = voxel_bound(triangles, WALL_MM * 1e-3, pitch,
                              samples=samples * 500) * 1e3  # mm
    voxel_seconds = time.perf_counter() - clock
    common = ["balance", path, "--units", "mm", "--density", str(RHO), "--wall", f"{WALL_MM}mm"]
    carved, void = os.path.join(folder, "carved.stl"), os.path.join(folder, "void.stl")
    # 95 %: met, on the written file
    met, wall_met, cpu_met = _plumbob([*common, "--margin", f"{0.95 * independent:.6f}mm",
                                       "--out", carved, "--void", void, "--json"])
    if met.returncode != 0:
        print(f"{size:>7} {kind:8s}: the 95 % target failed: {met.stderr.strip()}")
        return False
    hollow = json.loads(met.stdout)["hollow"]
    bound, achieved = hollow["bound"]["value"] * 1e3, hollow["margin"] * 1e3
    files, nearest = _files_ok(triangles, carved, void, samples)
    # 110 %: refused, the bound stated
    refused, wall_refused, cpu_refused = _plumbob([*common, "--margin",
                                                   f"{1.1 * independent:.6f}mm", "--out", carved])
    stated = re.search(r"reaches is a margin of ([0-9.]+) mm", refused.stderr)
    quoted = float(stated.group(1)) if stated else float("nan")
    ok = (achieved >= 0.95 * independent and refused.returncode != 0 and stated is not None
          and abs(quoted / independent - 1) <= 0.05 and files
          and max(cpu_met, cpu_refused) < 60)
    print(f"{len(triangles):>7} {kind:8s} {independent:8.3f} {bound:8.3f} "
          f"{bound / independent:6.3f} {achieved:8.3f} {achieved / independent:6.1%} "
          f"{wall_met:6.1f} {cpu_met:6.1f} {quoted:7.3f} {wall_refused:6.1f} {cpu_refused:6.1f} "
          f"{nearest:6.3f} {'yes' if files else 'NO':>5} {voxel_seconds:6.1f}"
          + ("" if not judge else ("  ok" if ok else "  MISSED")))
    sys.stdout.flush()
    return ok


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--smoke", action="store_true",
                        help="one small figurine, coarse voxels, nothing judged")
    parser.add_argument("--sizes", default=",".join(map(str, CASES)),
                        help="triangle counts, among " + ", ".join(map(str, CASES)))
    args = parser.parse_args()
    if args.smoke:
        cases, pitch, samples = [(400, SMOKE)], 1e-3, 200
    else:
        cases = [(int(s), CASES[int(s)]) for s in args.sizes.split(",")]
        pitch, samples = PITCH, 2000
    print(f"plumbob balance --wall {WALL_MM:g}mm on leaning figurines ({os.cpu_count()} cores, "
          f"load {os.getloadavg()[0]:.1f}); margins in mm, times in s (wall, processor)")
    print(f"{'tris':>7} {'kind':8s} {'voxels':>8} {'bound':>8} {'ratio':>6} {'met':>8} "
          f"{'of vox':>6} {'wall':>6} {'cpu':>6} {'refuse':>7} {'wall':>6} {'cpu':>6} "
          f"{'wall≥':>6} {'files':>5} {'vox s':>6}")
    with tempfile.TemporaryDirectory() as folder:
        results = [run(size, case, folder, pitch, samples, not args.smoke)
                   for size, case in cases]
    if not args.smoke and not all(results):
        raise SystemExit(1)


if __name__ == "__main__":
    main()
