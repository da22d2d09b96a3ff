"""The report of ``plumbob mass``: JSON object and text table."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..bodies.csg import Assembly
from ..massprops import MassProperties
from ..reading import Reading
from ..report import format_number, format_vector, mass_properties_dict, table

__all__ = ["mass_json", "mass_text"]


def _parts(reading: Reading) -> list[tuple[str, str, MassProperties]]:
    body = reading.body
    if not isinstance(body, Assembly):
        return []
    return [
        (p.name or f"part {i + 1}", p.kind, p.mass_properties()) for i, p in enumerate(body.parts)
    ]


def mass_json(reading: Reading) -> dict[str, Any]:
    """One JSON object: the body's mass properties, and each part of an assembly."""
    props = reading.body.mass_properties()
    out = mass_properties_dict(props, reading.body.kind)
    name = getattr(reading.body, "name", None)
    if name:
        out = {"name": name, **out}
    if reading.path:
        out = {"path": reading.path, **out}
    parts = _parts(reading)
    if parts:
        out["part_properties"] = [
            {
                "name": name,
                **{
                    k: v
                    for k, v in mass_properties_dict(p, kind).items()
                    if k in ("kind", "mass", "area", "volume", "center_of_mass", "exact")
                },
            }
            for name, kind, p in parts
        ]
    if reading.notices:
        out["notices"] = list(reading.notices)
    return out


def mass_text(reading: Reading) -> str:
    """A readable table."""
    body = reading.body
    props = body.mass_properties()
    size_label, size_unit = ("area", "m²") if props.dim == 2 and props.measure else ("volume", "m³")
    rows = [("kind", body.kind), ("mass", f"{format_number(props.mass)} kg")]
    if props.measure:
        rows.append((size_label, f"{format_number(props.measure)} {size_unit}"))
        density_unit = "kg/m²" if props.dim == 2 else "kg/m³"
        rows.append(("mean density", f"{format_number(props.density)} {density_unit}"))
    # Round-off far below the body's size is shown as 0 (the JSON keeps every digit).
    scale = float(np.abs(props.center_of_mass).max() + np.sqrt(np.trace(props.inertia) / props.mass))
    rows.append(("centre of mass", f"{format_vector(props.center_of_mass, scale=scale)} m"))
    inertia = np.where(np.abs(props.inertia) < 1e-12 * np.abs(props.inertia).max(), 0.0, props.inertia)
    labels = ("inertia (about centre)", "", "")
    for label, row in zip(labels, inertia):
        rows.append((label, "[" + ", ".join(f"{format_number(v):>12}" for v in row) + "]  kg·m²"))
    rows.append(("principal moments", f"{format_vector(props.principal_moments)} kg·m²"))
    for i, axis in enumerate(props.principal_axes):
        rows.append((f"principal axis {i + 1}", format_vector(np.round(axis, 12))))
    rows.append(
        ("exact", "yes" if props.exact else f"no (relative error ~{props.relative_error:.1e})")
    )
    rows.append(("parts", str(props.parts)))
    title = getattr(body, "name", None) or reading.path or "body"
    text = table(rows, title)
    parts = _parts(reading)
    if parts:
        width = max(len(n) for n, _, _ in parts)
        lines = ["", f"{'part':<{width}}  {'mass (kg)':>12}  centre of mass (m)"]
        lines += [
            f"{name:<{width}}  {format_number(p.mass):>12}  {format_vector(p.center_of_mass)}"
            for name, _, p in parts
        ]
        text += "\n" + "\n".join(lines)
    for note in props.notes:
        text += f"\nnote: {note}"
    return text
