"""How a triangle soup's faces connect: shared edges, winding, shells, boundary.

Everything is vectorised over faces and edges: edges are paired by sorting
their vertex keys, and graph components are found by hooking and pointer
jumping (:func:`connected_components`) — no Python loop over triangles.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..arrays import connected_components, stable_order
from .weld import merge_vertices, weld_near

__all__ = ["connected_components", "Topology", "mesh_topology"]


class Topology(NamedTuple):
    """How a triangle soup's faces connect.

    vertices: (V, 3) m, merged exact copies. faces: (n, 3) indices, winding as read.
    flip: (n,) bool, faces wound against the rest of their shell (to be turned).
    shell: (n,) shell label 0..shells-1 (faces joined through shared edges, however many
        faces share each).
    boundary: (b, 2) boundary half-edges (vertex indices), directed as in the
        turned faces, each paired with the face it belongs to in ``boundary_face``.
    nonmanifold: edges shared by more than two faces.
    orientable: False when a shell cannot be wound consistently (a Möbius strip).
    welded: vertices merged with a nearby one that was not an exact copy;
        weld_distance: the largest distance such a vertex moved, m.
    """

    vertices: np.ndarray
    faces: np.ndarray
    flip: np.ndarray
    shell: np.ndarray
    shells: int
    boundary: np.ndarray
    boundary_face: np.ndarray
    nonmanifold: int
    orientable: bool
    welded: int = 0
    weld_distance: float = 0.0

    @property
    def oriented_faces(self) -> np.ndarray:
        """The faces (n, 3) with those in ``flip`` turned: each shell wound one way."""
        faces = self.faces.copy()
        faces[self.flip] = faces[self.flip][:, ::-1]
        return faces

    def boundary_loops(self) -> np.ndarray:
        """Label 0..holes-1 of each boundary edge: the hole (loop of edges) it lies on."""
        edges = self.boundary
        loop_of_vertex = connected_components(len(self.vertices), edges[:, 0], edges[:, 1])
        return np.unique(loop_of_vertex[edges[:, 0]], return_inverse=True)[1].reshape(-1)


def mesh_topology(triangles: np.ndarray, tolerance: float = 0.0) -> Topology:
    """Merge vertices, pair edges, make winding consistent and find shells and boundary edges.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray
        A triangle soup, any float dtype.
    tolerance : float
        m; vertices on unshared edges closer than this are welded (copies an exporter
        wrote with different round-off). 0: only exact copies merge.

    Returns
    -------
    Topology

    Examples
    --------
    A tetrahedron with one face wound the wrong way, and the same without that face:

    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = v[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 3, 2]]]
    >>> topo = mesh_topology(tetra)
    >>> topo.shells, topo.orientable, topo.flip.tolist(), len(topo.boundary)
    (1, True, [False, False, False, True], 0)
    >>> open_topo = mesh_topology(tetra[:3])
    >>> len(open_topo.boundary), int(open_topo.boundary_loops().max()) + 1
    (3, 1)
    """
    n = len(triangles)
    vertices, index = merge_vertices(triangles.reshape(-1, 3))
    faces = index.reshape(n, 3).astype(np.int64)
    welded, moved = 0, 0.0
    pairing = _pair_edges(faces, len(vertices))
    if tolerance > 0 and len(pairing.single):
        faces, welded, moved = _weld_boundary(vertices, faces, pairing, tolerance)
        if welded:
            pairing = _pair_edges(faces, len(vertices))
    half, owner, order, skey, starts, counts = (pairing.half, pairing.owner, pairing.order,
                                                pairing.skey, pairing.starts, pairing.counts)
    pairs = starts[counts == 2]
    h1, h2 = order[pairs], order[pairs + 1]
    f1, f2 = owner[h1], owner[h2]
    same_direction = half[h1, 0] == half[h2, 0]  # the two faces disagree on winding
    if same_direction.any():
        flip, orientable = _winding(n, f1, f2, same_direction)
    else:  # wound consistently already (the common case): nothing to turn
        flip, orientable = np.zeros(n, dtype=bool), True
    # Shells: faces joined through any shared edge (also where more than two meet, as
    # when two cubes share a face), so a shell is a closed surface on its own.
    same_edge = np.flatnonzero(skey[1:] == skey[:-1])
    u, v = owner[order[same_edge]], owner[order[same_edge + 1]]
    if len(owner) < 3 * n:  # faces without area join a face at one of their corners
        at = np.full(len(vertices), -1)
        at[faces[owner[::3]]] = owner[::3, None]
        degenerate = np.setdiff1d(np.arange(n), owner[::3])
        host = at[faces[degenerate]].max(axis=1)
        u, v = np.r_[u, degenerate[host >= 0]], np.r_[v, host[host >= 0]]
    shell = connected_components(n, u, v)
    single = pairing.single
    boundary = half[single]
    boundary_face = owner[single]
    turned = flip[boundary_face]
    boundary[turned] = boundary[turned][:, ::-1]
    return Topology(vertices, faces, flip, shell, int(shell.max()) + 1 if n else 0,
                    boundary, boundary_face, int(np.count_nonzero(counts > 2)), orientable,
                    welded, moved)


def _winding(n: int, f1: np.ndarray, f2: np.ndarray, same_direction: np.ndarray
             ) -> tuple[np.ndarray, bool]:
    """Which of ``n`` faces to turn so that each shell is wound one way, and whether that
    is possible, given the face pairs ``f1``–``f2`` sharing an edge and whether the two
    run that edge the same way.

    Each face is two nodes, f (as wound) and f + n (turned); a shared edge joins the
    nodes that agree. A shell is then two components, one per orientation; a face is
    turned when fewer of its shell's faces lie, as wound, in the component of its turned
    node than in that of its own (on a tie, the later labelled is turned). Where no pair
    runs an edge the same way no face as wound shares a component with a turned node,
    and nothing is turned.
    """
    a = np.where(same_direction, f2 + n, f2)
    b = np.where(same_direction, f2, f2 + n)
    labels = connected_components(2 * n, np.r_[f1, f1 + n], np.r_[a, b])
    plus, minus = labels[:n], labels[n:]
    orientable = not bool(np.any(plus == minus))
    weight = np.bincount(plus, minlength=2 * n)
    flip = (weight[plus] < weight[minus]) | ((weight[plus] == weight[minus]) & (plus > minus))
    return flip, orientable


class _Pairing(NamedTuple):
    """Half-edges (h, 2) of the non-degenerate faces, their faces, and their sort by edge."""

    half: np.ndarray
    owner: np.ndarray
    order: np.ndarray
    skey: np.ndarray
    starts: np.ndarray
    counts: np.ndarray

    @property
    def single(self) -> np.ndarray:
        """Half-edges no other face shares: the boundary."""
        return self.order[self.starts[self.counts == 1]]


def _pair_edges(faces: np.ndarray, nv: int) -> _Pairing:
    """Sort the half-edges by their undirected edge. Faces with a repeated vertex (no area)
    share no edge: they would otherwise pair with themselves."""
    n = len(faces)
    proper = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & \
        (faces[:, 2] != faces[:, 0])
    half = faces[proper][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    owner = np.repeat(np.arange(n)[proper], 3)
    key = np.minimum(half[:, 0], half[:, 1]) * nv + np.maximum(half[:, 0], half[:, 1])
    order = stable_order(key)
    skey = key[order]
    starts = np.flatnonzero(np.r_[True, skey[1:] != skey[:-1]]) if len(skey) else \
        np.zeros(0, dtype=np.int64)
    counts = np.diff(np.r_[starts, len(skey)])
    return _Pairing(half, owner, order, skey, starts, counts)


def _weld_boundary(vertices: np.ndarray, faces: np.ndarray, pairing: _Pairing,
                   tolerance: float) -> tuple[np.ndarray, int, float]:
    """Faces with the boundary vertices closer than ``tolerance`` welded; how many
    vertices were merged, and the largest distance one moved (m).

    Only vertices on unshared edges can be copies that failed to merge (every edge
    at a copy is unshared), so only they are compared: a handful, not the mesh."""
    ends = np.unique(pairing.half[pairing.single].ravel())
    group = weld_near(vertices[ends], tolerance)
    _, first = np.unique(group, return_index=True)
    target = ends[first[group]]
    moved = target != ends
    if not moved.any():
        return faces, 0, 0.0
    remap = np.arange(len(vertices))
    remap[ends] = target
    distance = float(np.linalg.norm(vertices[ends[moved]] - vertices[target[moved]], axis=1).max())
    return remap[faces], int(moved.sum()), distance
