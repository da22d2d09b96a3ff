"""The interior of a body cut into cells: what hollowing chooses from.

Why cells: the moment of the weight about the support is linear in the material
kept, so once the interior is cut into pieces, each with its own mass and centre,
choosing which to empty is a small linear problem (:mod:`plumbob.balance.hollow`).

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

__all__ = ["GridCells", "box_union", "grid_cells", "manifold_rows"]


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
    them with their slot (0 below the first plane), empty ones dropped."""
    normal = np.zeros(3)
    normal[axis] = 1.0
    pieces, rest = [], manifold
    for slot, plane in enumerate(planes):
        if rest.is_empty():
            return pieces
        above, below = rest.split_by_plane(normal.tolist(), float(plane))
        if not below.is_empty():
            pieces.append((slot, below))
        rest = above
    if not rest.is_empty():
        pieces.append((len(planes), rest))
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


#: the six faces of a unit cube: outward direction and corners (counter-clockwise seen
#: from outside), as offsets of the cell's low corner in the lattice
_FACES = (
    ((-1, 0, 0), ((0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0))),
    ((1, 0, 0), ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1))),
    ((0, -1, 0), ((0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1))),
    ((0, 1, 0), ((0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0))),
    ((0, 0, -1), ((0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0))),
    ((0, 0, 1), ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))),
)


def box_union(cells: GridCells, chosen: np.ndarray):
    """The union of the chosen cells' grid boxes, a manifold3d ``Manifold`` built face by
    face: the faces between a chosen cell and one that is not, on the lattice's shared
    corners. No boolean of touching boxes is computed (those leave coincident slivers),
    and a well-composed choice (:func:`manifold_rows`) makes the result a 2-manifold.
    Intersected with the interior it is the union of the chosen cells.

    >>> import manifold3d
    >>> cells = grid_cells(manifold3d.Manifold.cube([2.0, 1.0, 1.0]), 0.5)
    >>> union = box_union(cells, cells.index[:, 0] >= 2)   # the half where x ≥ 1
    >>> union.status().name, round(union.volume(), 12)     # half a cell out beyond the box
    ('NoError', 2.8125)
    """
    import manifold3d

    picked = cells.index[chosen]
    shape = tuple(int(v) + 3 for v in cells.index.max(axis=0))
    flags = np.zeros(shape, dtype=bool)
    flags[tuple((picked + 1).T)] = True  # shifted by one: every neighbour index is valid
    quads = []
    for direction, corners in _FACES:
        neighbour = flags[tuple((picked + 1 + np.array(direction)).T)]
        base = picked[~neighbour]
        quads.append(base[:, None, :] + np.array(corners)[None])  # (m, 4, 3) lattice indices
    quads = np.concatenate(quads)
    keys, index = np.unique(quads.reshape(-1, 3), axis=0, return_inverse=True)
    verts = np.stack([cells.lattice[k][keys[:, k]] for k in range(3)], axis=1)
    q = index.reshape(-1, 4)
    tris = np.concatenate((q[:, [0, 1, 2]], q[:, [0, 2, 3]]))
    # Mesh64: manifold3d's Mesh would round the lattice's corners to float32
    mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(verts, dtype=np.float64),
                             tri_verts=tris.astype(np.uint32))
    return manifold3d.Manifold(mesh)


def manifold_rows(cells: GridCells):
    """Linear rows ``A x ≤ b`` (a sparse ``A``) that keep the emptied cells' union — and so
    the carved body — a 2-manifold: no two emptied cells (nor two kept ones) touching
    only along an edge or at a corner.

    Why: a set of grid cells has a manifold boundary iff it is *well-composed*
    (Latecki): no 2 × 2 square of cells holds a diagonal pair alone, and no 2 × 2 × 2
    block holds two opposite corners alone (or all but them). With ``x`` the emptied
    flags, and cells outside the interior never emptied, these read: for a square
    ``a b / c d``, ``x_a + x_d − x_b − x_c ≤ 1`` (and with the diagonals swapped); for
    a block's diagonal ``(p, q)`` and its other six cells ``O``, ``x_p + x_q − Σ_O x ≤ 1``
    and ``Σ_O x − x_p − x_q ≤ 5``.

    >>> import manifold3d
    >>> a, b = manifold_rows(grid_cells(manifold3d.Manifold.cube([1.0, 1.0, 0.5]), 0.5))
    >>> a.shape, b.tolist()   # one 2 × 2 square: two rows
    ((2, 4), [1.0, 1.0])
    """
    from scipy.sparse import coo_matrix

    n = len(cells)
    shape = cells.index.max(axis=0) + 2 if n else np.ones(3, dtype=np.int64)
    ids = np.full(tuple(int(v) + 1 for v in shape), -1, dtype=np.int64)
    ids[tuple(cells.index.T)] = np.arange(n)
    bases = np.stack(np.meshgrid(*(np.arange(-1, int(v)) for v in shape - 1), indexing="ij"),
                     axis=-1).reshape(-1, 3)
    corners = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)])
    block = ids[tuple((bases[:, None, :] + corners[None]).transpose(2, 0, 1))]  # (m, 8)
    rows, cols, vals, limits = [], [], [], []

    def add(positive: np.ndarray, negative: np.ndarray, limit: float, need: str) -> None:
        """Rows Σ x_positive − Σ x_negative ≤ limit over blocks; ``need``: the rows that can
        bind are those whose positive cells all exist."""
        live = np.all(positive >= 0, axis=1)
        if need == "all":
            live &= np.all(negative >= 0, axis=1)
        positive, negative = positive[live], negative[live]
        start = len(limits)
        for group, sign in ((positive, 1.0), (negative, -1.0)):
            r = np.repeat(np.arange(start, start + len(group)), group.shape[1])
            c = group.reshape(-1)
            keep = c >= 0
            rows.append(r[keep])
            cols.append(c[keep])
            vals.append(np.full(int(keep.sum()), sign))
        limits.extend([limit] * len(positive))

    flat = {tuple(c): i for i, c in enumerate(corners.tolist())}
    for axis in range(3):  # the squares in the planes across each axis, at the block's low side
        u, v = [a for a in range(3) if a != axis]
        sq = []
        for du, dv in ((0, 0), (1, 0), (0, 1), (1, 1)):
            c = [0, 0, 0]
            c[u], c[v] = du, dv
            sq.append(flat[tuple(c)])
        a, b, c, d = (block[:, s] for s in sq)
        add(np.stack((a, d), 1), np.stack((b, c), 1), 1.0, "positive")
        add(np.stack((b, c), 1), np.stack((a, d), 1), 1.0, "positive")
    for corner in range(4):  # the block's four diagonals
        p, q = corner, 7 - corner
        others = [i for i in range(8) if i not in (p, q)]
        add(block[:, [p, q]], block[:, others], 1.0, "positive")
        add(block[:, others], block[:, [p, q]], 5.0, "all")
    matrix = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                        shape=(len(limits), n)).tocsr()
    return matrix, np.array(limits)
