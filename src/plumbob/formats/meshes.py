"""OBJ, PLY, OFF, GLB and glTF solids, read through trimesh; 3MF, read by plumbob.

trimesh parses (``process=False``: nothing merged or dropped); plumbob then
checks every mesh as it checks an STL (:func:`~plumbob.mesh.check_solid`).
A file with several meshes (a 3MF with several objects, a glTF scene) gives an
:class:`~plumbob.bodies.csg.Assembly`, one named part per mesh instance, each
placed by its scene transform. A 3MF is read by plumbob's own reader
(:mod:`plumbob.formats.threemf`), which keeps each object's name and material.

3MF is a zip of XML. Before it is read, the archive's declared sizes and
expansion ratios are checked against :mod:`plumbob.limits` (a zip bomb is
refused unread) and every model part's start is parsed with defusedxml, which
refuses DTDs and entity declarations (entity-expansion bombs); the reader then
parses with entity resolution off.

glTF and GLB are +y up by their specification: the reading says so (``Reading.up``) and
the stability commands rest such a body toward −y unless ``--down`` says otherwise; 3MF,
STL, OBJ and PLY carry no up axis and are taken +z up, as plumbob takes every body.

OBJ face indices are checked before trimesh reads them (:func:`check_obj_indices`):
an index of 0 (a file counting from 0) or past the vertices would otherwise wrap
round to another vertex and give a wrong mass without a word.
"""

from __future__ import annotations

import os
import warnings
import zipfile

import numpy as np

from .. import limits
from ..errors import FormatError, InputFileError, LimitError, PlumbobError
from ..files import read_bytes
from ..limits import check_count
from ..reading import Reading
from ..units import file_unit_scale, reading_unit, unit_assumed, units_scale
from .checks import check_extent, finite_bounds
from .parts import assemble, stem
from .solids import mesh_solid

__all__ = ["MESH_SUFFIXES", "read_mesh", "check_3mf_archive", "check_obj_indices"]

#: glTF's up axis, by its specification (3MF, STL, OBJ and PLY are read +z up)
GLTF_UP = (0.0, 1.0, 0.0)
GLTF_UP_NOTICE = "up: +y, as glTF specifies: it rests toward -y unless --down says otherwise"

MESH_SUFFIXES = {".obj": "obj", ".ply": "ply", ".off": "off", ".3mf": "3mf", ".glb": "glb",
                 ".gltf": "gltf"}


def check_3mf_archive(path: str) -> str | None:
    """Check a 3MF archive before it is unpacked; return the unit its model declares.

    Every member's declared size is checked against :data:`plumbob.limits.MAX_ARCHIVE_BYTES`
    (all members together) and :data:`~plumbob.limits.MAX_ARCHIVE_RATIO` (each member's
    expansion) before anything is extracted, so a zip bomb is refused unread; each model
    part's start is then parsed with defusedxml up to its root element — where any DTD
    or entity declaration must stand — refusing them (entity-expansion bombs). Raises
    :class:`FormatError` or :class:`LimitError`. The unit is 3MF's ``unit`` attribute
    (default millimeter).
    """
    import defusedxml.ElementTree as safe_xml
    from defusedxml import DefusedXmlException

    try:
        archive = zipfile.ZipFile(path)
        members = archive.infolist()
    except NotImplementedError as error:  # a compression or zip version Python lacks
        raise FormatError(f"uses a zip feature Python cannot read ({error}): save it again "
                          "as a plain 3MF", path=path) from None
    except Exception as error:  # noqa: BLE001 - zipfile raises many kinds on corrupt input
        raise FormatError(f"is not a readable 3MF (zip) archive: {error}", path=path) from None
    with archive:
        check_count("archive parts", len(members), limits.MAX_ARCHIVE_MEMBERS, path=path)
        packed = max(os.path.getsize(path), 1)
        expanded = sum(m.file_size for m in members)
        if expanded > limits.MAX_ARCHIVE_BYTES:
            raise LimitError(
                f"would expand to {expanded} bytes, over plumbob's limit of "
                f"{limits.MAX_ARCHIVE_BYTES} (plumbob.limits.MAX_ARCHIVE_BYTES): refused unread",
                path=path)
        for m in members:  # a handful of parts
            ratio = m.file_size / max(m.compress_size, 1)
            if m.file_size > 2**20 and ratio > limits.MAX_ARCHIVE_RATIO:
                raise FormatError(
                    f"{m.filename} would expand {ratio:.0f} times, to {m.file_size / 2**20:.0f}"
                    f" MiB from a {packed / 2**20:.2g} MiB file (limit {limits.MAX_ARCHIVE_RATIO}"
                    " times, plumbob.limits.MAX_ARCHIVE_RATIO): refused unread as a possible zip "
                    "bomb", path=path)
        models = [m for m in members if m.filename.lower().endswith(".model")]
        if not models:
            raise FormatError("is a zip archive with no 3D model part (3D/3dmodel.model): "
                              "not a 3MF", path=path)
        unit = None
        for member in models:  # a handful of parts
            try:
                with archive.open(member) as stream:  # a DTD can only come before the root
                    events = safe_xml.iterparse(stream, events=("start",), forbid_dtd=True)
                    _, root = next(iter(events))
            except StopIteration:
                raise FormatError(f"{member.filename} is empty", path=path) from None
            except DefusedXmlException as error:
                raise FormatError(
                    f"{member.filename} declares a DTD or XML entities ({type(error).__name__}), "
                    "which 3MF never needs: refused (entity-expansion attack?)",
                    path=path) from None
            except NotImplementedError as error:
                raise FormatError(f"uses a zip feature Python cannot read ({error}): save it "
                                  "again as a plain 3MF", path=path) from None
            except Exception as error:  # noqa: BLE001 - XML and zip errors of every kind
                text = str(error).splitlines()[0][:200] if str(error) else type(error).__name__
                raise FormatError(f"{member.filename} is not well-formed XML: {text}",
                                  path=path) from None
            if "3dmodel.model" in member.filename.lower():
                unit = root.attrib.get("unit", "millimeter")
    return unit or "millimeter"


def read_mesh(path: str, units: str | None = None, repair: bool = False,
              units_override: bool = False) -> Reading:
    """Read an OBJ, PLY, OFF, 3MF, GLB or glTF file as a body (see module docstring);
    ``units_override``: a ``units`` that contradicts the unit the file declares is used
    rather than refused."""
    suffix = os.path.splitext(path)[1].lower()
    file_type = MESH_SUFFIXES.get(suffix)
    if file_type is None:
        raise InputFileError(f"is not a mesh file plumbob reads ({', '.join(MESH_SUFFIXES)})",
                             path=path)
    file_units = None
    if file_type == "3mf":
        file_units = check_3mf_archive(path)
    elif file_type == "obj":
        check_obj_indices(path)
    elif file_type == "ply":
        _check_ply_header(path)
    elif file_type in ("glb", "gltf"):
        file_units = "meter"  # glTF's unit, by its specification
    if file_units is not None and file_unit_scale(file_units) is None:
        if units is None:
            raise FormatError(f"declares the unknown unit {file_units!r}; pass --units",
                              path=path)
        file_units = None
    scale, notices = units_scale(units, file_units, file_unit_scale(file_units),
                                 override=units_override, path=path)
    notices = list(notices)
    instances = None
    if file_type == "3mf":  # plumbob's own reader: names and materials per object
        from .parts import unique_names
        from .threemf import load_3mf

        instances, more = load_3mf(path)
        notices.extend(more)
        meshes, skipped = list(zip(unique_names([i.name for i in instances]),
                                   [i.triangles for i in instances])), 0
    else:
        meshes, skipped = _load(path, file_type)
    if skipped:
        notices.append(f"{file_type}: ignored {skipped} item(s) without triangles "
                       "(points or lines)")
    if not meshes:
        raise FormatError("contains no triangle mesh", path=path)
    if file_type == "obj" and len(meshes) > 1:  # trimesh splits by material: one body
        meshes = [(stem(path), np.concatenate([tri for _, tri in meshes]))]
    several = len(meshes) > 1
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    parts = []
    for _, tri in meshes:  # per mesh instance
        tlo, thi = finite_bounds(tri, path=path)
        lo, hi = np.minimum(lo, tlo * scale), np.maximum(hi, thi * scale)
    notices += check_extent(lo, hi, path=path, assumed=units is None and file_units is None)
    for name, tri in meshes:
        body, more = mesh_solid(tri * scale if scale != 1.0 else tri, path=path, name=name,
                                repair=repair, label=f"mesh {name!r}" if several else None,
                                scale=scale)
        parts.append(body)
        notices.extend(more)
    up = GLTF_UP if file_type in ("glb", "gltf") else None
    if up is not None:
        notices.append(GLTF_UP_NOTICE)
    materials, required = (), False
    if instances:  # the parts' materials, applied by plumbob.read (after --part-material)
        from .threemf import material_notices

        chosen, more, required = material_notices([n for n, _ in meshes], instances)
        notices.extend(more)
        materials = tuple((n, m.name, m.density) for (n, _), m in zip(meshes, chosen)
                          if m is not None)
    return Reading(assemble(parts, stem(path)), tuple(notices), path,
                   reading_unit(units, file_units), up=up, file_materials=materials,
                   densities_required=required,
                   units_assumed=unit_assumed(units, file_units, file_unit_scale(file_units)))


def _load(path: str, file_type: str) -> tuple[list[tuple[str, np.ndarray]], int]:
    """(name, triangles (n, 3, 3) float64 placed in the scene) per mesh instance, and how
    many items without triangles were skipped."""
    import trimesh

    try:
        scene = trimesh.load(path, file_type=file_type, force="scene", process=False)
        meshes, skipped, triangles = [], 0, 0
        graph = scene.graph
        for node in graph.nodes_geometry:  # per instance
            # a placement that scales by 1e300 overflows in trimesh's rigidity check and
            # in ours: the coordinates it gives are refused by name after (check_reach)
            with np.errstate(over="ignore", invalid="ignore"):
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
            if not np.isfinite(matrix).all():
                raise FormatError(f"mesh {node!r} is placed by a matrix with a number that is "
                                  "not finite", path=path)
            if not np.allclose(matrix, np.eye(4)):
                with np.errstate(over="ignore", invalid="ignore"):
                    vertices = vertices @ matrix[:3, :3].T + matrix[:3, 3]
                if np.linalg.slogdet(matrix[:3, :3])[0] < 0:
                    faces = faces[:, ::-1]  # a mirror turns the winding inside out
            meshes.append((str(node), vertices[faces]))
            triangles += len(faces)
            check_count("triangles", triangles, limits.MAX_TRIANGLES, path=path)
    except PlumbobError:
        raise
    except Exception as error:  # noqa: BLE001 - trimesh's parsers raise every kind on bad input
        text = str(error).strip().splitlines()[0][:200] if str(error).strip() else ""
        raise FormatError(f"cannot be read as {file_type.upper()}: {type(error).__name__}"
                          f"{': ' + text if text else ''}", path=path) from None
    return meshes, skipped


def _blank(a: np.ndarray) -> np.ndarray:
    return (a == 32) | (a == 9) | (a == 13)


def check_obj_indices(path: str) -> None:
    """Refuse an OBJ whose face refers to a vertex it does not have, naming the line.

    OBJ counts vertices from 1; a negative index counts back from the last vertex
    defined before its line. One vectorised pass over the file's bytes: the first
    number of every word of every ``f`` line is parsed in one C call (texture and
    normal indices after ``/`` are blanked), and the triangle count is checked
    against :data:`plumbob.limits.MAX_TRIANGLES` before trimesh builds anything.
    """
    data = read_bytes(path) + b"\n"
    physical = np.frombuffer(data, dtype=np.uint8)
    # a line ending in a backslash continues on the next: join them, keeping byte offsets
    a = np.frombuffer(data.replace(b"\\\r\n", b"   ").replace(b"\\\n", b"  "), dtype=np.uint8)
    ends = np.flatnonzero(a == 10)
    starts = np.r_[0, ends[:-1] + 1]
    spaced = _blank(a[np.minimum(starts + 1, len(a) - 1)])
    vertex = (a[starts] == ord("v")) & spaced
    face = (a[starts] == ord("f")) & spaced
    if not face.any():
        return
    before = np.cumsum(vertex) - vertex  # vertices defined above each line
    total = int(vertex.sum())
    # the bytes of face lines after their 'f': one word per vertex reference
    step = np.zeros(len(a) + 1, dtype=np.int8)
    step[starts[face] + 2] += 1
    step[ends[face]] -= 1
    inside = np.cumsum(step[:-1], dtype=np.int8).view(bool)
    word = inside & ~_blank(a)
    word_start = np.flatnonzero(word & ~np.r_[False, word[:-1]])
    slash = (a == ord("/")) & word
    seen = np.cumsum(slash, dtype=np.int32)
    base = np.zeros(len(a), dtype=np.int32)
    base[word_start] = seen[word_start]
    keep = (word & (seen == np.maximum.accumulate(base))) | (a == 10)  # before any '/'
    numbers = np.where(keep, a, np.uint8(32))
    words = np.bincount(np.searchsorted(starts, word_start, side="right") - 1,
                        minlength=len(starts))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            values = np.fromstring(numbers.tobytes(), sep=" ")  # one C pass
    except ValueError:  # numpy ≥ 2.3 raises on text that is not numbers
        values = None
    if values is None or len(values) != len(word_start) or np.any(values != np.round(values)):
        bad = int(np.count_nonzero(physical[: starts[face][0]] == 10)) + 1
        raise FormatError(f"a face (from line {bad} on) is not a list of whole vertex "
                          "numbers", path=path)
    owner = np.repeat(np.arange(len(starts)), words)
    check_count("triangles", int(np.maximum(words[face] - 2, 0).sum()), limits.MAX_TRIANGLES,
                path=path)
    # checked as floats (whole numbers, exact to 2⁵³): an index beyond int64 (1e23) is
    # refused here, never cast
    wrong = (values == 0) | (values > total) | (-values > before[owner])
    if wrong.any():
        at = int(np.argmax(wrong))
        line = int(np.count_nonzero(physical[: starts[owner[at]]] == 10)) + 1
        raise FormatError(
            f"line {line}: face index {values[at]:.15g} refers to no vertex (the file has "
            f"{total} vertices{f', {before[owner[at]]} above that line' if values[at] < 0 else ''}"
            "; OBJ counts from 1, negative indices count back): a file counting from 0?",
            path=path)


def _check_ply_header(path: str) -> None:
    """Check the face count a PLY header declares against :data:`plumbob.limits.MAX_TRIANGLES`
    before trimesh allocates for it (the header is text, whatever the body's encoding)."""
    try:
        with open(path, "rb") as handle:
            head = handle.read(1 << 16)
    except OSError as error:
        raise InputFileError(f"cannot be read: {error.strerror or error}", path=path) from None
    for line in head.split(b"end_header", 1)[0].splitlines():  # a few header lines
        words = line.split()
        if len(words) == 3 and words[0] == b"element" and words[1] == b"face" and \
                words[2].isdigit():
            check_count("faces", int(words[2]), limits.MAX_TRIANGLES, path=path)
