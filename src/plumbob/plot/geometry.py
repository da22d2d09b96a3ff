"""What to draw of a body: outlines of laminas, triangles of solids, points of particles.

Pictures ask a body only for what any plumbob body can give — its outline (laminas),
its surface triangles (solids), its assembly parts — through the ``Body`` methods, so
this room imports no other room of plumbob and bodies and results may call into it.
Large meshes are decimated here for display only (vertex clustering: one vertex per
cell of a grid, pure numpy, linear in the triangles); every number a picture shows
comes from the caller's full-resolution results.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["Piece", "Drawing", "drawing", "decimate", "DISPLAY_FACES", "rest_frame", "in_frame"]

DISPLAY_FACES = 6000  # triangles drawn of a solid: enough to read the shape, fast to render
_CURVE_TOLERANCE = 2e-4  # curves flattened within this fraction of the body's size
_SEGMENTS = 96  # chords per turn when a curved solid is meshed for display
_SMALL_PART = 2000  # parts with fewer triangles are drawn whole


@dataclass
class Piece:
    """One part of a drawing.

    label: the part's name (or the body's). density: its mean density, or None.
    rings: closed polylines (k, 2), outer rings counter-clockwise, holes clockwise
        (laminas). triangles: (n, 3, 3) (solids). points, masses: particles.
    """

    label: str
    density: float | None = None
    rings: list[np.ndarray] = field(default_factory=list)
    triangles: np.ndarray | None = None
    points: np.ndarray | None = None
    masses: np.ndarray | None = None


@dataclass
class Drawing:
    """A body ready to draw: its pieces and how many triangles were dropped for display."""

    dim: int
    pieces: list[Piece]
    original_faces: int = 0
    shown_faces: int = 0

    @property
    def decimated(self) -> bool:
        return self.shown_faces < self.original_faces

    @property
    def note(self) -> str | None:
        """What the picture leaves out, for a caption."""
        if not self.decimated:
            return None
        return (f"display decimated from {self.original_faces:,} to {self.shown_faces:,} "
                "triangles; every number comes from the full mesh")

    def all_points(self) -> np.ndarray:
        """Every drawn point (n, dim), for the extent of the axes."""
        pts = [r for p in self.pieces for r in p.rings]
        pts += [p.triangles.reshape(-1, 3) for p in self.pieces if p.triangles is not None]
        pts += [p.points for p in self.pieces if p.points is not None]
        pts = [np.pad(q, ((0, 0), (0, self.dim - q.shape[1]))) for q in pts if len(q)]
        return np.concatenate(pts) if pts else np.zeros((1, self.dim))

    def moved(self, rows: np.ndarray) -> Drawing:
        """The drawing with every point ``p`` replaced by ``rows @ p`` (a rotation whose rows
        are the new axes: the ground frame's ``e1, (e2,) up``)."""
        pieces = []
        for p in self.pieces:
            tri = None if p.triangles is None else in_frame(p.triangles, rows)
            if tri is not None and np.linalg.det(rows) < 0:
                tri = tri[:, ::-1]
            pts = None if p.points is None else in_frame(p.points, rows)
            rings = [in_frame(r, rows) for r in p.rings]
            if rings and np.linalg.det(rows) < 0:
                rings = [r[::-1] for r in rings]
            pieces.append(Piece(p.label, p.density, rings, tri, pts, p.masses))
        return Drawing(self.dim, pieces, self.original_faces, self.shown_faces)


def in_frame(points: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Coordinates of ``points`` (…, d) along the unit vectors ``rows`` (d, d)."""
    return np.asarray(points, dtype=float) @ np.asarray(rows, dtype=float).T


def rest_frame(down, axes=None) -> np.ndarray:
    """Rows (e1, [e2,] up): the axes a body resting with gravity along ``down`` is drawn in.

    ``axes`` are the result's own ground axes (a verdict's ``support.frame.axes``) when it
    has them, so the picture and the numbers share one frame; otherwise the ground axis
    nearest +x (then +y) is taken, so a pose is drawn upright without turning about the
    vertical more than it must.
    """
    down = np.asarray(down, dtype=float)
    up = -down / np.linalg.norm(down)
    if axes is not None:
        return np.vstack((np.asarray(axes, dtype=float), up))
    if up.size == 2:
        return np.array([[up[1], -up[0]], up])
    candidates = np.eye(3) - np.outer(up, up)  # the three axes, made horizontal
    e1 = candidates[int(np.argmax(np.linalg.norm(candidates, axis=1) - 1e-9 * np.arange(3)))]
    e1 = e1 / np.linalg.norm(e1)
    return np.array([e1, np.cross(up, e1), up])


# -------------------------------------------------------------------- decimation
def decimate(triangles: np.ndarray, target: int = DISPLAY_FACES) -> np.ndarray:
    """At most about ``target`` triangles that look like ``triangles`` (n, 3, 3).

    Vertex clustering: vertices are snapped to the mean of their cell of a grid over the
    bounding box (as many cells along each side, so a thin part keeps its width),
    triangles that collapse are dropped, duplicates merged; the grid starts fine and is
    coarsened until the count fits. Features narrower than a cell may thin out, which
    is why a decimated picture says so.
    """
    tri = np.asarray(triangles, dtype=float)
    if len(tri) <= target:
        return tri
    pts = tri.reshape(-1, 3)
    lo = pts.min(axis=0)
    span = np.ptp(pts, axis=0)
    span = np.where(span > 0, span, 1.0)
    cells = max(4, int(np.sqrt(target / 5.0)))  # about 2 triangles per surface cell
    best = None  # the most detailed result within the target so far
    for _ in range(6):
        out = _cluster(pts, lo, span, cells)
        if len(out) <= target and (best is None or len(out) > len(best)):
            best = out
        if best is not None and (len(best) >= target // 2 or len(out) > target):
            break  # close enough, or the finer grid overshot: keep the best within
        if len(out) <= target and cells >= 4096:
            break
        cells = max(4, int(cells * np.sqrt(target / max(len(out), 1)) * 0.97))
    if best is None or not len(best):
        return tri[:: max(1, len(tri) // target)]
    return best


def _cluster(pts: np.ndarray, lo: np.ndarray, span: np.ndarray, cells: int) -> np.ndarray:
    """Triangles (m, 3, 3) after snapping the vertices ``pts`` (3n, 3) to a grid of ``cells``
    along each side of the bounding box."""
    ijk = np.minimum(((pts - lo) * (cells / span)).astype(np.int64), cells - 1)
    key = (ijk[:, 0] * cells + ijk[:, 1]) * cells + ijk[:, 2]
    _, inverse, counts = np.unique(key, return_inverse=True, return_counts=True)
    inverse = inverse.reshape(-1)
    centres = np.stack([np.bincount(inverse, weights=pts[:, k]) for k in range(3)], axis=1)
    centres /= counts[:, None]
    faces = inverse.reshape(-1, 3)
    alive = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    faces = faces[alive]
    ordered = np.sort(faces, axis=1)
    n = len(counts)
    _, first = np.unique((ordered[:, 0] * n + ordered[:, 1]) * n + ordered[:, 2], return_index=True)
    return centres[faces[np.sort(first)]]


# ------------------------------------------------------------------ body access
def _label(body, fallback: str) -> str:
    return getattr(body, "name", None) or fallback


def _density(body) -> float | None:
    try:
        value = float(body.mass_properties().density)
    except Exception:  # a picture never fails for want of a legend entry
        return None
    return value if np.isfinite(value) else None


def _lamina_rings(body, size: float) -> list[np.ndarray]:
    """Closed rings (k, 2) of a lamina (:meth:`Body.outline`), arcs and Béziers flattened
    finely enough to look curved at any print size."""
    return body.outline(_CURVE_TOLERANCE * size, 4 * _SEGMENTS)


def _solid_triangles(body) -> np.ndarray:
    """Outward-wound triangles (n, 3, 3) of a solid (:meth:`Body.surface`), m: the mesh
    itself when there is one."""
    return body.surface(_SEGMENTS).triangles


def _pieces(body, dim: int, size: float, label: str) -> list[Piece]:
    parts = body.assembly_parts()
    if parts:
        return [piece for i, part in enumerate(parts)
                for piece in _pieces(part, dim, size, _label(part, f"part {i + 1}"))]
    if getattr(body, "kind", None) == "particles":
        pts = np.asarray(body.positions, dtype=float)
        pts = np.pad(pts, ((0, 0), (0, max(0, dim - pts.shape[1]))))[:, :dim]
        return [Piece(label, None, points=pts, masses=np.asarray(body.masses, dtype=float))]
    if body.dim == 2:
        return [Piece(label, _density(body), rings=_lamina_rings(body, size))]
    return [Piece(label, _density(body), triangles=_solid_triangles(body))]


def drawing(body, max_faces: int = DISPLAY_FACES) -> Drawing:
    """The body's :class:`Drawing`, its solids decimated to about ``max_faces`` triangles in all."""
    dim = int(body.dim)
    size = float(np.linalg.norm(np.ptp(np.asarray(body.hull_points(), dtype=float), axis=0))) or 1.0
    pieces = _pieces(body, dim, size, _label(body, "body"))
    meshes = [p for p in pieces if p.triangles is not None]
    total = sum(len(p.triangles) for p in meshes)
    shown = 0
    for p in meshes:
        share = max(_SMALL_PART, int(max_faces * len(p.triangles) / max(total, 1)))
        p.triangles = decimate(p.triangles, share)
        shown += len(p.triangles)
    if dim == 3:  # a lamina part of a solid assembly lies in z = 0
        for p in pieces:
            p.rings = [np.pad(r, ((0, 0), (0, 1))) for r in p.rings]
    return Drawing(dim, pieces, total, shown)
