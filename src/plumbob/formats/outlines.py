"""Laminas from outline files: GeoJSON, WKT, WKB, CSV vertex lists, SVG and DXF.

This module reads the polygon formats (GeoJSON, WKT, WKB) and CSV vertex
lists itself, and hands SVG and DXF to their own readers (:mod:`.svg`,
:mod:`.dxf`, imported when such a file is read). Polygons become laminas
through :func:`~plumbob.formats.laminas.body_from_polygons`, bare closed curves
(CSV rings, drawings) through :func:`~plumbob.formats.laminas.body_from_outlines`,
by the even-odd rule. A file with several laminas gives an
:class:`~plumbob.bodies.csg.Assembly`.
"""

from __future__ import annotations

import json
import os
import re
import warnings

import numpy as np

from ..bodies.base import Body
from ..bodies.region import Ring
from ..errors import FormatError, GeometryError
from ..files import read_bytes
from ..limits import MAX_NESTING, MAX_OUTLINES, check_count
from ..reading import Reading
from ..units import reading_unit, unit_assumed, units_scale
from .laminas import Outline, body_from_outlines, body_from_polygons
from .nesting import check_wkb_nesting, check_wkt_nesting
from .parts import stem

__all__ = ["OUTLINE_SUFFIXES", "read_outline"]

OUTLINE_SUFFIXES = (".geojson", ".json", ".wkt", ".wkb", ".csv", ".svg", ".dxf")


# ------------------------------------------------------------------ dispatch
def read_outline(path: str, units: str | None = None, units_override: bool = False) -> Reading:
    """Read a lamina file; the format is chosen by the extension."""
    suffix = os.path.splitext(path)[1].lower()
    if suffix == ".svg":
        from .svg import read_svg

        return read_svg(path, units=units)
    if suffix == ".dxf":
        from .dxf import read_dxf

        return read_dxf(path, units=units, units_override=units_override)
    data = read_bytes(path)
    scale, notices = units_scale(units)
    if suffix == ".csv":
        outlines = _csv_outlines(data, path, scale)
        body, more = body_from_outlines(outlines, path=path, name=stem(path), scale=scale)
        return Reading(body, notices + more, path, reading_unit(units),
                       units_assumed=unit_assumed(units))
    if suffix in (".geojson", ".json"):
        named, more = _geojson_geometries(data, path)
        notices += more
    elif suffix == ".wkt":
        named = [(stem(path), _from_wkt(data, path))]
    elif suffix == ".wkb":
        named = [(stem(path), _from_wkb(data, path))]
    else:
        raise FormatError(f"is not an outline file plumbob reads ({', '.join(OUTLINE_SUFFIXES)})",
                          path=path)
    body, more = body_from_polygons(named, path=path, scale=scale)
    if suffix in (".geojson", ".json"):
        more = _lonlat_notice(body) + more
    return Reading(body, notices + more, path, reading_unit(units),
                   units_assumed=unit_assumed(units))


def _text(data: bytes, path: str, what: str) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as error:
        raise FormatError(f"is not UTF-8 text (byte {error.start}), so not {what}",
                          path=path) from None


def _polygonal(geometry, path: str, what: str):
    """The polygons of a shapely geometry (a Polygon, MultiPolygon or collection of them)."""
    import shapely

    if geometry is None or geometry.is_empty:
        raise FormatError(f"holds an empty {what} geometry: there is no area", path=path)
    kind = geometry.geom_type
    if kind in ("Polygon", "MultiPolygon"):
        return geometry
    if kind == "GeometryCollection":  # nested collections too (their depth is checked)
        parts = shapely.get_parts(geometry)
        while (shapely.get_type_id(parts) == 7).any():  # per level of nesting
            parts = shapely.get_parts(parts)
        polys = shapely.get_parts(parts[np.isin(shapely.get_type_id(parts), (3, 6))])
        if len(polys):
            return shapely.MultiPolygon(list(polys))
    raise FormatError(f"holds a {kind.upper()}, which has no area; plumbob needs a POLYGON or "
                      "MULTIPOLYGON", path=path)


def _from_wkt(data: bytes, path: str):
    import shapely

    text = _text(data, path, "WKT").strip()
    if not text:
        raise FormatError("holds no WKT geometry", path=path)
    check_wkt_nesting(text, path)  # GEOS would overflow its C stack
    try:
        with np.errstate(all="ignore"):  # 1e400 reads as inf: refused below, not warned
            geometry = shapely.from_wkt(text)
    except NotImplementedError:
        raise FormatError("holds curved geometry (CIRCULARSTRING, CURVEPOLYGON, …), which "
                          "plumbob does not read from WKT: linearise it, or draw it as DXF or "
                          "SVG arcs", path=path) from None
    except (shapely.errors.ShapelyError, ValueError, TypeError) as error:
        raise FormatError(f"is not valid WKT: {str(error).splitlines()[0]}", path=path) from None
    return _polygonal(geometry, path, "WKT")


def _from_wkb(data: bytes, path: str):
    import shapely

    payload: bytes | str = data
    stripped = data.strip()
    if stripped and re.fullmatch(rb"[0-9a-fA-F]+", stripped):
        payload = stripped.decode("ascii")  # hex-encoded WKB
        check_wkb_nesting(bytes.fromhex(payload) if len(payload) % 2 == 0 else b"", path)
    else:
        check_wkb_nesting(data, path)  # GEOS would overflow its C stack
    try:
        with np.errstate(all="ignore"):
            geometry = shapely.from_wkb(payload)
    except NotImplementedError:
        raise FormatError("holds curved geometry (CIRCULARSTRING, CURVEPOLYGON, …), which "
                          "plumbob does not read from WKB: linearise it", path=path) from None
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
    _walk_geojson(doc, stem(path), found, skipped, path, depth=0)
    notices = ()
    if skipped:
        kinds = ", ".join(f"{n} {k}" for k, n in sorted(skipped.items()))
        notices = (f"geojson: ignored geometries without area ({kinds})",)
    if not found:
        raise FormatError("has no Polygon or MultiPolygon geometry" +
                          (f" (only {', '.join(sorted(skipped))})" if skipped else ""), path=path)
    return found, notices


def _walk_geojson(obj, name: str, found: list, skipped: dict, path: str, depth: int) -> None:
    check_count("GeoJSON nesting depth", depth, MAX_NESTING, path=path)
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
            xy = _positions(ring, name, path)
            if len(xy) < 3:
                raise GeometryError(f"{name}: a ring has only {len(xy)} positions", path=path)
            if not np.isfinite(xy[:, :2]).all():
                raise GeometryError(f"{name}: a coordinate is not a finite number", path=path)
            rings.append(xy[:, :2])
        shapes.append(shapely.Polygon(rings[0], rings[1:]))
    return shapes[0] if obj["type"] == "Polygon" else shapely.MultiPolygon(shapes)


def _positions(ring, name: str, path: str) -> np.ndarray:
    """A ring's positions as an (n, ≥2) float array: JSON numbers only. ``true``/``false``
    (Python bools, which ``isinstance(x, int)`` accepts and numpy reads as 1/0: so the
    exact type is asked) and
    strings (which numpy would parse) are errors, not coordinates."""
    try:
        table = np.array(ring, dtype=object)
    except ValueError:  # ragged
        table = None
    if table is None or table.ndim != 2 or table.shape[1] < 2:
        raise FormatError(f"{name}: a ring must be a list of [x, y] positions", path=path)
    numeric = np.frompyfunc(lambda c: type(c) in (float, int), 1, 1)(table).astype(bool)
    if not numeric.all():
        bad = table[np.unravel_index(np.argmin(numeric), table.shape)]
        raise FormatError(f"{name}: a coordinate is {json.dumps(bad)[:40]}, not a number",
                          path=path)
    try:
        return table.astype(float)
    except OverflowError:
        raise GeometryError(f"{name}: a coordinate is too large for a number", path=path) from None


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
    rings, an optional header line (:func:`_is_header`). All numbers are parsed in one pass;
    the ring count is checked against :data:`~plumbob.limits.MAX_OUTLINES` before any ring
    is built."""
    text = _text(data, path, "CSV").replace("\r\n", "\n").replace("\r", "\n")
    lines = np.array(text.split("\n"), dtype=object)
    filled = np.array([bool(line.strip()) for line in lines], dtype=bool)
    rows = np.flatnonzero(filled)  # 0-based line indices of the data
    if len(rows) and _is_header(lines[rows[0]]):
        rows = rows[1:]
    if not len(rows):
        raise FormatError("holds no x,y rows", path=path)
    ring_of = np.cumsum(np.diff(rows, prepend=-2) > 1) - 1  # a gap starts a new ring
    check_count("outlines (rings)", int(ring_of[-1]) + 1, MAX_OUTLINES, path=path,
                hint="split the file")
    flat = re.sub(r"[,;\t]", " ", "\n".join(lines[rows]))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            values = np.fromstring(flat, sep=" ")
    except ValueError:  # numpy ≥ 2.3 raises on text that is not numbers
        values = None
    if values is None or len(values) != 2 * len(rows):
        _bad_csv_row(lines[rows], rows + 1, path)
    xy = values.reshape(-1, 2)
    finite = np.isfinite(xy).all(axis=1)
    if not finite.all():
        raise GeometryError(f"line {rows[np.argmin(finite)] + 1}: a coordinate is not a finite "
                            "number", path=path)
    starts = np.flatnonzero(np.diff(ring_of, prepend=-1))
    sizes = np.diff(starts, append=len(rows))
    if (sizes < 3).any():
        k = int(np.argmax(sizes < 3))
        raise GeometryError(f"ring {k + 1} (line {rows[starts[k]] + 1}) has only {sizes[k]} "
                            "points; an outline needs at least three", path=path)
    with np.errstate(over="ignore"):
        xy = xy * scale
    return [Outline(Ring(ring), f"ring {k + 1} (line {rows[start] + 1})")
            for k, (start, ring) in enumerate(zip(starts, np.split(xy, starts[1:])))]


#: a field that means a number, or tries to (``12``, ``-.5``, ``0mm``, ``nan``, ``inf``)
_NUMBERISH = re.compile(r"^[+-]?(?:\d|\.\d|nan|inf)", re.IGNORECASE)


def _is_header(row: str) -> bool:
    """Only a row of words is a header (``x,y``, ``"X (mm)";"Y (mm)"``): a row with any field
    that is, or starts like, a number (``0mm,0mm``, ``nan,0``) is data, so a bad first data
    row is an error naming its line, never dropped in silence.

    >>> _is_header("x,y"), _is_header("X (mm); Y (mm)"), _is_header("0mm,0mm"), _is_header("nan,0")
    (True, True, False, False)
    """
    fields = [f.strip("\"'") for f in re.split(r"[,;\t ]+", row.strip()) if f]
    return bool(fields) and not any(_NUMBERISH.match(f) for f in fields)


def _bad_csv_row(rows, numbers, path: str) -> None:
    """Raise the error naming the first row (line ``numbers``) that is not two numbers."""
    for row, number in zip(rows, numbers):  # error path only: find the line to name
        fields = [f for f in re.split(r"[,;\t ]+", row.strip()) if f]
        try:
            ok = len(fields) == 2 and len([float(f) for f in fields]) == 2
        except ValueError:
            ok = False
        if not ok:
            raise FormatError(f"line {number}: {row.strip()[:60]!r} is not two numbers x,y",
                              path=path)
    raise FormatError("a row is not two numbers x,y", path=path)
