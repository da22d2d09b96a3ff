"""Placed poses as mesh files: the body set down in each pose, ready to print or show.

:func:`export_poses` writes, for each pose, the body's surface moved by the pose's
``transform`` (resting on z = 0, centre of mass above the origin) to
``pose-01-p0.4123.stl`` (rank, then probability) in a folder: binary STL in the
length unit the body was read in, or 3MF, which states its unit. Each file is
written to a temporary name and renamed once complete, so a folder never holds a
partial file.
"""

from __future__ import annotations

import io
import os
import struct

import numpy as np

from ..errors import GeometryError, PlumbobError
from ..plot.files import write_atomic
from ..units import LENGTH_UNITS

__all__ = ["FORMATS", "UNIT_NAMES_3MF", "body_triangles", "stl_bytes", "threemf_bytes",
           "export_poses"]

FORMATS = ("stl", "3mf")
#: the 3MF spelling of each unit a user may name (3MF has no kilometre: written in metres)
UNIT_NAMES_3MF = {"m": "meter", "cm": "centimeter", "mm": "millimeter", "in": "inch",
                  "ft": "foot", "km": "meter"}


def body_triangles(body) -> np.ndarray:
    """The body's surface as triangles (n, 3, 3), m: a mesh's own triangles, else the
    boolean-geometry surface of :meth:`~plumbob.bodies.base.Body.to_geometry` (curves cut
    into 128 segments a turn: a curved shape's placed surface reaches below z = 0 by at
    most that tessellation's sagitta, 3·10⁻⁴ of its radius)."""
    tri = getattr(body, "triangles", None)
    if tri is not None:
        return np.asarray(tri, dtype=float)
    try:
        mesh = body.to_geometry().to_mesh()
    except GeometryError as exc:
        raise GeometryError(f"cannot export its poses as meshes: {exc}") from None
    verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    return verts[np.asarray(mesh.tri_verts, dtype=np.int64)]


def stl_bytes(triangles: np.ndarray, name: str = "plumbob") -> bytes:
    """Binary STL of ``triangles`` (n, 3, 3), in whatever unit they are given."""
    tri = np.asarray(triangles, dtype=np.float64)
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = normal / np.where(length > 0, length, 1.0)
    record = np.zeros(len(tri), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["n"], record["v"] = normal, tri
    head = name.encode("ascii", "replace")[:80].ljust(80, b" ")
    return head + struct.pack("<I", len(tri)) + record.tobytes()


def threemf_bytes(triangles: np.ndarray, unit: str) -> bytes:
    """A 3MF archive of ``triangles`` (n, 3, 3) given in ``unit`` (a 3MF unit name)."""
    import zipfile

    verts, index = np.unique(np.asarray(triangles, dtype=float).reshape(-1, 3), axis=0,
                             return_inverse=True)
    index = index.reshape(-1, 3)
    # one formatting pass each (no loop over vertices in Python)
    vtext = ('<vertex x="%.17g" y="%.17g" z="%.17g"/>' * len(verts)) % tuple(verts.ravel())
    ttext = ('<triangle v1="%d" v2="%d" v3="%d"/>' * len(index)) % tuple(index.ravel().tolist())
    model = ('<?xml version="1.0" encoding="UTF-8"?>\n'
             f'<model unit="{unit}" xml:lang="en-US" '
             'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">'
             f'<resources><object id="1" type="model"><mesh><vertices>{vtext}</vertices>'
             f'<triangles>{ttext}</triangles></mesh></object></resources>'
             '<build><item objectid="1"/></build></model>')
    types = ('<?xml version="1.0" encoding="UTF-8"?>\n<Types xmlns="http://schemas.openxmlformats'
             '.org/package/2006/content-types"><Default Extension="rels" ContentType="application/'
             'vnd.openxmlformats-package.relationships+xml"/><Default Extension="model" '
             'ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/></Types>')
    rels = ('<?xml version="1.0" encoding="UTF-8"?>\n<Relationships xmlns="http://schemas.'
            'openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/3dmodel.'
            'model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/'
            '3dmodel"/></Relationships>')
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("[Content_Types].xml", types)
        archive.writestr("_rels/.rels", rels)
        archive.writestr("3D/3dmodel.model", model)
    return buffer.getvalue()


def export_poses(body, poses, folder: str, fmt: str = "stl", units: str | None = None
                 ) -> list[str]:
    """Write each of ``poses`` (most probable first, ranked from 1) as the body placed by
    its ``transform``, to ``folder`` (made if missing) as ``pose-RR-pP.PPPP.<fmt>``.
    Lengths are written in ``units`` (default m; a 3MF file says which). Returns the
    paths written."""
    if fmt not in FORMATS:
        raise PlumbobError(f"cannot export poses as {fmt!r}: use one of {', '.join(FORMATS)}")
    unit = units or "m"
    if unit not in LENGTH_UNITS:
        raise PlumbobError(f"unknown length unit {unit!r}: use one of {', '.join(LENGTH_UNITS)}")
    if fmt == "3mf" and UNIT_NAMES_3MF[unit] == "meter":
        unit = "m"
    scale = 1.0 / LENGTH_UNITS[unit]
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
        placed = (tri @ T[:3, :3].T + T[:3, 3]) * scale
        name = f"pose-{rank:0{width}d}-p{pose.probability:.4f}.{fmt}"
        path = os.path.join(folder, name)
        data = (stl_bytes(placed, name) if fmt == "stl"
                else threemf_bytes(placed, UNIT_NAMES_3MF[unit]))
        write_atomic(path, data)
        paths.append(path)
    return paths
