"""Reader-side checks on coordinates: finite, and of a size a real object can have.

Every reader passes its coordinates (in metres, units applied) through these
before building a body, so that a NaN, an overflow or a file in the wrong
units is an error or a notice naming the file — not a silent absurd result.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError

__all__ = [
    "ABSURD_COORDINATE",
    "ASSUMED_METRES_LIMIT",
    "PLAUSIBLE_SIZE",
    "check_extent",
    "check_reach",
    "finite_bounds",
    "raise_nonfinite",
]

#: m; a coordinate beyond this is no real object (3 light-seconds)
ABSURD_COORDINATE = 1e9
#: m; bounding-box diagonals outside this range draw a warning about units
PLAUSIBLE_SIZE = (1e-5, 1e3)
#: m; a model with no unit in its file (metres assumed) that is larger than this along
#: any axis is almost surely in millimetres: a printed part, a figurine, a bracket —
#: metres would make it a building. It draws a specific notice suggesting --units mm.
ASSUMED_METRES_LIMIT = 10.0
#: items per pass of :func:`finite_bounds`
CHUNK = 1 << 16


def check_extent(lo: np.ndarray, hi: np.ndarray, *, path: str | None,
                 assumed: bool = False) -> tuple[str, ...]:
    """Reject absurd coordinates; warn when the size is implausible for its units.

    ``lo``, ``hi``: the bounding box corners in metres (units applied). ``assumed``:
    the file has no unit and none was given, so metres were assumed; then a model
    larger than :data:`ASSUMED_METRES_LIMIT` along an axis gets its own notice.

    >>> check_extent(np.zeros(2), np.array([2000.0, 0.0]), path=None)[0][:30]
    'size: the model is 2000 m acro'
    >>> print(check_extent(np.zeros(3), np.array([40.0, 30.0, 119.0]), path=None,
    ...                    assumed=True)[0])
    size: the model is 40 × 30 × 119 m, implausible for metres (assumed: the file has no \
unit); it is most likely in millimetres: pass --units mm
    """
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    check_reach(float(max(np.abs(lo).max(), np.abs(hi).max())), path=path)
    size = float(np.linalg.norm(hi - lo))
    sides = hi - lo
    if assumed and float(sides.max()) > ASSUMED_METRES_LIMIT:
        shown = " × ".join(f"{side:.4g}" for side in sides)
        return (f"size: the model is {shown} m, implausible for metres (assumed: the file "
                "has no unit); it is most likely in millimetres: pass --units mm",)
    small, large = PLAUSIBLE_SIZE
    if size > large:
        return (f"size: the model is {size:.4g} m across, implausible for its units; "
                "if the file is in millimetres pass --units mm",)
    if 0 < size < small:
        return (f"size: the model is only {size:.3g} m across, implausible for its units; "
                "pass --units to say what the file's lengths are in",)
    return ()


def check_reach(reach: float, *, path: str | None) -> None:
    """Reject a largest coordinate magnitude ``reach`` (m) that is not finite or absurd."""
    if not np.isfinite(reach):
        raise GeometryError("a coordinate is not a finite number (NaN or infinity)", path=path)
    if reach > ABSURD_COORDINATE:
        raise GeometryError(
            f"coordinates reach {reach:.3g} m, far beyond any real object "
            f"(limit {ABSURD_COORDINATE:g} m): the file is corrupt or in other units "
            "(use --units)", path=path)


def finite_bounds(points: np.ndarray, *, path: str | None, what: str = "triangle",
                  chunk: int = CHUNK) -> tuple[np.ndarray, np.ndarray]:
    """Bounding box (lo, hi) of ``points`` (n, …, d); a NaN or infinity is an error naming
    its item."""
    points = np.asarray(points)
    n = len(points)
    d = points.shape[-1]
    if n == 0:
        return np.zeros(d), np.zeros(d)
    lo = np.full(d, np.inf)
    hi = np.full(d, -np.inf)
    for start in range(0, n, chunk):
        block = points[start:start + chunk].reshape(-1, d)
        with np.errstate(invalid="ignore"):
            blo, bhi = block.min(axis=0), block.max(axis=0)
        if not (np.all(np.isfinite(blo)) and np.all(np.isfinite(bhi))):
            raise_nonfinite(points[start:start + chunk], start, path=path, what=what)
        lo = np.minimum(lo, blo)
        hi = np.maximum(hi, bhi)
    return lo, hi


def raise_nonfinite(block: np.ndarray, offset: int, *, path: str | None, what: str) -> None:
    """Raise the error for the first item of ``block`` with a NaN or infinite coordinate."""
    block = np.asarray(block)
    bad = ~np.isfinite(block.reshape(len(block), -1)).all(axis=1)
    index = int(np.argmax(bad))
    value = block.reshape(len(block), -1)[index]
    kind = "NaN" if np.isnan(value).any() else "infinity"
    raise GeometryError(
        f"{what} {offset + index + 1} has a coordinate that is not a finite number ({kind}); "
        "the file is corrupt or its exporter is faulty", path=path)
