"""Connected components of a graph given as edge lists, without scipy.

Used to find shells (faces joined through shared edges), holes (loops of
boundary edges), welded clusters of near vertices and chains of drawing segments.
"""

from __future__ import annotations

import numpy as np

__all__ = ["connected_components"]


def connected_components(n: int, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Component labels of a graph on nodes ``0..n-1`` with edges ``u[i]–v[i]``.

    Vectorised hooking and pointer jumping: as fast as scipy's, without scipy.

    Parameters
    ----------
    n : int
        Number of nodes.
    u, v : (e,) array_like of int
        The edges' ends.

    Returns
    -------
    (n,) int ndarray
        Label ``0..k-1`` of each node's component, numbered in the order of
        each component's smallest node.

    Examples
    --------
    >>> connected_components(5, [0, 3], [1, 4]).tolist()
    [0, 0, 1, 2, 2]
    >>> connected_components(3, [], []).tolist()  # no edges: every node alone
    [0, 1, 2]
    """
    parent = np.arange(n)
    u = np.asarray(u, dtype=np.int64)
    v = np.asarray(v, dtype=np.int64)
    while len(u):
        pu, pv = parent[u], parent[v]
        live = pu != pv
        if not live.any():
            break
        u, v, pu, pv = u[live], v[live], pu[live], pv[live]
        np.minimum.at(parent, np.maximum(pu, pv), np.minimum(pu, pv))
        while True:  # point every node at its root
            grand = parent[parent]
            if np.array_equal(grand, parent):
                break
            parent = grand
    return np.unique(parent, return_inverse=True)[1].reshape(-1)
