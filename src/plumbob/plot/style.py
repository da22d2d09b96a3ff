"""One look for every picture: colours that survive greyscale, labels with units, figures.

Verdict colours differ in lightness as well as hue (dark green, light amber, mid red)
and every coloured mark also carries a word or a marker shape, so a greyscale print
still reads. Figures are made with pyplot only when the caller gave no axes (the
scipy.spatial convention), so notebooks show them; the CLI draws on the Agg backend.
"""

from __future__ import annotations

import numpy as np

__all__ = ["STATUS_COLOURS", "PART_COLOURS", "status", "new_figure", "label_axes", "equal_3d",
           "fmt", "fmt_point", "fmt_length", "fmt_at", "part_colours", "title_for", "caption",
           "SI", "units_or_si", "scale_ticks"]

STATUS_COLOURS = {"stands": "#1a7f37", "amber": "#f0b400", "topples": "#c62828"}
STATUS_WORDS = {"stands": "stands", "amber": "below the required tilt", "topples": "topples"}
PART_COLOURS = ("#8fa8c8", "#d9a066", "#9cc89a", "#c79ac7", "#c8c070", "#e08f8f", "#7fc8c8")
COM_STYLE = dict(marker="o", markersize=9, markerfacecolor="white", markeredgecolor="black",
                 markeredgewidth=2.0, linestyle="none", zorder=20)
INK = "#222222"


_POWER = {2: "²", 3: "³"}


class SIUnits:
    """The units a picture labels lengths, masses and inertias in when none are given: SI.
    The duck type of :class:`plumbob.report.ReportUnits` (which this room may not import):
    a command passes the text report's units, so a part drawn in mm is drawn in mm and g
    too (``length``, ``mass``, ``measure``, ``density``, ``inertia`` convert from SI;
    ``unit`` names the symbol)."""

    length_unit, mass_unit = "m", "kg"

    def length(self, value):
        return value

    def mass(self, value):
        return value

    def measure(self, value, dim: int = 3):
        return value

    def density(self, value, dim: int = 3):
        return value

    def inertia(self, value):
        return value

    def unit(self, quantity: str, dim: int = 3) -> str:
        return {"length": "m", "mass": "kg", "inertia": "kg·m²", "measure": f"m{_POWER[dim]}",
                "density": f"kg/m{_POWER[dim]}"}[quantity]


SI = SIUnits()


def units_or_si(units):
    """``units`` (a :class:`~plumbob.report.ReportUnits`), or :data:`SI` for None."""
    return SI if units is None else units


def status(verdict) -> str:
    """``"stands"``, ``"amber"`` (stands, but below the required tilt, or neutral) or
    ``"topples"``, for a verdict-like object."""
    if verdict.verdict == "topples":
        return "topples"
    if verdict.verdict != "stands" or getattr(verdict, "passes", None) is False:
        return "amber"
    return "stands"


def new_figure(figsize=(6.4, 4.8)):
    """A new figure: pyplot's (shown in notebooks, ``plt.show()`` in scripts)."""
    import matplotlib.pyplot as plt

    return plt.figure(figsize=figsize, layout="constrained")


def fmt(value: float, digits: int = 4) -> str:
    """A number for a label: ``digits`` significant figures, no trailing noise."""
    value = float(value)
    if value == 0 or not np.isfinite(value):
        return f"{value:g}"
    return f"{value:.{digits}g}"


def fmt_point(point, digits: int = 4, scale: float | None = None) -> str:
    """``(x, y[, z])``; values far below ``scale`` (the body's size; default the point's
    largest coordinate), which the few digits of a label cannot show, shown as 0."""
    point = np.asarray(point, dtype=float)
    scale = np.abs(point).max(initial=0.0) if scale is None else scale
    point = np.where(np.abs(point) < 1e-7 * scale, 0.0, point)
    return "(" + ", ".join(fmt(v, digits) for v in point) + ")"


def fmt_length(value: float, units=None, digits: int = 4) -> str:
    """A length, m, in the picture's units: ``5 mm``.

    >>> fmt_length(0.005), fmt_length(0.005, _Millimetres())
    ('0.005 m', '5 mm')
    """
    u = units_or_si(units)
    return f"{fmt(u.length(float(value)), digits)} {u.length_unit}"


def fmt_at(point, units=None, digits: int = 4, scale: float | None = None) -> str:
    """A point, m, in the picture's units (round-off below ``scale``, m, as 0): ``(1, 2) mm``."""
    u = units_or_si(units)
    scale = None if scale is None else float(u.length(float(scale)))
    return f"{fmt_point(u.length(np.asarray(point, dtype=float)), digits, scale)} {u.length_unit}"


class _Millimetres(SIUnits):  # for the doctests: what plumbob.report.ReportUnits("mm") does
    length_unit = "mm"

    def length(self, value):
        return value * 1e3


def scale_ticks(axis, factor: float) -> None:
    """Ticks of ``axis`` (drawn in metres) at round numbers of the report's length unit,
    ``factor`` per metre, and labelled in it: the axes read in mm or inches while the
    geometry stays in metres (a lone tick at a short side's middle stays one, rounded).

    >>> import matplotlib.pyplot as plt
    >>> ax = plt.figure().add_subplot()
    >>> _ = ax.set_xlim(0, 0.05)
    >>> scale_ticks(ax.xaxis, 1 / 0.0254)
    >>> [ax.xaxis.get_major_formatter()(v, 0) for v in ax.xaxis.get_major_locator()()]
    ['0', '0.25', '0.5', '0.75', '1', '1.25', '1.5', '1.75', '2']
    """
    if factor == 1.0:
        return
    from matplotlib.ticker import FixedLocator, FuncFormatter, MaxNLocator

    class Scaled(MaxNLocator):
        def tick_values(self, vmin, vmax):
            return np.asarray(super().tick_values(vmin * factor, vmax * factor)) / factor

    old = axis.get_major_locator()
    if isinstance(old, FixedLocator) and len(old.locs) == 1:
        axis.set_major_locator(FixedLocator([float(f"{old.locs[0] * factor:.3g}") / factor]))
    else:
        nbins = old._nbins if isinstance(old, MaxNLocator) else "auto"
        axis.set_major_locator(Scaled(nbins=nbins, steps=[1, 2, 2.5, 5, 10]))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v * factor:.6g}"))


def label_axes(ax, names=("x", "y"), units=None) -> None:
    """Axis labels with the length unit (``x, m``; ``x, mm`` for a part drawn in mm, its
    ticks scaled to match)."""
    u = units_or_si(units)
    unit, factor = u.length_unit, float(u.length(1.0))
    ax.set_xlabel(f"{names[0]}, {unit}")
    ax.set_ylabel(f"{names[1]}, {unit}")
    scale_ticks(ax.xaxis, factor)
    scale_ticks(ax.yaxis, factor)
    if len(names) > 2 and hasattr(ax, "set_zlabel"):
        ax.set_zlabel(f"{names[2]}, {unit}")
        scale_ticks(ax.zaxis, factor)


def equal_3d(ax, points: np.ndarray) -> None:
    """Equal scales on a 3-D axes spanning ``points`` (n, 3)."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    span = np.maximum(hi - lo, 0.3 * max(float(np.max(hi - lo)), 1e-12))  # a flat body stays visible
    mid = (lo + hi) / 2
    ax.set_xlim(mid[0] - span[0] / 2, mid[0] + span[0] / 2)
    ax.set_ylim(mid[1] - span[1] / 2, mid[1] + span[1] / 2)
    ax.set_zlim(mid[2] - span[2] / 2, mid[2] + span[2] / 2)
    ax.set_box_aspect(tuple(span))
    from matplotlib.ticker import FixedLocator, MaxNLocator

    # fewer ticks on a short side (its labels crowd in projection: one, at its middle)
    for axis, extent, centre in zip((ax.xaxis, ax.yaxis, ax.zaxis), span, mid):
        if extent < 0.35 * span.max():
            axis.set_major_locator(FixedLocator([float(f"{centre:.3g}")]))
        else:
            axis.set_major_locator(MaxNLocator(max(2, int(5 * extent / span.max()))))


def part_colours(pieces) -> tuple[list[str], list[tuple[str, str]]]:
    """A colour per piece — every part its own, parts of one material too (a cabinet's
    oak carcass and oak drawer are two things to tell apart) — and one legend entry
    ``(colour, text)`` per part: its name (numbered when two share one) and its material's
    density. Past :data:`PART_COLOURS` the colours repeat a shade darker."""
    from matplotlib.colors import to_hex, to_rgb

    colours, legend = [], []
    names = [piece.label for piece in pieces]
    for k, piece in enumerate(pieces):
        base = np.array(to_rgb(PART_COLOURS[k % len(PART_COLOURS)]))
        colour = to_hex(base * 0.75 ** (k // len(PART_COLOURS)))
        colours.append(colour)
        name = piece.label
        if names.count(name) > 1:
            name = f"{name} {names[:k + 1].count(name)}"
        units = "kg/m³" if piece.triangles is not None else "kg/m²"
        text = name if piece.density is None else f"{name} ({fmt(piece.density)} {units})"
        legend.append((colour, text))
    return colours, legend


def title_for(body, path: str | None, what: str) -> str:
    """``what — file — body name`` for a figure's title."""
    import os

    parts = [what]
    if path:
        parts.append(os.path.basename(path))
    name = getattr(body, "name", None) if body is not None else None
    if name:
        parts.append(name)
    return " — ".join(parts)


def caption(fig, text: str) -> None:
    """A small note under the figure's panels (what the picture leaves out), with room kept
    for it so no axis label runs into it."""
    lines = text.count("\n") + 1
    height = fig.get_figheight()
    engine = fig.get_layout_engine()
    if engine is not None and hasattr(engine, "set"):
        engine.set(rect=(0, 0.2 * lines / height, 1, 1 - 0.2 * lines / height))
    fig.text(0.01, 0.005, text, fontsize="x-small", va="bottom")
