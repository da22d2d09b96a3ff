"""Where a body touches a horizontal plane, and the polygon it stands on.

A body resting on a plane with ``down`` (a unit vector in the body's frame)
touches it at its lowest points. Its *support polygon* is the convex hull of
that contact, seen in the plane: a polygon, or a segment (a cylinder on its
side) or a point (a sphere) in degenerate cases. A lamina stands in its own
plane on a line, so its support is an interval.

Everything here is measured from the *foot* of the centre of mass — the point
of the plane straight below it — in a ground frame built deterministically
from ``down``:

* solids: ``e1`` is +x projected onto the plane (+y when ``down`` is along x),
  ``e2 = up × e1``, so ``(e1, e2, up)`` is right-handed and for ``down = −z``
  the ground axes are +x and +y;
* laminas: ``e1`` is ``up`` turned a quarter turn clockwise, so for
  ``down = −y`` it is +x.

Contact tolerance
-----------------
Points within ``tolerance`` (m) of the lowest count as touching (default
``1e-6`` of the body's size). Curved surfaces are sampled, so a sample next to
the true contact may fall within the tolerance and widen the contact by about
``√(2ρ·tolerance)`` (ρ the radius of curvature). Edges of the support polygon
near enough to the foot for this to matter are re-measured with exact support
points: tilting ``down`` by a small angle ε toward the edge moves the lowest
point of a curved surface by ``ρ·ε`` but leaves a polytope's vertex in place,
and a Richardson step (two angles) removes the ``ρ·ε`` term.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError, StabilityError
from ..massprops import MassProperties
from ..tolerances import HULL_ROUND_OFF, SLIVER
from .frame import GroundFrame, ground_frame  # re-exported, as are the body questions:
from .ground import (  # the ground's are ground.py's and frame.py's
    body_dim,
    body_size,
    default_down,
    hull_points,
    is_polytope,
    support_points,
    unit_vector,
)
from .planar import drop_collinear, planar_hull

__all__ = [
    "DEFAULT_RELATIVE_TOLERANCE",
    "GroundFrame",
    "Support",
    "body_dim",
    "default_down",
    "ground_frame",
    "support_polygon",
    "body_size",
    "contact_kind",
    "hull_points",
    "is_polytope",
    "support_points",
    "unit_vector",
]

DEFAULT_RELATIVE_TOLERANCE = 1e-6  # contact tolerance, relative to the body's size
_PROBE_ANGLE = 1e-3  # rad: tilt used to re-measure edges with exact support points
_PROBE_LIMIT = 32  # at most this many edges are re-measured


# ------------------------------------------------------------------ support
@dataclass(frozen=True)
class Support:
    """A body's support on the plane below it, measured from the foot of its centre of mass.

    kind: ``"polygon"``, ``"segment"`` or ``"point"`` (a lamina's support is a
        ``"segment"`` — an interval of its ground line — or a ``"point"``).
    frame: the ground frame (down and ground axes, body frame).
    center_of_mass: (dim,) m, body frame.
    com_height: height of the centre of mass above the plane, m (> 0).
    vertices: (k, dim − 1) m, ground coordinates relative to the foot; a polygon's
        vertices run counter-clockwise about ``up``.
    plane_point: (dim,) m, the foot of the centre of mass (a point of the plane), body frame.
    edge_starts, edge_ends: (m, dim − 1) m, the support boundary's edges; a segment has four
        (its two sides and its two ends, an end being a single point), a lamina's
        interval two (its ends), a point none.
    edge_normals: (m, dim − 1) outward unit normals of the edges, ground coordinates.
    edge_distances: (m,) m, signed distance from the foot to each edge's line, positive
        inside; edges within reach of a curved contact's sampling are re-measured exactly.
    tolerance: the contact tolerance used, m.
    contact: (n, dim) m, the contact points found (body frame).
    size: the body's size, m (:func:`body_size`): what relative tolerances (the default
        contact tolerance, round-off in reports) are fractions of.
    """

    kind: str
    frame: GroundFrame
    center_of_mass: np.ndarray
    com_height: float
    vertices: np.ndarray
    plane_point: np.ndarray
    edge_starts: np.ndarray
    edge_ends: np.ndarray
    edge_normals: np.ndarray
    edge_distances: np.ndarray
    tolerance: float
    contact: np.ndarray
    size: float

    @property
    def dim(self) -> int:
        return self.frame.dim

    def to_body(self, ground: np.ndarray) -> np.ndarray:
        """Points of the plane (…, dim), body frame, from ground coordinates (…, dim − 1)."""
        return self.plane_point + self.frame.from_ground(ground)

    @property
    def polygon(self) -> np.ndarray:
        """The support polygon's vertices as points of the plane, body frame, (k, dim) m."""
        return self.to_body(self.vertices)

    def distance_to_boundary(self) -> float:
        """Euclidean distance from the foot to the support set (0 when the foot is in it), m."""
        v = self.vertices
        if self.kind == "point" or len(v) == 1:
            return float(np.linalg.norm(v[0]))
        a, b = v, np.roll(v, -1, axis=0)
        if self.kind == "segment" or len(v) == 2:
            a, b = v[:1], v[1:2]
        d = b - a
        lengths = np.einsum("ij,ij->i", d, d)
        t = np.clip(np.einsum("ij,ij->i", -a, d) / np.where(lengths > 0, lengths, 1.0), 0.0, 1.0)
        closest = a + t[:, None] * d
        return float(np.min(np.linalg.norm(closest, axis=1)))

    def nearest_point(self) -> np.ndarray:
        """The point of the support set nearest the foot, ground coordinates (dim − 1,)."""
        v = self.vertices
        if len(v) == 1:
            return v[0].copy()
        a, b = (v[:1], v[1:2]) if len(v) == 2 else (v, np.roll(v, -1, axis=0))
        d = b - a
        lengths = np.einsum("ij,ij->i", d, d)
        t = np.clip(np.einsum("ij,ij->i", -a, d) / np.where(lengths > 0, lengths, 1.0), 0.0, 1.0)
        closest = a + t[:, None] * d
        return closest[np.argmin(np.linalg.norm(closest, axis=1))]

    def ray_distance(self, direction: np.ndarray) -> float:
        """How far the foot can move along the ground ``direction`` (dim − 1,) before it leaves
        the support, m (0 or less when it is already on or outside the boundary)."""
        n = self.edge_normals
        if len(n) == 0:
            return -self.distance_to_boundary()
        cos = n @ direction
        facing = cos > 1e-12
        if not facing.any():
            return float("inf")
        return float(np.min(self.edge_distances[facing] / cos[facing]))


def _hull_2d(q: np.ndarray, tolerance: float) -> tuple[str, np.ndarray]:
    """Kind and vertices of the convex hull of ground points ``q`` (n, 2)."""
    centre = q.mean(axis=0)
    spread = q - centre
    if len(q) == 1 or np.max(np.linalg.norm(spread, axis=1)) <= tolerance:
        return "point", centre[None, :]
    _, _, vt = np.linalg.svd(spread, full_matrices=False)
    along, across = spread @ vt[0], spread @ vt[1]
    if np.ptp(across) <= tolerance or len(q) < 3:
        ends = q[[np.argmin(along), np.argmax(along)]]
        return "segment", ends
    try:
        corners = planar_hull(q)
    except GeometryError:
        ends = q[[np.argmin(along), np.argmax(along)]]
        return "segment", ends
    # corners collinear to rounding error are not corners (qhull's hull dropped them too)
    size = float(np.max(np.linalg.norm(spread, axis=1)))
    return "polygon", drop_collinear(q[corners], HULL_ROUND_OFF * size)  # counter-clockwise


def _edges(kind: str, v: np.ndarray, dim: int):
    """Edges (starts, ends, outward normals) of a support set with vertices ``v``."""
    if dim == 2:  # a lamina: an interval of its ground line
        lo, hi = float(v[:, 0].min()), float(v[:, 0].max())
        starts = np.array([[hi], [lo]])
        normals = np.array([[1.0], [-1.0]])
        return starts, starts.copy(), normals
    if kind == "point":
        empty = np.zeros((0, 2))
        return empty, empty, empty
    if kind == "segment":
        a, b = v
        t = (b - a) / np.linalg.norm(b - a)
        side = np.array([t[1], -t[0]])
        starts = np.array([a, b, b, a])
        ends = np.array([b, a, b, a])
        normals = np.array([side, -side, t, -t])
        return starts, ends, normals
    starts, ends = v, np.roll(v, -1, axis=0)
    d = ends - starts
    normals = np.stack((d[:, 1], -d[:, 0]), axis=1) / np.linalg.norm(d, axis=1)[:, None]
    return starts, ends, normals


def _curved_extent(body, frame: GroundFrame, com: np.ndarray, normal: np.ndarray,
                   tol: float, size: float) -> float | None:
    """The true contact's extent along the ground ``normal`` (from the foot), m, when the
    lowest point rolls with the tilt as on a smooth curved surface; None otherwise.

    A smooth surface moves its lowest point by ρε for a tilt ε: the moves over
    (ε, ε/2) and (ε/2, ε/4) are in the ratio 2, and a Richardson step removes them.
    Jumps between a fine mesh's vertices are not in that ratio and are left alone.
    """
    probe_tol = max(tol, 1e-3 * size)  # exact points come with any tolerance
    s1, s2, s4 = (_probe(body, frame, com, normal, _PROBE_ANGLE / k, probe_tol)
                  for k in (1, 2, 4))
    near, far = s2 - s4, s1 - s2
    if not (far > tol and near > 0 and 1.6 <= far / near <= 2.4):
        return None
    return _snap(2.0 * s4 - s2, tol)


def _probe(body, frame: GroundFrame, com: np.ndarray, normal: np.ndarray,
           angle: float, tolerance: float) -> float:
    """Offset along the ground ``normal`` (from the foot) of the body's lowest point when
    ``down`` is tilted by ``angle`` rad toward that normal."""
    n = frame.from_ground(normal)
    u = np.cos(angle) * frame.down + np.sin(angle) * n
    pts = support_points(body, u, tolerance)
    lowest_point = pts[np.argmax(pts @ u)]
    return float((lowest_point - com) @ n)


def support_polygon(body, down=None, *, tolerance: float | None = None,
                    props: MassProperties | None = None) -> Support:
    """The support of ``body`` resting on a horizontal plane below it.

    body: any plumbob body (or particle system).
    down: the direction of gravity in the body's frame, (dim,); default −z for
        solids, −y for a lamina.
    tolerance: contact tolerance, m; default 1e-6 of the body's size.
    props: the body's mass properties, if already computed.

    Raises :class:`StabilityError` when the centre of mass is not above the plane.

    >>> from plumbob.bodies.primitives import box
    >>> s = support_polygon(box(1, 1, 4))
    >>> s.kind, s.com_height, s.edge_distances.round(12).tolist()
    ('polygon', 2.0, [0.5, 0.5, 0.5, 0.5])
    """
    props = body.mass_properties() if props is None else props
    dim = body_dim(body, props)
    com = np.asarray(props.center_of_mass, dtype=float)
    if com.size < dim:
        com = np.pad(com, (0, dim - com.size))
    com = com[:dim]
    down = default_down(dim) if down is None else unit_vector(down, dim)
    size = body_size(body)
    if not np.isfinite(size) or size <= 0:
        raise GeometryError("the body has no extent to stand on")
    tol = DEFAULT_RELATIVE_TOLERANCE * size if tolerance is None else float(tolerance)
    if not (np.isfinite(tol) and tol > 0):
        raise StabilityError(f"the contact tolerance must be a positive length, not {tol:g}")
    if tol >= 0.1 * size:  # else every point touches and the verdict is about nothing
        raise StabilityError(f"the contact tolerance {tol:g} m is not small beside the body "
                             f"(size {size:.6g} m); the default is 1e-6 of the size")
    frame = ground_frame(down)
    pts = support_points(body, down, tol)
    depth = pts @ down
    height = float(depth.max() - com @ down)
    if abs(height) <= tol:
        raise StabilityError(
            "the body lies flat in the plane it rests on (its centre of mass is at the "
            "plane's height), so it has nothing to stand or topple on: give another down "
            "direction")
    if height < 0:
        raise StabilityError(
            "the centre of mass is not above the plane the body rests on "
            f"(its height is {height:.3g} m): it lies outside the body's hull — "
            "is the mesh open, or a density negative?")
    pts = pts[depth >= depth.max() - tol]
    foot = com + height * down
    q = frame.to_ground(pts - com)
    if dim == 2:
        lo, hi = q[:, 0].min(), q[:, 0].max()
        kind = "point" if hi - lo <= tol else "segment"
        vertices = np.array([[lo]]) if kind == "point" else np.array([[lo], [hi]])
    else:
        kind, vertices = _hull_2d(q, tol)
    starts, ends, normals = _edges(kind, vertices, dim)
    distances = _distances(starts, normals)
    if not is_polytope(body, size):  # sampled curved surfaces: their true contact
        exact = _remeasure(body, frame, com, normals, distances, tol, size)
        if np.any(exact < distances - tol):  # cut the sampling's widening away (not round-off)
            kind, vertices = _clip(kind, vertices, normals, exact, dim, tol)
            starts, ends, normals = _edges(kind, vertices, dim)
            distances = _distances(starts, normals)
        distances = _refine_critical(body, frame, com, normals, distances, tol, size)
    return Support(kind, frame, com, height, vertices, foot, starts, ends, normals,
                   distances, tol, pts, size)


def _distances(starts: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """Signed distances from the foot (the origin) to the edges' lines, positive inside."""
    return np.einsum("ij,ij->i", starts, normals) if len(normals) else np.zeros(0)


def _clip(kind: str, vertices: np.ndarray, normals: np.ndarray, limits: np.ndarray, dim: int,
          tol: float) -> tuple[str, np.ndarray]:
    """The support set cut down to ``normal · x ≤ limit`` for every edge."""
    if dim == 2:
        hi, lo = limits[0], -limits[1]
        if hi - lo <= tol:
            return "point", np.array([[(hi + lo) / 2]])
        return "segment", np.array([[lo], [hi]])
    poly = vertices
    for n, limit in zip(normals, limits):
        side = poly @ n - limit
        if np.all(side <= 0):
            continue
        out = []
        for i in range(len(poly)):
            p, q = poly[i], poly[(i + 1) % len(poly)]
            sp, sq = side[i], side[(i + 1) % len(poly)]
            if sp <= 0:
                out.append(p)
            if (sp < 0 < sq) or (sq < 0 < sp):
                out.append(p + (q - p) * (sp / (sp - sq)))
        if not out:  # inconsistent limits: keep the closest vertex
            out = [poly[np.argmin(side)]]
        poly = np.array(out)
    return _hull_2d(poly, tol)


def _refine_critical(body, frame: GroundFrame, com: np.ndarray, normals: np.ndarray,
                     distances: np.ndarray, tol: float, size: float) -> np.ndarray:
    """The nearest edge re-measured with exact support points.

    A curved contact far from the foot (a torus lying flat) is widened by its sampling
    like a near one; the Richardson step measures the nearest edge exactly. A polytope's
    vertex, or a flat base's rim (sampled within ``tol/4``), does not move with the tilt
    and keeps its distance.
    """
    if len(normals) == 0:
        return distances
    k = int(np.argmin(distances))
    if not distances[k] > tol:
        return distances
    extent = _curved_extent(body, frame, com, normals[k], tol, size)
    if extent is not None:  # a curved contact (a torus lying flat): its exact extent
        distances = distances.copy()
        distances[k] = min(distances[k], extent)
    return distances


def _remeasure(body, frame: GroundFrame, com: np.ndarray, normals: np.ndarray,
               distances: np.ndarray, tol: float, size: float) -> np.ndarray:
    """Edge distances with curved contacts' sampling removed (see the module notes)."""
    if len(normals) == 0:
        return distances
    reach = 4.0 * np.sqrt(2.0 * tol * size)
    near = np.flatnonzero(np.abs(distances) <= reach)
    if len(near) == 0:
        return distances
    if len(near) > _PROBE_LIMIT:  # the nearest edge and others spread evenly around
        angles = np.arctan2(normals[near, -1], normals[near, 0])
        spread = near[np.argsort(angles, kind="stable")]
        picks = spread[np.linspace(0, len(spread) - 1, _PROBE_LIMIT - 1).astype(int)]
        near = np.unique(np.append(picks, near[np.argmin(np.abs(distances[near]))]))
    out = distances.copy()
    for i in near:
        extent = _curved_extent(body, frame, com, normals[i], tol, size)
        if extent is not None:  # the lowest point rolls with the tilt: a curved contact
            out[i] = min(out[i], extent)
    return out


def _snap(distance: float, tol: float) -> float:
    """A re-measured distance within the tolerance of the foot is the foot itself: 0."""
    return 0.0 if abs(distance) <= tol else distance


def contact_kind(sup: Support, size: float) -> str | None:
    """``"point"``, ``"line"`` or ``"sliver"`` when a solid touches the ground with one
    (``size``: the body's, m; a sliver is a support polygon narrower than
    :data:`~plumbob.tolerances.SLIVER` of it, a segment shorter than that a point's
    sampling), else None."""
    if sup.dim != 3:
        return None
    if sup.kind == "point":
        return "point"
    if sup.kind == "segment":
        length = float(np.linalg.norm(sup.vertices[1] - sup.vertices[0]))
        return "line" if length >= SLIVER * size else "point"
    v = sup.vertices  # the polygon's width: its least extent across an edge
    across = np.einsum("ij,ij->i", sup.edge_starts, sup.edge_normals)[:, None] - (
        sup.edge_normals @ v.T)
    return "sliver" if float(across.max(axis=1).min()) < SLIVER * size else None
