"""Files in and out, safely: inputs are regular files read with a bound, outputs are
written whole or not at all.

A FIFO, a device such as ``/dev/zero`` or a folder given as input would otherwise
block or be read forever; every reader goes through :func:`require_regular_file`
(via :func:`plumbob.formats.read_checked`) and reads whole files with :func:`read_bytes`.
Every output file (pictures, pose meshes, hollowed bodies, HTML reports) is written by
:func:`write_atomic`: to a temporary file beside the target, renamed over it once
complete, so an interrupted or failed run never leaves a partial file.
"""

from __future__ import annotations

import os
import stat

from .errors import InputFileError, PlumbobError
from .limits import MAX_FILE_BYTES

__all__ = ["read_bytes", "require_regular_file", "write_atomic"]


def require_regular_file(path: str) -> int:
    """The size in bytes of ``path``, once it is known to be an existing regular file
    (symbolic links are followed); else an :class:`InputFileError` saying what it is.

    >>> require_regular_file("/dev/null")
    Traceback (most recent call last):
    ...
    plumbob.errors.InputFileError: /dev/null: is a device, not a regular file; give a file
    """
    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise InputFileError("no such file", path=path) from None
    except OSError as error:
        raise InputFileError(f"cannot be read: {error.strerror or error}", path=path) from None
    mode = info.st_mode
    if stat.S_ISDIR(mode):
        raise InputFileError("is a folder, not a file", path=path)
    if not stat.S_ISREG(mode):
        kind = ("a pipe (FIFO)" if stat.S_ISFIFO(mode) else
                "a socket" if stat.S_ISSOCK(mode) else "a device")
        raise InputFileError(f"is {kind}, not a regular file; give a file", path=path)
    if info.st_size > MAX_FILE_BYTES:
        raise InputFileError(
            f"is {info.st_size} bytes, over plumbob's limit of {MAX_FILE_BYTES} bytes "
            "(plumbob.limits.MAX_FILE_BYTES)", path=path)
    return info.st_size


def read_bytes(path: str, limit: int = MAX_FILE_BYTES) -> bytes:
    """The whole of the regular file ``path``, refusing one over ``limit`` bytes
    (checked before reading, and again while reading in case the file grows)."""
    size = require_regular_file(path)
    if size > limit:
        raise InputFileError(f"is {size} bytes, over the limit of {limit} bytes for this kind "
                             "of file", path=path)
    try:
        with open(path, "rb") as handle:
            data = handle.read(min(limit, size) + 1)  # never ask for more than is there
    except OSError as error:
        raise InputFileError(f"cannot be read: {error.strerror or error}", path=path) from None
    if len(data) > limit:
        raise InputFileError(f"grew past the limit of {limit} bytes while being read", path=path)
    return data


def write_atomic(path: str, data: bytes | None = None, writer=None) -> None:
    """Write ``data`` (or call ``writer(file)``) to ``path`` through a temporary file in the
    same folder, renamed over ``path`` only once complete."""
    import tempfile  # here: the commands import this module on every run

    folder = os.path.dirname(os.path.abspath(path))
    try:
        fd, tmp = tempfile.mkstemp(prefix=".plumbob-", suffix=os.path.splitext(path)[1],
                                   dir=folder)
    except OSError as exc:
        raise PlumbobError(f"cannot write {path}: {exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, "wb") as handle:
            if writer is not None:
                writer(handle)
            else:
                handle.write(data or b"")
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # as an ordinary new file, not mkstemp's private mode
        os.replace(tmp, path)
    except OSError as exc:
        raise PlumbobError(f"cannot write {path}: {exc.strerror or exc}") from None
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
