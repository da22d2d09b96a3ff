"""Checking the arguments of plumbob's public functions, in one place.

A library user who passes ``g=-9.81``, ``datum=nan`` or a (1, 3) array as a velocity
gets a :class:`~plumbob.errors.PlumbobError` naming the argument, what it must be and
what was given — never a foreign exception from deep inside numpy, and never a
silently wrong answer. Each checker returns the value in the form the caller works
with (a float, a 1-D array, an int), so a function checks and converts in one line.

``error`` picks the family a room promises (a :class:`DynamicsError` from the
dynamics, a :class:`StabilityError` from stability); the default is
:class:`ArgumentError`.
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np

from .errors import ArgumentError, DensityError, PlumbobError
from .limits import check_count

__all__ = [
    "check_density",
    "placement",
    "number",
    "positive",
    "non_negative",
    "in_range",
    "floats",
    "vector",
    "unit_vector",
    "matrix",
    "count",
    "file_path",
    "finite_result",
    "optional",
    "answering",
    "instance",
    "mass_fields",
]

Error = type[PlumbobError]


def number(value: Any, what: str, *, error: Error = ArgumentError) -> float:
    """``value`` as a finite float (numeric text such as ``"2.5"`` is read as a number);
    ``True``, other text, ``nan`` and ``inf`` are refused.

    >>> number(2, "datum")
    2.0
    >>> number(float("nan"), "datum")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: datum must be a finite number, not nan
    >>> number("high", "datum")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: datum must be a number, not 'high'
    """
    result = _float(value, what, error)
    if not math.isfinite(result):
        raise error(f"{what} must be a finite number, not {result:g}")
    return result


def _float(value: Any, what: str, error: Error) -> float:
    """``value`` as a float, finite or not; a bool or non-numeric value is an error."""
    if isinstance(value, (bool, np.bool_)):
        raise error(f"{what} must be a number, not {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        raise error(f"{what} must be a number, not {_short(value)}") from None


def positive(value: Any, what: str, *, error: Error = ArgumentError) -> float:
    """``value`` as a finite float > 0 (a length, a mass, ``g``).

    >>> positive(9.81, "g")
    9.81
    >>> positive(-9.81, "g")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: g must be a positive number, not -9.81
    """
    result = _float(value, what, error)
    if not (math.isfinite(result) and result > 0):
        raise error(f"{what} must be a positive number, not {result:g}")
    return result


def non_negative(value: Any, what: str, *, error: Error = ArgumentError) -> float:
    """``value`` as a finite float ≥ 0 (a friction coefficient, a height).

    >>> non_negative(0, "friction")
    0.0
    """
    result = _float(value, what, error)
    if not (math.isfinite(result) and result >= 0):
        raise error(f"{what} must be a non-negative number, not {result:g}")
    return result


def in_range(value: Any, what: str, low: float, high: float, *, unit: str = "",
             error: Error = ArgumentError) -> float:
    """``value`` as a finite float in ``[low, high]``.

    >>> in_range(10, "require_tilt_deg", 0, 90, unit="°")
    10.0
    >>> in_range(100, "require_tilt_deg", 0, 90, unit="°")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: require_tilt_deg must be from 0° to 90°, not 100°
    """
    result = number(value, what, error=error)
    if not low <= result <= high:
        raise error(f"{what} must be from {low:g}{unit} to {high:g}{unit}, not {result:g}{unit}")
    return result


def floats(value: Any, what: str, *, error: Error = ArgumentError) -> np.ndarray:
    """``value`` as a float array of any shape (the caller checks the shape), or an error
    naming ``what`` instead of numpy's ValueError for text or ragged lists.

    >>> floats([["a", 1]], "positions")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: positions must be numbers, not [['a', 1]]
    """
    try:
        return np.array(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise error(f"{what} must be numbers, not {_short(value)}") from None


def vector(value: Any, what: str, dims: tuple[int, ...] = (2, 3), *,
           error: Error = ArgumentError) -> np.ndarray:
    """``value`` as a 1-D float array of one of ``dims`` finite components.

    A (1, 3) array is refused, not flattened: a table of velocities passed where one
    velocity belongs is a mistake the caller must see.

    >>> vector([3, 4], "v1", (1, 2, 3))
    array([3., 4.])
    >>> vector([[1, 0, 0]], "v1", (3,))
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: v1 must be one vector of 3 numbers, not an array of shape (1, 3)
    """
    allowed = _choices(dims)
    if isinstance(value, (str, bytes)):
        raise error(f"{what} must be a vector of {allowed} numbers, not {value!r}")
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise error(f"{what} must be a vector of {allowed} numbers, not {_short(value)}"
                    ) from None
    if array.ndim == 0 and 1 in dims:
        array = array.reshape(1)
    if array.ndim != 1 or array.size not in dims:
        shape = f"an array of shape {array.shape}" if array.ndim != 1 else \
            f"{array.size} numbers"
        raise error(f"{what} must be one vector of {allowed} numbers, not {shape}")
    if not np.all(np.isfinite(array)):
        raise error(f"{what} has a component that is not a finite number: {_short(value)}")
    return array


def unit_vector(value: Any, what: str, dims: tuple[int, ...] = (2, 3), *,
                error: Error = ArgumentError) -> np.ndarray:
    """``value`` (any non-zero length) scaled to length 1, as :func:`vector` checks it.

    >>> unit_vector([0, 0, -2], "down", (3,))
    array([ 0.,  0., -1.])
    >>> unit_vector([0, 0, 0], "down", (3,))
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: down must be a non-zero vector, not [0, 0, 0]
    """
    array = vector(value, what, dims, error=error)
    biggest = float(np.max(np.abs(array)))
    if biggest == 0:
        raise error(f"{what} must be a non-zero vector, not {_short(value)}")
    scaled = array / biggest  # no overflow in the norm of (1e200, 1e200, 0)
    return scaled / float(np.linalg.norm(scaled))


def matrix(value: Any, what: str, shape: tuple[int, ...], *,
           error: Error = ArgumentError) -> np.ndarray:
    """``value`` as a float array of exactly ``shape`` with finite entries (a tensor).

    >>> matrix(np.eye(2), "inertia", (3, 3))
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: inertia must be a finite array of shape (3, 3), not (2, 2)
    """
    try:
        array = np.array(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise error(f"{what} must be a finite array of shape {shape}, not {_short(value)}"
                    ) from None
    if array.shape != shape or not np.all(np.isfinite(array)):
        given = array.shape if array.shape != shape else "one with a non-finite entry"
        raise error(f"{what} must be a finite array of shape {shape}, not {given}")
    return array


def placement(matrix_: Any, offset: Any, dim: int, *,
              error: Error = ArgumentError) -> tuple[np.ndarray, np.ndarray]:
    """A rigid placement of a body of ``dim`` dimensions: ``matrix_`` an orthogonal
    ``dim`` × ``dim`` array (a rotation or a reflection: a body is moved, never stretched,
    to within 1e-12) and ``offset`` one vector of ``dim`` numbers, m (None: no move).

    >>> placement(np.eye(2), None, 3)
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: matrix must be a finite array of shape (3, 3), not (2, 2)
    >>> placement(2 * np.eye(2), [0, 0], 2)
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: matrix must be orthogonal (a rotation or a reflection): a \
body is moved, never stretched or skewed
    """
    turn = matrix(matrix_, "matrix", (dim, dim), error=error)
    if not np.allclose(turn @ turn.T, np.eye(dim), rtol=0, atol=1e-12):
        raise error("matrix must be orthogonal (a rotation or a reflection): a body is moved, "
                    "never stretched or skewed")
    move = np.zeros(dim) if offset is None else vector(offset, "offset", (dim,), error=error)
    return turn, move


def count(value: Any, what: str, limit: float, *, minimum: int = 0, hint: str = "",
          error: Error = ArgumentError) -> int:
    """``value`` as an int from ``minimum`` to ``limit``: a whole number of sides,
    samples or people (over the limit: :class:`LimitError`, checked before the work).

    >>> count(64, "segments", 10**6, minimum=3)
    64
    >>> count(2.5, "segments", 10**6, minimum=3)
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: segments must be a whole number of at least 3, not 2.5
    """
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise error(f"{what} must be a whole number, not {value!r}")
    try:
        whole = isinstance(value, (int, np.integer)) or float(value) == int(value)
    except (TypeError, ValueError, OverflowError):
        whole = False
    if not whole or int(value) < minimum:
        raise error(f"{what} must be a whole number of at least {minimum}, not {_short(value)}")
    checked = check_count(what, int(value), limit, hint=hint)
    return int(value) if isinstance(value, (int, np.integer)) else checked


def file_path(value: Any, what: str = "path", *, error: Error = ArgumentError) -> str:
    """``value`` (text or a path-like object) as a path string: not empty, no NUL byte.

    >>> file_path(None)
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: path must be a file name (str or os.PathLike), not None
    """
    try:
        text = os.fspath(value)
    except TypeError:
        raise error(f"{what} must be a file name (str or os.PathLike), not {_short(value)}"
                    ) from None
    if isinstance(text, bytes):
        text = os.fsdecode(text)
    if not text or "\0" in text:
        raise error(f"{what} must be a file name, not {text!r}")
    return text


def optional(check: Any, value: Any, *args: Any, **options: Any) -> Any:
    """None for an argument not given, else ``check(value, *args, **options)``.

    >>> optional(positive, None, "tolerance") is None, optional(positive, 2, "tolerance")
    (True, 2.0)
    """
    return None if value is None else check(value, *args, **options)


def finite_result(value: Any, what: str, *, error: Error = ArgumentError) -> Any:
    """``value`` unchanged when every number in it is finite; else an error saying the
    answer overflows (finite inputs whose product is beyond 1.8e308).

    >>> finite_result(2.0, "the lift energy")
    2.0
    >>> finite_result(1e308 * 10, "the lift energy")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: the lift energy overflows (inf): the inputs are too large \
to give a finite answer in double precision
    """
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return value  # not numbers at all: the caller's own checks name what is wrong
    if not np.all(np.isfinite(array)):
        bad = float(array[~np.isfinite(array)].reshape(-1)[0])
        if math.isnan(bad):
            raise error(f"{what} is not a number (nan): the inputs are too large or undefined "
                        "for a finite answer in double precision")
        raise error(f"{what} overflows ({bad:g}): the inputs are too large to give a finite "
                    "answer in double precision")
    return value


def answering(value: Any, what: str, method: str, *, kind: str = "a plumbob body",
              error: Error = ArgumentError) -> Any:
    """``value`` when it offers ``method`` (a body's ``mass_properties``), else an error
    naming what was expected (duck-typed: this layer knows no body classes).

    >>> answering(None, "body", "mass_properties")
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: body must be a plumbob body (with mass_properties()), not None
    """
    if not callable(getattr(value, method, None)):
        raise error(f"{what} must be {kind} (with {method}()), not {_short(value)}")
    return value


def _choices(dims: tuple[int, ...]) -> str:
    """``(1, 2, 3)`` → ``"1, 2 or 3"``."""
    words = [str(d) for d in dims]
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + " or " + words[-1]


def _short(value: Any, limit: int = 60) -> str:
    """How a message shows a bad value: its repr, or an array's shape, cut to ``limit``."""
    if isinstance(value, np.ndarray) and value.size > 3:
        return f"an array of shape {value.shape}"
    text = repr(value.tolist() if isinstance(value, np.ndarray) else value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def instance(value: Any, what: str, cls: type, *, error: Error = ArgumentError) -> Any:
    """``value`` when it is a ``cls`` (``props`` must be :class:`MassProperties`).

    >>> instance(5, "props", dict)
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: props must be a dict, not int
    """
    if not isinstance(value, cls):
        raise error(f"{what} must be a {cls.__name__}, not {type(value).__name__}")
    return value


def mass_fields(dim: Any, mass: Any, measure: Any, center: Any, inertia: Any
                ) -> tuple[np.ndarray, np.ndarray, float, float]:
    """The fields of a mass-properties record checked and converted: ``dim`` 2 or 3, a
    finite centre of ``dim`` coordinates, a finite (3, 3) inertia tensor, a finite mass
    and size ≥ 0 (copies, as arrays and floats). Good values take one quick test (a
    record is built for every part); the checks that name what is wrong, an overflow
    as one, run only when it fails.

    >>> mass_fields(2, 1.0, 0.5, [0, 0, 0], np.eye(3))
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: center_of_mass must be one vector of 2 numbers, not 3 numbers
    """
    try:
        com, tensor = np.array(center, dtype=float), np.array(inertia, dtype=float)
        kg, size = float(mass), float(measure)
        good = (dim in (2, 3) and not isinstance(dim, bool) and com.shape == (dim,)
                and tensor.shape == (3, 3) and np.isfinite(com).all()
                and np.isfinite(tensor).all() and math.isfinite(kg) and kg >= 0
                and math.isfinite(size) and size >= 0)
    except (TypeError, ValueError, OverflowError):
        good = False
    if good:
        return com, tensor, kg, size
    if dim not in (2, 3) or isinstance(dim, bool):
        raise ArgumentError(f"dim must be 2 (a lamina) or 3, not {dim!r}")
    com = vector(center, "center_of_mass", (dim,)).copy()
    tensor = floats(inertia, "inertia")
    finite_result(tensor if tensor.shape == (3, 3) else 0.0, "the moment of inertia")
    finite_result([mass, measure], "the mass or size")
    tensor = matrix(tensor, "inertia", (3, 3))
    return com, tensor, non_negative(mass, "mass"), non_negative(measure, "measure")


def check_density(density: float | None, what: str = "density") -> float | None:
    """A density as a float, checked: a positive finite number, or None (not given).

    Parameters
    ----------
    density : float or None
        kg/m³ (kg/m² for a lamina given by its areal density).
    what : str
        How to name the value in the error message.

    Returns
    -------
    float or None

    Raises
    ------
    DensityError
        Not a number, not finite, zero or negative.

    Examples
    --------
    >>> check_density("2700"), check_density(None)
    (2700.0, None)
    >>> check_density(0, "--density")
    Traceback (most recent call last):
    ...
    plumbob.errors.DensityError: --density must be a positive finite number, not 0
    """
    if density is None:
        return None
    if isinstance(density, (bool, bytes)):
        raise DensityError(f"{what} must be a number, not {density!r}")
    try:
        value = float(density)
    except OverflowError:  # an int beyond 1.8e308
        raise DensityError(f"{what} must be a positive finite number, not a "
                           f"{len(str(density))}-digit number") from None
    except (TypeError, ValueError):
        raise DensityError(f"{what} must be a number, not {density!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise DensityError(f"{what} must be a positive finite number, not {value:g}")
    return value
