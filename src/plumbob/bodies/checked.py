"""The arguments of every body's public questions, checked once for every kind.

A body kind implements :meth:`Body.support_points`, :meth:`Body.contains` and the
rest for its own geometry; a library user may call any of them with anything (text
for a direction, a ragged list of points, ``None`` for a density field). Rather than
each of a dozen implementations checking (or forgetting to), :class:`Body` wraps
every override of these methods, in its own class and in each subclass, with the
checks below: the implementation then receives clean values (a unit ``down`` of the
body's dimension, an (m, dim) float array of points, a finite tolerance, a whole
number of segments) and a bad value raises a
:class:`~plumbob.errors.GeometryError` naming the argument, never numpy's
``ValueError`` from deep inside.

Adding a question to the contract means adding a line to :data:`CHECKS`.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from typing import Any

import numpy as np

from ..arguments import (
    answering,
    check_density,
    count,
    floats,
    non_negative,
    number,
    optional,
    positive,
    unit_vector,
)
from ..errors import GeometryError

__all__ = ["CHECKS", "checked_method"]

#: the most segments a turn a curve may be cut into (2·10⁶ triangles a sphere)
MAX_SEGMENTS = 4096

Check = Callable[[Any, Any, str], Any]  # (body, value, argument name) -> clean value


def _down(body: Any, value: Any, what: str) -> np.ndarray:
    return unit_vector(value, what, (body.dim,), error=GeometryError)


def _points(body: Any, value: Any, what: str) -> np.ndarray:
    if isinstance(value, (str, bytes)):
        raise GeometryError(f"{what} must be numbers, not {value!r}")
    points = np.atleast_2d(floats(value, what, error=GeometryError))
    if points.ndim != 2 or points.shape[1] != body.dim:
        raise GeometryError(f"a {body.dim}D body takes {what} with {body.dim} coordinates, "
                            f"not an array of shape {np.shape(value)}")
    if not np.all(np.isfinite(points)):
        raise GeometryError(f"{what} must be finite numbers; {int(np.sum(~np.isfinite(points)))} "
                            "coordinates are not")
    return points


def _tolerance(body: Any, value: Any, what: str) -> float | None:
    """A tolerance that may be left out, m: finite and positive."""
    return optional(positive, value, what, error=GeometryError)


def _length(body: Any, value: Any, what: str) -> float:
    """A tolerance that must be given, m: finite and positive."""
    return positive(value, what, error=GeometryError)


def _depth(body: Any, value: Any, what: str) -> float:
    """How far above the lowest point still counts as touching, m: finite, ≥ 0."""
    return non_negative(value, what, error=GeometryError)


def _signed_tolerance(body: Any, value: Any, what: str) -> float | None:
    """:meth:`Body.contains`'s tolerance: negative asks for points that far inside."""
    return optional(number, value, what, error=GeometryError)


def _segments(body: Any, value: Any, what: str) -> int:
    return count(value, what, MAX_SEGMENTS, minimum=3, error=GeometryError)


def _density(body: Any, value: Any, what: str) -> float:
    checked = check_density(value, what)
    if checked is None:
        raise GeometryError(f"{what} must be a positive number (kg/m³), not None")
    return checked


def _optional_density(body: Any, value: Any, what: str) -> float | None:
    return check_density(value, what)


def _thickness(body: Any, value: Any, what: str) -> float | None:
    return optional(positive, value, what, error=GeometryError)


def _grader(body: Any, value: Any, what: str) -> Any:
    return answering(value, what, "leaf", kind="a density-field grader (plumbob.bodies.graded."
                     "with_density_field)", error=GeometryError)


#: method name → {argument name: its check}; arguments not listed are passed as given
CHECKS: dict[str, dict[str, Check]] = {
    "support_points": {"down": _down, "tolerance": _depth},
    "contains": {"points": _points, "tolerance": _signed_tolerance},
    "hull_points": {"tolerance": _tolerance},
    "surface": {"segments": _segments},
    "to_geometry": {"segments": _segments},
    "outline": {"tolerance": _length, "segments": _segments},
    "with_default_density": {"density": _density},
    "with_material": {"density": _optional_density, "thickness": _thickness},
    "graded": {"grader": _grader},
}


def checked_method(name: str, method: Callable) -> Callable:
    """``method`` (a body's ``name`` question) with its arguments checked by :data:`CHECKS`
    first; already wrapped methods are returned as they are."""
    if getattr(method, "__plumbob_checked__", False):
        return method
    checks = CHECKS[name]
    signature = inspect.signature(method)
    names = list(signature.parameters)[1:]  # after self

    @functools.wraps(method)
    def wrapper(self, *args, **kwargs):
        if len(args) > len(names):
            return method(self, *args, **kwargs)  # let Python name the surplus argument
        args = list(args)
        for i, value in enumerate(args):
            check = checks.get(names[i])
            if check is not None:
                args[i] = check(self, value, names[i])
        for key, value in kwargs.items():
            check = checks.get(key)
            if check is not None:
                kwargs[key] = check(self, value, key)
        return method(self, *args, **kwargs)

    wrapper.__plumbob_checked__ = True
    return wrapper


def check_questions(cls: type) -> None:
    """Wrap every question of :data:`CHECKS` that ``cls`` defines itself."""
    for name in CHECKS:
        method = cls.__dict__.get(name)
        if inspect.isfunction(method):
            setattr(cls, name, checked_method(name, method))
