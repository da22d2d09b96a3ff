"""Where a load can act: the body's surface points up to a height, for the worst-point
searches (:class:`~plumbob.stability.loads.Push`, :class:`~plumbob.stability.loads.Press`).

A linear objective (a moment about an edge: the height of a point, or how far it
reaches out over the edge) is greatest over a body clipped at a height ``H`` at a corner
of the clipped surface: a vertex of the surface at most ``H`` high, or a point where a
surface edge crosses the height ``H``. For a polytope (a mesh, a spec of boxes and
prisms) those corners are exact; a curved surface is cut into facets first
(:meth:`~plumbob.bodies.base.Body.to_geometry`'s 128 segments a turn), and the answer
says so.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError, StabilityError

__all__ = ["surface_facets", "corners_below"]

#: the segments a turn of a curved surface is cut into for the searches
SEGMENTS = 128


def surface_facets(body) -> tuple[np.ndarray, bool]:
    """The body's surface as facets, m, body frame: triangles (n, 3, 3) for a solid,
    boundary segments (n, 2, 2) for a lamina; and whether they are exact (False: a curved
    surface cut into :data:`SEGMENTS` segments a turn)."""
    exact = bool(getattr(body, "is_polytope", True))
    own = getattr(body, "surface_triangles", None)  # the Body contract's, where offered
    if callable(own):
        return np.asarray(own(), dtype=float), exact
    tri = getattr(body, "triangles", None)
    if tri is not None:
        return np.asarray(tri, dtype=float), exact
    try:
        shape = body.to_geometry(SEGMENTS)
    except GeometryError as exc:
        raise StabilityError(f"cannot search the body's surface for the worst point: {exc}"
                             ) from None
    if getattr(body, "dim", 3) == 2:
        import shapely

        rings = shapely.get_rings(shape)
        segments = [np.stack((c[:-1], c[1:]), axis=1)
                    for c in (np.asarray(r.coords, dtype=float)[:, :2] for r in rings)]
        return np.concatenate(segments) if segments else np.zeros((0, 2, 2)), exact
    mesh = shape.to_mesh()
    verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    return verts[np.asarray(mesh.tri_verts, dtype=np.int64)], exact


def corners_below(facets: np.ndarray, up: np.ndarray, floor: float,
                  max_height: float | None) -> np.ndarray:
    """The corners of the surface clipped at ``max_height`` m above the floor (the plane
    ``up · p = floor``): facet vertices no higher, and the points where facet edges cross
    that height; (k, dim) m, body frame."""
    pts = facets.reshape(-1, facets.shape[-1])
    if max_height is None:
        return np.unique(pts, axis=0)
    level = floor + max_height
    h = facets @ up  # (n, k)
    keep = pts[(h.reshape(-1) <= level)]
    k = facets.shape[1]
    a, b = facets, np.roll(facets, -1, axis=1)
    ha, hb = h, np.roll(h, -1, axis=1)
    crossing = (ha - level) * (hb - level) < 0
    if k == 2:  # a segment has one edge, not two
        crossing[:, 1] = False
    t = (level - ha[crossing]) / (hb[crossing] - ha[crossing])
    cut = a[crossing] + t[:, None] * (b[crossing] - a[crossing])
    both = np.concatenate((keep, cut))
    if len(both) == 0:
        raise StabilityError(f"no part of the body is {max_height:g} m high or lower")
    return np.unique(both, axis=0)
