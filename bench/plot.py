"""Benchmark: what ``--plot`` costs on a large mesh (issue 12's acceptance: within 3×).

Times ``plumbob check`` and ``plumbob poses`` on a 1,000,000-triangle torus with and
without ``--plot`` (SVG for check, PNG for poses), each a whole process, and prints
the ratios. The pictures decimate the mesh for display only, so drawing costs about
the same whatever the mesh's size.

Run: ``python bench/plot.py [--triangles N] [--repeat R] [--smoke]`` (``--smoke``: a
small torus, each picture drawn once, no target judged).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

from _common import PYTHON, time_process, torus_triangles, write_binary_stl

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--triangles", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=1)
    parser.add_argument("--smoke", action="store_true", help="tiny sizes, no target judged")
    args = parser.parse_args(argv)
    if args.smoke:
        args.triangles = 500
    os.environ["PYTHONPATH"] = os.path.join(ROOT, "src")
    with tempfile.TemporaryDirectory() as folder:
        stl = os.path.join(folder, "torus.stl")
        write_binary_stl(stl, torus_triangles(args.triangles))
        print(f"torus of {args.triangles:,} triangles")
        worst = 0.0
        for command, picture in (("check", "c.svg"), ("poses", "p.png")):
            base = [PYTHON, "-m", "plumbob.cli", command, stl]
            drawn = time_process(base + ["--plot", os.path.join(folder, picture)], args.repeat)
            if args.smoke:  # each picture drawn once is the check
                print(f"{command:>6} with --plot {picture}: {drawn:6.2f} s")
                continue
            plain = time_process(base, args.repeat)
            worst = max(worst, drawn / plain)
            print(f"{command:>6}: {plain:6.2f} s, with --plot {picture}: {drawn:6.2f} s "
                  f"({drawn / plain:.2f}×)")
        print(f"worst ratio {worst:.2f}× (target: at most 3×)")
        return 0 if worst <= 3 or args.smoke else 1


if __name__ == "__main__":
    sys.exit(main())
