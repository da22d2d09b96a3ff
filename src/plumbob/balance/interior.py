"""The interior hollowing may empty: the inward offset by the wall, made true.

A closed-form offset (:mod:`plumbob.bodies.offset`) is taken as it is. Otherwise the
offset is a level set of the distance to the surface (exact distances at the points of a
grid, extracted by manifold3d), whose surface lies within about its grid step of the true
one; and a wall must never be thinner than asked: each corner of its surface is then
moved along its normal onto the exact offset (its exact distance to the body's surface,
libigl's search), a little deeper where a flat face between corners could come nearer
(:func:`carving_interior`).
"""

from __future__ import annotations

import numpy as np

from ..bodies.base import Body
from ..bodies.offset import InwardOffset, closed_form_offset, level_set_manifold, manifold_triangles
from ..bodies.solid import MeshSolid
from ..errors import GeometryError

__all__ = ["carving_interior", "WALL_STEPS"]

#: a level-set offset's step is at most the wall over this
WALL_STEPS = 2


def carving_interior(body: Body, wall: float, step: float | None, size: float):
    """The inward offset by ``wall`` (an :class:`InwardOffset`), its manifold3d geometry, and
    a rougher one to search on (the level set as extracted, before its corners are moved).

    A level-set offset's surface is made true (:func:`_projected`): its corners put on the
    exact offset, a little deeper where its flat faces could cut into a wall. Should that
    not settle, the level set is taken deeper by what its grid could hide instead (see
    :func:`_deeper`): walls thicker than asked, never thinner."""
    h = float(step) if step is not None else min(wall / WALL_STEPS, size / 64)
    if not (np.isfinite(h) and h > 0):
        raise GeometryError(f"an offset step must be a positive number, not {step!r}")
    # float32 files move vertices by ~1e-7 of the size: keep the exact walls that much thicker
    depth = wall * (1 + 1e-6) + 1e-6 * size
    offset = closed_form_offset(body, depth)
    if offset is not None:
        if offset.body is None:
            raise _too_thick(wall)
        interior = offset.body.to_geometry(256)
        return offset, interior, interior
    from ..bodies.distance import SurfaceDistance

    triangles = body.surface(256)[0]
    surface = SurfaceDistance(triangles)
    rough = level_set_manifold(triangles, depth, h, surface=surface)
    if rough.is_empty() or rough.volume() <= 0:
        raise _too_thick(wall)
    density = body.densities().pop()
    density = density if isinstance(density, float) else None
    projected = _projected(rough, surface, depth)
    if projected is not None:
        interior, deepest = projected
        method = "level set, corners on the exact offset"
    else:
        interior, deepest = _deeper(triangles, depth, h, surface), 2 * h
        method = "level set taken deeper by its grid's reach"
        if interior.is_empty() or interior.volume() <= 0:
            raise _too_thick(wall)
    # the interior's volume is that of the exact offset less at most its surface × the
    # extra depth of its corners
    error = interior.surface_area() * deepest / interior.volume()
    inner = MeshSolid(manifold_triangles(interior), density, exact=False, relative_error=error,
                      note=f"the inward offset is a level set on a {h:.3g} m grid, its "
                           "corners on the exact offset")
    offset = InwardOffset(inner, depth, False, method, h, deepest, error)
    return offset, interior, rough


def _too_thick(wall: float) -> GeometryError:
    return GeometryError(f"nothing lies {wall:g} m inside the body: give a thinner --wall")


def _deeper(triangles: np.ndarray, depth: float, h: float, surface):
    """The level set taken ``2 h`` deeper: manifold3d's marching tetrahedra (edges at most
    ``h``) interpolate exact distances at the grid's corners (and their trilinear means at
    the cells' centres, within ``√3 h / 2`` above the truth), so a point of its surface is
    within ``h + √3 h / 2 < 2 h`` of depth of what the level asks."""
    return level_set_manifold(triangles, depth + 2 * h, h, surface=surface)


def _projected(interior, surface, depth: float):
    """The level-set interior with each corner moved along its normal onto the exact
    offset: where the exact distance to the body's surface is ``depth + e² / (6 depth)``,
    ``e`` the longest edge of a face about it. Then no point of a face is nearer than
    ``depth``: a point ``p`` of a face is a weighted mean of its corners ``v_i``, so for any
    surface point ``q``, ``|q − p|² = Σ w_i |q − v_i|² − Σ w_i |v_i − p|² ≥ (depth + δ)² − R²``
    with ``R ≤ e/√3`` the face's enclosing radius, and ``2 depth δ ≥ e²/3`` makes it
    ≥ ``depth²``. The corners are moved once, the edges then split to a third of the depth,
    and moved again. Returns (the manifold, the largest extra depth, m), or None when
    they would not settle cleanly."""
    first = _settled(interior, surface, depth, strict=False)
    if first is None:
        return None
    return _settled(first[0].refine_to_length(depth / 3), surface, depth, strict=True)


def _settled(interior, surface, depth: float, strict: bool):
    """``interior``'s corners moved along their normals to ``depth + e² / (6 depth)`` from
    the surface (``strict``: at least that, all but a thousandth of them within 1 % of the
    depth; else within 2 % either way); (the manifold, the largest extra depth) or None.

    Each step is Newton's along the normal: the distance grows at the rate ``−n·g`` (``g``
    the unit vector from the nearest surface point), and only the corners not yet
    settled move and are measured again."""
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

    distance, nearest = surface.query(verts)
    for _ in range(12):
        floor = least()
        goal = floor + 1e-3 * depth  # aimed a hair deeper, so the corners end at least there
        gap = distance - goal
        # a corner left deeper is a thicker wall, not a thinner one: a few are let be
        # (where the distance has a crease and the steps would go back and forth)
        if strict:
            shallow = gap < floor - goal
            if not shallow.any() and np.quantile(gap, 0.999) <= 1e-2 * depth:
                break
            move = shallow | (gap > 0.5e-2 * depth)
        else:
            if np.all(np.abs(gap) <= 2e-2 * depth):
                break
            move = np.abs(gap) > 1e-2 * depth
        away = (verts[move] - nearest[move]) / np.maximum(distance[move], 1e-300)[:, None]
        rate = np.clip(-np.einsum("ij,ij->i", normal[move], away), 0.5, 1.0)
        verts[move] += (gap[move] / rate)[:, None] * normal[move]
        distance[move], nearest[move] = surface.query(verts[move])
    else:
        return None
    # Mesh64: manifold3d's Mesh would round the corners to float32
    moved = manifold3d.Manifold(manifold3d.Mesh64(vert_properties=np.ascontiguousarray(verts),
                                                  tri_verts=faces.astype(np.uint32)))
    if moved.status() != manifold3d.Error.NoError or moved.is_empty():
        return None
    return moved, float(np.max(goal - depth))
