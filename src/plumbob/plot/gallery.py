"""``plot_poses``: the pose gallery, one small picture per stable resting pose.

Each panel shows the body turned to rest on the ground in that pose (its face on the
ground outlined, the centre of mass marked), captioned with its probability and
critical tilt, most probable first — the order of the result. The body is decimated
once for all panels; without the body each panel shows the face it rests on and the
foot of its centre of mass.
"""

from __future__ import annotations

import math

import numpy as np
from matplotlib.patches import Polygon

from .geometry import Drawing, drawing, in_frame, rest_frame
from .lamina import draw_com, draw_outline
from .solid import draw_3d, draw_com_3d, new_3d_axes
from .style import INK, caption, fmt, fmt_length, new_figure, part_colours, title_for

__all__ = ["plot_poses", "MAX_PANELS"]

MAX_PANELS = 24  # poses drawn at most; the rest are summed up in a caption
_PANEL_FACES = 2500  # triangles per panel


def _caption(k: int, pose, units=None) -> str:
    """``#k  p = …``, then the critical tilt and the height of G (in the report's unit)."""
    text = (f"#{k}  p = {pose.probability:.3f}\ntilt {fmt(pose.critical_tilt_deg, 3)}°, "
            f"G at {fmt_length(pose.com_height, units, 3)}")
    return text + ("  (rolls)" if pose.neutral else "")


def _panel_3d(ax, pose, com, base: Drawing | None, colours) -> None:
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    rows = rest_frame(pose.down)
    c = in_frame(com, rows)
    ground = c[2] - pose.com_height
    face = in_frame(pose.face, rows)
    d = base.moved(rows) if base is not None else None
    pts = d.all_points() if d is not None else face
    lo, hi = pts[:, :2].min(axis=0), pts[:, :2].max(axis=0)
    pad = 0.12 * max(float(np.max(hi - lo)), 1e-9)
    plate = np.array([[lo[0] - pad, lo[1] - pad, ground], [hi[0] + pad, lo[1] - pad, ground],
                      [hi[0] + pad, hi[1] + pad, ground], [lo[0] - pad, hi[1] + pad, ground]])
    ax.add_collection3d(Poly3DCollection([plate], facecolors="#9e9e9e", alpha=0.25, edgecolors="none"))
    if d is not None:
        draw_3d(ax, d, colours, alpha=0.75, extra_points=plate)
    loop = np.vstack((face, face[:1]))
    ax.plot(loop[:, 0], loop[:, 1], np.full(len(loop), ground), color=INK, linewidth=2)
    draw_com_3d(ax, c, label="centre of mass", markersize=7)
    ax.plot([c[0], c[0]], [c[1], c[1]], [c[2], ground], linestyle="--", color=INK, linewidth=1)
    ax.set_axis_off()


def _panel_2d(ax, pose, com, base: Drawing | None, colours) -> None:
    rows = rest_frame(pose.down)
    c = in_frame(com, rows)
    ground = c[1] - pose.com_height
    face = in_frame(pose.face, rows)
    if base is not None:
        draw_outline(ax, base.moved(rows), colours)
    else:
        ax.update_datalim(np.vstack((face, c[None], [c[0], ground])))
        ax.set_aspect("equal", adjustable="datalim")
    ax.axhline(ground, color=INK, linewidth=1)
    ax.plot(face[:, 0], np.full(len(face), ground), color=INK, linewidth=4)
    draw_com(ax, c, label="centre of mass", markersize=7)
    ax.plot([c[0], c[0]], [c[1], ground], linestyle="--", color=INK, linewidth=1)
    ax.set_xticks([])
    ax.set_yticks([])


def _panel_plan(ax, pose, com) -> None:
    """Without the body: the face it rests on, seen from above, and the foot of G."""
    rows = rest_frame(pose.down)
    face = in_frame(pose.face, rows)[:, :2]
    foot = in_frame(com, rows)[:2]
    if len(face) >= 3:
        ax.add_patch(Polygon(face, closed=True, facecolor="#cfd8e3", edgecolor=INK, linewidth=1.5))
    else:
        ax.plot(face[:, 0], face[:, 1], color=INK, linewidth=3)
    draw_com(ax, foot, label="foot of G", markersize=7)
    ax.update_datalim(np.vstack((face, foot)))
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xticks([])
    ax.set_yticks([])


def plot_poses(poses, body=None, fig=None, *, path: str | None = None,
               max_panels: int = MAX_PANELS, units=None):
    """Draw the pose gallery of a :class:`~plumbob.stability.poses.Poses` result.

    Parameters
    ----------
    poses : the result of :func:`plumbob.stability.resting_poses`.
    body : the body, to draw it resting in each pose; without it each panel shows the
        face the pose rests on and the foot of the centre of mass.
    fig : a matplotlib figure to draw the panels in (the gallery needs a grid of axes,
        so it takes a figure rather than one axes); None makes a new one.
    path : the file the body came from, for the title.
    max_panels : poses drawn at most, most probable first.
    units : the report's units (:class:`plumbob.report.ReportUnits`): each panel's height
        of the centre of mass in them (a part drawn in mm: mm); default SI.

    Returns
    -------
    matplotlib.figure.Figure, with one panel (an axes whose gid is ``"pose"``) per pose drawn.
    """
    shown = list(poses.poses[:max_panels])
    n = max(len(shown), 1)
    ncols = min(4, n)
    nrows = math.ceil(n / ncols)
    if fig is None:
        fig = new_figure((3.3 * ncols, 3.3 * nrows + 0.9))
    com = np.asarray(poses.center_of_mass, dtype=float)
    dim = com.size
    base = None
    colours: list[str] = []
    if body is not None:
        base = drawing(body, _PANEL_FACES)
        colours, _ = part_colours(base.pieces)
    for k, pose in enumerate(shown, 1):
        if body is not None and dim == 3:
            ax = new_3d_axes(fig, nrows, ncols, k)
            _panel_3d(ax, pose, com, base, colours)
        else:
            ax = fig.add_subplot(nrows, ncols, k)
            if dim == 2:  # a lamina: its ground line, the face on it, and G
                _panel_2d(ax, pose, com, base, colours)
            else:
                _panel_plan(ax, pose, com)
        ax.set_gid("pose")
        ax.set_title(_caption(k, pose, units), fontsize="small")
    title = title_for(body, path, f"resting poses ({len(poses)}), most probable first")
    fig.suptitle(title, fontsize="medium")
    notes = []
    if len(poses) > len(shown):
        rest = float(sum(p.probability for p in poses.poses[len(shown):]))
        notes.append(f"{len(poses) - len(shown)} less probable poses not drawn "
                     f"(total probability {rest:.3f})")
    if base is not None and base.note:
        notes.append(base.note)
    if notes:
        caption(fig, "; ".join(notes))
    return fig
