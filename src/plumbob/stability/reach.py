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
    """The body's surface as facets, m, body frame: triangles (n, 3, 3) for a solid
    (:meth:`~plumbob.bodies.base.Body.surface`), boundary segments (n, 2, 2) for a lamina
    (:meth:`~plumbob.bodies.base.Body.outline`); and whether they are exact (False: a
    curved surface cut into :data:`SEGMENTS` segments a turn). An assembly's are its
    parts' together (a point inside another part is never beyond the union's surface, so
    the searches' extremes are the union's)."""
    parts = body.assembly_parts() if callable(getattr(body, "assembly_parts", None)) else ()
    if parts:
        found = [surface_facets(part) for part in parts]
        return np.concatenate([f for f, _ in found]), all(exact for _, exact in found)
    try:
        if getattr(body, "dim", 3) == 2:
            rings = body.outline(1e-4 * body.size(), SEGMENTS)
            segments = [np.stack((r[:-1], r[1:]), axis=1) for r in rings]
            return (np.concatenate(segments) if segments else np.zeros((0, 2, 2)),
                    bool(body.is_polytope))
        surface = body.surface(SEGMENTS)
    except (GeometryError, AttributeError) as exc:
        raise StabilityError(f"cannot search the body's surface for the worst point: {exc}"
                             ) from None
    return np.asarray(surface.triangles, dtype=float), bool(surface.exact)


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
