"""Checking what a file gave us, and fixing what can be fixed safely.

Every reader ends here. Coordinates must be finite and of a size a real
object can have; units are applied and said. A triangle mesh must close and
face outward: the cheap test (its vector area vanishes) runs on every mesh;
the full topological check — vertices merged, edges paired, boundary edges
counted and located, winding made consistent, shells found and checked for
overlap — runs when the cheap test fails, when the user asks for ``repair``,
or when the mesh is small enough (:data:`FULL_CHECK_LIMIT`) that it costs
little. Everything here is vectorised over triangles; only the shells of a
mesh (usually a handful) are visited one by one.

Nothing in this module imports shapely, trimesh or scipy; manifold3d is
imported only to unite overlapping shells.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..bodies.solid import CLOSURE_TOLERANCE, MeshSolid
from ..errors import GeometryError, PlumbobError
from ..integrals.mesh import VolumeMoments, triangle_soup_moments
from ..units import length_scale

__all__ = [
    "ABSURD_COORDINATE",
    "PLAUSIBLE_SIZE",
    "FULL_CHECK_LIMIT",
    "HOLE_AREA_FRACTION",
    "UNITS_ASSUMED",
    "units_scale",
    "fmt_point",
    "check_extent",
    "check_reach",
    "block_bounds",
    "finite_bounds",
    "SurfaceSummary",
    "surface_summary",
    "unique_names",
    "Topology",
    "mesh_topology",
    "connected_components",
    "check_solid",
]

#: m; a coordinate beyond this is no real object (3 light-seconds)
ABSURD_COORDINATE = 1e9
#: m; bounding-box diagonals outside this range draw a warning about units
PLAUSIBLE_SIZE = (1e-5, 1e3)
#: triangles; meshes up to this size always get the full topological check
FULL_CHECK_LIMIT = 50_000
#: a hole is closed by --repair when its patch is at most this share of the surface
HOLE_AREA_FRACTION = 0.05
#: shells beyond which the overlap check is skipped (it costs shells × triangles)
MAX_SHELLS_CHECKED = 64
#: volume below this share of area^1.5 counts as none
ZERO_VOLUME = 1e-9
#: triangles per pass in the chunked kernels
CHUNK = 1 << 16
#: triangles per pass of the closure test: its float64 temporaries stay in cache

UNITS_ASSUMED = "units: none in file; metres assumed (use --units)"

# Metres per unit for the spellings files use (DXF, 3MF, SVG) beyond length_scale's.
FILE_UNITS: dict[str, float] = {
    "micron": 1e-6, "micrometer": 1e-6, "um": 1e-6,
    "millimeter": 1e-3, "millimetre": 1e-3, "millimeters": 1e-3, "mm": 1e-3,
    "centimeter": 1e-2, "centimetre": 1e-2, "cm": 1e-2,
    "decimeter": 0.1, "dm": 0.1,
    "meter": 1.0, "metre": 1.0, "meters": 1.0, "m": 1.0,
    "kilometer": 1e3, "km": 1e3,
    "inch": 0.0254, "in": 0.0254,
    "foot": 0.3048, "feet": 0.3048, "ft": 0.3048,
    "yard": 0.9144, "yd": 0.9144,
    "mile": 1609.344, "mi": 1609.344,
}


# ---------------------------------------------------------------- units, sizes
def units_scale(units: str | None, file_units: str | None = None,
                file_scale: float | None = None) -> tuple[float, tuple[str, ...]]:
    """Metres per file unit, and the notice that says where it came from.

    ``units``: what the user passed (``--units``), or None.
    ``file_units``/``file_scale``: the unit the file declares (its name and
    metres per unit), or None when the format carries none (STL, OBJ, …).
    """
    if units is not None:
        scale = length_scale(units)
        if file_units is not None and file_scale is not None and not np.isclose(scale, file_scale):
            return scale, (f"units: the file says {file_units}; {units} used as --units asks",)
        return scale, ()
    if file_units is not None and file_scale is not None:
        return file_scale, (f"units: {file_units} (from the file)",)
    return 1.0, (UNITS_ASSUMED,)


def fmt_point(point: np.ndarray) -> str:
    """``(x, y[, z])`` with 6 significant digits, for messages."""
    return "(" + ", ".join(f"{float(c):.6g}" for c in np.asarray(point).reshape(-1)) + ")"


def check_extent(lo: np.ndarray, hi: np.ndarray, *, path: str | None) -> tuple[str, ...]:
    """Reject absurd coordinates; warn when the size is implausible for its units.

    ``lo``, ``hi``: the bounding box corners in metres (units applied).
    """
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    check_reach(float(max(np.abs(lo).max(), np.abs(hi).max())), path=path)
    size = float(np.linalg.norm(hi - lo))
    small, large = PLAUSIBLE_SIZE
    if size > large:
        return (f"size: the model is {size:.4g} m across, implausible for its units; "
                "if the file is in millimetres pass --units mm",)
    if 0 < size < small:
        return (f"size: the model is only {size:.3g} m across, implausible for its units; "
                "pass --units to say what the file's lengths are in",)
    return ()


def check_reach(reach: float, *, path: str | None) -> None:
    """Reject a largest coordinate magnitude ``reach`` (m) that is not finite or absurd."""
    if not np.isfinite(reach):
        raise GeometryError("a coordinate is not a finite number (NaN or infinity)", path=path)
    if reach > ABSURD_COORDINATE:
        raise GeometryError(
            f"coordinates reach {reach:.3g} m, far beyond any real object "
            f"(limit {ABSURD_COORDINATE:g} m): the file is corrupt or in other units "
            "(use --units)", path=path)


def block_bounds(block: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per-axis min and max of points (…, 3), NaN propagating.

    Reduces rows of 1024 points at a time, keeping numpy's inner loop long (a
    reduction of (m, 3) along axis 0 is ten times slower).
    """
    flat = block.reshape(-1, 3)
    main = len(flat) // 1024 * 1024
    parts = []
    if main:
        wide = flat[:main].reshape(-1, 3072)
        parts.append((wide.min(axis=0).reshape(-1, 3).min(axis=0),
                      wide.max(axis=0).reshape(-1, 3).max(axis=0)))
    if main < len(flat) or not parts:
        rest = flat[main:]
        parts.append((rest.min(axis=0), rest.max(axis=0)) if len(rest) else
                     (np.full(3, np.inf), np.full(3, -np.inf)))
    return (np.minimum.reduce([p[0] for p in parts]), np.maximum.reduce([p[1] for p in parts]))


def finite_bounds(points: np.ndarray, *, path: str | None, what: str = "triangle",
                  chunk: int = CHUNK) -> tuple[np.ndarray, np.ndarray]:
    """Bounding box (lo, hi) of ``points`` (n, …, d); a NaN or infinity is an error naming
    its item."""
    points = np.asarray(points)
    n = len(points)
    d = points.shape[-1]
    if n == 0:
        return np.zeros(d), np.zeros(d)
    lo = np.full(d, np.inf)
    hi = np.full(d, -np.inf)
    for start in range(0, n, chunk):
        block = points[start:start + chunk].reshape(-1, d)
        with np.errstate(invalid="ignore"):
            blo, bhi = block.min(axis=0), block.max(axis=0)
        if not (np.all(np.isfinite(blo)) and np.all(np.isfinite(bhi))):
            raise_nonfinite(points[start:start + chunk], start, path=path, what=what)
        lo = np.minimum(lo, blo)
        hi = np.maximum(hi, bhi)
    return lo, hi


def raise_nonfinite(block: np.ndarray, offset: int, *, path: str | None, what: str) -> None:
    """Raise the error for the first item of ``block`` with a NaN or infinite coordinate."""
    block = np.asarray(block)
    bad = ~np.isfinite(block.reshape(len(block), -1)).all(axis=1)
    index = int(np.argmax(bad))
    value = block.reshape(len(block), -1)[index]
    kind = "NaN" if np.isnan(value).any() else "infinity"
    raise GeometryError(
        f"{what} {offset + index + 1} has a coordinate that is not a finite number ({kind}); "
        "the file is corrupt or its exporter is faulty", path=path)


# ---------------------------------------------------------------- cheap test
@dataclass(frozen=True, eq=False)
class SurfaceSummary:
    """What one pass over a triangle soup tells: enough to judge closure and sign.

    origin: (3,) m, the point volumes are summed about.
    volume: signed enclosed volume, m³ (meaningful only when closed).
    vector_area: (3,) m², zero on a closed surface.
    area: m².
    lo, hi: (3,) m, the bounding box.
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
        return bool(np.linalg.norm(self.vector_area) <= CLOSURE_TOLERANCE * max(self.area, 1e-300))

    @property
    def flat(self) -> bool:
        return abs(self.volume) <= ZERO_VOLUME * self.area ** 1.5


def surface_summary(triangles: np.ndarray) -> SurfaceSummary:
    """Volume, vector area, area and bounding box of ``triangles`` (n, 3, 3): one pass
    of the divergence-theorem kernel, whose moments the solid then reuses."""
    m = triangle_soup_moments(triangles)
    return SurfaceSummary(m.origin, m.m0, m.vector_area, m.area, m.lower, m.upper, m)


# ---------------------------------------------------------------- topology
def connected_components(n: int, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Component label (0..k-1, in order of each component's smallest node) of nodes 0..n-1
    joined by edges ``u[i]–v[i]``: vectorised hooking and pointer jumping."""
    parent = np.arange(n)
    u = np.asarray(u, dtype=np.int64)
    v = np.asarray(v, dtype=np.int64)
    while len(u):
        pu, pv = parent[u], parent[v]
        live = pu != pv
        if not live.any():
            break
        u, v, pu, pv = u[live], v[live], pu[live], pv[live]
        np.minimum.at(parent, np.maximum(pu, pv), np.minimum(pu, pv))
        while True:  # point every node at its root
            grand = parent[parent]
            if np.array_equal(grand, parent):
                break
            parent = grand
    return np.unique(parent, return_inverse=True)[1].reshape(-1)


def _mix(z: np.ndarray) -> np.ndarray:
    """splitmix64's finaliser: every input bit reaches every output bit (uint64, wraps)."""
    z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
    z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    return z ^ (z >> np.uint64(31))


def _merge_vertices(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unique points (V, 3) float64 and the index of each input point, merging exact copies."""
    p = np.ascontiguousarray(points, dtype=float) + 0.0  # -0.0 → 0.0
    bits = p.view(np.uint64)
    key = _mix(_mix(_mix(bits[:, 0]) ^ bits[:, 1]) ^ bits[:, 2])
    _, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    unique = p[first]
    if not np.array_equal(unique[inverse], p):  # a hash collision: merge exactly instead
        unique, inverse = np.unique(p, axis=0, return_inverse=True)
    return unique, inverse.reshape(-1)


@dataclass(frozen=True, eq=False)
class Topology:
    """How a triangle soup's faces connect.

    vertices: (V, 3) m, merged exact copies. faces: (n, 3) indices, winding as read.
    flip: (n,) bool, faces wound against the rest of their shell (to be turned).
    shell: (n,) shell label 0..shells-1 (faces joined through shared edges, however many
        faces share each).
    boundary: (b, 2) boundary half-edges (vertex indices), directed as in the
        turned faces, each paired with the face it belongs to in ``boundary_face``.
    nonmanifold: edges shared by more than two faces.
    orientable: False when a shell cannot be wound consistently (a Möbius strip).
    """

    vertices: np.ndarray
    faces: np.ndarray
    flip: np.ndarray
    shell: np.ndarray
    shells: int
    boundary: np.ndarray
    boundary_face: np.ndarray
    nonmanifold: int
    orientable: bool

    @property
    def oriented_faces(self) -> np.ndarray:
        faces = self.faces.copy()
        faces[self.flip] = faces[self.flip][:, ::-1]
        return faces


def mesh_topology(triangles: np.ndarray) -> Topology:
    """Merge vertices, pair edges, make winding consistent and find shells and boundary edges."""
    n = len(triangles)
    vertices, index = _merge_vertices(triangles.reshape(-1, 3))
    faces = index.reshape(n, 3).astype(np.int64)
    nv = len(vertices)
    half = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    owner = np.repeat(np.arange(n), 3)
    proper = half[:, 0] != half[:, 1]
    half, owner = half[proper], owner[proper]
    lo = np.minimum(half[:, 0], half[:, 1])
    hi = np.maximum(half[:, 0], half[:, 1])
    key = lo * nv + hi
    order = np.argsort(key, kind="stable")
    skey = key[order]
    starts = np.flatnonzero(np.r_[True, skey[1:] != skey[:-1]])
    counts = np.diff(np.r_[starts, len(skey)])
    pairs = starts[counts == 2]
    h1, h2 = order[pairs], order[pairs + 1]
    f1, f2 = owner[h1], owner[h2]
    same_direction = half[h1, 0] == half[h2, 0]  # the two faces disagree on winding
    # Each face is two nodes, f (as wound) and f + n (turned); a shared edge joins
    # the nodes that agree. A shell is then two components, one per orientation.
    a = np.where(same_direction, f2 + n, f2)
    b = np.where(same_direction, f2, f2 + n)
    labels = connected_components(2 * n, np.r_[f1, f1 + n], np.r_[a, b])
    plus, minus = labels[:n], labels[n:]
    orientable = not bool(np.any(plus == minus))
    weight = np.bincount(plus, minlength=2 * n)
    flip = (weight[plus] < weight[minus]) | ((weight[plus] == weight[minus]) & (plus > minus))
    # Shells: faces joined through any shared edge (also where more than two meet, as
    # when two cubes share a face), so a shell is a closed surface on its own.
    same_edge = np.flatnonzero(skey[1:] == skey[:-1])
    shell = connected_components(n, owner[order[same_edge]], owner[order[same_edge + 1]])
    single = order[starts[counts == 1]]
    boundary = half[single]
    boundary_face = owner[single]
    turned = flip[boundary_face]
    boundary[turned] = boundary[turned][:, ::-1]
    return Topology(vertices, faces, flip, shell, int(shell.max()) + 1 if n else 0,
                    boundary, boundary_face, int(np.count_nonzero(counts > 2)), orientable)


# ---------------------------------------------------------------- repairs
def _fill_holes(topo: Topology, faces: np.ndarray, shell: np.ndarray, total_area: float,
                *, path: str | None, label: str, scale: float = 1.0
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray, str]:
    """Close every boundary loop with a fan from its centroid (a new vertex).

    Returns vertices, faces, shell labels and a notice. Raises when a hole is
    larger than :data:`HOLE_AREA_FRACTION` of the surface.
    """
    edges = topo.boundary
    nv = len(topo.vertices)
    loop_of_vertex = connected_components(nv, edges[:, 0], edges[:, 1])
    loop = np.unique(loop_of_vertex[edges[:, 0]], return_inverse=True)[1].reshape(-1)
    loops = int(loop.max()) + 1
    start = topo.vertices[edges[:, 0]]
    size = np.bincount(loop, minlength=loops)
    centre = np.stack([np.bincount(loop, start[:, i], loops) for i in range(3)], axis=1)
    centre /= size[:, None]
    new_faces = np.stack((edges[:, 1], edges[:, 0], nv + loop), axis=1)
    vertices = np.concatenate((topo.vertices, centre))
    tri = vertices[new_faces]
    patch = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1) / 2
    patch_area = np.bincount(loop, patch, loops)
    too_big = patch_area > HOLE_AREA_FRACTION * total_area
    if too_big.any():
        worst = int(np.argmax(patch_area))
        raise GeometryError(
            f"{label}is open with a hole too large to close safely ({size[worst]} boundary edges, "
            f"{patch_area[worst] / total_area:.0%} of the surface) near "
            f"{fmt_point(centre[worst] / scale)}: close it in a mesh editor", path=path)
    notice = (f"repair: closed {loops} hole{'s' if loops > 1 else ''} ({len(edges)} boundary "
              f"edges) near {fmt_point(centre[np.argmax(patch_area)] / scale)}, adding "
              f"{patch_area.sum():.4g} m² of surface")
    return (vertices, np.concatenate((faces, new_faces)),
            np.concatenate((shell, shell[topo.boundary_face])), f"{label}{notice}")


def _solid_angles(points: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Signed solid angle (k, m) each triangle (m, 3, 3) subtends at each point (k, 3)."""
    a = tri[None, :, 0] - points[:, None]
    b = tri[None, :, 1] - points[:, None]
    c = tri[None, :, 2] - points[:, None]
    la, lb, lc = (np.sqrt(np.einsum("...i,...i->...", x, x)) for x in (a, b, c))
    det = np.einsum("...i,...i->...", a, np.cross(b, c))
    den = (la * lb * lc + np.einsum("...i,...i->...", a, b) * lc
           + np.einsum("...i,...i->...", a, c) * lb + np.einsum("...i,...i->...", b, c) * la)
    return 2 * np.arctan2(det, den)


def _winding_matrix(vertices: np.ndarray, faces: np.ndarray, shell: np.ndarray, shells: int,
                    points: np.ndarray) -> np.ndarray:
    """W[i, j]: winding number of ``points[i]`` about shell j (0 on the diagonal)."""
    k = len(points)
    total = np.zeros((k, shells))
    step = max(1, 2_000_000 // max(k, 1))
    for s in range(0, len(faces), step):
        tri = vertices[faces[s:s + step]]
        omega = _solid_angles(points, tri)
        for i in range(k):  # per shell point, not per triangle
            total[i] += np.bincount(shell[s:s + step], omega[i], shells)
    total /= 4 * np.pi
    np.fill_diagonal(total, 0.0)
    return total


def _unite_shells(vertices: np.ndarray, faces: np.ndarray, shell: np.ndarray,
                  groups: list[np.ndarray], *, path: str | None, label: str):
    """Union (manifold3d) of solids, each a group of shells; returns (volume, triangles)."""
    import manifold3d

    solids = []
    for group in groups:
        mask = np.isin(shell, group)
        used, local = np.unique(faces[mask], return_inverse=True)
        mesh = manifold3d.Mesh64(vert_properties=np.ascontiguousarray(vertices[used]),
                                 tri_verts=local.reshape(-1, 3).astype(np.uint64))
        solid = manifold3d.Manifold(mesh)
        if solid.status() != manifold3d.Error.NoError:
            raise GeometryError(
                f"{label}has overlapping shells that could not be united "
                f"(manifold3d: {solid.status().name}); unite them in a mesh editor", path=path)
        solids.append(solid)
    union = manifold3d.Manifold.batch_boolean(solids, manifold3d.OpType.Add)
    out = union.to_mesh64()
    verts = np.asarray(out.vert_properties)[:, :3]
    tris = np.asarray(out.tri_verts).astype(np.int64)
    return float(union.volume()), verts[tris]


def _resolve_shells(vertices, faces, shell, shells, *, path, label):
    """Classify shells as solids, voids or inside out; unite overlapping ones.

    Returns ``(faces, shell, united, notices)``: faces with inside-out shells
    turned (flat shells dropped), their shell labels, and the united triangles
    (or None) when shells overlapped.
    """
    notices: list[str] = []
    tri = vertices[faces]
    origin = vertices.mean(axis=0)
    a, b, c = tri[:, 0] - origin, tri[:, 1] - origin, tri[:, 2] - origin
    det = np.einsum("ij,ij->i", a, np.cross(b, c))
    volume = np.bincount(shell, det, shells) / 6
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = np.bincount(shell, np.linalg.norm(normal, axis=1), shells) / 2
    flat = np.abs(volume) <= ZERO_VOLUME * area ** 1.5
    if flat.all():
        raise GeometryError(f"{label}encloses no volume: the surface is flat or its faces cancel",
                            path=path)
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
    if shells > MAX_SHELLS_CHECKED or shells * len(faces) > 50_000_000:
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
    raw = _winding_matrix(vertices, faces, shell, shells, points)
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
    for v in np.flatnonzero(~positive):
        hosts = pos[winding[v, pos] >= 1]
        if len(hosts):
            groups[int(hosts[np.argmin(volume[hosts])])].append(int(v))
        else:
            groups[int(v)] = [int(v)]
    total = float(volume.sum())
    try:
        united, triangles = _unite_shells(vertices, faces, shell,
                                          [np.array(g) for g in groups.values()],
                                          path=path, label=label)
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


# ---------------------------------------------------------------- the check
def check_solid(triangles: np.ndarray, *, path: str | None = None, name: str | None = None,
                repair: bool = False, label: str | None = None, scale: float = 1.0,
                extent: bool = False) -> tuple[MeshSolid, tuple[str, ...]]:
    """A :class:`MeshSolid` from a triangle soup (n, 3, 3) in metres, checked and fixed.

    Raises :class:`GeometryError` for an empty, flat, open (unless ``repair``
    closes its small holes), non-orientable or non-finite mesh; turns an
    inside-out mesh or inconsistently wound faces (with a notice) and unites
    overlapping shells (with a notice). ``label`` names the body in messages
    when a file holds several; ``scale`` (metres per file unit) puts the points
    that messages name in the file's own coordinates; ``extent`` adds the
    implausible-size check on the mesh's bounding box (see :func:`check_extent`).
    """
    prefix = f"{label}: " if label else ""
    n = len(triangles)
    if n == 0:
        raise GeometryError(f"{prefix}has no triangles: there is no solid to measure", path=path)
    summary = surface_summary(triangles)
    if not summary.area > 0:
        raise GeometryError(f"{prefix}all {n} triangles have zero area: there is no surface",
                            path=path)
    notices: list[str] = list(check_extent(summary.lo, summary.hi, path=path)) if extent else []
    full = repair or not summary.closed or n <= FULL_CHECK_LIMIT
    if not full:
        if summary.flat:
            raise GeometryError(f"{prefix}encloses no volume: the surface is flat or its faces "
                                "cancel", path=path)
        moments = summary.moments
        if summary.volume < 0:
            notices.append(f"{prefix}inside out: its faces pointed inward; turned outward")
            triangles, moments = triangles[:, ::-1], None
        notices.append(f"{prefix}shells: not checked for overlap ({n} triangles, over "
                       f"{FULL_CHECK_LIMIT}; --repair checks)")
        return _solid(triangles, name, path, moments), tuple(notices)

    topo = mesh_topology(triangles)
    if not topo.orientable:
        raise GeometryError(f"{prefix}cannot be wound consistently (it is non-orientable, like a "
                            "Möbius strip): it bounds no solid", path=path)
    faces = topo.oriented_faces
    flipped = int(topo.flip.sum())
    if flipped:
        notices.append(f"{prefix}winding: {flipped} of {n} triangles were wound against their "
                       "neighbours; turned to match")
    vertices, shell = topo.vertices, topo.shell
    closed_after = summary.closed if not flipped else surface_summary(vertices[faces]).closed
    changed = bool(flipped)
    if len(topo.boundary) and not closed_after:
        loops = connected_components(len(vertices), topo.boundary[:, 0], topo.boundary[:, 1])
        holes = len(np.unique(loops[topo.boundary[:, 0]]))
        near = vertices[topo.boundary[0]].mean(axis=0)
        if not repair:
            raise GeometryError(
                f"{prefix}the mesh is open: {len(topo.boundary)} boundary edges "
                f"({holes} hole{'s' if holes > 1 else ''}), e.g. near {fmt_point(near / scale)}; "
                "close it in a mesh editor or pass --repair", path=path)
        vertices, faces, shell, notice = _fill_holes(topo, faces, shell, summary.area,
                                                     path=path, label=prefix, scale=scale)
        notices.append(notice)
        changed = True
    elif len(topo.boundary):
        notices.append(f"{prefix}{len(topo.boundary)} edges are not shared by two triangles "
                       "(T-junctions?), but the surface still closes")
    elif not closed_after:
        raise GeometryError(f"{prefix}the mesh is not closed although every edge is shared: "
                            "its faces do not enclose a volume", path=path)
    if topo.nonmanifold:
        notices.append(f"{prefix}{topo.nonmanifold} edges are shared by more than two triangles")
    before = faces
    faces, shell, united, more = _resolve_shells(vertices, faces, shell, topo.shells,
                                                 path=path, label=prefix)
    notices.extend(more)
    if united is not None:
        return _solid(united, name, path), tuple(notices)
    if not changed and faces is not before:
        # only whole shells turned: reuse the input's dtype (float32 stays float32)
        same_dtype = vertices[faces].astype(triangles.dtype, copy=False)
        return _solid(same_dtype, name, path), tuple(notices)
    if not changed:
        return _solid(triangles, name, path, summary.moments), tuple(notices)
    return _solid(vertices[faces], name, path), tuple(notices)


def unique_names(names: list[str]) -> list[str]:
    """Names made distinct for a per-body table: repeats get " (2)", " (3)", …"""
    seen: dict[str, int] = {}
    out = []
    for name in names:
        seen[name] = seen.get(name, 0) + 1
        out.append(name if seen[name] == 1 else f"{name} ({seen[name]})")
    return out


def _solid(triangles: np.ndarray, name: str | None, path: str | None,
           moments: VolumeMoments | None = None) -> MeshSolid:
    try:
        return MeshSolid(triangles, name=name, moments=moments)
    except PlumbobError as error:
        raise GeometryError(error.message, path=path) from None
