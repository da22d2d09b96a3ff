"""3MF files read by plumbob itself: every build instance a named part, with its material.

A 3MF is a zip of XML model parts. :func:`~plumbob.formats.meshes.check_3mf_archive`
checks the zip's sizes and refuses any DTD (with defusedxml) before this reads
anything; each part is then parsed here by lxml, entities and the network off
(:meth:`_Model.parse`): the ``<object>`` resources (a ``<mesh>``, or ``<components>``
placing other objects, also from other model parts of the archive: the production
extension's ``p:path``), the ``<build>`` items and the core ``<basematerials>``.
Every build item is walked down its components (depth
:data:`~plumbob.limits.MAX_NESTING`, at most :data:`~plumbob.limits.MAX_PARTS`
instances, a cycle refused) to the mesh objects it places.

**Materials.** An object's ``pid``/``pindex`` naming a base material (or, for a
components object, the nearest ancestor's) is its part's material. Slicers write
multi-material prints this way: one object per material. A base material's name
that names a plumbob material (:func:`match_material`: the whole name, ``PLA``, or
a single filament word in it, ``Generic PETG``) gives the part that density; what
was matched is always said in a notice, and a name that matches nothing leaves the
part without a density (``--part-material NAME=MATERIAL`` gives it). Triangles that
carry other materials (painted faces) do not change the volume's material: a notice
says so.
"""

from __future__ import annotations

import io
import zipfile
from dataclasses import dataclass, field, replace

import numpy as np

from .. import limits
from ..errors import FormatError, LimitError
from ..limits import check_count

__all__ = ["Instance", "load_3mf", "match_material", "material_notices"]

_PRODUCTION = "{http://schemas.microsoft.com/3dmanufacturing/production/2015/06}"


@dataclass(frozen=True)
class Instance:
    """One placed mesh object of a 3MF: name, triangles (n, 3, 3) in the file's unit,
    material (a base material's name, or None), and whether its triangles name other
    materials (painted faces); the ids of the build item's object and of the mesh
    object, for a slicer's settings (:mod:`plumbob.formats.slicers`)."""

    name: str
    triangles: np.ndarray
    material: str | None
    painted: bool = False
    source: str | None = None  # where the material was named, for the notices
    top: str = ""  # the id of the object the build item places
    object_id: str = ""  # the id of the mesh object


@dataclass
class _Object:
    name: str | None
    material: str | None = None  # its pid/pindex's base material
    vertices: np.ndarray | None = None
    faces: np.ndarray | None = None
    painted: set = field(default_factory=set)  # base materials its triangles name
    components: list = field(default_factory=list)  # (part, object id, 4 × 4 matrix)


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _matrix(text: str | None, path: str) -> np.ndarray:
    """A 3MF ``transform`` (12 numbers, row-vector form) as a 4 × 4 column-vector matrix."""
    out = np.eye(4)
    if text is None:
        return out
    try:
        m = np.array(text.split(), dtype=float)
    except ValueError:
        raise FormatError(f"has a transform that is not 12 numbers: {text[:80]!r}",
                          path=path) from None
    if m.shape != (12,) or not np.isfinite(m).all():
        raise FormatError(f"has a transform that is not 12 finite numbers: {text[:80]!r}",
                          path=path)
    out[:3, :3] = m[:9].reshape(3, 3).T
    out[:3, 3] = m[9:]
    return out


def _numbers(values: list[str], whole: bool, what: str, path: str) -> np.ndarray:
    """The numbers of ``values`` (three each) as an (n, 3) array, parsed in one C pass:
    float64, or int64 when ``whole``."""
    import warnings

    text = " ".join(values)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            # stops (or raises) at a word that is not a number: "1.5" as an index included
            array = np.fromstring(text, dtype=np.int64 if whole else float, sep=" ")
    except ValueError:
        array = None
    if array is None or len(array) != len(values) * 3:
        raise FormatError(f"has {what} with a coordinate or index that is not a number (or "
                          "is missing)", path=path)
    return array.reshape(-1, 3)


class _Model:
    """The objects, build items and base materials of a 3MF's model parts."""

    def __init__(self, archive: zipfile.ZipFile, path: str) -> None:
        self.archive, self.path = archive, path
        self.objects: dict[tuple[str, str], _Object] = {}
        self.items: list[tuple[str, str, np.ndarray]] = []
        self.parsed: set[str] = set()
        self.triangles = 0
        self.names = {i.filename.lower().lstrip("/"): i.filename for i in archive.infolist()}

    def part(self, name: str) -> str:
        """The archive member a model part's name (``/3D/3dmodel.model``) refers to."""
        member = self.names.get(name.lower().lstrip("/"))
        if member is None:
            raise FormatError(f"refers to a model part {name!r} the archive does not hold",
                              path=self.path)
        if not member.lower().endswith(".model"):  # only those were checked for DTDs
            raise FormatError(f"refers to {name!r} as a model part: a model part's name ends "
                              "in .model", path=self.path)
        return member

    def parse(self, member: str, root: bool = False) -> None:
        """Read the model part ``member``: its base materials, objects and (for the root
        part) build items. :func:`~plumbob.formats.meshes.check_3mf_archive` has refused
        any DTD in it with defusedxml (there can be no entity to expand after its root);
        the bulk is parsed by lxml with entity resolution, DTDs and the network off."""
        from lxml import etree

        if member in self.parsed:
            return
        self.parsed.add(member)
        check_count("model parts", len(self.parsed), limits.MAX_ARCHIVE_MEMBERS, path=self.path)
        bases: dict[str, list[str]] = {}
        try:
            with self.archive.open(member) as raw, io.BufferedReader(raw, 1 << 20) as stream:
                for _, element in etree.iterparse(
                        stream, events=("end",), resolve_entities=False, no_network=True,
                        load_dtd=False, tag=("{*}basematerials", "{*}object", "{*}item")):
                    tag = _local(element.tag)
                    if tag == "basematerials":
                        bases[element.get("id", "")] = [
                            b.get("name", "") for b in element if _local(b.tag) == "base"]
                    elif tag == "object":
                        self._object(member, element, bases)
                    elif tag == "item" and root:
                        target = element.get(f"{_PRODUCTION}path")
                        check_count("build items", len(self.items) + 1, limits.MAX_PARTS,
                                    path=self.path)
                        self.items.append((self.part(target) if target else member,
                                           element.get("objectid", ""),
                                           _matrix(element.get("transform"), self.path)))
                    element.clear()
                    while element.getprevious() is not None:  # what was read is let go
                        del element.getparent()[0]
        except (FormatError, LimitError):
            raise
        except Exception as error:  # noqa: BLE001 - XML and zip errors of every kind
            text = str(error).splitlines()[0][:200] if str(error) else type(error).__name__
            raise FormatError(f"{member} cannot be read as a 3MF model: {text}",
                              path=self.path) from None

    def _object(self, member: str, element, bases: dict[str, list[str]]) -> None:
        found = _Object(name=element.get("name") or None,
                        material=_base(bases, element.get("pid"), element.get("pindex")))
        mesh = next((e for e in element if _local(e.tag) == "mesh"), None)
        if mesh is not None:
            vertices = next((e for e in mesh if _local(e.tag) == "vertices"), ())
            triangles = next((e for e in mesh if _local(e.tag) == "triangles"), ())
            self.triangles += len(triangles)
            check_count("triangles", self.triangles, limits.MAX_TRIANGLES, path=self.path)
            found.vertices = _numbers([f"{v.get('x')} {v.get('y')} {v.get('z')}"
                                       for v in vertices], False, "vertices", self.path)
            found.faces = _numbers([f"{t.get('v1')} {t.get('v2')} {t.get('v3')}"
                                    for t in triangles], True, "triangles", self.path)
            if len(found.faces) and (found.faces.min() < 0
                                     or found.faces.max() >= len(found.vertices)):
                raise FormatError(f"object {element.get('id')!r} has a triangle referring to a "
                                  "vertex it does not have", path=self.path)
            painted = set() if not len(triangles) or triangles.find(
                "{*}triangle[@p1]") is None else {
                (t.get("pid"), t.get("p1")) for t in triangles if t.get("p1") is not None}
            found.painted = {_base(bases, pid or element.get("pid"), p1) for pid, p1 in painted}
            found.painted.discard(None)
        for c in next((e for e in element if _local(e.tag) == "components"), ()):
            target = c.get(f"{_PRODUCTION}path")
            found.components.append((self.part(target) if target else member,
                                     c.get("objectid", ""), _matrix(c.get("transform"),
                                                                   self.path)))
        self.objects[(member, element.get("id", ""))] = found
        check_count("objects", len(self.objects), limits.MAX_PARTS, path=self.path)

    def instances(self) -> list[Instance]:
        """Every mesh object every build item places, placed, named and with its material."""
        out: list[Instance] = []
        visits = 0
        for member, top, matrix in self.items:  # per build item
            stack = [(member, top, matrix, None, None, ())]
            while stack:
                member, object_id, matrix, name, material, path = stack.pop()
                visits += 1  # components of components multiply: bounded, not just deep
                check_count("placed objects", visits, limits.MAX_PARTS, path=self.path)
                key = (member, object_id)
                if key in path:
                    raise FormatError(f"object {object_id!r} contains itself", path=self.path)
                if len(path) >= limits.MAX_NESTING:
                    raise LimitError(f"nests its components over {limits.MAX_NESTING} deep, "
                                     "plumbob's limit (plumbob.limits.MAX_NESTING)",
                                     path=self.path)
                if key not in self.objects and member not in self.parsed:
                    self.parse(member)
                found = self.objects.get(key)
                if found is None:
                    raise FormatError(f"places object {object_id!r}, which it does not define",
                                      path=self.path)
                name, material = found.name or name, found.material or material
                if found.faces is not None and len(found.faces):
                    check_count("part instances", len(out) + 1, limits.MAX_PARTS, path=self.path)
                    out.append(replace(self._placed(found, matrix, name or f"object {object_id}",
                                                    material), top=top, object_id=object_id))
                for part, child, inner in reversed(found.components):  # in the file's order
                    stack.append((part, child, matrix @ inner, name, material, path + (key,)))
        return out

    @staticmethod
    def _placed(found: _Object, matrix: np.ndarray, name: str,
                material: str | None) -> Instance:
        vertices, faces = found.vertices, found.faces
        if not np.allclose(matrix, np.eye(4)):
            with np.errstate(over="ignore", invalid="ignore"):
                vertices = vertices @ matrix[:3, :3].T + matrix[:3, 3]
            if np.linalg.slogdet(matrix[:3, :3])[0] < 0:
                faces = faces[:, ::-1]  # a mirror turns the winding inside out
        if material is None and len(found.painted) == 1:
            material = next(iter(found.painted))  # every triangle names the same one
        return Instance(name, vertices[faces], material, bool(found.painted - {material}),
                        None if material is None else f"base material {material!r}")


def _base(bases: dict[str, list[str]], pid: str | None, pindex: str | None) -> str | None:
    """The name of base material ``pindex`` of group ``pid``, or None (another kind of
    property: a colour, a texture; or none)."""
    group = bases.get(pid or "")
    if group is None:
        return None
    try:
        return group[int(pindex or 0)] or None
    except (ValueError, IndexError):
        return None


def _root_part(archive: zipfile.ZipFile, path: str) -> str:
    """The model part the package's relationships name (else ``3D/3dmodel.model``)."""
    import defusedxml.ElementTree as safe_xml

    names = {i.filename.lower(): i.filename for i in archive.infolist()}
    if "_rels/.rels" in names:
        try:
            rels = safe_xml.fromstring(archive.read(names["_rels/.rels"]), forbid_dtd=True)
        except Exception:  # noqa: BLE001 - a broken relationships part: fall back
            rels = ()
        for rel in rels:
            target = (rel.get("Target") or "").lstrip("/").lower()
            if rel.get("Type", "").endswith("/3dmodel") and target in names:
                return names[target]
    found = [n for low, n in names.items() if low.endswith("3dmodel.model")]
    if not found:
        raise FormatError("is a zip archive with no 3D model part (3D/3dmodel.model): "
                          "not a 3MF", path=path)
    return found[0]


def load_3mf(path: str) -> tuple[list[Instance], list[str]]:
    """The placed mesh objects of the 3MF ``path``, in the order its build gives them,
    as the slicer that wrote it has them (parts, names, extruders' filaments:
    :func:`~plumbob.formats.slicers.with_slicer_settings`), and notices about what was
    left out (check the archive first: :func:`~plumbob.formats.meshes.check_3mf_archive`)."""
    from .slicers import with_slicer_settings

    with zipfile.ZipFile(path) as archive:
        model = _Model(archive, path)
        model.parse(_root_part(archive, path), root=True)
        return with_slicer_settings(model.instances(), archive, path)


def material_notices(names: list[str], instances: list[Instance]):
    """For the parts ``names`` (one per instance): each one's plumbob material or None,
    the notices saying what was matched and what was not, and whether the file is
    multi-material (its parts name several materials: then every part needs a density)."""
    found: dict[str, tuple] = {}
    for instance in instances:  # per part
        if instance.material is not None and instance.material not in found:
            found[instance.material] = match_material(instance.material)
    notices = []
    sources = dict.fromkeys(i.source for i in instances if i.source is not None)
    for source in sources:  # per base material or extruder
        parts = ", ".join(repr(n) for n, i in zip(names, instances) if i.source == source)
        matched, how = found[next(i.material for i in instances if i.source == source)]
        if matched is None:
            notices.append(f"3mf: {source} ({parts}) names no plumbob material; "
                           "give it with --part-material NAME=MATERIAL")
        else:
            notices.append(f"3mf: {source} is {matched.name} "
                           f"({matched.density:g} kg/m³, by {how}): {parts}")
    painted = [repr(n) for n, i in zip(names, instances) if i.painted]
    if painted:
        notices.append(f"3mf: the triangles of {', '.join(painted)} name other materials "
                       "(painted faces); each part's volume takes its object's material")
    chosen = [found[i.material][0] if i.material is not None else None for i in instances]
    return chosen, notices, len(found) > 1


def match_material(name: str):
    """The plumbob material a 3MF base material's ``name`` names, and how, or
    ``(None, None)``: the whole name (``PLA``, ``Stainless steel``), else the one word of
    it that names a filament (``Generic PETG``, ``Bambu PLA Basic``).

    >>> m, how = match_material("Generic PETG"); m.name, how
    ('petg', "the word 'PETG'")
    >>> match_material("Green")
    (None, None)
    """
    from ..errors import MaterialError
    from ..materials import material, materials

    try:
        return material(name), "the name"
    except MaterialError:
        pass
    filaments = {k for k, m in materials().items() if m.category == "filament"}
    words = [w for w in name.replace("_", " ").replace("-", " ").split()
             if w.lower() in filaments]
    if len({w.lower() for w in words}) == 1:
        return material(words[0]), f"the word {words[0]!r}"
    return None, None
