"""Reading bodies from files: dispatch on the file's extension.

``read(path, units=None, repair=False)`` returns a :class:`Reading`: the body
and the notices a user should see (assumed units, repaired defects).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from ..bodies.base import Body
from ..errors import InputFileError

__all__ = ["Reading", "read", "SUFFIXES"]


@dataclass(frozen=True)
class Reading:
    """A body read from a file, with notices for the user (assumptions, repairs)."""

    body: Body
    notices: tuple[str, ...] = ()
    path: str | None = None


SUFFIXES = {
    ".toml": "spec",
    ".stl": "stl",
    ".geojson": "outline", ".json": "outline", ".wkt": "outline",
}


def read(path: str, *, units: str | None = None, repair: bool = False) -> Reading:
    """Read the body in ``path``; the reader is chosen by the file's extension."""
    suffix = os.path.splitext(path)[1].lower()
    kind = SUFFIXES.get(suffix)
    if kind is None:
        known = ", ".join(sorted(SUFFIXES))
        raise InputFileError(f"unknown file type {suffix or '(no extension)'!r}; plumbob reads {known}",
                             path=path)
    if not os.path.exists(path):
        raise InputFileError("no such file", path=path)
    if os.path.isdir(path):
        raise InputFileError("is a folder, not a file", path=path)
    if kind == "spec":
        from ..spec.loader import load_spec

        return load_spec(path)
    if kind == "stl":
        from .stl import read_stl

        return read_stl(path, units=units)
    from .outlines import read_outline

    return read_outline(path, units=units)
