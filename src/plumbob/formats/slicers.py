"""What a slicer's 3MF project adds to the core model: part names, and which extruder
(so which filament) prints each part.

Two conventions are read, both from the ``Metadata/`` folder of the archive:

* **PrusaSlicer** — ``Slic3r_PE_model.config`` (XML): per object (by its id in the
  model) its ``name`` and ``extruder``, and its *volumes*, ranges of the object's
  triangles (``firstid``…``lastid``) each with its own ``name``, ``extruder`` and
  ``volume_type``; the filaments are the ``; filament_type = PLA;PETG`` line of
  ``Slic3r_PE.config`` (extruder 1 first).
* **Bambu Studio / OrcaSlicer** — ``model_settings.config`` (XML): per object its
  ``name`` and ``extruder`` and per *part* (a component's object id) its ``name``,
  ``extruder`` and ``subtype``; the filaments are ``filament_type`` of
  ``project_settings.config`` (JSON).

Only printed parts count (PrusaSlicer's ``ModelPart``, Bambu's ``normal_part``):
modifiers and support blockers or enforcers are not material and are left out, with a
notice; a negative volume (a cut the slicer applies) is refused, since the mass
without the cut would be wrong. An extruder of 0 (or none) means the object's, and
the object's 0 means extruder 1. A part's filament type is its material name (matched
as a base material's is, :func:`plumbob.formats.threemf.match_material`); it takes
precedence over a core base material, since it is what will be printed.

The configuration parts are parsed with defusedxml; a part that cannot be read is
ignored (the model stays as the core specification has it), with a notice.
"""

from __future__ import annotations

import json
import zipfile
from dataclasses import replace

from ..errors import FormatError

__all__ = ["with_slicer_settings"]

_PRUSA_MODEL = "metadata/slic3r_pe_model.config"
_PRUSA_PRINT = "metadata/slic3r_pe.config"
_BAMBU_MODEL = "metadata/model_settings.config"
_BAMBU_PROJECT = "metadata/project_settings.config"
#: the slicers' names of printed parts
_PRINTED = {"modelpart", "normal_part", ""}
_NEGATIVE = {"negativevolume", "negative_part"}
#: the largest configuration part read (it holds settings, not geometry)
_MAX_CONFIG = 16 * 2**20


def _read(archive: zipfile.ZipFile, names: dict[str, str], name: str) -> bytes | None:
    member = names.get(name)
    if member is None or archive.getinfo(member).file_size > _MAX_CONFIG:
        return None
    return archive.read(member)


def _metadata(element) -> dict[str, str]:
    return {m.get("key", ""): m.get("value", "") for m in element if m.tag == "metadata"}


def _filaments_prusa(data: bytes | None) -> list[str]:
    for line in (data or b"").decode("utf-8", "replace").splitlines():
        key, _, value = line.lstrip("; ").partition("=")
        if key.strip() == "filament_type":
            return [v.strip().strip('"') for v in value.split(";")]
    return []


def _filaments_bambu(data: bytes | None) -> list[str]:
    try:
        types = json.loads(data or b"{}").get("filament_type", [])
    except (ValueError, AttributeError):
        return []
    return [str(t) for t in types] if isinstance(types, list) else []


def _extruder(*values: str | None) -> int:
    """The first extruder number of ``values`` that is set (not 0), else 1."""
    for value in values:
        try:
            number = int(value or 0)
        except ValueError:
            continue
        if number > 0:
            return number
    return 1


def with_slicer_settings(instances: list, archive: zipfile.ZipFile,
                         path: str) -> tuple[list, list[str]]:
    """``instances`` (:class:`~plumbob.formats.threemf.Instance`) as the slicer that wrote
    the archive has them — split into its parts, named, each with its extruder's
    filament — and notices saying what was left out; unchanged, with no notice, when
    the archive holds no slicer settings."""
    import defusedxml.ElementTree as safe_xml

    names = {i.filename.lower(): i.filename for i in archive.infolist()}
    prusa, bambu = _PRUSA_MODEL in names, _BAMBU_MODEL in names
    if not (prusa or bambu):
        return instances, []
    text = _read(archive, names, _PRUSA_MODEL if prusa else _BAMBU_MODEL)
    try:
        config = safe_xml.fromstring(text, forbid_dtd=True) if text is not None else None
    except Exception as error:  # noqa: BLE001 - a broken settings part: the core model stands
        return instances, [f"3mf: the slicer's settings ({type(error).__name__}) cannot be "
                           "read; parts and materials are the core model's"]
    if config is None:
        return instances, []
    if prusa:
        filaments = _filaments_prusa(_read(archive, names, _PRUSA_PRINT))
        return _prusa(instances, config, filaments, path)
    filaments = _filaments_bambu(_read(archive, names, _BAMBU_PROJECT))
    return _bambu(instances, config, filaments, path)


def _material(instance, extruder: int, filaments: list[str]):
    """``instance`` printed by ``extruder``: its filament's type as its material (when the
    project names the filaments; else its base material, if any, stands)."""
    if extruder <= len(filaments) and filaments[extruder - 1]:
        kind = filaments[extruder - 1]
        return replace(instance, material=kind, source=f"extruder {extruder} ({kind})")
    return instance


def _left_out(kinds: dict[str, list[str]]) -> list[str]:
    return [f"3mf: the slicer's {kind} {', '.join(repr(n) for n in parts)} "
            f"{'is' if len(parts) == 1 else 'are'} not printed material: left out"
            for kind, parts in kinds.items()]


def _prusa(instances: list, config, filaments: list[str], path: str):
    objects = {o.get("id", ""): o for o in config if o.tag == "object"}
    out, left = [], {}
    for instance in instances:  # per placed object
        found = objects.get(instance.object_id)
        if found is None:
            out.append(instance)
            continue
        meta = _metadata(found)
        name = meta.get("name") or instance.name
        volumes = [v for v in found if v.tag == "volume"]
        if not volumes:
            out.append(_material(replace(instance, name=name), _extruder(meta.get("extruder")),
                                 filaments))
            continue
        for volume in volumes:  # per volume of the object
            vmeta = _metadata(volume)
            kind = vmeta.get("volume_type", "ModelPart")
            part = vmeta.get("name") or name
            if kind.lower() in _NEGATIVE:
                raise FormatError(f"PrusaSlicer's negative volume {part!r} cuts object "
                                  f"{name!r}: apply the cut in the slicer (or export the "
                                  "objects as a plain 3MF or STL) and read that", path=path)
            if kind.lower() not in _PRINTED:
                left.setdefault(kind, []).append(part)
                continue
            try:
                first, last = int(volume.get("firstid", "")), int(volume.get("lastid", ""))
            except ValueError:
                raise FormatError(f"its PrusaSlicer settings give volume {part!r} no "
                                  "triangle range (firstid, lastid)", path=path) from None
            if not 0 <= first <= last < len(instance.triangles):
                raise FormatError(f"its PrusaSlicer settings give volume {part!r} triangles "
                                  f"{first}…{last}, which object {name!r} does not have",
                                  path=path)
            piece = replace(instance, name=part, triangles=instance.triangles[first:last + 1])
            out.append(_material(piece, _extruder(vmeta.get("extruder"), meta.get("extruder")),
                                 filaments))
    return out, _left_out(left)


def _bambu(instances: list, config, filaments: list[str], path: str):
    objects = {o.get("id", ""): o for o in config if o.tag == "object"}
    out, left = [], {}
    for instance in instances:  # per placed mesh object
        found = objects.get(instance.top)
        if found is None:
            out.append(instance)
            continue
        meta = _metadata(found)
        parts = {p.get("id", ""): p for p in found if p.tag == "part"}
        part = parts.get(instance.object_id)
        pmeta = _metadata(part) if part is not None else {}
        name = pmeta.get("name") or meta.get("name") or instance.name
        kind = (part.get("subtype", "normal_part") if part is not None else "normal_part")
        if kind.lower() in _NEGATIVE:
            raise FormatError(f"Bambu Studio's negative part {name!r} cuts object "
                              f"{meta.get('name') or instance.top!r}: apply the cut in the "
                              "slicer (or export the objects as a plain 3MF or STL) and read "
                              "that", path=path)
        if kind.lower() not in _PRINTED:
            left.setdefault(kind, []).append(name)
            continue
        out.append(_material(replace(instance, name=name),
                             _extruder(pmeta.get("extruder"), meta.get("extruder")), filaments))
    return out, _left_out(left)
