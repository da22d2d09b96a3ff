"""Reading any file plumbob understands: a TOML spec, a mesh or an outline.

:func:`read` chooses by the file's extension: ``.toml`` goes to the spec reader
(:mod:`plumbob.spec`), every other known extension to the file-format readers
(:mod:`plumbob.io`). Living above both, this dispatcher lets spec read its mesh
files through io while io never imports spec.
"""

from __future__ import annotations

import os

from . import io
from .reading import Reading

__all__ = ["read", "SUFFIXES"]

#: file extension → reader family: specs, and every format :mod:`plumbob.io` reads
SUFFIXES = {".toml": "spec", **io.SUFFIXES}


def read(path: str, *, units: str | None = None, repair: bool = False) -> Reading:
    """Read the body in ``path``: a shape or simulation spec (``.toml``), a mesh or an
    outline file, chosen by the extension.

    ``units``: the length unit of a mesh's or outline's coordinates (``mm``, ``cm``,
    ``m``, ``in``, ``ft``); None uses the unit the file declares, else metres (with a
    notice). ``repair``: close small holes in open meshes. A spec gives its own units
    and ignores both. Every failure is a :class:`~plumbob.errors.PlumbobError` naming
    the file.
    """
    path = os.fspath(path)
    if io.file_family(path, SUFFIXES) == "spec":
        from .spec.loader import load_spec  # the spec builders are needed only for specs

        return load_spec(path)
    return io.read(path, units=units, repair=repair)
