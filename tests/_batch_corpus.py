"""A small corpus for the batch tests: meshes of several sizes, a lamina, a spec and
files broken on purpose (each with the error it must give)."""

from __future__ import annotations

import os
import shutil

import numpy as np
from conftest import SHAPES

STL_DTYPE = np.dtype([("normal", "<f4", 3), ("tri", "<f4", (3, 3)), ("attr", "<u2")])


def torus(triangles: int, major: float, minor: float, shift=(0.0, 0.0, 0.0)) -> np.ndarray:
    """A closed, outward-wound torus, (n, 3, 3)."""
    nv = max(3, int(np.sqrt(triangles / 4)))
    nu = max(3, -(-triangles // (2 * nv)))
    u, v = np.meshgrid(2 * np.pi * np.arange(nu) / nu, 2 * np.pi * np.arange(nv) / nv,
                       indexing="ij")
    ring = major + minor * np.cos(v)
    verts = np.stack((ring * np.cos(u), ring * np.sin(u), minor * np.sin(v)), axis=-1) + shift
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a, b, c, d = verts[i, j], verts[(i + 1) % nu, j], verts[(i + 1) % nu, (j + 1) % nv], \
        verts[i, (j + 1) % nv]
    return np.concatenate((np.stack((a, b, c), axis=-2).reshape(-1, 3, 3),
                           np.stack((a, c, d), axis=-2).reshape(-1, 3, 3)))


def write_stl(path: str, triangles: np.ndarray, count: int | None = None) -> None:
    records = np.zeros(len(triangles), dtype=STL_DTYPE)
    records["tri"] = triangles
    with open(path, "wb") as handle:
        handle.write(b"plumbob test".ljust(80, b" "))
        handle.write(np.uint32(len(triangles) if count is None else count).tobytes())
        records.tofile(handle)


def make_corpus(folder: str, meshes: int = 8) -> dict[str, str]:
    """Write the corpus; returns {file name: 'ok' or the error class it must give}."""
    os.makedirs(os.path.join(folder, "sub"), exist_ok=True)
    expect = {}
    for k in range(meshes):
        name = os.path.join("sub" if k % 2 else "", f"torus_{k}.stl")
        write_stl(os.path.join(folder, name),
                  torus(40 + 90 * k, 10 + k, 2 + 0.3 * k, shift=(k, -k, 0.5 * k)))
        expect[name] = "ok"
    # specs that set no units and no density, so --units and --material apply to them
    for name in ("stepped_cylinder.toml", "triangle.toml"):
        shutil.copy(os.path.join(SHAPES, name), os.path.join(folder, name))
        expect[name] = "ok"
    write_stl(os.path.join(folder, "truncated.stl"), torus(200, 10, 3)[:50], count=200)
    expect["truncated.stl"] = "InputFileError"
    open(os.path.join(folder, "empty.stl"), "wb").close()
    expect["empty.stl"] = "InputFileError"
    write_stl(os.path.join(folder, "open.stl"), torus(200, 10, 3)[:-7])
    expect["open.stl"] = "GeometryError"
    with open(os.path.join(folder, "notes.txt"), "w") as handle:  # not a known extension
        handle.write("not a part")
    return expect
