"""Regenerate the pictures in docs/pictures/ from the seed's examples, through the CLI.

    python docs/make_pictures.py

Each picture is made exactly as a user makes it (``plumbob ... --plot FILE``), so the
documentation shows what the commands draw today. Run it after changing anything under
``src/plumbob/plot/`` and look at the results.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "src"))

from plumbob.cli import main  # noqa: E402

SHAPES = os.path.join(ROOT, "shapes")
OUT = os.path.join(HERE, "pictures")
STL = os.path.join(HERE, "models", "featuretype.stl")

PICTURES = [
    # (picture, command line)
    ("sculpture_check.png", ["check", os.path.join(SHAPES, "sculpture.toml"), "--require-tilt", "10"]),
    ("sculpture_mass.png", ["mass", os.path.join(SHAPES, "sculpture.toml")]),
    ("stepped_cylinder_check.png", ["check", os.path.join(SHAPES, "stepped_cylinder.toml")]),
    ("stepped_cylinder_poses.png", ["poses", os.path.join(SHAPES, "stepped_cylinder.toml")]),
    ("l_shape_mass.png", ["mass", os.path.join(SHAPES, "l_shape.toml")]),
    ("l_shape_poses.png", ["poses", os.path.join(SHAPES, "l_shape.toml")]),
    ("mace_assembly_mass.png", ["mass", os.path.join(SHAPES, "mace_assembly.toml")]),
    ("pyramid_lift.png", ["lift", os.path.join(SHAPES, "pyramid_cheops.toml")]),
    ("featuretype_poses.png", ["poses", STL, "--units", "in", "--material", "aluminium"]),
    ("featuretype_check.png", ["check", STL, "--units", "in", "--material", "aluminium",
                               "--require-tilt", "10"]),
]


def make(names: list[str] | None = None) -> list[str]:
    """Write the pictures (all, or those named) and return their paths."""
    os.makedirs(OUT, exist_ok=True)
    written = []
    for name, command in PICTURES:
        if names and name not in names:
            continue
        target = os.path.join(OUT, name)
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            status = main([*command, "--plot", target])
        if status not in (0, 1):  # 1: a design check that fails is still a picture
            raise SystemExit(f"plumbob {' '.join(command)} failed with status {status}")
        written.append(target)
        print(os.path.relpath(target, ROOT))
    return written


if __name__ == "__main__":
    make(sys.argv[1:] or None)
