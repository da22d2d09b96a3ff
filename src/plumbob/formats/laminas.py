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
from ..bodies.validity import CHECK_TOLERANCE, suspects, validity_error
from ..errors import FormatError, GeometryError, fmt_point
from ..limits import MAX_FLAT_POINTS, MAX_OUTLINE_PAIRS, MAX_OUTLINES, check_count
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


def _signed_areas(outlines: list[Outline], flats: list[np.ndarray]) -> np.ndarray:
    """Signed areas (m²): the shoelace sum over all polygonal rings at once (about each
    ring's first vertex), exact moments for curved rings."""
    counts = np.array([len(flat) for flat in flats])
    starts = np.concatenate(([0], np.cumsum(counts)[:-1]))
    coords = np.concatenate(flats)
    local = coords - np.repeat(coords[starts], counts, axis=0)
    following = np.arange(1, len(coords) + 1)
    following[starts + counts - 1] = starts
    ahead = local[following]
    cross = local[:, 0] * ahead[:, 1] - ahead[:, 0] * local[:, 1]
    areas = 0.5 * np.add.reduceat(cross, starts)
    for k, outline in enumerate(outlines):  # per outline: curved ones integrate exactly
        if outline.ring.is_curved:
            ring = outline.ring
            areas[k] = float(ring.moments(ring.vertices.mean(axis=0)).m0)
    return areas


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
                       scale: float | np.ndarray = 1.0) -> tuple[Body, tuple[str, ...]]:
    """Laminas from bare closed curves (metres) by the even-odd rule (see module docstring).

    ``scale``: metres per file unit (or per unit along x and y, negative for a flipped axis,
    as SVG's), so messages give points in the file's coordinates.
    Outlines drawn twice are dropped (a hash of their normalised coordinates, then
    topological equality among the pairs that nest); the nesting is found through a
    spatial index, its pairs counted against :data:`~plumbob.limits.MAX_OUTLINE_PAIRS`
    before they are compared.
    """
    import shapely

    if not outlines:
        raise FormatError("has no closed outline", path=path)
    check_count("outlines", len(outlines), MAX_OUTLINES, path=path,
                hint="split the drawing into several files")
    pts = [o.ring.vertices for o in outlines]
    pts += [o.ring.controls[~np.isnan(o.ring.controls)].reshape(-1, 2)
            for o in outlines if o.ring.controls is not None]
    pts = np.concatenate(pts)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    notices = list(check_extent(lo, hi, path=path))
    size = float(np.linalg.norm(hi - lo))
    tol = max(size * CHECK_TOLERANCE, 1e-300)
    keep = _distinct(outlines)
    if len(keep) < len(outlines):  # before flattening: 3,000 copies cost what one does
        first_dup = int(np.setdiff1d(np.arange(len(outlines)), keep)[0])
        notices.append(f"outlines: dropped {len(outlines) - len(keep)} duplicate outline(s) "
                       f"({outlines[first_dup].label}, …)")
        outlines = [outlines[int(k)] for k in keep]
    pairs = _candidate_pairs(outlines, path)
    flats, total = [], 0
    for outline in outlines:  # per outline, counting the points before they pile up
        flats.append(outline.ring.flattened(tol))
        total += len(flats[-1])
        check_count("points the outlines are flattened to for checking", total,
                    MAX_FLAT_POINTS, path=path, hint="draw fewer or simpler curves")
    short = next((k for k, flat in enumerate(flats) if len(flat) < 3), None)
    if short is not None:
        raise GeometryError(f"{outlines[short].label} has zero area: it has fewer than three "
                            "distinct points", path=path)
    counts = np.array([len(flat) for flat in flats])
    rings = shapely.linearrings(np.concatenate(flats), indices=np.repeat(np.arange(len(flats)),
                                                                         counts))
    polygons = shapely.polygons(rings)
    areas = _signed_areas(outlines, flats)
    _check_each(outlines, polygons, areas, size, path, scale)
    inside = _nesting(outlines, polygons, pairs, path, scale, lo)
    same = shapely.equals(polygons[inside[0]], polygons[inside[1]])
    if same.any():  # the same outline drawn with other vertices: drop the later copies
        dup = np.unique(np.maximum(inside[0, same], inside[1, same]))
        notices.append(f"outlines: dropped {len(dup)} duplicate outline(s) "
                       f"({outlines[int(dup[0])].label}, …)")
        kept = np.setdiff1d(np.arange(len(outlines)), dup)
        renumber = np.full(len(outlines), -1)
        renumber[kept] = np.arange(len(kept))
        inside = renumber[inside[:, ~np.isin(inside, dup).any(axis=0)]]
        outlines, areas = [outlines[int(k)] for k in kept], areas[kept]
    depth = np.bincount(inside[1], minlength=len(outlines))
    parent = np.full(len(outlines), -1)
    direct = depth[inside[0]] == depth[inside[1]] - 1
    parent[inside[1, direct]] = inside[0, direct]
    outer = np.flatnonzero(depth % 2 == 0)
    names = unique_names([outlines[k].name or f"outline {i + 1}" for i, k in enumerate(outer)])
    holes_of = _group(parent, depth % 2 == 1)
    parts = []
    for k, part_name in zip(outer, names):  # per outer boundary
        holes = holes_of.get(int(k), [])
        members = [outlines[k]] + [outlines[h] for h in holes]
        rings = [_oriented(outlines[k].ring, areas[k], True)]
        rings += [_oriented(outlines[h].ring, areas[h], False) for h in holes]
        parts.append(_lamina(rings, part_name, sum(m.error for m in members),
                             {m.approximation for m in members if m.approximation}))
    return assemble(parts, name), tuple(notices)


def _distinct(outlines: list[Outline]) -> np.ndarray:
    """Indices of the first of each set of identical outlines, found by hashing their exact
    edges (:func:`_ring_key`) — linear, not pairwise, and before any curve is flattened."""
    first: dict[bytes, int] = {}
    for k, outline in enumerate(outlines):  # per outline
        first.setdefault(_ring_key(outline.ring), k)
    return np.array(sorted(first.values()), dtype=int)


def _ring_key(ring: Ring) -> bytes:
    """The ring's edges (start, end, bulge, Bézier controls) each written the way round that
    sorts first, then sorted: the same bytes for the same curve drawn from any vertex,
    either way round."""
    v = ring.vertices
    n = len(v)
    ahead = np.roll(v, -1, axis=0)
    bulge = np.zeros((n, 1)) if ring.bulges is None else ring.bulges[:, None]
    controls = np.full((n, 4), np.inf) if ring.controls is None else \
        np.nan_to_num(ring.controls.reshape(n, 4), nan=np.inf)
    forward = np.hstack((v, ahead, bulge, controls)) + 0.0  # + 0.0: no −0.0 in the bytes
    backward = np.hstack((ahead, v, -bulge, controls[:, [2, 3, 0, 1]])) + 0.0
    differs = forward != backward
    first = np.argmax(differs, axis=1)
    rows = np.arange(n)
    flip = differs[rows, first] & (backward[rows, first] < forward[rows, first])
    edges = np.where(flip[:, None], backward, forward)
    return edges[np.lexsort(edges.T[::-1])].tobytes()


def _check_each(outlines: list[Outline], polygons: np.ndarray, areas: np.ndarray, size: float,
                path: str | None, scale: float | np.ndarray) -> None:
    """Every outline simple and enclosing area (vectorised; the first bad one is named)."""
    import shapely

    floor = 1e-14 * size * size
    good = shapely.is_valid(polygons) & (shapely.area(shapely.convex_hull(polygons)) > floor)
    for k in np.flatnonzero(~good):  # the first that has an error (error path only)
        error = validity_error(polygons[k], outlines[k].label, path, scale)
        if error is not None:
            raise error
    flat = np.flatnonzero(~(np.abs(areas) > floor))
    if len(flat):
        raise GeometryError(f"{outlines[flat[0]].label} has zero area: it encloses nothing",
                            path=path)


def _ring_box(ring: Ring) -> np.ndarray:
    """A box (xmin, ymin, xmax, ymax) holding the exact curve, from its own data: vertices,
    Bézier controls (the convex hull property) and, per arc, the disc about its chord's
    midpoint of radius chord/2 · max(1, |bulge|), which holds the whole arc."""
    points = [ring.vertices]
    if ring.controls is not None:
        points.append(ring.controls[~np.isnan(ring.controls)].reshape(-1, 2))
    if ring.bulges is not None:
        ahead = np.roll(ring.vertices, -1, axis=0)
        middle = (ring.vertices + ahead) / 2
        reach = np.linalg.norm(ahead - ring.vertices, axis=1) / 2 \
            * np.maximum(1.0, np.abs(ring.bulges))
        points += [middle - reach[:, None], middle + reach[:, None]]
    every = np.concatenate(points)
    return np.concatenate((every.min(axis=0), every.max(axis=0)))


def _candidate_pairs(outlines: list[Outline], path: str | None) -> np.ndarray:
    """The pairs (i, j), i ≠ j, of outlines whose boxes meet, (2, m): the only pairs that may
    nest or cross. Counted, in chunks, against :data:`MAX_OUTLINE_PAIRS` from the exact
    curves' boxes — before anything is flattened or compared, so no drawing asks for n²
    work or memory."""
    import shapely

    boxes = shapely.box(*np.array([_ring_box(o.ring) for o in outlines]).T)
    tree = shapely.STRtree(boxes)
    chunk = max(1, MAX_OUTLINE_PAIRS // len(boxes))
    found, total = [], 0
    for start in range(0, len(boxes), chunk):  # per chunk of outlines
        pairs = tree.query(boxes[start:start + chunk])
        pairs[0] += start
        total += pairs.shape[1]
        check_count("pairs of outlines whose bounding boxes meet", total, MAX_OUTLINE_PAIRS,
                    path=path, hint="the outlines nest or overlap too much to be compared")
        found.append(pairs[:, pairs[0] != pairs[1]])
    return np.concatenate(found, axis=1)


def _nesting(outlines: list[Outline], polygons: np.ndarray, pairs: np.ndarray,
             path: str | None, scale: float | np.ndarray, lo: np.ndarray) -> np.ndarray:
    """The pairs (container, contained), (2, m), among the candidate ``pairs``; outlines
    that cross are an error naming a point."""
    import shapely

    a, b = polygons[pairs[0]], polygons[pairs[1]]
    crossing = np.flatnonzero(shapely.overlaps(a, b))
    if len(crossing):
        i, j = pairs[:, crossing[0]]
        where = shapely.intersection(polygons[i].exterior, polygons[j].exterior)
        point = np.asarray(shapely.get_coordinates(where))[0] if not where.is_empty else lo
        raise GeometryError(f"{outlines[i].label} and {outlines[j].label} cross each other at "
                            f"{fmt_point(point / scale)}: outlines must nest or stay apart",
                            path=path)
    return pairs[:, shapely.contains(a, b)]


def _group(parent: np.ndarray, mask: np.ndarray) -> dict[int, list[int]]:
    """``{p: [children k with parent[k] == p and mask[k]]}``, in order, in one pass."""
    children = np.flatnonzero(mask & (parent >= 0))
    groups: dict[int, list[int]] = {}
    for k in children:  # per child
        groups.setdefault(int(parent[k]), []).append(int(k))
    return groups


def body_from_polygons(named: list[tuple[str, object]], *, path: str | None,
                       scale: float = 1.0) -> tuple[Body, tuple[str, ...]]:
    """Laminas from shapely (Multi)Polygons, one per entry, coordinates × ``scale`` (m)."""
    import shapely

    if not named:
        raise FormatError("has no Polygon or MultiPolygon", path=path)
    parts_of = shapely.get_parts([g for _, g in named])
    rings = len(parts_of) + int(shapely.get_num_interior_rings(parts_of).sum())
    check_count("rings", rings, MAX_OUTLINES, path=path, hint="split the file")
    with np.errstate(over="ignore", invalid="ignore"):
        geometries = [shapely.transform(g, lambda c: c * scale) if scale != 1.0 else g
                      for _, g in named]
        bounds = np.array([shapely.bounds(g) for g in geometries])
    if not np.isfinite(bounds).all():
        raise GeometryError("a coordinate is not a finite number (NaN or infinity)", path=path)
    # bounds skip a NaN (GEOS compares with it), so every coordinate is looked at
    counts = shapely.get_num_coordinates(geometries)
    finite = np.isfinite(shapely.get_coordinates(geometries)).all(axis=1)
    if not finite.all():
        at = int(np.argmin(finite))
        which = int(np.searchsorted(np.cumsum(counts), at, side="right"))
        label = f"polygon {named[which][0]!r}" if len(named) > 1 else "the polygon"
        point = at - int(np.sum(counts[:which])) + 1
        raise GeometryError(f"{label}: point {point} has a coordinate that is not a finite "
                            "number (NaN or infinity)", path=path)
    notices = check_extent(bounds[:, :2].min(axis=0), bounds[:, 2:].max(axis=0), path=path)
    names = unique_names([n for n, _ in named])
    several = len(named) > 1
    doubtful = suspects(geometries)
    empty = ~(shapely.area(np.asarray(geometries, dtype=object)) > 0)
    for k in np.flatnonzero(doubtful | empty).tolist():  # only those flagged, for the message
        label = f"polygon {names[k]!r}" if several else "the polygon"
        error = validity_error(geometries[k], label, path, scale) if doubtful[k] else None
        if error is not None:
            raise error
        raise GeometryError(f"{label} has zero area: it encloses nothing", path=path)
    parts = [Lamina(region, name=part_name)
             for region, part_name in zip(Region.many_from_shapely(geometries), names)]
    return assemble(parts, stem(path) if path else None), notices
