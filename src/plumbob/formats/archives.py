"""Compressed and archived inputs: ``.zip``, ``.gz``, ``.bz2``, ``.xz``, ``.tar``, ``.tgz``.

A mesh or outline often travels packed (``part.stl.gz``, ``rock.obj.bz2``, a ``.zip``
from a download site). The archive is unpacked into a private temporary folder and
the one file plumbob reads in it is handed to the ordinary reader for its extension:

* a single compressed file (``.gz``, ``.bz2``, ``.xz``) holds the file its name
  says once the compression suffix is dropped (``part.stl.gz`` holds ``part.stl``);
* a ``.zip``, ``.tar``, ``.tar.gz``/``.tgz``, ``.tar.bz2``, ``.tar.xz`` must hold
  exactly one file of a format plumbob reads (other members — a glTF's ``.bin``,
  an OBJ's ``.mtl``, textures — are unpacked beside it; macOS ``__MACOSX/`` and
  ``._`` resource forks are ignored); several are refused, listing them.

Why a temporary folder rather than memory: the readers take paths (a glTF finds
its buffers beside it), and a file on disk keeps memory bounded however large the
member. Nothing is ever written outside that folder: a member named absolutely or
with ``..`` is refused, links and devices in a tar are never created (skipped),
and two members of one name are refused rather than one overwriting the other.

Every byte is counted while it is decompressed (streaming, never trusting the sizes
an archive declares): past :data:`plumbob.limits.MAX_ARCHIVE_BYTES`, or past
:data:`~plumbob.limits.MAX_ARCHIVE_RATIO` times the archive's own size (beyond a
1 MiB allowance), the archive is refused as a possible bomb. A 3MF is a zip too but
keeps its own reader (:mod:`plumbob.formats.meshes`). An archive inside an archive is
refused. Errors name ``archive:member``; a notice says which member was read.
"""

from __future__ import annotations

import bz2
import gzip
import lzma
import os
import shutil
import tarfile
import tempfile
import zipfile
import zlib
from collections.abc import Callable
from dataclasses import replace
from typing import IO

from .. import limits
from ..errors import FormatError, LimitError, PlumbobError, printable
from ..limits import check_count
from ..reading import Reading

__all__ = ["ARCHIVE_SUFFIXES", "archive_kind", "read_archive"]

#: archive name endings, longest first, → (container, compression)
ARCHIVE_SUFFIXES = {
    ".tar.gz": ("tar", "gzip"), ".tar.bz2": ("tar", "bzip2"), ".tar.xz": ("tar", "xz"),
    ".tgz": ("tar", "gzip"), ".tar": ("tar", None), ".zip": ("zip", None),
    ".gz": ("single", "gzip"), ".bz2": ("single", "bzip2"), ".xz": ("single", "xz"),
}
_OPENERS = {"gzip": gzip.open, "bzip2": bz2.open, "xz": lzma.open}
#: every archive may expand to this much whatever its ratio (small files compress well)
RATIO_ALLOWANCE = 1 << 20
CHUNK = 1 << 20


def archive_kind(name: str) -> tuple[str, str | None, str]:
    """(container, compression, the name's ending) of an archive's file name."""
    lower = name.lower()
    for ending, (container, compression) in ARCHIVE_SUFFIXES.items():  # a few endings
        if lower.endswith(ending):
            return container, compression, ending
    raise FormatError("is not an archive plumbob reads "
                      f"({', '.join(ARCHIVE_SUFFIXES)})", path=name)


class _Budget:
    """The bytes an archive may still expand to; counting every decompressed byte."""

    def __init__(self, path: str) -> None:
        self.path = path
        packed = os.path.getsize(path)
        by_ratio = max(RATIO_ALLOWANCE, limits.MAX_ARCHIVE_RATIO * packed)
        self.limit = min(limits.MAX_ARCHIVE_BYTES, by_ratio)
        self.ratio_bound = by_ratio < limits.MAX_ARCHIVE_BYTES
        self.used = 0

    def take(self, count: int) -> None:
        self.used += count
        if self.used > self.limit:
            if self.ratio_bound:
                raise LimitError(
                    f"expands past {self.limit} bytes, over {limits.MAX_ARCHIVE_RATIO} times its "
                    "own size (plumbob.limits.MAX_ARCHIVE_RATIO): refused as a possible "
                    "decompression bomb", path=self.path)
            raise LimitError(f"expands past plumbob's limit of {limits.MAX_ARCHIVE_BYTES} bytes "
                             "(plumbob.limits.MAX_ARCHIVE_BYTES): refused", path=self.path)


class _Counted:
    """A read-only stream charging every byte it gives to a :class:`_Budget`."""

    def __init__(self, stream: IO[bytes], budget: _Budget) -> None:
        self.stream, self.budget = stream, budget

    def read(self, size: int = -1) -> bytes:
        size = CHUNK if size is None or size < 0 else min(size, CHUNK)
        data = self.stream.read(size)
        self.budget.take(len(data))
        return data


def _copy(source: IO[bytes], target_path: str, budget: _Budget | None) -> None:
    """Copy ``source`` to a new file ``target_path`` chunk by chunk, within ``budget``
    (None: ``source`` is already counted)."""
    with open(target_path, "xb") as target:
        while data := source.read(CHUNK):
            if budget is not None:
                budget.take(len(data))
            target.write(data)


def _safe_name(name: str, archive: str) -> str | None:
    """The member ``name`` as a relative path inside the unpacking folder; None for
    macOS resource forks and folders; a :class:`FormatError` for a name reaching
    outside (absolute, a drive, ``..``) or holding control characters."""
    parts = name.replace("\\", "/").split("/")
    if name.startswith(("/", "\\")) or (name[:1].isalpha() and name[1:2] == ":") or ".." in parts \
            or any(ord(c) < 32 or ord(c) == 127 for c in name):
        raise FormatError(f"holds a member named '{printable(name)}', which points outside "
                          "the archive (absolute, a drive or '..'): refused unread", path=archive)
    parts = [p for p in parts if p not in ("", ".")]
    if not parts or parts[0] == "__MACOSX" or parts[-1].startswith("._"):
        return None
    return os.path.join(*parts)


def _place(folder: str, relative: str, archive: str) -> str:
    target = os.path.join(folder, relative)
    os.makedirs(os.path.dirname(target), exist_ok=True)
    if os.path.lexists(target):
        raise FormatError(f"holds two members named '{printable(relative)}': refused",
                          path=archive)
    return target


def _unpack_zip(path: str, folder: str, budget: _Budget) -> list[str]:
    try:
        archive = zipfile.ZipFile(path)
        members = archive.infolist()
    except Exception as error:  # noqa: BLE001 - zipfile raises many kinds on corrupt input
        raise FormatError(f"is not a readable zip archive: {error}", path=path) from None
    with archive:
        check_count("archive members", len(members), limits.MAX_ARCHIVE_MEMBERS, path=path)
        declared = sum(m.file_size for m in members)
        if declared > budget.limit:  # refused unread; the counting below is what binds
            budget.take(declared)
        names = []
        for member in members:  # per member: a few
            relative = _safe_name(member.filename, path)
            if relative is None or member.is_dir():
                continue
            target = _place(folder, relative, path)
            with archive.open(member) as stream:  # a link is unpacked as plain data
                _copy(stream, target, budget)
            names.append(relative)
    return names


def _unpack_tar(stream: IO[bytes], path: str, folder: str, budget: _Budget) -> list[str]:
    names, count = [], 0
    with tarfile.open(fileobj=_Counted(stream, budget), mode="r|") as archive:
        for member in archive:  # streaming, in order
            count += 1
            check_count("archive members", count, limits.MAX_ARCHIVE_MEMBERS, path=path)
            relative = _safe_name(member.name, path)
            if relative is None or not member.isreg():  # links, devices: never created
                continue
            source = archive.extractfile(member)
            if source is None:
                continue
            _copy(source, _place(folder, relative, path), None)  # counted as read
            names.append(relative)
    return names


def _unpack(path: str, folder: str) -> tuple[list[str], str]:
    """Unpack ``path`` into ``folder``: the member paths written, and the archive's kind."""
    container, compression, ending = archive_kind(path)
    budget = _Budget(path)
    kind = f"{container} ({compression})" if container == "tar" and compression else \
        compression or container
    opener = _OPENERS[compression] if compression else open
    try:
        if container == "zip":
            return _unpack_zip(path, folder, budget), kind
        with opener(path, "rb") as stream:
            if container == "tar":
                return _unpack_tar(stream, path, folder, budget), kind
            inner = _safe_name(os.path.basename(path)[: -len(ending)], path)
            if inner is None or os.path.splitext(inner)[1] == "":
                raise FormatError(f"is a {compression} file whose name does not say what it "
                                  "holds: name it like part.stl.gz", path=path)
            _copy(stream, os.path.join(folder, inner), budget)
            return [inner], kind
    except PlumbobError:
        raise
    except NotImplementedError as error:  # a zip compression Python lacks
        raise FormatError(f"uses a compression Python cannot read ({error}): pack it again "
                          "with plain zip (deflate)", path=path) from None
    except (OSError, EOFError, lzma.LZMAError, tarfile.TarError, zipfile.BadZipFile,
            ValueError, zlib.error) as error:
        text = str(error).splitlines()[0][:200] if str(error) else type(error).__name__
        raise FormatError(f"is not a readable {kind} archive: {text}", path=path) from None


def read_archive(path: str, read_member: Callable[[str], Reading],
                 readable: Callable[[str], bool]) -> Reading:
    """Read the one file plumbob reads inside the archive ``path`` (see module docstring).

    ``readable(name)``: whether plumbob reads a file of that name (not an archive);
    ``read_member(path)``: its reading. Errors name ``archive:member``.
    """
    folder = tempfile.mkdtemp(prefix="plumbob-")  # private: mode 0700
    try:
        names, kind = _unpack(path, folder)
        chosen = [n for n in names if readable(n)]
        if len(chosen) != 1:
            shown = ", ".join(printable(n) for n in (chosen or names)[:8])
            more = ", …" if len(chosen or names) > 8 else ""
            if not chosen:
                raise FormatError(f"holds no file plumbob reads ({len(names)} member(s)"
                                  f"{': ' + shown + more if names else ''}); archives "
                                  "inside archives are not opened", path=path)
            raise FormatError(f"holds {len(chosen)} files plumbob reads ({shown}{more}): "
                              "give one of them, or an archive holding one", path=path)
        member = chosen[0]
        inner = os.path.join(folder, member)
        shown = f"{path}:{printable(member)}"
        try:
            reading = read_member(inner)
        except PlumbobError as error:
            if error.path and error.path.startswith(folder):  # never show the temp folder
                error.path, error.message = None, error.message.replace(inner, shown)
                raise error.within(path=shown) from None
            raise
        notices = tuple(n.replace(inner, shown) for n in reading.notices)
        note = f"{kind}: read {printable(member)} from the archive"
        return replace(reading, notices=(note, *notices), path=path)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
