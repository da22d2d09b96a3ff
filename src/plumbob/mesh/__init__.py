"""Triangle meshes on their own: welding, topology, closure, repair, shells, the solid check.

The closure rule is :mod:`plumbob.mesh.closure`'s: a surface is closed when no loop
of its unshared edges spans an area, once copies of a vertex closer than
:data:`plumbob.tolerances.WELD` of the size are welded (:mod:`plumbob.mesh.weld`).

These functions take any triangle soup — an ``(n, 3, 3)`` array of corners in
metres, as a reader, a generator or a user's own code makes it — and need
nothing from files or bodies. The readers in :mod:`plumbob.formats` call
:func:`check_solid` on every mesh; call it yourself to check a mesh before
you build a :class:`~plumbob.bodies.solid.MeshSolid` from it.

Everything is vectorised over triangles; only shells (usually a handful) are
visited one by one. Nothing here imports shapely, trimesh or scipy;
manifold3d is imported only to unite overlapping shells.

Examples
--------
>>> import numpy as np
>>> from plumbob import mesh
>>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
>>> tetra = v[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]
>>> mesh.surface_summary(tetra).closed
True
>>> checked = mesh.check_solid(tetra[:, ::-1])
>>> checked.notices
('inside out: its faces pointed inward; turned outward',)
>>> mesh.check_solid(tetra[:3], repair=True)  # the hole is most of the surface
Traceback (most recent call last):
...
plumbob.errors.GeometryError: is open with a hole too large to close safely (3 boundary edges, \
58% of the surface) near (0.333333, 0.333333, 0.333333): close it in a mesh editor
"""

from __future__ import annotations

from typing import TYPE_CHECKING as _TYPE_CHECKING

from ..arrays import connected_components
from ..lazy import lazy_exports as _lazy_exports
from .closure import (
    CLOSURE_TOLERANCE,
    Holes,
    SurfaceSummary,
    edges_pair,
    holes,
    is_closed,
    require_closed,
    surface_summary,
)
from .solid import FULL_CHECK_LIMIT, CheckedSolid, check_solid
from .weld import merge_vertices, weld_near

if _TYPE_CHECKING:  # for readers and type checkers; at run time see __getattr__
    from .repair import HOLE_AREA_FRACTION, fill_holes
    from .shells import resolve_shells, unite_shells
    from .topology import Topology, mesh_topology
    from .winding import solid_angle, solid_angles, winding_numbers

__all__ = [
    "CLOSURE_TOLERANCE",
    "FULL_CHECK_LIMIT",
    "HOLE_AREA_FRACTION",
    "CheckedSolid",
    "Holes",
    "SurfaceSummary",
    "Topology",
    "check_solid",
    "connected_components",
    "edges_pair",
    "fill_holes",
    "holes",
    "is_closed",
    "merge_vertices",
    "mesh_topology",
    "require_closed",
    "resolve_shells",
    "solid_angle",
    "solid_angles",
    "surface_summary",
    "unite_shells",
    "weld_near",
    "winding_numbers",
]

#: public name → the module (of this package) that defines it, imported on first use: a
#: large mesh whose edges pair (the check's cheap tests) never builds its topology, so
#: reading one loads neither the topology nor the repair and shell code
_LAZY = {
    **dict.fromkeys(("HOLE_AREA_FRACTION", "fill_holes"), ".repair"),
    **dict.fromkeys(("resolve_shells", "unite_shells"), ".shells"),
    **dict.fromkeys(("Topology", "mesh_topology"), ".topology"),
    **dict.fromkeys(("solid_angle", "solid_angles", "winding_numbers"), ".winding"),
}

__getattr__, __dir__ = _lazy_exports(__name__, _LAZY, __all__)
