"""Is this triangle soup a solid? The check every mesh passes before it is measured.

A triangle mesh must close and face outward. The cheap tests run on every
mesh: its vector area vanishes and every directed edge meets its reverse
(:func:`~plumbob.mesh.closure.edges_pair`, one pass, no sort). The full
topological check — vertices welded (exact copies, then copies within
:data:`plumbob.tolerances.WELD` of the size), edges paired, holes told from
T-junction slits and located, winding made consistent, shells found and checked
for overlap — runs when a cheap test fails, when ``repair`` is asked for, or
when the mesh is small enough (:data:`FULL_CHECK_LIMIT`) that it costs little.
The closure rule itself is :mod:`plumbob.mesh.closure`'s.

Errors here name no file: a reader adds its path (see :mod:`plumbob.formats.solids`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..errors import GeometryError, fmt_point
from ..integrals.mesh import VolumeMoments
from ..tolerances import WELD, weld_tolerance
from .closure import (
    SurfaceSummary,
    holes,
    join_at_slits,
    open_message,
    paired_keys,
    surface_summary,
)

# the topology, repair and shells load for the full check only (a small mesh, one whose
# cheap tests fail, or --repair): a large mesh that closes edge to edge never needs them

__all__ = ["FULL_CHECK_LIMIT", "CheckedSolid", "check_solid", "unrepaired_message"]

#: triangles; meshes up to this size always get the full topological check
FULL_CHECK_LIMIT = 50_000


class CheckedSolid(NamedTuple):
    """A triangle soup found (or made) closed and outward-facing.

    triangles: (n, 3, 3) m, closed and wound outward; the input array itself
        (its dtype kept) when nothing had to change.
    notices: what was assumed, turned, repaired or united, for the user.
    moments: the triangles' volume moments when the check already summed them, else None.
    surface: the one-pass summary of the triangles as given (bounding box, area, …).
    vertices: the distinct corners of ``triangles`` (V, 3) float64, exactly as
        :func:`~plumbob.mesh.weld.merge_vertices` gives them, when the check welded them
        on the way (so a body need not weld them again), else None.
    index: (n, 3) int64, each triangle's corners as rows of ``vertices`` (the index
        :func:`~plumbob.mesh.weld.merge_vertices` gives), when ``vertices`` is known.
    keys: (n, 3) uint64, the hashes of ``triangles``' corners as float64 by which
        :func:`~plumbob.mesh.weld.merge_vertices` welds them, when the check computed them
        (a large mesh whose edges pair, not stored as float32) and ``vertices`` is not known:
        a body that welds the triangles need not hash them again.
    """

    triangles: np.ndarray
    notices: tuple[str, ...]
    moments: VolumeMoments | None
    surface: SurfaceSummary
    vertices: np.ndarray | None = None
    index: np.ndarray | None = None
    keys: np.ndarray | None = None


def check_solid(triangles: np.ndarray, *, repair: bool = False, label: str | None = None,
                scale: float = 1.0) -> CheckedSolid:
    """Check that a triangle soup bounds a solid; turn or unite what can be fixed safely.

    Parameters
    ----------
    triangles : (n, 3, 3) ndarray
        A triangle soup, m, any float dtype (float32 is kept when nothing changes).
    repair : bool
        Close small holes (:func:`~plumbob.mesh.repair.fill_holes`) instead of
        refusing an open mesh; also forces the full check on a large mesh.
    label : str, optional
        Names the body in messages when a file holds several (``"solid 'lid'"``).
    scale : float
        Metres per unit of the coordinates that messages name points in (the
        file's own units).

    Returns
    -------
    CheckedSolid
        The closed, outward triangles, with notices for what was turned
        (inside-out shells, inconsistently wound faces), repaired or united
        (overlapping shells, through manifold3d).

    Raises
    ------
    GeometryError
        For an empty, flat, open (unless ``repair`` closes its small holes) or
        non-orientable mesh. The error names no file.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    >>> tetra = v[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]
    >>> checked = check_solid(tetra)
    >>> checked.triangles is tetra, checked.notices
    (True, ())
    >>> check_solid(tetra[:, ::-1]).notices
    ('inside out: its faces pointed inward; turned outward',)
    >>> check_solid(tetra[:3])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the mesh is open: 3 boundary edges (1 hole), e.g. near \
(0.5, 0, 0.5); close it in a mesh editor or pass --repair
    """
    prefix = f"{label}: " if label else ""
    n = len(triangles)
    if n == 0:
        raise GeometryError(f"{prefix}has no triangles: there is no solid to measure")
    summary = surface_summary(triangles)
    if not summary.area > 0:
        raise GeometryError(f"{prefix}all {n} triangles have zero area: there is no surface")
    notices: list[str] = []
    keys = None if repair or n <= FULL_CHECK_LIMIT or not summary.closed else \
        paired_keys(triangles)
    if keys is not None:  # closed edge to edge: the cheap tests suffice
        if summary.flat:
            raise GeometryError(f"{prefix}encloses no volume: the surface is flat or its faces "
                                "cancel")
        moments = summary.moments
        if summary.volume < 0:
            notices.append(f"{prefix}inside out: its faces pointed inward; turned outward")
            triangles, moments, keys = triangles[:, ::-1], None, keys[:, ::-1]
        notices.append(f"{prefix}shells: not checked for overlap ({n} triangles, over "
                       f"{FULL_CHECK_LIMIT}; --repair checks)")
        # float32 corners were hashed by their own bits, not as the float64 a weld hashes
        return CheckedSolid(triangles, tuple(notices), moments, summary,
                            keys=keys if triangles.dtype != np.float32 else None)

    from .repair import fill_holes
    from .shells import resolve_shells
    from .topology import mesh_topology

    size = float(np.linalg.norm(summary.hi - summary.lo))
    weld = weld_tolerance(size)
    topo = mesh_topology(triangles, weld)
    if topo.welded:
        notices.append(f"{prefix}weld: merged {topo.welded} vertices with a copy up to "
                       f"{topo.weld_distance:.2g} m away that was not identical (round-off in "
                       f"the exporter; tolerance {weld:.2g} m, {WELD:g} of the size)")
    if not topo.orientable:
        raise GeometryError(f"{prefix}cannot be wound consistently (it is non-orientable, like a "
                            "Möbius strip): it bounds no solid")
    faces = topo.oriented_faces
    flipped = int(topo.flip.sum())
    if flipped:
        notices.append(f"{prefix}winding: {flipped} of {n} triangles were wound against their "
                       "neighbours; turned to match")
    vertices, shell, shells = topo.vertices, topo.shell, topo.shells
    found = holes(topo, summary.area)
    changed = bool(flipped)
    if found.loops:
        if not repair:
            raise GeometryError(open_message(found, prefix=prefix, scale=scale))
        vertices, faces, shell, notice = fill_holes(topo, faces, shell, summary.area,
                                                    label=prefix, scale=scale)
        notices.append(notice)
        changed = True
    elif not (summary.closed if not flipped else surface_summary(vertices[faces]).closed):
        raise GeometryError(f"{prefix}the mesh is not closed although no loop of its edges is "
                            "open: its faces do not enclose a volume")
    elif found.slits:
        notices.append(f"{prefix}{found.slits} edges end at T-junctions (a vertex on another "
                       "triangle's edge); the surface still closes")
        shell, shells = join_at_slits(topo, found)
    if topo.nonmanifold:
        notices.append(f"{prefix}{topo.nonmanifold} edges are shared by more than two triangles")
    before = faces
    # unturned, unwelded, unrepaired: vertices[faces] are the triangles summed above
    totals = None if changed or topo.welded else (summary.volume, summary.area)
    faces, shell, united, more = resolve_shells(vertices, faces, shell, shells, label=prefix,
                                                totals=totals)
    notices.extend(more)
    if found.loops and not surface_summary(united if united is not None
                                           else vertices[faces]).closed:
        raise GeometryError(unrepaired_message(vertices, faces, found, topo.nonmanifold,
                                               prefix=prefix, scale=scale))
    if united is not None:
        return CheckedSolid(united, tuple(notices), None, summary)
    # The topology's vertices are the input's distinct corners; they are the output's
    # too unless a weld or a repair changed the corners or flat shells were dropped.
    known = topo.vertices if not (topo.welded or found.loops or len(faces) != n) else None
    index = faces if known is not None else None
    if not changed and faces is not before:
        # only whole shells turned: reuse the input's dtype (float32 stays float32)
        same_dtype = vertices[faces].astype(triangles.dtype, copy=False)
        return CheckedSolid(same_dtype, tuple(notices), None, summary, known, index)
    if not changed:
        return CheckedSolid(triangles, tuple(notices), summary.moments, summary, known, index)
    return CheckedSolid(vertices[faces], tuple(notices), None, summary, known, index)


def unrepaired_message(vertices: np.ndarray, faces: np.ndarray, found, nonmanifold: int, *,
                       prefix: str = "", scale: float = 1.0) -> str:
    """The one line for a mesh that ``--repair`` patched and that still encloses no volume:
    what repair did, what is left and where (in file units, ``scale`` m per unit), and what
    would fix it — never "pass --repair" again."""
    did = (f"--repair closed {found.loops} hole{'s' if found.loops > 1 else ''} "
           f"({found.edges} boundary edges)")
    if not nonmanifold:
        return (f"{prefix}{did}, but the surface still encloses no volume (its faces do not "
                "cancel): close or rebuild it in a mesh editor")
    edges = np.sort(np.concatenate((faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]])),
                    axis=1)
    keys, counts = np.unique(edges, axis=0, return_counts=True)
    where = vertices[keys[int(np.argmax(counts))]].mean(axis=0) / scale
    return (f"{prefix}{did}, but the surface still encloses no volume: {nonmanifold} edges are "
            f"shared by more than two triangles, e.g. near {fmt_point(where)}, where faces hang "
            "off the surface (fins, sheets, or parts touching along an edge); --repair only "
            "fills holes: delete those faces or separate the parts in a mesh editor (MeshLab: "
            "Select Non Manifold Edges, then delete them)")
