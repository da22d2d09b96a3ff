"""The command line's value types: what ``argparse`` calls on the text of an option
(numbers, lengths with a unit, vectors, loads, assignments), each a one-line
:class:`argparse.ArgumentTypeError` or :class:`~plumbob.errors.ArgumentError` on bad
text. Only the standard library and plumbob's checks load here.
"""

from __future__ import annotations

import argparse
import math

from ..errors import DynamicsError, PlumbobError

__all__ = [
    "number",
    "positive",
    "count",
    "non_negative",
    "length",
    "parse_vector",
    "direction",
    "material_name",
    "tilt_limit",
    "pose_or_auto",
    "number_option",
    "length_unit",
    "assignment",
]


def number(text: str) -> float:
    """An argparse type: a finite number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"not a finite number: {text!r}")
    return value


def positive(text: str) -> float:
    """An argparse type: a positive finite number."""
    value = number(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"must be positive, not {text}")
    return value


def count(text: str) -> int:
    """A whole number of at least 1 (people in a crew, worker processes)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, not {value}")
    return value


def non_negative(text: str) -> float:
    """An argparse type: a finite number ≥ 0."""
    value = number(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"must not be negative, not {text}")
    return value


def length(text: str) -> float:
    """An argparse type: a length ≥ 0 in metres, or with a unit (``3mm``, ``0.5 in``), read
    by :func:`plumbob.units.parse_length`."""
    from ..units import parse_length

    try:
        value = parse_length(text)
    except PlumbobError as error:
        raise argparse.ArgumentTypeError(str(error)) from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite length, not {text}")
    if value < 0:
        raise argparse.ArgumentTypeError(f"must not be negative, not {text}")
    return value


def parse_vector(text: str, dims: tuple[int, ...] = (2, 3)) -> list[float]:
    """'X,Y[,Z]' → floats (for argparse ``type=``)."""
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"expected numbers separated by commas, not {text!r}"
        ) from None
    if len(values) not in dims:
        raise argparse.ArgumentTypeError(
            f"expected {' or '.join(map(str, dims))} numbers, not {text!r}"
        )
    if not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected finite numbers, not {text!r}")
    return values


def direction(text: str) -> list[float]:
    """An argparse type: 'X,Y[,Z]', a direction (``--down``): finite and not zero."""
    values = parse_vector(text)
    if not any(values):
        raise argparse.ArgumentTypeError(f"a direction must not be the zero vector: {text!r}")
    return values


def material_name(text: str) -> str:
    """An argparse type: a material name, not empty (``--material ''`` is a mistake,
    never "no material")."""
    if not text.strip():
        raise argparse.ArgumentTypeError("a material name must not be empty; "
                                         "'plumbob materials' lists them")
    return text


def tilt_limit(text: str) -> float:
    """An argparse type: a tilt in degrees from 0 to 90 (``--require-tilt``)."""
    value = number(text)
    if not 0 <= value <= 90:
        raise argparse.ArgumentTypeError(f"a tilt must be from 0 to 90 degrees, not {text}")
    return value


def pose_or_auto(text: str) -> int | str:
    """A resting pose's number K, or ``auto`` (``balance --target-pose``)."""
    if text.strip().lower() == "auto":
        return "auto"
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a pose number or 'auto', not {text!r}") from None


def number_option(text: str, label: str, *, infinite: bool = False) -> float:
    """The number given as option ``label`` of the dynamics commands, or a
    :class:`DynamicsError` naming it; ``infinite`` lets ``inf`` through (a wall's mass)."""
    try:
        value = float(text)
    except ValueError:
        raise DynamicsError(f"{label} must be a number (got {text!r})") from None
    if math.isnan(value) or (math.isinf(value) and not infinite):
        kind = "a number" if infinite else "a finite number"
        raise DynamicsError(f"{label} must be {kind} (got {text!r})")
    return value


def length_unit(text: str) -> str:
    """``--units``: a length unit in any spelling a person types, as its symbol."""
    from ..units import unit_symbol

    try:
        return unit_symbol(text)
    except PlumbobError as error:
        raise argparse.ArgumentTypeError(error.message) from None


def assignment(text: str) -> tuple[str, str]:
    """An argparse type: ``NAME=VALUE`` (``--set``) as (name, value)."""
    name, sep, value = text.partition("=")
    if not sep or not name.strip() or not value.strip():
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, not {text!r}")
    return name.strip(), value.strip()
