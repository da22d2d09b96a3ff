"""Errors: every failure a user can act on is a subclass of :class:`PlumbobError`.

The message names the file (when there is one), what is wrong and what to do.
The CLI prints ``str(error)`` on one line and exits with status 2.
"""

from __future__ import annotations


class PlumbobError(Exception):
    """Base class of every error plumbob raises on bad input."""

    def __init__(self, message: str, *, path: str | None = None) -> None:
        self.path = path
        self.message = message
        super().__init__(f"{path}: {message}" if path else message)


class InputFileError(PlumbobError):
    """A file is missing, unreadable, empty, truncated or of an unknown kind."""


class FormatError(PlumbobError):
    """A file's contents do not follow its format."""


class SpecError(PlumbobError):
    """A shape spec has an unknown key, a missing value or a value of the wrong kind."""


class ExpressionError(SpecError):
    """A spec expression is malformed or uses something the evaluator does not allow."""


class GeometryError(PlumbobError):
    """The geometry is degenerate or invalid: zero area or volume, an open or
    self-intersecting boundary, non-finite coordinates."""


class DensityError(PlumbobError):
    """A density is negative, zero, not finite or unknown."""


class MaterialError(DensityError):
    """A material name is not in the material table."""


class StabilityError(PlumbobError):
    """A stability question cannot be answered for this body (e.g. its centre of
    mass lies outside its convex hull)."""


class DynamicsError(PlumbobError):
    """Bad input to a particle simulation or a collision."""


class BodyQueryError(PlumbobError):
    """A kind of body cannot answer a question asked of it: it does not implement
    that part of the :class:`plumbob.bodies.base.Body` interface (for example
    ``contains`` or ``is_polytope``), so no answer is guessed."""
