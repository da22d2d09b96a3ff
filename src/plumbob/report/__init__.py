"""Text reports for the CLI: numbers, vectors and two-column tables.

Formatting only: the numbers come from the results, the JSON from their
``as_dict()`` (written by :func:`plumbob.commands._common.dump_json`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ArgumentError, printable
from ..tolerances import TEXT_ROUND_OFF
from ..units import LENGTH_UNITS

__all__ = ["MASS_UNITS", "ReportUnits", "format_number", "format_vector", "table", "clean",
           "loads_report", "standard_report", "sheet_markdown", "sheet_html"]

#: kilograms per unit, for the mass units a text report may be asked for
MASS_UNITS: dict[str, float] = {"kg": 1.0, "g": 1e-3, "t": 1000.0, "lb": 0.45359237}


def format_number(value: float | None, digits: int = 6) -> str:
    """A number with ``digits`` significant figures; "—" for none.

    >>> format_number(2 / 3), format_number(0.0), format_number(None), format_number(float("inf"))
    ('0.666667', '0', '—', 'inf')
    """
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—" if value is None else str(value)
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def clean(values, scale: float):
    """Round-off far below ``scale`` (a body's size) shown as 0 in text reports (the JSON
    keeps every digit).

    >>> clean([1.0, 1e-17], 1.0).tolist()
    [1.0, 0.0]
    """
    values = np.asarray(values, dtype=float)
    return np.where(np.abs(values) < TEXT_ROUND_OFF * scale, 0.0, values)


def format_vector(vector: Iterable[float], digits: int = 6, scale: float | None = None) -> str:
    """Numbers in parentheses; with ``scale``, round-off below ``TEXT_ROUND_OFF`` of it shown as 0.

    >>> format_vector([1.0, 1e-17, 2.5], scale=1.0)
    '(1, 0, 2.5)'
    """
    values = [float(v) for v in vector]
    if scale is not None:
        values = [0.0 if abs(v) < TEXT_ROUND_OFF * scale else v for v in values]
    return "(" + ", ".join(format_number(v, digits) for v in values) + ")"


def table(rows: Sequence[tuple[str, str]], title: str | None = None) -> str:
    """Two aligned columns: label and value, under an underlined title. Names from
    files (a title, a part's name) may hold control characters: every cell is shown
    through :func:`~plumbob.errors.printable`, so none reaches the terminal raw.

    >>> print(table([("mass", "2 kg"), ("volume", "1 m³")], "block"))
    block
    -----
    mass    2 kg
    volume  1 m³
    """
    rows = [(printable(label), printable(value)) for label, value in rows]
    width = max((len(label) for label, _ in rows), default=0)
    title = printable(title) if title else title
    lines = [title, "-" * len(title)] if title else []
    lines += [f"{label:<{width}}  {value}" for label, value in rows]
    return "\n".join(lines)


_POWERS = {2: "²", 3: "³"}

#: the mass unit people pair with a length unit: a part drawn in mm is weighed in g
_NATURAL_MASS = {"mm": "g", "cm": "g", "in": "lb", "ft": "lb"}


def units_for(units, length_unit: str | None = None) -> ReportUnits:
    """The units a result's ``text()`` is shown in: ``units`` as given (a
    :class:`ReportUnits`, or ``"mm,g"``), else the part's own (:func:`natural_units` of
    the unit it was read in).

    >>> units_for("mm,g"), units_for(None, "in").length_unit, units_for(None).si
    (ReportUnits(length_unit='mm', mass_unit='g'), 'in', True)
    """
    if units is None:
        return natural_units(length_unit)
    return ReportUnits.parse(units) if isinstance(units, str) else units


def natural_units(length_unit: str | None) -> ReportUnits:
    """The report units for a part read in ``length_unit`` (the user's ``--units`` or
    the file's declared unit): millimetres and grams for a part drawn in mm, inches and
    pounds for one in inches, SI otherwise (metres, kilometres, or no unit known).

    >>> natural_units("mm"), natural_units("in")
    (ReportUnits(length_unit='mm', mass_unit='g'), ReportUnits(length_unit='in', mass_unit='lb'))
    >>> natural_units(None).si, natural_units("km").si
    (True, True)
    """
    if length_unit in _NATURAL_MASS:
        return ReportUnits(length_unit, _NATURAL_MASS[length_unit])
    return ReportUnits()


@dataclass(frozen=True)
class ReportUnits:
    """The units a text report shows lengths and masses in (``--report-units mm,g``);
    derived quantities follow (area mm², density g/mm³, inertia g·mm²). Results and
    JSON stay SI: this converts only at the moment of printing. Energies stay in
    joules, accelerations in m/s², angles in degrees.

    >>> units = ReportUnits.parse("mm,g")
    >>> units.length(0.5), units.mass(2.0), units.inertia(1.0), units.unit("inertia")
    (500.0, 2000.0, 1000000000.0, 'g·mm²')
    >>> ReportUnits.parse("g").unit("density")
    'g/m³'
    >>> ReportUnits.parse("mm,furlong")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: unknown report unit 'furlong'; lengths: m, cm, mm, km, in, \
ft; masses: kg, g, t, lb
    """

    length_unit: str = "m"
    mass_unit: str = "kg"

    @classmethod
    def parse(cls, text: str) -> ReportUnits:
        """``"mm,g"``, ``"mm"`` or ``"g"``: a length unit, a mass unit or one of each."""
        length = mass = None
        for word in (w.strip() for w in text.split(",")):
            if word in LENGTH_UNITS and length is None:
                length = word
            elif word in MASS_UNITS and mass is None:
                mass = word
            else:
                raise ArgumentError(f"unknown report unit {word!r}; lengths: "
                                    f"{', '.join(LENGTH_UNITS)}; masses: {', '.join(MASS_UNITS)}")
        return cls(length or "m", mass or "kg")

    @property
    def si(self) -> bool:
        return (self.length_unit, self.mass_unit) == ("m", "kg")

    def _per(self, mass_power: int, length_power: int) -> float:
        return MASS_UNITS[self.mass_unit] ** -mass_power * \
            LENGTH_UNITS[self.length_unit] ** -length_power

    def length(self, metres):
        """Metres (a number or an array) in the report's length unit."""
        return _scaled(metres, self._per(0, 1))

    def mass(self, kilograms):
        return _scaled(kilograms, self._per(1, 0))

    def measure(self, value, dim: int):
        """An area (``dim`` 2, m²) or a volume (3, m³)."""
        return _scaled(value, self._per(0, dim))

    def density(self, value, dim: int):
        """kg/m³ (kg/m² for a lamina, ``dim`` 2)."""
        return _scaled(value, self._per(1, -dim))

    def inertia(self, value):
        """kg·m² (a moment or a tensor)."""
        return _scaled(value, self._per(1, 2))

    def unit(self, quantity: str, dim: int = 3) -> str:
        """The unit's symbol for ``length``, ``mass``, ``measure``, ``density``, ``inertia``."""
        length, mass = self.length_unit, self.mass_unit
        return {"length": length, "mass": mass, "measure": f"{length}{_POWERS[dim]}",
                "density": f"{mass}/{length}{_POWERS[dim]}",
                "inertia": f"{mass}·{length}²"}[quantity]


def _scaled(value, factor: float):
    if factor == 1.0:
        return value
    return float(value) * factor if np.ndim(value) == 0 else np.asarray(value) * factor


def loads_report(loaded, units: ReportUnits | None = None, scale: float = 1.0) -> str:
    """The lines of a verdict under loads (:class:`~plumbob.stability.loaded.LoadVerdict`):
    each load's point, force and moment about the critical edge, the resisting and
    overturning moments, the factor of safety and the verdict. Forces stay in N and
    moments in N·m; points are in the report's length unit; ``scale`` (m, the body's size)
    sets what round-off shows as 0."""
    u = units or ReportUnits()

    def vec(values, digits: int = 5) -> str:
        return format_vector(u.length(np.asarray(values, dtype=float)), digits, scale=scale)

    factor = loaded.overturning_safety_factor
    verdict = {"stands": "stands", "topples": "TOPPLES", "slides": "SLIDES (before it tips)",
               "lifts": "LIFTS (the loads pull it off the floor)",
               "neutral": "neutral (balanced on the critical edge)"}[loaded.verdict]
    shown = "none: nothing overturns it" if factor is None else format_number(factor, 6)
    rows = [("verdict", verdict),
            ("critical edge", f"{vec(loaded.edge_start)}-{vec(loaded.edge_end)} "
                              f"{u.length_unit}, tipping toward "
                              f"{format_vector(loaded.edge_normal, 4, scale=1.0)}"),
            ("resisting moment", f"{format_number(loaded.resisting_moment)} N·m"),
            ("overturning moment", f"{format_number(loaded.overturning_moment)} N·m"),
            ("factor of safety", f"{shown} (resisting / overturning; below 1 it topples)")]
    if loaded.load_factor is not None:
        rows.append(("load factor", f"{format_number(loaded.load_factor, 6)} (the loads may "
                                    "grow this many times before it tips)"))
    if loaded.tilt_deg is not None:
        rows.append(("floor", f"tilted {format_number(loaded.tilt_deg, 4)}° toward "
                              f"{format_vector(loaded.tilt_direction, 4, scale=1.0)}"))
    if loaded.friction is not None:
        rows.append(("friction", f"μ {format_number(loaded.friction)}: "
                                 f"{'slides' if loaded.slides else 'holds'} "
                                 f"({format_number(loaded.tangential_force)} N along the floor, "
                                 f"{format_number(loaded.normal_force)} N onto it); "
                                 f"{'slides' if loaded.slides_first else 'tips'} first as the "
                                 "loads grow"))
    lines = [table(rows, title="under the applied loads"), ""]
    names = [printable(m.name) + (" (outside)" if m.outside else "") for m in loaded.moments]
    width = max(12, *(len(n) for n in names)) + 1
    lines.append(f"{'load':<{width}}{'at (' + u.length_unit + ')':<30}{'force N':<30}"
                 f"{'moment N·m':>12}")
    for name, m in zip(names, loaded.moments):
        role = "overturns" if m.moment > 0 else "resists" if m.moment < 0 else ""
        lines.append(f"{name:<{width}}{vec(m.at):<30}"
                     f"{format_vector(m.force, 5, scale=float(np.abs(m.force).max() or 1)):<30}"
                     f"{format_number(m.moment, 6):>12} {role}")
    lines += [f"note: {printable(n)}" for n in loaded.notes]
    return "\n".join(lines)


def standard_report(result, units: ReportUnits | None = None, scale: float = 1.0) -> str:
    """The lines of a standard's bundle (:class:`~plumbob.stability.standards.StandardResult`):
    each test's clause, verdict, margin, point and direction, and whether the bundle
    (its groups of alternatives) passes; with the edition cited and the disclaimer."""
    u = units or ReportUnits()
    lines = [f"{printable(result.title)}, {result.edition}, clause {result.clause}"]
    lines.append("-" * len(lines[0]))
    for t in result.tests:
        case = f" [{printable(t.case)}]" if t.case else ""
        status = "PASS" if t.passes else "FAIL"
        if t.margin_unit == "deg":
            margin = f"critical tilt {format_number(t.margin, 4)}° beyond the test's"
        elif t.overturning_safety_factor is None:
            margin = "nothing overturns it"
        else:
            margin = f"factor of safety {format_number(t.overturning_safety_factor, 4)}"
        where = "" if t.point is None else (
            f", at {format_vector(u.length(np.asarray(t.point)), 4, scale=scale)} "
            f"{u.length_unit}")
        lines.append(f"{status}  {t.name}{case} ({printable(t.clause)}): {t.description}: "
                     f"{t.verdict}, {margin}{where}, toward "
                     f"{format_vector(t.direction, 3, scale=1.0)}")
    groups = " and ".join("(" + " or ".join(g) + ")" for g in result.groups)
    lines.append(f"bundle: {'PASSES' if result.passes else 'FAILS'} (needs {groups})")
    lines.append(f"note: {result.disclaimer}")
    lines += [f"note: {printable(n)}" for n in result.notes]
    return "\n".join(lines)


def _v(values, digits: int = 6) -> str:
    """A vector, its round-off far below its largest entry shown as 0."""
    values = np.asarray(values, dtype=float)
    return format_vector(values, digits, scale=float(np.abs(values).max(initial=0.0)) or 1.0)


def sheet_markdown(sheet) -> str:
    """A calculation sheet (:class:`~plumbob.stability.sheet.Sheet`) as Markdown: the steps
    of the seed's worked solutions, SI units, every number plumbob's."""
    v = sheet.verdict
    n = lambda x, d=6: format_number(float(x), d)  # noqa: E731
    corners = ", ".join(_v(c) for c in v.support.polygon)
    lines = [f"# Calculation sheet: {printable(sheet.title)}", "",
             "Will it stand? Worked as the seed's solutions work it (Unit 19: the centre of "
             "mass by equation (15), the toppling condition of section 2.2). SI units.", "",
             "## 1. The parts and their centres of mass", "",
             "| part | mass m_i (kg) | centre r_i (m) | first moment m_i r_i (kg·m) |",
             "|---|---:|---|---|"]
    for p in sheet.parts:
        sign = "" if p.sign > 0 else " (hole, taken away)"
        lines.append(f"| {printable(p.name)}{sign} | {n(p.sign * p.mass)} | {_v(p.center)} | "
                     f"{_v(p.first_moment)} |")
    lines.append(f"| **total** | **M = {n(sheet.mass)}** | | **Σ m_i r_i = "
                 f"{_v(sheet.first_moment)}** |")
    lines += ["", "Equation (15): r_G = Σ m_i r_i / M = "
              f"{_v(sheet.first_moment)} / {n(sheet.mass)} = **{_v(sheet.center_of_mass)} m**.",
              "", "## 2. The support", "",
              f"Gravity acts along {_v(v.down, 4)}. The centre of mass is h_G = "
              f"{n(v.com_height)} m above the floor. The body rests on "
              f"a {v.support.kind} with corners {corners} (m).",
              "", "| support edge | outward normal | distance d of G inside it (m) | "
              "tipping angle atan(d/h_G) (°) |", "|---|---|---:|---:|"]
    for e in v.edges:
        lines.append(f"| {_v(e.start)}–{_v(e.end)} | {_v(e.normal, 4)} | {n(e.distance)} | "
                     f"{n(e.tipping_angle_deg, 5)} |")
    lines += ["", "## 3. The critical edge and the moments about it", "",
              f"The critical edge runs {_v(sheet.edge_start)}–{_v(sheet.edge_end)} m; the body "
              f"would tip toward {_v(sheet.edge_normal, 4)}. A force F at a point p has the "
              "moment M = (u·r)(n·F) − (u·F)(n·r) about it (r = p − a, a a point of the edge, "
              "n its outward normal, u up): positive overturns, negative resists.", "",
              "| force | at (m) | force (N) | moment (N·m) |", "|---|---|---|---:|"]
    for p in sheet.parts:
        lines.append(f"| weight of {printable(p.name)} | {_v(p.center)} | "
                     f"{_v(p.sign * p.mass * v.g * v.down)} | {n(p.moment)} |")
    for m in sheet.loads:
        outside = " (outside the body)" if m.outside else ""
        lines.append(f"| {printable(m.name)} ({m.kind}){outside} | {_v(m.at)} | {_v(m.force)} | "
                     f"{n(m.moment)} |")
    factor = sheet.overturning_safety_factor
    lines += ["", f"Resisting moment R = {n(sheet.resisting_moment)} N·m; overturning moment "
              f"O = {n(sheet.overturning_moment)} N·m (the weight taken as one force at r_G).",
              "", "Factor of safety against overturning R / O = " +
              ("none: nothing overturns it." if factor is None else
               f"{n(sheet.resisting_moment)} / {n(sheet.overturning_moment)} = **{n(factor)}**"
               + (" (below 1: it topples)." if factor < 1 else "."))]
    lines += ["", "## 4. Verdict", ""]
    if v.verdict == "stands":
        lines.append(f"The centre of mass lies over the support, {n(v.margin)} m inside its "
                     f"nearest edge: **it stands** (it does not topple). Critical tilt "
                     f"atan({n(v.margin)} / {n(v.com_height)}) = {n(v.critical_tilt_deg, 5)}°.")
    elif v.verdict == "topples":
        lines.append(f"The centre of mass lies {n(-v.margin)} m beyond the support: **it "
                     "topples**.")
    else:
        lines.append("The centre of mass lies over the edge of its support: **neutral** "
                     "(balanced; a round body rolls that way).")
    if v.loaded is not None:
        lines.append(f"Under the applied loads: **{v.loaded.verdict}**.")
    lines += ["", f"Energy to raise its material from the floor: M g h_G = {n(sheet.mass)} × "
              f"{n(v.g)} × {n(v.com_height)} = {n(sheet.lift_energy)} J.", ""]
    return "\n".join(lines)


def sheet_html(sheet) -> str:
    """The calculation sheet as a standalone HTML page (the Markdown's headings, tables and
    paragraphs)."""
    import html

    out = ["<!DOCTYPE html>", "<html><head><meta charset='utf-8'><title>",
           html.escape(printable(sheet.title)), "</title><style>body{font-family:sans-serif;"
           "max-width:60em;margin:2em auto}table{border-collapse:collapse}td,th{border:1px "
           "solid #999;padding:.2em .5em}</style></head><body>"]
    table: list[list[str]] = []

    def flush() -> None:
        if table:
            head, rows = table[0], table[2:]
            out.append("<table><tr>" + "".join(f"<th>{c}</th>" for c in head) + "</tr>")
            out.extend("<tr>" + "".join(f"<td>{c}</td>" for c in r) + "</tr>" for r in rows)
            out.append("</table>")
            table.clear()

    for line in sheet_markdown(sheet).splitlines():
        text = html.escape(line)
        bold = text.split("**")
        text = "".join(f"<b>{t}</b>" if i % 2 else t for i, t in enumerate(bold))
        if line.startswith("|"):
            table.append([c.strip() for c in text.strip("|").split("|")])
            continue
        flush()
        if line.startswith("## "):
            out.append(f"<h2>{text[3:]}</h2>")
        elif line.startswith("# "):
            out.append(f"<h1>{text[2:]}</h1>")
        elif line.strip():
            out.append(f"<p>{text}</p>")
    flush()
    out.append("</body></html>")
    return "\n".join(out) + "\n"
