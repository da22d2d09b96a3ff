"""Placed poses as mesh files: the body set down in each pose, ready to print or show.

:func:`export_poses` writes, for each pose, the body's surface moved by the pose's
``transform`` (resting on z = 0, centre of mass above the origin) to
``pose-01-p0.4123.stl`` (rank, then probability) in a folder, through
:func:`plumbob.formats.writers.write_mesh`: binary STL in the length unit the body was
read in, or 3MF, which states its unit; each file whole or not at all.
"""

from __future__ import annotations

import os

import numpy as np

from ..errors import GeometryError, PlumbobError
from ..formats.writers import MESH_FORMATS, mesh_unit, write_mesh

__all__ = ["FORMATS", "body_triangles", "export_poses"]

FORMATS = MESH_FORMATS


def body_triangles(body) -> np.ndarray:
    """The body's surface as triangles (n, 3, 3), m: a mesh's own triangles, else the
    boolean-geometry surface of :meth:`~plumbob.bodies.base.Body.to_geometry` (curves cut
    into 128 segments a turn: a curved shape's placed surface reaches below z = 0 by at
    most that tessellation's sagitta, 3·10⁻⁴ of its radius)."""
    try:
        return body.surface().triangles
    except GeometryError as exc:
        raise GeometryError(f"cannot export its poses as meshes: {exc}") from None


def export_poses(body, poses, folder: str, fmt: str = "stl", units: str | None = None
                 ) -> list[str]:
    """Write each of ``poses`` (most probable first, ranked from 1) as the body placed by
    its ``transform``, to ``folder`` (made if missing) as ``pose-RR-pP.PPPP.<fmt>``.
    Lengths are written in ``units`` (default m; a 3MF file says which). Returns the
    paths written."""
    if fmt not in FORMATS:
        raise PlumbobError(f"cannot export poses as {fmt!r}: use one of {', '.join(FORMATS)}")
    unit = mesh_unit(fmt, units)
    if any(np.asarray(p.down).size != 3 for p in poses):
        raise GeometryError("cannot export a lamina's poses as meshes: it stands in its own "
                            "plane and has no surface of triangles (--plot draws them)")
    tri = body_triangles(body)
    if tri.ndim != 3 or tri.shape[1:] != (3, 3):
        raise GeometryError("cannot export its poses as meshes: it is not a solid with a "
                            "surface of triangles")
    if os.path.exists(folder) and not os.path.isdir(folder):
        raise PlumbobError(f"cannot export poses to {folder}: it is a file, not a folder; "
                           "name a folder (it is made if missing)")
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError as exc:
        raise PlumbobError(f"cannot make the folder {folder}: {exc.strerror or exc}") from None
    width = max(2, len(str(len(poses))))
    paths = []
    for rank, pose in enumerate(poses, 1):
        T = np.asarray(pose.transform, dtype=float)
        name = f"pose-{rank:0{width}d}-p{pose.probability:.4f}.{fmt}"
        path = os.path.join(folder, name)
        write_mesh(path, tri @ T[:3, :3].T + T[:3, 3], unit, name)
        paths.append(path)
    return paths
