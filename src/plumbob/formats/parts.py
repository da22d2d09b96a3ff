"""Naming the bodies of a file, and gathering several into one.

A file may hold several bodies (ASCII STL ``solid`` blocks, 3MF objects, the
outlines of a drawing); they become the named parts of one
:class:`~plumbob.bodies.csg.Assembly`, named after the file.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import replace

from ..bodies.base import Body
from ..errors import DensityError
from ..reading import Reading

__all__ = ["stem", "unique_names", "assemble", "with_part_materials", "with_file_materials",
           "require_part_densities", "CAD_SUFFIXES"]

#: the files whose assemblies need a density for every part (:func:`require_part_densities`)
CAD_SUFFIXES = (".step", ".stp", ".iges", ".igs", ".brep")


def stem(path: str) -> str:
    """The file's name without folder or extension: the name of what it holds.

    >>> stem("parts/bracket.v2.stl")
    'bracket.v2'
    """
    return os.path.splitext(os.path.basename(path))[0]


def unique_names(names: list[str]) -> list[str]:
    """Names made distinct for a per-body table: repeats get " (2)", " (3)", …

    >>> unique_names(["lid", "box", "lid", "lid"])
    ['lid', 'box', 'lid (2)', 'lid (3)']
    """
    seen: dict[str, int] = {}
    out = []
    for name in names:  # per body
        seen[name] = seen.get(name, 0) + 1
        out.append(name if seen[name] == 1 else f"{name} ({seen[name]})")
    return out


def assemble(parts: list[Body], name: str | None) -> Body:
    """The one body, or an :class:`~plumbob.bodies.csg.Assembly` of several named ``name``."""
    if len(parts) == 1:
        return parts[0]
    from ..bodies.csg import Assembly

    return Assembly(tuple(parts), name=name)


def with_part_materials(reading: Reading, materials: Mapping[str, str], option: str) -> Reading:
    """``reading`` with a density for each part of its assembly (or its one body) whose
    name matches a key of ``materials`` (an exact name or a glob: ``"post*"``); the value
    is a material name from ``plumbob materials`` or a density in kg/m³. A part takes
    the first key that matches it. A key that matches no part, or a part that gives its
    own density, is an error (``option`` names the option in messages).

    >>> from plumbob.bodies.csg import Assembly
    >>> from plumbob.bodies.primitives import box
    >>> two = Reading(Assembly((box(1, 1, 1, name="base"), box(1, 1, 1, name="post"))))
    >>> read = with_part_materials(two, {"base": "steel", "p*": "1000"}, "--part-material")
    >>> [p.mass_properties().mass for p in read.body.assembly_parts()], read.materials
    ([7850.0, 1000.0], (('base', 'steel'), ('post', '1000 kg/m³')))
    """
    from fnmatch import fnmatchcase

    from ..materials import check_density
    from ..materials import material as named

    body = reading.body
    parts = body.assembly_parts() or (body,)
    names = [p.name or f"part {i + 1}" for i, p in enumerate(parts)]
    unused = [key for key in materials if not any(fnmatchcase(n, key) for n in names)]
    if unused:
        raise DensityError(f"{option}: {', '.join(repr(k) for k in unused)} matches no part; "
                           f"the parts are {', '.join(repr(n) for n in names)}", path=reading.path)
    new, given = [], []
    for part, name in zip(parts, names):
        key = next((k for k in materials if fnmatchcase(name, k)), None)
        if key is None:
            new.append(part)
            continue
        value = str(materials[key]).strip()
        try:
            density, label = check_density(float(value), f"{option} {key}"), f"{value} kg/m³"
        except ValueError:
            density, label = named(value).density, value
        if part.densities() != {None}:
            raise DensityError(f"{option}: part {name!r} gives its own density in the file; "
                               "remove it from the option", path=reading.path)
        new.append(part.with_default_density(density))
        given.append((name, label))
    if body.assembly_parts():
        from ..bodies.csg import Assembly

        body = Assembly(tuple(new), name=body.name)
    else:
        body = new[0]
    return replace(reading, body=body, materials=reading.materials + tuple(given))


def with_file_materials(reading: Reading) -> Reading:
    """``reading`` with the materials its file names (:attr:`Reading.file_materials`: a
    3MF's base materials, a slicer's filaments) given to the parts that have no density
    yet — after ``--part-material``, so a part the user names keeps the user's.

    >>> from plumbob.bodies.csg import Assembly
    >>> from plumbob.bodies.primitives import box
    >>> two = Reading(Assembly((box(1, 1, 1, name="a"), box(1, 1, 1, name="b"))),
    ...               file_materials=(("a", "pla", 1240.0), ("b", "petg", 1270.0)))
    >>> mine = with_part_materials(two, {"b": "abs"}, "--part-material")
    >>> read = with_file_materials(mine)
    >>> [p.mass_properties().mass for p in read.body.assembly_parts()], read.materials
    ([1240.0, 1040.0], (('b', 'abs'), ('a', 'pla')))
    """
    if not reading.file_materials:
        return reading
    given = dict((name, (label, density)) for name, label, density in reading.file_materials)
    body = reading.body
    parts = body.assembly_parts() or (body,)
    names = [p.name or f"part {i + 1}" for i, p in enumerate(parts)]
    new, labels = [], []
    for part, name in zip(parts, names):
        if name in given and part.densities() == {None}:
            part = part.with_default_density(given[name][1])
            labels.append((name, given[name][0]))
        new.append(part)
    if body.assembly_parts():
        from ..bodies.csg import Assembly

        body = Assembly(tuple(new), name=body.name)
    else:
        body = new[0]
    return replace(reading, body=body, materials=reading.materials + tuple(labels),
                   file_materials=())


def require_part_densities(reading: Reading, how: str) -> Reading:
    """``reading`` unchanged when it is not a CAD or multi-material assembly or every part
    has a density; else a :class:`DensityError` listing every part without one (``how``:
    the option that gives them). A CAD file's parts, or a multi-material 3MF's
    (:attr:`Reading.densities_required`), are of different materials: one default
    density for all would be a wrong answer, not an assumption."""
    parts = reading.body.assembly_parts()
    cad = reading.path is not None and reading.path.lower().endswith(CAD_SUFFIXES)
    if len(parts) < 2 or not (cad or reading.densities_required):
        return reading
    missing = [p.name or f"part {i + 1}" for i, p in enumerate(parts) if None in p.densities()]
    if missing:
        raise DensityError(f"{len(missing)} part{'s' if len(missing) > 1 else ''} with no "
                           f"density: {', '.join(repr(n) for n in missing)}; give each a "
                           f"material with {how} (a glob matches several)", path=reading.path)
    return reading
