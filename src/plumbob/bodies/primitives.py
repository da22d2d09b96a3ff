"""Primitives with closed forms, each built on an exact generator.

2D (laminas, exact regions of lines and arcs): rectangle, triangle, polygon,
regular polygon, disc, semicircle, sector, segment, annulus.
3D: box and pyramid (exact meshes), cylinder, cone, frustum, sphere,
hemisphere and torus (exact solids of revolution), prism (extrusion) of any
lamina, revolution of any lamina.

Frames: every primitive sits in a stated local frame; place it with
``body.transformed(matrix, offset)``. Axial solids have their axis along +z
with the base at z = 0; round laminas are centred at the origin.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError
from .lamina import Lamina
from .region import Region, Ring
from .solid import Extrusion, MeshSolid, Revolution

__all__ = [
    "rectangle",
    "triangle",
    "polygon",
    "regular_polygon",
    "disc",
    "semicircle",
    "sector",
    "circular_segment",
    "annulus",
    "box",
    "pyramid",
    "tetrahedron",
    "cylinder",
    "cone",
    "frustum",
    "sphere",
    "hemisphere",
    "torus",
    "prism",
    "revolve",
]


def _positive(value: float, what: str) -> float:
    value = float(value)
    if not (np.isfinite(value) and value > 0):
        raise GeometryError(f"{what} must be a positive number, not {value:g}")
    return value


def _ccw(vertices: np.ndarray) -> np.ndarray:
    v = np.asarray(vertices, dtype=float)
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
    w, h = _positive(width, "width"), _positive(height, "height")
    return Region((Ring(np.array([[0, 0], [w, 0], [w, h], [0, h]], dtype=float)),))


def polygon_region(vertices, holes=()) -> Region:
    """A polygon (n, 2) with optional polygonal holes, m; orientation is normalised
    (the outline counter-clockwise, holes clockwise).

    >>> polygon_region([[0, 0], [0, 1], [1, 0]]).moments().m0   # given clockwise: still +½
    0.5
    """
    rings = [Ring(_ccw(vertices))]
    rings += [Ring(_ccw(hole)[::-1]) for hole in holes]
    return Region(tuple(rings))


def disc_region(radius: float, centre=(0.0, 0.0)) -> Region:
    """A disc of ``radius`` (m) about ``centre``: two semicircular arcs.

    >>> disc_region(1, centre=(2, 0)).bounds.tolist()
    [[1.0, -1.0], [3.0, 1.0]]
    """
    r = _positive(radius, "radius")
    c = np.asarray(centre, dtype=float)
    return Region((Ring(np.array([[r, 0.0], [-r, 0.0]]) + c, bulges=np.array([1.0, 1.0])),))


def semicircle_region(radius: float) -> Region:
    """The half disc y ≥ 0 of ``radius`` (m) about the origin.

    >>> semicircle_region(1).bounds.tolist()
    [[-1.0, 0.0], [1.0, 1.0]]
    """
    r = _positive(radius, "radius")
    return Region((Ring(np.array([[-r, 0.0], [r, 0.0]]), bulges=np.array([0.0, 1.0])),))


def sector_region(radius: float, angle: float) -> Region:
    """Apex at the origin, symmetric about +x, opening ``angle`` radians (≤ 2π)."""
    r = _positive(radius, "radius")
    a = _positive(angle, "angle")
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
    r = _positive(radius, "radius")
    a = _positive(angle, "angle")
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
        Vertices that enclose no area (collinear or repeated).

    Examples
    --------
    >>> frame = polygon([[0, 0], [4, 0], [4, 4], [0, 4]], holes=[[[1, 1], [3, 1], [3, 3], [1, 3]]])
    >>> frame.mass_properties().measure
    12.0
    >>> polygon([[0, 0], [1, 1], [2, 2]])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the polygon has no area (its vertices are collinear or repeated)
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
    plumbob.errors.GeometryError: the polygon has no area (its vertices are collinear or repeated)
    """
    return polygon(np.array([p0, p1, p2], dtype=float), **kw)


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
    plumbob.errors.GeometryError: a regular polygon needs a whole number of sides, at least 3
    """
    if int(sides) != sides or sides < 3:
        raise GeometryError("a regular polygon needs a whole number of sides, at least 3")
    r = _positive(circumradius, "circumradius")
    t = 2 * np.pi * np.arange(int(sides)) / sides
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
    if not _positive(outer_radius, "outer radius") > _positive(inner_radius, "inner radius"):
        raise GeometryError("an annulus needs an outer radius larger than its inner radius")
    hole = disc_region(inner_radius).rings[0].reversed()
    return Lamina(Region(disc_region(outer_radius).rings + (hole,)), **kw)


# ------------------------------------------------------------------ solids
# Every solid primitive passes ``**kw`` to its body: ``density`` (kg/m³) and ``name``.

def _mesh_from_faces(vertices: np.ndarray, faces: list[list[int]], **kw) -> MeshSolid:
    """Triangulate convex planar faces (fans) of a polyhedron."""
    tris = [[f[0], f[i], f[i + 1]] for f in faces for i in range(1, len(f) - 1)]
    return MeshSolid(np.asarray(vertices, dtype=float)[np.array(tris)], **kw)


def box(length: float, width: float, height: float, **kw) -> MeshSolid:
    """A rectangular box, corner at the origin, edges along +x, +y, +z (an exact mesh).

    Parameters
    ----------
    length, width, height : float
        m, positive: the extents along x, y, z.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    MeshSolid
        12 triangles.

    Examples
    --------
    >>> props = box(1, 2, 3, density=2.0).mass_properties()
    >>> props.mass, props.center_of_mass.tolist()
    (12.0, [0.5, 1.0, 1.5])
    >>> box(1, 1, float("nan"))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: height must be a positive number, not nan
    """
    a, b, c = _positive(length, "length"), _positive(width, "width"), _positive(height, "height")
    v = np.array(
        [[0, 0, 0], [a, 0, 0], [a, b, 0], [0, b, 0], [0, 0, c], [a, 0, c], [a, b, c], [0, b, c]],
        dtype=float,
    )
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    return _mesh_from_faces(v, faces, **kw)


def pyramid(base, height: float, apex=None, **kw) -> MeshSolid:
    """A pyramid on a polygonal base in the plane z = 0 (an exact mesh).

    Parameters
    ----------
    base : array_like, shape (n, 2)
        The base polygon, m, in either orientation; non-convex bases are fine.
    height : float
        m, positive: the apex's height above the base.
    apex : array_like, shape (2,), optional
        (x, y) of the apex, m; default the base's centroid.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    MeshSolid

    Examples
    --------
    A pyramid's centre of mass is a quarter of the way up, its volume a third of
    base × height:

    >>> props = pyramid([[0, 0], [2, 0], [2, 2], [0, 2]], 3).mass_properties()
    >>> round(props.measure, 14), props.center_of_mass.round(14).tolist()
    (4.0, [1.0, 1.0, 0.75])
    >>> pyramid([[0, 0], [1, 0], [1, 1]], 0)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: height must be a positive number, not 0
    """
    h = _positive(height, "height")
    base = _ccw(np.asarray(base, dtype=float))
    if apex is None:
        lam = polygon(base).mass_properties()
        apex = lam.center_of_mass
    n = len(base)
    verts = np.vstack((np.pad(base, ((0, 0), (0, 1))), [[apex[0], apex[1], h]]))
    sides = [[i, (i + 1) % n, n] for i in range(n)]
    # The base, wound clockwise seen from above (outward = down), fanned from
    # vertex 0: for a non-convex base the signed triangles still sum exactly.
    bottom = [[0, i + 1, i] for i in range(1, n - 1)]
    return MeshSolid(verts[np.array(sides + bottom)], **kw)


def tetrahedron(p0, p1, p2, p3, **kw) -> MeshSolid:
    """A tetrahedron with corners ``p0`` … ``p3`` (each (3,), m), in any order.

    Parameters
    ----------
    p0, p1, p2, p3 : array_like, shape (3,)
        m.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    MeshSolid
        4 triangles, wound outward whatever the corners' order.

    Examples
    --------
    >>> t = tetrahedron((0, 0, 0), (0, 1, 0), (1, 0, 0), (0, 0, 1)).mass_properties()
    >>> bool(np.isclose(t.measure, 1 / 6)), t.center_of_mass.tolist()
    (True, [0.25, 0.25, 0.25])
    >>> tetrahedron((0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the tetrahedron's four points are coplanar
    """
    v = np.array([p0, p1, p2, p3], dtype=float)
    if np.linalg.det(v[1:] - v[0]) < 0:
        v[[1, 2]] = v[[2, 1]]
    if np.linalg.det(v[1:] - v[0]) == 0:
        raise GeometryError("the tetrahedron's four points are coplanar")
    return _mesh_from_faces(v, [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], **kw)


def frustum(bottom_radius: float, top_radius: float, height: float, **kw) -> Revolution:
    """A truncated cone, axis +z, base at z = 0 (an exact solid of revolution).

    Parameters
    ----------
    bottom_radius, top_radius : float
        m, at z = 0 and z = ``height``; either may be 0 (a cone), not both.
    height : float
        m, positive.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Revolution

    Examples
    --------
    >>> v = frustum(2, 1, 3).mass_properties().measure   # πh(R² + Rr + r²)/3
    >>> bool(np.isclose(v, 7 * np.pi, rtol=1e-15))
    True
    >>> frustum(0, 0, 1)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a frustum needs non-negative radii, not both zero
    """
    h = _positive(height, "height")
    r0, r1 = float(bottom_radius), float(top_radius)
    if r0 < 0 or r1 < 0 or not (r0 > 0 or r1 > 0):
        raise GeometryError("a frustum needs non-negative radii, not both zero")
    pts = [[0, 0], [r0, 0], [r1, h], [0, h]]
    pts = [p for i, p in enumerate(pts) if not (i in (1, 2) and p[0] == 0)]
    return Revolution(Region((Ring(np.array(pts, dtype=float)),)), **kw)


def cylinder(radius: float, height: float, **kw) -> Revolution:
    """A circular cylinder, axis +z, base at z = 0 (an exact solid of revolution).

    Parameters
    ----------
    radius, height : float
        m, positive.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Revolution

    Examples
    --------
    >>> props = cylinder(1, 2).mass_properties()
    >>> bool(np.isclose(props.measure, 2 * np.pi, rtol=1e-15)), props.center_of_mass.tolist()
    (True, [0.0, 0.0, 1.0])
    >>> cylinder(1, -2)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: height must be a positive number, not -2
    """
    r = _positive(radius, "radius")
    return frustum(r, r, height, **kw)


def cone(radius: float, height: float, **kw) -> Revolution:
    """A circular cone, axis +z, base (``radius``) at z = 0, apex at z = ``height``.

    Parameters
    ----------
    radius, height : float
        m, positive.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Revolution

    Examples
    --------
    Its centre of mass is a quarter of the way up:

    >>> cone(1, 4).mass_properties().center_of_mass.tolist()
    [0.0, 0.0, 1.0]
    >>> cone(0, 1)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: radius must be a positive number, not 0
    """
    return frustum(_positive(radius, "radius"), 0.0, height, **kw)


def sphere(radius: float, **kw) -> Revolution:
    """A ball centred at the origin (an exact solid of revolution).

    Parameters
    ----------
    radius : float
        m, positive.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Revolution

    Examples
    --------
    >>> props = sphere(1, density=3.0).mass_properties()
    >>> bool(np.isclose(props.mass, 4 * np.pi, rtol=1e-15))   # 4/3 π r³ × 3
    True
    >>> bool(np.allclose(np.diag(props.inertia), 0.4 * props.mass, rtol=1e-15))   # 2/5 m r²
    True
    """
    r = _positive(radius, "radius")
    return Revolution(
        Region((Ring(np.array([[0.0, -r], [0.0, r]]), bulges=np.array([1.0, 0.0])),)), **kw
    )


def hemisphere(radius: float, **kw) -> Revolution:
    """Half a ball: flat face on z = 0, dome up, the sphere's centre at the origin.

    Parameters
    ----------
    radius : float
        m, positive.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Revolution

    Examples
    --------
    Its centre of mass is 3r/8 above the flat face:

    >>> round(float(hemisphere(8).mass_properties().center_of_mass[2]), 14)
    3.0
    """
    r = _positive(radius, "radius")
    quarter = Ring(
        np.array([[0.0, 0.0], [r, 0.0], [0.0, r]]), bulges=np.array([0.0, np.tan(np.pi / 8), 0.0])
    )
    return Revolution(Region((quarter,)), **kw)


def torus(major_radius: float, minor_radius: float, **kw) -> Revolution:
    """A ring torus centred at the origin, axis +z.

    Parameters
    ----------
    major_radius : float
        m: from the axis to the centre of the tube.
    minor_radius : float
        m: the tube's radius, at most ``major_radius``.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Revolution

    Examples
    --------
    >>> v = torus(2, 0.5).mass_properties().measure   # 2π² R r²
    >>> bool(np.isclose(v, 2 * np.pi**2 * 2 * 0.25, rtol=1e-15))
    True
    >>> torus(1, 2)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a torus needs its tube radius no larger than its major radius
    """
    big, small = _positive(major_radius, "major radius"), _positive(minor_radius, "minor radius")
    if small > big:
        raise GeometryError("a torus needs its tube radius no larger than its major radius")
    return Revolution(disc_region(small, centre=(big, 0.0)), **kw)


def prism(lamina: Lamina | Region, height: float, **kw) -> Extrusion:
    """A lamina (or region) swept from z = 0 to z = ``height``: exact for any profile.

    Parameters
    ----------
    lamina : Lamina or Region
        The cross-section in the xy-plane (its density is not used).
    height : float
        m, positive.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Extrusion

    Examples
    --------
    >>> props = prism(disc(1), 2).mass_properties()
    >>> bool(np.isclose(props.measure, 2 * np.pi, rtol=1e-15)), props.center_of_mass.tolist()
    (True, [0.0, 0.0, 1.0])
    >>> prism(disc(1), 0)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: height must be a positive number, not 0
    """
    region = lamina.region if isinstance(lamina, Lamina) else lamina
    return Extrusion(region, _positive(height, "height"), **kw)


def revolve(lamina: Lamina | Region, **kw) -> Revolution:
    """A lamina (or region) turned a full circle about its y-axis; the result's axis is +z.

    Parameters
    ----------
    lamina : Lamina or Region
        The profile in the half-plane x ≥ 0: x is the radius, y the height.
    **kw
        ``density`` (kg/m³), ``name``.

    Returns
    -------
    Revolution

    Raises
    ------
    GeometryError
        A profile reaching x < 0.

    Examples
    --------
    A rectangle beside the axis turns into a tube (Pappus: V = 2π x̄ A):

    >>> tube = revolve(polygon([[1, 0], [2, 0], [2, 1], [1, 1]])).mass_properties()
    >>> bool(np.isclose(tube.measure, 2 * np.pi * 1.5 * 1, rtol=1e-15))
    True
    >>> revolve(rectangle(1, 1).transformed(np.eye(2), [-0.5, 0]))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a profile to revolve must lie where x ≥ 0 (x is the radius)
    """
    region = lamina.region if isinstance(lamina, Lamina) else lamina
    return Revolution(region, **kw)
