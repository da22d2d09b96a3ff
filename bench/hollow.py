"""Hollowing leaning figurines (issue 23): time, and how close to the bound.

Target: with 2 mm walls, figurines of 10k to 200k triangles carved for 95 % of the best
margin any carve reaches, each in under 60 s on 2 cores, the margin checked on the
written file; the plan's bound beside an independent one (tests/_voxel_bound.py: 0.5 mm
voxels, scipy's distance transform, every plane carve) as a ratio.

The figurines are tests/_figurines.py's (a capsule leaning out of a plinth, a bent arm,
an off-centre head), their faceting chosen for the triangle count.

Run: ``PYTHONPATH=src python bench/hollow.py [--smoke]`` (``--smoke``: one small figurine,
every step run once and no target judged).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))

from _figurines import figurine_triangles  # noqa: E402
from _voxel_bound import voxel_bound  # noqa: E402

WALL = 2e-3
RHO = 1200.0
#: (kind, seed, segments): about 10k, 50k and 200k triangles
CASES = [("capsule", 1, 150), ("head", 2, 200), ("arm", 1, 250), ("capsule", 1, 640),
         ("arm", 1, 450)]


def run(kind: str, seed: int, segments: int, folder: str, judge: bool) -> bool:
    from plumbob.balance.hollow import hollow, write_hollow
    from plumbob.balance.targets import target_for
    from plumbob.formats.writers import stl_bytes
    from plumbob.loading import read

    triangles = figurine_triangles(kind, seed, 1.0, segments)
    path = os.path.join(folder, f"{kind}{seed}.stl")
    with open(path, "wb") as handle:
        handle.write(stl_bytes(triangles, kind, 1e-3))
    independent = voxel_bound(triangles, WALL, 0.5e-3)
    start = time.perf_counter()
    body = read(path, units="mm").body.with_default_density(RHO)
    plan = hollow(body, wall=WALL, target=target_for(body, margin=0.95 * independent))
    written = write_hollow(plan, os.path.join(folder, "carved.stl"), units="mm")
    seconds = time.perf_counter() - start
    achieved = written.verdict.margin
    ok = seconds < 60 and achieved >= 0.95 * independent
    print(f"{kind:8s} seed {seed} {len(triangles):7d} triangles: bound {plan.bound.value * 1e3:.3f} mm "
          f"(independent {independent * 1e3:.3f} mm, ratio {plan.bound.value / independent:.3f}), "
          f"achieved {achieved * 1e3:.3f} mm on the file = {achieved / independent:.1%} of the "
          f"independent bound, {seconds:.1f} s (plan {plan.seconds:.1f} s)"
          + ("" if not judge else ("  ok" if ok else "  MISSED")))
    return ok


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--smoke", action="store_true", help="one small figurine, nothing judged")
    args = parser.parse_args()
    cases = [("capsule", 1, 48)] if args.smoke else CASES
    with tempfile.TemporaryDirectory() as folder:
        results = [run(*case, folder, not args.smoke) for case in cases]
    if not args.smoke and not all(results):
        raise SystemExit(1)


if __name__ == "__main__":
    main()
