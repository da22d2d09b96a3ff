"""A :class:`~plumbob.bodies.solid.MeshSolid` from a file's triangles, checked.

The mesh checks themselves (closure, winding, shells, repair) are
:func:`plumbob.mesh.check_solid`'s and name no file; here their errors get
the file's path, and the reader-side size check is added.
"""

from __future__ import annotations

import numpy as np

from ..bodies.solid import MeshSolid
from ..errors import GeometryError, PlumbobError
from ..mesh.solid import check_solid
from .checks import check_extent

__all__ = ["mesh_solid"]


def mesh_solid(triangles: np.ndarray, *, path: str | None = None, name: str | None = None,
               repair: bool = False, label: str | None = None, scale: float = 1.0,
               extent: bool = False, assumed: bool = False) -> tuple[MeshSolid, tuple[str, ...]]:
    """A :class:`MeshSolid` from a triangle soup (n, 3, 3) in metres, checked and fixed.

    See :func:`plumbob.mesh.check_solid` for ``repair``, ``label`` and ``scale``;
    errors name ``path``. ``extent`` adds the implausible-size check on the
    mesh's bounding box (:func:`~plumbob.formats.checks.check_extent`), for readers
    that did not find the box while parsing; ``assumed``: the file has no unit and
    metres were assumed (see :func:`~plumbob.formats.checks.check_extent`).
    """
    try:
        checked = check_solid(triangles, repair=repair, label=label, scale=scale)
    except PlumbobError as error:
        raise type(error)(error.message, path=path) from None
    notices = check_extent(checked.surface.lo, checked.surface.hi, path=path,
                           assumed=assumed) if extent else ()
    try:
        body = MeshSolid(checked.triangles, name=name, moments=checked.moments, checked=True,
                         vertices=checked.vertices, index=checked.index, keys=checked.keys)
    except PlumbobError as error:
        raise GeometryError(error.message, path=path) from None
    return body, notices + checked.notices
