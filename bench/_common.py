"""Helpers shared by the benchmarks: test files and timing."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import numpy as np

STL_DTYPE = np.dtype([("normal", "<f4", 3), ("tri", "<f4", (3, 3)), ("attr", "<u2")])


def sphere_triangles(min_triangles: int) -> np.ndarray:
    """A closed UV sphere (float64, (n, 3, 3)) of radius 1 with at least ``min_triangles``."""
    rings = int(np.ceil(np.sqrt(min_triangles / 4))) + 1
    segments = 2 * rings
    theta = np.linspace(0, np.pi, rings + 1)
    phi = np.linspace(0, 2 * np.pi, segments + 1)[:-1]
    t, p = np.meshgrid(theta, phi, indexing="ij")
    grid = np.stack((np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)), axis=-1)
    a = grid[:-1, :]
    b = grid[1:, :]
    c = np.roll(grid[1:, :], -1, axis=1)
    d = np.roll(grid[:-1, :], -1, axis=1)
    upper = np.stack((a, b, c), axis=2)[1:].reshape(-1, 3, 3)  # skip the degenerate pole row
    lower = np.stack((a, c, d), axis=2)[:-1].reshape(-1, 3, 3)
    tri = np.concatenate((upper, lower))
    # scale so that the mesh is non-symmetric enough not to be a special case
    return tri * np.array([1.0, 0.8, 0.6])


def write_binary_stl(path: str, triangles: np.ndarray) -> None:
    records = np.zeros(len(triangles), dtype=STL_DTYPE)
    records["tri"] = triangles
    with open(path, "wb") as handle:
        handle.write(b"plumbob benchmark".ljust(80, b" "))
        handle.write(np.uint32(len(triangles)).tobytes())
        records.tofile(handle)


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
