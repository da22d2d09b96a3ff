"""Helpers shared by the benchmarks: test files and timing."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import numpy as np

STL_DTYPE = np.dtype([("normal", "<f4", 3), ("tri", "<f4", (3, 3)), ("attr", "<u2")])


def torus_triangles(triangles: int, major: float = 1.0, minor: float = 0.3) -> np.ndarray:
    """A closed, outward-wound torus mesh with about ``triangles`` triangles, (n, 3, 3) m."""
    nv = max(3, int(np.sqrt(triangles / 4)))
    nu = max(3, -(-triangles // (2 * nv)))
    u = 2 * np.pi * np.arange(nu) / nu
    v = 2 * np.pi * np.arange(nv) / nv
    uu, vv = np.meshgrid(u, v, indexing="ij")
    ring = major + minor * np.cos(vv)
    verts = np.stack((ring * np.cos(uu), ring * np.sin(uu), minor * np.sin(vv)), axis=-1)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    i1, j1 = (i + 1) % nu, (j + 1) % nv
    a, b, c, d = verts[i, j], verts[i1, j], verts[i1, j1], verts[i, j1]
    return np.concatenate((np.stack((a, b, c), axis=-2).reshape(-1, 3, 3),
                           np.stack((a, c, d), axis=-2).reshape(-1, 3, 3)))


def write_binary_stl(path: str, triangles: np.ndarray) -> None:
    records = np.zeros(len(triangles), dtype=STL_DTYPE)
    records["tri"] = triangles
    with open(path, "wb") as handle:
        handle.write(b"plumbob benchmark".ljust(80, b" "))
        handle.write(np.uint32(len(triangles)).tobytes())
        records.tofile(handle)


def compile_bytecode(package: str) -> str:
    """Compile the bytecode of ``package`` (a directory) once, before any process is timed;
    returns the line the benchmarks print to say so.

    An installed package has its bytecode (pip compiles it, as it did for numpy, trimesh
    and the other libraries timed here). Run from a source tree with
    ``PYTHONDONTWRITEBYTECODE`` set (as in this project's sandbox), every process would
    compile each plumbob module again, ~50 ms no user pays. With the bytecode in place
    every process timed is treated alike, with the environment it was given.
    """
    import compileall

    ok = compileall.compile_dir(package, quiet=1)
    if not ok:
        raise SystemExit(f"could not compile {package}")
    return f"bytecode compiled first (python -m compileall {package}), as an installed package has it"


def time_process(args: list[str], repeat: int = 3) -> float:
    """Best wall time (s) of a whole process over ``repeat`` runs."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run(args, check=True, stdout=subprocess.DEVNULL, env=dict(os.environ))
        best = min(best, time.perf_counter() - start)
    return best


def time_call(function, repeat: int = 3) -> float:
    """Best wall time (s) of ``function()`` over ``repeat`` calls."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        best = min(best, time.perf_counter() - start)
    return best


PYTHON = sys.executable
SRC = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "src")


def src_environment(**extra: str) -> dict[str, str]:
    """This process's environment for a timed child, plumbob's ``src/`` first on
    ``PYTHONPATH`` and whatever was there kept after it (packages a machine keeps
    outside the interpreter's own, such as wheels unpacked into a folder), plus
    ``extra``."""
    kept = os.environ.get("PYTHONPATH")
    return dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, (SRC, kept))), **extra)
