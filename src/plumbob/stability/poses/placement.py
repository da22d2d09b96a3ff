"""Placements: the rigid transform that sets a body down in one of its poses.

A pose rests the body with ``down`` (a unit vector in the body's frame) pointing
at the ground and its centre of mass ``c`` at height ``h`` above it. The placement
is the 4×4 rigid transform ``T`` (row-major, acting on column vectors
``[x, y, z, 1]``) taking body coordinates to a world where the ground is the plane
z = 0, up is +z and the centre of mass lies straight above the origin:

    T·x = R (x − c) + (0, 0, h),   R's rows: e1, e2, up = −down,

with ``(e1, e2)`` the ground axes of :func:`plumbob.stability.ground.ground_axes`
(so ``down = −z`` gives the identity rotation). Every point of the body then has
z ≥ 0 and the face it rests on lies at z = 0.

A lamina stands in its own plane: its plane becomes the vertical plane y = 0 of
the world (its ``e1`` along +x, its up along +z), so its placement is a 4×4 too.
"""

from __future__ import annotations

import numpy as np

from ..ground import ground_axes

__all__ = ["placement"]


def placement(down: np.ndarray, center_of_mass: np.ndarray, height: float) -> np.ndarray:
    """The 4×4 rigid transform resting a body on z = 0 with ``down`` (dim,) pointing at the
    ground and its ``center_of_mass`` (dim,), m, ``height`` m above the origin.

    >>> placement(np.array([0.0, 0.0, -1.0]), np.array([1.0, 2.0, 3.0]), 0.5)
    array([[ 1. ,  0. ,  0. , -1. ],
           [ 0. ,  1. ,  0. , -2. ],
           [ 0. ,  0. ,  1. , -2.5],
           [ 0. ,  0. ,  0. ,  1. ]])
    """
    down = np.asarray(down, dtype=float)
    com = np.asarray(center_of_mass, dtype=float)
    axes, up = ground_axes(down), -down
    if down.size == 2:  # the lamina's plane becomes the world's xz plane
        e1 = axes[0]
        R = np.array([[e1[0], e1[1], 0.0], [0.0, 0.0, -1.0], [up[0], up[1], 0.0]])
        com = np.append(com, 0.0)
    else:
        R = np.vstack((axes, up))
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = -R @ com + np.array([0.0, 0.0, float(height)])
    return T + 0.0  # no negative zeros
