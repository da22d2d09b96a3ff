"""The tilt rose: how far the ground may tilt toward each direction before the body goes over.

A polar plot of the verdict's own ``tipping_over_deg`` around the vertical (one
sample per degree; a lamina has two directions, along its ground line), with the
required tilt as a dashed circle and the critical direction marked, so the weakest
direction is obvious at a glance. Every kind of support has its rose: on a line of
contact it rolls across (a cylinder on its side) the rose is the tilt that tips it over
the line's ends (and the legend says it rolls across the line at any tilt); on a
rocking point, the rocker's tilt each way.
"""

from __future__ import annotations

import numpy as np

from .style import INK, STATUS_COLOURS, fmt, new_figure, status

__all__ = ["tilt_rose", "rose_samples"]


def rose_samples(verdict, step_deg: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """(angles, rad, from the ground axis e1 toward e2; tipping tilts, degrees) of a verdict."""
    axes = np.asarray(verdict.support.frame.axes, dtype=float)
    if len(axes) == 1:  # a lamina: its ground line, both ways
        angles = np.array([0.0, np.pi])
        directions = np.array([axes[0], -axes[0]])
    else:
        angles = np.radians(np.arange(0.0, 360.0 + step_deg / 2, step_deg))
        directions = np.cos(angles)[:, None] * axes[0] + np.sin(angles)[:, None] * axes[1]
    over = getattr(verdict, "tipping_over_deg", verdict.tipping_angle_deg)
    tilts = np.array([over(d) for d in directions])
    return angles, tilts


def _direction_name(vector: np.ndarray, fallback: str) -> str:
    """``+x``, ``−y``, … for a coordinate axis, else ``fallback``."""
    k = int(np.argmax(np.abs(vector)))
    if not np.isclose(abs(vector[k]), 1.0):
        return fallback
    return ("+" if vector[k] > 0 else "−") + "xyz"[k]


def tilt_rose(verdict, ax=None, *, require_tilt_deg: float | None = None,
              names: tuple[str, ...] | None = None):
    """Draw the tilt rose of a :class:`~plumbob.stability.verdict.Verdict`; returns the figure.

    ax: a polar axes, or None for a new figure. require_tilt_deg: the circle to draw
    (default: the verdict's own required tilt, if any). names: the ground axes' names in
    the figure's frame (``("x", "y")``, ``("e1", "e2")``); default the body's axes they
    lie along.
    """
    if ax is None:
        fig = new_figure((4.8, 4.8))
        ax = fig.add_subplot(projection="polar")
    required = verdict.required_tilt_deg if require_tilt_deg is None else require_tilt_deg
    angles, tilts = rose_samples(verdict)
    colour = STATUS_COLOURS[status(verdict)]
    shown = np.maximum(tilts, 0.0)
    if len(angles) == 2:
        ax.bar(angles, shown, width=0.18, color=colour, edgecolor=INK, alpha=0.8,
               label="critical tilt", gid="rose")
    else:
        ax.fill(angles, shown, color=colour, alpha=0.35, gid="rose")
        ax.plot(angles, shown, color=INK, linewidth=1.4, label="critical tilt by direction")
    top = max(float(shown.max()), float(required or 0.0), 1.0) * 1.3  # marks clear of labels
    if required is not None:
        circle = np.linspace(0, 2 * np.pi, 181)
        ax.plot(circle, np.full_like(circle, required), linestyle="--", color=INK, linewidth=1.2,
                label=f"required {fmt(required, 3)}°", gid="required tilt")
    g = np.asarray(verdict.support.frame.axes, dtype=float) @ np.asarray(verdict.critical_direction)
    critical = float(np.arctan2(g[1], g[0])) if len(g) > 1 else (0.0 if g[0] > 0 else np.pi)
    ax.plot([critical], [max(verdict.critical_tilt_deg, 0.0)], marker="v", markersize=11,
            color=STATUS_COLOURS["topples"], markeredgecolor=INK, linestyle="none",
            label=f"weakest: {fmt(verdict.critical_tilt_deg, 3)}°", gid="critical")
    rolls = getattr(verdict, "rolls", None)
    if rolls is not None:  # what the rose cannot show as a tilt
        ax.plot([], [], linestyle="none", marker="$\\circlearrowleft$", color=INK,
                label=f"rolls {rolls} at any tilt", gid="rolls")
    ax.set_ylim(0, top)
    # the radial scale along the diagonal farthest from the weakest mark, few labels
    diagonals = np.radians([22.5, 157.5, 202.5, 337.5])
    away = diagonals[np.argmax(np.abs(np.angle(np.exp(1j * (diagonals - critical)))))]
    ax.set_rlabel_position(np.degrees(away))
    from matplotlib.ticker import MaxNLocator

    ax.yaxis.set_major_locator(MaxNLocator(4))
    axes = np.asarray(verdict.support.frame.axes, dtype=float)
    if names is not None:
        labels = [f"+{names[0]}", "", f"−{names[0]}", ""]
        if len(axes) > 1:
            labels[1::2] = f"+{names[1]}", f"−{names[1]}"
    else:
        labels = [_direction_name(axes[0], "+e1"), "", _direction_name(-axes[0], "−e1"), ""]
        if len(axes) > 1:  # a lamina tilts only along its ground line
            labels[1::2] = _direction_name(axes[1], "+e2"), _direction_name(-axes[1], "−e2")
    ax.set_xticks(np.radians([0, 90, 180, 270]))
    ax.set_xticklabels(["toward " + labels[0]] + labels[1:])
    ax.tick_params(axis="x", pad=8)
    title = "tilt rose: critical tilt (°) by direction"
    if verdict.verdict == "topples":  # in the title, not over the marks at the centre
        title = "tilt rose: it topples already, on level ground"
    ax.set_title(title, fontsize="medium",
                 color=STATUS_COLOURS["topples"] if verdict.verdict == "topples" else INK)
    ax.legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.05, 1.0))
    return ax.figure
