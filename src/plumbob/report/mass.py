"""The text report of ``plumbob mass``: the mass properties as a table, then a line per
part of an assembly and the notes.

Formatting only: every number comes from the :class:`~plumbob.commands.mass_report.MassReport`
(its mass properties and sizes); round-off far below the body's size is shown as 0.
"""

from __future__ import annotations

import numpy as np

from ..errors import printable
from ..tolerances import TEXT_ROUND_OFF
from . import ReportUnits, format_number, format_vector, table

__all__ = ["mass_text", "props_text"]


class _Alone:
    """Mass properties without the command's report around them: what :func:`mass_text`
    reads of a :class:`~plumbob.commands.mass_report.MassReport`, from the properties and
    where they came from (their ``source``)."""

    about = frame = inertia_in_frame = None
    parts = ()

    def __init__(self, props):
        s = props.source
        self.props, self.kind = props, (s.kind if s is not None and s.kind else
                                        "lamina" if "area" in props.as_dict() else
                                        "solid" if props.measure else "particles")
        moments = np.maximum(props.principal_moments, 0.0)
        self.sizes = {"radii_of_gyration": np.sqrt(moments / props.mass)}
        self.title = (s.name or s.path) if s is not None else None


def props_text(props, units=None) -> str:
    """The table of ``plumbob mass`` for mass properties alone (``str(props)``): lengths
    and masses in ``units`` (:class:`ReportUnits` or ``"mm,g"``; default the part's own,
    from ``props.source``, else SI)."""
    from . import units_for

    s = props.source
    return mass_text(_Alone(props), units_for(units, s.length_unit if s is not None else None))


def mass_text(report, units: ReportUnits | None = None) -> str:
    """The report of ``report`` (a :class:`~plumbob.commands.mass_report.MassReport`):
    lengths and masses in ``units`` (default SI)."""
    u = units or ReportUnits()
    props = report.props
    dim = 2 if props.dim == 2 and props.measure else 3
    size_label = "area" if dim == 2 else "volume"
    rows = [("kind", report.kind), ("mass", f"{format_number(u.mass(props.mass))} {u.mass_unit}")]
    if props.measure:
        rows.append((size_label, f"{format_number(u.measure(props.measure, dim))} "
                                 f"{u.unit('measure', dim)}"))
        rows.append(("mean density", f"{format_number(u.density(props.density, props.dim))} "
                                     f"{u.unit('density', props.dim)}"))
    # Round-off far below the body's size is shown as 0 (the JSON keeps every digit).
    scale = float(np.abs(props.center_of_mass).max() + np.sqrt(np.trace(props.inertia) / props.mass))
    centre = np.where(np.abs(props.center_of_mass) < TEXT_ROUND_OFF * scale, 0.0,
                      props.center_of_mass)
    rows.append(("centre of mass", f"{format_vector(u.length(centre))} {u.length_unit}"))
    inertia = np.where(np.abs(props.inertia) < 1e-12 * np.abs(props.inertia).max(), 0.0, props.inertia)
    labels = ("inertia (about centre)", "", "")
    for label, row in zip(labels, u.inertia(inertia)):
        rows.append((label, "[" + ", ".join(f"{format_number(v):>12}" for v in row)
                     + f"]  {u.unit('inertia')}"))
    rows.append(("principal moments", f"{format_vector(u.inertia(props.principal_moments))} "
                                      f"{u.unit('inertia')}"))
    for i, axis in enumerate(props.principal_axes):
        rows.append((f"principal axis {i + 1}", format_vector(np.round(axis, 12))))
    sizes = report.sizes
    rows.append(("radii of gyration", f"{format_vector(u.length(sizes['radii_of_gyration']))}"
                                      f" {u.length_unit}"))
    if report.about is not None:
        about = report.props.inertia_about(report.about)
        about = np.where(np.abs(about) < 1e-12 * np.abs(about).max(initial=0.0), 0.0, about)
        point = f"inertia (about {format_vector(u.length(report.about))} {u.length_unit})"
        for label, row in zip((point, "", ""), u.inertia(about)):
            rows.append((label, "[" + ", ".join(f"{format_number(v):>12}" for v in row)
                         + f"]  {u.unit('inertia')}"))
    framed = getattr(report, "inertia_in_frame", None)
    if framed is not None:
        tensor = framed["inertia"]
        tensor = np.where(np.abs(tensor) < 1e-12 * np.abs(tensor).max(initial=0.0), 0.0, tensor)
        where = ("centre" if report.about is None else
                 f"{format_vector(u.length(report.about))} {u.length_unit}")
        frame = "principal axes" if isinstance(report.frame, str) else "the frame below"
        head = f"inertia (about {where}, in {frame})"
        for label, row in zip((head, "", ""), u.inertia(tensor)):
            rows.append((label, "[" + ", ".join(f"{format_number(v):>12}" for v in row)
                         + f"]  {u.unit('inertia')}"))
        for name, axis in zip("xyz", framed["axes"]):
            rows.append((f"frame axis {name}", format_vector(np.round(axis, 12) + 0.0)))
    if "surface_area" in sizes:
        bound = "" if sizes["surface_area_exact"] else (
            f" (curved faces faceted: within {sizes['surface_area_relative_error']:.1e} "
            "relative)")
        rows.append(("surface area", f"{format_number(u.measure(sizes['surface_area'], 2))} "
                                     f"{u.unit('measure', 2)}{bound}"))
    if "bounding_box_lower" in sizes:
        lower, upper = sizes["bounding_box_lower"], sizes["bounding_box_upper"]
        rows.append(("bounding box", " × ".join(format_number(v)
                                                for v in u.length(upper - lower))
                     + f" {u.length_unit}, from {format_vector(u.length(lower))}"))
    rows.append(("exact", props.exactness))
    rows.append(("parts", str(props.parts)))
    title = (report.title if isinstance(report, _Alone) else
             getattr(report.reading.body, "name", None) or report.reading.path) or "body"
    text = table(rows, title)
    if report.parts:
        names = [printable(n) for n, _, _ in report.parts]
        width = max(len(n) for n in names)
        given = dict(report.reading.materials)
        materials = [printable(given.get(n, "")) for n, _, _ in report.parts]
        mwidth = max(len(m) for m in materials)
        column = f"{'material':<{mwidth}}  " if mwidth else ""
        lines = ["", f"{'part':<{width}}  {column}{f'mass ({u.mass_unit})':>12}  "
                     f"centre of mass ({u.length_unit})"]
        lines += [
            f"{name:<{width}}  {f'{m:<{mwidth}}  ' if mwidth else ''}"
            f"{format_number(u.mass(p.mass)):>12}  {format_vector(u.length(p.center_of_mass))}"
            for name, m, (_, _, p) in zip(names, materials, report.parts)
        ]
        text += "\n" + "\n".join(lines)
    for note in props.notes:
        text += f"\nnote: {printable(note)}"
    return text
