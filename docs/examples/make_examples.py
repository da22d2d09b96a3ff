"""Write the mesh files the commands in README.md and docs/ read.

The docs show commands on ``part.stl``, ``box.stl``, ``figurine.stl`` and the like;
this script makes each of them from plumbob's exact primitives, so every command a
page shows can be run as it stands (``tests/test_docs_commands.py`` runs them all):

    python docs/examples/make_examples.py            # writes them into the current folder
    python docs/examples/make_examples.py FOLDER

The files (binary STL, no unit inside, as most exports are):

* ``part.stl``   an L-bracket in mm: a 60 × 40 × 8 foot, a 8 × 40 × 50 upright, a
  10 mm hole through the foot;
* ``box.stl``    a 0.4 × 0.3 × 1.2 m cabinet-sized box, in metres;
* ``cube.stl``   a 20 mm cube, in mm;
* ``figurine.stl`` the leaning figurine of docs/printing.md, in mm: a 36 × 36 × 12
  plinth, a body (radius 9, 55 long) leaning 58° from a foot 6 mm off centre, a head
  of radius 11 (as a solid it topples);
* ``l-block.stl`` a 3 × 1 × 1 bar with a 1 × 1 × 1 block on one end, in metres.

and the small specs whose errors docs/shapes.md and docs/density.md show
(``x.toml``, ``y.toml``, ``z.toml``, ``negative.toml``).
"""

from __future__ import annotations

import os
import sys

import numpy as np

MM = 1e-3


def _bodies() -> dict:
    from plumbob import difference, union
    from plumbob.bodies.primitives import box, cylinder, sphere

    lean = _rotation_y(np.radians(58))
    foot = np.array([6 * MM, 0, 8 * MM])
    figurine = union(
        box(36 * MM, 36 * MM, 12 * MM).translated([-18 * MM, -18 * MM, 0]),
        cylinder(9 * MM, 55 * MM).transformed(lean, foot),
        sphere(11 * MM).translated(lean @ np.array([0, 0, 55 * MM]) + foot),
    )
    bracket = difference(
        union(box(60 * MM, 40 * MM, 8 * MM), box(8 * MM, 40 * MM, 50 * MM)),
        cylinder(5 * MM, 20 * MM).translated([35 * MM, 20 * MM, -5 * MM]),
    )
    return {
        "part.stl": (bracket, MM),
        "box.stl": (box(0.4, 0.3, 1.2), 1.0),
        "cube.stl": (box(20 * MM, 20 * MM, 20 * MM), MM),
        "figurine.stl": (figurine, MM),
        "l-block.stl": (union(box(3, 1, 1), box(1, 1, 2)), 1.0),
    }


#: specs with a mistake each, for the error messages the docs show
SPECS = {
    "x.toml": '[[part]]\ntype = "box"\nwidht = 1\nlength = 1\nheight = 1\n',
    "y.toml": '[[part]]\ntype = "sphere"\nradius = "__import__(\'os\')"\n',
    "z.toml": '[[part]]\ntype = "box"\nlength = 1\nwidth = 1\nheight = 1\ncentered = "no"\n',
    "negative.toml": '[shape]\ndensity = "x - 0.25"\n\n[[part]]\ntype = "cube"\nside = 1\n',
}


def _rotation_y(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def make_examples(folder: str = ".") -> list[str]:
    """Write every example file into ``folder``; returns their paths."""
    from plumbob.formats.writers import stl_bytes

    os.makedirs(folder, exist_ok=True)
    written = []
    for name, (body, unit) in _bodies().items():
        path = os.path.join(folder, name)
        with open(path, "wb") as handle:
            handle.write(stl_bytes(body.surface().triangles, os.path.splitext(name)[0], unit))
        written.append(path)
    for name, text in SPECS.items():
        path = os.path.join(folder, name)
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(text)
        written.append(path)
    return written


if __name__ == "__main__":
    for written_path in make_examples(sys.argv[1] if len(sys.argv) > 1 else "."):
        print(f"wrote {written_path}")
