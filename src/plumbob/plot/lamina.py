"""Drawing in a plane: a lamina's outline, a solid's silhouette seen along an axis.

Holes are holes (one compound path per part, filled by the non-zero rule over rings
wound the opposite way), arcs are drawn from finely flattened rings, so a circle
looks like a circle at any print size.
"""

from __future__ import annotations

import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.patches import PathPatch
from matplotlib.path import Path

from .geometry import Drawing
from .style import COM_STYLE, INK, fmt_at

__all__ = ["draw_outline", "draw_silhouette", "draw_com", "draw_legend"]


def _ring_path(rings: list[np.ndarray]) -> Path:
    verts, codes = [], []
    for ring in rings:
        ring = np.asarray(ring)[:, :2]
        verts.append(ring)
        codes += [Path.MOVETO] + [Path.LINETO] * (len(ring) - 2) + [Path.CLOSEPOLY]
    return Path(np.concatenate(verts), codes)


def draw_outline(ax, drawing: Drawing, colours: list[str]) -> list:
    """Each lamina piece filled in its colour with a dark outline; particles as dots
    sized by mass. Returns the artists."""
    artists = []
    for piece, colour in zip(drawing.pieces, colours):
        if piece.rings:
            patch = PathPatch(_ring_path(piece.rings), facecolor=colour, edgecolor=INK,
                              linewidth=1.2, label=piece.label, gid="body")
            ax.add_patch(patch)
            artists.append(patch)
        if piece.points is not None:
            sizes = 30 + 200 * piece.masses / piece.masses.max()
            artists.append(ax.scatter(piece.points[:, 0], piece.points[:, 1], s=sizes,
                                      color=colour, edgecolors=INK, label=piece.label, zorder=5))
    ax.update_datalim(drawing.all_points()[:, :2])
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    return artists


def draw_silhouette(ax, drawing: Drawing, colours: list[str], across: int = 0,
                    vertical: int = 2) -> list:
    """A solid seen along the remaining axis: its triangles projected onto the plane of
    coordinates ``across`` and ``vertical`` and filled (their union is the silhouette).
    Rasterised in vector output, so an SVG of a large mesh stays small."""
    artists = []
    for piece, colour in zip(drawing.pieces, colours):
        if piece.triangles is not None and len(piece.triangles):
            flat = piece.triangles[:, :, [across, vertical]]
            coll = PolyCollection(flat, facecolors=colour, edgecolors=colour, linewidths=0.3,
                                  rasterized=True, label=piece.label, gid="body")
            ax.add_collection(coll)
            artists.append(coll)
        if piece.rings:
            for ring in piece.rings:
                artists += ax.fill(ring[:, across], ring[:, vertical], color=colour, gid="body")
        if piece.points is not None:
            artists.append(ax.scatter(piece.points[:, across], piece.points[:, vertical],
                                      color=colour, edgecolors=INK, zorder=5))
    ax.update_datalim(drawing.all_points()[:, [across, vertical]])
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    return artists


def draw_com(ax, point, label: str | None = None, scale: float | None = None, units=None,
             **style):
    """The centre-of-mass marker (a ringed dot, gid ``"centre of mass"``) at ``point``,
    labelled in ``units`` (default SI)."""
    point = np.asarray(point, dtype=float)
    text = label if label is not None else f"centre of mass G {fmt_at(point, units, scale=scale)}"
    (marker,) = ax.plot([point[0]], [point[1]], **{**COM_STYLE, **style}, label=text)
    marker.set_gid("centre of mass")
    ax.plot([point[0]], [point[1]], marker="+", color="black", markersize=9, zorder=21)
    return marker


def draw_legend(ax, entries: list[tuple[str, str]], **kw) -> None:
    """A legend of parts (colour, text), added beside the axes' own entries."""
    from matplotlib.patches import Patch

    handles, labels = ax.get_legend_handles_labels()
    keep = [(h, lab) for h, lab in zip(handles, labels) if h.get_gid() != "body"]
    seen = set()
    for colour, text in entries:
        if text not in seen:
            keep.append((Patch(facecolor=colour, edgecolor=INK), text))
            seen.add(text)
    if keep:
        ax.legend(*zip(*keep), **{"fontsize": "small", "loc": "upper left", **kw})
