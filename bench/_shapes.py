"""Smooth, non-symmetric closed meshes for the benchmarks: lumpy potatoes, eggs, and a
box united with a tilted cylinder, each from a seed, at about a given triangle count.

Every function returns the triangles, (n, 3, 3) float64, wound outward. Curved
surfaces are facets of the smooth shape: the benchmarks time the meshes, they do not
compare answers with the smooth shapes.
"""

from __future__ import annotations

import numpy as np


def _grid(faces: int) -> tuple[int, int]:
    """(latitude rings, longitude steps) of a lat-long grid of about ``faces`` triangles
    (``2 · lon · (rings − 1)``, the longitudes twice the rings as on a globe)."""
    rings = max(2, int(round(np.sqrt(faces / 4))))
    return rings + 1, max(3, int(round(faces / (2 * rings))))


def _lat_long(directions_to_points, n_lat: int, n_lon: int) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and faces of a closed lat-long surface: ``directions_to_points`` maps unit
    directions (…, 3) to points; the poles are (0, 0, ±1)'s images."""
    theta = np.linspace(0, np.pi, n_lat + 1)[1:-1]
    phi = np.linspace(0, 2 * np.pi, n_lon, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    d = np.stack((np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)), axis=-1)
    poles = directions_to_points(np.array([[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]))
    verts = np.vstack((directions_to_points(d).reshape(-1, 3), poles))
    top, bottom = len(verts) - 2, len(verts) - 1
    idx = np.arange(len(theta) * len(phi)).reshape(len(theta), len(phi))
    a, b = idx[:-1], idx[1:]
    a2, b2 = np.roll(a, -1, axis=1), np.roll(b, -1, axis=1)
    faces = [np.stack((a, b, b2), -1).reshape(-1, 3), np.stack((a, b2, a2), -1).reshape(-1, 3),
             np.stack((np.full(len(phi), top), idx[0], np.roll(idx[0], -1)), 1),
             np.stack((np.full(len(phi), bottom), np.roll(idx[-1], -1), idx[-1]), 1)]
    return verts, np.concatenate(faces)


def potato(n_lat: int, n_lon: int, *, seed: int = 1, bump: float = 0.12
           ) -> tuple[np.ndarray, np.ndarray]:
    """A closed, outward-wound, non-symmetric blob on a latitude-longitude grid:
    ``2 · n_lon · (n_lat − 1)`` triangles. Returns (vertices (n, 3), faces (m, 3))."""
    rng = np.random.default_rng(seed)
    lobes = [(k / np.linalg.norm(k), rng.integers(2, 6), bump * rng.uniform(0.3, 1.0),
              rng.uniform(0, 2 * np.pi)) for k in rng.normal(size=(6, 3))]
    radii = np.array([1.0, 0.75, 0.55])

    def points(d: np.ndarray) -> np.ndarray:
        r = np.ones(d.shape[:-1])
        for k, n, size, phase in lobes:
            r = r + size * np.cos(n * np.arccos(np.clip(d @ k, -1, 1)) + phase)
        return d * r[..., None] * radii

    return _lat_long(points, n_lat, n_lon)


def lumpy_potato(faces: int, seed: int = 1) -> np.ndarray:
    """A potato (see :func:`potato`) of about ``faces`` triangles, 10 cm long."""
    verts, tris = potato(*_grid(faces), seed=seed)
    return 0.1 * verts[tris]


def egg(faces: int, seed: int = 1) -> np.ndarray:
    """A tapered egg, 6 cm long, about ``faces`` triangles, its axis tilted and its
    cross-sections slightly elliptic and off-centre by the seed (no symmetry left)."""
    rng = np.random.default_rng(seed)
    taper = rng.uniform(0.15, 0.3)
    squash = np.array([1.0, rng.uniform(0.85, 0.97), 1.0])
    lean = rng.uniform(-0.08, 0.08, 2)

    def points(d: np.ndarray) -> np.ndarray:
        z = d[..., 2]
        p = d * (1 + taper * z)[..., None] * squash * [0.7, 0.7, 1.0]
        p[..., 0] += lean[0] * (1 - z**2)
        p[..., 1] += lean[1] * z**2
        return 0.03 * p

    verts, tris = _lat_long(points, *_grid(faces))
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    angle = rng.uniform(0.2, 1.2)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    rotation = np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k
    return (verts @ rotation.T)[tris]


def box_with_tilted_cylinder(faces: int, seed: int = 1) -> np.ndarray:
    """A 40 × 30 × 20 mm box united with a Ø14 mm cylinder through it, tilted 15° to
    40° from the vertical by the seed, its circle cut to make about ``faces``
    triangles (manifold3d)."""
    import manifold3d as m3

    rng = np.random.default_rng(seed)
    tilt, turn = rng.uniform(15, 40), rng.uniform(0, 360)
    offset = rng.uniform(-6, 6, 2)
    segments = max(8, faces // 8)  # the union has about 8 triangles per segment
    cylinder = (m3.Manifold.cylinder(44, 7, 7, segments, center=True)
                .rotate([tilt, 0, turn]).translate([offset[0], offset[1], 6]))
    solid = m3.Manifold.cube([40, 30, 20], center=True) + cylinder
    mesh = solid.to_mesh()
    verts = np.asarray(mesh.vert_properties)[:, :3].astype(np.float64)
    return 1e-3 * verts[np.asarray(mesh.tri_verts)]


#: the families bench/poses.py times: name -> function(faces, seed) -> triangles (m)
SMOOTH = {"lumpy potato": lumpy_potato, "egg": egg,
          "box + tilted cylinder": box_with_tilted_cylinder}
