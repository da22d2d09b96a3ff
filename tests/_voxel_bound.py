"""The best margin any carve with given walls can reach, computed independently of plumbob:
trimesh's voxels and mass properties, scipy's Euclidean distance transform and shapely's
distances to the support polygon.

The carved body keeps every point within ``wall`` of its surface (the voxels whose
centres lie ``wall`` or more from the outside, by the distance transform) and may empty
any set of the rest. The best margin over such sets is reached by a half-space (the
linear-programming relaxation over the voxels is optimal at a threshold of a linear
function — horizontal, for margin rows — see plumbob's balance/hollow.py): every
direction in the plane and every threshold along it are tried.
"""

from __future__ import annotations

import numpy as np


def support_polygon(triangles: np.ndarray, tolerance: float = 1e-7):
    """The convex hull of the lowest vertices (shapely), for a body resting on z = min."""
    import shapely

    points = triangles.reshape(-1, 3)
    low = points[points[:, 2] <= points[:, 2].min() + tolerance][:, :2]
    return shapely.MultiPoint(low).convex_hull


def _layer(triangles: np.ndarray, z: float, gx: np.ndarray, gy: np.ndarray) -> np.ndarray:
    """Which grid points (gx, gy) at height ``z`` lie inside the mesh: the triangles' cuts
    by the plane, merged into rings by shapely, and a point inside an odd number of rings."""
    import shapely
    from shapely.ops import linemerge

    h = triangles[:, :, 2] - z
    above = h > 0
    crossed = above.any(axis=1) & ~above.all(axis=1)
    t, h, a = triangles[crossed], h[crossed], above[crossed]
    odd = np.where(a.sum(axis=1) == 1, np.argmax(a, axis=1), np.argmax(~a, axis=1))
    ends = []
    for step in (1, 2):
        q = (odd + step) % 3
        p0, p1 = t[np.arange(len(t)), odd], t[np.arange(len(t)), q]
        h0, h1 = h[np.arange(len(t)), odd], h[np.arange(len(t)), q]
        # from the corner below to the one above, so both triangles of an edge agree
        swap = h0 > h1
        p0, p1 = np.where(swap[:, None], p1, p0), np.where(swap[:, None], p0, p1)
        h0, h1 = np.where(swap, h1, h0), np.where(swap, h0, h1)
        ends.append(p0 + (p1 - p0) * (h0 / (h0 - h1))[:, None])
    inside = np.zeros(gx.shape, dtype=bool)
    if not len(t):
        return inside
    merged = linemerge(shapely.multilinestrings([[e0[:2], e1[:2]] for e0, e1 in zip(*ends)]))
    lines = getattr(merged, "geoms", [merged])
    for line in lines:
        if line.is_ring:
            inside ^= shapely.contains_xy(shapely.Polygon(line.coords), gx, gy)
    return inside


def voxel_bound(triangles: np.ndarray, wall: float, pitch: float, directions: int = 24,
                levels: int = 400, samples: int = 1_000_000) -> float:
    """The best margin (m) any carve keeping walls ``wall`` m reaches, on a ``pitch`` m grid."""
    import shapely
    import trimesh
    from scipy.ndimage import distance_transform_edt
    from scipy.spatial import cKDTree

    mesh = trimesh.Trimesh(**trimesh.triangles.to_kwargs(triangles))
    mass, centre = mesh.volume, mesh.center_mass
    lo = triangles.reshape(-1, 3).min(axis=0) - pitch
    hi = triangles.reshape(-1, 3).max(axis=0) + pitch
    axes = [np.arange(a + pitch / 2, b, pitch) for a, b in zip(lo, hi)]
    gx, gy = np.meshgrid(axes[0], axes[1], indexing="ij")
    inside = np.stack([_layer(triangles, z, gx, gy) for z in axes[2]], axis=-1)
    # distance from a voxel's centre to the nearest outside voxel's centre, less half a
    # voxel: the distance to the surface, within about half a voxel either way — and
    # near the wall's depth, the distance to the nearest of a million points scattered
    # over the surface (trimesh), by scipy's k-d tree
    depth = distance_transform_edt(inside) * pitch - pitch / 2
    band = np.argwhere(np.abs(depth - wall) <= pitch)
    spots = np.stack([axes[k][band[:, k]] for k in range(3)], axis=1)
    scattered, _ = trimesh.sample.sample_surface(mesh, samples, seed=0)
    depth[tuple(band.T)] = cKDTree(scattered).query(spots)[0]
    index = np.argwhere(depth >= wall)
    points = np.stack([axes[k][index[:, k]] for k in range(3)], axis=1)
    cell = pitch**3
    polygon = support_polygon(triangles)
    ring = polygon.exterior

    def margin(angle: float) -> float:
        """The best margin of the carves across the direction at ``angle``."""
        u = np.array([np.cos(angle), np.sin(angle), 0.0])
        order = np.argsort(-(points @ u))  # the farthest out first
        taken = np.arange(1, len(order) + 1)
        moment = np.cumsum(points[order], axis=0)
        pick = np.unique(np.linspace(0, len(order) - 1, levels).astype(int))
        removed = taken[pick] * cell
        after = (mass * centre - cell * moment[pick]) / (mass - removed)[:, None]
        spots = shapely.points(after[:, :2])
        signed = shapely.distance(ring, spots) * np.where(shapely.contains(polygon, spots), 1, -1)
        return float(signed.max())

    angles = np.linspace(0, 2 * np.pi, directions, endpoint=False)
    found = {float(a): margin(a) for a in angles}
    step = 2 * np.pi / directions
    for _ in range(3):  # finer about the best direction
        best = max(found, key=found.get)
        for a in best + np.linspace(-step, step, 5):
            found.setdefault(float(a), margin(a))
        step /= 4
    return max(found.values())
