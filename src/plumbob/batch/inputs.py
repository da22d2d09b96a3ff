"""Which files a batch reads: files as given, folders searched recursively for the
extensions plumbob reads, and glob patterns (``**`` crosses folders)."""

from __future__ import annotations

import glob
import os
from collections.abc import Iterable

from ..errors import ArgumentError, InputFileError

__all__ = ["discover"]

_GLOB_CHARACTERS = set("*?[")


def _known(path: str) -> bool:
    from ..loading import SUFFIXES

    return os.path.splitext(path)[1].lower() in SUFFIXES


def _walk(folder: str) -> list[str]:
    """Files under ``folder`` with a known extension, in a stable (sorted) order."""
    found = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        found += [os.path.join(root, f) for f in sorted(files)
                  if not f.startswith(".") and _known(f)]
    return found


def discover(inputs: Iterable[str], exclude: Iterable[str] = ()) -> list[str]:
    """The files to read, each once, in the order the inputs name them.

    A file given by name is kept whatever its extension (an unreadable one becomes a
    failed row that says why); folders and globs keep only known extensions. Paths in
    ``exclude`` (the run's own output files) are left out. A glob or folder that finds
    nothing is an error: it is almost always a typo.
    """
    skip = {os.path.realpath(p) for p in exclude}
    seen: set[str] = set()
    files: list[str] = []
    for item in inputs:
        if not isinstance(item, (str, os.PathLike)):
            raise ArgumentError(f"inputs must be files, folders or globs, not {item!r}")
        item = os.fspath(item)
        if os.path.isdir(item):
            found = _walk(item)
        elif _GLOB_CHARACTERS & set(item) and not os.path.exists(item):
            found = [p for p in sorted(glob.glob(item, recursive=True))
                     if os.path.isfile(p) and _known(p)]
        else:
            found = [item]
        found = [p for p in found if os.path.realpath(p) not in skip]
        if not found:
            what = "folder" if os.path.isdir(item) else "pattern"
            raise InputFileError(f"this {what} holds no file plumbob reads", path=item)
        for path in found:
            key = os.path.normpath(path)
            if key not in seen:
                seen.add(key)
                files.append(path)
    return files
