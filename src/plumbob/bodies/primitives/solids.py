"""Solid primitives with closed forms, each built on an exact generator.

Box, pyramid and tetrahedron are exact meshes; cylinder, cone, frustum,
sphere, hemisphere and torus are exact solids of revolution; a prism
(extrusion) or revolution of any lamina is exact too. Axial solids have their
axis along +z with the base at z = 0.
"""

from __future__ import annotations

import numpy as np

from ...arguments import floats
from ...errors import GeometryError
from ..lamina import Lamina
from ..profiled import Extrusion, Revolution
from ..region import Region, Ring
from ..solid import MeshSolid
from ..validity import check_polygon
from .laminas import counter_clockwise, disc_region, polygon, positive_number

# ------------------------------------------------------------------ solids
# Every solid primitive passes ``**kw`` to its body: ``density`` (kg/m³) and ``name``.

def _mesh_from_faces(vertices: np.ndarray, faces: list[list[int]], **kw) -> MeshSolid:
    """Triangulate convex planar faces (fans) of a polyhedron. The faces close by
    construction (a box's six, a tetrahedron's four), so the mesh's closure is not
    checked again (10⁴ cubes of a spec: half their building time)."""
    tris = [[f[0], f[i], f[i + 1]] for f in faces for i in range(1, len(f) - 1)]
    return MeshSolid(np.asarray(vertices, dtype=float)[np.array(tris)], checked=True, **kw)


def box(length: float, width: float, height: float, *, centered: bool = False,
        **kw) -> MeshSolid:
    """A rectangular box, corner at the origin, edges along +x, +y, +z (an exact mesh);
    with ``centered=True`` its centre at the origin instead (as trimesh's boxes are).

    Parameters
    ----------
    length, width, height : float
        m, positive: the extents along x, y, z.
    centered : bool
        Centre the box on the origin rather than putting a corner there.
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
    >>> box(1, 2, 3, centered=True).mass_properties().center_of_mass.tolist()
    [0.0, 0.0, 0.0]
    >>> box(1, 1, float("nan"))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: height must be a positive number, not nan
    """
    a, b, c = (positive_number(v, what) for v, what in
               ((length, "length"), (width, "width"), (height, "height")))
    v = np.array(
        [[0, 0, 0], [a, 0, 0], [a, b, 0], [0, b, 0], [0, 0, c], [a, 0, c], [a, b, c], [0, b, c]],
        dtype=float,
    )
    if centered:  # halves of floats are exact: the corners stay exact
        v -= np.array([a, b, c]) / 2
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
    h = positive_number(height, "height")
    check_polygon(base, label="the base")
    base = counter_clockwise(np.asarray(base, dtype=float))
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
    v = floats([p0, p1, p2, p3], "a tetrahedron's corners", error=GeometryError)
    if v.shape != (4, 3) or not np.all(np.isfinite(v)):
        raise GeometryError(f"a tetrahedron needs four finite corners of 3 coordinates, not "
                            f"an array of shape {v.shape}")
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
    h = positive_number(height, "height")
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
    r = positive_number(radius, "radius")
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
    return frustum(positive_number(radius, "radius"), 0.0, height, **kw)


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
    r = positive_number(radius, "radius")
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
    r = positive_number(radius, "radius")
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
    big, small = positive_number(major_radius, "major radius"), positive_number(minor_radius, "minor radius")
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
    >>> from plumbob.bodies.primitives import disc
    >>> props = prism(disc(1), 2).mass_properties()
    >>> bool(np.isclose(props.measure, 2 * np.pi, rtol=1e-15)), props.center_of_mass.tolist()
    (True, [0.0, 0.0, 1.0])
    >>> prism(disc(1), 0)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: height must be a positive number, not 0
    """
    return Extrusion(_profile(lamina, "prism"), positive_number(height, "height"), **kw)


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

    >>> from plumbob.bodies.primitives import rectangle
    >>> tube = revolve(polygon([[1, 0], [2, 0], [2, 1], [1, 1]])).mass_properties()
    >>> bool(np.isclose(tube.measure, 2 * np.pi * 1.5 * 1, rtol=1e-15))
    True
    >>> revolve(rectangle(1, 1).transformed(np.eye(2), [-0.5, 0]))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a profile to revolve must lie where x ≥ 0 (x is the radius)
    """
    return Revolution(_profile(lamina, "revolve"), **kw)


def _profile(lamina: Lamina | Region, what: str) -> Region:
    """The region of a lamina, or the region itself; anything else is refused."""
    if isinstance(lamina, Lamina):
        return lamina.region
    if isinstance(lamina, Region):
        return lamina
    raise GeometryError(f"{what} needs a lamina or a region as its profile (e.g. "
                        f"primitives.polygon(...)), not {type(lamina).__name__}")
