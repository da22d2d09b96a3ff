"""Speed of `plumbob mass` against trimesh and shapely, measured in the same run.

Targets (issue 2):
* a binary STL of ≥ 1M triangles: `plumbob mass FILE --json` ≥ 10× faster than trimesh
  (load with defaults, then mass_properties) as whole processes, and within 3× of a
  process that merely reads the file into numpy; ≥ 20× for the library call alone;
* a 1M-vertex lamina: full second moments within 3× of shapely's centroid.

plumbob's bytecode is compiled first (``compileall`` on the plumbob package the
benchmark imports), as an installed package has it, like trimesh and shapely: with
``PYTHONDONTWRITEBYTECODE`` set each plumbob process would otherwise recompile every
module it loads. All processes run with the same environment.

Run: PYTHONPATH=src python bench/mass.py [--triangles N] [--vertices N] [--smoke]
(``--smoke``: tiny sizes, each step once; it judges nothing and compiles no bytecode).
"""

from __future__ import annotations

import argparse
import os
import tempfile

import numpy as np
from _common import PYTHON, compile_bytecode, time_call, time_process, torus_triangles, write_binary_stl


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--triangles", type=int, default=1_000_000)
    parser.add_argument("--vertices", type=int, default=1_000_000)
    parser.add_argument("--smoke", action="store_true", help="tiny sizes, each step once")
    args = parser.parse_args(argv)
    repeat = 1 if args.smoke else 3
    if args.smoke:
        args.triangles, args.vertices = 2_000, 1_000

    import shapely
    import trimesh

    import plumbob
    from plumbob.bodies.lamina import Lamina
    from plumbob.bodies.region import Region, Ring
    from plumbob.formats import read

    if not args.smoke:
        print(compile_bytecode(os.path.dirname(plumbob.__file__)))
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "torus.stl")
        triangles = torus_triangles(args.triangles)
        write_binary_stl(path, triangles)
        size = os.path.getsize(path)
        print(f"binary STL: {len(triangles):,} triangles, {size / 1e6:.1f} MB")

        read_only = time_process(
            [PYTHON, "-c", f"import numpy; numpy.fromfile({path!r}, dtype=numpy.uint8)"],
            repeat,
        )
        ours = time_process([PYTHON, "-m", "plumbob", "mass", path, "--json"], repeat)
        theirs = time_process(
            [PYTHON, "-c", f"import trimesh; m = trimesh.load({path!r}); m.mass_properties"],
            repeat=min(repeat, 2),
        )
        print("whole processes (best of runs):")
        print(f"  numpy.fromfile           {read_only:8.3f} s")
        ratio = ours / read_only
        print(f"  plumbob mass --json      {ours:8.3f} s   {ratio:5.2f}× reading (target ≤ 3)")
        speedup = theirs / ours
        print(f"  trimesh load + mass      {theirs:8.3f} s   plumbob is {speedup:5.1f}× faster (target ≥ 10)")

        ours_call = time_call(lambda: read(path).body.mass_properties(), repeat)
        theirs_call = time_call(lambda: trimesh.load(path).mass_properties,
                                repeat=min(repeat, 2))
        print("library calls:")
        print(f"  plumbob read + mass_properties  {ours_call:8.3f} s")
        print(
            f"  trimesh load + mass_properties  {theirs_call:8.3f} s   "
            f"plumbob is {theirs_call / ours_call:5.1f}× faster (target ≥ 20)"
        )

    n = args.vertices
    angles = 2 * np.pi * np.arange(n) / n
    radii = 1 + 0.1 * np.sin(7 * angles)
    ring = np.stack((radii * np.cos(angles), radii * np.sin(angles)), axis=1) + [1e3, -2e3]
    polygon = shapely.Polygon(ring)
    lamina = Lamina(Region((Ring(ring),)))
    ours_2d = time_call(lamina.mass_properties, repeat=1 if args.smoke else 5)
    theirs_2d = time_call(lambda: shapely.centroid(polygon), repeat=1 if args.smoke else 5)
    props = lamina.mass_properties()
    assert np.allclose(props.center_of_mass, polygon.centroid.coords[0], rtol=1e-12)
    print(f"lamina: {n:,} vertices")
    print(f"  shapely centroid                 {theirs_2d * 1e3:8.2f} ms")
    print(
        f"  plumbob full second moments      {ours_2d * 1e3:8.2f} ms   "
        f"{ours_2d / theirs_2d:5.2f}× shapely (target ≤ 3)"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
