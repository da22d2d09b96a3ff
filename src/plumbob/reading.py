"""What reading a file or spec gives: the body, and what the user should be told.

Readers (:mod:`plumbob.formats`, :mod:`plumbob.spec`) return a :class:`Reading`;
commands print its notices and measure its body. It sits above the bodies and
below every reader, so readers and commands share it without importing each other.
"""

from __future__ import annotations

from dataclasses import dataclass

from .bodies.base import Body

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
    """

    body: Body
    notices: tuple[str, ...] = ()
    path: str | None = None
    length_unit: str | None = None
    loads: tuple = ()
    extendables: tuple = ()
