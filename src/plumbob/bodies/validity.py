"""Is a plane region a lamina? Simple rings, holes inside their outline and apart.

Green's theorem integrates whatever rings it is given: a bow-tie's two lobes
cancel or add, a "hole" outside the outline is subtracted from nothing. So every
outline is checked before it is integrated — the same check wherever it comes
from (an outline file in :mod:`plumbob.formats`, a spec's ``polygon`` or ``outline``,
:func:`plumbob.bodies.primitives.polygon`) — and a defect is one error naming it
and a point where GEOS found it.
"""

from __future__ import annotations

import re

import numpy as np

from ..errors import GeometryError, fmt_point
from .region import Region

__all__ = ["CHECK_TOLERANCE", "MAX_BULGE", "check_bulges", "check_polygon", "check_region",
           "validity_error", "suspects"]

#: curved edges are flattened within this fraction of the region's size to be checked
CHECK_TOLERANCE = 1e-7

#: the largest |bulge| (tan of a quarter of the arc's sweep) of an edge: 1e4 is an arc within
#: 0.03° of a full circle on a chord 5000 times shorter than its radius, past anything a
#: drawing holds; beyond it the arc's moments lose digits as bulge² × round-off.
MAX_BULGE = 1e4

#: GEOS's reasons for an invalid polygon → what the message says
_REASONS = {
    "Self-intersection": "crosses itself at {p} (a bow-tie or a twisted outline)",
    "Ring Self-intersection": "touches itself at {p}",
    "Too few points": "has fewer than three distinct points",
    "Hole lies outside shell": "has a hole outside its outer boundary, near {p}",
    "Nested holes": "has a hole inside another hole, near {p}",
    "Holes are nested": "has a hole inside another hole, near {p}",
    "Interior is disconnected": "has holes that cut it apart, near {p}",
    "Invalid Coordinate": "has a coordinate that is not a finite number, near {p}",
    "Too few points in geometry component": "has fewer than three distinct points, near {p}",
    "Duplicate Rings": "has the same ring twice, near {p}",
}


def validity_error(geometry, label: str, path: str | None = None,
                   scale: float | np.ndarray = 1.0, unit: str = "") -> GeometryError | None:
    """The error for a degenerate or invalid shapely (Multi)Polygon, None if it is valid.

    ``geometry``'s coordinates are in metres; the point GEOS names is given in the
    caller's coordinates (metres / ``scale``, a number or one per axis) followed by
    ``unit``, so a file's reader names it as the file has it.

    >>> import shapely
    >>> str(validity_error(shapely.Polygon([(0, 0), (2, 2), (2, 0), (0, 2)]), "the bow-tie"))
    'the bow-tie crosses itself at (1, 1) (a bow-tie or a twisted outline)'
    """
    import shapely

    hull = shapely.convex_hull(geometry)
    size = float(np.hypot(*np.ptp(np.asarray(shapely.get_coordinates(geometry)), axis=0))) \
        if not geometry.is_empty else 0.0
    if not hull.area > 1e-14 * size * size:
        return GeometryError(f"{label} has zero area: its points lie on a line and enclose no "
                             "area", path=path)
    parts = shapely.get_parts(geometry)
    rings, owner = shapely.get_rings(parts, return_index=True)  # each part: outer, then holes
    flat = np.flatnonzero(~(shapely.area(shapely.convex_hull(rings)) > 1e-14 * size * size))
    if len(flat):
        return GeometryError(f"{label}: {_ring_name(owner, int(flat[0]))} has zero area (its "
                             "points lie on a line)", path=path)
    reason = shapely.is_valid_reason(geometry)
    if reason is None or reason == "Valid Geometry":
        return None
    match = re.match(r"^(.*?)\s*\[\s*([^\s\]]+)\s+([^\s\]]+)", reason)
    what, point = (match.group(1), (float(match.group(2)), float(match.group(3)))) if match \
        else (reason, None)
    where = fmt_point(np.array(point) / scale) + unit if point is not None else "?"
    if what == "Self-intersection" and point is not None:
        near = shapely.distance(shapely.Point(point), rings)
        names = [_ring_name(owner, int(k)) for k in np.flatnonzero(near <= 1e-9 * size)[:2]]
        if len(names) == 2 and all(n.endswith("outer boundary") for n in names):
            return GeometryError(f"{label}: {names[1]} overlaps {names[0]} at {where}; the "
                                 "polygons of a MultiPolygon must lie apart", path=path)
        if len(names) == 2:
            return GeometryError(f"{label}: {names[1]} crosses or touches {names[0]} at {where}; "
                                 "holes must lie apart, inside the outer boundary", path=path)
        if names and "hole" in names[0]:
            return GeometryError(f"{label}: {names[0]} crosses itself at {where}", path=path)
    template = _REASONS.get(what, what.lower() + " near {p}")
    return GeometryError(f"{label} {template.format(p=where)}", path=path)


def suspects(geometries) -> np.ndarray:
    """Which of ``geometries`` (shapely (Multi)Polygons, m) :func:`validity_error` might
    refuse, in a few vectorised calls: the invalid ones and those with a ring of (nearly)
    no area, by the same tests. A reader of 10⁴ polygons asks :func:`validity_error` only
    for these (for its message), not for each.

    >>> import shapely
    >>> suspects([shapely.box(0, 0, 1, 1), shapely.Polygon([(0, 0), (2, 2), (2, 0), (0, 2)])]).tolist()
    [False, True]
    """
    import shapely

    geometries = np.asarray(geometries, dtype=object)
    low, high = np.split(shapely.bounds(geometries), 2, axis=1)
    size2 = np.sum((high - low) ** 2, axis=1)
    flat = ~(shapely.area(shapely.convex_hull(geometries)) > 1e-14 * size2)
    parts, part_owner = shapely.get_parts(geometries, return_index=True)
    rings, ring_part = shapely.get_rings(parts, return_index=True)
    owner = part_owner[ring_part]
    flat_ring = ~(shapely.area(shapely.convex_hull(rings)) > 1e-14 * size2[owner])
    flat |= np.bincount(owner[flat_ring], minlength=len(geometries)) > 0
    return flat | ~shapely.is_valid(geometries)


def _ring_name(owner: np.ndarray, k: int) -> str:
    """What messages call ring ``k`` of a (Multi)Polygon's rings (``owner``: each ring's
    polygon, its rings in order: the outer boundary, then the holes)."""
    part = int(owner[k])
    within = k - int(np.searchsorted(owner, part))
    prefix = f"polygon {part + 1}'s " if owner[-1] > 0 else "the "
    return f"{prefix}outer boundary" if within == 0 else f"{prefix}hole {within}".replace(
        "the hole", "hole")


def _xy(points, what: str) -> np.ndarray:
    try:
        xy = np.asarray(points, dtype=float)
    except (TypeError, ValueError):
        raise GeometryError(f"{what} must be a list of [x, y] points (numbers)") from None
    if xy.ndim != 2 or xy.shape[1] != 2:
        raise GeometryError(f"{what} must be a list of [x, y] points, not an array of shape "
                            f"{xy.shape}")
    if not np.isfinite(xy).all():
        raise GeometryError(f"{what} has a coordinate that is not a finite number")
    if len(np.unique(xy, axis=0)) < 3:
        raise GeometryError(f"{what} has fewer than three distinct points: it encloses nothing")
    return xy


def check_polygon(vertices, holes=(), label: str = "the polygon") -> None:
    """Raise a :class:`GeometryError` unless ``vertices`` (n, 2) and ``holes`` (each (k, 2)),
    m, bound a lamina: no ring crossing or touching itself, every hole inside the outline,
    no hole crossing, touching along an edge, or inside another. Points are named in m.

    >>> check_polygon([[0, 0], [4, 0], [4, 4], [0, 4]], [[[5, 5], [6, 5], [6, 6]]])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the polygon has a hole outside its outer boundary, near (5, 5) m
    """
    import shapely

    shell = _xy(vertices, label)
    try:
        holes = list(holes)
    except TypeError:
        raise GeometryError(f"{label}'s holes must be a list of point lists") from None
    inner = [_xy(h, f"{label}'s hole {i + 1}") for i, h in enumerate(holes)]
    error = validity_error(shapely.Polygon(shell, inner), label, unit=" m")
    if error is not None:
        raise error


def check_bulges(bulges: np.ndarray, label: str) -> None:
    """Raise a :class:`GeometryError` for a bulge that is not a finite number up to
    :data:`MAX_BULGE` in size.

    >>> check_bulges(np.array([0.5, 1e300]), "edge")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: edge has a bulge of 1e+300, an arc within round-off of a ...
    """
    bulges = np.asarray(bulges, dtype=float)
    bad = ~(np.abs(bulges) <= MAX_BULGE)
    if bad.any():
        raise GeometryError(f"{label} has a bulge of {bulges[np.argmax(bad)]:.3g}, an arc within "
                            f"round-off of a full circle (|bulge| ≤ {MAX_BULGE:g}): draw it as "
                            "two arcs")


def check_region(region: Region, label: str = "the outline") -> None:
    """:func:`check_polygon` for a region of curved rings: the first ring is the outline,
    the others its holes; curves are flattened within :data:`CHECK_TOLERANCE` of its size."""
    for ring in region.rings:  # per ring: few
        if ring.bulges is not None:
            check_bulges(ring.bulges, label)
    tolerance = max(region.size * CHECK_TOLERANCE, 1e-300)
    rings = [ring.flattened(tolerance) for ring in region.rings]
    check_polygon(rings[0], rings[1:], label)
