"""Mesh files out: the one home of plumbob's STL and 3MF writers and their unit policy.

Every mesh plumbob writes (placed poses, a hollowed body and its void) goes through
:func:`write_mesh`, which keeps one policy: lengths are given in metres and written
in ``units`` (default m); binary STL carries no unit, a 3MF states it (3MF has no
kilometre, so a ``km`` 3MF is written in metres). The file is written whole or not
at all (:func:`plumbob.files.write_atomic`).
"""

from __future__ import annotations

import io
import os
import struct

import numpy as np

from ..errors import PlumbobError
from ..files import write_atomic
from ..units import LENGTH_UNITS

__all__ = ["MESH_FORMATS", "UNIT_NAMES_3MF", "stl_bytes", "threemf_bytes", "write_mesh",
           "mesh_unit", "mesh_format"]

#: the mesh formats plumbob writes, by extension (without the dot)
MESH_FORMATS = ("stl", "3mf")
#: the 3MF spelling of each unit a user may name (3MF has no kilometre: written in metres)
UNIT_NAMES_3MF = {"m": "meter", "cm": "centimeter", "mm": "millimeter", "in": "inch",
                  "ft": "foot", "km": "meter"}


def stl_bytes(triangles: np.ndarray, name: str = "plumbob", scale: float = 1.0) -> bytes:
    """Binary STL of ``triangles`` (n, 3, 3) divided by ``scale`` (the file's unit in the
    triangles' unit: 1e-3 writes metres as millimetres); ``name`` heads the file."""
    tri = np.asarray(triangles, dtype=np.float64) / scale
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


def mesh_unit(fmt: str, units: str | None) -> str:
    """The length unit a mesh file of format ``fmt`` (``stl`` or ``3mf``) is written in
    when ``units`` is asked for (default m): ``units`` itself, but metres for a ``km``
    3MF; a :class:`PlumbobError` for an unknown format or unit."""
    if fmt not in MESH_FORMATS:
        raise PlumbobError(f"cannot write a mesh as {fmt!r}: use one of {', '.join(MESH_FORMATS)}")
    unit = units or "m"
    if unit not in LENGTH_UNITS:
        raise PlumbobError(f"unknown length unit {unit!r}: use one of {', '.join(LENGTH_UNITS)}")
    return "m" if fmt == "3mf" and UNIT_NAMES_3MF[unit] == "meter" else unit


def mesh_format(path: str) -> str | None:
    """``stl`` or ``3mf`` by the extension of ``path`` (any case); ``None`` for another."""
    fmt = os.path.splitext(str(path))[1].lower().lstrip(".")
    return fmt if fmt in MESH_FORMATS else None


def write_mesh(path: str, triangles: np.ndarray, units: str | None = None,
               name: str = "plumbob") -> str:
    """Write ``triangles`` (n, 3, 3), m, to ``path`` (``.stl`` or ``.3mf`` by its extension)
    in ``units`` (default m; see :func:`mesh_unit`), atomically. Returns the unit written."""
    fmt = mesh_format(path)
    if fmt is None:
        raise PlumbobError(f"cannot write a mesh to {path!r}: name a .stl or .3mf file")
    unit = mesh_unit(fmt, units)
    scale = LENGTH_UNITS[unit]
    data = (stl_bytes(triangles, name, scale) if fmt == "stl"
            else threemf_bytes(np.asarray(triangles, dtype=float) / scale, UNIT_NAMES_3MF[unit]))
    write_atomic(str(path), data)
    return unit
