"""STL, binary and ASCII, read fast and in bounded memory.

No vertex merging is needed for mass properties, so the reader hands the
triangle soup straight to :class:`~plumbob.bodies.solid.MeshSolid`:

* binary STL is recognised by its length (``84 + 50 n`` bytes for the ``n``
  triangles its header announces) and read in chunks of records into one
  float32 array (n, 3, 3) — about 0.72 × the file size, nothing more is kept;
* ASCII STL is read in blocks cut at facet ends; each block's ``vertex`` lines
  are found with numpy byte comparisons and their numbers parsed in one C call
  — no Python loop per line. Several ``solid … endsolid`` blocks become several
  bodies.

This module imports neither shapely, trimesh nor manifold3d (manifold3d only
if overlapping shells have to be united).
"""

from __future__ import annotations

import sys
import warnings
from typing import NamedTuple

import numpy as np

from .. import limits
from ..errors import FormatError, InputFileError
from ..files import require_regular_file
from ..limits import check_count
from ..reading import Reading
from ..units import reading_unit, unit_assumed, units_scale
from .checks import check_extent, check_reach, raise_nonfinite
from .parts import assemble, stem, unique_names

__all__ = ["STL_RECORD", "StlSolid", "StlFile", "load_stl", "read_stl"]

#: one binary STL record: normal, three vertices, attribute byte count
STL_RECORD = np.dtype([("normal", "<f4", (3,)), ("tri", "<f4", (3, 3)), ("attr", "<u2")])
CHUNK = 1 << 14  # binary records per read (3.2 MB)
ASCII_BLOCK = 1 << 23  # bytes per ASCII read
MAX_LINE = 1 << 24  # an ASCII STL with no facet end in this many bytes is not one


class StlSolid(NamedTuple):
    """One solid of an STL file: its name (or None) and triangles (n, 3, 3) in file units."""

    name: str | None
    triangles: np.ndarray


class StlFile(NamedTuple):
    """What an STL file holds: solids, whether it was binary, the largest coordinate
    magnitude (``reach``, file units), the bounding box when it was found while
    parsing (``lo``, ``hi``; ASCII only) and notices about the file itself."""

    solids: tuple[StlSolid, ...]
    binary: bool
    reach: float
    lo: np.ndarray | None = None
    hi: np.ndarray | None = None
    notices: tuple[str, ...] = ()

    @property
    def triangles(self) -> int:
        return sum(len(s.triangles) for s in self.solids)


def load_stl(path: str) -> StlFile:
    """Parse the STL at ``path`` (no units, no checks beyond the format, finiteness and
    :data:`plumbob.limits.MAX_TRIANGLES`, checked from the header before allocating).

    Only a regular file is read (:func:`plumbob.files.require_regular_file`), in blocks
    bounded by its size."""
    size = require_regular_file(path)
    try:
        with open(path, "rb") as f:
            head = f.read(84)
    except OSError as error:
        raise InputFileError(f"cannot be read: {error.strerror or error}", path=path) from None
    if size == 0:
        raise InputFileError("is empty (0 bytes): nothing to read", path=path)
    looks_ascii = head.lstrip()[:5].lower() == b"solid"
    if size >= 84:
        count = int.from_bytes(head[80:84], "little")
        if 84 + 50 * count == size and not (count == 0 and looks_ascii):
            if count == 0:
                raise FormatError("is a binary STL of 0 triangles: there is no solid to "
                                  "measure", path=path)
            check_count("triangles", count, limits.MAX_TRIANGLES, path=path,
                        hint="split the mesh or raise plumbob.limits.MAX_TRIANGLES")
            return _load_binary(path, count)
        if looks_ascii:
            loaded = _load_ascii(path, size)
            if loaded is not None:
                return loaded
        _length_mismatch(path, count, size)
    if looks_ascii:
        loaded = _load_ascii(path, size)
        if loaded is not None:
            return loaded
        raise FormatError("starts like an ASCII STL ('solid') but has no facets", path=path)
    raise InputFileError(
        f"is {size} bytes: too short for a binary STL (at least 84) and not an ASCII STL "
        "(which starts with 'solid'); it is truncated or not an STL", path=path)


def _length_mismatch(path: str, count: int, size: int) -> None:
    need = 84 + 50 * count
    room = (size - 84) // 50
    if size < need:
        raise InputFileError(
            f"binary STL header says {count} triangles, which need {need} bytes, but the file "
            f"has {size} (room for {room}): it is truncated (an interrupted download?) or corrupt",
            path=path)
    raise FormatError(
        f"binary STL header says {count} triangles, which need {need} bytes, but the file has "
        f"{size} ({size - need} more): it is corrupt or not an STL", path=path)


def _load_binary(path: str, count: int) -> StlFile:
    triangles = np.empty((count, 3, 3), dtype=np.float32)
    reach = 0.0
    records = np.empty(min(count, CHUNK), dtype=STL_RECORD)
    raw = records.view(np.uint8)
    # On a little-endian machine each record's 36 vertex bytes are the float32s we want:
    # copy them as opaque 36-byte items (one memcpy each), not field by field.
    item = np.dtype((np.void, 36))
    little = sys.byteorder == "little"
    target = triangles.reshape(count, 9).view(item).reshape(count) if little else None
    source = np.ndarray((len(records),), dtype=item, buffer=raw, offset=12, strides=(50,))
    with open(path, "rb") as f:
        header = f.read(84)
        for start in range(0, count, CHUNK):
            k = min(CHUNK, count - start)
            if f.readinto(raw[: 50 * k]) != 50 * k:
                raise InputFileError("ended while being read (was it being written?)", path=path)
            if little:
                target[start:start + k] = source[:k]
            else:
                triangles[start:start + k] = records["tri"][:k]
            block = triangles[start:start + k]
            low, high = float(block.min()), float(block.max())  # NaN propagates
            if not (np.isfinite(low) and np.isfinite(high)):
                raise_nonfinite(block, start, path=path, what="triangle")
            reach = max(reach, -low, high)
    name = _header_name(header[:80])
    # The bounding box comes with the closure test (one float64 pass in check_solid).
    return StlFile((StlSolid(name, triangles),), True, reach)


def _header_name(header: bytes) -> str | None:
    """The name in a binary STL header of the form ``solid NAME`` (many exporters write
    it); other header text (an exporter's banner, ``COLOR=…``) names nothing."""
    text = header.split(b"\0", 1)[0].strip()
    if text[:6].lower() != b"solid ":
        return None
    text = text[6:].strip()
    if not text or not all(32 <= c < 127 for c in text):
        return None
    return text.decode("ascii")


# ------------------------------------------------------------------ ASCII
def _line_tokens(a: np.ndarray, prev: np.ndarray, word: bytes) -> np.ndarray:
    """Start positions of ``word`` as the first token of a line of ``a`` (lower-case uint8).

    ``prev[i]``: position of the last newline or non-blank byte at or before i (−1: none).
    """
    n = len(word)
    pos = np.flatnonzero(a[: max(len(a) - n + 1, 0)] == word[0])
    for i in range(1, n):
        pos = pos[a[pos + i] == word[i]]
    pos = pos[pos + n < len(a)]
    pos = pos[_space(a[pos + n])]
    head = np.ones(len(pos), dtype=bool)
    inner = pos > 0
    before = prev[pos[inner] - 1]
    head[inner] = (before < 0) | (a[np.maximum(before, 0)] == 10)
    return pos[head]


def _space(byte: np.ndarray) -> np.ndarray:
    return (byte == 32) | ((byte >= 9) & (byte <= 13))


class _AsciiState:
    """Vertices per solid, accumulated across blocks."""

    def __init__(self) -> None:
        self.names: list[str | None] = []
        self.parts: list[list[np.ndarray]] = []
        self.vertices = 0
        self.facets = 0
        self.line = 0  # lines before the current block

    def add(self, points: np.ndarray, name: str | None = None, new: bool = False) -> None:
        if new or not self.parts:
            self.names.append(name)
            self.parts.append([])
        if len(points):
            self.parts[-1].append(points)


def _parse_block(block: bytes, state: _AsciiState, path: str) -> None:
    """Add the vertices of ``block`` (whole facets) to ``state``."""
    low = block.lower()
    a = np.frombuffer(low + b"\n", dtype=np.uint8)
    index = np.arange(len(a))
    prev = np.maximum.accumulate(np.where(~_space(a) | (a == 10), index, -1))
    newlines = np.flatnonzero(a == 10)
    solids = _line_tokens(a, prev, b"solid")
    vertex = _line_tokens(a, prev, b"vertex")
    state.facets += low.count(b"endfacet")
    check_count("triangles", state.facets, limits.MAX_TRIANGLES, path=path,
                hint="split the mesh or raise plumbob.limits.MAX_TRIANGLES")
    ends = newlines[np.searchsorted(newlines, vertex + 6)]
    # Keep the bytes from after each 'vertex' to its line's end (newline included).
    spans = np.bincount(vertex + 6, minlength=len(a) + 1) - np.bincount(ends + 1,
                                                                       minlength=len(a) + 1)
    keep = np.cumsum(spans[: len(a)]) > 0
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            values = np.fromstring(a[keep].tobytes(), sep=" ")  # one C pass over all vertex lines
    except ValueError:  # numpy ≥ 2.3 raises on text that is not numbers
        values = None
    if values is None or len(values) != 3 * len(vertex):
        _bad_vertex_line(block, a, vertex, ends, state.line, path)
    points = values.reshape(-1, 3)
    owner = np.searchsorted(solids, vertex, side="right") - 1
    edges = np.searchsorted(owner, np.arange(-1, len(solids) + 1))
    if edges[1] > edges[0]:
        state.add(points[edges[0]:edges[1]])
    for i, start in enumerate(solids + 5):  # per solid header, not per vertex
        stop = newlines[np.searchsorted(newlines, start)]
        name = block[start:stop].strip().decode("utf-8", "replace") or None
        state.add(points[edges[i + 1]:edges[i + 2]], name, new=True)
    state.vertices += len(points)
    state.line += len(newlines) - 1


def _bad_vertex_line(block: bytes, a: np.ndarray, vertex: np.ndarray, ends: np.ndarray,
                     line0: int, path: str) -> None:
    """Name the first vertex line that is not three numbers (error path only)."""
    for p, e in zip(vertex, ends):  # stops at the first bad line
        words = block[p + 6:e].split()
        try:
            ok = len(words) == 3 and len([float(w) for w in words]) == 3
        except ValueError:
            ok = False
        if not ok:
            line = line0 + int(np.count_nonzero(a[:p] == 10)) + 1
            shown = block[p:e].strip().decode("utf-8", "replace")[:60]
            raise FormatError(f"line {line}: {shown!r} is not 'vertex' and three numbers",
                              path=path)
    raise FormatError("a vertex line is not 'vertex' and three numbers", path=path)


def _load_ascii(path: str, size: int) -> StlFile | None:
    """Parse an ASCII STL; None when it has no vertex at all (then it is not one)."""
    state = _AsciiState()
    with open(path, "rb") as f:
        carry = b""
        while True:
            data = f.read(ASCII_BLOCK)
            block = carry + data
            if not data:
                if block.strip():
                    _parse_block(block, state, path)
                break
            last = block.lower().rfind(b"endfacet")
            cut = block.find(b"\n", last) + 1 if last >= 0 else 0
            if cut <= 0:
                if len(block) > MAX_LINE:
                    if state.vertices == 0:
                        return None
                    raise FormatError(f"has no facet end ('endfacet') in {len(block)} bytes: "
                                      "it is corrupt", path=path)
                carry = block
                continue
            _parse_block(block[:cut], state, path)
            carry = block[cut:]
        f.seek(max(0, size - 512))
        ending = f.read().strip().lower().rsplit(b"\n", 1)[-1].strip()
    if state.vertices == 0:
        return None
    if state.vertices % 3 or state.facets * 3 != state.vertices:
        if state.facets * 3 < state.vertices:
            raise InputFileError(
                f"ends in the middle of a facet ({state.facets} complete facets, then "
                f"{state.vertices - 3 * state.facets} stray vertices): it is truncated",
                path=path)
        raise FormatError(f"has {state.facets} facets but {state.vertices} vertices: every "
                          "facet of an ASCII STL needs exactly three", path=path)
    notices = []
    if not ending.startswith(b"endsolid"):
        notices.append("stl: no 'endsolid' at the end; the file may be truncated")
    solids = [StlSolid(name, np.concatenate(parts).reshape(-1, 3, 3))
              for name, parts in zip(state.names, state.parts) if parts]
    lo = np.min([s.triangles.reshape(-1, 3).min(axis=0) for s in solids], axis=0)
    hi = np.max([s.triangles.reshape(-1, 3).max(axis=0) for s in solids], axis=0)
    if not (np.isfinite(lo).all() and np.isfinite(hi).all()):
        offset = 0
        for s in solids:
            if not np.isfinite(s.triangles).all():
                raise_nonfinite(s.triangles, offset, path=path, what="facet")
            offset += len(s.triangles)
    reach = float(max(np.abs(lo).max(), np.abs(hi).max()))
    return StlFile(tuple(solids), False, reach, lo, hi, tuple(notices))


# ------------------------------------------------------------------ bodies
def read_stl(path: str, units: str | None = None, repair: bool = False) -> Reading:
    """Read an STL file as a body: one :class:`MeshSolid`, or an :class:`Assembly`
    of one per ``solid`` block (ASCII files with several)."""
    from .solids import mesh_solid

    stl = load_stl(path)
    scale, notices = units_scale(units)
    notices = list(notices) + list(stl.notices)
    if stl.lo is not None:
        notices += check_extent(stl.lo * scale, stl.hi * scale, path=path,
                                assumed=units is None)
    else:
        check_reach(stl.reach * scale, path=path)
    several = len(stl.solids) > 1
    parts = []
    names = unique_names([s.name or (f"solid {i + 1}" if several else stem(path))
                           for i, s in enumerate(stl.solids)])
    for solid, name in zip(stl.solids, names):
        tri = solid.triangles if scale == 1.0 else solid.triangles.astype(float)
        if scale != 1.0:  # in place: one float64 copy, not two
            tri *= scale
        body, more = mesh_solid(tri, path=path, name=name, repair=repair, extent=stl.lo is None,
                                assumed=units is None,
                                label=f"solid {name!r}" if several else None, scale=scale)
        parts.append(body)
        notices.extend(more)
    return Reading(assemble(parts, stem(path)), tuple(notices), path, reading_unit(units),
                   units_assumed=unit_assumed(units))
