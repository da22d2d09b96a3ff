"""Shells of a closed mesh: solids, voids, inside-out shells and overlaps.

A mesh may hold several closed shells: separate solids, a solid with voids
(an inward shell inside it), a solid inside a void inside a solid — or
shells that overlap and would count their shared volume twice. Shells are
told apart by their signed volumes and by the winding number
(:func:`~plumbob.mesh.winding.winding_numbers`) of a point of each shell about
the others; overlapping solids are united with manifold3d (imported only then).
Only the shells (usually a handful) are visited one by one.
"""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError
from .closure import ZERO_VOLUME
from .winding import winding_numbers

__all__ = ["MAX_SHELLS_CHECKED", "resolve_shells", "unite_shells"]

#: shells beyond which the overlap check is skipped (it costs shells × triangles)
MAX_SHELLS_CHECKED = 64
#: shells × triangles beyond which the overlap check is skipped
MAX_SHELL_WORK = 50_000_000


def unite_shells(vertices: np.ndarray, faces: np.ndarray, shell: np.ndarray,
                 groups: list[np.ndarray], *, label: str = "") -> tuple[float, np.ndarray]:
    """Union (manifold3d) of solids, each a group of shell labels; returns (volume m³,
    triangles (m, 3, 3)). Raises :class:`GeometryError` when a group is not manifold."""
    import manifold3d

    solids = []
    for group in groups:  # per solid (a handful)
        mask = np.isin(shell, group)
        used, local = np.unique(faces[mask], return_inverse=True)
        mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(vertices[used]),
                                 tri_verts=local.reshape(-1, 3).astype(np.uint64))
        solid = manifold3d.Manifold(mesh)
        if solid.status() != manifold3d.Error.NoError:
            raise GeometryError(
                f"{label}has overlapping shells that could not be united "
                f"(manifold3d: {solid.status().name}); unite them in a mesh editor")
        solids.append(solid)
    union = manifold3d.Manifold.batch_boolean(solids, manifold3d.OpType.Add)
    out = union.to_mesh64()
    verts = np.asarray(out.vert_properties)[:, :3]
    tris = np.asarray(out.tri_verts).astype(np.int64)
    return float(union.volume()), verts[tris]


def _shell_measures(vertices: np.ndarray, faces: np.ndarray, shell: np.ndarray, shells: int
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Each shell's signed volume (m³) and area (m²), (shells,) each."""
    tri = vertices[faces]
    origin = vertices.mean(axis=0)
    a, b, c = tri[:, 0] - origin, tri[:, 1] - origin, tri[:, 2] - origin
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    volume = np.bincount(shell, det, shells) / 6
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = np.bincount(shell, np.linalg.norm(normal, axis=1), shells) / 2
    return volume, area


def resolve_shells(vertices: np.ndarray, faces: np.ndarray, shell: np.ndarray, shells: int,
                   *, label: str = "", totals: tuple[float, float] | None = None
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, list[str]]:
    """Classify shells as solids, voids or inside out; unite overlapping ones.

    Parameters
    ----------
    vertices : (V, 3) ndarray
        m.
    faces : (n, 3) int ndarray
        Closed shells, each wound consistently.
    shell : (n,) int ndarray
        Each face's shell label ``0..shells-1``.
    shells : int
        How many shells.
    label : str
        Prefix naming the body in messages, or ``""``.
    totals : (float, float), optional
        The signed volume (m³) and area (m²) of the surface ``vertices[faces]``, when
        already summed (:func:`~plumbob.mesh.closure.surface_summary`): with one shell
        they are that shell's, and its faces are not summed again.

    Returns
    -------
    faces, shell : ndarray
        The faces with inside-out shells turned (flat shells dropped), and their labels.
    united : (m, 3, 3) ndarray or None
        The united triangles when shells overlapped, else None.
    notices : list of str
        What was turned, dropped, united or left unchecked.

    Raises
    ------
    GeometryError
        When no shell encloses volume, or overlapping shells cannot be united.

    Examples
    --------
    A unit cube with a cube of side ½ inside it, wound outward too — a void
    wound the wrong way, or a duplicate shell — is united:

    >>> import numpy as np
    >>> from plumbob.mesh.topology import mesh_topology
    >>> v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    >>> quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4),
    ...          (1, 5, 7, 3)]
    >>> cube = v[[f for a, b, c, d in quads for f in ((a, b, c), (a, c, d))]]
    >>> topo = mesh_topology(np.concatenate((cube, 0.25 + cube / 2)))
    >>> faces, shell, united, notices = resolve_shells(topo.vertices, topo.oriented_faces,
    ...                                                topo.shell, topo.shells)
    >>> notices
    ['shells: 2 shells overlap; united with manifold3d (volume 1.125 → 1 m³)']
    """
    notices: list[str] = []
    if totals is not None and shells == 1:
        volume, area = np.array([totals[0]], dtype=float), np.array([totals[1]], dtype=float)
    else:
        volume, area = _shell_measures(vertices, faces, shell, shells)
    flat = np.abs(volume) <= ZERO_VOLUME * area ** 1.5
    if flat.all():
        raise GeometryError(f"{label}encloses no volume: the surface is flat or its faces cancel")
    if flat.any():
        keep = ~flat[shell]
        notices.append(f"{label}shells: dropped {int(flat.sum())} flat shell(s) enclosing no "
                       f"volume ({int((~keep).sum())} triangles)")
        faces, shell = faces[keep], np.unique(shell[keep], return_inverse=True)[1].reshape(-1)
        volume, area = volume[~flat], area[~flat]
        shells = len(volume)
    if shells == 1:
        if volume[0] < 0:
            notices.append(f"{label}inside out: its faces pointed inward; turned outward")
            faces = faces[:, ::-1]
        return faces, shell, None, notices
    corners = vertices[faces]
    order = np.argsort(shell, kind="stable")
    starts = np.r_[0, np.cumsum(np.bincount(shell, minlength=shells))[:-1]]
    lo = np.minimum.reduceat(corners.min(axis=1)[order], starts, axis=0)
    hi = np.maximum.reduceat(corners.max(axis=1)[order], starts, axis=0)
    boxes_meet = (lo[:, None] <= hi[None, :]).all(axis=2) & (lo[None, :] <= hi[:, None]).all(axis=2)
    np.fill_diagonal(boxes_meet, False)
    if not boxes_meet.any():  # shells apart: each is a solid of its own
        inward = volume < 0
        if inward.any():
            faces = np.where(inward[shell][:, None], faces[:, ::-1], faces)
            what = "its faces" if inward.all() else f"{int(inward.sum())} of {shells} shells"
            notices.append(f"{label}inside out: {what} pointed inward; turned outward")
        return faces, shell, None, notices
    if shells > MAX_SHELLS_CHECKED or shells * len(faces) > MAX_SHELL_WORK:
        notices.append(f"{label}shells: {shells} shells, not checked for overlap (too many)")
        if volume.sum() < 0:
            notices.append(f"{label}inside out: its faces pointed inward; turned outward")
            faces = faces[:, ::-1]
        return faces, shell, None, notices
    if volume.sum() < 0:  # the whole mesh inside out (the common case): turn it first
        notices.append(f"{label}inside out: its faces pointed inward; turned outward")
        faces, volume = faces[:, ::-1], -volume
    first = np.unique(shell, return_index=True)[1]
    points = vertices[faces[first]].mean(axis=1)  # a point on each shell
    raw = winding_numbers(points, vertices[faces], shell, shells)
    np.fill_diagonal(raw, 0.0)  # W[i, j]: winding of shell i's point about shell j
    winding = np.rint(raw)
    ambiguous = bool(np.any(np.abs(raw - winding) > 0.05))
    depth = winding.sum(axis=1)
    lone = (volume < 0) & (depth <= 0)  # faces inward but not inside any material: inside out
    if lone.any():
        faces = np.where(lone[shell][:, None], faces[:, ::-1], faces)
        winding[:, lone] *= -1
        volume[lone] *= -1
        depth = winding.sum(axis=1)
        notices.append(f"{label}inside out: {int(lone.sum())} of {shells} shells faced inward; "
                       "turned outward")
    positive = volume > 0
    # On its surface a solid shell must have no material outside it (depth 0), a void
    # shell exactly its host (depth 1); anything else means shells overlap.
    certain = ambiguous or bool(np.any(np.where(positive, depth != 0, depth != 1)))
    pos = np.flatnonzero(positive)
    if not (certain or boxes_meet[np.ix_(pos, pos)].any()):
        return faces, shell, None, notices
    # Group each void with the smallest solid shell around it; unite the solids.
    groups = {int(p): [int(p)] for p in pos}
    for v in np.flatnonzero(~positive):  # per void shell
        hosts = pos[winding[v, pos] >= 1]
        if len(hosts):
            groups[int(hosts[np.argmin(volume[hosts])])].append(int(v))
        else:
            groups[int(v)] = [int(v)]
    total = float(volume.sum())
    try:
        united, triangles = unite_shells(vertices, faces, shell,
                                         [np.array(g) for g in groups.values()], label=label)
    except GeometryError:
        if certain:
            raise
        notices.append(f"{label}shells: {shells} shells whose boxes meet could not be checked "
                       "for overlap (not manifold)")
        return faces, shell, None, notices
    if abs(united - total) <= 1e-9 * abs(total):
        return faces, shell, None, notices
    notices.append(f"{label}shells: {shells} shells overlap; united with manifold3d "
                   f"(volume {total:.6g} → {united:.6g} m³)")
    return faces, shell, triangles, notices
