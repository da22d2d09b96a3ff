"""Reading bodies from files: dispatch on the file's extension.

``read(path, units=None, repair=False)`` returns a :class:`~plumbob.reading.Reading`: the body
and the notices a user should see (assumed units, repaired defects, implausible
sizes). A file holding several bodies gives an
:class:`~plumbob.bodies.csg.Assembly` whose parts carry their names.

Formats (see ``docs/formats.md``):

* solids — STL (binary and ASCII, plumbob's own fast reader), OBJ, PLY, OFF,
  3MF, GLB and glTF (through trimesh); STEP, IGES and BREP CAD solids from their
  B-rep (through OpenCASCADE, ``plumbob[cad]``: :mod:`plumbob.formats.step`);
* laminas — GeoJSON, WKT, WKB, CSV vertex lists, SVG paths and DXF outlines;
* any of these compressed (``.gz``, ``.bz2``, ``.xz``) or alone in an archive
  (``.zip``, ``.tar``, ``.tgz``, ``.tar.gz``, …; :mod:`plumbob.formats.archives`).

Formats plumbob knows of but does not read (COLLADA, 3DXML, FBX, …: see
:data:`FOREIGN`) are refused in one line naming the format and what to convert to.

TOML specs are not read here: :func:`plumbob.loading.read` sends them to
:mod:`plumbob.spec` (which reads its mesh and outline files through this package),
so io never depends on spec. It shares :func:`file_family` and :func:`read_checked`.

Every failure is a :class:`~plumbob.errors.PlumbobError` naming the file.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from typing import TypeVar

from ..errors import InputFileError, PlumbobError
from ..files import require_regular_file
from ..reading import Reading

__all__ = ["read", "read_checked", "file_family", "SUFFIXES", "UNITLESS", "FOREIGN"]


_Read = TypeVar("_Read")

#: file extension → reader family
SUFFIXES = {
    ".stl": "stl",
    ".obj": "mesh", ".ply": "mesh", ".off": "mesh", ".3mf": "mesh", ".glb": "mesh", ".gltf": "mesh",
    ".geojson": "outline", ".json": "outline", ".wkt": "outline", ".wkb": "outline",
    ".csv": "outline", ".svg": "outline", ".dxf": "outline",
    ".zip": "archive", ".gz": "archive", ".bz2": "archive", ".xz": "archive", ".tgz": "archive",
    ".tar": "archive",
    ".step": "cad", ".stp": "cad", ".iges": "cad", ".igs": "cad", ".brep": "cad",
}

#: extensions of 3D formats plumbob does not read → the format's name. None of them is
#: read as a watertight volume here (trimesh's COLLADA, 3DXML and XAML loaders split
#: every face group into an open sheet; OpenCTM, Gmsh and binvox need libraries
#: plumbob does not use), so each is refused, saying what to convert it to.
#: the extensions of formats that cannot state a length unit: their unit is the caller's
UNITLESS = frozenset({".stl", ".csv", ".geojson", ".json", ".wkt", ".wkb"})

FOREIGN = {
    ".dae": "COLLADA", ".zae": "zipped COLLADA", ".3dxml": "3DXML", ".xaml": "XAML",
    ".ctm": "OpenCTM", ".msh": "Gmsh mesh", ".binvox": "binvox voxels",
    ".fbx": "FBX", ".blend": "Blender", ".3ds": "3D Studio", ".x3d": "X3D", ".wrl": "VRML",
    ".dwg": "DWG", ".amf": "AMF", ".vtk": "VTK",
}


def read(path: str, *, units: str | None = None, repair: bool = False,
         units_override: bool = False) -> Reading:
    """Read the body in the mesh or outline file ``path``; the reader is chosen by the
    file's extension.

    ``units``: the length unit of the file's coordinates (``mm``, ``cm``, ``m``,
    ``in``, ``ft``); None uses the unit the file declares, else metres (with a
    notice); one that contradicts the unit a file declares is refused unless
    ``units_override``. ``repair``: close small holes in open meshes (reported in the
    notices).
    """
    path = os.fspath(path)
    if path.lower().endswith(".toml"):
        raise InputFileError("is a TOML spec, not a mesh or outline: read it with plumbob.read "
                             "(plumbob.loading.read)", path=path)
    kind = file_family(path, SUFFIXES)
    return read_checked(path, lambda: _dispatch(kind, path, units, repair, units_override))


def file_family(path: str, suffixes: Mapping[str, str]) -> str:
    """The reader family ``suffixes`` gives the extension of ``path``; an unknown
    extension is an :class:`InputFileError` listing the ones known."""
    if os.path.isdir(path):
        raise InputFileError("is a folder, not a file; to measure every file in it, use "
                             "'plumbob batch FOLDER'", path=path)
    suffix = os.path.splitext(path)[1].lower()
    kind = suffixes.get(suffix)
    if kind is None and suffix in FOREIGN:
        raise InputFileError(
            f"unsupported file type {suffix!r} ({FOREIGN[suffix]}): plumbob does not read it; "
            "export or convert it to STL, 3MF, OBJ or PLY (one closed mesh)", path=path)
    if kind is None:
        known = ", ".join(sorted(suffixes))
        raise InputFileError(
            f"unknown file type {suffix or '(no extension)'!r}; plumbob reads {known}", path=path)
    return kind


def read_checked(path: str, reader: Callable[[], _Read]) -> _Read:
    """Run ``reader`` (of a file's body, or of a simulation spec) on the file ``path``
    once it is known to exist, be a file and hold something; any failure, including
    one raised below the readers (a body's own check), becomes a
    :class:`PlumbobError` naming the file."""
    if require_regular_file(path) == 0:
        raise InputFileError("is empty (0 bytes): nothing to read", path=path)
    try:
        return reader()
    except PlumbobError as error:
        if error.path is None:
            raise error.within(path=path) from None
        raise
    except MemoryError:
        raise InputFileError("is too large to read into memory", path=path) from None
    except (OSError, UnicodeError) as error:
        raise InputFileError(f"cannot be read: {getattr(error, 'strerror', None) or error}",
                             path=path) from None


def _dispatch(kind: str, path: str, units: str | None, repair: bool,
              units_override: bool = False) -> Reading:
    if kind == "archive":
        from .archives import read_archive

        def member(inner: str) -> Reading:
            family = file_family(inner, SUFFIXES)
            return read_checked(inner, lambda: _dispatch(family, inner, units, repair,
                                                         units_override))

        return read_archive(path, member, _readable)
    if kind == "stl":
        from .stl import read_stl

        return read_stl(path, units=units, repair=repair)
    if kind == "mesh":
        from .meshes import read_mesh

        return read_mesh(path, units=units, repair=repair, units_override=units_override)
    if kind == "cad":
        from .step import read_step

        return read_step(path, units=units, units_override=units_override)
    from .outlines import read_outline

    return read_outline(path, units=units, units_override=units_override)


def _readable(name: str) -> bool:
    """Whether ``name`` is a file plumbob reads inside an archive (not another archive)."""
    return SUFFIXES.get(os.path.splitext(name)[1].lower(), "archive") != "archive"
