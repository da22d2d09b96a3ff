"""The ground a body stands on, and what stability asks a body about it.

Down directions as unit vectors, the deterministic ground axes of a ``down`` (the
frame made of them, :class:`.frame.GroundFrame`, is loaded where a support polygon or a
tilt asks for it), and a body's hull and lowest points, size,
dimension and whether its hull points are exact. The support polygon itself is
:mod:`plumbob.stability.support`'s (which re-exports these); resting poses need only
these, so ``plumbob poses`` never defines the support's result.
"""

from __future__ import annotations

import numpy as np

from ..arguments import unit_vector as _checked_unit_vector
from ..bodies.base import Body, lowest
from ..errors import GeometryError, StabilityError
from ..massprops import MassProperties
from ..tolerances import size_of

__all__ = [
    "body_dim",
    "body_size",
    "default_down",
    "ground_axes",
    "hull_points",
    "is_polytope",
    "support_points",
    "unit_vector",
]


def unit_vector(vector, dim: int, what: str = "down") -> np.ndarray:
    """``vector`` as a unit vector of ``dim`` components (a 3-vector with z = 0 is accepted
    for a lamina).

    >>> unit_vector([0, 0, -2], 3)
    array([ 0.,  0., -1.])
    >>> unit_vector([1, -1, 0], 2)
    array([ 0.70710678, -0.70710678])
    """
    try:
        v = np.asarray(vector, dtype=float).reshape(-1)
    except (TypeError, ValueError, OverflowError):
        v = vector  # arguments.unit_vector says what is wrong with it
    else:
        if dim == 2 and v.size == 3:
            if v[2] != 0:
                raise StabilityError(f"a lamina stands in its own plane: {what} needs z = 0")
            v = v[:2]
    return _checked_unit_vector(v, what, (dim,), error=StabilityError)


def default_down(dim: int) -> np.ndarray:
    """−z for solids, −y for a lamina (in its own plane).

    >>> default_down(2)
    array([ 0., -1.])
    """
    return np.array([0.0, -1.0]) if dim == 2 else np.array([0.0, 0.0, -1.0])


def ground_axes(down: np.ndarray) -> np.ndarray:
    """The deterministic ground axes (dim − 1, dim) of a unit ``down`` (2 or 3
    components), as rows: ``e1`` and, for solids, ``e2`` (:class:`.frame.GroundFrame`'s
    ``axes``; resting poses place a body by them without making the frame).

    >>> ground_axes(np.array([0.0, 0.0, -1.0]))
    array([[1., 0., 0.],
           [0., 1., 0.]])
    >>> ground_axes(np.array([0.0, -1.0]))
    array([[1., 0.]])
    """
    down = np.asarray(down, dtype=float)
    up = -down
    if down.size == 2:
        return np.array([[up[1], -up[0]]]) + 0.0
    seed = np.array([1.0, 0.0, 0.0]) if abs(up[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    e1 = seed - (seed @ up) * up
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(up, e1)
    axes = np.array([e1, e2])
    axes[np.abs(axes) < 1e-15] = 0.0
    return axes + 0.0


# --------------------------------------------------------------- body access
def hull_points(body, tolerance: float | None = None) -> np.ndarray:
    """Points spanning the body's convex hull (n, dim) m, for any body or particle system."""
    if isinstance(body, Body):
        pts = body.hull_points(tolerance)
    else:
        pts = body.hull_points()
    pts = np.asarray(pts, dtype=float)
    if pts.ndim != 2 or len(pts) == 0:
        raise GeometryError("the body has no points to stand on")
    if not np.all(np.isfinite(pts)):
        raise GeometryError("the body has a coordinate that is not a finite number")
    return pts


def support_points(body, down: np.ndarray, tolerance: float) -> np.ndarray:
    """The body's lowest points along ``down`` within ``tolerance`` m, shape (k, dim)."""
    down = np.asarray(down, dtype=float)
    if isinstance(body, Body):
        pts = np.asarray(body.support_points(down, tolerance), dtype=float)
    else:
        pts = lowest(hull_points(body), down, tolerance)
    if len(pts) == 0:
        raise GeometryError("the body has no lowest point along the given down direction")
    return pts


def body_size(body) -> float:
    """Diagonal of the bounding box of the body's hull points, m."""
    if isinstance(body, Body):
        return float(body.size)
    return size_of(hull_points(body))


def body_dim(body, props: MassProperties) -> int:
    dim = getattr(body, "dim", props.dim)
    if dim not in (2, 3):
        raise StabilityError(f"cannot rest a {dim}-dimensional body on a plane")
    return dim


def is_polytope(body, size: float) -> bool:
    """Whether the body's hull points are exact: no curved surface sampled.

    A :class:`Body` answers itself (:attr:`Body.is_polytope`); any other object
    with hull points is measured: exact when its hull points do not change with
    the sampling tolerance (``size``, m, sets the two tolerances).
    """
    if isinstance(body, Body):
        return body.is_polytope
    coarse = hull_points(body, 1e-3 * size)
    return len(coarse) == len(hull_points(body, 2.5e-4 * size))
