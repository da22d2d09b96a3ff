"""OBJ, PLY, OFF, 3MF, GLB and glTF solids, read through trimesh.

trimesh parses (``process=False``: nothing merged or dropped); plumbob then
checks every mesh as it checks an STL (:func:`~plumbob.mesh.check_solid`).
A file with several meshes (a 3MF with several objects, a glTF scene) gives an
:class:`~plumbob.bodies.csg.Assembly`, one named part per mesh instance, each
placed by its scene transform.

3MF is a zip of XML. Before trimesh opens it, the archive's declared sizes are
checked against :data:`MAX_EXPANDED_BYTES` (a zip bomb is refused unread) and
the start of every model part is parsed with defusedxml, which refuses DTDs and
entity declarations (entity-expansion bombs). trimesh itself parses with entity
resolution off.
"""

from __future__ import annotations

import os
import zipfile

import numpy as np

from ..errors import FormatError, InputFileError, PlumbobError
from ..reading import Reading
from ..units import file_unit_scale, units_scale
from .checks import check_extent, finite_bounds
from .parts import assemble, stem
from .solids import mesh_solid

__all__ = ["MESH_SUFFIXES", "MAX_EXPANDED_BYTES", "read_mesh", "check_3mf_archive"]

MESH_SUFFIXES = {".obj": "obj", ".ply": "ply", ".off": "off", ".3mf": "3mf", ".glb": "glb",
                 ".gltf": "gltf"}
#: bytes; a 3MF archive whose parts expand past this is refused
MAX_EXPANDED_BYTES = 1 << 30
#: a 3MF with more parts than this is refused
MAX_ARCHIVE_MEMBERS = 10_000


def check_3mf_archive(path: str, max_expanded: int = MAX_EXPANDED_BYTES) -> str | None:
    """Check a 3MF archive before it is unpacked; return the unit its model declares.

    Raises :class:`FormatError` when it is not a zip, expands past
    ``max_expanded`` bytes, has no model, or its model XML declares a DTD or
    entities. The unit is 3MF's ``unit`` attribute (default millimeter).
    """
    import defusedxml.ElementTree as safe_xml
    from defusedxml import DefusedXmlException

    try:
        archive = zipfile.ZipFile(path)
    except (zipfile.BadZipFile, zipfile.LargeZipFile, ValueError, EOFError) as error:
        raise FormatError(f"is not a readable 3MF (zip) archive: {error}", path=path) from None
    with archive:
        try:
            members = archive.infolist()
        except Exception as error:  # noqa: BLE001 - zipfile raises many kinds on corrupt input
            raise FormatError(f"has a corrupt zip directory: {error}", path=path) from None
        if len(members) > MAX_ARCHIVE_MEMBERS:
            raise FormatError(f"has {len(members)} archive parts (limit {MAX_ARCHIVE_MEMBERS}): "
                              "refused", path=path)
        expanded = sum(m.file_size for m in members)
        if expanded > max_expanded:
            raise FormatError(
                f"would expand to {expanded / 2**20:.0f} MiB (limit {max_expanded / 2**20:.0f} MiB)"
                f" from {os.path.getsize(path) / 2**20:.2g} MiB: refused as a possible zip bomb",
                path=path)
        models = [m for m in members if m.filename.lower().endswith(".model")]
        if not models:
            raise FormatError("is a zip archive with no 3D model part (3D/3dmodel.model): "
                              "not a 3MF", path=path)
        unit = None
        for member in models:  # a handful of parts
            try:
                with archive.open(member) as stream:
                    events = safe_xml.iterparse(stream, events=("start",), forbid_dtd=True)
                    _, root = next(iter(events))
            except DefusedXmlException as error:
                raise FormatError(
                    f"{member.filename} declares a DTD or XML entities ({type(error).__name__}), "
                    "which 3MF never needs: refused (entity-expansion attack?)",
                    path=path) from None
            except StopIteration:
                raise FormatError(f"{member.filename} is empty", path=path) from None
            except Exception as error:  # noqa: BLE001 - XML and zip errors of every kind
                raise FormatError(f"{member.filename} is not well-formed XML: {error}",
                                  path=path) from None
            if "3dmodel.model" in member.filename.lower():
                unit = root.attrib.get("unit", "millimeter")
    return unit or "millimeter"


def read_mesh(path: str, units: str | None = None, repair: bool = False,
              *, max_expanded: int = MAX_EXPANDED_BYTES) -> Reading:
    """Read an OBJ, PLY, OFF, 3MF, GLB or glTF file as a body (see module docstring)."""
    suffix = os.path.splitext(path)[1].lower()
    file_type = MESH_SUFFIXES.get(suffix)
    if file_type is None:
        raise InputFileError(f"is not a mesh file plumbob reads ({', '.join(MESH_SUFFIXES)})",
                             path=path)
    file_units = None
    if file_type == "3mf":
        file_units = check_3mf_archive(path, max_expanded)
    elif file_type in ("glb", "gltf"):
        file_units = "meter"  # glTF's unit, by its specification
    if file_units is not None and file_unit_scale(file_units) is None:
        if units is None:
            raise FormatError(f"declares the unknown unit {file_units!r}; pass --units",
                              path=path)
        file_units = None
    scale, notices = units_scale(units, file_units, file_unit_scale(file_units))
    notices = list(notices)
    meshes, skipped = _load(path, file_type)
    if skipped:
        notices.append(f"{file_type}: ignored {skipped} item(s) without triangles "
                       "(points or lines)")
    if not meshes:
        raise FormatError("contains no triangle mesh", path=path)
    several = len(meshes) > 1
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    parts = []
    for _, tri in meshes:  # per mesh instance
        tlo, thi = finite_bounds(tri, path=path)
        lo, hi = np.minimum(lo, tlo * scale), np.maximum(hi, thi * scale)
    notices += check_extent(lo, hi, path=path)
    for name, tri in meshes:
        body, more = mesh_solid(tri * scale if scale != 1.0 else tri, path=path, name=name,
                                repair=repair, label=f"mesh {name!r}" if several else None,
                                scale=scale)
        parts.append(body)
        notices.extend(more)
    return Reading(assemble(parts, stem(path)), tuple(notices), path)


def _load(path: str, file_type: str) -> tuple[list[tuple[str, np.ndarray]], int]:
    """(name, triangles (n, 3, 3) float64 placed in the scene) per mesh instance, and how
    many items without triangles were skipped."""
    import trimesh

    try:
        scene = trimesh.load(path, file_type=file_type, force="scene", process=False)
        meshes, skipped = [], 0
        graph = scene.graph
        for node in graph.nodes_geometry:  # per instance
            transform, geometry_name = graph[node]
            geometry = scene.geometry[geometry_name]
            if not isinstance(geometry, trimesh.Trimesh) or len(geometry.faces) == 0:
                skipped += 1
                continue
            vertices = np.asarray(geometry.vertices, dtype=float)
            faces = np.asarray(geometry.faces, dtype=np.int64)
            if vertices.ndim != 2 or vertices.shape[1] != 3:
                raise FormatError(f"mesh {node!r} has vertices that are not 3D points",
                                  path=path)
            if faces.ndim != 2 or faces.shape[1] != 3 or faces.min() < 0 or \
                    faces.max() >= len(vertices):
                raise FormatError(f"mesh {node!r} has a face referring to a vertex it does not "
                                  "have", path=path)
            matrix = np.asarray(transform, dtype=float)
            if not np.allclose(matrix, np.eye(4)):
                vertices = vertices @ matrix[:3, :3].T + matrix[:3, 3]
                if np.linalg.det(matrix[:3, :3]) < 0:
                    faces = faces[:, ::-1]  # a mirror turns the winding inside out
            meshes.append((str(node), vertices[faces]))
    except PlumbobError:
        raise
    except Exception as error:  # noqa: BLE001 - trimesh's parsers raise every kind on bad input
        text = str(error).strip().splitlines()[0][:200] if str(error).strip() else ""
        raise FormatError(f"cannot be read as {file_type.upper()}: {type(error).__name__}"
                          f"{': ' + text if text else ''}", path=path) from None
    return meshes, skipped
