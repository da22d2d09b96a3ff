"""Laminas from closed outlines and polygons, checked.

Polygon formats (GeoJSON, WKT, WKB) say which ring is a hole; each polygon
becomes one lamina (:func:`body_from_polygons`). Drawing formats (SVG, DXF,
CSV) give bare closed curves (:class:`Outline`): a curve inside an odd number
of others is a hole, inside an even number an outer boundary (the even-odd
rule a laser cutter follows), and each outer boundary with the holes directly
inside it becomes one lamina (:func:`body_from_outlines`).

Every outline is checked: plausible size, non-zero area, no self-intersection
(the error names the crossing point), no two outlines crossing each other.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..bodies.base import Body
from ..bodies.lamina import Lamina
from ..bodies.region import Region, Ring
from ..bodies.validity import CHECK_TOLERANCE, validity_error
from ..errors import FormatError, GeometryError, fmt_point
from .checks import check_extent
from .parts import assemble, stem, unique_names

__all__ = ["Outline", "body_from_outlines", "body_from_polygons"]


@dataclass(frozen=True, eq=False)
class Outline:
    """A closed curve read from a drawing, any orientation, in metres.

    ring: the exact boundary. label: where it came from, for messages.
    name: the part name the file gives it (element id, layer), if any.
    error: m², a bound on the area error of approximated curves (0 when exact).
    approximation: what was approximated, for the lamina's note.
    """

    ring: Ring
    label: str
    name: str | None = None
    error: float = 0.0
    approximation: str | None = None


def _ring_area(ring: Ring) -> float:
    return float(ring.moments(ring.vertices.mean(axis=0)).m0)


def _oriented(ring: Ring, area: float, outer: bool) -> Ring:
    return ring if (area > 0) == outer else ring.reversed()


def _lamina(rings: list[Ring], name: str | None, error: float, approximations: set[str]) -> Lamina:
    region = Region(tuple(rings))
    area = abs(float(region.moments().m0))
    if error > 0 and area > 0:
        note = "; ".join(sorted(approximations)) or "curves approximated"
        return Lamina(region, name=name, exact=False, relative_error=error / area, note=note)
    return Lamina(region, name=name)


def body_from_outlines(outlines: list[Outline], *, path: str | None, name: str | None = None,
                       scale: float = 1.0) -> tuple[Body, tuple[str, ...]]:
    """Laminas from bare closed curves (metres) by the even-odd rule (see module docstring).

    ``scale``: metres per file unit, so messages give points in the file's coordinates.
    """
    import shapely

    if not outlines:
        raise FormatError("has no closed outline", path=path)
    notices: list[str] = []
    pts = [o.ring.vertices for o in outlines]
    pts += [o.ring.controls[~np.isnan(o.ring.controls)].reshape(-1, 2)
            for o in outlines if o.ring.controls is not None]
    pts = np.concatenate(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    notices += check_extent(lo, hi, path=path)
    size = float(np.linalg.norm(hi - lo))
    tol = max(size * CHECK_TOLERANCE, 1e-300)
    areas = np.array([_ring_area(o.ring) for o in outlines])
    polygons = []
    for outline, area in zip(outlines, areas):  # per outline
        flat = outline.ring.flattened(tol)
        if len(flat) < 3:
            raise GeometryError(f"{outline.label} has zero area: it has fewer than three "
                                "distinct points", path=path)
        polygon = shapely.Polygon(flat)
        error = validity_error(polygon, outline.label, path, scale)
        if error is not None:
            raise error
        if not abs(area) > 1e-14 * size * size:
            raise GeometryError(f"{outline.label} has zero area: it encloses nothing", path=path)
        polygons.append(polygon)
    polygons = np.array(polygons, dtype=object)
    tree = shapely.STRtree(polygons)
    crossing = tree.query(polygons, predicate="overlaps")
    if crossing.shape[1]:
        i, j = crossing[:, 0]
        where = shapely.intersection(polygons[i].exterior, polygons[j].exterior)
        point = np.asarray(shapely.get_coordinates(where))[0] if not where.is_empty else lo
        raise GeometryError(f"{outlines[i].label} and {outlines[j].label} cross each other at "
                            f"{fmt_point(point / scale)}: outlines must nest or stay apart",
                            path=path)
    inside = tree.query(polygons, predicate="contains")  # rows: (container, contained)
    inside = inside[:, inside[0] != inside[1]]
    same = shapely.equals(polygons[inside[0]], polygons[inside[1]])
    if same.any():
        dup = np.unique(np.maximum(inside[0, same], inside[1, same]))
        notices.append(f"outlines: dropped {len(dup)} duplicate outline(s) "
                       f"({outlines[int(dup[0])].label}, …)")
        keep = np.setdiff1d(np.arange(len(outlines)), dup)
        kept = [outlines[int(k)] for k in keep]
        body, more = body_from_outlines(kept, path=path, name=name, scale=scale)
        return body, tuple(notices) + tuple(m for m in more if m not in notices)
    depth = np.bincount(inside[1], minlength=len(outlines))
    parent = np.full(len(outlines), -1)
    direct = depth[inside[0]] == depth[inside[1]] - 1
    parent[inside[1, direct]] = inside[0, direct]
    outer = np.flatnonzero(depth % 2 == 0)
    names = unique_names([outlines[k].name or f"outline {i + 1}" for i, k in enumerate(outer)])
    parts = []
    for k, part_name in zip(outer, names):  # per outer boundary
        holes = np.flatnonzero((parent == k) & (depth % 2 == 1))
        members = [outlines[k]] + [outlines[h] for h in holes]
        rings = [_oriented(outlines[k].ring, areas[k], True)]
        rings += [_oriented(outlines[h].ring, areas[h], False) for h in holes]
        parts.append(_lamina(rings, part_name, sum(m.error for m in members),
                             {m.approximation for m in members if m.approximation}))
    return assemble(parts, name), tuple(notices)

def body_from_polygons(named: list[tuple[str, object]], *, path: str | None,
                       scale: float = 1.0) -> tuple[Body, tuple[str, ...]]:
    """Laminas from shapely (Multi)Polygons, one per entry, coordinates × ``scale`` (m)."""
    import shapely

    if not named:
        raise FormatError("has no Polygon or MultiPolygon", path=path)
    with np.errstate(over="ignore", invalid="ignore"):
        geometries = [shapely.transform(g, lambda c: c * scale) if scale != 1.0 else g
                      for _, g in named]
        bounds = np.array([shapely.bounds(g) for g in geometries])
    if not np.isfinite(bounds).all():
        raise GeometryError("a coordinate is not a finite number (NaN or infinity)", path=path)
    notices = check_extent(bounds[:, :2].min(axis=0), bounds[:, 2:].max(axis=0), path=path)
    names = unique_names([n for n, _ in named])
    parts = []
    several = len(named) > 1
    for part_name, geometry in zip(names, geometries):  # per polygon
        label = f"polygon {part_name!r}" if several else "the polygon"
        error = validity_error(geometry, label, path, scale)
        if error is not None:
            raise error
        if not geometry.area > 0:
            raise GeometryError(f"{label} has zero area: it encloses nothing", path=path)
        parts.append(Lamina(Region.from_shapely(geometry), name=part_name))
    return assemble(parts, stem(path) if path else None), notices
