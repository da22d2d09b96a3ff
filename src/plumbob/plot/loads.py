"""Loads drawn on a check's picture: each force as an arrow at its point, the critical
edge the loads tip the body over, and each force's moment arm about it.

Drawn in a 2-D view of the check's ground frame (the side view of a solid, a lamina's
own plane): ``axes`` picks the frame's two coordinates shown. Reads only the verdict's
attributes (``verdict.loaded``: :class:`plumbob.stability.loaded.LoadVerdict`).
"""

from __future__ import annotations

import numpy as np

from .geometry import in_frame
from .style import INK, fmt

__all__ = ["draw_loads"]

_ARROW = "#1565c0"
_EDGE = "#c62828"


def draw_loads(ax, verdict, rows: np.ndarray, axes: tuple[int, int], size: float) -> None:
    """Arrows, the critical edge and the moment arms of ``verdict.loaded`` on ``ax``."""
    loaded = getattr(verdict, "loaded", None)
    if loaded is None:
        return
    i, j = axes
    start = in_frame(loaded.edge_start, rows)[[i, j]]
    end = in_frame(loaded.edge_end, rows)[[i, j]]
    factor = loaded.overturning_safety_factor
    ax.plot([start[0], end[0]], [start[1], end[1]], color=_EDGE, linewidth=6, marker="o",
            markersize=9, solid_capstyle="round", zorder=19, gid="critical edge",
            label=f"critical edge (factor of safety {'—' if factor is None else fmt(factor, 3)})")
    pivot = 0.5 * (start + end)
    forces = [m for m in loaded.moments if m.kind != "weight"]
    biggest = max((float(np.linalg.norm(m.force)) for m in forces), default=0.0) or 1.0
    for m in forces:
        at = in_frame(m.at, rows)[[i, j]]
        f = in_frame(m.force, rows)[[i, j]]
        tail = at - 0.3 * size * f / biggest
        ax.annotate("", xy=at, xytext=tail, zorder=20,
                    arrowprops=dict(arrowstyle="-|>", color=_ARROW, linewidth=2.2))
        ax.annotate(f"{m.name}: {fmt(float(np.linalg.norm(m.force)), 4)} N, "
                    f"{fmt(m.moment, 4)} N·m", xy=tail, xytext=(4, 4),
                    textcoords="offset points", fontsize="small", color=_ARROW, zorder=20)
        # the moment arm: from the edge to the nearest point of the force's line of action
        norm = float(np.linalg.norm(f))
        if norm > 0:
            u = f / norm
            foot = at + ((pivot - at) @ u) * u
            ax.plot([pivot[0], foot[0]], [pivot[1], foot[1]], linestyle=":", color=_ARROW,
                    linewidth=1.2, zorder=19)
    ax.plot([], [], linestyle=":", color=_ARROW, label="moment arms about the critical edge")
    ax.plot([], [], color=INK, alpha=0)  # keeps the legend's colours in step
