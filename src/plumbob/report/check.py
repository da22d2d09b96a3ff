"""The text report of ``plumbob check``: the verdict's table, its weakest tipping edges,
the slope and friction lines, the design checks, the loads, a standard's bundle and
the notes.

Formatting only: every number comes from the :class:`~plumbob.stability.verdict.Verdict`
(and a parameter solve's :class:`~plumbob.balance.solve.Solution`); nothing here
computes a stability answer.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import printable
from . import ReportUnits, clean, format_number, format_vector, loads_report, standard_report, table

__all__ = ["check_text", "solution_text"]


class _Shown:
    """Numbers as the report shows them: round-off far below the body's size as 0,
    lengths and points in the report's unit."""

    def __init__(self, size: float, units: ReportUnits):
        self.size, self.u = size, units

    def num(self, value: float, digits: int = 6) -> str:
        return format_number(float(clean(value, self.size)), digits)

    def vec(self, values, digits: int = 6) -> str:
        return format_vector(clean(values, self.size), digits)

    def at(self, value, digits: int = 6) -> str:
        """A length or a point, with the report's length unit."""
        u = self.u
        if np.ndim(value):
            return f"{format_vector(u.length(clean(value, self.size)), digits)} {u.length_unit}"
        return f"{format_number(u.length(float(clean(value, self.size))), digits)} {u.length_unit}"

    def pt(self, value, digits: int = 4) -> str:
        """A point without its unit, in the report's unit."""
        return format_vector(self.u.length(clean(value, self.size)), digits)


def _support_words(v, f: _Shown, groups) -> str:
    s = v.support
    if s.kind == "point":
        return f"a point, {f.at(s.polygon[0])}"
    if s.kind == "segment":
        return f"a segment from {f.pt(s.polygon[0], 6)} to {f.at(s.polygon[1])}"
    arcs = [g for g in groups if g.kind == "arc"]
    where = f"a polygon of {len(s.vertices)} corners"
    if arcs:
        on = sum(g.count for g in arcs)
        where += (f" ({on} short edges on {len(arcs)} arc{'s' if len(arcs) > 1 else ''}, "
                  "of a round base)")
    return where


def _settling_rows(settled, f: _Shown) -> list[tuple[str, str]]:
    """Where a body set down on a point, a line or a sliver comes to rest."""
    contact = {"point": "a point", "line": "a line", "sliver": "a sliver of a face"}
    rest_on = {"face": "on its face", "rocking": "at the bottom of its curved bowl",
               "rolling": "on the surface it rolls along"}[settled.pose_kind]
    if not settled.own_face:
        rest_on = "on another face of its family"
    rows = [("set down", f"down {f.vec(settled.down_from)}, touching on "
                         f"{contact[settled.contact]}"),
            ("comes to rest", f"down {f.vec(settled.down)} after turning "
                              f"{f.num(settled.angle_deg, 4)}°: pose {settled.pose} "
                              f"({rest_on}), centre {f.at(settled.drop)} lower")]
    if not settled.stays:
        rows.append(("", "the numbers below are where it was set down"))
    return rows


def _rows(v, f: _Shown, groups) -> list[tuple[str, str]]:
    """The verdict's table: verdict, mass, centre, support, margin, critical tilt, energy."""
    u = f.u
    verdict = {"stands": "stands", "topples": "TOPPLES",
               "neutral": "neutral (centre of mass over the edge of its support)"}[v.verdict]
    settled = v.settling
    if settled is not None:  # set down on a point, a line or a sliver: where it comes to rest
        verdict = f"{verdict.split(' (')[0]} ({settled.phrase})"
    if v.verdict == "topples":
        margin = (f"{f.at(v.margin)}: the centre of mass is {f.at(v.overhang)} beyond "
                  "the support")
        critical = (f"none: it is over by {f.num(v.over_by_deg, 4)}°, falling toward "
                    f"{f.vec(v.critical_direction, 4)}")
    else:
        margin = f.at(v.margin)
        critical = f"{f.num(v.critical_tilt_deg, 4)}° toward {f.vec(v.critical_direction, 4)}"
    rows = [
        ("verdict", verdict),
        ("mass", f"{format_number(u.mass(v.mass))} {u.mass_unit}"),
        ("centre of mass", f.at(v.center_of_mass)),
        ("down", f.vec(v.down)),
    ]
    if settled is not None:
        rows += _settling_rows(settled, f)
    return rows + [
        ("height of centre", f.at(v.com_height)),
        ("support", _support_words(v, f, groups)),
        ("stability margin", margin),
        ("critical tilt", critical),
        ("energy to topple", f"{f.num(v.energy_to_topple)} J"),
    ]


def _edge_lines(v, f: _Shown, groups, edges: int | None) -> list[str]:
    """The ``edges`` weakest tipping edges (arcs of a round base as one), or all of them."""
    shown = groups if edges is None else groups[:edges]
    title = "tipping over" if len(shown) == len(groups) else "weakest tipping edges"
    labels = []
    for g in shown:
        if g.kind == "arc" and g.count == len(v.edges):
            labels.append(f"the whole round rim ({g.count} edges)")
        elif g.kind == "arc":
            labels.append(f"arc of {g.count} edges {f.pt(g.start)}-{f.pt(g.end)}")
        elif np.allclose(g.start, g.end):
            labels.append(f.pt(g.start))
        else:
            labels.append(f"{f.pt(g.start)}-{f.pt(g.end)}")
    width = max(33, *(len(label) for label in labels)) + 1
    lines = ["", f"{title:<{width}}{f'distance {f.u.length_unit}':>13}{'angle °':>10}"
                 f"{'energy J':>14}"]
    for label, g in zip(labels, shown):
        distance = format_number(f.u.length(float(clean(g.distance, f.size))), 5)
        lines.append(f"{label:<{width}} {distance:>12} "
                     f"{f.num(g.tipping_angle_deg, 4):>9} {f.num(g.energy, 5):>13}")
    if len(shown) < len(groups):
        rest = groups[len(shown):]
        edges = sum(g.count for g in rest)
        lines.append(f"… and {len(rest)} more ({edges} edge{'s' if edges > 1 else ''}, "
                     "--all-edges lists them)")
    return lines


def _slope_lines(v, f: _Shown) -> list[str]:
    """On a tilted plane (``--tilt``), and with friction, which comes first."""
    if v.slope is not None:
        sl = v.slope
        lines = ["", f"on a plane tilted {f.num(sl.tilt_deg, 4)}° toward "
                     f"{f.num(sl.toward_deg, 4)}° {f.vec(sl.direction, 4)}: {sl.verdict} (it goes "
                     f"over at {f.num(sl.tipping_angle_deg, 4)}° that way)"]
        if sl.friction is not None:
            first = "slides before it topples" if sl.slides_first else "topples before it slides"
            slides = "slides" if sl.slides else "does not slide"
            lines.append(f"with friction {f.num(sl.friction)}: {slides} at this tilt; tilted "
                         f"further that way it {first}")
        return lines
    if v.friction is None:
        return []
    if v.slides_first:
        return ["", f"with friction {f.num(v.friction)}: it slides before it topples, "
                    "whichever way the plane is tilted"]
    return ["", f"with friction {f.num(v.friction)}: tilted toward the critical direction it "
                "topples before it slides"]


def _tilt_check_lines(v, f: _Shown) -> list[str]:
    """``--require-tilt``: no overturning at the required tilt in any direction."""
    if v.required_tilt_deg is None:
        return []
    required = f.num(v.required_tilt_deg, 4)
    if v.passes:
        status = f"PASS (critical tilt {f.num(v.critical_tilt_deg, 4)}°)"
    elif v.verdict == "topples":
        status = (f"FAIL (it topples, over by {f.num(v.over_by_deg, 4)}°: "
                  f"{f.num(v.shortfall_deg, 4)}° short of {required}°)")
    elif v.verdict == "neutral":
        status = "FAIL (it is balanced on the edge of its support: critical tilt 0°)"
    else:
        status = (f"FAIL (critical tilt {f.num(v.critical_tilt_deg, 4)}°, "
                  f"{f.num(v.shortfall_deg, 4)}° short of {required}°)")
    return ["", f"design check, no overturning at {required}° in any direction: {status}"]


def _margin_check_lines(v) -> list[str]:
    """``--margin``: the static stability margin at least the required one."""
    if v.required_margin is None:
        return []
    status = "PASS" if v.margin_passes else (
        f"FAIL ({max(v.required_margin - v.margin, 0.0):.6g} m short)")
    return [f"design check, stability margin at least {v.required_margin:g} m: {status}"]


def solution_text(sol) -> str:
    """The line of ``--solve-for``: the smallest change of a parameter that meets the
    requirement, or that it is met already."""
    num = format_number
    if sol.measure == "critical_tilt_deg":
        what = f"critical tilt {num(sol.achieved, 6)}° (≥ {num(sol.required, 4)}°)"
    elif sol.measure == "overturning_safety_factor":
        what = (f"factor of safety against overturning {num(sol.achieved, 6)} under the loads "
                f"(≥ {num(sol.required, 4)})")
    else:
        what = f"stability margin {num(sol.achieved)} m (≥ {num(sol.required)} m)"
    if sol.change == 0:
        return f"{sol.name} = {num(sol.start)} meets it already: {what}"
    return (f"smallest change of {sol.name} that meets it: {num(sol.start)} → "
            f"{num(sol.value)} ({sol.change:+.6g}): {what}, by the check of the rebuilt body")


def check_text(v, path: str, kind: str, notes: Sequence[str], units: ReportUnits, *,
               edges: int | None = None, solution=None, standard=None) -> str:
    """The text report of the verdict ``v`` on the body read from ``path`` (a ``kind``):
    lengths in ``units``; the ``edges`` weakest tipping edges (None: all); the loads'
    table, ``notes`` after the checks, then the margin check, a parameter
    ``solution``'s line and a ``standard``'s bundle when there are ones."""
    f = _Shown(v.support.size, units)  # round-off is relative to the body's size
    groups = v.edge_groups()
    lines = [table(_rows(v, f, groups), title=f"plumbob check {path} ({kind})")]
    if groups:
        lines += _edge_lines(v, f, groups, edges)
    lines += _slope_lines(v, f)
    lines += _tilt_check_lines(v, f)
    if v.loaded is not None:
        lines += ["", loads_report(v.loaded, units, f.size)]
    lines += [f"note: {printable(note)}" for note in notes]
    lines += _margin_check_lines(v)
    if solution is not None:
        lines.append(solution_text(solution))
    if standard is not None:
        lines += ["", standard_report(standard, units, f.size)]
    return "\n".join(lines)
