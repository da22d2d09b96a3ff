"""The worked example of docs/printing.md: a leaning figurine hollowed so that it stands.

    PYTHONPATH=src python docs/hollow_figurine.py [--margin MM]

Generates the figurine (tests/_figurines.py: a capsule leaning out of a cylinder plinth it
is sunk into, 128 segments a turn), writes it to docs/models/leaning_figurine.stl, runs
the commands of the page through the CLI (check, balance --wall 2mm, check of the carved
file) and draws docs/pictures/hollow_before.png and hollow_after.png: the figurine cut
through its lean, before and after, with the support's edge and the centre of mass.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "src"))
sys.path.insert(0, os.path.join(ROOT, "tests"))

import numpy as np  # noqa: E402
from _figurines import figurine_triangles  # noqa: E402

from plumbob.cli import main as cli  # noqa: E402
from plumbob.formats.writers import stl_bytes  # noqa: E402

MODEL = os.path.join(HERE, "models", "leaning_figurine.stl")
PICTURES = os.path.join(HERE, "pictures")


def section(path: str, normal: np.ndarray, title: str, picture: str) -> None:
    """The mesh at ``path`` (mm) cut by the vertical plane along ``normal`` through its
    plinth's axis, drawn filled (trimesh's section, shapely's polygons), with the centre
    of mass and the plinth's edge on that side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import trimesh

    mesh = trimesh.load(path)
    side = np.cross([0.0, 0.0, 1.0], normal)
    cut = mesh.section(plane_origin=[0, 0, 0], plane_normal=side)
    planar, to_3d = cut.to_2D(normal=side)
    figure, axes = plt.subplots(figsize=(5, 4.2))
    for polygon in planar.polygons_full:
        outline = np.asarray(polygon.exterior.coords)
        ring = np.column_stack((outline, np.zeros(len(outline)), np.ones(len(outline))))
        world = (to_3d @ ring.T).T[:, :3]
        axes.fill(world @ normal, world[:, 2], color="#b9c7d8", edgecolor="#34495e", lw=0.8)
        for hole in polygon.interiors:
            inner = np.column_stack((np.asarray(hole.coords), np.zeros(len(hole.coords)),
                                     np.ones(len(hole.coords))))
            world = (to_3d @ inner.T).T[:, :3]
            axes.fill(world @ normal, world[:, 2], color="white", edgecolor="#c0392b", lw=0.8)
    centre = mesh.center_mass
    axes.plot([centre @ normal] * 2, [0, centre[2]], color="#c0392b", ls="--", lw=1)
    axes.plot(centre @ normal, centre[2], "o", color="#c0392b", label="centre of mass")
    edge = float((mesh.vertices[mesh.vertices[:, 2] < 1e-6] @ normal).max())
    axes.axvline(edge, color="#7f8c8d", lw=1, ls=":", label="edge of the plinth")
    axes.set_aspect("equal")
    axes.set_xlabel("mm, along the lean")
    axes.set_ylabel("mm, up")
    axes.set_title(title, fontsize=10)
    axes.legend(loc="upper left", fontsize=8, frameon=False)
    figure.tight_layout()
    figure.savefig(picture, dpi=110)
    plt.close(figure)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--margin", type=float, default=3.0, help="mm (default 3)")
    args = parser.parse_args()
    triangles = figurine_triangles("capsule", 1, 1.0, 128)
    with open(MODEL, "wb") as handle:
        handle.write(stl_bytes(triangles, "leaning figurine", 1e-3))
    print(f"{MODEL}: {len(triangles)} triangles")
    common = ["--units", "mm", "--density", "1200"]
    cli(["check", MODEL, *common])
    with tempfile.TemporaryDirectory() as folder:
        carved = os.path.join(folder, "carved.stl")
        start = time.perf_counter()
        cli(["balance", MODEL, *common, "--wall", "2mm", "--margin", f"{args.margin}mm",
             "--out", carved])
        print(f"balance took {time.perf_counter() - start:.1f} s")
        cli(["balance", MODEL, *common, "--wall", "2mm", "--margin", "5mm", "--out", carved])
        cli(["check", carved, *common])
        from plumbob import load
        from plumbob.balance.hollow import hollow
        from plumbob.balance.targets import target_for

        body = load(MODEL, units="mm", density=1200)
        plan = hollow(body, wall=2e-3, target=target_for(body, margin=args.margin * 1e-3))
        normal = np.array([plan.cut.normal[0], plan.cut.normal[1], 0.0])
        normal /= np.linalg.norm(normal)
        section(MODEL, normal, "as modelled: it topples",
                os.path.join(PICTURES, "hollow_before.png"))
        section(carved, normal, f"carved, 2 mm walls: it stands with a {args.margin:g} mm margin",
                os.path.join(PICTURES, "hollow_after.png"))


if __name__ == "__main__":
    main()
