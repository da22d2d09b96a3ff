"""Plane regions bounded by lines, circular arcs and cubic Béziers, kept exact.

A :class:`Ring` is a closed boundary: vertices joined by edges; edge ``i`` runs
from ``vertices[i]`` to ``vertices[(i + 1) % n]`` and is straight, a circular
arc (its DXF *bulge* ``tan(sweep / 4)`` non-zero; positive turns
counter-clockwise) or a cubic Bézier (two control points). A :class:`Region` is
a set of rings: outer boundaries counter-clockwise, holes clockwise, so the
signed sum of their moments is the region's.

Rigid motions act on the exact description (mirrors flip bulges and
orientation); :meth:`Region.to_shapely` flattens curves only when a boolean
operation or a picture needs it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import GeometryError
from ..integrals.polygon import (
    AreaMoments,
    arc_cap_moments,
    bulge_arc_geometry,
    cubic_cap_moments,
    polygon_moments,
    rings_moments,
)
from ..tolerances import sampling_tolerance

__all__ = ["Ring", "Region"]


def _frozen(array: np.ndarray | None) -> np.ndarray | None:
    if array is None:
        return None
    array = np.ascontiguousarray(array, dtype=float)
    array.setflags(write=False)
    return array


def _edge_words(edges: int, arcs: int, beziers: int) -> str:
    """``"4 edges (2 arcs, 1 Bézier)"``."""
    curved = [f"{n} {what}{'s' if n > 1 else ''}" for n, what in ((arcs, "arc"), (beziers, "Bézier"))
              if n]
    return f"{edges} edge{'s' if edges > 1 else ''}" + (f" ({', '.join(curved)})" if curved else "")


@dataclass(frozen=True, eq=False, repr=False)
class Ring:
    """A closed boundary.

    vertices: (n, 2) m, not repeating the first at the end.
    bulges: (n,) or None; ``tan(sweep/4)`` of edge i, 0 for a straight edge.
    controls: (n, 2, 2) or None; the two inner control points of a cubic
        Bézier edge i, NaN for other edges.
    """

    vertices: np.ndarray
    bulges: np.ndarray | None = None
    controls: np.ndarray | None = None

    def __post_init__(self) -> None:
        v = np.asarray(self.vertices, dtype=float)
        if v.ndim != 2 or v.shape[1] != 2:
            raise GeometryError("a ring needs an (n, 2) array of vertices")
        if len(v) > 1 and np.array_equal(v[0], v[-1]):
            v = v[:-1]
            if self.bulges is not None:
                object.__setattr__(self, "bulges", np.asarray(self.bulges)[:-1])
            if self.controls is not None:
                object.__setattr__(self, "controls", np.asarray(self.controls)[:-1])
        if not np.all(np.isfinite(v)):
            raise GeometryError("a ring has a coordinate that is not a finite number")
        object.__setattr__(self, "vertices", _frozen(v))
        bulges = self.bulges
        if bulges is not None:
            bulges = np.asarray(bulges, dtype=float).reshape(-1)
            if bulges.shape != (len(v),) or not np.all(np.isfinite(bulges)):
                raise GeometryError("a ring needs one finite bulge per edge")
            bulges = None if not bulges.any() else bulges
        object.__setattr__(self, "bulges", _frozen(bulges))
        controls = self.controls
        if controls is not None:
            controls = np.asarray(controls, dtype=float)
            if controls.shape != (len(v), 2, 2):
                raise GeometryError("a ring needs an (n, 2, 2) array of Bézier controls")
            curved = ~np.isnan(controls).any(axis=(1, 2))
            if not np.all(np.isfinite(controls[curved])):
                raise GeometryError("a Bézier control point is not a finite number")
            if bulges is not None and np.any(curved & (bulges != 0)):
                raise GeometryError("an edge cannot be both an arc and a Bézier curve")
            controls = None if not curved.any() else controls
        object.__setattr__(self, "controls", _frozen(controls))

    @classmethod
    def _checked(cls, vertices: np.ndarray) -> Ring:
        """A straight ring from vertices already checked: (n, 2) finite floats, the first
        not repeated at the end (a caller that checked many rings at once)."""
        ring = object.__new__(cls)
        object.__setattr__(ring, "vertices", _frozen(vertices))
        object.__setattr__(ring, "bulges", None)
        object.__setattr__(ring, "controls", None)
        return ring

    # ----------------------------------------------------------- queries
    @property
    def is_curved(self) -> bool:
        return self.bulges is not None or self.controls is not None

    def edge_counts(self) -> tuple[int, int, int]:
        """(edges, circular arcs, Bézier curves).

        >>> Ring(np.array([[1.0, 0.0], [-1.0, 0.0]]), bulges=np.array([1.0, 1.0])).edge_counts()
        (2, 2, 0)
        """
        arcs = 0 if self.bulges is None else int(np.count_nonzero(self.bulges))
        beziers = 0 if self.controls is None else int((~np.isnan(self.controls).any(axis=(1, 2))).sum())
        return len(self.vertices), arcs, beziers

    def __repr__(self) -> str:
        return f"<Ring {_edge_words(*self.edge_counts())}>"

    def _ends(self, mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        idx = np.flatnonzero(mask)
        return self.vertices[idx], self.vertices[(idx + 1) % len(self.vertices)]

    def moments(self, origin: np.ndarray, degree: int = 2) -> AreaMoments:
        """Signed moments about ``origin`` (see :mod:`plumbob.integrals.polygon`)."""
        total = polygon_moments(self.vertices, origin, degree)
        if self.bulges is not None:
            arcs = self.bulges != 0
            p0, p1 = self._ends(arcs)
            total = total + arc_cap_moments(p0, p1, self.bulges[arcs], origin, degree)
        if self.controls is not None:
            curved = ~np.isnan(self.controls).any(axis=(1, 2))
            p0, p1 = self._ends(curved)
            ctrl = np.concatenate((p0[:, None], self.controls[curved], p1[:, None]), axis=1)
            total = total + cubic_cap_moments(ctrl, origin, degree)
        return total

    def transformed(self, matrix: np.ndarray, offset: np.ndarray) -> Ring:
        """Turned or mirrored by the 2×2 orthogonal ``matrix``, then moved by ``offset``."""
        matrix = np.asarray(matrix, dtype=float)
        vertices = self.vertices @ matrix.T + offset
        controls = None if self.controls is None else self.controls @ matrix.T + offset
        bulges = self.bulges
        if np.linalg.det(matrix) < 0 and bulges is not None:
            bulges = -bulges
        return Ring(vertices, bulges, controls)

    def reversed(self) -> Ring:
        """The same curve run the other way (flips the sign of its area)."""
        v = self.vertices[::-1]
        v = np.roll(v, 1, axis=0)  # edge i of the result is edge n-1-i of self, reversed
        bulges = None if self.bulges is None else -self.bulges[::-1]
        controls = None if self.controls is None else self.controls[::-1, ::-1]
        return Ring(v, bulges, controls)

    def flattened(self, tolerance: float, segments: int | None = None) -> np.ndarray:
        """Vertices (m, 2) of a polygon within ``tolerance`` (m) of every curved edge.

        With ``segments``, arcs are cut into that many chords per full turn instead
        (the explicit count booleans use, the same in 2D and 3D).
        """
        if not self.is_curved:
            return self.vertices
        n = len(self.vertices)
        pieces = []
        for i in range(n):  # per edge, not per vertex: curved rings are short
            p0, p1 = self.vertices[i], self.vertices[(i + 1) % n]
            if self.bulges is not None and self.bulges[i] != 0:
                centre, r, alpha, u = bulge_arc_geometry(p0[None], p1[None], self.bulges[i : i + 1])
                r, alpha = r[0], alpha[0]
                if segments is not None:
                    steps = max(2, int(np.ceil(segments * alpha / np.pi)))
                else:
                    steps = max(2, int(np.ceil(alpha / np.arccos(max(-1.0, 1 - tolerance / r)))))
                start = np.arctan2(*(p0 - centre[0])[::-1])
                sweep = 2 * alpha * np.sign(self.bulges[i])
                angles = start + sweep * np.arange(steps) / steps
                pieces.append(centre[0] + r * np.stack((np.cos(angles), np.sin(angles)), axis=1))
            elif self.controls is not None and not np.isnan(self.controls[i]).any():
                c1, c2 = self.controls[i]
                spread = np.abs(np.array([p0 - 2 * c1 + c2, c1 - 2 * c2 + p1])).max()
                steps = max(2, int(np.ceil(np.sqrt(0.75 * spread / tolerance))) + 1)
                t = (np.arange(steps) / steps)[:, None]
                pieces.append(
                    (1 - t) ** 3 * p0
                    + 3 * (1 - t) ** 2 * t * c1
                    + 3 * (1 - t) * t**2 * c2
                    + t**3 * p1
                )
            else:
                pieces.append(p0[None])
        return np.concatenate(pieces)


@dataclass(frozen=True, eq=False, repr=False)
class Region:
    """A plane region: outer rings counter-clockwise, hole rings clockwise."""

    rings: tuple[Ring, ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "rings", tuple(self.rings))
        if not self.rings:
            raise GeometryError("a region needs at least one ring")

    @property
    def is_curved(self) -> bool:
        return any(r.is_curved for r in self.rings)

    def describe(self) -> str:
        """Its rings and edges in a few words, for reprs.

        >>> from plumbob.bodies.primitives import annulus, rectangle_region
        >>> rectangle_region(2, 1).describe(), annulus(1, 2).region.describe()
        ('1 ring of 4 edges', '2 rings of 4 edges (4 arcs)')
        """
        counts = np.array([r.edge_counts() for r in self.rings]).sum(axis=0)
        rings = len(self.rings)
        return f"{rings} ring{'s' if rings > 1 else ''} of {_edge_words(*counts)}"

    def __repr__(self) -> str:
        return f"<Region {self.describe()}>"

    @property
    def bounds(self) -> np.ndarray:
        """(2, 2): [[xmin, ymin], [xmax, ymax]] of the vertices and control points, m."""
        pts = [r.vertices for r in self.rings]
        pts += [
            r.controls[~np.isnan(r.controls)].reshape(-1, 2)
            for r in self.rings
            if r.controls is not None
        ]
        for r in self.rings:
            if r.bulges is not None:
                arcs = r.bulges != 0
                p0, p1 = r._ends(arcs)
                centre, radius, _, u = bulge_arc_geometry(p0, p1, r.bulges[arcs])
                pts.append(centre + u * radius[:, None])
        allpts = np.concatenate(pts)
        return np.array([allpts.min(axis=0), allpts.max(axis=0)])

    @property
    def size(self) -> float:
        """The diagonal of the bounding box, m."""
        return float(np.linalg.norm(np.ptp(self.bounds, axis=0)))

    def local_origin(self) -> np.ndarray:
        """A point near the region to sum products about: a vertex of its first ring
        (every offset is then at most the region's size)."""
        return self.rings[0].vertices[0].copy()

    def moments(self, origin: np.ndarray | None = None, degree: int = 2) -> AreaMoments:
        """Signed moments of the region about ``origin`` (default: a local origin)."""
        origin = self.local_origin() if origin is None else np.asarray(origin, dtype=float)
        straight = [r.vertices for r in self.rings if not r.is_curved]
        total = rings_moments(straight, origin, degree)
        for ring in self.rings:
            if ring.is_curved:
                total = total + ring.moments(origin, degree)
        return total

    def transformed(
        self, matrix: np.ndarray, offset: np.ndarray | list[float] = (0.0, 0.0)
    ) -> Region:
        """Turned or mirrored by a 2×2 orthogonal matrix about (0, 0), then moved.

        A mirror reverses every ring, so outer rings stay counter-clockwise.
        """
        matrix = np.asarray(matrix, dtype=float)
        offset = np.asarray(offset, dtype=float)
        rings = tuple(r.transformed(matrix, offset) for r in self.rings)
        if np.linalg.det(matrix) < 0:
            rings = tuple(r.reversed() for r in rings)
        return Region(rings)

    def translated(self, offset: np.ndarray | list[float]) -> Region:
        return self.transformed(np.eye(2), offset)

    def to_shapely(self, tolerance: float | None = None, segments: int | None = None):
        """A shapely (Multi)Polygon; curved edges flattened to ``tolerance`` m
        (default 1e-4 of the region's size), arcs to ``segments`` per turn if given."""
        import shapely

        tol = sampling_tolerance(self.size, tolerance)
        rings = [r.flattened(tol, segments) for r in self.rings]
        signs = [polygon_moments(v, v.mean(axis=0)).m0 for v in rings]
        shells = [shapely.Polygon(v) for v, s in zip(rings, signs) if s > 0]
        holes = [shapely.Polygon(v) for v, s in zip(rings, signs) if s < 0]
        result = shapely.union_all(shells)
        if holes:
            result = shapely.difference(result, shapely.union_all(holes))
        return result

    @classmethod
    def many_from_shapely(cls, geometries) -> list[Region]:
        """One region per shapely (Multi)Polygon of ``geometries``, as :meth:`from_shapely`
        makes each, in a few vectorised calls over all of them (a map of 10⁴ islands
        costs no Python loop over its polygons, only the making of their rings).

        >>> import shapely
        >>> Region.many_from_shapely([shapely.box(0, 0, 1, 1), shapely.MultiPolygon(
        ...     [shapely.box(2, 0, 3, 1), shapely.box(0, 2, 3, 3).difference(shapely.box(1, 2.2, 2, 2.8))])])
        [<Region 1 ring of 4 edges>, <Region 3 rings of 12 edges>]
        """
        import shapely

        geometries = shapely.normalize(np.asarray(geometries, dtype=object))
        polygons, owner = shapely.get_parts(geometries, return_index=True)
        keep = ~shapely.is_empty(polygons) & (
            shapely.get_type_id(polygons) == shapely.GeometryType.POLYGON)
        polygons, owner = polygons[keep], owner[keep]
        if len(np.unique(owner)) < len(geometries):
            raise GeometryError("the geometry has no polygon with area")
        polygons = _oriented(polygons)
        rings, ring_polygon = shapely.get_rings(polygons, return_index=True)
        xy, point_ring = shapely.get_coordinates(rings, return_index=True)
        if not np.all(np.isfinite(xy)):
            raise GeometryError("a ring has a coordinate that is not a finite number")
        starts = np.flatnonzero(np.r_[True, point_ring[1:] != point_ring[:-1]])
        ends = np.r_[starts[1:], len(point_ring)] - 1  # a ring repeats its first point last
        made = [Ring._checked(xy[a:b]) for a, b in zip(starts.tolist(), ends.tolist())]
        ring_owner = owner[ring_polygon].tolist()
        grouped: list[list[Ring]] = [[] for _ in range(len(geometries))]
        for ring, k in zip(made, ring_owner):  # per ring: rings are what a region holds
            grouped[k].append(ring)
        return [cls(tuple(group)) for group in grouped]

    @classmethod
    def from_shapely(cls, geometry) -> Region:
        """A region from a shapely Polygon or MultiPolygon (orientation normalised): its
        polygons' exteriors, then each one's holes, as the rings of the region (see
        :meth:`many_from_shapely`, which makes many at once)."""
        return cls.many_from_shapely([geometry])[0]


def _oriented(polygons: np.ndarray) -> np.ndarray:
    """Shapely polygons with their exteriors counter-clockwise and holes clockwise."""
    import shapely

    if hasattr(shapely, "orient_polygons"):
        return shapely.orient_polygons(polygons)
    return np.array([shapely.geometry.polygon.orient(p, 1.0) for p in polygons],  # shapely 2.0
                    dtype=object)
