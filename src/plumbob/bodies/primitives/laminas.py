"""Plane primitives: exact regions and laminas of lines and circular arcs.

Rectangle, triangle, polygon, regular polygon, disc, semicircle, sector,
segment and annulus, each an exact :class:`Lamina` (and its :class:`Region`,
for solids built on a profile). Round laminas are centred at the origin; a
rectangle has its corner there.
"""

from __future__ import annotations

import numpy as np

from ...arguments import count, floats, positive
from ...errors import GeometryError
from ...limits import MAX_SIDES
from ...units import MAX_LENGTH, too_long
from ..lamina import Lamina
from ..region import Region, Ring
from ..validity import check_polygon


def positive_number(value: float, what: str) -> float:
    """``value`` as a float, checked to be a positive finite number (a primitive's size).

    >>> positive_number("2.5", "radius")
    2.5
    >>> positive_number(float("inf"), "radius")
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: radius must be a positive number, not inf
    >>> positive_number(1e200, "radius")
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: radius 1e+200 m is beyond plumbob's largest length, 1e+50 m: \
its mass properties would overflow double precision (give lengths in other units)
    """
    size = positive(value, what, error=GeometryError)
    if size > MAX_LENGTH:
        raise GeometryError(too_long(what, size))
    return size


def counter_clockwise(vertices: np.ndarray) -> np.ndarray:
    """The polygon's vertices (n, 2), reversed if they ran clockwise.

    >>> counter_clockwise([[0, 0], [0, 1], [1, 0]]).tolist()
    [[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]
    """
    v = floats(vertices, "a polygon's vertices", error=GeometryError)
    if v.ndim != 2 or v.shape[1:] != (2,) or len(v) < 3:
        raise GeometryError(f"a polygon needs an (n, 2) array of at least 3 vertices, not an "
                            f"array of shape {v.shape}")
    x, y = v[:, 0] - v[0, 0], v[:, 1] - v[0, 1]
    signed = np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)
    if signed == 0:
        raise GeometryError("the polygon has no area (its vertices are collinear or repeated)")
    return v if signed > 0 else v[::-1]


# ------------------------------------------------------------------ regions
def rectangle_region(width: float, height: float) -> Region:
    """The rectangle [0, width] × [0, height], m, as an exact region.

    >>> rectangle_region(2, 1).bounds.tolist()
    [[0.0, 0.0], [2.0, 1.0]]
    """
    w, h = positive_number(width, "width"), positive_number(height, "height")
    return Region((Ring(np.array([[0, 0], [w, 0], [w, h], [0, h]], dtype=float)),))


def polygon_region(vertices, holes=()) -> Region:
    """A polygon (n, 2) with optional polygonal holes, m; orientation is normalised
    (the outline counter-clockwise, holes clockwise).

    >>> polygon_region([[0, 0], [0, 1], [1, 0]]).moments().m0   # given clockwise: still +½
    0.5
    """
    check_polygon(vertices, holes)  # a bow-tie or a hole outside would integrate to a wrong area
    rings = [Ring(counter_clockwise(vertices))]
    rings += [Ring(counter_clockwise(hole)[::-1]) for hole in holes]
    return Region(tuple(rings))


def disc_region(radius: float, centre=(0.0, 0.0)) -> Region:
    """A disc of ``radius`` (m) about ``centre``: two semicircular arcs.

    >>> disc_region(1, centre=(2, 0)).bounds.tolist()
    [[1.0, -1.0], [3.0, 1.0]]
    """
    r = positive_number(radius, "radius")
    c = np.asarray(centre, dtype=float)
    return Region((Ring(np.array([[r, 0.0], [-r, 0.0]]) + c, bulges=np.array([1.0, 1.0])),))


def semicircle_region(radius: float) -> Region:
    """The half disc y ≥ 0 of ``radius`` (m) about the origin.

    >>> semicircle_region(1).bounds.tolist()
    [[-1.0, 0.0], [1.0, 1.0]]
    """
    r = positive_number(radius, "radius")
    return Region((Ring(np.array([[-r, 0.0], [r, 0.0]]), bulges=np.array([0.0, 1.0])),))


def sector_region(radius: float, angle: float) -> Region:
    """Apex at the origin, symmetric about +x, opening ``angle`` radians (≤ 2π)."""
    r = positive_number(radius, "radius")
    a = positive_number(angle, "angle")
    if a > 2 * np.pi:
        raise GeometryError("a sector's angle must be at most 2π")
    if a == 2 * np.pi:
        return disc_region(r)
    ends = r * np.array([[np.cos(a / 2), -np.sin(a / 2)], [np.cos(a / 2), np.sin(a / 2)]])
    return Region(
        (Ring(np.vstack(([0.0, 0.0], ends)), bulges=np.array([0.0, np.tan(a / 4), 0.0])),)
    )


def segment_region(radius: float, angle: float) -> Region:
    """The circular segment cut off by a chord subtending ``angle`` at the centre
    (the origin), symmetric about +x."""
    r = positive_number(radius, "radius")
    a = positive_number(angle, "angle")
    if a >= 2 * np.pi:
        raise GeometryError("a segment's angle must be less than 2π")
    ends = r * np.array([[np.cos(a / 2), -np.sin(a / 2)], [np.cos(a / 2), np.sin(a / 2)]])
    return Region((Ring(ends, bulges=np.array([np.tan(a / 4), 0.0])),))


# ------------------------------------------------------------------ laminas
# Every lamina primitive passes ``**kw`` to :class:`Lamina`: ``density`` (kg/m², or
# kg/m³ with ``thickness`` in m), ``thickness`` and ``name``.

def rectangle(width: float, height: float, **kw) -> Lamina:
    """A rectangular lamina, corner at the origin, sides along +x and +y.

    Parameters
    ----------
    width, height : float
        m, positive.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Raises
    ------
    GeometryError
        A side that is not a positive number.

    Examples
    --------
    >>> plate = rectangle(2, 1, density=3.0)
    >>> props = plate.mass_properties()
    >>> props.mass, props.center_of_mass.tolist()
    (6.0, [1.0, 0.5])
    >>> rectangle(0, 1)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: width must be a positive number, not 0
    """
    return Lamina(rectangle_region(width, height), **kw)


def polygon(vertices, holes=(), **kw) -> Lamina:
    """A lamina bounded by any simple polygon, with optional polygonal holes.

    Parameters
    ----------
    vertices : array_like, shape (n, 2)
        m, in either orientation (it is normalised); the first vertex need not
        be repeated.
    holes : sequence of array_like, shape (k, 2)
        Polygons removed from the inside.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Raises
    ------
    GeometryError
        Vertices that enclose no area (collinear or repeated), an outline that crosses
        or touches itself, a hole outside the outline, crossing or inside another.

    Examples
    --------
    >>> frame = polygon([[0, 0], [4, 0], [4, 4], [0, 4]], holes=[[[1, 1], [3, 1], [3, 3], [1, 3]]])
    >>> frame.mass_properties().measure
    12.0
    >>> polygon([[0, 0], [1, 1], [2, 2]])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the polygon has zero area: its points lie on a line and enclose no area
    >>> polygon([[0, 0], [2, 0], [0, 1], [2, 1]])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the polygon crosses itself at (1, 0.5) m (a bow-tie or a twisted outline)
    """
    return Lamina(polygon_region(vertices, holes), **kw)


def triangle(p0, p1, p2, **kw) -> Lamina:
    """A triangular lamina with corners ``p0``, ``p1``, ``p2`` (each (2,), m), in any order.

    Parameters
    ----------
    p0, p1, p2 : array_like, shape (2,)
        m.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Examples
    --------
    >>> t = triangle((0, 0), (3, 0), (0, 3)).mass_properties()
    >>> t.measure, t.center_of_mass.tolist()     # the centroid: the corners' mean
    (4.5, [1.0, 1.0])
    >>> triangle((0, 0), (1, 0), (2, 0))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the polygon has zero area: its points lie on a line and enclose no area
    """
    return polygon(floats([p0, p1, p2], "a triangle's corners", error=GeometryError), **kw)


def regular_polygon(sides: int, circumradius: float, **kw) -> Lamina:
    """A regular polygon centred at the origin with a vertex on +x.

    Parameters
    ----------
    sides : int
        At least 3.
    circumradius : float
        m: the distance from the centre to each vertex.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Examples
    --------
    >>> round(regular_polygon(4, 1).mass_properties().measure, 15)   # a square of diagonal 2
    2.0
    >>> regular_polygon(2, 1)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: sides must be a whole number of at least 3, not 2
    >>> regular_polygon(1e8, 1)
    Traceback (most recent call last):
    ...
    plumbob.errors.LimitError: sides 100000000 is over plumbob's limit of 1000000; use a disc \
for a circle (plumbob.limits.MAX_SIDES)
    """
    sides = count(sides, "sides", MAX_SIDES, minimum=3, error=GeometryError,
                  hint="use a disc for a circle (plumbob.limits.MAX_SIDES)")
    r = positive_number(circumradius, "circumradius")
    t = 2 * np.pi * np.arange(sides) / sides
    return polygon(r * np.stack((np.cos(t), np.sin(t)), axis=1), **kw)


def disc(radius: float, **kw) -> Lamina:
    """A circular lamina centred at the origin, exact (two circular arcs).

    Parameters
    ----------
    radius : float
        m, positive.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Examples
    --------
    >>> props = disc(1).mass_properties()
    >>> float(props.measure) == np.pi, props.exact
    (True, True)
    >>> disc(-1)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: radius must be a positive number, not -1
    """
    return Lamina(disc_region(radius), **kw)


def semicircle(radius: float, **kw) -> Lamina:
    """A half disc: straight edge on the x-axis, circle centre at the origin, y ≥ 0 (the
    seed's Figure 27).

    Parameters
    ----------
    radius : float
        m, positive.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Examples
    --------
    Its centre of mass lies 4r/3π above the diameter:

    >>> y = semicircle(3).mass_properties().center_of_mass[1]
    >>> bool(np.isclose(y, 4 * 3 / (3 * np.pi), rtol=1e-15))
    True
    """
    return Lamina(semicircle_region(radius), **kw)


def sector(radius: float, angle: float, **kw) -> Lamina:
    """A circular sector: apex at the origin, symmetric about +x, opening ``angle``.

    Parameters
    ----------
    radius : float
        m, positive.
    angle : float
        The opening, radians, in (0, 2π]; 2π is the whole disc.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Examples
    --------
    Its centre of mass lies 2r sin(α)/3α from the apex (α the half angle):

    >>> x = sector(1, np.pi / 2).mass_properties().center_of_mass[0]
    >>> bool(np.isclose(x, 2 * np.sin(np.pi / 4) / (3 * np.pi / 4), rtol=1e-15))
    True
    >>> sector(1, 7)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a sector's angle must be at most 2π
    """
    return Lamina(sector_region(radius, angle), **kw)


def circular_segment(radius: float, angle: float, **kw) -> Lamina:
    """The circular segment cut off a disc (centre the origin) by a chord subtending
    ``angle`` at the centre, symmetric about +x.

    Parameters
    ----------
    radius : float
        m, positive.
    angle : float
        Radians, in (0, 2π): π gives a half disc on the +x side.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Examples
    --------
    >>> bool(np.isclose(circular_segment(1, np.pi).mass_properties().measure, np.pi / 2))
    True
    >>> circular_segment(1, 2 * np.pi)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a segment's angle must be less than 2π
    """
    return Lamina(segment_region(radius, angle), **kw)


def annulus(inner_radius: float, outer_radius: float, **kw) -> Lamina:
    """A ring between two circles centred at the origin.

    Parameters
    ----------
    inner_radius, outer_radius : float
        m, positive, inner < outer.
    **kw
        ``density``, ``thickness``, ``name`` (see :class:`Lamina`).

    Returns
    -------
    Lamina

    Examples
    --------
    >>> bool(np.isclose(annulus(1, 2).mass_properties().measure, 3 * np.pi, rtol=1e-15))
    True
    >>> annulus(2, 1)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: an annulus needs an outer radius larger than its inner radius
    """
    if not positive_number(outer_radius, "outer radius") > positive_number(inner_radius, "inner radius"):
        raise GeometryError("an annulus needs an outer radius larger than its inner radius")
    hole = disc_region(inner_radius).rings[0].reversed()
    return Lamina(Region(disc_region(outer_radius).rings + (hole,)), **kw)
