"""Leaning figurines for the hollowing tests and benchmark: closed meshes (manifold3d) that
topple as solids, in metres.

* ``"capsule"``: a capsule leaning out of a cylinder plinth it is sunk into (issue 23);
* ``"arm"``: an upright capsule on the plinth with a bent arm held out to one side;
* ``"head"``: an upright capsule with a large head set off its axis.

A ``seed`` varies the lean, the reach and the direction; ``size`` scales it (1: a plinth
of radius 18 mm); ``segments`` sets the faceting (about 2 × segments² triangles).
"""

from __future__ import annotations

import numpy as np

KINDS = ("capsule", "arm", "head")
MM = 1e-3


def _capsule(a, b, radius: float, segments: int):
    import manifold3d

    ends = [manifold3d.Manifold.sphere(radius, segments).translate(list(map(float, p)))
            for p in (a, b)]
    return manifold3d.Manifold.batch_hull(ends)


def figurine_manifold(kind: str = "capsule", seed: int = 0, size: float = 1.0,
                      segments: int = 64):
    """The figurine (a manifold3d ``Manifold``, metres)."""
    import manifold3d

    rng = np.random.default_rng(seed)
    s = size * MM
    turn = rng.uniform(0, 2 * np.pi)
    u = np.array([np.cos(turn), np.sin(turn), 0.0])
    radius, height = 18 * s, 8 * s
    plinth = manifold3d.Manifold.cylinder(height, radius, radius, segments)
    if kind == "capsule":
        lean, r = np.radians(rng.uniform(56, 62)), rng.uniform(8, 10) * s
        foot = np.array([0, 0, r + s]) + 4 * s * u
        top = foot + 62 * s * (np.sin(lean) * u + np.array([0, 0, np.cos(lean)]))
        parts = [_capsule(foot, top, r, segments)]
    elif kind == "arm":
        foot, top = np.array([0, 0, 9 * s]), np.array([0, 0, 40 * s])
        elbow = top + 52 * s * (0.95 * u + np.array([0, 0, 0.3]))
        hand = elbow + rng.uniform(30, 36) * s * (0.55 * u + np.array([0, 0, -0.84]))
        parts = [_capsule(foot, top, 8 * s, segments),
                 _capsule(top - 4 * s * u, elbow, rng.uniform(7, 8) * s, segments),
                 _capsule(elbow, hand, 7 * s, segments)]
    elif kind == "head":
        foot, top = np.array([0, 0, 9 * s]), np.array([0, 0, 36 * s]) + 6 * s * u
        head = top + rng.uniform(26, 30) * s * u + np.array([0, 0, 12 * s])
        parts = [_capsule(foot, top, 8 * s, segments),
                 manifold3d.Manifold.sphere(rng.uniform(16, 18) * s, segments).translate(
                     list(map(float, head)))]
    else:
        raise ValueError(kind)
    return manifold3d.Manifold.batch_boolean([plinth, *parts], manifold3d.OpType.Add)


def figurine_triangles(kind: str = "capsule", seed: int = 0, size: float = 1.0,
                       segments: int = 64) -> np.ndarray:
    """The figurine's triangles (n, 3, 3), metres, outward wound."""
    mesh = figurine_manifold(kind, seed, size, segments).to_mesh64()
    verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    return verts[np.asarray(mesh.tri_verts, dtype=np.int64)]
