"""``plot_body``: a body and its centre of mass (``plumbob mass --plot``, ``body.plot()``)."""

from __future__ import annotations

import numpy as np

from .geometry import DISPLAY_FACES, drawing
from .lamina import draw_com, draw_legend, draw_outline, draw_silhouette
from .solid import draw_3d, draw_com_3d, new_3d_axes
from .style import caption, fmt, fmt_at, label_axes, new_figure, part_colours, title_for, units_or_si

__all__ = ["plot_body"]


def _com(body, props) -> np.ndarray:
    props = body.mass_properties() if props is None else props
    return np.asarray(props.center_of_mass, dtype=float)


def _moments(props, u) -> str:
    """The principal moments in the picture's inertia unit (round-off of a flat body as 0)."""
    moments = np.asarray(u.inertia(np.asarray(props.principal_moments, dtype=float)))
    top = float(np.abs(moments).max(initial=0.0))
    return "(" + ", ".join(fmt(0.0 if abs(m) < 1e-12 * top else m, 6) for m in moments) + ")"


def plot_body(body, ax=None, *, props=None, path: str | None = None,
              max_faces: int = DISPLAY_FACES, units=None):
    """Draw ``body`` with its centre of mass marked; returns the figure.

    Parameters
    ----------
    body : a plumbob body (lamina, solid, assembly or particle system).
    ax : matplotlib axes, optional. ``None`` makes a new figure: a lamina in its plane,
        a solid as a shaded 3-D view beside views from the side (x–z) and from below
        (x–y). A 3-D axes gets the 3-D view; a plain axes the lamina, or the solid seen
        from the side.
    props : the body's mass properties, if already computed.
    path : the file it came from, for the title.
    max_faces : triangles drawn at most (large meshes are decimated for display).
    units : the report's units (:class:`plumbob.report.ReportUnits`: a part drawn in mm
        is labelled in mm, g and g·mm²); default SI.

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> from plumbob.bodies.primitives import rectangle
    >>> fig = plot_body(rectangle(2.0, 1.0))
    >>> [a.get_gid() for a in fig.axes[0].lines if a.get_gid()]
    ['centre of mass']
    """
    d = drawing(body, max_faces)
    props = body.mass_properties() if props is None else props
    com = _com(body, props)
    u = units_or_si(units)
    colours, legend = part_colours(d.pieces)
    title = title_for(body, path, "centre of mass")
    size = float(np.ptp(d.all_points(), axis=0).max())
    if d.dim == 2:
        fig = ax.figure if ax is not None else new_figure()
        ax = ax if ax is not None else fig.add_subplot()
        draw_outline(ax, d, colours)
        draw_com(ax, com, scale=size, units=u)
        label_axes(ax, units=u)
        ax.set_title(title)
        draw_legend(ax, legend if len(d.pieces) > 1 else [])
        return fig
    if ax is not None:
        if hasattr(ax, "zaxis"):
            draw_3d(ax, d, colours)
            draw_com_3d(ax, com, scale=size, units=u)
            label_axes(ax, ("x", "y", "z"), u)
        else:
            draw_silhouette(ax, d, colours, 0, 2)
            draw_com(ax, com[[0, 2]], label=f"centre of mass G {fmt_at(com, u, scale=size)}")
            label_axes(ax, ("x", "z"), u)
        return ax.figure
    fig = new_figure((13, 4.6))
    grid = fig.add_gridspec(1, 3, width_ratios=(1.3, 1, 1))
    ax3 = new_3d_axes(fig, grid[0, 0])
    draw_3d(ax3, d, colours)
    draw_com_3d(ax3, com, scale=size, units=u)
    label_axes(ax3, ("x", "y", "z"), u)
    ax3.set_title("3-D view")
    for k, (across, vertical, name) in enumerate(((0, 2, "from the side (x–z)"),
                                                   (0, 1, "from below (x–y)"))):
        axk = fig.add_subplot(grid[0, k + 1])
        draw_silhouette(axk, d, colours, across, vertical)
        draw_com(axk, com[[across, vertical]], label="centre of mass G")
        label_axes(axk, ("xyz"[across], "xyz"[vertical]), u)
        if vertical == 1:
            axk.invert_yaxis()  # seen from below, +y points down the page
        axk.set_title(name)
    draw_legend(fig.axes[1], legend if len(d.pieces) > 1 else [], loc="upper right")
    text = (f"G = {fmt_at(com, u, 6, scale=size)}, mass {fmt(u.mass(props.mass), 6)} "
            f"{u.mass_unit}, principal moments {_moments(props, u)} {u.unit('inertia')}")
    if d.note:
        text += f"\n{d.note}"
    fig.suptitle(title)
    caption(fig, text)
    return fig
