"""Density fields: a density given as a function of position, ρ(x, y, z).

A :class:`DensityField` wraps a vectorised function of points and, when it is
a polynomial, its degree (a polynomial field is integrated exactly). Fields
come from a spec expression (:meth:`DensityField.from_expression`) or a
Python function (:meth:`DensityField.from_callable`); a field moves with the
body it is given to (:meth:`DensityField.composed`).
:func:`plumbob.bodies.graded.with_density_field` gives a body one.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from ..errors import DensityError, ExpressionError, LimitError
from ..limits import MAX_DENSITY_DEGREE

__all__ = ["DensityField", "FIELD_DENSITY", "COORDINATES"]

COORDINATES = ("x", "y", "z")


# ------------------------------------------------------------------ fields
class _FieldMarker(str):
    """The string "field", standing for a density field where a number is expected.

    Equal to "field"; ``float()`` of it raises a :class:`DensityError`, so code
    that would turn a graded body into a uniform one (a faceted boolean) stops
    with a message instead of silently dropping the field.
    """

    def __float__(self) -> float:
        raise DensityError(
            "a density field cannot be carried through a boolean of overlapping parts: "
            "combine the parts first, then give the combined body the field")


FIELD_DENSITY = _FieldMarker("field")


@dataclass(frozen=True, eq=False, repr=False)
class DensityField:
    """A density given as a function of position.

    function: vectorised, points (n, d) m → values (n,): kg/m³ for solids,
        kg/m² (areal) for laminas, whose points have d = 2 (z = 0).
    degree: the polynomial degree in x, y, z, or None (not a polynomial, or
        not known): a polynomial field is integrated exactly.
    text: how the field is named in messages and notes.
    path, place: the file and the place in it the field was given (``shape.density``),
        named by every message about its values; None and "" for a field built in code.

    >>> f = DensityField.from_expression("1 + x")
    >>> f.degree, f(np.array([[0.5, 0.0]])).tolist()
    (1, [1.5])
    """

    function: Callable[[np.ndarray], np.ndarray]
    degree: int | None = None
    text: str = "the density field"
    path: str | None = None
    place: str = ""

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise DensityError(f"a density field needs a function, not {self.function!r}")
        if self.degree is not None:
            if int(self.degree) != self.degree or self.degree < 0:
                raise DensityError(f"a polynomial degree is a whole number ≥ 0, not {self.degree!r}")
            object.__setattr__(self, "degree", int(self.degree))
            # A rule of degree d has O(d³) points per cell: check before anything is built.
            if self.degree > MAX_DENSITY_DEGREE:
                shown = f"{self.degree}" if self.degree < 10**9 else f"{float(self.degree):.3g}"
                raise LimitError(
                    f"the density field {self.text!r} is a polynomial of degree {shown}, over "
                    f"plumbob's limit of {MAX_DENSITY_DEGREE} (plumbob.limits.MAX_DENSITY_DEGREE)"
                    "; lower its degree")

    def __call__(self, points: np.ndarray) -> np.ndarray:
        """Values (n,) at ``points`` (n, d), d = 2 or 3 (m)."""
        pts = np.asarray(points, dtype=float)
        if pts.ndim == 1:
            pts = pts[None, :]
        values = np.asarray(self.function(pts), dtype=float)
        if values.ndim == 0:
            values = np.full(len(pts), float(values))
        values = values.reshape(-1)
        if values.shape != (len(pts),):
            raise DensityError(
                f"{self.text} gave {values.size} values for {len(pts)} points: a density "
                "function takes points (n, d) and returns n values")
        return values

    def __repr__(self) -> str:
        kind = "of unknown degree" if self.degree is None else f"of degree {self.degree}"
        return f"<DensityField {self.text!r} {kind}>"

    def __float__(self) -> float:
        raise DensityError(
            f"{self.text} is a density field, not a number: a boolean of overlapping "
            "parts cannot carry it; combine the parts first, then give the body the field")

    # ---------------------------------------------------------- constructors
    @classmethod
    def from_expression(cls, expression, scale: float = 1.0, *,
                        constants: Mapping[str, float] | None = None) -> DensityField:
        """A field from a spec expression in x, y, z (an ``Expression`` or its text).

        ``scale`` multiplies every value (e.g. a lamina's thickness, m, turning
        kg/m³ into kg/m²); ``constants`` supplies other names (parameters).

        >>> DensityField.from_expression("2400 * (1 + 0.1*z)").degree
        1
        >>> DensityField.from_expression("exp(x)").degree is None
        True
        """
        from ..expr import Expression, parse

        if isinstance(expression, str):
            expression = parse(expression)
        if not isinstance(expression, Expression):
            raise DensityError(f"a density expression must be text, not {expression!r}")
        constants = {k: float(v) for k, v in (constants or {}).items()}
        unknown = set(expression.names) - set(COORDINATES) - set(constants)
        if unknown:
            raise ExpressionError(
                f"in {expression.text!r}: unknown name(s) {', '.join(sorted(unknown))}; "
                "a density field may use x, y, z and the spec's parameters")
        scale = float(scale)
        if not (np.isfinite(scale) and scale > 0):
            raise DensityError(f"a density scale must be a positive number, not {scale:g}")
        coordinates = {n for n in expression.names if n in COORDINATES}
        degree = expression.degree(set(COORDINATES), constants) if coordinates else 0

        def function(points: np.ndarray) -> np.ndarray:
            env: dict[str, float | np.ndarray] = dict(constants)
            env["x"], env["y"] = points[:, 0], points[:, 1]
            env["z"] = points[:, 2] if points.shape[1] > 2 else np.zeros(len(points))
            values = expression.evaluate(env)
            return values * scale if scale != 1.0 else values

        text = expression.text if scale == 1.0 else f"({expression.text}) × {scale:g}"
        return cls(function, degree, text)

    @classmethod
    def from_callable(cls, f: Callable[[np.ndarray], np.ndarray], degree: int | None = None,
                      text: str | None = None) -> DensityField:
        """A field from a Python function of points (n, d) → (n,).

        Give ``degree`` only when ``f`` is a polynomial of at most that degree:
        the rule is then chosen to be exact for it, and nothing checks the claim.

        >>> DensityField.from_callable(lambda p: 1 + p[:, 0] ** 2, degree=2).degree
        2
        """
        return cls(f, degree, text or getattr(f, "__name__", "the density field"))

    # ---------------------------------------------------------- algebra
    def composed(self, matrix: np.ndarray, offset: np.ndarray) -> DensityField:
        """The field seen from a body placed by ``p ↦ matrix @ p + offset``: ``p ↦ f(M p + o)``.

        An affine substitution keeps the polynomial degree.

        >>> f = DensityField.from_expression("1 + x").composed(np.eye(2), np.array([2.0, 0.0]))
        >>> f.degree, f(np.array([[0.0, 0.0]])).tolist()   # the body's origin sits at x = 2
        (1, [3.0])
        """
        matrix = np.asarray(matrix, dtype=float)
        offset = np.asarray(offset, dtype=float)
        outer = self

        def function(points: np.ndarray) -> np.ndarray:
            return outer.function(points @ matrix.T + offset)

        return DensityField(function, self.degree, self.text)

    def scaled(self, factor: float) -> DensityField:
        """Every value multiplied by ``factor`` (> 0): a lamina's thickness turns kg/m³
        into kg/m².

        >>> DensityField.from_expression("2 + x").scaled(0.5)(np.array([[2.0, 0.0]])).tolist()
        [2.0]
        >>> DensityField.from_expression("x").scaled(0)
        Traceback (most recent call last):
        ...
        plumbob.errors.DensityError: a density scale must be a positive number, not 0
        """
        factor = float(factor)
        if not (np.isfinite(factor) and factor > 0):
            raise DensityError(f"a density scale must be a positive number, not {factor:g}")
        outer = self
        return DensityField(lambda p: outer.function(p) * factor, self.degree,
                            f"({self.text}) × {factor:g}")
