"""The text report of ``plumbob poses``: a line for the body, then a row per shown pose
(probability, down, height, critical tilt, energy barrier, how it rolls or rocks), the
poses left out, the files written and the notes.

Formatting only: every number comes from the :class:`~plumbob.stability.poses.Poses`.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..errors import printable
from . import ReportUnits, clean, format_number, format_vector

__all__ = ["poses_text"]


def poses_text(result, shown: Sequence, path: str, size: float, units: ReportUnits, *,
               left_out: tuple[int, float] = (0, 0.0), written: Sequence[str] = (),
               notes: Sequence[str] = ()) -> str:
    """The report of ``result`` (:class:`~plumbob.stability.poses.Poses`) on the file
    ``path``: the ``shown`` poses, ``left_out`` (how many are not shown, and their total
    probability), the files ``written`` and the ``notes``; lengths and masses in
    ``units``, round-off below the body's ``size`` (m) shown as 0."""

    def vec(values, digits: int = 6) -> str:
        return format_vector(clean(values, size), digits)

    num = format_number
    length = units.length_unit
    centre = units.length(clean(result.center_of_mass, size))
    lines = [f"plumbob poses {path}: {len(result)} stable pose(s), mass "
             f"{num(units.mass(result.mass))} {units.mass_unit}, centre of mass "
             f"{format_vector(centre)} {length}",
             f"{'#':>3}  {'probability':>11}  {'down':<28}{'height ' + length:>11}{'tilt °':>9}"
             f"{'barrier J':>13}"]
    for k, p in enumerate(shown, 1):
        barrier = "—" if p.energy_barrier is None else num(p.energy_barrier, 5)
        tag = ""
        if p.kind == "rolling":
            tag = "  rolls" + ("" if p.axis is None else f" about {vec(p.axis, 4)}")
        elif p.kind == "rocking":
            tag = "  rocks"
        height = num(units.length(p.com_height), 5)
        lines.append(f"{k:>3}  {p.probability:>11.6f}  {vec(p.down, 4):<28}{height:>11}"
                     f"{num(p.critical_tilt_deg, 4):>9}{barrier:>13}{tag}")
    rest, rest_p = left_out
    if rest:
        lines.append(f"     {rest} more pose(s) with total probability {rest_p:.4g} not shown "
                     "(--top, --min-probability)")
    lines += [f"wrote {printable(p)}" for p in written]
    lines += [f"note: {printable(n)}" for n in notes]
    return "\n".join(lines)
