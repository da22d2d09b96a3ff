"""Closing small holes in a mesh, and refusing to guess at large ones.

A hole (a loop of boundary edges) is closed by a fan of triangles from the
centroid of its loop: exact for a planar convex hole, a small smooth cap
otherwise. Only holes whose patch is a small share of the surface
(:data:`HOLE_AREA_FRACTION`) are closed; a larger one is a missing part
that no rule can invent, and is an error naming where it is.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError, fmt_point
from .topology import Topology

__all__ = ["HOLE_AREA_FRACTION", "fill_holes"]

#: a hole is closed when its patch is at most this share of the surface
HOLE_AREA_FRACTION = 0.05


def fill_holes(topo: Topology, faces: np.ndarray, shell: np.ndarray, total_area: float,
               *, label: str = "", scale: float = 1.0
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, str]:
    """Close every boundary loop of ``topo`` with a fan from its centroid (a new vertex).

    Parameters
    ----------
    topo : Topology
        The mesh's topology; its vertices and boundary edges are used.
    faces : (n, 3) int ndarray
        The faces, consistently wound (``topo.oriented_faces``).
    shell : (n,) int ndarray
        Each face's shell label; the patch faces join the shell of their hole's edges.
    total_area : float
        The surface's area, m², that patches are compared with.
    label : str
        Prefix naming the body in messages (``"solid 'lid': "``), or ``""``.
    scale : float
        Metres per unit of the coordinates that messages name points in.

    Returns
    -------
    vertices, faces, shell : ndarray
        The mesh with the patches added (one new vertex per hole).
    notice : str
        What was closed, for the user.

    Raises
    ------
    GeometryError
        When a hole's patch exceeds :data:`HOLE_AREA_FRACTION` of ``total_area``.

    Examples
    --------
    A cube of twelve triangles without one of them: the missing half of a side is
    one 24th of the surface, closed for a surface of 12 m² but not of 6 m²:

    >>> import numpy as np
    >>> from plumbob.mesh.topology import mesh_topology
    >>> v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4),
    ...          (1, 5, 7, 3)]
    >>> faces = np.array([f for a, b, c, d in quads for f in ((a, b, c), (a, c, d))])
    >>> topo = mesh_topology(v[faces[1:]])
    >>> _, patched, _, notice = fill_holes(topo, topo.oriented_faces, topo.shell, 12.0)
    >>> len(patched)
    14
    >>> notice
    'repair: closed 1 hole (3 boundary edges) near (0, 0.333333, 0.666667), adding 0.5 m² of surface'
    >>> fill_holes(topo, topo.oriented_faces, topo.shell, 6.0)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: is open with a hole too large to close safely (3 boundary \
edges, 8% of the surface) near (0, 0.333333, 0.666667): close it in a mesh editor
    """
    edges = topo.boundary
    nv = len(topo.vertices)
    loop = topo.boundary_loops()
    loops = int(loop.max()) + 1
    start = topo.vertices[edges[:, 0]]
    size = np.bincount(loop, minlength=loops)
    centre = np.stack([np.bincount(loop, start[:, i], loops) for i in range(3)], axis=1)
    centre /= size[:, None]
    new_faces = np.stack((edges[:, 1], edges[:, 0], nv + loop), axis=1)
    vertices = np.concatenate((topo.vertices, centre))
    tri = vertices[new_faces]
    patch = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1) / 2
    patch_area = np.bincount(loop, patch, loops)
    too_big = patch_area > HOLE_AREA_FRACTION * total_area
    if too_big.any():
        worst = int(np.argmax(patch_area))
        raise GeometryError(
            f"{label}is open with a hole too large to close safely ({size[worst]} boundary edges, "
            f"{patch_area[worst] / total_area:.0%} of the surface) near "
            f"{fmt_point(centre[worst] / scale)}: close it in a mesh editor")
    notice = (f"repair: closed {loops} hole{'s' if loops > 1 else ''} ({len(edges)} boundary "
              f"edges) near {fmt_point(centre[np.argmax(patch_area)] / scale)}, adding "
              f"{patch_area.sum():.4g} m² of surface")
    return (vertices, np.concatenate((faces, new_faces)),
            np.concatenate((shell, shell[topo.boundary_face])), f"{label}{notice}")
