"""SVG outlines: every closed path and shape, curves kept exact.

The file is read once (bounded) and first parsed with defusedxml, which
refuses entity declarations (entity-expansion bombs) and external references;
what its ``<use>`` references expand to — shapes and copies, through every
level — is counted against :mod:`plumbob.limits` before anything is expanded;
then svgelements resolves styles, ``<use>`` and transforms. Segments become
ring edges: lines as they are, circular arcs as bulges (exact), quadratic
Béziers raised exactly to cubics, cubic Béziers as they are, elliptical arcs as
cubic Béziers within about 1e-11 of their size (the lamina is then marked not
exact, with a bound).

Coordinates are read in user units (the numbers in the path data). Their size
comes from the ``<svg>`` element: with a viewBox and a physical width or
height (``100mm``, ``4in``, a number of CSS px), one user unit is that length
over the viewBox's (exact CSS factors: 1 in = 96 px = 25.4 mm); without a
viewBox a user unit is a CSS px (1/96 in); ``--units`` overrides both.

SVG's y axis points down the page; plumbob's points up, so y is flipped: a
drawing's up is up (a T drawn standing on its stem rests on its stem). Points in
messages are in the file's own coordinates (y down).
"""

from __future__ import annotations

import re

import numpy as np

from ..bodies.region import Ring
from ..errors import FormatError, GeometryError, fmt_point
from ..files import read_bytes
from ..limits import MAX_ELEMENT_DEPTH, MAX_NESTING, MAX_OUTLINES, MAX_PARTS, check_count
from ..reading import Reading
from ..units import METRES_PER_UNIT, reading_unit, units_scale
from .checks import ABSURD_COORDINATE
from .curves import arc_bulges, elliptic_arc_cubics
from .laminas import Outline, body_from_outlines
from .parts import stem

__all__ = ["read_svg", "PX"]

PX = METRES_PER_UNIT["px"]  #: metres per CSS px


def read_svg(path: str, units: str | None = None) -> Reading:
    """Laminas from the closed paths and shapes of an SVG file (see module docstring)."""
    data = read_bytes(path)
    _check_xml(data, path)
    import svgelements as se

    svg = _parse(data, path, None)
    try:
        text = svg.viewbox_transform
        viewport = se.Matrix(text) if text else se.Matrix()
        det = viewport.a * viewport.d - viewport.b * viewport.c
    except (ArithmeticError, ValueError, TypeError):
        det = np.nan
    if not (np.isfinite(det) and det != 0 and np.isfinite([viewport.e, viewport.f]).all()):
        raise FormatError("has a degenerate size or viewBox (zero, infinite or not a number)",
                          path=path)
    per_unit = _metres_per_user_unit(svg)
    if not viewport.is_identity():  # read coordinates in user units, not svgelements' px
        inverse = ~viewport
        numbers = " ".join(repr(float(getattr(inverse, k))) for k in "abcdef")
        svg = _parse(data, path, f"matrix({numbers})")
    notices: list[str] = []
    if units is not None:
        scale, more = units_scale(units)
        notices += more
        if per_unit is not None and not np.isclose(per_unit, scale):
            notices.append(f"units: the SVG's size says one user unit is {per_unit * 1e3:.6g} mm; "
                           f"--units {units} used instead")
    elif per_unit is not None:
        scale = per_unit
        notices.append(f"units: from the SVG's width and viewBox (one user unit is "
                       f"{per_unit * 1e3:.6g} mm)")
    else:
        scale = PX
        notices.append("units: the SVG gives no physical size; one user unit read as 1 px "
                       "(1/96 in) — use --units to say otherwise")
    outlines, skipped = _outlines(svg, path, scale)
    if skipped:
        notices.append(f"svg: ignored {skipped} open line/polyline element(s), which enclose "
                       "no area")
    if not outlines:
        raise FormatError("has no closed path or shape", path=path)
    file_axes = np.array([scale, -scale])  # metres per file unit along x and y (flipped)
    body, more = body_from_outlines(outlines, path=path, name=stem(path), scale=file_axes)
    return Reading(body, tuple(notices) + more, path, reading_unit(units))


def _check_xml(data: bytes, path: str) -> None:
    """Parse once with defusedxml: no entities, no external references, well-formed, an
    ``<svg>`` root, and ``<use>`` expansion within the limits (:func:`_check_expansion`)."""
    import xml.etree.ElementTree as ElementTree

    import defusedxml.ElementTree as safe_xml
    from defusedxml import DefusedXmlException

    try:
        root = safe_xml.fromstring(data, forbid_dtd=False, forbid_entities=True,
                                   forbid_external=True)
    except DefusedXmlException as error:
        raise FormatError(f"declares XML entities or external references "
                          f"({type(error).__name__}): refused (entity-expansion attack?)",
                          path=path) from None
    except ElementTree.ParseError as error:
        raise FormatError(f"is not well-formed XML: {error}", path=path) from None
    except (ValueError, RecursionError) as error:
        raise FormatError(f"is not well-formed XML: {error}", path=path) from None
    if not root.tag.lower().endswith("svg"):
        raise FormatError(f"is XML but not SVG (its root element is <{root.tag}>)", path=path)
    check_count("the depth of its element tree (groups within groups)", _depth(root),
                MAX_ELEMENT_DEPTH, hint="ungroup the drawing (Inkscape: Object ▸ Ungroup) "
                "or flatten it", path=path)
    _check_expansion(root, path)


def _depth(root) -> int:
    """How many levels deep the element tree under ``root`` goes (1: the root alone),
    one level at a time, without recursion."""
    depth, level = 0, [root]
    while level:
        depth += 1
        level = [child for element in level for child in element]
    return depth


#: the sizes of shapes that SVG forbids to be negative
_SIZES = {"circle": ("r",), "ellipse": ("rx", "ry"), "rect": ("width", "height")}
#: the SVG elements that draw a shape
_SHAPES = {"path", "rect", "circle", "ellipse", "polygon", "polyline", "line"}
_HUGE = 10**18  # expansion counts are capped here before they are compared (as floats)


def _local(tag) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _check_expansion(root, path: str) -> None:
    """Count the shapes the document draws and the ``<use>`` copies it places, through every
    level of reference, against MAX_OUTLINES and MAX_PARTS before svgelements expands them
    (ten levels of ten ``<use>`` each is 10¹⁰ shapes from a 1 KB file). Each referenced
    element is counted once; a reference to itself, or a chain deeper than MAX_NESTING, is an
    error."""
    ids = {e.get("id"): e for e in root.iter() if e.get("id") is not None}
    memo: dict[int, tuple[int, int, int]] = {}  # per referenced element: shapes, copies, depth

    def total(element, chain: tuple[int, ...]) -> tuple[int, int, int]:
        shapes = copies = depth = 0
        for e in element.iter():  # the element and everything inside it
            tag = _local(e.tag)
            if tag in _SHAPES:
                shapes += 1
            elif tag == "use":
                href = e.get("href") or e.get("{http://www.w3.org/1999/xlink}href") or ""
                target = ids.get(href[1:]) if href.startswith("#") else None
                if target is None:
                    continue
                if id(target) in chain:
                    raise FormatError(f"<use> refers to {href!r}, which contains it: an endless "
                                      "loop", path=path)
                if id(target) not in memo:
                    check_count("<use> nesting depth", len(chain) + 1, MAX_NESTING, path=path)
                    memo[id(target)] = total(target, chain + (id(target),))
                s, c, d = memo[id(target)]
                shapes, copies = min(shapes + s, _HUGE), min(copies + 1 + c, _HUGE)
                depth = max(depth, d + 1)
                check_count("<use> nesting depth", depth, MAX_NESTING, path=path)
        return shapes, copies, depth

    shapes, copies, _ = total(root, ())
    hint = "the drawing's <use> references expand to too much"
    check_count("<use> copies", copies, MAX_PARTS, path=path, hint=hint)
    check_count("shapes", shapes, MAX_OUTLINES, path=path, hint=hint)


def _parse(data: bytes, path: str, transform: str | None):
    import io

    import svgelements as se

    try:
        svg = se.SVG.parse(io.BytesIO(data), reify=True, transform=transform)
    except Exception as error:  # noqa: BLE001 - svgelements raises every kind on bad input
        raise FormatError(f"cannot be read as SVG: {type(error).__name__}: "
                          f"{str(error)[:200]}", path=path) from None
    if not isinstance(svg, se.SVG):
        raise FormatError("has no <svg> element in the SVG namespace "
                          "(xmlns=\"http://www.w3.org/2000/svg\")", path=path)
    return svg


_LENGTH = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*([a-zA-Z]*)\s*$")
#: the absolute CSS length units (a bare number is in px)
_CSS_UNITS = ("px", "mm", "cm", "q", "in", "pt", "pc")


def _css_length(text) -> float | None:
    """A CSS length in metres (``100mm``, ``4in``, ``300`` px); None for %, em or nothing."""
    if text is None:
        return None
    match = _LENGTH.match(str(text))
    unit = (match.group(2).lower() or "px") if match else None
    if unit not in _CSS_UNITS:
        return None
    value = float(match.group(1)) * METRES_PER_UNIT[unit]
    return value if value > 0 and np.isfinite(value) else None


def _metres_per_user_unit(svg) -> float | None:
    """Metres per user unit from the root's width/height and viewBox (exact CSS factors);
    without a viewBox a user unit is a px; None when the file gives no physical size."""
    box = svg.viewbox
    width, height = _css_length(svg.values.get("width")), _css_length(svg.values.get("height"))
    if box is None:
        return PX if (width or height) else None
    bw, bh = float(box.width or 0), float(box.height or 0)
    scales = [s for s in (width and bw > 0 and width / bw, height and bh > 0 and height / bh)
              if s and np.isfinite(s)]
    return min(scales) if scales else None


def _outlines(svg, path: str, scale: float) -> tuple[list[Outline], int]:
    import svgelements as se

    outlines: list[Outline] = []
    skipped = 0
    count = 0
    try:
        elements = list(svg.elements())
    except Exception as error:  # noqa: BLE001
        raise FormatError(f"cannot be read as SVG: {error}", path=path) from None
    for element in elements:  # per element
        if not isinstance(element, se.Shape) or isinstance(element, se.Text):
            continue
        count += 1
        ident = element.id
        kind = type(element).__name__.lower()
        name = f"{kind} {ident!r}" if ident else f"{kind} {count}"
        for key in _SIZES.get(kind, ()):  # svgelements would draw -1 as 1
            value = str(element.values.get(key, "")).strip()
            if value.startswith("-") and re.search(r"[1-9]", value):
                raise GeometryError(f"{name}: {key} = {value} is negative, which SVG calls an "
                                    "error (nothing is drawn); fix the file", path=path)
        try:
            segments = list(abs(se.Path(element)))
        except Exception as error:  # noqa: BLE001
            raise FormatError(f"{name}: cannot be read ({error})", path=path) from None
        open_shape = isinstance(element, (se.SimpleLine, se.Polyline))
        found, was_open = _subpaths(segments, name, path, scale, allow_open=open_shape)
        skipped += was_open
        for k, (ring, error, approx) in enumerate(found):
            label = name if len(found) == 1 else f"{name} (subpath {k + 1})"
            outlines.append(Outline(ring, label, ident or None, error, approx))
    return outlines, skipped


def _subpaths(segments, name: str, path: str, scale: float, allow_open: bool):
    """Closed rings of one element's path: (ring, area error m², approximation) each."""
    import svgelements as se

    rings = []
    skipped = 0
    points: list[np.ndarray] = []
    bulges: list[float] = []
    controls: list[np.ndarray] = []
    error = 0.0
    approx: str | None = None
    start = None
    nan = np.full((2, 2), np.nan)
    axes = np.array([scale, -scale])  # SVG's y runs down the page: flipped to up

    def xy(point) -> np.ndarray:  # metres, y up; plain floats: called for every point
        x, y = float(point.x) * scale, -float(point.y) * scale
        if not (abs(x) <= ABSURD_COORDINATE and abs(y) <= ABSURD_COORDINATE):  # NaN fails
            raise GeometryError(f"{name}: the coordinate {fmt_point((point.x, point.y))} is "
                                "not a finite number of plausible size", path=path)
        return np.array((x, y))

    def finish(closed: bool, end) -> None:
        nonlocal points, bulges, controls, error, approx, skipped
        if points:
            first = points[0]
            gap = float(np.linalg.norm(end - first)) if end is not None else 0.0
            size = float(np.ptp(np.array(points), axis=0).max()) if len(points) > 1 else 0.0
            if not closed and gap > 1e-9 * max(size, gap):
                if allow_open:
                    skipped += 1
                else:
                    k = len(rings) + 1
                    raise GeometryError(
                        f"{name} (subpath {k}) never closes: it ends at {fmt_point(end / axes)}, "
                        f"not at its start {fmt_point(first / axes)}; close it with Z",
                        path=path)
            else:
                rings.append((Ring(np.array(points), np.array(bulges), np.array(controls)),
                              error, approx))
        points, bulges, controls, error, approx = [], [], [], 0.0, None

    end = None
    for seg in segments:  # per segment of one element
        if isinstance(seg, se.Move):
            finish(False, end)
            start = xy(seg.end)
            end = start
            continue
        if seg.start is None or seg.end is None:
            continue
        p0, p1 = xy(seg.start), xy(seg.end)
        if start is None:
            start = p0
        if isinstance(seg, se.Close):
            if np.linalg.norm(p1 - p0) > 0:
                points.append(p0), bulges.append(0.0), controls.append(nan)
            finish(True, p1)
            start, end = None, p1
            continue
        if np.array_equal(p0, p1) and not isinstance(seg, se.Arc):
            if isinstance(seg, se.CubicBezier | se.QuadraticBezier):
                pass  # a closed loop in one Bézier: keep it (area between its controls)
            else:
                continue
        if isinstance(seg, se.Line):
            points.append(p0), bulges.append(0.0), controls.append(nan)
        elif isinstance(seg, se.QuadraticBezier):
            q = xy(seg.control)
            points.append(p0), bulges.append(0.0)
            controls.append(np.array([p0 + 2 / 3 * (q - p0), p1 + 2 / 3 * (q - p1)]))
        elif isinstance(seg, se.CubicBezier):
            points.append(p0), bulges.append(0.0)
            controls.append(np.array([xy(seg.control1), xy(seg.control2)]))
        elif isinstance(seg, se.Arc):
            e, a = _arc(seg, p0, p1, xy, points, bulges, controls)
            error += e
            approx = approx or a
        else:
            raise FormatError(f"{name}: unsupported path segment {type(seg).__name__}", path=path)
        end = p1
    finish(False, end)
    return rings, skipped


def _arc(seg, p0, p1, xy, points, bulges, controls) -> tuple[float, str | None]:
    """Append an SVG arc: exact bulges when circular, else cubic pieces; returns the area
    error bound (m²) and a description of any approximation."""
    centre = xy(seg.center)
    u = xy(seg.prx) - centre
    v = xy(seg.pry) - centre
    basis = np.column_stack((u, v))
    if np.linalg.norm(p1 - p0) == 0 or abs(np.linalg.det(basis)) <= 1e-15 * np.sum(basis**2):
        if np.linalg.norm(p1 - p0) > 0:  # a degenerate ellipse: SVG says draw a line
            points.append(p0), bulges.append(0.0), controls.append(np.full((2, 2), np.nan))
        return 0.0, None
    t0 = np.arctan2(*np.linalg.solve(basis, p0 - centre)[::-1])
    t1 = np.arctan2(*np.linalg.solve(basis, p1 - centre)[::-1])
    delta = (t1 - t0) % (2 * np.pi)
    mid = xy(seg.point(0.5))
    candidates = (delta, delta - 2 * np.pi)
    sweep = min(candidates, key=lambda s: np.linalg.norm(
        centre + np.cos(t0 + s / 2) * u + np.sin(t0 + s / 2) * v - mid))
    nan = np.full((2, 2), np.nan)
    ru, rv = np.linalg.norm(u), np.linalg.norm(v)
    if abs(ru - rv) <= 1e-9 * max(ru, rv) and abs(u @ v) <= 1e-9 * ru * rv:
        geometric = sweep * np.sign(np.linalg.det(basis))  # counter-clockwise positive
        start = np.arctan2(*(p0 - centre)[::-1])
        starts, bulge = arc_bulges(centre, (ru + rv) / 2, start, geometric)
        starts[0] = p0  # keep the path's own point exactly
        for s, b in zip(starts, bulge):
            points.append(s), bulges.append(float(b)), controls.append(nan)
        return 0.0, None
    ends, ctrl, error = elliptic_arc_cubics(centre, u, v, t0, sweep)
    ends[0] = p0
    for s, c in zip(ends[:-1], ctrl):
        points.append(s), bulges.append(0.0), controls.append(c)
    return error, "elliptical arcs as cubic Béziers (error below 1e-10 of their size)"
