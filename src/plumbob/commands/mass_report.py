"""The report of ``plumbob mass``: a body's mass properties and, for an assembly, each
part's, as a JSON object (:meth:`MassReport.as_dict`) or a text table."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..arguments import vector
from ..bodies.measures import MASS_KEYS, size_keys
from ..massprops import MassProperties, size_key
from ..reading import Reading
from ..report import ReportUnits
from ..results import Result

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
    inertia tensor about as well (``--about``), or None. frame: ``"principal"`` or the
    rows (3, 3) of a frame to give the inertia tensor in as well (``--frame``), or None.
    """

    reading: Reading
    props: MassProperties
    parts: tuple[tuple[str, str, MassProperties], ...] = ()
    sizes: dict = field(default_factory=dict)
    about: np.ndarray | None = None
    frame: Any = None

    #: the keys of ``plumbob mass --json``, in order (docs/cli.md's table is made from
    #: them; declared beside the mass properties, whose keys they are, for the batch table)
    KEYS = MASS_KEYS

    @classmethod
    def of(cls, reading: Reading, about=None, sizes: bool = False, frame=None) -> MassReport:
        """The report on the body of ``reading`` (``about``: a point for the inertia;
        ``sizes``: the bounding box and surface area too; ``frame``: ``"principal"`` or
        axes as rows, a frame for the inertia)."""
        body = reading.body
        parts = tuple((p.name or f"part {i + 1}", p.kind, p.mass_properties())
                      for i, p in enumerate(body.assembly_parts()))
        props = body.mass_properties()
        if about is not None:
            about = vector(about, "about", (props.dim, 3))
        return cls(reading, props, parts, size_keys(body, props, sizes), about, frame)

    @property
    def kind(self) -> str:
        """``lamina``, ``solid``, ``particles`` or ``assembly``."""
        return self.reading.body.kind

    def _repr_items(self) -> list[tuple[str, Any]]:
        return [("path", self.reading.path), ("kind", self.kind), ("props", self.props),
                ("parts", len(self.parts))]

    # the values of the declared keys that are not the mass properties' own
    @property
    def path(self) -> str | None:
        """The file read, or None."""
        return self.reading.path or None

    @property
    def name(self) -> str | None:
        """The body's name, or None."""
        return getattr(self.reading.body, "name", None) or None

    @property
    def volume(self) -> float | None:
        """m³, for a body that has a volume (not a lamina, not particles)."""
        return self.props.measure if size_key(self.props, self.kind) == "volume" else None

    @property
    def area(self) -> float | None:
        """m², for a lamina."""
        return self.props.measure if size_key(self.props, self.kind) == "area" else None

    @property
    def part_properties(self) -> list[dict[str, Any]]:
        """Each part's ``name`` (and ``material`` when given by name) and its mass
        properties' ``kind``, ``mass``, ``volume``/``area``, ``center_of_mass``, ``exact``."""
        materials = dict(self.reading.materials)
        return [{"name": name, **({"material": materials[name]} if name in materials else {}),
                 **{k: v for k, v in props.as_dict(kind).items() if k in _PART_KEYS}}
                for name, kind, props in self.parts]

    @property
    def inertia_about(self) -> dict[str, Any] | None:
        """``point`` (m) and ``inertia`` (kg·m², about it) with ``--about``, else None."""
        if self.about is None:
            return None
        return {"point": self.about, "inertia": self.props.inertia_about(self.about)}

    @property
    def inertia_in_frame(self) -> dict[str, Any] | None:
        """With ``--frame``: ``axes`` (rows, unit vectors in the body's coordinates),
        ``point`` (m: the centre of mass, or the ``--about`` point) and ``inertia``
        (kg·m², ``R I Rᵀ`` about that point), else None."""
        if self.frame is None:
            return None
        rows = self.props.principal_axes if isinstance(self.frame, str) else self.frame
        point = self.props.center_of_mass if self.about is None else self.about
        return {"axes": rows, "point": point, "inertia": self.props.inertia_in(rows, point)}

    def text(self, units: ReportUnits | None = None) -> str:
        """A readable table, then a line per part and the notes; lengths and masses in
        ``units`` (default SI): :func:`plumbob.report.mass.mass_text`."""
        from ..report.mass import mass_text

        return mass_text(self, units)
