"""The interior hollowing may empty: the inward offset by the wall, made true.

A closed-form offset (:mod:`plumbob.bodies.offset`) is taken as it is. A level-set
offset's surface lies within about its grid step of the true one, and a wall must never
be thinner than asked: each corner of its surface is moved along its normal onto the
exact offset (its exact distance to the body's surface), a little deeper where a flat
face between corners could come nearer (:func:`carving_interior`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..bodies.base import Body
from ..bodies.offset import inward_offset, manifold_triangles
from ..bodies.solid import MeshSolid
from ..errors import GeometryError

__all__ = ["carving_interior", "WALL_STEPS", "PROJECTED_TRIANGLES"]

#: a level-set offset's step is at most the wall over this
WALL_STEPS = 2
#: the exact projection's distance search grows with the surface's fineness against the
#: wall (a 53k-triangle figurine with 2 mm walls ran for minutes): past this many surface
#: triangles the level set is taken deeper by its own error bound instead (walls thicker
#: than asked by at most h² / (2 wall), never thinner)
PROJECTED_TRIANGLES = 20_000


def carving_interior(body: Body, wall: float, step: float | None, size: float):
    """The inward offset by ``wall``, its manifold3d geometry, and a rougher one to search on.

    A level-set offset's surface is then made true (:func:`_projected`): its corners put on
    the exact offset, a little deeper where its flat faces could cut into a wall."""
    h = float(step) if step is not None else min(wall / WALL_STEPS, size / 64)
    # float32 files move vertices by ~1e-7 of the size: keep the exact walls that much thicker
    depth = wall * (1 + 1e-6) + 1e-6 * size
    offset = inward_offset(body, depth, step=h)
    if offset.body is None:
        raise GeometryError(f"nothing lies {wall:g} m inside the body: give a thinner --wall")
    interior = rough = offset.body.to_geometry(256)
    if not offset.exact:
        surface = body.surface(256)[0]
        projected = _projected(interior, surface, depth) \
            if len(surface) <= PROJECTED_TRIANGLES else None
        if projected is None:  # the level set taken deeper by its own error instead
            offset = inward_offset(body, depth, step=h, extra=h * h / (2 * wall))
            if offset.body is None:
                raise GeometryError(f"nothing lies {wall:g} m inside the body: give a "
                                    "thinner --wall")
            interior = rough = offset.body.to_geometry(256)
        else:
            interior, deepest = projected
            offset = replace(offset, body=MeshSolid(manifold_triangles(interior),
                                                    offset.body.densities().pop(), exact=False),
                             method=offset.method + ", corners on the exact offset",
                             surface_error=deepest)
    return offset, interior, rough


def _projected(interior, triangles: np.ndarray, depth: float):
    """The level-set interior with each corner moved along its normal onto the exact
    offset: where the distance to the body's surface (exact, to the nearest of a few
    candidate triangles) is ``depth + e² / (6 depth)``, ``e`` the longest edge of a face
    about it. Then no point of a face is nearer than ``depth``: a point ``p`` of a face
    is a weighted mean of its corners ``v_i``, so for any surface point ``q``,
    ``|q − p|² = Σ w_i |q − v_i|² − Σ w_i |v_i − p|² ≥ (depth + δ)² − R²`` with ``R ≤ e/√3``
    the face's enclosing radius, and ``2 depth δ ≥ e²/3`` makes it ≥ ``depth²``. The corners are
    moved once, the edges then split to a third of the depth, and moved again. Returns
    (the manifold, the largest extra depth, m), or None when they would not move cleanly."""
    from scipy.spatial import cKDTree

    from ..bodies.distance import point_triangle_distances

    gap = depth / 2
    samples, owner = _own_samples(triangles, gap)
    if samples is None:  # too fine a mesh to sample: the level set taken deeper instead
        return None
    tree = cKDTree(samples, balanced_tree=False, compact_nodes=False)

    def rough(points: np.ndarray) -> np.ndarray:
        """Nearly: the nearest of the triangles of the 8 nearest samples."""
        which = tree.query(points, k=min(8, len(samples)))[1].reshape(len(points), -1)
        return point_triangle_distances(points[:, None, :], triangles[owner[which]]).min(axis=1)

    def distance(points: np.ndarray) -> np.ndarray:
        """Exact: the nearest triangle has a sample within ``gap`` of its nearest point, so
        within the distance found + ``gap``: the triangles of the 48 nearest samples are
        measured, and where a farther sample could still be that near, every triangle
        owning a sample within it."""
        k = min(48, len(samples))
        near, which = tree.query(points, k=k)
        near, which = near.reshape(len(points), -1), which.reshape(len(points), -1)
        out = np.full(len(points), np.inf)
        for j in range(0, k, 8):  # eight candidates at a time: small temporaries
            cand = triangles[owner[which[:, j:j + 8]]]
            out = np.minimum(out, point_triangle_distances(points[:, None, :], cand).min(axis=1))
        unsure = np.flatnonzero(near[:, -1] < out + gap)
        if len(unsure):
            lists = tree.query_ball_point(points[unsure], out[unsure] + gap)
            counts = np.fromiter((len(x) for x in lists), dtype=np.int64, count=len(unsure))
            at = np.repeat(unsure, counts)
            tris = owner[np.concatenate(lists).astype(np.int64)]
            pairs = np.unique(at * len(triangles) + tris)
            at, tris = pairs // len(triangles), pairs % len(triangles)
            np.minimum.at(out, at, point_triangle_distances(points[at], triangles[tris]))
        return out

    first = _settled(interior, rough, depth, strict=False)
    if first is None:
        return None
    return _settled(first[0].refine_to_length(depth / 3), distance, depth, strict=True)


def _own_samples(triangles: np.ndarray, gap: float):
    """Points inside each triangle, its own (none shared with a neighbour): the centroids
    of its pieces when each side is cut into ``n`` steps, ``n`` its longest edge over
    ``gap`` — every point of a triangle is within ``gap`` of one of them. Returns
    (points, the triangle of each), or (None, None) past plumbob's sample limit."""
    from ..limits import MAX_SAMPLES

    edges = np.linalg.norm(triangles - np.roll(triangles, 1, axis=1), axis=2).max(axis=1)
    steps = np.maximum(1, np.ceil(edges / gap)).astype(np.int64)
    if float((steps * steps).sum()) > 2 * MAX_SAMPLES:
        return None, None
    points, owner = [], []
    for n in np.unique(steps):
        which = np.flatnonzero(steps == n)
        i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
        up = i + j <= n - 1  # pieces pointing up, centroid at (i + 1/3, j + 1/3) / n
        down = i + j <= n - 2  # and down, at (i + 2/3, j + 2/3) / n
        a = np.concatenate((i[up] + 1 / 3, i[down] + 2 / 3))
        b = np.concatenate((j[up] + 1 / 3, j[down] + 2 / 3))
        w = np.stack((n - a - b, a, b), axis=1) / n  # (n², 3)
        points.append(np.einsum("mk,tkd->tmd", w, triangles[which]).reshape(-1, 3))
        owner.append(np.repeat(which, len(w)))
    return np.concatenate(points), np.concatenate(owner)


def _settled(interior, distance, depth: float, strict: bool):
    """``interior``'s corners moved along their normals to ``depth + e² / (6 depth)`` from
    the surface (``strict``: at least that, all but a thousandth of them within 1 % of the
    depth; else within 2 % either way); (the manifold, the largest extra depth) or None."""
    import manifold3d

    mesh = interior.to_mesh64()
    verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3].copy()
    faces = np.asarray(mesh.tri_verts, dtype=np.int64)
    corners = verts[faces]
    normal = np.zeros_like(verts)
    area = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    for j in range(3):
        np.add.at(normal, faces[:, j], area)
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)

    def least() -> np.ndarray:
        """Each corner's least distance, by the longest edge of its faces as they are now."""
        tri = verts[faces]
        edges = np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2).max(axis=1)  # (f,)
        longest = np.zeros(len(verts))
        for j in range(3):
            np.maximum.at(longest, faces[:, j], edges)
        return depth + longest**2 / (6 * depth)

    for _ in range(12):
        floor = least()
        goal = floor + 1e-3 * depth  # aimed a hair deeper, so the corners end at least there
        gap = distance(verts) - goal
        # a corner left deeper is a thicker wall, not a thinner one: a few are let be
        # (where the distance has a crease and the steps would go back and forth)
        if strict and np.all(gap >= floor - goal) and np.quantile(gap, 0.999) <= 1e-2 * depth:
            break
        if not strict and np.all(np.abs(gap) <= 2e-2 * depth):
            break
        verts += gap[:, None] * normal
    else:
        return None
    # Mesh64: manifold3d's Mesh would round the corners to float32
    moved = manifold3d.Manifold(manifold3d.Mesh64(vert_properties=np.ascontiguousarray(verts),
                                                  tri_verts=faces.astype(np.uint32)))
    if moved.status() != manifold3d.Error.NoError or moved.is_empty():
        return None
    return moved, float(np.max(goal - depth))
