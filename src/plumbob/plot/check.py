"""``plot_check``: the verdict drawn — body, centre of mass, support, tipping edges, tilt rose.

Everything is drawn in one frame per figure: the verdict's ground frame (e1, e2, up),
which is the body's own frame (x, y, z) for the default down (−z; −y for a lamina), so
the marks sit at the numbers the report prints; in any other orientation (``--pose K``,
``--down``) every panel, the rose's directions and the centre of mass in the title are
in e1, e2, up. The side view looks across the weakest direction (the critical
direction runs left to right, and its axis says so), so what makes a body weak that
way — an overhang, a drawer — is in view. The foot of the centre of mass is coloured by
margin: green stands, amber below the required tilt (or neutral), red topples; the words
are in the legend. Legends sit beside their panels and labels beside what they name, so
nothing covers anything (the tests measure the drawn boxes).
"""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Polygon

from .geometry import DISPLAY_FACES, Drawing, drawing, in_frame, rest_frame
from .lamina import draw_com, draw_legend, draw_outline, draw_silhouette
from .loads import draw_loads
from .rose import tilt_rose
from .solid import draw_3d, draw_com_3d, new_3d_axes
from .style import (
    INK,
    STATUS_COLOURS,
    STATUS_WORDS,
    caption,
    fmt,
    fmt_at,
    fmt_length,
    fmt_point,
    label_axes,
    new_figure,
    part_colours,
    scale_ticks,
    status,
    title_for,
    units_or_si,
)

__all__ = ["plot_check"]

_GROUND = "#9e9e9e"
_MAX_EDGE_LABELS = 12


def _size(verdict) -> float:
    """The body's size (what the report's round-off is relative to)."""
    return verdict.support.size


def _frame(verdict) -> np.ndarray:
    return rest_frame(verdict.down, verdict.support.frame.axes)


def _names(verdict, rows: np.ndarray) -> tuple[str, ...]:
    """Axis names: the body's own when the frame is the identity."""
    if np.allclose(rows, np.eye(len(rows))):
        return ("x", "y", "z")[: len(rows)]
    return ("e1", "e2", "up") if len(rows) == 3 else ("e1", "up")


def _com_label(verdict, rows: np.ndarray, u) -> str:
    """G in the figure's frame (its axes' names when that is not the body's own), in the
    report's length unit."""
    names = _names(verdict, rows)
    where = "" if names[0] == "x" else f" ({', '.join(names)})"
    point = in_frame(verdict.center_of_mass, rows)
    return f"centre of mass G{where} {fmt_at(point, u, scale=_size(verdict))}"


def _way_name(verdict, rows: np.ndarray, vector=None) -> str:
    """A horizontal direction (default the side view's, :func:`side_rows`) in the figure's
    frame: ``−y``, ``+e1``, or its components."""
    names = _names(verdict, rows)
    vector = side_rows(verdict, rows)[0] if vector is None else vector
    g = in_frame(vector, rows)[:-1]
    k = int(np.argmax(np.abs(g)))
    if abs(abs(g[k]) - 1.0) < 1e-9:
        return ("+" if g[k] > 0 else "−") + names[k]
    return f"{fmt_point(g, 3)} in {', '.join(names[:-1])}"


def _foot_label(verdict, u) -> str:
    word = STATUS_WORDS[status(verdict)] if verdict.verdict != "neutral" else "neutral"
    return f"foot of G: {word}, margin {fmt_length(verdict.margin, u, 3)}"


def _draw_foot(ax, point, verdict, u) -> None:
    colour = STATUS_COLOURS[status(verdict)]
    marker = {"stands": "s", "amber": "D", "topples": "X"}[status(verdict)]
    (foot,) = ax.plot(*[[c] for c in point], marker=marker, markersize=10, color=colour,
                      markeredgecolor=INK, linestyle="none", zorder=19,
                      label=_foot_label(verdict, u))
    foot.set_gid("foot")


def _lamina_panel(ax, verdict, d: Drawing | None, rows: np.ndarray, u) -> None:
    com = in_frame(verdict.center_of_mass, rows)
    foot = in_frame(verdict.support.plane_point, rows)
    support = in_frame(verdict.support.polygon, rows)
    if d is not None:
        colours, legend = part_colours(d.pieces)
        draw_outline(ax, d, colours)
    lo, hi = ax.get_xlim() if d is not None else (support[:, 0].min() - 1, support[:, 0].max() + 1)
    width = hi - lo
    ground = foot[1]
    ax.axhspan(ground - 0.04 * width, ground, color=_GROUND, alpha=0.5, hatch="///",
               linewidth=0, gid="ground")
    ax.axhline(ground, color=INK, linewidth=1.0)
    (base,) = ax.plot(support[:, 0], support[:, 1], color=INK, linewidth=5, solid_capstyle="butt",
                      label=f"support ({verdict.support.kind})", zorder=15)
    base.set_gid("support")
    ax.annotate("", xy=foot, xytext=com, zorder=18,
                arrowprops=dict(arrowstyle="-|>", linestyle="--", color=INK, linewidth=1.2))
    ax.plot([], [], linestyle="--", color=INK, label="line of action of the weight")
    draw_com(ax, com, label=_com_label(verdict, rows, u))
    _draw_foot(ax, foot, verdict, u)
    for edge in verdict.edges:
        tip = in_frame(edge.start, rows)
        (mark,) = ax.plot([tip[0]], [tip[1]], marker="^", markersize=10, color="white",
                          markeredgecolor=INK, linestyle="none", zorder=16)
        mark.set_gid("tipping point")
        ax.annotate(f"tips here at {fmt(edge.tipping_angle_deg, 3)}°", xy=tip, xytext=(0, -22),
                    textcoords="offset points", ha="center", va="top", fontsize="small",
                    arrowprops=dict(arrowstyle="-", color=INK, linewidth=0.6))
    ax.update_datalim([[lo, ground - 0.12 * width]])
    ax.autoscale_view()
    label_axes(ax, _names(verdict, rows), u)
    draw_legend(ax, legend if d is not None and len(d.pieces) > 1 else [], loc="upper left")


def _plan_panel(ax, verdict, d: Drawing | None, rows: np.ndarray, u) -> None:
    """The ground seen from above: footprint, support polygon, foot of G, critical direction."""
    if d is not None:
        shapes = draw_silhouette(ax, d, ["#dddddd"] * len(d.pieces), 0, 1)
        for k, artist in enumerate(shapes):  # one legend entry for the whole footprint
            artist.set_label("footprint" if k == 0 else "_footprint")
    support = in_frame(verdict.support.polygon, rows)[:, :2]
    foot = in_frame(verdict.support.plane_point, rows)[:2]
    colour = STATUS_COLOURS[status(verdict)]
    if len(support) >= 3:
        patch = Polygon(support, closed=True, facecolor=colour, alpha=0.25, edgecolor=INK,
                        linewidth=2, hatch="..", label="support polygon", zorder=10)
        patch.set_gid("support polygon")
        ax.add_patch(patch)
    else:
        (line,) = ax.plot(support[:, 0], support[:, 1], color=INK, linewidth=4, marker="o",
                          label=f"support ({verdict.support.kind})", zorder=10)
        line.set_gid("support polygon")
    _draw_foot(ax, foot, verdict, u)
    size = float(np.ptp(ax.dataLim.get_points(), axis=0).max()) if d is not None else \
        max(float(np.ptp(support, axis=0).max()), abs(verdict.margin), 1e-9)
    ax.update_datalim(np.vstack((support, foot)))
    direction = in_frame(verdict.critical_direction, rows)[:2]
    # the arrow alone on the plan; its words in the legend, beside the panel
    arrow = ax.annotate("", xy=foot + 0.3 * size * direction, xytext=foot, zorder=21,
                        arrowprops=dict(arrowstyle="-|>", color=STATUS_COLOURS["topples"],
                                        linewidth=2))
    arrow.set_gid("weakest way")
    ax.plot([], [], color=STATUS_COLOURS["topples"], linewidth=2, marker=">",
            label=f"weakest way ({_way_name(verdict, rows, verdict.critical_direction)}): "
                  f"{fmt(verdict.critical_tilt_deg, 3)}°")
    if len(verdict.edges) <= _MAX_EDGE_LABELS and verdict.support.kind == "polygon":
        for edge in verdict.edges:  # just inside its edge, clear of the foot and the arrow
            a, b = in_frame(edge.start, rows)[:2], in_frame(edge.end, rows)[:2]
            ab = b - a
            inward = -in_frame(edge.normal, rows)[:2]
            # the arrow crosses the weakest edge, and the foot may sit near an edge, where
            # each projects onto it: a label near there moves toward the far end
            t0 = float((foot - a) @ ab / max(float(ab @ ab), 1e-300))
            crossed = float(inward @ direction) < -0.999 or abs(edge.distance) < 0.15 * size
            t = 0.5 if not crossed or abs(t0 - 0.5) > 0.3 else (0.2 if t0 > 0.5 else 0.8)
            label = ax.annotate(f"{fmt(edge.tipping_angle_deg, 3)}°", xy=a + t * ab,
                                xytext=tuple(6 * inward), textcoords="offset points",
                                fontsize="x-small", zorder=12,
                                ha="left" if inward[0] > 0.5 else "right" if inward[0] < -0.5
                                else "center",
                                va="bottom" if inward[1] > 0.5 else "top" if inward[1] < -0.5
                                else "center")
            label.set_gid("edge label")
    ax.autoscale_view()
    ax.set_aspect("equal", adjustable="datalim")
    names = _names(verdict, rows)
    label_axes(ax, names[:2], u)
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.02, 1.0))
    ax.set_title(f"ground plan ({names[0]}–{names[1]}): support and foot of G", fontsize="medium")


def _ground_patch(verdict, d: Drawing | None, rows: np.ndarray) -> np.ndarray:
    pts = d.all_points() if d is not None else in_frame(verdict.support.polygon, rows)
    lo, hi = pts[:, :2].min(axis=0), pts[:, :2].max(axis=0)
    pad = 0.15 * max(float(np.max(hi - lo)), 1e-9)
    z = in_frame(verdict.support.plane_point, rows)[2]
    return np.array([[lo[0] - pad, lo[1] - pad, z], [hi[0] + pad, lo[1] - pad, z],
                     [hi[0] + pad, hi[1] + pad, z], [lo[0] - pad, hi[1] + pad, z]])


def _solid_3d_panel(ax, verdict, d: Drawing | None, rows: np.ndarray, u) -> None:
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    ground = _ground_patch(verdict, d, rows)
    plate = Poly3DCollection([ground], facecolors=_GROUND, alpha=0.25, edgecolors="none")
    plate.set_gid("ground")
    ax.add_collection3d(plate)
    if d is not None:
        colours, _ = part_colours(d.pieces)
        draw_3d(ax, d, colours, extra_points=ground)
    support = in_frame(verdict.support.polygon, rows)
    loop = np.vstack((support, support[:1])) if len(support) >= 3 else support
    ax.plot(*loop.T, color=INK, linewidth=2.5, marker="o" if len(support) < 3 else None,
            label="support polygon", gid="support polygon")
    com = in_frame(verdict.center_of_mass, rows)
    foot = in_frame(verdict.support.plane_point, rows)
    ax.plot(*np.array([com, foot]).T, linestyle="--", color=INK, label="weight", zorder=18)
    draw_com_3d(ax, com, label=_com_label(verdict, rows, u))
    _draw_foot(ax, foot, verdict, u)
    # the axes' names in the title: a 3-D axis' own label lands on its tick labels
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        scale_ticks(axis, float(u.length(1.0)))
    ax.set_title(f"3-D view, resting on the ground (axes {', '.join(_names(verdict, rows))}, "
                 f"{u.length_unit})", fontsize="medium")


def side_rows(verdict, rows: np.ndarray) -> np.ndarray:
    """Rows (along, across, up) of the side view: ``along`` the critical direction (body
    frame, horizontal) — under loads, the critical edge's outward normal — so the side view
    looks across the weakest way."""
    up = rows[-1]
    loaded = getattr(verdict, "loaded", None)
    along = np.asarray(verdict.critical_direction if loaded is None else loaded.edge_normal,
                       dtype=float)
    along = along - (along @ up) * up
    norm = float(np.linalg.norm(along))
    along = rows[0] if norm < 1e-12 else along / norm
    return np.array([along, np.cross(up, along), up])


def _side_panel(ax, verdict, d: Drawing | None, rows: np.ndarray, u,
                legend: list[tuple[str, str]] | None = None) -> None:
    """The body from the side, cut by the vertical plane of the critical direction: that
    direction left to right (``d`` drawn in :func:`side_rows`)."""
    side = side_rows(verdict, rows)
    if d is not None:
        colours, _ = part_colours(d.pieces)
        draw_silhouette(ax, d, colours, 0, 2)
    com = in_frame(verdict.center_of_mass, side)
    foot = in_frame(verdict.support.plane_point, side)
    support = in_frame(verdict.support.polygon, side)
    lo, hi = ax.get_xlim() if d is not None else (support[:, 0].min() - 1, support[:, 0].max() + 1)
    ax.axhline(foot[2], color=INK, linewidth=1.0)
    ax.axhspan(foot[2] - 0.04 * (hi - lo), foot[2], color=_GROUND, alpha=0.5, hatch="///",
               linewidth=0, gid="ground")
    ax.plot([support[:, 0].min(), support[:, 0].max()], [foot[2]] * 2, color=INK, linewidth=5,
            solid_capstyle="butt", label="support", gid="support")
    ax.annotate("", xy=foot[[0, 2]], xytext=com[[0, 2]], zorder=18,
                arrowprops=dict(arrowstyle="-|>", linestyle="--", color=INK, linewidth=1.2))
    draw_com(ax, com[[0, 2]], label="centre of mass G")
    _draw_foot(ax, foot[[0, 2]], verdict, u)
    ax.update_datalim([[lo, foot[2] - 0.08 * (hi - lo)]])
    ax.autoscale_view()
    names = _names(verdict, rows)
    way = _way_name(verdict, rows)
    unit = u.length_unit
    ax.set_xlabel(f"along the weakest way, toward {way} →, {unit}")
    ax.set_ylabel(f"{names[-1]}, {unit}")
    scale_ticks(ax.xaxis, float(u.length(1.0)))
    scale_ticks(ax.yaxis, float(u.length(1.0)))
    ax.set_title(f"from the side, across the weakest way: toward {way}", fontsize="medium")
    if legend:  # an assembly: one entry per part
        draw_legend(ax, legend, loc="upper left", bbox_to_anchor=(1.02, 1.0))


def _summary(verdict, rows: np.ndarray, u) -> str:
    settled = getattr(verdict, "settling", None)
    word = verdict.verdict if settled is None else f"{verdict.verdict} ({settled.phrase})"
    names = _names(verdict, rows)
    where = "" if names[0] == "x" else f" ({', '.join(names)})"
    point = in_frame(verdict.center_of_mass, rows)
    text = (f"{word}: critical tilt {fmt(verdict.critical_tilt_deg, 3)}°, margin "
            f"{fmt_length(verdict.margin, u, 3)}, height of G "
            f"{fmt_length(verdict.com_height, u, 4)}, energy to topple "
            f"{fmt(verdict.energy_to_topple, 4)} J, G{where} "
            f"{fmt_at(point, u, scale=_size(verdict))}")
    if verdict.required_tilt_deg is not None:
        text += f"; required tilt {fmt(verdict.required_tilt_deg, 3)}°: " + \
            ("PASS" if verdict.passes else "FAIL")
    loaded = getattr(verdict, "loaded", None)
    if loaded is not None:
        factor = loaded.overturning_safety_factor
        text += (f"; under the loads: {loaded.verdict}, factor of safety "
                 f"{'—' if factor is None else fmt(factor, 3)}")
    return text


def plot_check(verdict, body=None, ax=None, *, path: str | None = None,
               max_faces: int = DISPLAY_FACES, units=None):
    """Draw a stability verdict; returns the figure.

    Parameters
    ----------
    verdict : the result of :func:`plumbob.stability.check`.
    body : the body checked, to draw its outline; without it only the support, the
        centre of mass and the tilt rose are drawn.
    ax : None for a new figure (a lamina and its tilt rose; a solid's 3-D view, side
        view, ground plan and tilt rose); a given axes gets the main panel only (the
        lamina, or the solid's ground plan — its 3-D view on a 3-D axes).
    path : the file the body came from, for the title.
    max_faces : triangles drawn at most.
    units : the report's units (:class:`plumbob.report.ReportUnits`): margins, heights and
        points labelled in them (a part drawn in mm reads in mm); default SI.

    Returns
    -------
    matplotlib.figure.Figure
    """
    rows = _frame(verdict)
    u = units_or_si(units)
    base = drawing(body, max_faces) if body is not None else None
    d = base.moved(rows) if base is not None else None
    lamina = verdict.support.frame.dim == 2
    names = _names(verdict, rows)
    if ax is not None:
        if lamina:
            _lamina_panel(ax, verdict, d, rows, u)
        elif hasattr(ax, "zaxis"):
            _solid_3d_panel(ax, verdict, d, rows, u)
        else:
            _plan_panel(ax, verdict, d, rows, u)
        return ax.figure
    if lamina:
        fig = new_figure((12, 5.4))
        grid = fig.add_gridspec(1, 2, width_ratios=(1.7, 1))
        main = fig.add_subplot(grid[0, 0])
        _lamina_panel(main, verdict, d, rows, u)
        draw_loads(main, verdict, rows, (0, 1), _size(verdict))
        tilt_rose(verdict, fig.add_subplot(grid[0, 1], projection="polar"), names=names[:1])
    elif d is None:
        fig = new_figure((11, 5))
        _plan_panel(fig.add_subplot(1, 2, 1), verdict, None, rows, u)
        tilt_rose(verdict, fig.add_subplot(1, 2, 2, projection="polar"), names=names[:2])
    else:
        fig = new_figure((14, 10))
        _solid_3d_panel(new_3d_axes(fig, 2, 2, 1), verdict, d, rows, u)
        _, legend = part_colours(d.pieces)
        side = fig.add_subplot(2, 2, 2)
        across = side_rows(verdict, rows)
        _side_panel(side, verdict, base.moved(across), rows, u,
                    legend if len(d.pieces) > 1 else None)
        draw_loads(side, verdict, across, (0, 2), _size(verdict))
        _plan_panel(fig.add_subplot(2, 2, 3), verdict, d, rows, u)
        tilt_rose(verdict, fig.add_subplot(2, 2, 4, projection="polar"), names=names[:2])
    fig.suptitle(title_for(body, path, "plumbob check") + "\n" + _summary(verdict, rows, u),
                 fontsize="medium")
    if d is not None and d.note:
        caption(fig, d.note)
    return fig
