"""The report of ``plumbob mass``: a body's mass properties and, for an assembly, each
part's, as a JSON object (:meth:`MassReport.as_dict`) or a text table."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..arguments import vector
from ..bodies.measures import MASS_KEYS, size_keys
from ..errors import printable
from ..massprops import MassProperties
from ..reading import Reading
from ..report import ReportUnits, format_number, format_vector, table
from ..results import Result
from ..tolerances import TEXT_ROUND_OFF
from ._common import header

__all__ = ["MassReport"]

#: the keys of each entry of ``part_properties`` besides its name
_PART_KEYS = ("kind", "mass", "area", "volume", "center_of_mass", "exact")


@dataclass(frozen=True, repr=False)
class MassReport(Result):
    """What ``plumbob mass`` reports on a body read from a file.

    reading: the body, its file and the reader's notices. props: the body's mass
    properties. parts: (name, kind, mass properties) of each part of an assembly
    (empty for other bodies). sizes: radii of gyration, bounding box and surface area
    (:func:`~plumbob.bodies.measures.size_keys`). about: a point, m, to give the
    inertia tensor about as well (``--about``), or None.
    """

    reading: Reading
    props: MassProperties
    parts: tuple[tuple[str, str, MassProperties], ...] = ()
    sizes: dict = field(default_factory=dict)
    about: np.ndarray | None = None

    #: the keys of ``plumbob mass --json``, in order (docs/cli.md's table is made from
    #: them; declared beside the mass properties, whose keys they are, for the batch table)
    KEYS = MASS_KEYS

    @classmethod
    def of(cls, reading: Reading, about=None, sizes: bool = False) -> MassReport:
        """The report on the body of ``reading`` (``about``: a point for the inertia;
        ``sizes``: the bounding box and surface area too)."""
        body = reading.body
        parts = tuple((p.name or f"part {i + 1}", p.kind, p.mass_properties())
                      for i, p in enumerate(body.assembly_parts()))
        props = body.mass_properties()
        if about is not None:
            about = vector(about, "about", (props.dim, 3))
        return cls(reading, props, parts, size_keys(body, props, sizes), about)

    @property
    def kind(self) -> str:
        """``lamina``, ``solid``, ``particles`` or ``assembly``."""
        return self.reading.body.kind

    def _repr_items(self) -> list[tuple[str, Any]]:
        return [("path", self.reading.path), ("kind", self.kind), ("props", self.props),
                ("parts", len(self.parts))]

    def as_dict(self) -> dict[str, Any]:
        """The JSON object of ``plumbob mass``: ``path`` and ``name`` when known, the
        mass properties (:meth:`MassProperties.as_dict`), ``part_properties`` for an
        assembly (each ``name``, ``kind``, ``mass``, ``area``/``volume``,
        ``center_of_mass``, ``exact``) and the reader's ``notices``."""
        out = {**header(self.reading, self.kind), **self.props.as_dict(self.kind)}
        if self.parts:
            materials = dict(self.reading.materials)
            out["part_properties"] = [
                {"name": name, **({"material": materials[name]} if name in materials else {}),
                 **{k: v for k, v in props.as_dict(kind).items() if k in _PART_KEYS}}
                for name, kind, props in self.parts
            ]
        out["radii_of_gyration"] = self.sizes["radii_of_gyration"]
        if self.about is not None:
            out["inertia_about"] = {"point": self.about,
                                    "inertia": self.props.inertia_about(self.about)}
        out.update((k, v) for k, v in self.sizes.items() if k != "radii_of_gyration")
        if self.reading.notices:
            out["notices"] = list(self.reading.notices)
        return out

    def text(self, units: ReportUnits | None = None) -> str:
        """A readable table, then a line per part and the notes; lengths and masses in
        ``units`` (default SI)."""
        u = units or ReportUnits()
        props = self.props
        dim = 2 if props.dim == 2 and props.measure else 3
        size_label = "area" if dim == 2 else "volume"
        rows = [("kind", self.kind), ("mass", f"{format_number(u.mass(props.mass))} {u.mass_unit}")]
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
        sizes = self.sizes
        rows.append(("radii of gyration", f"{format_vector(u.length(sizes['radii_of_gyration']))}"
                                          f" {u.length_unit}"))
        if self.about is not None:
            about = self.props.inertia_about(self.about)
            about = np.where(np.abs(about) < 1e-12 * np.abs(about).max(initial=0.0), 0.0, about)
            point = f"inertia (about {format_vector(u.length(self.about))} {u.length_unit})"
            for label, row in zip((point, "", ""), u.inertia(about)):
                rows.append((label, "[" + ", ".join(f"{format_number(v):>12}" for v in row)
                             + f"]  {u.unit('inertia')}"))
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
        title = getattr(self.reading.body, "name", None) or self.reading.path or "body"
        text = table(rows, title)
        if self.parts:
            names = [printable(n) for n, _, _ in self.parts]
            width = max(len(n) for n in names)
            given = dict(self.reading.materials)
            materials = [printable(given.get(n, "")) for n, _, _ in self.parts]
            mwidth = max(len(m) for m in materials)
            column = f"{'material':<{mwidth}}  " if mwidth else ""
            lines = ["", f"{'part':<{width}}  {column}{f'mass ({u.mass_unit})':>12}  "
                         f"centre of mass ({u.length_unit})"]
            lines += [
                f"{name:<{width}}  {f'{m:<{mwidth}}  ' if mwidth else ''}"
                f"{format_number(u.mass(p.mass)):>12}  {format_vector(u.length(p.center_of_mass))}"
                for name, m, (_, _, p) in zip(names, materials, self.parts)
            ]
            text += "\n" + "\n".join(lines)
        for note in props.notes:
            text += f"\nnote: {printable(note)}"
        return text
