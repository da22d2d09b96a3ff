"""How deeply a WKT or WKB geometry nests, measured before GEOS parses it.

GEOS reads nested GEOMETRYCOLLECTIONs recursively, in C: a 2 MB file nesting
100 000 levels overflows its stack and kills the process (a segmentation fault,
no message). So the depth is measured first — in one vectorised pass over WKT's
brackets, in a walk of WKB's headers that keeps its own stack — and checked
against :data:`~plumbob.limits.MAX_NESTING`.
"""

from __future__ import annotations

import struct

import numpy as np

from ..limits import MAX_NESTING, check_count

__all__ = ["check_wkb_nesting", "check_wkt_nesting"]

#: brackets a POLYGON's coordinates take inside a MULTIPOLYGON (not nesting of geometries)
_COORDINATE_BRACKETS = 3


def check_wkt_nesting(text: str, path: str | None) -> None:
    """Refuse WKT whose brackets nest deeper than a MULTIPOLYGON's inside MAX_NESTING
    collections.

    >>> check_wkt_nesting("MULTIPOLYGON (((0 0, 1 0, 1 1, 0 0)))", None)
    >>> check_wkt_nesting("GEOMETRYCOLLECTION (" * 99 + ")" * 99, None)
    Traceback (most recent call last):
    ...
    plumbob.errors.LimitError: geometry nesting depth 96 is over plumbob's limit of 64
    """
    codes = np.frombuffer(text.encode("utf-8", "replace"), dtype=np.uint8)
    steps = (codes == ord("(")).astype(np.int64) - (codes == ord(")"))
    depth = int(np.cumsum(steps).max(initial=0))
    check_count("geometry nesting depth", max(depth - _COORDINATE_BRACKETS, 0), MAX_NESTING,
                path=path)


def check_wkb_nesting(data: bytes, path: str | None) -> None:
    """Refuse WKB (ISO or EWKB) whose geometry collections nest deeper than MAX_NESTING.

    Walks the headers with an explicit stack of counts still to read, skipping
    coordinates by their declared lengths; malformed data ends the walk (GEOS then
    refuses it with its own message).

    >>> import shapely
    >>> check_wkb_nesting(shapely.from_wkt("POLYGON ((0 0, 1 0, 1 1, 0 0))").wkb, None)
    >>> check_wkb_nesting(struct.pack("<BII", 1, 7, 1) * 99, None)
    Traceback (most recent call last):
    ...
    plumbob.errors.LimitError: geometry nesting depth 65 is over plumbob's limit of 64
    """
    pos, remaining = 0, [1]
    while remaining and pos + 5 <= len(data):  # per geometry header
        if remaining[-1] == 0:
            remaining.pop()
            continue
        remaining[-1] -= 1
        order = "<" if data[pos] == 1 else ">"
        (code,) = struct.unpack_from(order + "I", data, pos + 1)
        pos += 5 + (4 if code & 0x20000000 else 0)  # EWKB: an SRID follows
        kind = (code & 0xFFFF) % 1000
        dims = 2 + bool(code & 0x80000000) + bool(code & 0x40000000) \
            + {0: 0, 1: 1, 2: 1, 3: 2}.get((code & 0xFFFF) // 1000, 0)
        if pos + 4 > len(data) and kind != 1:
            return
        if kind == 1:
            pos += 8 * dims
        elif kind == 2:
            pos += 4 + 8 * dims * struct.unpack_from(order + "I", data, pos)[0]
        elif kind == 3:
            (rings,) = struct.unpack_from(order + "I", data, pos)
            pos += 4
            for _ in range(rings):  # per ring
                if pos + 4 > len(data):
                    return
                pos += 4 + 8 * dims * struct.unpack_from(order + "I", data, pos)[0]
        elif kind in (4, 5, 6, 7):
            remaining.append(struct.unpack_from(order + "I", data, pos)[0])
            pos += 4
            check_count("geometry nesting depth", len(remaining) - 1, MAX_NESTING, path=path)
        else:
            return
