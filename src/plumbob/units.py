"""Length units accepted for coordinates in files and specs, and the default g."""

from __future__ import annotations

from .errors import PlumbobError

__all__ = ["LENGTH_UNITS", "STANDARD_GRAVITY", "length_scale"]

#: m/s², the seed unit's value of g, the default wherever gravity enters
STANDARD_GRAVITY = 9.81

#: metres per unit
LENGTH_UNITS: dict[str, float] = {
    "m": 1.0,
    "cm": 1e-2,
    "mm": 1e-3,
    "km": 1e3,
    "in": 0.0254,
    "ft": 0.3048,
}


def length_scale(unit: str | None, default: str = "m") -> float:
    """Metres per ``unit``.

    >>> length_scale("mm")
    0.001
    """
    name = default if unit is None else unit.strip().lower()
    try:
        return LENGTH_UNITS[name]
    except KeyError:
        known = ", ".join(LENGTH_UNITS)
        raise PlumbobError(f"unknown length unit {unit!r}; use one of {known}") from None
