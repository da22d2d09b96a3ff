"""Frames: rotation matrices, and right-handed orthonormal frames given by their axes.

Pure numpy; the mass properties turn their tensors by them (``R I Rᵀ``) and the specs
place parts with them.
"""

from __future__ import annotations

import numpy as np

from .arguments import floats, number, unit_vector
from .errors import GeometryError

__all__ = ["rotation_matrix", "frame_axes", "frame_rows"]


def rotation_matrix(axis: np.ndarray | list[float], angle: float) -> np.ndarray:
    """The matrix of a turn about an axis through the origin.

    Parameters
    ----------
    axis, angle : array_like (3,), float
        The axis (any length but zero); radians, by the right-hand rule.

    Returns
    -------
    numpy.ndarray, shape (3, 3)
        The rotation matrix; quarter turns are exact.

    Examples
    --------
    >>> rotation_matrix([0, 0, 1], np.pi / 2) @ [1, 0, 0]
    array([0., 1., 0.])
    >>> rotation_matrix([0, 0, 0], 1.0)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a rotation axis must be a non-zero vector, not [0, 0, 0]
    """
    x, y, z = unit_vector(axis, "a rotation axis", (3,), error=GeometryError)
    angle = number(angle, "angle", error=GeometryError)
    c, s = np.cos(angle), np.sin(angle)
    # Quarter turns are exact: cos(π/2) is 6e-17 in floating point, not 0.
    c, s = (0.0 if abs(c) < 1e-15 else c), (0.0 if abs(s) < 1e-15 else s)
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return c * np.eye(3) + s * k + (1 - c) * np.outer([x, y, z], [x, y, z])


def frame_axes(x=None, y=None, z=None) -> np.ndarray:
    """The rows (x, y, z) of a right-handed orthonormal frame given two of its axes (any
    lengths, at right angles); the third is their cross product.

    Parameters
    ----------
    x, y, z : array_like (3,), optional
        Exactly two of the frame's axes, in the body's coordinates.

    Returns
    -------
    numpy.ndarray, shape (3, 3)
        The unit axes as rows: ``R``, so that a tensor ``I`` reads ``R I Rᵀ`` in the frame.

    Examples
    --------
    >>> frame_axes(x=[1, 1, 0], y=[-1, 1, 0]).round(6)
    array([[ 0.707107,  0.707107,  0.      ],
           [-0.707107,  0.707107,  0.      ],
           [ 0.      ,  0.      ,  1.      ]])
    >>> frame_axes(x=[1, 0, 0], y=[1, 1, 0])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a frame's axes must be at right angles: x and y are 45° apart
    """
    given = {name: unit_vector(v, f"the frame's {name} axis", (3,), error=GeometryError)
             for name, v in (("x", x), ("y", y), ("z", z)) if v is not None}
    if len(given) != 2:
        raise GeometryError(f"a frame is given by two of its axes (x, y, z), not {len(given)}")
    (a, u), (b, v) = given.items()
    cosine = float(np.dot(u, v))
    if abs(cosine) > 1e-9:  # round-off of unit vectors typed to a dozen digits
        angle = np.degrees(np.arccos(np.clip(cosine, -1.0, 1.0)))
        raise GeometryError(f"a frame's axes must be at right angles: {a} and {b} are "
                            f"{angle:.4g}° apart")
    rows = dict(given)
    if "z" not in rows:
        rows["z"] = np.cross(rows["x"], rows["y"])
    elif "y" not in rows:
        rows["y"] = np.cross(rows["z"], rows["x"])
    else:
        rows["x"] = np.cross(rows["y"], rows["z"])
    return np.array([rows["x"], rows["y"], rows["z"]], dtype=float) + 0.0  # no -0


def frame_rows(axes) -> np.ndarray:
    """``axes`` (3, 3) checked to be a frame's unit axes as rows: at right angles and
    right-handed; else a :class:`GeometryError`.

    >>> frame_rows(np.diag([1.0, 1.0, -1.0]))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a frame's axes must be three unit rows at right angles, \
right-handed (or 'principal')
    """
    rows = floats(axes, "axes", error=GeometryError)
    if rows.shape != (3, 3) or not np.allclose(rows @ rows.T, np.eye(3), atol=1e-9) \
            or np.linalg.det(rows) < 0:
        raise GeometryError("a frame's axes must be three unit rows at right angles, "
                            "right-handed (or 'principal')")
    return rows
