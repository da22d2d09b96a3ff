"""Reading bodies from files: dispatch on the file's extension.

``read(path, units=None, repair=False)`` returns a :class:`~plumbob.reading.Reading`: the body
and the notices a user should see (assumed units, repaired defects, implausible
sizes). A file holding several bodies gives an
:class:`~plumbob.bodies.csg.Assembly` whose parts carry their names.

Formats (see ``docs/formats.md``):

* solids — STL (binary and ASCII, plumbob's own fast reader), OBJ, PLY, OFF,
  3MF, GLB and glTF (through trimesh);
* laminas — GeoJSON, WKT, WKB, CSV vertex lists, SVG paths and DXF outlines;
* shape specs — TOML.

Every failure is a :class:`~plumbob.errors.PlumbobError` naming the file.
"""

from __future__ import annotations

import os

from ..errors import InputFileError, PlumbobError
from ..reading import Reading

__all__ = ["read", "SUFFIXES"]


#: file extension → reader family
SUFFIXES = {
    ".toml": "spec",
    ".stl": "stl",
    ".obj": "mesh", ".ply": "mesh", ".off": "mesh", ".3mf": "mesh", ".glb": "mesh", ".gltf": "mesh",
    ".geojson": "outline", ".json": "outline", ".wkt": "outline", ".wkb": "outline",
    ".csv": "outline", ".svg": "outline", ".dxf": "outline",
}


def read(path: str, *, units: str | None = None, repair: bool = False) -> Reading:
    """Read the body in ``path``; the reader is chosen by the file's extension.

    ``units``: the length unit of the file's coordinates (``mm``, ``cm``, ``m``,
    ``in``, ``ft``); None uses the unit the file declares, else metres (with a
    notice). ``repair``: close small holes in open meshes (reported in the notices).
    """
    path = os.fspath(path)
    suffix = os.path.splitext(path)[1].lower()
    kind = SUFFIXES.get(suffix)
    if kind is None:
        known = ", ".join(sorted(SUFFIXES))
        raise InputFileError(
            f"unknown file type {suffix or '(no extension)'!r}; plumbob reads {known}", path=path)
    if not os.path.exists(path):
        raise InputFileError("no such file", path=path)
    if os.path.isdir(path):
        raise InputFileError("is a folder, not a file", path=path)
    try:
        with open(path, "rb") as f:
            empty = not f.read(1)
    except OSError as error:
        raise InputFileError(f"cannot be read: {error.strerror or error}", path=path) from None
    if empty:
        raise InputFileError("is empty (0 bytes): nothing to read", path=path)
    try:
        return _dispatch(kind, path, units, repair)
    except PlumbobError as error:
        if error.path is None:  # raised below the readers (a body's own check): name the file
            raise type(error)(error.message, path=path) from None
        raise
    except MemoryError:
        raise InputFileError("is too large to read into memory", path=path) from None
    except (OSError, UnicodeError) as error:
        raise InputFileError(f"cannot be read: {getattr(error, 'strerror', None) or error}",
                             path=path) from None


def _dispatch(kind: str, path: str, units: str | None, repair: bool) -> Reading:
    if kind == "spec":
        from ..spec.loader import load_spec

        return load_spec(path)
    if kind == "stl":
        from .stl import read_stl

        return read_stl(path, units=units, repair=repair)
    if kind == "mesh":
        from .meshes import read_mesh

        return read_mesh(path, units=units, repair=repair)
    from .outlines import read_outline

    return read_outline(path, units=units)
