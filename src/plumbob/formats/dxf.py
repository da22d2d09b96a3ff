"""DXF outlines through ezdxf, arcs kept exact.

Closed entities become outlines directly: LWPOLYLINE and 2D POLYLINE (bulges
are exact circular arcs), CIRCLE (two half-turn arcs), closed SPLINE and
full ELLIPSE. Open pieces — LINE, ARC, open polylines, open splines and
elliptical arcs — are joined end to end (within 1e-9 of the drawing's size)
into closed chains. Block references (INSERT) are expanded.

SPLINEs that are non-rational and clamped are split exactly into Bézier
pieces (degree 3 as they are, degree 2 raised to cubic, degree 1 as lines);
rational or unclamped ones are flattened within 1e-7 of the drawing's size and
the lamina marked not exact. Elliptical arcs become cubic Béziers (see
:func:`~plumbob.formats.curves.elliptic_arc_cubics`).

Units come from the ``$INSUNITS`` header unless ``--units`` is given.
Entities drawn in another plane than XY are ignored (with a notice); a mirrored
coordinate system (extrusion (0, 0, −1)) is mapped into XY exactly.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from ..bodies.region import Ring
from ..bodies.validity import check_bulges
from ..errors import FormatError, GeometryError, PlumbobError, fmt_point
from ..files import read_bytes
from ..limits import MAX_NESTING, MAX_OUTLINES, MAX_PARTS, MAX_SIDES, check_count
from ..mesh.topology import connected_components
from ..reading import Reading
from ..tolerances import size_of
from ..units import reading_unit, unit_assumed, units_scale
from .checks import ABSURD_COORDINATE
from .curves import arc_bulges, clamped_bspline, elliptic_arc_cubics
from .laminas import Outline, body_from_outlines
from .parts import stem

__all__ = ["read_dxf", "INSUNITS"]

#: $INSUNITS code → the unit's name and metres per unit (exact definitions; 0 is "unitless")
INSUNITS: dict[int, tuple[str, float]] = {
    1: ("inch", 0.0254), 2: ("foot", 0.3048), 3: ("mile", 1609.344), 4: ("millimeter", 1e-3),
    5: ("centimeter", 1e-2), 6: ("meter", 1.0), 7: ("kilometer", 1e3),
    8: ("microinch", 2.54e-8), 9: ("mil", 2.54e-5), 10: ("yard", 0.9144),
    11: ("angstrom", 1e-10), 12: ("nanometer", 1e-9), 13: ("micron", 1e-6),
    14: ("decimeter", 0.1), 15: ("decameter", 10.0), 16: ("hectometer", 100.0),
    17: ("gigameter", 1e9), 18: ("astronomical unit", 149_597_870_700.0),
    19: ("light year", 9_460_730_472_580_800.0), 20: ("parsec", 3.085_677_581_491_367e16),
    21: ("US survey foot", 1200 / 3937), 22: ("US survey inch", 100 / 3937),
    23: ("US survey yard", 3600 / 3937), 24: ("US survey mile", 6_336_000 / 3937),
}
JOIN_TOLERANCE = 1e-9  # relative to the drawing's size
FLATTEN_TOLERANCE = 1e-7  # relative to the drawing's size
_NAN = np.full((2, 2), np.nan)
_TILTED = object()  # what a maker returns for an entity that is not drawn in a plane z = c
#: segments a span needs at most when flattened within FLATTEN_TOLERANCE (√(1/8t))
_SEGMENTS_PER_SPAN = int(np.ceil(np.sqrt(1 / (8 * FLATTEN_TOLERANCE))))
_HUGE = 10**18  # expansion counts are capped here before they are compared (as floats)
#: the entity kinds that draw outlines (read, or expanded), as ezdxf's messages name them
_DRAWN = re.compile(r"\b(LWPOLYLINE|POLYLINE|CIRCLE|ARC|LINE|ELLIPSE|SPLINE|INSERT)\b")


@dataclass(eq=False)
class _Piece:
    """An open or closed run of edges: points (m+1, 2) including its end, bulges (m,),
    controls (m, 2, 2) NaN except cubic edges."""

    points: np.ndarray
    bulges: np.ndarray
    controls: np.ndarray
    label: str
    name: str | None
    error: float = 0.0
    approximation: str | None = None

    def reversed(self) -> _Piece:
        return _Piece(self.points[::-1], -self.bulges[::-1], self.controls[::-1, ::-1], self.label,
                      self.name, self.error, self.approximation)

    def outline(self, scale: float) -> Outline:
        ring = Ring(self.points[:-1] * scale, self.bulges, self.controls * scale)
        return Outline(ring, self.label, self.name, self.error * scale * scale, self.approximation)


def read_dxf(path: str, units: str | None = None, units_override: bool = False) -> Reading:
    """Laminas from the closed outlines of a DXF drawing (see module docstring);
    ``units_override`` as for :func:`plumbob.units.units_scale`."""
    doc = _open(path)
    file_units, file_scale = _file_units(doc.header.get("$INSUNITS", 0), path)
    scale, notices = units_scale(units, file_units, file_scale, override=units_override,
                                 path=path)
    notices = list(notices)
    pieces: list[_Piece] = []
    counts: dict[str, int] = {}
    try:
        _check_expansion(doc, path)
        for entity in doc.modelspace():  # per entity
            _collect(entity, pieces, counts, 0, ABSURD_COORDINATE / scale, path)
    except PlumbobError:
        raise
    except Exception as error:  # noqa: BLE001 - ezdxf raises every kind on corrupt entities
        raise FormatError(f"has an entity ezdxf cannot interpret: {type(error).__name__}: "
                          f"{str(error)[:200]}", path=path) from None
    tilted = counts.pop("tilted", 0)
    if tilted:
        notices.append(f"dxf: ignored {tilted} entities not drawn in the XY plane")
    other = {k[6:]: counts.pop(k) for k in sorted(counts) if k.startswith("other ")}
    if other:
        kinds = ", ".join(f"{n} {k}" for k, n in other.items())
        notices.append(f"dxf: ignored {kinds} (kinds that draw no outline plumbob reads)")
    closed, open_pieces = _split_closed(pieces)
    loops, leftovers = _join(open_pieces)
    closed += loops
    if not closed:
        kinds = ", ".join(f"{n} {k}" for k, n in sorted(counts.items())) or "no drawable entities"
        where = (f"; an open end at {fmt_point(leftovers[0].points[-1])}" if leftovers else "")
        where += f"; {tilted} not drawn in the XY plane" if tilted else ""
        raise FormatError(
            f"has no closed outline ({kinds}){where}: draw closed LWPOLYLINEs, CIRCLEs or "
            "LINE/ARC chains that meet end to end", path=path)
    if leftovers:
        notices.append(f"dxf: ignored {len(leftovers)} open piece(s) that do not close "
                       f"(e.g. {leftovers[0].label} ending at "
                       f"{fmt_point(leftovers[0].points[-1])})")
    outlines = [p.outline(scale) for p in closed]
    body, more = body_from_outlines(outlines, path=path, name=stem(path), scale=scale)
    return Reading(body, tuple(notices) + more, path, reading_unit(units, file_units),
                   units_assumed=unit_assumed(units, file_units, file_scale))


def _open(path: str):
    """The drawing, read by ezdxf's recovering reader from a bounded read of the file. A
    number ezdxf had to guess (``$INSUNITS 1e999`` read as 1, an inch) is an error naming its
    line: the recovered value would be a silent wrong unit or coordinate."""
    import io
    import logging

    import ezdxf
    from ezdxf import recover
    from ezdxf.audit import AuditError

    logging.getLogger("ezdxf").addHandler(logging.NullHandler())  # a library never prints
    data = read_bytes(path)
    try:
        doc, auditor = recover.read(io.BytesIO(data))
    except (ezdxf.DXFError, OSError, UnicodeError, ValueError) as error:
        raise FormatError(f"is not a readable DXF file: {str(error)[:200] or type(error).__name__}",
                          path=path) from None
    except Exception as error:  # noqa: BLE001 - the recovering parser may raise anything
        raise FormatError(f"is not a readable DXF file: {type(error).__name__}: "
                          f"{str(error)[:200]}", path=path) from None
    for fix in auditor.fixes:  # per repair: an outline ezdxf dropped is no silent loss
        message = str(fix.message)
        if message.startswith(("Removed", "Deleted")) and "unused" not in message \
                and _DRAWN.search(message):
            raise FormatError(f"has an entity ezdxf had to remove ({message[:200]}); fix the "
                              "file", path=path)
    guessed = (AuditError.INVALID_INTEGER_VALUE, AuditError.INVALID_FLOATING_POINT_VALUE)
    for problem in auditor.errors:  # per repair ezdxf made: few
        if problem.code in guessed:
            found = re.search(r'value "(.*?)" near line (\d+) as "(.*?)"', str(problem.message))
            what = "a whole number" if problem.code == guessed[0] else "a number"
            text = (f"line {found.group(2)}: {found.group(1)[:40]!r} is not {what} (ezdxf would "
                    f"guess {found.group(3)[:20]})") if found else str(problem.message)[:200]
            raise FormatError(f"{text}; fix the file", path=path)
    return doc


def _file_units(code, path: str) -> tuple[str | None, float | None]:
    """The unit ``$INSUNITS`` declares (name, metres per unit); (None, None) when unitless."""
    # a whole number first (a float 1e999 is infinite, a nan is no number: int() of either
    # would raise), then one of the codes
    whole = (isinstance(code, int) and not isinstance(code, bool)) or (
        isinstance(code, float) and code.is_integer())
    if not whole or not (code == 0 or int(code) in INSUNITS):
        raise FormatError(f"has $INSUNITS = {code!r}, which is no unit code (0 to 24): fix the "
                          "header or pass --units", path=path)
    return INSUNITS.get(int(code), (None, None))


def _mcount(entity) -> int:
    """How many copies an INSERT places: rows × columns of a MINSERT array, else 1."""
    rows = int(entity.dxf.get("row_count", 1) or 1)
    columns = int(entity.dxf.get("column_count", 1) or 1)
    return max(rows, 1) * max(columns, 1)


def _check_expansion(doc, path: str) -> None:
    """Count what the modelspace's block references expand to — copies placed and entities
    drawn, through every level of nesting — against :data:`~plumbob.limits.MAX_PARTS` and
    :data:`~plumbob.limits.MAX_OUTLINES` before anything is expanded (ten blocks each
    placing the next ten times is 10¹⁰ entities from a 5 KB file); each block is counted once."""
    memo: dict[str, tuple[int, int, int]] = {}  # per block: copies, entities, depth

    def load(name: str, stack: list[str]) -> tuple[int, int, int]:
        if name in stack:
            raise FormatError(f"block {name!r} contains a reference to itself", path=path)
        check_count("block nesting depth", len(stack) + 1, MAX_NESTING, path=path)
        if name not in memo:
            copies = entities = depth = 0
            block = doc.blocks.get(name)
            for entity in block if block is not None else ():  # per entity of the block
                c, e, d = entity_load(entity, stack + [name])
                copies, entities, depth = copies + c, entities + e, max(depth, d)
            memo[name] = (min(copies, _HUGE), min(entities, _HUGE), depth + 1)
        check_count("block nesting depth", len(stack) + memo[name][2], MAX_NESTING, path=path)
        return memo[name]

    def entity_load(entity, stack: list[str]) -> tuple[int, int, int]:
        kind = entity.dxftype()
        if kind == "INSERT":
            copies, entities, depth = load(entity.dxf.name, stack)
            k = _mcount(entity)
            return min(k * (1 + copies), _HUGE), min(k * entities, _HUGE), depth
        return 0, int(kind in _MAKERS), 0

    copies = entities = 0
    for entity in doc.modelspace():  # per entity
        c, e, _ = entity_load(entity, [])
        copies, entities = min(copies + c, _HUGE), min(entities + e, _HUGE)
    hint = "the drawing's blocks expand to too much; explode or simplify them"
    check_count("block copies", copies, MAX_PARTS, path=path, hint=hint)
    check_count("entities placed by blocks", entities, MAX_OUTLINES, path=path, hint=hint)


# ------------------------------------------------------------------ entities
def _collect(entity, pieces: list[_Piece], counts: dict[str, int], depth: int, limit: float,
             path: str, block: str | None = None) -> None:
    """Add the outline pieces of ``entity`` (expanding blocks); ``limit``: the largest
    plausible coordinate in file units; ``block``: the block it was placed from, if any."""
    kind = entity.dxftype()
    if kind == "INSERT":  # counted by _check_expansion: bounded
        copies = entity.multi_insert() if _mcount(entity) > 1 else (entity,)
        for copy in copies:  # per copy of a MINSERT array
            for sub in copy.virtual_entities():
                _collect(sub, pieces, counts, depth + 1, limit, path, entity.dxf.name)
        return
    maker = _MAKERS.get(kind)
    if maker is None:
        counts[f"other {kind}"] = counts.get(f"other {kind}", 0) + 1
        return
    counts[kind] = counts.get(kind, 0) + 1
    extrusion = np.asarray(entity.dxf.get("extrusion", (0.0, 0.0, 1.0)), dtype=float)
    tilted = abs(abs(extrusion[2]) - np.linalg.norm(extrusion)) > 1e-12 * np.linalg.norm(extrusion)
    if kind in ("LINE", "SPLINE", "ELLIPSE"):  # drawn in world coordinates
        extrusion = np.array([0.0, 0.0, 1.0])
    if tilted and kind != "LINE":
        counts["tilted"] = counts.get("tilted", 0) + 1
        return
    handle = entity.dxf.get("handle", None)
    layer = entity.dxf.get("layer", "0")
    name = f"{kind} #{handle}" if handle else f"{kind} of block {block!r}"
    label = f"{name} (layer {layer!r})"
    with np.errstate(all="ignore"):
        piece = maker(entity, label, name)
    if piece is None:
        return
    if piece is _TILTED:  # a 3D polyline, line or spline whose z varies: not a plane outline
        counts["tilted"] = counts.get("tilted", 0) + 1
        return
    if not (np.isfinite(piece.points).all() and np.abs(piece.points).max() <= limit
            and np.isfinite(piece.bulges).all()
            and np.all(np.isnan(piece.controls) | (np.abs(piece.controls) <= limit))):
        raise GeometryError(f"{label} has a coordinate that is not a finite number of plausible "
                            "size", path=path)
    check_bulges(piece.bulges, label)  # (read_checked names the file)
    reach = _arc_reach(piece)
    if not reach <= limit:
        raise GeometryError(f"{label} has a bulge of {np.abs(piece.bulges).max():.3g}: its arc "
                            f"reaches {reach:.3g} drawing units from the origin, no plausible "
                            "drawing", path=path)
    if extrusion[2] < 0:  # OCS mirrored: x ↦ −x, arcs turn the other way
        piece.points = piece.points * np.array([-1.0, 1.0])
        piece.controls = piece.controls * np.array([-1.0, 1.0])
        piece.bulges = -piece.bulges
    pieces.append(piece)


def _arc_reach(piece: _Piece) -> float:
    """How far from the origin the piece's arcs reach: a bulge b on a chord c bows out by
    c·|b|/2 (its sagitta), so a huge bulge is a huge circle — checked before any arc
    geometry is computed from it."""
    if not piece.bulges.any():
        return 0.0
    chords = np.linalg.norm(np.diff(piece.points, axis=0), axis=1)
    with np.errstate(over="ignore", invalid="ignore"):
        bow = chords * np.maximum(np.abs(piece.bulges), 1.0)
        return float(np.abs(piece.points).max() + bow.max())


def _z_varies(points) -> bool:
    """Whether points given in world coordinates leave a plane z = constant (beyond
    :data:`JOIN_TOLERANCE` of their extent): such an entity is no plane outline, and
    projecting it onto XY would change its shape in silence."""
    xyz = np.array([[float(c) for c in p][:3] for p in points], dtype=float).reshape(-1, 3)
    if len(xyz) < 2 or xyz.shape[1] < 3:
        return False
    extent = np.ptp(xyz, axis=0)
    return bool(extent[2] > JOIN_TOLERANCE * (float(np.linalg.norm(extent)) or 1.0))


def _xy(points) -> np.ndarray:
    return np.array([[float(p[0]), float(p[1])] for p in points]).reshape(-1, 2)


def _polyline(points: np.ndarray, bulges: np.ndarray, closed: bool, label: str,
              name: str) -> _Piece | None:
    if len(points) < 2:
        return None
    if closed and not np.array_equal(points[0], points[-1]):
        points = np.vstack((points, points[:1]))
    else:
        bulges = bulges[:-1]
    n = len(points) - 1
    return _Piece(points, bulges[:n].astype(float), np.broadcast_to(_NAN, (n, 2, 2)).copy(),
                  label, name)


def _lwpolyline(entity, label, name):
    data = np.array([(x, y, b) for x, y, b in entity.get_points("xyb")], dtype=float).reshape(-1, 3)
    return _polyline(data[:, :2], data[:, 2], bool(entity.closed), label, name)


def _polyline2d(entity, label, name):
    if not (entity.is_2d_polyline or entity.is_3d_polyline):
        return None  # polyface and polygon meshes have no outline
    vertices = list(entity.vertices)
    if _z_varies([v.dxf.location for v in vertices]):
        return _TILTED
    points = _xy([v.dxf.location for v in vertices])
    bulges = np.array([float(v.dxf.get("bulge", 0.0)) for v in vertices])
    if entity.is_3d_polyline:
        bulges[:] = 0.0
    return _polyline(points, bulges, bool(entity.is_closed), label, name)


def _circle(entity, label, name):
    centre = _xy([entity.dxf.center])[0]
    radius = float(entity.dxf.radius)
    if not radius > 0:
        return None
    starts, bulges = arc_bulges(centre, radius, 0.0, 2 * np.pi)
    points = np.vstack((starts, starts[:1]))
    return _Piece(points, bulges, np.broadcast_to(_NAN, (2, 2, 2)).copy(), label, name)


def _arc(entity, label, name):
    centre = _xy([entity.dxf.center])[0]
    radius = float(entity.dxf.radius)
    start = np.radians(float(entity.dxf.start_angle) % 360)
    sweep = np.radians((float(entity.dxf.end_angle) - float(entity.dxf.start_angle)) % 360)
    if sweep == 0:
        sweep = 2 * np.pi
    if not radius > 0:
        return None
    starts, bulges = arc_bulges(centre, radius, start, sweep)
    end, _ = arc_bulges(centre, radius, start + sweep, 0.0)
    return _Piece(np.vstack((starts, end)), bulges,
                  np.broadcast_to(_NAN, (len(bulges), 2, 2)).copy(), label, name)


def _line(entity, label, name):
    if _z_varies([entity.dxf.start, entity.dxf.end]):
        return _TILTED
    points = _xy([entity.dxf.start, entity.dxf.end])
    if np.array_equal(points[0], points[1]):
        return None
    return _Piece(points, np.zeros(1), _NAN[None].copy(), label, name)


def _ellipse(entity, label, name):
    centre = _xy([entity.dxf.center])[0]
    u = _xy([entity.dxf.major_axis])[0]
    v = _xy([entity.minor_axis])[0]
    t0 = float(entity.dxf.start_param)
    sweep = (float(entity.dxf.end_param) - t0) % (2 * np.pi)
    if sweep < 1e-12:
        sweep = 2 * np.pi
    ru, rv = np.linalg.norm(u), np.linalg.norm(v)
    if abs(ru - rv) <= 1e-12 * ru:  # a circle
        turn = np.sign(u[0] * v[1] - u[1] * v[0])  # −1 when the ellipse runs clockwise
        start = np.arctan2(u[1], u[0]) + t0 * turn
        starts, bulges = arc_bulges(centre, ru, start, sweep * turn)
        end, _ = arc_bulges(centre, ru, start + sweep * turn, 0.0)
        return _Piece(np.vstack((starts, end)), bulges,
                      np.broadcast_to(_NAN, (len(bulges), 2, 2)).copy(), label, name)
    points, controls, error = elliptic_arc_cubics(centre, u, v, t0, sweep)
    return _Piece(points, np.zeros(len(controls)), controls, label, name, error,
                  "elliptical arcs as cubic Béziers (error below 1e-10 of their size)")


def _spline(entity, label, name):
    """A SPLINE on its own domain: non-rational ones of degree ≤ 3 as exact Bézier pieces,
    others flattened within :data:`FLATTEN_TOLERANCE` of their size (a stated error).
    Unclamped (periodic, closed) splines are first clamped exactly by knot insertion."""
    from ezdxf.math import BSpline, open_uniform_knot_vector

    if _z_varies(entity.control_points) or _z_varies(entity.fit_points):
        return _TILTED
    control = _xy(entity.control_points)
    if len(control):
        degree = int(entity.dxf.degree)
        knots = np.asarray(entity.knots, dtype=float)
        weights = np.asarray(entity.weights, dtype=float) if len(entity.weights) else None
    else:  # fit points only: ezdxf's interpolation, a clamped cubic
        tool = entity.construction_tool()
        control, degree = _xy(tool.control_points), int(tool.degree)
        knots, weights = np.asarray(tool.knots(), dtype=float), None
    check_count("spline control points", len(control), MAX_SIDES)
    if len(control) <= degree:
        return None
    if knots.size == 0:
        knots = np.asarray(open_uniform_knot_vector(len(control), degree + 1), dtype=float)
    if weights is not None and not (np.isfinite(weights).all() and (weights > 0).all()):
        raise ValueError("a spline's weights must be positive numbers")
    if weights is not None and np.ptp(weights) == 0:
        weights = None  # equal weights: not rational
    w = np.ones(len(control)) if weights is None else weights
    homogeneous, knots = clamped_bspline(np.column_stack((control * w[:, None], w)), knots,
                                         degree)
    control, w = homogeneous[:, :2] / homogeneous[:, 2:], homogeneous[:, 2]
    tool = BSpline(np.column_stack((control, np.zeros(len(control)))), order=degree + 1,
                   knots=list(knots), weights=None if weights is None else list(w))
    if weights is None and degree <= 3:
        beziers = [np.asarray([(p[0], p[1]) for p in b], dtype=float)
                   for b in tool.bezier_decomposition()]
        return _bezier_piece(beziers, degree, label, name)
    # rational or of high degree: flatten within a stated distance
    spans = len(np.unique(knots)) - 1
    check_count("segments of a flattened spline", spans * _SEGMENTS_PER_SPAN, MAX_SIDES)
    size = size_of(control) or 1.0
    distance = FLATTEN_TOLERANCE * size
    points = _xy(tool.flattening(distance))
    if len(points) < 2:
        return None
    length = float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    n = len(points) - 1
    return _Piece(points, np.zeros(n), np.broadcast_to(_NAN, (n, 2, 2)).copy(), label, name,
                  distance * length, "splines flattened (error below 1e-7 of their size)")


def _bezier_piece(beziers: list[np.ndarray], degree: int, label: str, name: str) -> _Piece:
    starts, ends, controls = [], [], []
    for b in beziers:  # per Bézier span
        if degree == 3:
            c = b[1:3]
        elif degree == 2:  # raise exactly to a cubic
            c = np.array([b[0] + 2 / 3 * (b[1] - b[0]), b[2] + 2 / 3 * (b[1] - b[2])])
        else:
            c = _NAN
        starts.append(b[0])
        ends.append(b[-1])
        controls.append(c)
    points = np.vstack((np.array(starts), ends[-1][None]))
    return _Piece(points, np.zeros(len(starts)), np.array(controls), label, name)


_MAKERS = {
    "LWPOLYLINE": _lwpolyline,
    "POLYLINE": _polyline2d,
    "CIRCLE": _circle,
    "ARC": _arc,
    "LINE": _line,
    "ELLIPSE": _ellipse,
    "SPLINE": _spline,
}


# ------------------------------------------------------------------ joining
def _join_tolerance(pieces: list[_Piece]) -> float:
    """:data:`JOIN_TOLERANCE` of the drawing's size — of all its points, not only the pieces'
    ends (a full ellipse alone has both ends at one point, and a size of nothing)."""
    points = np.concatenate([p.points for p in pieces])
    return JOIN_TOLERANCE * (size_of(points) or 1.0)


def _split_closed(pieces: list[_Piece]) -> tuple[list[_Piece], list[_Piece]]:
    if not pieces:
        return [], []
    tol = _join_tolerance(pieces)
    closed, open_ = [], []
    for p in pieces:  # per entity
        gap = np.linalg.norm(p.points[-1] - p.points[0])
        if gap <= tol and len(p.bulges) >= 1 and not (len(p.bulges) == 1 and p.bulges[0] == 0
                                                      and np.isnan(p.controls[0]).all()):
            p.points = np.vstack((p.points[:-1], p.points[:1]))
            closed.append(p)
        else:
            open_.append(p)
    return closed, open_


def _join(pieces: list[_Piece]) -> tuple[list[_Piece], list[_Piece]]:
    """Chain open pieces whose ends meet into closed pieces; return (loops, leftovers)."""
    if not pieces:
        return [], []
    ends = np.concatenate([p.points[[0, -1]] for p in pieces])  # (2k, 2): start, end
    tol = _join_tolerance(pieces)
    order = np.lexsort((ends[:, 1], ends[:, 0]))
    # Ends that meet: near in x after sorting, then checked in full (few candidates).
    i, j = [], []
    for shift in range(1, 9):
        a, b = order[:-shift], order[shift:]
        near = np.linalg.norm(ends[a] - ends[b], axis=1) <= tol
        i.append(a[near])
        j.append(b[near])
    node = connected_components(len(ends), np.concatenate(i), np.concatenate(j))
    degree = np.bincount(node)
    used = np.zeros(len(pieces), dtype=bool)
    loops, leftovers = [], []
    at: dict[int, list[int]] = {}
    for e, n in enumerate(node):  # per piece end
        at.setdefault(int(n), []).append(e)
    for first in range(len(pieces)):  # walk each chain once
        if used[first]:
            continue
        chain = [pieces[first]]
        used[first] = True
        start_node, current = node[2 * first], node[2 * first + 1]
        ok = degree[start_node] == 2
        while current != start_node:
            if degree[current] != 2:
                ok = False
                break
            nxt = [e for e in at[int(current)] if not used[e // 2]]
            if not nxt:
                ok = False
                break
            e = nxt[0]
            used[e // 2] = True
            piece = pieces[e // 2]
            chain.append(piece if e % 2 == 0 else piece.reversed())
            current = node[e + 1] if e % 2 == 0 else node[e - 1]
        if ok and current == start_node:
            loops.append(_concat(chain))
        else:
            leftovers.extend(chain)
    return loops, leftovers


def _concat(chain: list[_Piece]) -> _Piece:
    points = np.vstack([p.points[:-1] for p in chain] + [chain[0].points[:1]])
    labels = ", ".join(p.label for p in chain[:3]) + (", …" if len(chain) > 3 else "")
    approx = next((p.approximation for p in chain if p.approximation), None)
    return _Piece(points, np.concatenate([p.bulges for p in chain]),
                  np.concatenate([p.controls for p in chain]), f"chain of {labels}",
                  chain[0].name, sum(p.error for p in chain), approx)
