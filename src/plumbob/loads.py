"""Applied loads: forces pushing on a body and masses hung from it.

A :class:`Force` is a force vector (N) acting at a point of the body's frame (m); a
:class:`Hang` is a mass (kg) hung at a point, pulling along gravity with ``m g``. Both
are checked when made, so a NaN force, a point with the wrong number of coordinates
or a negative mass never reaches the arithmetic. The verdict under loads (which edge
the body goes over, the resisting and overturning moments about it, the factor of
safety) is :mod:`plumbob.stability.loaded`; a body read from a spec carries its
``[[load]]`` tables as these (:attr:`plumbob.reading.Reading.loads`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from .arguments import non_negative, positive, vector
from .errors import StabilityError

__all__ = ["Force", "Hang", "Push", "Press", "Load", "Extendable", "is_search", "loads_from_options"]


def _point(at, what: str) -> np.ndarray:
    return vector(at, what, (2, 3), error=StabilityError)


@dataclass(frozen=True)
class Force:
    """A force acting on the body.

    force: (dim,) N, body frame (a lamina's in its own plane: 2 numbers).
    at: (dim,) m, the point it acts at, body frame.
    name: what it is, for the report (optional).
    """

    force: np.ndarray
    at: np.ndarray
    name: str | None = None

    def __post_init__(self) -> None:
        label = f"the force {self.name!r}" if self.name else "a force"
        force = vector(self.force, f"{label}'s vector (N)", (2, 3), error=StabilityError)
        at = _point(self.at, f"{label}'s point")
        if force.shape != at.shape:
            raise StabilityError(f"{label} has {force.size} components but its point "
                                 f"{at.size} coordinates: give both in 2D or both in 3D")
        object.__setattr__(self, "force", force)
        object.__setattr__(self, "at", at)

    @property
    def dim(self) -> int:
        return int(self.at.size)

    def vector(self, gravity: np.ndarray) -> np.ndarray:
        """The force, N, body frame (``gravity``, the acceleration vector, is unused)."""
        return self.force

    def describe(self) -> str:
        return self.name or "force"


@dataclass(frozen=True)
class Hang:
    """A mass hung from the body: it pulls along gravity with ``mass · g``.

    mass: kg (≥ 0).
    at: (dim,) m, the point it hangs from, body frame.
    name: what it is, for the report (optional).
    """

    mass: float
    at: np.ndarray
    name: str | None = None

    def __post_init__(self) -> None:
        label = f"the hung mass {self.name!r}" if self.name else "a hung mass"
        object.__setattr__(self, "mass", non_negative(self.mass, f"{label} (kg)",
                                                      error=StabilityError))
        object.__setattr__(self, "at", _point(self.at, f"{label}'s point"))

    @property
    def dim(self) -> int:
        return int(self.at.size)

    def vector(self, gravity: np.ndarray) -> np.ndarray:
        """Its pull, N, body frame: ``mass`` times the acceleration vector ``gravity``."""
        return self.mass * np.asarray(gravity, dtype=float)

    def describe(self) -> str:
        return self.name or "hung mass"


@dataclass(frozen=True)
class _Searched:
    """A force of ``force`` N whose point the check searches for, no higher than
    ``max_height`` m above the floor (:class:`Push`, :class:`Press`)."""

    force: float
    max_height: float | None = None
    name: str | None = None

    #: what the report calls it
    _what: ClassVar[str] = "load"
    dim = None  # any body

    def __post_init__(self) -> None:
        label = f"the {self._what} {self.name!r}" if self.name else f"a {self._what}"
        object.__setattr__(self, "force", non_negative(self.force, f"{label} (N)",
                                                       error=StabilityError))
        if self.max_height is not None:
            object.__setattr__(self, "max_height", positive(
                self.max_height, f"{label}'s highest point (m)", error=StabilityError))

    def describe(self) -> str:
        return self.name or self._what


@dataclass(frozen=True)
class Push(_Searched):
    """A horizontal force of ``force`` N in every direction, anywhere on the body no
    higher than ``max_height`` m above the floor: the check finds the point and the
    direction that overturn it most (the highest point it may reach, pushed straight
    out over the weakest edge).

    force: N (≥ 0). max_height: m (> 0), or None for no limit. name: for the report.
    """

    _what: ClassVar[str] = "push"


@dataclass(frozen=True)
class Press(_Searched):
    """A downward force of ``force`` N anywhere on the body's top, no higher than
    ``max_height`` m: the check finds the point that overturns it most (the highest of
    the body's points that reach furthest out over the weakest edge).

    force: N (≥ 0). max_height: m (> 0), or None for no limit. name: for the report.
    """

    _what: ClassVar[str] = "press"


Load = Force | Hang | Push | Press

#: the load kinds a check places itself (the worst point), by their report name
SEARCHES = (Push, Press)


def is_search(load) -> bool:
    """Whether the check finds the load's point (a :class:`Push` or :class:`Press`)."""
    return isinstance(load, SEARCHES)


@dataclass(frozen=True)
class Extendable:
    """A part that opens — a drawer, a door, a pull-out shelf — as a spec marks it for the
    standards that open them (ASTM F2057).

    name: the part's name (its ``[[part]]`` name). parts: the names of every part that
        moves with it (the part itself first, then what it carries).
    travel: (dim,) m, body frame: how far and which way it moves from where the spec
        draws it to its stop.
    volume: m³, its storage volume (what a standard fills).
    """

    name: str
    parts: tuple[str, ...]
    travel: np.ndarray
    volume: float

    def __post_init__(self) -> None:
        label = f"the extendable {self.name!r}"
        object.__setattr__(self, "travel", vector(self.travel, f"{label}'s travel", (2, 3),
                                                  error=StabilityError))
        object.__setattr__(self, "volume", non_negative(self.volume, f"{label}'s volume (m³)",
                                                        error=StabilityError))
        object.__setattr__(self, "parts", tuple(self.parts) or (self.name,))


def loads_from_options(options, scale: float = 1.0) -> tuple:
    """Loads from the command line's parsed ``--force``/``--hang``/``--push``/``--press``
    values — ``("force", [FX, FY, FZ], [X, Y, Z])``, ``("hang", M, [X, Y, Z])``,
    ``("push" or "press", F, H or None)`` — with points and heights in a file's length unit
    (``scale`` metres per unit)."""
    made = []
    for kind, value, where in options or ():
        if kind == "force":
            made.append(Force(value, [scale * v for v in where]))
        elif kind == "hang":
            made.append(Hang(value, [scale * v for v in where]))
        else:
            made.append((Push if kind == "push" else Press)(
                value, None if where is None else scale * where))
    return tuple(made)
