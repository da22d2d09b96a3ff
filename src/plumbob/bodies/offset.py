"""The inward offset of a solid: the points at least a given distance inside it.

A printed part's infill and a hollowed figurine's void both start here: what is
left inside walls of thickness ``t``. The offset is the set ``{p : ball(p, t) ⊂ body}``.

Exact where a closed form exists — and then the offset is one of plumbob's exact
bodies, so its mass properties stay exact:

* a **convex mesh** (a box, pyramid, tetrahedron, any convex polyhedron): every face
  plane moved inward by ``t``, intersected (a convex body is the intersection of
  its faces' half-spaces, and a ball fits exactly where it fits each one);
* a **sphere** or a **torus**: the same circle profile with its radius less ``t``;
* a **solid of revolution or prism of a convex polygon** (cylinder, cone, frustum, a
  box as a prism): the profile's edges moved inward by ``t`` — for a revolution
  every edge but those on the axis (the nearest boundary point of a point in a
  meridian half-plane lies in that half-plane), for a prism the end faces too;
* a **placed** body: the offset of the body, placed.

Anything else (a free-form mesh, a boolean) is offset as a level set of its signed
distance on a grid (:mod:`plumbob.bodies.distance`), extracted by manifold3d's
marching tetrahedra at a stated step ``h``. That offset is not exact: its surface
lies within about ``h`` of the true one, and its mass properties carry the change
between steps ``h`` and ``2h`` as their relative error (the csg module's rule:
the extrapolation's own change as a conservative estimate).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import GeometryError
from ..results import Result
from .base import Body, Transformed
from .profiled import Extrusion, Revolution
from .region import Region, Ring
from .solid import MeshSolid

__all__ = ["InwardOffset", "inward_offset", "closed_form_offset", "DEFAULT_STEPS"]

#: the default level-set step is the body's size over this (or half the distance, if finer)
DEFAULT_STEPS = 64


@dataclass(frozen=True, eq=False, repr=False)
class InwardOffset(Result):
    """The part of a body at least ``distance`` m inside it.

    body: the offset, with the input's density (None when nothing is that far inside).
    distance: m.
    exact: whether ``body`` is the exact offset (a closed form).
    method: how it was made (``"convex polyhedron"``, ``"sphere"``, ``"level set"`` …).
    step: m, the level-set grid step (None for a closed form).
    surface_error: m, how far the offset's surface may lie from the true one: 0 for a
        closed form, the step for a level set.
    relative_error: the estimated relative error of the offset's volume (0 exact).
    """

    body: Body | None
    distance: float
    exact: bool
    method: str
    step: float | None = None
    surface_error: float = 0.0
    relative_error: float = 0.0

    @property
    def empty(self) -> bool:
        """Whether nothing of the body lies ``distance`` inside it."""
        return self.body is None

    def as_dict(self) -> dict:
        volume = None if self.body is None else self.body.mass_properties().measure
        return {"distance": self.distance, "exact": self.exact, "method": self.method,
                "step": self.step, "surface_error": self.surface_error,
                "relative_error": self.relative_error, "volume": volume}

    @property
    def note(self) -> str:
        """One sentence for a report's notes."""
        if self.exact:
            return f"the inward offset by {self.distance:.4g} m is exact ({self.method})"
        return (f"the inward offset by {self.distance:.4g} m is a level set on a "
                f"{self.step:.3g} m grid: its surface lies within {self.surface_error:.3g} m "
                f"of the true one, its volume within about {self.relative_error:.1e} (relative)")


def inward_offset(body: Body, distance: float, *, step: float | None = None,
                  extra: float = 0.0) -> InwardOffset:
    """The part of ``body`` at least ``distance`` m inside it (see the module's doc).

    Parameters
    ----------
    body : Body
        A solid.
    distance : float
        m, positive: the wall thickness.
    step : float, optional
        The level-set grid step, m, for bodies without a closed form; default the
        smaller of half the distance and the body's size / 64 (coarser for a large
        body with a thin wall, to keep the grid within half a million points).
    extra : float
        m, added to the distance of a level set only: a level-set offset taken
        deeper by its own surface error keeps every wall at least ``distance`` thick.

    Returns
    -------
    InwardOffset

    Raises
    ------
    GeometryError
        For a lamina or particles, or a distance that is not a positive number.

    Examples
    --------
    >>> from plumbob.bodies.primitives import box, sphere
    >>> inner = inward_offset(box(4, 4, 2), 0.5)
    >>> inner.exact, inner.method, inner.body.mass_properties().measure
    (True, 'convex polyhedron', 9.0)
    >>> ball = inward_offset(sphere(1), 0.25).body
    >>> ball.mass_properties().measure == sphere(0.75).mass_properties().measure
    True
    >>> inward_offset(box(1, 1, 1), 0.5).empty
    True
    """
    exact = closed_form_offset(body, distance)  # checks the distance and the body
    return exact if exact is not None else _level_set_offset(body, float(distance), step, extra)


# ------------------------------------------------------------ closed forms
def closed_form_offset(body: Body, distance: float) -> InwardOffset | None:
    """The exact inward offset by ``distance`` m when ``body`` has a closed form (see the
    module's doc), else None (without computing a level set).

    >>> from plumbob.bodies.primitives import box
    >>> closed_form_offset(box(4, 4, 2), 0.5).method
    'convex polyhedron'
    """
    t = float(distance)
    if not (np.isfinite(t) and t > 0):
        raise GeometryError(f"an inward offset needs a positive distance, not {distance!r}")
    if body.dim != 3 or body.kind not in ("solid",):
        raise GeometryError(f"only a solid has an inward offset, not a {body.kind}")
    closed = _closed_form(body, t)
    return None if closed is None else InwardOffset(closed[0], t, True, closed[1])


def _closed_form(body: Body, t: float) -> tuple[Body | None, str] | None:
    """(offset or None when empty, method) for bodies with a closed form, else None."""
    if isinstance(body, Transformed):
        inner = _closed_form(body.body, t)
        if inner is None or inner[0] is None:
            return inner
        return inner[0].transformed(body.matrix, body.offset), inner[1]
    if isinstance(body, MeshSolid):
        return _convex_mesh(body, t)
    if isinstance(body, Revolution):
        return _revolution(body, t)
    if isinstance(body, Extrusion):
        return _prism(body, t)
    return None


def _dented(triangles: np.ndarray) -> bool:
    """Whether a corner lies clearly beyond the plane of one of the mesh's 64 largest faces
    (by 1e-7 of its size): a quick sign that it is not convex, before its hull is taken."""
    corners = triangles.reshape(-1, 3)
    origin = corners.min(axis=0)
    normal = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    area = np.linalg.norm(normal, axis=1)
    # the largest faces, then faces spread over the mesh, sixteen at a time
    picks = np.concatenate((np.argsort(-area)[:64],
                            np.linspace(0, len(area) - 1, min(len(area), 192)).astype(np.int64)))
    picks = picks[area[picks] > 0]
    tolerance = 1e-7 * float(np.linalg.norm(np.ptp(corners, axis=0)))
    for start in range(0, len(picks), 16):
        big = picks[start:start + 16]
        unit = normal[big] / area[big, None]
        height = ((corners - origin) @ unit.T
                  - np.einsum("ij,ij->i", triangles[big, 0] - origin, unit))
        if np.any(height > tolerance):
            return True
    return False


def _halfspace_vertices(normals: np.ndarray, offsets: np.ndarray) -> np.ndarray | None:
    """Vertices of ``{x : normals @ x <= offsets}`` (a bounded convex set), or None if it
    has no interior."""
    from scipy.optimize import linprog
    from scipy.spatial import HalfspaceIntersection

    dim = normals.shape[1]
    # the Chebyshev centre: the deepest point, a strictly interior start for qhull
    norms = np.linalg.norm(normals, axis=1)
    cost = np.zeros(dim + 1)
    cost[-1] = -1.0
    lp = linprog(cost, A_ub=np.hstack((normals, norms[:, None])), b_ub=offsets,
                 bounds=[(None, None)] * dim + [(0, None)], method="highs")
    scale = float(np.abs(offsets).max() + 1.0)
    if lp.status != 0 or lp.x[-1] <= 1e-12 * scale:
        return None
    hs = HalfspaceIntersection(np.hstack((normals, -offsets[:, None])), lp.x[:dim])
    return hs.intersections


def _convex_mesh(body: MeshSolid, t: float) -> tuple[Body | None, str] | None:
    """Every face plane of a convex mesh moved in by ``t``; None when not convex."""
    from scipy.spatial import ConvexHull

    tri = body.triangles.astype(float)
    if _dented(tri):
        return None
    hull = ConvexHull(tri.reshape(-1, 3))
    volume = body.mass_properties().measure
    if abs(hull.volume - volume) > 1e-9 * volume:
        return None  # not convex
    normals, offsets = hull.equations[:, :3], -hull.equations[:, 3]
    normals, index = np.unique(np.round(np.hstack((normals, offsets[:, None])), 12), axis=0,
                               return_index=True)
    normals, offsets = hull.equations[index, :3], -hull.equations[index, 3]
    vertices = _halfspace_vertices(normals, offsets - t)
    if vertices is None:
        return None, "convex polyhedron"
    inner = ConvexHull(vertices)
    faces = vertices[inner.simplices]
    # qhull's simplices are unordered: wind each one outward, along its facet's normal
    n = np.cross(faces[:, 1] - faces[:, 0], faces[:, 2] - faces[:, 0])
    flip = np.einsum("ij,ij->i", n, inner.equations[:, :3]) < 0
    faces[flip] = faces[flip][:, ::-1]
    return replace(body, triangles=faces, moments=None, name=None), "convex polyhedron"


def _circle(ring: Ring) -> tuple[np.ndarray, float] | None:
    """(centre, radius) when ``ring`` is a full circle (two half-circle arcs)."""
    if len(ring.vertices) != 2 or ring.bulges is None or ring.controls is not None:
        return None
    if not np.allclose(np.abs(ring.bulges), 1.0, rtol=0, atol=1e-15) or ring.bulges[0] != ring.bulges[1]:
        return None
    return ring.vertices.mean(axis=0), float(np.linalg.norm(ring.vertices[1] - ring.vertices[0]) / 2)


def _polygon_offset(vertices: np.ndarray, t: float, fixed: np.ndarray) -> np.ndarray | None:
    """A convex CCW polygon with its edges moved in by ``t`` (edges flagged ``fixed`` stay),
    as CCW vertices; None when nothing is left."""
    from scipy.spatial import ConvexHull

    p, q = vertices, np.roll(vertices, -1, axis=0)
    d = q - p
    normals = np.stack((d[:, 1], -d[:, 0]), axis=1) / np.linalg.norm(d, axis=1)[:, None]
    offsets = np.einsum("ij,ij->i", normals, p) - np.where(fixed, 0.0, t)
    pts = _halfspace_vertices(normals, offsets)
    if pts is None:
        return None
    return pts[ConvexHull(pts).vertices]  # counter-clockwise in 2D


def _convex_polygon(region: Region) -> np.ndarray | None:
    """The CCW vertices of a region that is one straight-edged convex polygon, else None."""
    if len(region.rings) != 1 or region.rings[0].is_curved:
        return None
    v = region.rings[0].vertices.astype(float)
    d = np.roll(v, -1, axis=0) - v
    turns = d[:, 0] * np.roll(d, -1, axis=0)[:, 1] - d[:, 1] * np.roll(d, -1, axis=0)[:, 0]
    scale = float(np.abs(d).max()) ** 2
    if np.any(turns < -1e-12 * scale):
        return None  # a reflex corner (or clockwise)
    return v


def _revolution(body: Revolution, t: float) -> tuple[Body | None, str] | None:
    rings = body.profile.rings
    if len(rings) != 1:
        return None
    ring = rings[0]
    size = body.profile.size
    circle = _circle(ring)
    if circle is not None:  # a torus' tube
        centre, r = circle
        if r <= t:
            return None, "torus"
        return replace(body, profile=Region((Ring(np.array([[r - t, 0.0], [t - r, 0.0]]) + centre,
                                                  bulges=ring.bulges),)), name=None), "torus"
    v = ring.vertices
    if (len(v) == 2 and ring.bulges is not None and ring.controls is None
            and np.all(np.abs(v[:, 0]) <= 1e-12 * size) and sorted(np.abs(ring.bulges)) == [0.0, 1.0]):
        r = abs(float(v[1, 1] - v[0, 1])) / 2  # a ball: a half disc on the axis
        if r <= t:
            return None, "sphere"
        z = float(v[:, 1].mean())
        half = Ring(np.array([[0.0, z - (r - t)], [0.0, z + (r - t)]]), bulges=ring.bulges)
        return replace(body, profile=Region((half,)), name=None), "sphere"
    poly = _convex_polygon(body.profile)
    if poly is None:
        return None
    on_axis = np.abs(poly[:, 0]) <= 1e-12 * size
    inner = _polygon_offset(poly, t, on_axis & np.roll(on_axis, -1))
    if inner is None:
        return None, "revolved convex polygon"
    inner[:, 0] = np.maximum(inner[:, 0], 0.0)  # the axis edge stays at r = 0 exactly
    return replace(body, profile=Region((Ring(inner),)), name=None), "revolved convex polygon"


def _prism(body: Extrusion, t: float) -> tuple[Body | None, str] | None:
    if body.height <= 2 * t:
        return None, "prism"
    rings = body.profile.rings
    circle = _circle(rings[0]) if len(rings) == 1 else None
    if circle is not None:
        centre, r = circle
        if r <= t:
            return None, "prism"
        region = Region((Ring(np.array([[r - t, 0.0], [t - r, 0.0]]) + centre, bulges=rings[0].bulges),))
    else:
        poly = _convex_polygon(body.profile)
        if poly is None:
            return None
        inner = _polygon_offset(poly, t, np.zeros(len(poly), dtype=bool))
        if inner is None:
            return None, "prism"
        region = Region((Ring(inner),))
    inner_body = replace(body, profile=region, height=body.height - 2 * t, name=None)
    return inner_body.translated([0.0, 0.0, t]), "prism"


# ------------------------------------------------------------ level set
def level_set_manifold(triangles: np.ndarray, t: float, step: float, *, surface=None):
    """The manifold3d ``Manifold`` of the points more than ``t`` m inside the mesh, a level
    set of its signed distance on a ``step`` m grid (empty when nothing is); ``surface``:
    the mesh's :class:`plumbob.bodies.distance.SurfaceDistance`, when built already."""
    import manifold3d

    from .distance import distance_grid

    lo, hi = triangles.reshape(-1, 3).min(axis=0), triangles.reshape(-1, 3).max(axis=0)
    if np.any(hi - lo <= 2 * t):
        return manifold3d.Manifold()
    # the offset lies inside [lo + t, hi − t]; two steps more keep the grid's rim outside it
    lower, upper = lo + t - 2 * step, hi - t + 2 * step
    grid = distance_grid(triangles, lower, upper, step, band=(t - 2 * step, t + 2 * step),
                         surface=surface)
    values = (grid.values - t).reshape(-1).tolist()
    nx, ny, nz = grid.values.shape
    x0, y0, z0 = (float(v) for v in grid.origin)
    inv = 1.0 / step
    sy, sx = nz, ny * nz

    hx, hy, hz = nx - 1.000001, ny - 1.000001, nz - 1.000001

    def sdf(x: float, y: float, z: float) -> float:
        # trilinear interpolation of the grid (clamped to it: outside is outside); called
        # once a sample point, so plain comparisons rather than min() and max()
        fx, fy, fz = (x - x0) * inv, (y - y0) * inv, (z - z0) * inv
        fx = 0.0 if fx < 0.0 else (hx if fx > hx else fx)
        fy = 0.0 if fy < 0.0 else (hy if fy > hy else fy)
        fz = 0.0 if fz < 0.0 else (hz if fz > hz else fz)
        i, j, k = int(fx), int(fy), int(fz)
        u, v, w = fx - i, fy - j, fz - k
        n = i * sx + j * sy + k
        c00 = values[n] * (1 - w) + values[n + 1] * w
        c01 = values[n + sy] * (1 - w) + values[n + sy + 1] * w
        c10 = values[n + sx] * (1 - w) + values[n + sx + 1] * w
        c11 = values[n + sx + sy] * (1 - w) + values[n + sx + sy + 1] * w
        return (c00 * (1 - v) + c01 * v) * (1 - u) + (c10 * (1 - v) + c11 * v) * u

    bounds = [*(lower + step), *(upper - step)]
    return manifold3d.Manifold.level_set(sdf, bounds, step, 0.0)


def manifold_triangles(manifold) -> np.ndarray:
    """A manifold3d ``Manifold``'s triangles (n, 3, 3), m, in double precision."""
    mesh = manifold.to_mesh64()
    verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    return verts[np.asarray(mesh.tri_verts, dtype=np.int64)]


def _default_step(triangles: np.ndarray, t: float, size: float) -> float:
    """The smaller of ``t / 2`` and the size / 64 — or coarser, so the grid stays within
    half the sample limit (there is no option to ask for less on the command line)."""
    from ..limits import MAX_SAMPLES

    h = min(t / 2, size / DEFAULT_STEPS)
    extent = np.ptp(triangles.reshape(-1, 3), axis=0) - 2 * t
    cells = float(np.prod(np.maximum(extent, 0.0) + 5 * h))
    return max(h, (cells / (MAX_SAMPLES / 2)) ** (1 / 3))


def _level_set_offset(body: Body, t: float, step: float | None, extra: float) -> InwardOffset:
    triangles, own = body.surface(256)
    size = float(np.linalg.norm(np.ptp(triangles.reshape(-1, 3), axis=0)))
    h = float(step) if step is not None else _default_step(triangles, t, size)
    if not (np.isfinite(h) and h > 0):
        raise GeometryError(f"an offset step must be a positive number, not {step!r}")
    from .distance import SurfaceDistance

    surface = SurfaceDistance(triangles)
    fine = level_set_manifold(triangles, t + extra, h, surface=surface)
    if fine.is_empty() or fine.volume() <= 0:
        return InwardOffset(None, t, False, "level set", h, h)
    coarse = level_set_manifold(triangles, t + extra, 2 * h, surface=surface)
    error = abs(fine.volume() - coarse.volume()) / fine.volume()
    density = next(iter(body.densities()), None)
    inner = MeshSolid(manifold_triangles(fine), density if isinstance(density, float) else None,
                      exact=False, relative_error=error,
                      note=f"the inward offset is a level set on a {h:.3g} m grid")
    return InwardOffset(inner, t, False, "level set" if own else "level set of the faceted body",
                        h, h, error)
