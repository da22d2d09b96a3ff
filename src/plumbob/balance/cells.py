"""The interior of a body cut into cells: the variables of hollowing's relaxation.

Why cells: the moment of the weight about the support is linear in the material
kept, so once the interior is cut into pieces, each with its own mass and centre,
the best fractions of them to empty are a linear program
(:mod:`plumbob.balance.relax`).

The cells are the interior (a manifold3d ``Manifold``) sliced by the planes of a
regular grid — slabs along x, each cut into columns along y, each into cells
along z — so every cell is an exact piece of the interior (a cube deep inside,
a cube clipped by the interior's surface near the walls) and together they tile
it without gaps or overlaps.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..integrals.mesh import triangle_soup_moments
from ..limits import MAX_PARTS, check_count

__all__ = ["GridCells", "grid_cells"]


@dataclass(frozen=True, eq=False)
class GridCells:
    """Pieces of a body's interior.

    pieces: the cells, manifold3d ``Manifold`` objects.
    volumes: (n,) m³. centres: (n, 3) m, each cell's centroid.
    size: m, the grid's cell size.
    index: (n, 3) int, each cell's place in the grid.
    lattice: per axis, the grid planes (counts + 1,) m: the cuts, and beyond the
        interior's bounding box a plane half a cell out on each side.
    """

    pieces: tuple
    volumes: np.ndarray
    centres: np.ndarray
    size: float
    index: np.ndarray
    lattice: tuple[np.ndarray, ...] = ()

    def __len__(self) -> int:
        return len(self.pieces)


def _slices(manifold, axis: int, planes: np.ndarray) -> list[tuple[int, object]]:
    """``manifold`` cut by the planes ``x[axis] = planes`` (ascending): the pieces between
    them with their slot (0 below the first plane), empty ones dropped. Halved at the
    middle plane, then each half again: each triangle is cut ~log₂(planes) times, not
    once per plane below it."""
    normal = np.zeros(3)
    normal[axis] = 1.0
    pieces: list[tuple[int, object]] = []

    def cut(part, first: int, last: int) -> None:
        """``part`` lies between planes ``first − 1`` and ``last`` (slots first..last)."""
        if part.is_empty():
            return
        if first == last:
            pieces.append((first, part))
            return
        middle = (first + last) // 2  # plane ``middle`` parts slots ≤ middle from the rest
        above, below = part.split_by_plane(normal.tolist(), float(planes[middle]))
        cut(below, first, middle)
        cut(above, middle + 1, last)

    cut(manifold, 0, len(planes))
    return pieces


def grid_cells(interior, size: float) -> GridCells:
    """The interior (a manifold3d ``Manifold``) cut into cells of a ``size`` m grid.

    Parameters
    ----------
    interior : manifold3d.Manifold
    size : float
        m, the grid's cell edge.

    Returns
    -------
    GridCells

    Examples
    --------
    >>> import manifold3d
    >>> cells = grid_cells(manifold3d.Manifold.cube([2.0, 1.0, 1.0]), 0.5)
    >>> len(cells), round(float(cells.volumes.sum()), 12), cells.index.max(axis=0).tolist()
    (16, 2.0, [3, 1, 1])
    """
    lower, upper = (np.asarray(v, dtype=float) for v in
                    (interior.bounding_box()[:3], interior.bounding_box()[3:]))
    counts = np.maximum(1, np.ceil((upper - lower) / size - 1e-9)).astype(np.int64)
    check_count("hollowing cells", float(np.prod(counts.astype(float))), MAX_PARTS,
                hint="give a larger cell size")
    planes = [lower[k] + size * np.arange(1, counts[k]) for k in range(3)]
    pieces: list[tuple[tuple[int, ...], object]] = [((), interior)]
    for axis in range(3):
        pieces = [(slot + (i,), cut) for slot, piece in pieces
                  for i, cut in _slices(piece, axis, planes[axis])]
    volumes, centres, kept, index = [], [], [], []
    for slot, piece in pieces:
        mesh = piece.to_mesh64()
        verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
        tri = verts[np.asarray(mesh.tri_verts, dtype=np.int64)]
        m = triangle_soup_moments(tri)
        if m.m0 > 0:
            kept.append(piece)
            index.append(slot)
            volumes.append(m.m0)
            centres.append(m.origin + m.m1 / m.m0)
    lattice = tuple(np.concatenate(([lower[k] - size / 2], planes[k], [upper[k] + size / 2]))
                    for k in range(3))
    return GridCells(tuple(kept), np.array(volumes), np.array(centres).reshape(-1, 3), float(size),
                 np.array(index, dtype=np.int64).reshape(-1, 3), lattice)
