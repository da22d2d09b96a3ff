"""What reading a file or spec gives: the body, and what the user should be told.

Readers (:mod:`plumbob.formats`, :mod:`plumbob.spec`) return a :class:`Reading`;
commands print its notices and measure its body. It sits above the bodies and
below every reader, so readers and commands share it without importing each other.
"""

from __future__ import annotations

from dataclasses import dataclass

from .bodies.base import DEFAULT_DENSITY_NOTE, Body
from .results import Source

__all__ = ["Reading"]


@dataclass(frozen=True)
class Reading:
    """A body read from a file, with notices for the user (assumptions, repairs).

    body: what the file describes. notices: assumed units, repaired defects,
    implausible sizes, one line each. path: the file, when there is one.
    length_unit: the unit the file's coordinates were read in (``"mm"``, ``"in"``:
    given by the user or declared by the file); None when metres were assumed or the
    file's own scale has no unit name. The body is in metres either way; text reports
    show the part in this unit (:func:`plumbob.report.natural_units`).
    loads: the applied loads a spec's ``[[load]]`` tables give
    (:class:`~plumbob.loads.Force`, :class:`~plumbob.loads.Hang`, …), in metres;
    extendables: the parts its ``[[extendable]]`` tables mark as opening
    (:class:`~plumbob.loads.Extendable`).
    up: the up axis the file's format specifies (glTF: +y), a unit vector in the body's
    frame; None when the format has none (then +z is assumed for solids, +y for laminas).
    materials: (part name, material) for the parts given a material by name
    (``--part-material``, a spec's ``materials``, a 3MF's base materials), for the
    reports' part tables.
    units_assumed: True when neither the caller nor the file gave a length unit and the
    reader assumed metres (its notices say so); a spec applies its own unit to such a
    file (:func:`plumbob.units.unit_assumed`).
    densities_required: the file gives its parts different materials (a multi-material
    3MF), so every part needs a density: one assumed for all would be wrong
    (:func:`plumbob.formats.parts.require_part_densities`).
    file_materials: (part name, material, density kg/m³) for the parts the file gives a
    material by a name plumbob knows (a 3MF's base materials, a slicer's filaments): applied
    by :func:`plumbob.formats.parts.with_file_materials` after ``--part-material``, which
    may name another.
    """

    body: Body
    notices: tuple[str, ...] = ()
    path: str | None = None
    length_unit: str | None = None
    loads: tuple = ()
    extendables: tuple = ()
    up: tuple[float, ...] | None = None
    materials: tuple[tuple[str, str], ...] = ()
    units_assumed: bool = False
    densities_required: bool = False
    file_materials: tuple[tuple[str, str, float], ...] = ()

    def source(self, props, size: float = 0.0) -> Source:
        """Where a result on this body came from, for its ``str()`` (the command line's
        report): the file, its unit, the body's kind and name, the notes of its mass
        properties ``props`` (assumed densities, faceted curves) and, when known, its
        ``size`` (m)."""
        body = self.body
        return Source(self.path, self.length_unit, body.kind, tuple(props.notes), size,
                      getattr(body, "name", None) or None)

    def default_down(self) -> list[float] | None:
        """Gravity's direction when the user gives none: against the file's up axis, or
        None (the stability code's own default: −z, −y for a lamina)."""
        return None if self.up is None else [-float(u) + 0.0 for u in self.up]

    def assumed(self, oriented: bool = False) -> tuple[str, ...]:
        """What was assumed where neither the file nor the options said, one line each,
        for the user to see (the command line prints them on stderr): the density of 1
        when a part gives none, and with ``oriented`` (a question that needs a down
        direction, none given) the up axis. An assumed unit is already a notice.

        >>> from plumbob.bodies.primitives import box
        >>> Reading(box(1, 1, 1)).assumed(oriented=True)  # doctest: +NORMALIZE_WHITESPACE
        ('no density given: 1 kg/m³ (1 kg/m² for a lamina) assumed',
         'up: +z assumed (the file gives no up axis): it rests toward -z; --down chooses')
        >>> Reading(box(1, 1, 1, density=2.0), up=(0.0, 1.0, 0.0)).assumed(oriented=True)
        ()
        """
        lines = []
        if None in self.body.densities():
            lines.append(DEFAULT_DENSITY_NOTE)
        if oriented and self.up is None:
            axis = "y" if self.body.dim == 2 else "z"
            lines.append(f"up: +{axis} assumed (the file gives no up axis): it rests toward "
                         f"-{axis}; --down chooses")
        return tuple(lines)
