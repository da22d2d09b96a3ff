"""Benchmark plumbob's binary STL reader.

    python bench/read.py [TRIANGLES] [--smoke]

Writes a closed torus of at least TRIANGLES (default 1 048 576) triangles as a
binary STL in a temporary folder, then times (best of several, file in the page
cache):

* ``numpy.fromfile`` of the same bytes — the floor;
* ``plumbob.formats.stl.load_stl`` — parsing: triangles, bounds, NaN check;
* ``plumbob.formats.stl.read_stl`` — the whole read: units, the closure and sign
  test, the body;
* ``trimesh.load`` — for comparison.

Targets (issue 4): load_stl ≤ 2 × fromfile; peak memory of load_stl ≤ 1.5 × the
file size beyond the interpreter's baseline (measured with tracemalloc and, in a
fresh process, with the resident-set high-water mark). ``--smoke``: a small torus, each
step once, no target judged.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import tracemalloc

import numpy as np
from _common import time_call, torus_triangles, write_binary_stl


def torus_stl(path: str, triangles: int) -> int:
    """Write a closed torus (R = 1 m, r = 0.3 m) of ≥ ``triangles`` triangles; return the count."""
    tri = torus_triangles(triangles)
    write_binary_stl(path, tri)
    return len(tri)


_RSS = """
import sys
from plumbob.formats.stl import load_stl

def high_water():  # this process's peak resident set, bytes (VmHWM starts afresh at exec)
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    import resource
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024

base = high_water()
stl = load_stl(sys.argv[1])
print(high_water() - base)
"""


def main(argv: list[str] | None = None) -> int:
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("triangles", nargs="?", type=int, default=1 << 20)
    parser.add_argument("--smoke", action="store_true", help="tiny sizes, no target judged")
    args = parser.parse_args(argv)
    triangles, rounds = (2_000, 1) if args.smoke else (args.triangles, 15)
    from plumbob.formats.stl import load_stl, read_stl

    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "torus.stl")
        count = torus_stl(path, triangles)
        size = os.path.getsize(path)
        print(f"binary STL: {count} triangles, {size / 1e6:.1f} MB")
        np.fromfile(path, dtype=np.uint8)  # warm the page cache
        # Interleaved, best of many: other processes on the machine add noise to both.
        t_numpy, t_load = float("inf"), float("inf")
        for _ in range(rounds):
            t_numpy = min(t_numpy, time_call(lambda: np.fromfile(path, dtype=np.uint8), 1))
            t_load = min(t_load, time_call(lambda: load_stl(path), 1))
        t_read = time_call(lambda: read_stl(path), min(rounds, 3))
        volume = read_stl(path).body.mass_properties().volume
        tracemalloc.start()
        load_stl(path)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        rss = int(subprocess.run([sys.executable, "-c", _RSS, path], capture_output=True,
                                 text=True, check=True).stdout.strip())
        try:
            import trimesh

            t_trimesh = time_call(lambda: trimesh.load(path), 1)
            t_trimesh_raw = time_call(lambda: trimesh.load(path, process=False), min(rounds, 2))
        except ImportError:  # pragma: no cover
            t_trimesh = t_trimesh_raw = float("nan")
    print(f"  numpy.fromfile              {t_numpy * 1e3:8.1f} ms")
    print(f"  plumbob load_stl (parse)    {t_load * 1e3:8.1f} ms   "
          f"{t_load / t_numpy:5.2f} × fromfile")
    print(f"  plumbob read_stl (checked)  {t_read * 1e3:8.1f} ms   "
          f"{t_read / t_numpy:5.2f} × fromfile")
    print(f"  trimesh.load                {t_trimesh * 1e3:8.1f} ms   "
          f"{t_trimesh / t_load:5.1f} × load_stl")
    print(f"  trimesh.load(process=False) {t_trimesh_raw * 1e3:8.1f} ms   "
          f"{t_trimesh_raw / t_load:5.1f} × load_stl")
    print(f"  peak memory of load_stl: {peak / 1e6:.1f} MB traced = {peak / size:.2f} × file; "
          f"{rss / 1e6:.1f} MB resident in a fresh process = {rss / size:.2f} × file")
    print(f"  torus volume {volume:.9f} m³ (exact {2 * np.pi**2 * 0.09:.9f} for the smooth torus)")
    ok = t_load <= 2 * t_numpy and peak <= 1.5 * size and rss <= 1.5 * size
    print("targets (≤ 2 × fromfile, ≤ 1.5 × file size):", "met" if ok else "NOT met")
    return 0 if ok or args.smoke else 1


if __name__ == "__main__":
    sys.exit(main())
