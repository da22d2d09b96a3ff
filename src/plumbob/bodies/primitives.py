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
from .base import Body
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
    w, h = _positive(width, "width"), _positive(height, "height")
    return Region((Ring(np.array([[0, 0], [w, 0], [w, h], [0, h]], dtype=float)),))


def polygon_region(vertices, holes=()) -> Region:
    rings = [Ring(_ccw(vertices))]
    rings += [Ring(_ccw(hole)[::-1]) for hole in holes]
    return Region(tuple(rings))


def disc_region(radius: float, centre=(0.0, 0.0)) -> Region:
    r = _positive(radius, "radius")
    c = np.asarray(centre, dtype=float)
    return Region((Ring(np.array([[r, 0.0], [-r, 0.0]]) + c, bulges=np.array([1.0, 1.0])),))


def semicircle_region(radius: float) -> Region:
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
def rectangle(width: float, height: float, **kw) -> Lamina:
    """Corner at the origin, sides along +x (width) and +y (height), m."""
    return Lamina(rectangle_region(width, height), **kw)


def polygon(vertices, holes=(), **kw) -> Lamina:
    """Any simple polygon (n, 2) with optional holes; orientation is normalised."""
    return Lamina(polygon_region(vertices, holes), **kw)


def triangle(p0, p1, p2, **kw) -> Lamina:
    return polygon(np.array([p0, p1, p2], dtype=float), **kw)


def regular_polygon(sides: int, circumradius: float, **kw) -> Lamina:
    """Centred at the origin with a vertex on +x."""
    if int(sides) != sides or sides < 3:
        raise GeometryError("a regular polygon needs a whole number of sides, at least 3")
    r = _positive(circumradius, "circumradius")
    t = 2 * np.pi * np.arange(int(sides)) / sides
    return polygon(r * np.stack((np.cos(t), np.sin(t)), axis=1), **kw)


def disc(radius: float, **kw) -> Lamina:
    return Lamina(disc_region(radius), **kw)


def semicircle(radius: float, **kw) -> Lamina:
    """Straight edge on the x-axis, circle centre at the origin, y ≥ 0 (the seed's Figure 27)."""
    return Lamina(semicircle_region(radius), **kw)


def sector(radius: float, angle: float, **kw) -> Lamina:
    return Lamina(sector_region(radius, angle), **kw)


def circular_segment(radius: float, angle: float, **kw) -> Lamina:
    return Lamina(segment_region(radius, angle), **kw)


def annulus(inner_radius: float, outer_radius: float, **kw) -> Lamina:
    if not _positive(outer_radius, "outer radius") > _positive(inner_radius, "inner radius"):
        raise GeometryError("an annulus needs an outer radius larger than its inner radius")
    hole = disc_region(inner_radius).rings[0].reversed()
    return Lamina(Region(disc_region(outer_radius).rings + (hole,)), **kw)


# ------------------------------------------------------------------ solids
def _mesh_from_faces(vertices: np.ndarray, faces: list[list[int]], **kw) -> MeshSolid:
    """Triangulate convex planar faces (fans) of a polyhedron."""
    tris = [[f[0], f[i], f[i + 1]] for f in faces for i in range(1, len(f) - 1)]
    return MeshSolid(np.asarray(vertices, dtype=float)[np.array(tris)], **kw)


def box(length: float, width: float, height: float, **kw) -> MeshSolid:
    """Corner at the origin, edges along +x, +y, +z (m)."""
    a, b, c = _positive(length, "length"), _positive(width, "width"), _positive(height, "height")
    v = np.array(
        [[0, 0, 0], [a, 0, 0], [a, b, 0], [0, b, 0], [0, 0, c], [a, 0, c], [a, b, c], [0, b, c]],
        dtype=float,
    )
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    return _mesh_from_faces(v, faces, **kw)


def pyramid(base, height: float, apex=None, **kw) -> MeshSolid:
    """A pyramid on the polygon ``base`` (n, 2) in the plane z = 0, apex at ``height``
    above ``apex`` (x, y) (default: the base's centroid). Non-convex bases are fine."""
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
    v = np.array([p0, p1, p2, p3], dtype=float)
    if np.linalg.det(v[1:] - v[0]) < 0:
        v[[1, 2]] = v[[2, 1]]
    if np.linalg.det(v[1:] - v[0]) == 0:
        raise GeometryError("the tetrahedron's four points are coplanar")
    return _mesh_from_faces(v, [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], **kw)


def frustum(bottom_radius: float, top_radius: float, height: float, **kw) -> Revolution:
    """Axis +z, base (radius ``bottom_radius``) at z = 0; a cone when one radius is 0."""
    h = _positive(height, "height")
    r0, r1 = float(bottom_radius), float(top_radius)
    if r0 < 0 or r1 < 0 or not (r0 > 0 or r1 > 0):
        raise GeometryError("a frustum needs non-negative radii, not both zero")
    pts = [[0, 0], [r0, 0], [r1, h], [0, h]]
    pts = [p for i, p in enumerate(pts) if not (i in (1, 2) and p[0] == 0)]
    return Revolution(Region((Ring(np.array(pts, dtype=float)),)), **kw)


def cylinder(radius: float, height: float, **kw) -> Revolution:
    r = _positive(radius, "radius")
    return frustum(r, r, height, **kw)


def cone(radius: float, height: float, **kw) -> Revolution:
    return frustum(_positive(radius, "radius"), 0.0, height, **kw)


def sphere(radius: float, **kw) -> Revolution:
    """Centred at the origin."""
    r = _positive(radius, "radius")
    return Revolution(
        Region((Ring(np.array([[0.0, -r], [0.0, r]]), bulges=np.array([1.0, 0.0])),)), **kw
    )


def hemisphere(radius: float, **kw) -> Revolution:
    """Flat face on z = 0, dome up, centre of the sphere at the origin."""
    r = _positive(radius, "radius")
    quarter = Ring(
        np.array([[0.0, 0.0], [r, 0.0], [0.0, r]]), bulges=np.array([0.0, np.tan(np.pi / 8), 0.0])
    )
    return Revolution(Region((quarter,)), **kw)


def torus(major_radius: float, minor_radius: float, **kw) -> Revolution:
    """Centred at the origin, axis +z."""
    big, small = _positive(major_radius, "major radius"), _positive(minor_radius, "minor radius")
    if small > big:
        raise GeometryError("a torus needs its tube radius no larger than its major radius")
    return Revolution(disc_region(small, centre=(big, 0.0)), **kw)


def prism(lamina: Lamina | Region, height: float, **kw) -> Extrusion:
    """The lamina swept from z = 0 to z = ``height``."""
    region = lamina.region if isinstance(lamina, Lamina) else lamina
    return Extrusion(region, _positive(height, "height"), **kw)


def revolve(lamina: Lamina | Region, **kw) -> Body:
    """The lamina (in the half-plane x ≥ 0, x the radius, y the axis) turned about the y-axis;
    the result's axis is +z."""
    region = lamina.region if isinstance(lamina, Lamina) else lamina
    return Revolution(region, **kw)
