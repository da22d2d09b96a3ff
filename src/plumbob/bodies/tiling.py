"""Cutting a body's shape into the signed cells a density field is integrated over.

A density field has no closed form, so its moments are sums over cells, each
with a quadrature rule (:mod:`plumbob.integrals.rules`):

* plane regions — the chord polygon's triangles (shapely's constrained
  Delaunay triangulation, signed per ring when the rings do not nest cleanly),
  and one cap cell per curved edge: circular caps in the arc's angle (exact to
  rounding: see :func:`plumbob.integrals.rules.arc_points_for_degree`),
  Bézier caps by Green's theorem along the curve (exact);
* closed meshes — the signed tetrahedra from a local origin near the mesh;
* prisms — the profile's cells times an interval in z (exact);
* solids of revolution — the profile's cells in (r, z) times a whole turn
  (exact for polynomial densities: a polynomial in x, y is a trigonometric
  polynomial in the angle).

Cells are signed: their sum is the body even where single cells reach outside
it (the fan of a non-convex polygon, a cap removed from a chord polygon).
"""

from __future__ import annotations

import numpy as np

from ..integrals.cells import ArcCells, BezierCells, Cells, ProductCells, SimplexCells
from ..integrals.polygon import bulge_arc_geometry
from .region import Region

__all__ = ["mesh_cells", "prism_cells", "region_cells", "revolution_cells"]


def _signed_area(v: np.ndarray) -> float:
    x, y = v[:, 0] - v[0, 0], v[:, 1] - v[0, 1]
    return float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)) / 2


def _orient(triangles: np.ndarray, sign: float) -> np.ndarray:
    """Triangles (m, 3, 2) turned so their orientation has ``sign``."""
    e = triangles[:, 1:] - triangles[:, :1]
    det = e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0]
    flip = np.sign(det) == -np.sign(sign)
    out = triangles.copy()
    out[flip, 1:] = out[flip, 1:][:, ::-1]
    return out


def _cdt(geometry) -> np.ndarray:
    import shapely

    parts = shapely.get_parts(shapely.constrained_delaunay_triangles(geometry))
    if len(parts) == 0:
        return np.zeros((0, 3, 2))
    coords = shapely.get_coordinates(parts)
    return coords.reshape(len(parts), 4, 2)[:, :3]


def _fan(v: np.ndarray) -> np.ndarray:
    """Signed fan of a closed polygon (n, 2) from its first vertex: exact for any polygon."""
    n = len(v)
    return np.stack((np.broadcast_to(v[0], (n - 2, 2)), v[1:-1], v[2:]), axis=1)


def _chord_triangles(region: Region) -> np.ndarray:
    """Signed triangles (m, 3, 2), world coordinates, tiling the region's chord polygons.

    Clean regions (outer rings disjoint, holes inside them and disjoint) are
    triangulated as one polygon, so no point falls in a hole; otherwise each
    ring is triangulated on its own and signed by its orientation (the sum is
    the same, by Green's theorem).
    """
    import shapely

    rings = [r.vertices for r in region.rings if len(r.vertices) >= 3]
    areas = [_signed_area(v) for v in rings]
    scale = sum(abs(a) for a in areas)
    if scale == 0:
        return np.zeros((0, 3, 2))
    rings = [(v, a) for v, a in zip(rings, areas) if abs(a) > 1e-15 * scale]
    polys = [shapely.Polygon(v) for v, _ in rings]
    simple = [bool(p.is_valid) for p in polys]
    if all(simple):
        shells = [p for p, (_, a) in zip(polys, rings) if a > 0]
        holes = [p for p, (_, a) in zip(polys, rings) if a < 0]
        tol = 1e-12 * scale
        union = shapely.union_all(shells)
        clean = abs(union.area - sum(p.area for p in shells)) <= tol
        if clean and holes:
            hole_union = shapely.union_all(holes)
            clean = (abs(hole_union.area - sum(p.area for p in holes)) <= tol
                     and abs(shapely.intersection(union, hole_union).area - hole_union.area) <= tol)
            union = shapely.difference(union, hole_union) if clean else union
        if clean:
            tris = _orient(_cdt(union), 1.0)
            if abs(_tri_area(tris) - sum(areas)) <= 1e-11 * scale:
                return tris
    pieces = []
    for poly, ok, (v, a) in zip(polys, simple, rings):
        tris = _cdt(poly) if ok else np.zeros((0, 3, 2))
        if not ok or abs(_tri_area(tris) - abs(a)) > 1e-11 * abs(a):
            pieces.append(_fan(v))  # signed by construction
        else:
            pieces.append(_orient(tris, np.sign(a)))
    return np.concatenate(pieces) if pieces else np.zeros((0, 3, 2))


def _tri_area(t: np.ndarray) -> float:
    e = t[:, 1:] - t[:, :1]
    return float(np.abs(e[:, 0, 0] * e[:, 1, 1] - e[:, 0, 1] * e[:, 1, 0]).sum() / 2)


def region_cells(region: Region, origin: np.ndarray) -> list[Cells]:
    """Signed cells tiling a plane region.

    Triangles of the chord polygon, one :class:`ArcCells` per circular edge (plus
    a rectangle of two triangles for a cap larger than a half disc) and one
    :class:`BezierCells` per Bézier edge.

    Parameters
    ----------
    region : Region
    origin : ndarray, shape (2,)
        m: the cells' coordinates are relative to it.

    Returns
    -------
    list of Cells
        Their signed sum is the region.

    Examples
    --------
    >>> from plumbob.bodies.primitives import disc_region, rectangle_region
    >>> [(type(c).__name__, len(c)) for c in region_cells(rectangle_region(2, 1), np.zeros(2))]
    [('SimplexCells', 2)]

    A disc's chord polygon (two vertices) has no area: two half-disc caps tile it.

    >>> [(type(c).__name__, len(c)) for c in region_cells(disc_region(1), np.zeros(2))]
    [('SimplexCells', 0), ('ArcCells', 2)]
    """
    origin = np.asarray(origin, dtype=float)
    tris = [_chord_triangles(region)]
    arcs: list[tuple[np.ndarray, ...]] = []
    beziers: list[np.ndarray] = []
    for ring in region.rings:
        if ring.bulges is not None:
            mask = ring.bulges != 0
            p0, p1 = ring._ends(mask)
            centre, radius, alpha, bisector = bulge_arc_geometry(p0, p1, ring.bulges[mask])
            normal = np.stack((-bisector[:, 1], bisector[:, 0]), axis=1)
            frame = np.stack((bisector, normal), axis=2)  # columns
            sign = np.sign(ring.bulges[mask])
            arcs.append((centre, radius, frame, alpha, sign))
            big = alpha > np.pi / 2
            if big.any():
                x0 = radius[big] * np.cos(alpha[big])
                h = radius[big] * np.sin(alpha[big])
                z = np.zeros_like(x0)
                corners = np.stack([np.stack(c, axis=1) for c in
                                    ((x0, -h), (z, -h), (z, h), (x0, h))], axis=1)  # (m, 4, 2)
                world = centre[big][:, None, :] + np.einsum("kij,knj->kni", frame[big], corners)
                for s in (1.0, -1.0):
                    pick = sign[big] == s
                    quads = world[pick]
                    t = np.concatenate((quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]))
                    tris.append(_orient(t, s))
        if ring.controls is not None:
            curved = ~np.isnan(ring.controls).any(axis=(1, 2))
            p0, p1 = ring._ends(curved)
            beziers.append(np.concatenate((p0[:, None], ring.controls[curved], p1[:, None]), axis=1))
    cells: list[Cells] = [SimplexCells(np.concatenate(tris) - origin)]
    if arcs:
        centre, radius, frame, alpha, sign = (np.concatenate(a) for a in zip(*arcs))
        box = np.tile(np.array([[0.0, 1.0], [0.0, 1.0]]), (len(radius), 1, 1))
        cells.append(ArcCells(box=box, centre=centre - origin, radius=radius, frame=frame,
                              half_angle=alpha, sign=sign))
    if beziers:
        ctrl = np.concatenate(beziers)
        along = ctrl[:, 3] - ctrl[:, 0]
        length = np.hypot(along[:, 0], along[:, 1])
        along = np.where(length[:, None] > 0, along / np.where(length > 0, length, 1)[:, None],
                         np.array([0.0, 1.0]))
        across = np.stack((along[:, 1], -along[:, 0]), axis=1)
        frame = np.stack((across, along), axis=2)
        box = np.tile(np.array([[0.0, 1.0], [0.0, 1.0]]), (len(ctrl), 1, 1))
        cells.append(BezierCells(box=box, controls=ctrl - origin, frame=frame))
    return cells


def prism_cells(profile: Region, height: float, origin: np.ndarray) -> list[Cells]:
    """Cells tiling the prism ``profile`` × [0, ``height``] (relative to ``origin`` (2,) in
    the profile's plane, z from 0).

    >>> from plumbob.bodies.primitives import rectangle_region
    >>> cells = prism_cells(rectangle_region(1, 2), 3.0, np.zeros(2))
    >>> [type(c).__name__ for c in cells], len(cells[0])
    (['ProductCells'], 2)
    """
    flat = region_cells(profile, origin)
    return [ProductCells(c, np.tile([0.0, float(height)], (len(c), 1)), "z") for c in flat]


def revolution_cells(profile: Region, z0: float) -> list[Cells]:
    """Cells tiling the solid swept by ``profile`` (in the (r, z) half-plane) turning a full
    circle about z: the profile's cells (relative to (0, ``z0``)) times a whole turn.

    >>> from plumbob.bodies.primitives import rectangle_region
    >>> cells = revolution_cells(rectangle_region(1, 2), 0.0)
    >>> cells[0].axis, bool(cells[0].periodic), cells[0].interval[0].tolist()
    ('phi', True, [0.0, 6.283185307179586])
    """
    flat = region_cells(profile, np.array([0.0, float(z0)]))
    return [ProductCells(c, np.tile([0.0, 2 * np.pi], (len(c), 1)), "phi", periodic=True)
            for c in flat]


def mesh_cells(triangles: np.ndarray, origin: np.ndarray) -> list[Cells]:
    """The signed tetrahedra (``origin``, a, b, c) of a closed mesh (n, 3, 3), relative to
    ``origin`` (3,): they sum to the solid the mesh bounds (the caller checks it is closed).

    >>> from plumbob.bodies.primitives import box
    >>> len(mesh_cells(box(1, 1, 1).triangles, np.zeros(3))[0])
    12
    """
    return [SimplexCells(np.asarray(triangles).astype(float) - origin)]
