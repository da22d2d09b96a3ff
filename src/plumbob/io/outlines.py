"""Laminas from outline files: GeoJSON, WKT, WKB, CSV vertex lists, SVG and DXF.

Polygon formats (GeoJSON, WKT, WKB) say which ring is a hole; each polygon
(or multipolygon, or GeoJSON feature) becomes one lamina. Drawing formats
(SVG, DXF, CSV) give bare closed curves: a curve inside an odd number of
others is a hole, inside an even number an outer boundary (the even-odd rule a
laser cutter follows), and each outer boundary with the holes directly inside
it becomes one lamina. A file with several laminas gives an
:class:`~plumbob.bodies.csg.Assembly`.

Curves stay exact where the geometry allows: circular arcs as DXF bulges,
quadratic Béziers raised exactly to cubics, cubic Béziers as they are — their
area moments are exact by Green's theorem. Elliptical arcs (not polynomial)
become cubic Béziers within a stated tolerance, and rational splines are
flattened; such laminas are marked not exact, with an error bound.

Every outline is checked: finite coordinates of plausible size, non-zero area,
no self-intersection (the error names the crossing point), no two outlines
crossing each other.
"""

from __future__ import annotations

import json
import os
import re
import warnings
from dataclasses import dataclass

import numpy as np

from ..bodies.base import Body
from ..bodies.lamina import Lamina
from ..bodies.region import Region, Ring
from ..errors import FormatError, GeometryError
from . import Reading
from .validate import check_extent, fmt_point, unique_names, units_scale

__all__ = [
    "OUTLINE_SUFFIXES",
    "Outline",
    "read_outline",
    "body_from_outlines",
    "body_from_polygons",
    "elliptic_arc_cubics",
    "arc_bulges",
    "validity_error",
]

OUTLINE_SUFFIXES = (".geojson", ".json", ".wkt", ".wkb", ".csv", ".svg", ".dxf")
#: flattening tolerance for checks, relative to the drawing's size
CHECK_TOLERANCE = 1e-7
#: parameter step of the cubic pieces approximating elliptical arcs (64 per turn)
ELLIPSE_STEP = 2 * np.pi / 64


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


# ------------------------------------------------------------------ dispatch
def read_outline(path: str, units: str | None = None) -> Reading:
    """Read a lamina file; the format is chosen by the extension."""
    suffix = os.path.splitext(path)[1].lower()
    if suffix == ".svg":
        from .svg import read_svg

        return read_svg(path, units=units)
    if suffix == ".dxf":
        from .dxf import read_dxf

        return read_dxf(path, units=units)
    data = _read_bytes(path)
    scale, notices = units_scale(units)
    if suffix == ".csv":
        outlines = _csv_outlines(data, path, scale)
        body, more = body_from_outlines(outlines, path=path, name=_stem(path), scale=scale)
        return Reading(body, notices + more, path)
    if suffix in (".geojson", ".json"):
        named, more = _geojson_geometries(data, path)
        notices += more
    elif suffix == ".wkt":
        named = [(_stem(path), _from_wkt(data, path))]
    elif suffix == ".wkb":
        named = [(_stem(path), _from_wkb(data, path))]
    else:
        raise FormatError(f"is not an outline file plumbob reads ({', '.join(OUTLINE_SUFFIXES)})",
                          path=path)
    body, more = body_from_polygons(named, path=path, scale=scale)
    if suffix in (".geojson", ".json"):
        more = _lonlat_notice(body) + more
    return Reading(body, notices + more, path)


def _read_bytes(path: str) -> bytes:
    with open(path, "rb") as f:
        return f.read()


def _stem(path: str) -> str:
    return os.path.splitext(os.path.basename(path))[0]


def _text(data: bytes, path: str, what: str) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise FormatError(f"is not UTF-8 text (byte {error.start}), so not {what}",
                          path=path) from None


# ------------------------------------------------------------------ checks
_REASONS = {
    "Self-intersection": "crosses itself at {p} (a bow-tie or a twisted outline)",
    "Ring Self-intersection": "touches itself at {p}",
    "Too few points": "has fewer than three distinct points",
    "Hole lies outside shell": "has a hole outside its outer boundary, near {p}",
    "Nested holes": "has a hole inside another hole, near {p}",
    "Interior is disconnected": "has holes that cut it apart, near {p}",
    "Invalid Coordinate": "has a coordinate that is not a finite number, near {p}",
    "Too few points in geometry component": "has fewer than three distinct points, near {p}",
    "Duplicate Rings": "has the same ring twice, near {p}",
}


def validity_error(geometry, label: str, path: str | None,
                   scale: float = 1.0) -> GeometryError | None:
    """The error for a degenerate or invalid shapely polygon (coordinates in metres), naming
    the point GEOS found in the file's coordinates (metres / ``scale``); None if valid."""
    import shapely

    hull = shapely.convex_hull(geometry)
    size = float(np.hypot(*np.ptp(np.asarray(shapely.get_coordinates(geometry)), axis=0))) \
        if not geometry.is_empty else 0.0
    if not hull.area > 1e-14 * size * size:
        return GeometryError(f"{label} has zero area: its points lie on a line", path=path)
    reason = shapely.is_valid_reason(geometry)
    if reason is None or reason == "Valid Geometry":
        return None
    match = re.match(r"^(.*?)\s*\[\s*([^\s\]]+)\s+([^\s\]]+)", reason)
    what, point = (match.group(1), (float(match.group(2)), float(match.group(3)))) if match \
        else (reason, None)
    template = _REASONS.get(what, what.lower() + " near {p}")
    text = template.format(p=fmt_point(np.array(point) / scale) if point is not None else "?")
    return GeometryError(f"{label} {text}", path=path)


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


def _assemble(parts: list[Lamina], name: str | None) -> Body:
    if len(parts) == 1:
        return parts[0]
    from ..bodies.csg import Assembly

    return Assembly(tuple(parts), name=name)


# ------------------------------------------------------------------ even-odd
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
    return _assemble(parts, name), tuple(notices)


# ------------------------------------------------------------------ polygons
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
    return _assemble(parts, _stem(path) if path else None), notices


def _polygonal(geometry, path: str, what: str):
    """The polygons of a shapely geometry (a Polygon, MultiPolygon or collection of them)."""
    import shapely

    if geometry is None or geometry.is_empty:
        raise FormatError(f"holds an empty {what} geometry: there is no area", path=path)
    kind = geometry.geom_type
    if kind in ("Polygon", "MultiPolygon"):
        return geometry
    if kind == "GeometryCollection":
        polys = [g for g in geometry.geoms if g.geom_type in ("Polygon", "MultiPolygon")]
        if polys:
            return shapely.MultiPolygon([p for g in polys for p in getattr(g, "geoms", [g])])
    raise FormatError(f"holds a {kind.upper()}, which has no area; plumbob needs a POLYGON or "
                      "MULTIPOLYGON", path=path)


def _from_wkt(data: bytes, path: str):
    import shapely

    text = _text(data, path, "WKT").strip()
    if not text:
        raise FormatError("holds no WKT geometry", path=path)
    try:
        geometry = shapely.from_wkt(text)
    except (shapely.errors.ShapelyError, ValueError, TypeError) as error:
        raise FormatError(f"is not valid WKT: {str(error).splitlines()[0]}", path=path) from None
    return _polygonal(geometry, path, "WKT")


def _from_wkb(data: bytes, path: str):
    import shapely

    payload: bytes | str = data
    stripped = data.strip()
    if stripped and re.fullmatch(rb"[0-9a-fA-F]+", stripped):
        payload = stripped.decode("ascii")  # hex-encoded WKB
    try:
        geometry = shapely.from_wkb(payload)
    except (shapely.errors.ShapelyError, ValueError, TypeError) as error:
        raise FormatError(f"is not valid WKB: {str(error).splitlines()[0]}", path=path) from None
    return _polygonal(geometry, path, "WKB")


# ------------------------------------------------------------------ GeoJSON
def _geojson_geometries(data: bytes, path: str) -> tuple[list[tuple[str, object]], tuple[str, ...]]:
    text = _text(data, path, "GeoJSON")
    try:
        doc = json.loads(text)
    except (ValueError, RecursionError) as error:
        raise FormatError(f"is not valid JSON: {str(error)[:200]}", path=path) from None
    found: list[tuple[str, object]] = []
    skipped: dict[str, int] = {}
    _walk_geojson(doc, _stem(path), found, skipped, path, depth=0)
    notices = ()
    if skipped:
        kinds = ", ".join(f"{n} {k}" for k, n in sorted(skipped.items()))
        notices = (f"geojson: ignored geometries without area ({kinds})",)
    if not found:
        raise FormatError("has no Polygon or MultiPolygon geometry" +
                          (f" (only {', '.join(sorted(skipped))})" if skipped else ""), path=path)
    return found, notices


def _walk_geojson(obj, name: str, found: list, skipped: dict, path: str, depth: int) -> None:
    if depth > 32:
        raise FormatError("nests GeoJSON objects too deeply", path=path)
    if not isinstance(obj, dict):
        raise FormatError(f"{name}: a GeoJSON object must be a JSON object, not "
                          f"{type(obj).__name__}", path=path)
    kind = obj.get("type")
    if kind == "FeatureCollection":
        features = obj.get("features")
        if not isinstance(features, list):
            raise FormatError("a FeatureCollection needs a 'features' list", path=path)
        for i, feature in enumerate(features):  # per feature
            _walk_geojson(feature, f"feature {i + 1}", found, skipped, path, depth + 1)
    elif kind == "Feature":
        props = obj.get("properties") if isinstance(obj.get("properties"), dict) else {}
        label = props.get("name", obj.get("id", name))
        label = str(label) if label is not None else name
        if obj.get("geometry") is not None:
            _walk_geojson(obj["geometry"], label, found, skipped, path, depth + 1)
    elif kind == "GeometryCollection":
        geoms = obj.get("geometries")
        if not isinstance(geoms, list):
            raise FormatError(f"{name}: a GeometryCollection needs a 'geometries' list", path=path)
        for geom in geoms:
            _walk_geojson(geom, name, found, skipped, path, depth + 1)
    elif kind in ("Polygon", "MultiPolygon"):
        found.append((name, _geojson_polygon(obj, name, path)))
    elif isinstance(kind, str) and kind in ("Point", "MultiPoint", "LineString",
                                            "MultiLineString"):
        skipped[kind] = skipped.get(kind, 0) + 1
    else:
        raise FormatError(f"{name}: unknown GeoJSON type {kind!r}", path=path)


def _geojson_polygon(obj: dict, name: str, path: str):
    import shapely

    coords = obj.get("coordinates")
    polygons = [coords] if obj["type"] == "Polygon" else coords
    if not isinstance(polygons, list) or not polygons:
        raise FormatError(f"{name}: a {obj['type']} needs a non-empty 'coordinates' list",
                          path=path)
    shapes = []
    for polygon in polygons:  # per polygon, then per ring
        if not isinstance(polygon, list) or not polygon:
            raise FormatError(f"{name}: a polygon needs a list of rings", path=path)
        rings = []
        for ring in polygon:
            try:
                xy = np.asarray(ring, dtype=float)
            except (ValueError, TypeError):
                raise FormatError(f"{name}: a ring's positions are not lists of numbers",
                                  path=path) from None
            if xy.ndim != 2 or xy.shape[1] < 2:
                raise FormatError(f"{name}: a ring must be a list of [x, y] positions",
                                  path=path)
            if len(xy) < 3:
                raise GeometryError(f"{name}: a ring has only {len(xy)} positions", path=path)
            if not np.isfinite(xy[:, :2]).all():
                raise GeometryError(f"{name}: a coordinate is not a finite number", path=path)
            rings.append(xy[:, :2])
        shapes.append(shapely.Polygon(rings[0], rings[1:]))
    return shapes[0] if obj["type"] == "Polygon" else shapely.MultiPolygon(shapes)


def _lonlat_notice(body: Body) -> tuple[str, ...]:
    """GeoJSON's coordinates are longitude/latitude unless projected: say so when they look it."""
    pts = body.hull_points()
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    if (np.abs(pts[:, 0]) <= 180).all() and (np.abs(pts[:, 1]) <= 90).all() and \
            float(np.max(hi - lo)) < 0.5 and (np.abs(lo) > 1).any():
        return ("geojson: the coordinates look like longitude/latitude degrees (GeoJSON's "
                "default); plumbob reads them as plane lengths — project the file first",)
    return ()


# ------------------------------------------------------------------ CSV
def _csv_outlines(data: bytes, path: str, scale: float) -> list[Outline]:
    """Rings of ``x,y`` lines (comma, semicolon, tab or space separated), blank lines between
    rings, an optional header line."""
    text = _text(data, path, "CSV").replace("\r\n", "\n").replace("\r", "\n")
    outlines = []
    blocks = re.finditer(r"(?:[^\n]*\S[^\n]*(?:\n|$))+", text)  # runs of non-blank lines
    for b, match in enumerate(blocks):  # per ring
        rows = match.group().rstrip("\n").split("\n")
        start_line = text.count("\n", 0, match.start()) + 1
        if b == 0 and re.search(r"[A-Za-df-z_]", rows[0]):
            rows, start_line = rows[1:], start_line + 1  # a header
        if not rows:
            continue
        flat = re.sub(r"[,;\t]", " ", "\n".join(rows))
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                values = np.fromstring(flat, sep=" ")
        except ValueError:  # numpy ≥ 2.3 raises on text that is not numbers
            values = None
        if values is None or len(values) != 2 * len(rows):
            _bad_csv_row(rows, start_line, path)
        xy = values.reshape(-1, 2)
        if not np.isfinite(xy).all():
            bad = int(np.argmax(~np.isfinite(xy).all(axis=1)))
            raise GeometryError(f"line {start_line + bad}: a coordinate is not a finite number",
                                path=path)
        if len(xy) < 3:
            raise GeometryError(f"ring {len(outlines) + 1} (line {start_line}) has only "
                                f"{len(xy)} points; an outline needs at least three", path=path)
        with np.errstate(over="ignore"):
            ring = Ring(xy * scale)
        outlines.append(Outline(ring, f"ring {len(outlines) + 1} (line {start_line})"))
    if not outlines:
        raise FormatError("holds no x,y rows", path=path)
    return outlines


def _bad_csv_row(rows: list[str], start_line: int, path: str) -> None:
    for i, row in enumerate(rows):  # error path only: find the line to name
        fields = [f for f in re.split(r"[,;\t ]+", row.strip()) if f]
        try:
            ok = len(fields) == 2 and len([float(f) for f in fields]) == 2
        except ValueError:
            ok = False
        if not ok:
            raise FormatError(f"line {start_line + i}: {row.strip()[:60]!r} is not two numbers "
                              "x,y", path=path)
    raise FormatError("a row is not two numbers x,y", path=path)


# ------------------------------------------------------------------ curves
def _arc_error(step: float) -> float:
    """Largest radial deviation of the standard cubic (k = 4/3 tan(step/4)) from a unit
    circular arc of angle ``step``."""
    k = 4 / 3 * np.tan(step / 4)
    t = np.linspace(0, 1, 257)[:, None]
    p0, p3 = np.array([1.0, 0.0]), np.array([np.cos(step), np.sin(step)])
    p1, p2 = p0 + k * np.array([0.0, 1.0]), p3 - k * np.array([-np.sin(step), np.cos(step)])
    b = (1 - t) ** 3 * p0 + 3 * (1 - t) ** 2 * t * p1 + 3 * (1 - t) * t**2 * p2 + t**3 * p3
    return float(np.abs(np.hypot(b[:, 0], b[:, 1]) - 1).max())


_ELLIPSE_STEP_ERROR = _arc_error(ELLIPSE_STEP)


def elliptic_arc_cubics(centre: np.ndarray, u: np.ndarray, v: np.ndarray, t0: float,
                        sweep: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Cubic Béziers for ``E(t) = centre + cos t·u + sin t·v``, t from t0 through ``sweep``.

    u, v: conjugate semi-diameters (2,), m. Returns the piece ends (m+1, 2), their
    inner controls (m, 2, 2) and a bound on the area between curve and cubics, m².
    Each piece is the affine image of the standard cubic for a circular arc of at
    most :data:`ELLIPSE_STEP` (error ~1e-11 of the radius).
    """
    pieces = max(1, int(np.ceil(abs(sweep) / ELLIPSE_STEP - 1e-9)))
    h = sweep / pieces
    t = t0 + h * np.arange(pieces + 1)
    c, s = np.cos(t), np.sin(t)
    points = centre + c[:, None] * u + s[:, None] * v
    tangent = -s[:, None] * u + c[:, None] * v
    k = 4 / 3 * np.tan(h / 4)
    controls = np.stack((points[:-1] + k * tangent[:-1], points[1:] - k * tangent[1:]), axis=1)
    stretch = float(np.linalg.norm(np.column_stack((u, v)), 2))
    error = _arc_error(abs(h)) * stretch * stretch * abs(sweep)
    return points, controls, error


def arc_bulges(centre: np.ndarray, radius: float, start: float, sweep: float
               ) -> tuple[np.ndarray, np.ndarray]:
    """A circular arc as bulge edges: start points (m, 2) and bulges (m,), m ≤ 2.

    ``start``, ``sweep``: radians, positive sweep counter-clockwise; sweeps over
    half a turn are split in two so no bulge nears infinity. Quarter-turn angles
    give exact cosines.
    """
    pieces = 2 if abs(sweep) > np.pi else 1
    angles = start + sweep * np.arange(pieces) / pieces
    cos, sin = _exact_cos_sin(angles)
    points = centre + radius * np.stack((cos, sin), axis=1)
    return points, np.full(pieces, np.tan(sweep / pieces / 4))


def _exact_cos_sin(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    cos, sin = np.cos(angles), np.sin(angles)
    quarter = angles / (np.pi / 2)
    on_axis = np.abs(quarter - np.rint(quarter)) < 1e-12
    q = np.rint(quarter[on_axis]).astype(int) % 4
    cos[on_axis] = np.array([1.0, 0.0, -1.0, 0.0])[q]
    sin[on_axis] = np.array([0.0, 1.0, 0.0, -1.0])[q]
    return cos, sin
