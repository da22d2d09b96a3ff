"""Naming the bodies of a file, and gathering several into one.

A file may hold several bodies (ASCII STL ``solid`` blocks, 3MF objects, the
outlines of a drawing); they become the named parts of one
:class:`~plumbob.bodies.csg.Assembly`, named after the file.
"""

from __future__ import annotations

import os

from ..bodies.base import Body

__all__ = ["stem", "unique_names", "assemble"]


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
