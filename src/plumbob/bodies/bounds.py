"""How far the result of a boolean on facets may lie from the true one: a bound, not a guess.

A boolean's result differs from the true shape only inside the region between the two
(their symmetric difference). Let ``moved`` bound that region's size (m³, or m² for a
lamina). Every quantity is an integral over the body, so each changes by at most
``moved`` times the largest value its integrand takes there:

* the measure (volume, area) by ``moved``;
* the centre by ``R · moved / (V − moved)``, with ``R`` the body's radius about its centre;
* the inertia about the centre (Frobenius norm) by ``√2 R² moved`` plus the shift of the
  centre; the norm is at least ``trace / √3`` (its eigenvalues are not negative).

:func:`relative_bound` turns ``moved`` into one relative error that holds for all three
(the centre's relative to ``R``). ``moved`` itself comes from:

* :func:`roundoff_moved`: a boolean of polytopes is exact but for round-off. manifold3d
  works in float64 and merges features smaller than its tolerance (1e-12 of the
  coordinates' size); no point of the surface moves further, so the region between is at
  most twice that tolerance times the surface area. shapely works in float64 too.
* :func:`faceting_moved`: a curved operand is cut into facets. For a convex one (a
  sphere, a cylinder) the facets lie inside it and the region between is exactly the
  difference of the two measures; for any other, twice the facets' area times the
  largest deviation of a chord, ``diagonal · (1 − cos(π / n))``, twice over.

A boolean is 1-Lipschitz in the symmetric difference, so the operands' ``moved`` add up.
"""

from __future__ import annotations

import numpy as np

from ..massprops import MassProperties
from .base import Body
from .booleans import measure as geometry_measure

__all__ = ["faceting_moved", "relative_bound", "roundoff_moved", "change"]

#: manifold3d's and shapely's merging tolerance, relative to the coordinates' size
MERGE_TOLERANCE = 1e-12

#: how much a radius measured on the facets is widened to cover the true shape's
RADIUS_MARGIN = 1.01


def _boundary(geometry, dim: int) -> float:
    return float(geometry.length) if dim == 2 else float(geometry.surface_area())


def _extent(geometry, dim: int) -> tuple[float, float]:
    """(largest coordinate, diagonal) of the geometry's bounding box, m."""
    if dim == 2:
        low, high = np.array(geometry.bounds[:2]), np.array(geometry.bounds[2:])
    else:
        bounds = np.asarray(geometry.bounding_box(), dtype=float)
        low, high = bounds[:3], bounds[3:]
    return float(np.max(np.abs(np.concatenate((low, high))))), float(np.linalg.norm(high - low))


def roundoff_moved(geometry, dim: int) -> float:
    """A bound on the region the boolean's round-off and merging may have moved, m³ (m²).

    >>> import manifold3d
    >>> cube = manifold3d.Manifold.cube([1.0, 1.0, 1.0])
    >>> roundoff_moved(cube, 3)   # 2 · 1e-12 m · 6 m²
    1.2e-11
    """
    largest, _ = _extent(geometry, dim)
    tolerance = MERGE_TOLERANCE * largest
    if dim == 3:
        tolerance = max(tolerance, float(geometry.get_tolerance()))
    return 2 * tolerance * _boundary(geometry, dim)


def _convex(geometry, dim: int) -> bool:
    measure = geometry_measure(geometry, dim)
    hull = float(geometry.convex_hull.area) if dim == 2 else float(geometry.hull().volume())
    return hull - measure <= 1e-9 * hull


def faceting_moved(body: Body, geometry, segments: int, dim: int) -> float:
    """A bound on the region between ``body`` and ``geometry``, its shape faceted at
    ``segments`` per turn, m³ (m²); with the body's own stated error carried along.

    >>> from plumbob.bodies.primitives import box, sphere
    >>> faceting_moved(box(1, 1, 1), box(1, 1, 1).to_geometry(64), 64, 3)
    0.0
    >>> ball = sphere(1.0)
    >>> lost = ball.mass_properties().measure - ball.to_geometry(64).volume()
    >>> bool(faceting_moved(ball, ball.to_geometry(64), 64, 3) == lost)   # convex: the lost volume
    True
    """
    props = body.mass_properties()
    exact = abs(float(props.measure))
    carried = float(props.relative_error) * exact
    if body.is_polytope and props.exact:
        return carried
    faceted = geometry_measure(geometry, dim)
    lost = abs(exact - faceted)
    if _convex(geometry, dim):
        return lost + carried
    _, diagonal = _extent(geometry, dim)
    chord = 2 * diagonal * (1 - np.cos(np.pi / segments))
    return lost + 2 * chord * _boundary(geometry, dim) + carried


def _radius(props: MassProperties, points: np.ndarray) -> float:
    centre = np.asarray(props.center_of_mass, dtype=float)
    return RADIUS_MARGIN * float(np.max(np.linalg.norm(points[:, :len(centre)] - centre, axis=1)))


def relative_bound(moved: float, props: MassProperties, points: np.ndarray) -> float:
    """The largest relative error of the measure, the centre (relative to the body's radius
    about it) and the inertia (Frobenius norm) that ``moved`` m³ (m²) of material can make.

    Parameters
    ----------
    moved : float
        m³ (m² for a lamina): a bound on the region between the computed and the true body.
    props : MassProperties
        The computed body's, at any density.
    points : ndarray, shape (n, dim)
        m: points spanning the body (its vertices), for its radius about the centre.

    Returns
    -------
    float
        1.0 or more when ``moved`` is as large as the body itself.

    Examples
    --------
    >>> from plumbob.bodies.primitives import box
    >>> cube = box(1, 1, 1)
    >>> round(relative_bound(1e-9, cube.mass_properties(), cube.hull_points()), 12)  # inertia
    3.748e-09
    """
    measure = abs(float(props.measure))
    if not moved > 0:
        return 0.0
    if moved >= measure / 2:
        return max(1.0, moved / measure)
    density = float(props.mass) / measure
    radius = _radius(props, np.asarray(points, dtype=float))
    centre = RADIUS_MARGIN * moved / (measure - moved)
    shift = radius * centre
    inertia = np.sqrt(2) * radius**2 * moved + np.sqrt(2) * (measure + moved) * shift**2
    trace = float(np.trace(props.inertia)) / density
    spread = np.sqrt(3) * inertia / trace if trace > 0 else 1.0
    return float(max(moved / measure, centre, spread))


def change(a: MassProperties, b: MassProperties, points: np.ndarray) -> float:
    """The largest relative difference between two mass properties of (nearly) one body:
    measure, centre (relative to the radius about it) and inertia (Frobenius norm).

    >>> from plumbob.bodies.primitives import box
    >>> cube = box(1, 1, 1)
    >>> change(cube.mass_properties(), cube.translated([0, 0, 1e-9]).mass_properties(),
    ...        cube.hull_points()) < 2e-9
    True
    """
    radius = _radius(a, np.asarray(points, dtype=float))
    measure = abs(float(a.measure))
    norm = float(np.linalg.norm(a.inertia))
    return float(max(abs(float(a.measure) - float(b.measure)) / measure,
                     float(np.linalg.norm(a.center_of_mass - b.center_of_mass)) / radius,
                     float(np.linalg.norm(a.inertia - b.inertia)) / norm if norm > 0 else 0.0))
