"""Does a triangle soup close? The one closure rule, and the one pass that feeds it.

The rule: **a surface is closed when no loop of its unshared edges spans an
area** — more than :data:`CLOSURE_TOLERANCE` of the surface's area — once
vertices closer than the weld tolerance (:data:`plumbob.tolerances.WELD`) are one.

* Every edge shared (by faces wound opposite ways): closed.
* A hole — a loop of unshared edges around a missing patch — spans the patch's
  vector area: open. This catches what the vector area of the whole surface
  cannot: an open tube, or a cube without top and bottom, has holes whose
  areas cancel.
* A T-junction — a vertex lying on another face's edge — leaves unshared
  edges too, but their loop is a slit along that edge and spans nothing:
  closed, and the divergence theorem's volume is exact.

The sum of all loops' vector areas is minus the surface's own vector area
(Σ of its faces' area vectors), so the cheap necessary test :func:`is_closed`
(one pass, no topology) is this rule summed. :func:`edges_pair` certifies the
common case — every directed edge met by its reverse — in one more pass,
without sorting; only when it fails is the topology built.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..arrays import connected_components
from ..errors import GeometryError, fmt_point
from ..integrals.mesh import VolumeMoments, triangle_soup_moments
from ..tolerances import weld_tolerance
from .weld import point_keys

if TYPE_CHECKING:
    from .topology import Topology

# the topology (a sort of every edge) loads only for a mesh whose cheap tests fail

__all__ = ["CLOSURE_TOLERANCE", "ZERO_VOLUME", "Holes", "SurfaceSummary", "edges_pair", "holes",
           "join_at_slits", "paired_keys",
           "is_closed", "open_message", "require_closed", "require_sums_close", "surface_summary"]

#: |vector area| / area above which a surface is open
CLOSURE_TOLERANCE = 1e-9
#: triangles per pass of :func:`edges_pair`
PAIR_CHUNK = 1 << 14
#: volume below this share of area^1.5 counts as none
ZERO_VOLUME = 1e-9


def is_closed(vector_area: np.ndarray, area: float) -> bool:
    """Whether a surface with this vector area (3,) m² and area (m²) is closed.

    Its faces' area vectors must cancel to :data:`CLOSURE_TOLERANCE` of its area.

    Examples
    --------
    >>> import numpy as np
    >>> is_closed(np.array([0.0, 0.0, 1e-12]), 6.0)
    True
    >>> is_closed(np.array([0.0, 0.0, 1.0]), 5.0)  # a box without its lid
    False
    >>> is_closed(np.zeros(3), 0.0)  # no surface at all cancels trivially
    True
    """
    return bool(np.linalg.norm(vector_area) <= CLOSURE_TOLERANCE * max(area, 1e-300))


class SurfaceSummary(NamedTuple):
    """What one pass over a triangle soup tells: enough to judge closure and sign.

    origin: (3,) m, the point volumes are summed about.
    volume: signed enclosed volume, m³ (meaningful only when closed).
    vector_area: (3,) m², zero on a closed surface.
    area: m².
    lo, hi: (3,) m, the bounding box.
    moments: the pass's volume moments, for a solid to reuse.
    """

    origin: np.ndarray
    volume: float
    vector_area: np.ndarray
    area: float
    lo: np.ndarray
    hi: np.ndarray
    moments: VolumeMoments | None = None

    @property
    def closed(self) -> bool:
        """The surface closes (:func:`is_closed`)."""
        return is_closed(self.vector_area, self.area)

    @property
    def flat(self) -> bool:
        """The surface encloses no volume worth the name (:data:`ZERO_VOLUME`)."""
        return abs(self.volume) <= ZERO_VOLUME * self.area ** 1.5


def surface_summary(triangles: np.ndarray) -> SurfaceSummary:
    """Volume, vector area, area and bounding box of a triangle soup, in one pass.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray
        Any float dtype, m.

    Returns
    -------
    SurfaceSummary
        Its moments are the divergence-theorem kernel's, which a solid reuses.

    Examples
    --------
    >>> import numpy as np
    >>> tetra = np.array([[[0, 0, 0], [0, 1, 0], [1, 0, 0]], [[0, 0, 0], [1, 0, 0], [0, 0, 1]],
    ...                   [[0, 0, 0], [0, 0, 1], [0, 1, 0]], [[1, 0, 0], [0, 1, 0], [0, 0, 1]]],
    ...                  dtype=float)
    >>> s = surface_summary(tetra)
    >>> s.closed, round(s.volume * 6, 12)
    (True, 1.0)
    >>> surface_summary(tetra[:3]).closed  # one face missing
    False
    """
    m = triangle_soup_moments(triangles)
    return SurfaceSummary(m.origin, m.m0, m.vector_area, m.area, m.lower, m.upper, m)


def edges_pair(triangles: np.ndarray) -> bool:
    """Whether every directed edge of the soup is met by the reverse edge of another face
    (counting exact copies of a point as one vertex): a closed, consistently wound surface.

    One pass, no sort: each vertex gets a 64-bit hash ``h`` of its bits and
    ``g = h xor (h >> 31)``, and ``Σ h(u)g(v) − h(v)g(u)`` over the directed edges ``u → v``
    is summed with wrap-around (exact integer arithmetic). Reversed pairs cancel exactly, so a
    closed surface sums to 0; otherwise the sum is 0 only by a 2⁻⁶⁴ accident.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = v[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]
    >>> edges_pair(tetra), edges_pair(tetra[:3]), edges_pair(tetra[[0, 1, 2, 3, 3]])
    (True, False, False)
    """
    return paired_keys(triangles) is not None


def paired_keys(triangles: np.ndarray) -> np.ndarray | None:
    """The hashes (n, 3) uint64 of the triangles' corners (:func:`~plumbob.mesh.weld.point_keys`
    of each block's corners, in the soup's dtype) when every directed edge meets its reverse
    (:func:`edges_pair`), else None: a body welds float64 corners by these same keys
    (:func:`~plumbob.mesh.weld.merge_vertices`), so a mesh read from a file hashes them once.

    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = v[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]
    >>> keys = paired_keys(tetra)
    >>> keys.shape, bool(keys[0, 0] == keys[1, 0]), paired_keys(tetra[:3]) is None
    ((4, 3), True, True)
    """
    keys = np.empty((len(triangles), 3), dtype=np.uint64)
    total = np.uint64(0)
    with np.errstate(over="ignore"):
        for start in range(0, len(triangles), PAIR_CHUNK):  # bounded temporaries
            h = keys[start:start + PAIR_CHUNK]
            h[...] = point_keys(triangles[start:start + PAIR_CHUNK]).reshape(-1, 3)
            g = h ^ (h >> np.uint64(31))  # not linear in h: no cancellation but by pairs
            # Σ over the edges 0→1, 1→2, 2→0 of h(u)g(v) − h(v)g(u), gathered by corner
            s = h[:, 0] * (g[:, 1] - g[:, 2])
            s += h[:, 1] * (g[:, 2] - g[:, 0])
            s += h[:, 2] * (g[:, 0] - g[:, 1])
            total += s.sum(dtype=np.uint64)
    return keys if total == 0 else None


class Holes(NamedTuple):
    """The loops of unshared edges of a mesh, told apart by whether they span an area.

    edges: unshared edges on holes (loops spanning an area). loops: how many holes.
    where: (3,) m, the middle of an edge of the largest hole (None without holes).
    span: (3,) m², the largest hole's vector area. slits: unshared edges on loops
    that span nothing (T-junctions: a vertex on another face's edge).
    on_slit, loop: (b,) per unshared edge of the topology, whether it lies on a slit, and
    its loop's label.
    """

    edges: int
    loops: int
    where: np.ndarray | None
    span: float
    slits: int
    on_slit: np.ndarray | None = None
    loop: np.ndarray | None = None


def holes(topo: Topology, area: float) -> Holes:
    """The holes of a mesh's topology: loops of unshared edges whose vector area
    ``½ Σ (pᵤ − c) × (pᵥ − c)`` (c the loop's mean vertex) exceeds
    :data:`CLOSURE_TOLERANCE` of ``area`` (m², the surface's).

    Examples
    --------
    An open tube (a square one, no ends): its surface's vector area is zero, its two
    loops are not.

    >>> import numpy as np
    >>> from plumbob.mesh.topology import mesh_topology
    >>> v = np.array([[x, y, z] for z in (0, 1) for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))],
    ...              dtype=float)
    >>> sides = [(i, (i + 1) % 4, 4 + (i + 1) % 4, 4 + i) for i in range(4)]
    >>> tube = v[[f for a, b, c, d in sides for f in ((a, b, c), (a, c, d))]]
    >>> is_closed(surface_summary(tube).vector_area, 4.0)
    True
    >>> h = holes(mesh_topology(tube), 4.0)
    >>> h.loops, h.edges, h.slits
    (2, 8, 0)
    """
    edges = topo.boundary
    if not len(edges):
        return Holes(0, 0, None, 0.0, 0)
    loop = topo.boundary_loops()
    loops = int(loop.max()) + 1
    start, end = topo.vertices[edges[:, 0]], topo.vertices[edges[:, 1]]
    size = np.bincount(loop, minlength=loops)
    centre = np.stack([np.bincount(loop, start[:, i], loops) for i in range(3)], axis=1)
    centre /= size[:, None]
    twice = np.cross(start - centre[loop], end - centre[loop])
    vector = np.stack([np.bincount(loop, twice[:, i], loops) for i in range(3)], axis=1) / 2
    span = np.linalg.norm(vector, axis=1)
    hole = span > CLOSURE_TOLERANCE * max(area, 1e-300)
    on_slit = ~hole[loop]
    if not hole.any():
        return Holes(0, 0, None, 0.0, len(edges), on_slit, loop)
    worst = int(np.argmax(span))
    first = int(np.argmax(loop == worst))
    return Holes(int(size[hole].sum()), int(hole.sum()), (start[first] + end[first]) / 2,
                 float(span[worst]), int(size[~hole].sum()), on_slit, loop)


def join_at_slits(topo: Topology, found: Holes) -> tuple[np.ndarray, int]:
    """Shell labels (n,) and count with the shells that meet at a slit joined.

    T-junctions can cut a surface into pieces that share no edge yet close only
    together (a face's edge runs along several smaller faces' edges). The faces on one
    slit's two sides belong to one closed surface, so they share a shell.
    """
    if found.on_slit is None or not found.on_slit.any():
        return topo.shell, topo.shells
    face = topo.boundary_face[found.on_slit]
    loop = found.loop[found.on_slit]
    order = np.argsort(loop, kind="stable")
    face, loop = face[order], loop[order]
    same = loop[1:] == loop[:-1]
    shell = topo.shell
    label = connected_components(topo.shells, shell[face[:-1][same]], shell[face[1:][same]])
    return label[shell], int(label.max()) + 1


def open_message(found: Holes, *, prefix: str = "", scale: float = 1.0) -> str:
    """The one line that refuses an open mesh: its holes and a point on the largest, in
    file units (``scale`` m per unit)."""
    return (f"{prefix}the mesh is open: {found.edges} boundary edges ({found.loops} "
            f"hole{'s' if found.loops > 1 else ''}), e.g. near {fmt_point(found.where / scale)}; "
            "close it in a mesh editor or pass --repair")


def require_sums_close(vector_area: np.ndarray, area: float) -> None:
    """Raise a :class:`GeometryError` unless faces of vector area ``vector_area`` (3,) m² and
    area ``area`` m² cancel (:func:`is_closed`): the rule summed, for a caller that has only
    the sums (a field integrated over a mesh's faces). Any volume of an open surface would
    depend on the origin.

    >>> require_sums_close(np.zeros(3), 6.0)
    >>> require_sums_close(np.array([0.0, 0.0, 1.0]), 6.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the mesh is not closed (...): repair it or pass --repair
    """
    if not np.all(np.isfinite(vector_area)):
        raise GeometryError("the mesh has a coordinate that is not a finite number")
    if not is_closed(vector_area, area):
        raise GeometryError("the mesh is not closed (its faces do not enclose a volume, so any "
                            "volume would depend on the origin): repair it or pass --repair")


def require_closed(triangles: np.ndarray, *, summary: SurfaceSummary | None = None) -> None:
    """Raise a :class:`GeometryError` naming the holes unless the triangle soup (n, 3, 3), m,
    is closed by the module's rule. Costs one pass when the surface closes edge to edge.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = v[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]
    >>> require_closed(tetra)
    >>> require_closed(tetra[:3])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the mesh is open: 3 boundary edges (1 hole), e.g. near \
(0.5, 0, 0.5); close it in a mesh editor or pass --repair
    """
    summary = surface_summary(triangles) if summary is None else summary
    if not np.all(np.isfinite(summary.vector_area)):
        raise GeometryError("the mesh has a coordinate that is not a finite number")
    if summary.closed and edges_pair(triangles):
        return
    from .topology import mesh_topology

    size = float(np.linalg.norm(summary.hi - summary.lo))
    found = holes(mesh_topology(triangles, weld_tolerance(size)), summary.area)
    if found.loops:
        raise GeometryError(open_message(found))
    if not summary.closed:
        raise GeometryError("the mesh is not closed although no loop of its edges is open: "
                            "its faces do not enclose a volume")
