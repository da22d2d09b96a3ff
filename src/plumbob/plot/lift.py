"""``plot_lift``: the body over its ground datum and the height its centre of mass is lifted."""

from __future__ import annotations

import numpy as np

from .geometry import DISPLAY_FACES, drawing
from .lamina import draw_com, draw_legend, draw_outline, draw_silhouette
from .style import (
    INK,
    caption,
    fmt,
    fmt_length,
    label_axes,
    new_figure,
    part_colours,
    title_for,
    units_or_si,
)

__all__ = ["plot_lift"]


def plot_lift(lift, body, ax=None, *, props=None, path: str | None = None,
              max_faces: int = DISPLAY_FACES, units=None):
    """Draw a :class:`~plumbob.energy.LiftEnergy` result: the body from the side (x–z; a
    lamina in its plane), the datum, the centre of mass and its height above the datum.

    ax: None for a new figure. props: the body's mass properties, if computed. units:
    the report's units (:class:`plumbob.report.ReportUnits`; a part drawn in mm reads in mm
    and g), default SI. Returns the figure.
    """
    u = units_or_si(units)
    props = body.mass_properties() if props is None else props
    com = np.asarray(props.center_of_mass, dtype=float)
    d = drawing(body, max_faces)
    colours, legend = part_colours(d.pieces)
    fig = ax.figure if ax is not None else new_figure((7, 6))
    ax = ax if ax is not None else fig.add_subplot()
    if d.dim == 2:
        draw_outline(ax, d, colours)
        point, names = com[:2], ("x", "y")
    else:
        draw_silhouette(ax, d, colours, 0, 2)
        point, names = com[[0, 2]], ("x", "z")
    width = float(np.ptp(ax.dataLim.get_points(), axis=0).max())
    ax.axhspan(lift.datum - 0.03 * width, lift.datum, color="#9e9e9e", alpha=0.5, hatch="///",
               linewidth=0)
    (datum,) = ax.plot([], [], color=INK, linewidth=1.2, label=f"ground datum, {fmt_length(lift.datum, u)}")
    ax.axhline(lift.datum, color=INK, linewidth=1.2).set_gid("datum")
    datum.set_gid("datum legend")
    ax.annotate("", xy=(point[0] + 0.08 * width, point[1]), xytext=(point[0] + 0.08 * width, lift.datum),
                arrowprops=dict(arrowstyle="<|-|>", color=INK, linewidth=1.2))
    ax.text(point[0] + 0.1 * width, (point[1] + lift.datum) / 2,
            f"z_G − datum = {fmt_length(lift.com_height, u)}", va="center", fontsize="small",
            bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="none", alpha=0.85))
    draw_com(ax, point, scale=width, units=u)
    ax.update_datalim([[point[0], lift.datum - 0.06 * width]])
    ax.autoscale_view()
    label_axes(ax, names, u)
    draw_legend(ax, legend if len(d.pieces) > 1 else [], loc="upper left")
    ax.set_title(title_for(body, path, "plumbob lift") +
                 f"\nlift energy M g z_G = {fmt(lift.lift_energy)} J (mass {fmt(u.mass(lift.mass))} "
                 f"{u.mass_unit})",
                 fontsize="medium")
    if d.note:
        caption(fig, d.note)
    return fig
