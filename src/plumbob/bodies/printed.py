"""A part as a 3D printer makes it: solid walls, the inside a sparse infill.

Why: an FDM or SLA part is not solid. Its walls (the shell, ``t`` thick) are at full
density and its interior — the inward offset of the surface by ``t``
(:mod:`plumbob.bodies.offset`) — at the infill fraction ``f``, so its mass and,
for any shape less symmetric than a ball, its centre of mass differ from the
solid's. By the mass-property algebra the printed part is the solid less a share
``1 − f`` of its interior::

    P_printed = P_solid − (1 − f) · P_interior        (interior at the solid's density)

exact whenever the offset is (boxes, convex meshes, spheres, cylinders, cones,
tori, convex prisms), else within the level set's stated error.

A :class:`Printed` body is a :class:`~plumbob.bodies.base.Body`: its outside — hull,
contact, containment, booleans — is the solid's, so ``mass``, ``check`` and
``poses`` take it as they take any body.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import DensityError, GeometryError
from ..massprops import MassProperties, combine
from ..units import parse_length as units_parse_length
from ..units import split_length
from .base import Body, Grader, density_words
from .cells import DensityCells
from .offset import InwardOffset, inward_offset

__all__ = ["Printed", "printed", "parse_length", "parse_fraction"]


@dataclass(frozen=True, eq=False, repr=False)
class Printed(Body):
    """A solid printed with walls ``shell`` m thick and its interior filled to ``infill``.

    outer: the solid as designed.
    offset: its inward offset by ``shell`` (the interior; empty for a part that is all
        wall).
    infill: the interior's fill fraction, 0 (hollow) to 1 (solid).
    """

    outer: Body
    offset: InwardOffset
    infill: float
    name: str | None = None

    kind = "solid"
    dim = 3

    @property
    def shell(self) -> float:
        """The wall thickness, m."""
        return self.offset.distance

    def mass_properties(self) -> MassProperties:
        solid = self.outer.mass_properties()
        rule = (f"printed: walls {self.shell:.4g} m at full density, the interior at "
                f"{self.infill:.4g} of it")
        if self.offset.body is None or self.infill == 1.0:
            notes = (rule + " (the part is all wall)",) if self.offset.body is None else (rule,)
            return replace(solid, notes=solid.notes + notes)
        inner = self.offset.body.mass_properties()  # at the solid's density (the offset keeps it)
        props = combine([solid, inner], [1.0, -(1.0 - self.infill)])
        notes = tuple(n for n in props.notes if n not in inner.notes) + (rule,)
        if not self.offset.exact:
            notes += (self.offset.note,)
        return replace(props, measure=solid.measure, parts=solid.parts, notes=notes)

    # the outside is the solid's
    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        return self.outer.hull_points(tolerance)

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        return self.outer.support_points(down, tolerance)

    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        return self.outer.contains(points, tolerance)

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return self.outer._contains_tolerance(tolerance)

    def to_geometry(self, segments: int = 128):
        return self.outer.to_geometry(segments)

    def surface(self, segments: int = 128):
        return self.outer.surface(segments)

    def outline(self, tolerance: float, segments: int = 384) -> list[np.ndarray]:
        return self.outer.outline(tolerance, segments)

    @property
    def is_polytope(self) -> bool:
        return self.outer.is_polytope

    def densities(self) -> set:
        return self.outer.densities()

    def with_default_density(self, density: float) -> Body:
        inner = self.offset.body
        offset = self.offset if inner is None else replace(
            self.offset, body=inner.with_default_density(density))
        return replace(self, outer=self.outer.with_default_density(density), offset=offset)

    def density_cells(self) -> DensityCells:
        raise DensityError("a printed part's density is its walls' and its infill's: "
                           "give the density field to the solid, not the printed part")

    def graded(self, grader: Grader) -> Body:
        return self.density_cells()

    def _describe(self) -> str:
        density = next(iter(self.outer.densities()), None)
        return (f"printed solid, shell {self.shell:.4g} m, infill {self.infill:.4g}"
                f"{density_words(density if isinstance(density, float) else None)}")


def printed(body: Body, shell: float, infill: float, *, step: float | None = None) -> Printed:
    """``body`` as printed: walls ``shell`` m thick at full density, the rest at ``infill``.

    Parameters
    ----------
    body : Body
        A solid of one density (a mesh, a primitive, a boolean).
    shell : float
        m, positive: the wall thickness (perimeters and top/bottom layers).
    infill : float
        The interior's fill fraction, 0 (hollow) to 1 (solid).
    step : float, optional
        The level-set step, m, for shapes whose offset has no closed form
        (see :func:`plumbob.bodies.offset.inward_offset`).

    Returns
    -------
    Printed

    Raises
    ------
    GeometryError
        A shell that is not positive, an infill outside [0, 1], or a body that is not
        a solid of one density.

    Examples
    --------
    A 20 mm cube of PLA (1240 kg/m³) printed with 1 mm walls and 20 % infill weighs
    ``ρ (a³ − 0.8 (a − 2t)³)``:

    >>> from plumbob.bodies.primitives import box
    >>> cube = printed(box(0.02, 0.02, 0.02, density=1240.0), 0.001, 0.2)
    >>> bool(np.isclose(cube.mass_properties().mass, 1240 * (0.02**3 - 0.8 * 0.018**3), rtol=1e-12))
    True
    >>> printed(box(1, 1, 1), 0.1, 1.5)
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: an infill fraction must be between 0 and 1 (0 % to 100 %), not 1.5
    """
    f = float(infill)
    if not (np.isfinite(f) and 0.0 <= f <= 1.0):
        raise GeometryError(f"an infill fraction must be between 0 and 1 (0 % to 100 %), not {infill!r}")
    if body.dim != 3 or body.kind != "solid":
        raise GeometryError(f"only a solid can be printed with a shell and infill, not a {body.kind}")
    densities = body.densities()
    if len(densities) != 1 or "field" in densities:
        raise GeometryError("a printed part needs one density throughout (its walls' material): "
                            "print each part of an assembly on its own")
    return Printed(body, inward_offset(body, shell, step=step), f, name=getattr(body, "name", None))


def parse_length(text: str, scale: float = 1.0, *, what: str = "a length") -> float:
    """A length such as ``"1.2mm"`` or ``"0.0012"`` (a bare number in units of ``scale``
    m) in metres, by :func:`plumbob.units.parse_length`; a :class:`GeometryError` if not.

    >>> parse_length("1.2mm"), parse_length("2", scale=1e-3), parse_length("0.5 in")
    (0.0012, 0.002, 0.0127)
    """
    return units_parse_length(text, scale, what=what, error=GeometryError)


def parse_fraction(text: str) -> float:
    """A fraction from ``"20%"`` or ``"0.2"``.

    >>> parse_fraction("20%"), parse_fraction("0.35"), parse_fraction("100 %")
    (0.2, 0.35, 1.0)
    """
    text = str(text)
    percent = text.rstrip().endswith("%")
    parts = split_length(text.rstrip()[:-1] if percent else text)
    if parts is None or parts[1]:
        raise GeometryError(f"an infill must be a fraction (0.2) or a percentage (20%), not {text!r}")
    return parts[0] / 100 if percent else parts[0]


def printed_from_options(body: Body, shell: str | None, infill: str | None, *,
                         scale: float = 1.0, where: str = "--shell/--infill") -> Printed:
    """``body`` as printed with a shell and infill given as text (``"1.2mm"``, ``"20%"``),
    as the command line (``--shell``, ``--infill``) and a spec part give them; a bare
    shell number is in units of ``scale`` m.

    Both are needed: a shell without an infill (or the reverse) is an error that says so,
    rather than a guessed default.

    >>> from plumbob.bodies.primitives import box
    >>> printed_from_options(box(0.02, 0.02, 0.02), "1mm", "20%").infill
    0.2
    >>> printed_from_options(box(1, 1, 1), "1mm", None)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: --shell/--infill: give both the wall thickness and the infill (...)
    """
    if shell is None or infill is None:
        raise GeometryError(f"{where}: give both the wall thickness and the infill "
                            "(--shell 1.2mm --infill 20%)")
    try:
        thickness = parse_length(shell, scale, what="a shell thickness")
        if not thickness > 0:
            raise GeometryError(f"a shell thickness must be positive, not {shell!r}")
        return printed(body, thickness, parse_fraction(infill))
    except GeometryError as error:
        raise error.within(where) from None
