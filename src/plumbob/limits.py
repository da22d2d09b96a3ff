"""The one home of plumbob's work limits.

Every count, expansion and degree a file, a spec or an option can ask for is checked
against a limit here *before* the work starts, so a small hostile input ends in one
line naming the limit (exit status 2) instead of a hang or an exhausted machine. The
limits sit far above anything a real part needs; each is a plain module constant so
a library user with a bigger machine can raise it.
"""

from __future__ import annotations

import math

from .errors import LimitError

__all__ = [
    "MAX_ARCHIVE_BYTES",
    "MAX_ARCHIVE_MEMBERS",
    "MAX_ARCHIVE_RATIO",
    "MAX_DENSITY_DEGREE",
    "MAX_ELEMENT_DEPTH",
    "MAX_EXPRESSION_NODES",
    "MAX_FILE_BYTES",
    "MAX_FLAT_POINTS",
    "MAX_NESTING",
    "MAX_OUTLINE_PAIRS",
    "MAX_OUTLINES",
    "MAX_PARTS",
    "MAX_PERIODS",
    "MAX_SAMPLES",
    "MAX_SEGMENTS",
    "MAX_SIDES",
    "MAX_SPEC_NESTING",
    "MAX_STEP_BYTES",
    "MAX_STEP_ENTITIES",
    "MAX_TRIANGLES",
    "check_count",
]

#: Bytes read from any one input file (8 GiB would be a 160M-triangle STL).
MAX_FILE_BYTES = 2 * 1024**3
#: Bytes an archive (3MF, zipped input) may expand to, all members together.
MAX_ARCHIVE_BYTES = 1024**3
#: Members (files, folders) in one archive (3MF, zipped or tarred input).
MAX_ARCHIVE_MEMBERS = 10_000
#: How many times larger than its compressed size an archive member may expand.
MAX_ARCHIVE_RATIO = 200
#: Bytes of one STEP file, checked before OpenCASCADE reads it.
MAX_STEP_BYTES = 512 * 1024**2
#: Entities (``#n = …`` records) in one STEP file, counted before OpenCASCADE reads it.
MAX_STEP_ENTITIES = 2_000_000
#: Triangles in one mesh.
MAX_TRIANGLES = 50_000_000
#: Nodes in one spec expression (numbers, names, operators, calls).
MAX_EXPRESSION_NODES = 2_000
#: Depth of nesting: TOML tables and arrays, spec groups, SVG ``<use>``, DXF ``INSERT``.
MAX_NESTING = 64
#: Depth of a spec's TOML tables and arrays (two levels a group of parts: groups 490 deep).
#: The reader and the builder walk it without deep recursion (900-deep groups were built
#: in tests), so this bounds the work, far beyond the few levels an assembly needs.
MAX_SPEC_NESTING = 1_000
#: Depth of an SVG's element tree (groups within groups): svgelements follows it by
#: recursion and fails near 1 000 levels; drawing programs nest a few dozen.
MAX_ELEMENT_DEPTH = 256
#: Copies that references may place (SVG ``<use>``, DXF ``INSERT``/``MINSERT``), cells a
#: hollowing may cut, jobs: work a few bytes can ask for. Parts written out in a file —
#: a spec's parts and particles, a drawing's polygons, rings and rectangles — are not
#: counted: each costs its bytes, so the file-size limits (and MAX_OUTLINES, MAX_FLAT_POINTS
#: for a drawing's checks) bound their work.
MAX_PARTS = 10_000
#: Outlines (rings) one drawing may hold.
MAX_OUTLINES = 100_000
#: Pairs of outlines close enough to be compared (bounding boxes meet): how deeply and how
#: densely a drawing's outlines may nest or crowd, since nesting is found pairwise.
MAX_OUTLINE_PAIRS = 4_000_000
#: Points one drawing's outlines may be flattened to for checking (crossings, nesting):
#: a curve is flattened within 1e-7 of the drawing's size, ~7,000 points a full circle.
MAX_FLAT_POINTS = 4_000_000
#: Sides of a regular polygon or segments of a tessellated curve.
MAX_SIDES = 1_000_000
#: Circular segments per turn of a faceted boolean (a sphere costs about n²/2 triangles).
MAX_SEGMENTS = 2048
#: Polynomial degree of a density field (a quadrature rule of this degree per cell).
MAX_DENSITY_DEGREE = 64
#: Samples one command may ask for (simulate --samples, sampled surfaces, drops).
MAX_SAMPLES = 1_000_000
#: Oscillations of the fastest spring or pendulum one simulation may span (tens of
#: integration steps each: about a minute of work).
MAX_PERIODS = 10_000


def check_count(what: str, value: float, limit: float, *, hint: str = "",
                path: str | None = None) -> int:
    """``value`` as an int when it is a finite whole count within ``0..limit``; else a
    :class:`LimitError` naming ``what``, the value and the limit (and ``hint``, what to do).

    >>> check_count("sides", 64, MAX_SIDES)
    64
    >>> check_count("sides", 1e8, MAX_SIDES)
    Traceback (most recent call last):
    ...
    plumbob.errors.LimitError: sides 100000000 is over plumbob's limit of 1000000
    """
    try:
        number = float(value)
    except OverflowError:  # an int beyond 1.8e308
        number = math.inf
    if not math.isfinite(number) or number < 0 or number != int(number):
        raise LimitError(f"{what} must be a whole number from 0 to {limit:g}, not {value!r}",
                         path=path)
    if number > limit:
        message = f"{what} {int(number)} is over plumbob's limit of {int(limit)}"
        raise LimitError(f"{message}; {hint}" if hint else message, path=path)
    return int(number)
