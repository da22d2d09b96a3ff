"""The text report of ``plumbob lift``: the mass, the datum, the height of the centre of
mass above it, the lift energy and, with a crew, the days of work; then the notes.

Formatting only: every number comes from the :class:`~plumbob.energy.LiftEnergy` (and a
:class:`~plumbob.energy.CrewTime`).
"""

from __future__ import annotations

from collections.abc import Sequence

from ..errors import printable
from . import ReportUnits, clean, format_number, table

__all__ = ["lift_text"]


def lift_text(lift, path: str, units: ReportUnits, *, crew=None, notes: Sequence[str] = (),
              size: float = 0.0) -> str:
    """The report of ``lift`` on the file ``path``: lengths and masses in ``units``,
    energies in J, round-off below ``size`` (m, the body's; 0: the heights') as 0."""
    u, num = units, format_number
    size = size or max(abs(lift.datum), abs(lift.com_height), 1e-300)

    def length(value: float) -> str:
        return f"{num(u.length(float(clean(value, size))))} {u.length_unit}"

    rows = [
        ("mass", f"{num(u.mass(lift.mass))} {u.mass_unit}"),
        ("ground datum", length(lift.datum)),
        ("centre of mass above it", length(lift.com_height)),
        ("lift energy", f"{num(lift.lift_energy)} J"),
    ]
    if crew is not None:
        rows += [
            ("work per person per day", f"{num(crew.work_per_day)} J"),
            ("person-days", num(crew.person_days)),
            (f"days for a crew of {crew.crew}", num(crew.crew_days)),
            ("years", num(crew.crew_years, 4)),
        ]
    lines = [table(rows, title=f"plumbob lift {path}")]
    lines += [f"note: {printable(note)}" for note in notes]
    return "\n".join(lines)
