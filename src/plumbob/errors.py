"""Errors: every failure a user can act on is a subclass of :class:`PlumbobError`.

The message names the file (when there is one), what is wrong and what to do.
The CLI prints ``str(error)`` on one line and exits with status 2.
"""

from __future__ import annotations

import numpy as np


class PlumbobError(Exception):
    """Base class of every error plumbob raises on bad input."""

    def __init__(self, message: str, *, path: str | None = None) -> None:
        self.path = path
        self.message = message
        super().__init__(f"{path}: {message}" if path else message)

    def within(
        self,
        context: str | None = None,
        *,
        path: str | None = None,
        cls: type[PlumbobError] | None = None,
    ) -> PlumbobError:
        """The same error placed where it happened: ``context: message``, naming
        ``path`` when it names no file yet (a file it already names is kept).

        The one way to add context, so an error raised deep in a builder reaches the
        user as ``file: place: problem``. ``cls``: the family the caller promises (every
        error building a spec is a :class:`SpecError`): an error not of it becomes one;
        otherwise the class is kept.

        >>> error = GeometryError("must be positive").within("part 1", path="a.toml")
        >>> type(error).__name__, str(error)
        ('GeometryError', 'a.toml: part 1: must be positive')
        >>> str(error.within(path="b.toml"))
        'a.toml: part 1: must be positive'
        >>> type(error.within(cls=SpecError)).__name__
        'SpecError'
        """
        message = f"{context}: {self.message}" if context else self.message
        family = type(self) if cls is None or isinstance(self, cls) else cls
        error = family(message, path=self.path or path)
        error.__dict__.update({k: v for k, v in self.__dict__.items()
                               if k not in ("message", "path")})
        return error


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


class TargetNotMet(StabilityError):
    """What was asked of a design (a margin, a tilt, a standard) cannot be reached by the
    means given (ballast, a carve): a failed requirement, not bad input — the command
    line exits with status 1, as ``check`` does when a requirement fails."""

    exit_status = 1


class DynamicsError(PlumbobError):
    """Bad input to a particle simulation or a collision."""


class LimitError(PlumbobError):
    """An input asks for more work than plumbob's limits allow (:mod:`plumbob.limits`):
    too many parts, too deep a nesting, too high a degree, too large an expansion."""


class ArgumentError(PlumbobError):
    """A library function was called with an argument of the wrong kind, shape or range
    (``g=-9.81``, ``datum=nan``, a (1, 3) array as one velocity); the message names the
    argument (:mod:`plumbob.arguments` checks them)."""


class BodyQueryError(PlumbobError):
    """A kind of body cannot answer a question asked of it: it does not implement
    that part of the :class:`plumbob.bodies.base.Body` interface (for example
    ``contains`` or ``is_polytope``), so no answer is guessed."""


def printable(text: object) -> str:
    r"""``text`` safe to print on a terminal: control and other non-printable characters
    (a file or part name with an ESC, a newline or a NUL) shown as Python escapes, so a
    name can neither rewrite the terminal nor forge a line of the report. Printable
    Unicode (``m³``, ``°``, ``é``) is kept.

    >>> print(printable("part\x1b[31m red\nnext"))
    part\x1b[31m red\nnext
    >>> printable("bloc³ é")
    'bloc³ é'
    """
    text = str(text)
    if text.isprintable():
        return text
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in text)


def fmt_point(point: np.ndarray) -> str:
    """``(x, y[, z])`` with 6 significant digits: how messages name a point.

    >>> fmt_point([0.5, 1 / 3, 2e-7])
    '(0.5, 0.333333, 2e-07)'
    """
    return "(" + ", ".join(f"{float(c):.6g}" for c in np.asarray(point).reshape(-1)) + ")"
