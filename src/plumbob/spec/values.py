"""The values in a spec, for shape and simulation specs alike: numbers or expressions,
points and vectors, tables whose keys are checked, and the ``[parameters]``.

Every complaint is a :class:`~plumbob.errors.SpecError` naming the spec's file and the
place (``part 2.radius``), so a user can find and fix it.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..bodies.csg import DEFAULT_SEGMENTS
from ..errors import LimitError, PlumbobError, SpecError
from ..expr import CONSTANTS, parse
from ..units import LENGTH_UNITS, MAX_LENGTH, parse_length, split_length, too_long, unit_symbol

__all__ = ["SpecContext", "LoadOptions", "suggest", "shown", "read_parameters", "RESERVED_NAMES"]

#: names a parameter may not take: the coordinates of a density field and the constants
RESERVED_NAMES = ("x", "y", "z", "pi", "e")


#: how a message names the type of a TOML value
_TOML_TYPES = {bool: "a boolean", int: "an integer", float: "a number", str: "text",
               list: "an array", dict: "a table"}


def shown(value: Any) -> str:
    """``value`` and its TOML type for a message, kept short: ``'no' (text)``.

    >>> shown(["m"]), shown(True), shown(list(range(100)))[:20]
    ("['m'] (an array)", 'True (a boolean)', '[0, 1, 2, 3, 4, 5, 6')
    """
    kind = _TOML_TYPES.get(type(value), f"a {type(value).__name__}")
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) > 10**30:
        return f"an integer of {len(str(abs(value)))} digits"
    text = repr(value)
    if len(text) > 60:
        text = text[:57] + "…"
    return f"{text} ({kind})"


@dataclass(frozen=True)
class LoadOptions:
    """How a spec is read, beyond its own text: the caller's choices.

    parameters: values replacing ``[parameters]`` entries by name (``--set``).
    units: the length unit the caller gives (``--units``): the spec's unit when it
        sets none; an error when it sets another.
    repair: close small holes in the spec's mesh files.
    units_override: ``units`` replaces the spec's own unit (``--units-override``).
    allow_outside_files: let a ``file`` name a path outside the spec's folder
        (absolute, or climbing out with ``..``); refused by default.
    """

    parameters: Mapping[str, float | str] | None = None
    units: str | None = None
    repair: bool = False
    allow_outside_files: bool = False
    units_override: bool = False


@dataclass(frozen=True)
class SpecContext:
    """What reading one spec needs at every value: the file (for messages), the
    parameters an expression may use, metres per length unit of the spec, the unit's
    name when the spec (or the caller) states one, the caller's load options, the
    notices gathered while building (a mesh file's, say), and the segments per turn
    of its faceted booleans."""

    path: str | None
    names: Mapping[str, float]
    scale: float = 1.0
    unit: str | None = None
    options: LoadOptions = LoadOptions()
    notices: list[str] = field(default_factory=list, compare=False)
    #: circular segments per turn for a boolean of overlapping curved parts
    segments: int = DEFAULT_SEGMENTS

    def error(
        self, where: str | None, message: str, cls: type[PlumbobError] = SpecError
    ) -> PlumbobError:
        """The error to raise for ``message`` at ``where`` (None: the spec as a whole)."""
        return cls(f"{where}: {message}" if where else message, path=self.path)

    @contextmanager
    def at(self, where: str) -> Iterator[None]:
        """Place any error raised inside (by a primitive, a boolean, the expression
        parser, the material table) at ``where`` in this spec, as a SpecError; an
        error already naming a file (a nested place, a mesh file) passes unchanged."""
        try:
            yield
        except PlumbobError as error:
            if error.path is not None:
                raise
            # a limit stays a LimitError (its own kind of refusal); all else is the spec's
            family = None if isinstance(error, LimitError) else SpecError
            raise error.within(where, path=self.path, cls=family) from None

    def number(self, value: Any, where: str, length: bool = False) -> float:
        """A TOML number or an expression over the parameters; ``length``: scaled to
        metres by the spec's unit."""
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise self.error(where, f"expected a number or an expression, not {shown(value)}")
        if isinstance(value, str):
            with self.at(where):
                result = parse(value).evaluate(self.names)
            if np.ndim(result) != 0:
                raise self.error(where, f"{value!r} must give a single number")
        else:
            result = value
        try:
            result = float(result)
        except OverflowError:
            raise self.error(where, f"{shown(value)} is beyond the range of a number "
                             "(about ±1.8e308)") from None
        if not np.isfinite(result):
            raise self.error(where, f"{shown(value)} is not a finite number")
        if length and abs(result * self.scale) > MAX_LENGTH:
            raise self.error(where, too_long("the length", result * self.scale))
        return result * (self.scale if length else 1.0)

    def text(self, value: Any, where: str, choices: Iterable[str] | None = None,
             what: str = "text") -> str:
        """A non-empty string (one of ``choices`` when given)."""
        if not isinstance(value, str):
            raise self.error(where, f"expected {what}, not {shown(value)}")
        if not value.strip():
            raise self.error(where, f"expected {what}, not an empty string")
        if choices is not None and value not in choices:
            raise self.error(where, f"unknown {what} {value!r}{suggest(value, set(choices))}")
        return value

    def flag(self, value: Any, where: str) -> bool:
        """A TOML boolean: ``true`` or ``false``, never a string (``"no"`` is not false)."""
        if not isinstance(value, bool):
            raise self.error(where, f"expected true or false (a boolean), not {shown(value)}")
        return value

    def unit_name(self, value: Any, where: str) -> str:
        """A length unit a spec may name (``units = "mm"``)."""
        if not isinstance(value, str):
            raise self.error(where, f"expected a length unit as text ({', '.join(LENGTH_UNITS)}),"
                             f" not {shown(value)}")
        try:
            return unit_symbol(value)
        except PlumbobError:
            raise self.error(where, f"unknown unit {value!r}; use one of "
                             f"{', '.join(LENGTH_UNITS)}") from None

    def points(
        self, value: Any, where: str, dims: tuple[int, ...] = (2,), length: bool = True
    ) -> np.ndarray:
        """A list of points, each of one of ``dims`` coordinates, all alike."""
        if not isinstance(value, list) or not value:
            raise self.error(where, "expected a list of points like [[0, 0], [1, 0], [0, 1]], "
                             f"not {shown(value)}")
        rows = []
        for i, row in enumerate(value):
            if not isinstance(row, list) or len(row) not in dims:
                raise self.error(
                    where, f"point {i + 1} must be a list of {' or '.join(map(str, dims))} numbers"
                )
            rows.append([self.number(v, f"{where}[{i + 1}]", length) for v in row])
        if len({len(r) for r in rows}) != 1:
            raise self.error(where, "all points must have the same number of coordinates")
        return np.array(rows)

    def vector(
        self,
        value: Any,
        where: str,
        dims: tuple[int, ...],
        length: bool = True,
        like: str | None = None,
    ) -> np.ndarray:
        """A list of one of ``dims`` numbers; ``like`` names what fixes the count
        (``the positions``) for the message when it is wrong."""
        count = " or ".join(map(str, dims))
        if not isinstance(value, list):
            raise self.error(where, f"expected a list of {count} numbers, not {shown(value)}")
        if len(value) not in dims:
            reason = f" like {like}" if like else ""
            raise self.error(where, f"expected {count} components{reason}, not {len(value)}")
        return np.array([self.number(v, f"{where}[{i + 1}]", length) for i, v in enumerate(value)])

    def table(self, value: Any, allowed: set[str], where: str, what: str = "key") -> dict:
        """``value`` as a table of ``allowed`` keys (``what`` names them in the message)."""
        if not isinstance(value, dict):
            raise self.error(where, f"expected a table, not {shown(value)}")
        for key in value:
            if key not in allowed:
                raise self.error(where, f"unknown {what} {key!r}{suggest(key, allowed)}")
        return value


def suggest(key: str, allowed: set[str]) -> str:
    """``; did you mean 'width'?`` for a near miss, else the keys allowed."""
    close = difflib.get_close_matches(key, sorted(allowed), n=1)
    return f"; did you mean {close[0]!r}?" if close else f"; allowed: {', '.join(sorted(allowed))}"


def read_parameters(
    path: str | None,
    table: Any,
    overrides: Mapping[str, float | str] | None = None,
    scale: float = 1.0,
) -> dict[str, float]:
    """``[parameters]``: numbers or expressions evaluated in order, each over those
    before it (never in the spec's length unit: a parameter is a plain number).

    ``overrides`` replace entries by name before evaluation (``--set name=value``), so
    the parameters after an overridden one follow it. An override is a number, an
    expression over the parameters before it, or a number with a length unit
    (``"30 cm"``), converted into the spec's unit (``scale``: metres per spec unit).
    An override naming no parameter is an error listing the known ones.

    >>> read_parameters(None, {"a": 1, "b": "2*a"}, {"a": "3"})
    {'a': 3.0, 'b': 6.0}
    >>> read_parameters(None, {"w": 100}, {"w": "0.3 m"}, scale=1e-3)
    {'w': 300.0}
    >>> read_parameters("s.toml", {"a": 1}, {"b": 2})
    Traceback (most recent call last):
    ...
    plumbob.errors.SpecError: s.toml: parameters: no parameter 'b' to set; known: a
    """
    if not isinstance(table, dict):
        raise SpecError("[parameters] must be a table of name = value", path=path)
    overrides = dict(overrides or {})
    unknown = sorted(set(overrides) - set(table))
    if unknown:
        known = ", ".join(table) if table else "none (the spec has no [parameters])"
        names_ = ", ".join(map(repr, unknown))
        raise SpecError(f"parameters: no parameter {names_} to set; known: {known}", path=path)
    names: dict[str, float] = {}
    context = SpecContext(path, names)
    for key, value in table.items():
        if key in RESERVED_NAMES:
            raise context.error(f"parameters.{key}", f"{key!r} is reserved; choose another name")
        if key in overrides:
            names[key] = _override(context, overrides[key], f"parameters.{key} (as set)", scale)
        else:
            names[key] = context.number(value, f"parameters.{key}")
    return names


def _override(context: SpecContext, value: Any, where: str, scale: float) -> float:
    """An override's value: a number, an expression, or a number with a length unit
    in the spec's unit."""
    if isinstance(value, str):
        parts = split_length(value)
        if parts is not None and parts[1] and parts[1] not in CONSTANTS:  # not "2pi"
            try:
                metres = parse_length(value)
            except PlumbobError as error:
                raise context.error(where, str(error)) from None
            return context.number(metres / scale, where)
    return context.number(value, where)
