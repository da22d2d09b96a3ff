"""A shaded 3-D view of a solid, readable in print.

Flat shading from a fixed light (lightness carries the shape, so it prints in grey),
the body a little translucent so the centre of mass inside it shows; marks drawn
after the body stay on top (``computed_zorder`` off).
"""

from __future__ import annotations

import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from .geometry import Drawing
from .style import COM_STYLE, INK, equal_3d, fmt_at

__all__ = ["draw_3d", "draw_com_3d", "shade", "new_3d_axes"]

_LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])


def shade(triangles: np.ndarray, colour: str) -> np.ndarray:
    """RGBA face colours (n, 4): ``colour`` darkened by the angle to the light."""
    from matplotlib.colors import to_rgba

    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    normal = np.cross(b - a, c - a)
    length = np.linalg.norm(normal, axis=1)
    normal = normal / np.where(length > 0, length, 1.0)[:, None]
    light = 0.45 + 0.55 * np.abs(normal @ _LIGHT)
    rgba = np.tile(np.array(to_rgba(colour)), (len(triangles), 1))
    rgba[:, :3] *= light[:, None]
    return rgba


def new_3d_axes(fig, *args):
    """A 3-D subplot of ``fig`` that draws marks in the order given (marks over the body)."""
    ax = fig.add_subplot(*args, projection="3d", computed_zorder=False)
    ax.view_init(elev=22, azim=-60)
    return ax


def draw_3d(ax, drawing: Drawing, colours: list[str], alpha: float = 0.55,
            extra_points: np.ndarray | None = None) -> list:
    """The drawing's solids shaded, lamina parts as flat plates, particles as dots; the
    axes scaled equally over the body (and ``extra_points``, e.g. a ground patch)."""
    artists = []
    for piece, colour in zip(drawing.pieces, colours):
        if piece.triangles is not None and len(piece.triangles):
            coll = Poly3DCollection(piece.triangles, facecolors=shade(piece.triangles, colour),
                                    edgecolors="none", alpha=alpha, rasterized=True)
            coll.set_gid("body")
            ax.add_collection3d(coll)
            artists.append(coll)
        for ring in piece.rings:
            coll = Poly3DCollection([ring], facecolors=colour, edgecolors=INK, alpha=alpha)
            coll.set_gid("body")
            ax.add_collection3d(coll)
            artists.append(coll)
        if piece.points is not None:
            sizes = 30 + 200 * piece.masses / piece.masses.max()
            artists.append(ax.scatter(*piece.points.T, s=sizes, color=colour, edgecolors=INK,
                                      depthshade=False))
    pts = drawing.all_points()
    if extra_points is not None:
        pts = np.vstack((pts, extra_points))
    equal_3d(ax, pts)
    return artists


def draw_com_3d(ax, point, label: str | None = None, scale: float | None = None, units=None,
                **style):
    """The centre-of-mass marker (gid ``"centre of mass"``) at ``point`` (3,), labelled in
    ``units`` (default SI)."""
    point = np.asarray(point, dtype=float)
    text = label if label is not None else f"centre of mass G {fmt_at(point, units, scale=scale)}"
    (marker,) = ax.plot([point[0]], [point[1]], [point[2]], **{**COM_STYLE, **style}, label=text)
    marker.set_gid("centre of mass")
    return marker
