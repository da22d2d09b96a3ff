"""Length units: the one table of metres per unit, and the default g.

Every length unit plumbob knows is in :data:`METRES_PER_UNIT`, keyed by its
symbol. A user may name the common ones (:data:`LENGTH_UNITS`: ``--units``, a
spec's ``units``); files may also declare the others (DXF's ``$INSUNITS``, 3MF's
``unit`` attribute, CSS lengths in SVG), often spelled out (``millimeter``,
``feet``): :data:`UNIT_SPELLINGS` maps those spellings to symbols.
"""

from __future__ import annotations

import re

import numpy as np

from .errors import ArgumentError, PlumbobError
from .gravity import SEED_GRAVITY, STANDARD_GRAVITY

__all__ = [
    "MAX_LENGTH",
    "too_long",
    "METRES_PER_UNIT",
    "LENGTH_UNITS",
    "UNIT_SPELLINGS",
    "UNITS_ASSUMED",
    "unit_assumed",
    "SEED_GRAVITY",
    "STANDARD_GRAVITY",
    "length_scale",
    "unit_symbol",
    "reading_unit",
    "file_unit_scale",
    "units_scale",
    "split_length",
    "parse_length",
]

#: The largest length or coordinate a body may have, m. Mass properties multiply up to five
#: lengths and a density (an inertia is ρ L⁵), which overflows double precision (1.8e308)
#: from L ≈ 1e61 m; 1e50 m (some 10²³ times the observable universe) leaves room for the
#: density and for distances between parts, and no real body comes near it.
MAX_LENGTH = 1e50


def too_long(what: str, value: float) -> str:
    """The message for a length or coordinate ``value`` (m) beyond :data:`MAX_LENGTH`.

    >>> too_long("radius", 1e200)
    "radius 1e+200 m is beyond plumbob's largest length, 1e+50 m: its mass properties would \
overflow double precision (give lengths in other units)"
    """
    return (f"{what} {value:g} m is beyond plumbob's largest length, {MAX_LENGTH:g} m: its mass "
            "properties would overflow double precision (give lengths in other units)")

#: metres per unit, for every length unit plumbob knows (px, pt, pc and q are CSS's)
METRES_PER_UNIT: dict[str, float] = {
    "m": 1.0,
    "cm": 1e-2,
    "mm": 1e-3,
    "km": 1e3,
    "in": 0.0254,
    "ft": 0.3048,
    "um": 1e-6,
    "dm": 0.1,
    "yd": 0.9144,
    "mi": 1609.344,
    "px": 0.0254 / 96,
    "pt": 0.0254 / 72,
    "pc": 0.0254 / 6,
    "q": 2.5e-4,
}

#: metres per unit, for the units a user may name (``--units``, a spec's ``units``)
LENGTH_UNITS: dict[str, float] = {
    unit: METRES_PER_UNIT[unit] for unit in ("m", "cm", "mm", "km", "in", "ft")
}

#: unit names files spell out → the symbol in :data:`METRES_PER_UNIT`
UNIT_SPELLINGS: dict[str, str] = {
    "micron": "um", "micrometer": "um", "micrometre": "um", "µm": "um",
    "millimeter": "mm", "millimetre": "mm", "millimeters": "mm", "millimetres": "mm",
    "centimeter": "cm", "centimetre": "cm", "centimeters": "cm", "centimetres": "cm",
    "decimeter": "dm",
    "meter": "m", "metre": "m", "meters": "m", "metres": "m",
    "kilometer": "km", "kilometre": "km", "kilometers": "km", "kilometres": "km",
    "inch": "in", "inches": "in", '"': "in", "″": "in",
    "foot": "ft", "feet": "ft", "'": "ft", "′": "ft",
    "yard": "yd",
    "mile": "mi",
}

#: the notice when neither the user nor the file says what the lengths are in
UNITS_ASSUMED = "units: none in file; metres assumed (use --units)"


def unit_symbol(unit: str) -> str:
    """The symbol of a length unit a person may type: any case, spelled out or as a
    symbol (``MM``, ``millimetre``, ``Inch``, ``"``), one of :data:`LENGTH_UNITS`.

    >>> unit_symbol("MM"), unit_symbol(" Millimetre "), unit_symbol('"'), unit_symbol("feet")
    ('mm', 'mm', 'in', 'ft')
    >>> unit_symbol("furlong")
    Traceback (most recent call last):
    ...
    plumbob.errors.PlumbobError: unknown length unit 'furlong'; use one of m, cm, mm, km, in, \
ft (or spelled out: millimetre, inch, …)
    """
    if not isinstance(unit, str):
        raise PlumbobError(f"a length unit must be text such as 'mm', not {unit!r}")
    key = unit.strip().lower()
    key = UNIT_SPELLINGS.get(key, key)
    if key not in LENGTH_UNITS:
        known = ", ".join(LENGTH_UNITS)
        raise PlumbobError(f"unknown length unit {unit!r}; use one of {known} "
                           "(or spelled out: millimetre, inch, …)")
    return key


def length_scale(unit: str | None, default: str = "m") -> float:
    """Metres per ``unit``, one of :data:`LENGTH_UNITS` in any spelling
    :func:`unit_symbol` reads (None: ``default``).

    >>> length_scale("mm")
    0.001
    >>> length_scale("Inch")
    0.0254
    >>> length_scale(None)
    1.0
    """
    return LENGTH_UNITS[unit_symbol(default if unit is None else unit)]


def reading_unit(units: str | None, file_units: str | None = None) -> str | None:
    """The length unit a file's coordinates were read in, as a symbol: the one the user
    gave, else the one the file declares, else None (metres assumed or no unit known).
    Reports show a part in its own unit (:class:`plumbob.reading.Reading`).

    >>> reading_unit("Millimetre"), reading_unit(None, "inch"), reading_unit(None)
    ('mm', 'in', None)
    >>> reading_unit(None, "furlong") is None
    True
    """
    if units is not None:
        return unit_symbol(units)
    if file_units is None:
        return None
    key = file_units.strip().lower()
    key = UNIT_SPELLINGS.get(key, key)
    return key if key in METRES_PER_UNIT else None


def file_unit_scale(name: str | None) -> float | None:
    """Metres per the unit a file declares, spelled out or as a symbol; None when unknown.

    >>> file_unit_scale("Millimeter")
    0.001
    >>> file_unit_scale("ft")
    0.3048
    >>> file_unit_scale("furlong") is None
    True
    """
    if name is None:
        return None
    key = name.strip().lower()
    return METRES_PER_UNIT.get(UNIT_SPELLINGS.get(key, key))


def units_scale(units: str | None, file_units: str | None = None,
                file_scale: float | None = None, override: bool = False,
                path: str | None = None) -> tuple[float, tuple[str, ...]]:
    """Metres per file unit, and the notice that says where it came from.

    ``units``: what the user passed (``--units``), or None.
    ``file_units``/``file_scale``: the unit the file declares (its name and
    metres per unit), or None when the format carries none (STL, OBJ, …).
    ``override``: a ``units`` that contradicts the file's unit is used (with a
    notice) rather than refused (``--units-override``); ``path`` names the file in
    the refusal.

    >>> units_scale("in")
    (0.0254, ())
    >>> units_scale(None, "millimeter", 1e-3)
    (0.001, ('units: millimeter (from the file)',))
    >>> units_scale(None)[1] == (UNITS_ASSUMED,)
    True
    >>> units_scale("in", "millimeter", 1e-3)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: the file says its unit is millimeter, not in (--units): ...
    >>> units_scale("in", "millimeter", 1e-3, override=True)[1]
    ('units: the file says millimeter; in used as --units-override asks',)
    """
    if units is not None:
        scale = length_scale(units)
        if file_units is not None and file_scale is not None and not np.isclose(scale, file_scale):
            if not override:
                raise ArgumentError(
                    f"the file says its unit is {file_units}, not {units} (--units): leave "
                    f"--units out, or pass --units-override to read it in {units} anyway",
                    path=path)
            return scale, (f"units: the file says {file_units}; {units} used as --units-override "
                           "asks",)
        return scale, ()
    if not unit_assumed(units, file_units, file_scale):
        return file_scale, (f"units: {file_units} (from the file)",)
    return 1.0, (UNITS_ASSUMED,)


def unit_assumed(units: str | None, file_units: str | None = None,
                 file_scale: float | None = None) -> bool:
    """Whether :func:`units_scale` assumes metres for these arguments: neither the user
    nor the file gave a unit (a reader records it in ``Reading.units_assumed``).

    >>> unit_assumed(None), unit_assumed("mm"), unit_assumed(None, "millimeter", 1e-3)
    (True, False, False)
    """
    return units is None and (file_units is None or file_scale is None)


#: a number with an optional length unit: ``3mm``, ``0.5 in``, ``-2.5e-3``, ``30 cm``
_QUANTITY = re.compile(
    r"\s*(?P<number>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(?P<unit>[A-Za-z]*)\s*")


def split_length(text: str) -> tuple[float, str] | None:
    """The number and the unit (``""`` when none is written) of a length such as
    ``"3mm"`` or ``"0.5 in"``, as written; ``None`` for text of another form. The one
    grammar of a length in text, for the command line, specs and printed parts.

    >>> split_length("3mm"), split_length(" -2.5e-3 in "), split_length("0.2"), split_length("2*pi")
    ((3.0, 'mm'), (-0.0025, 'in'), (0.2, ''), None)
    """
    match = _QUANTITY.fullmatch(str(text))
    return None if match is None else (float(match["number"]), match["unit"])


def parse_length(text: str, scale: float = 1.0, *, what: str = "a length",
                 error: type[PlumbobError] = PlumbobError) -> float:
    """A length such as ``"1.2mm"``, ``"0.05 in"`` or ``"0.0012"`` in metres; a bare
    number is in units of ``scale`` m (a file's or a spec's unit). Raises ``error``
    naming what is wrong.

    >>> parse_length("1.2mm"), parse_length("2", scale=1e-3), parse_length("0.5 in")
    (0.0012, 0.002, 0.0127)
    >>> parse_length("2 furlongs")
    Traceback (most recent call last):
    ...
    plumbob.errors.PlumbobError: unknown length unit 'furlongs' in '2 furlongs'; use one of m, \
cm, mm, km, in, ft
    >>> parse_length("three", what="--margin")
    Traceback (most recent call last):
    ...
    plumbob.errors.PlumbobError: --margin must be a number with an optional unit (m, cm, mm, \
km, in, ft; e.g. 0.003 or 3mm), not 'three'
    """
    parts = split_length(text)
    if parts is None:
        raise error(f"{what} must be a number with an optional unit "
                    f"({', '.join(LENGTH_UNITS)}; e.g. 0.003 or 3mm), not {text!r}")
    value, unit = parts
    if unit and unit not in LENGTH_UNITS:
        raise error(f"unknown length unit {unit!r} in {text!r}; use one of "
                    f"{', '.join(LENGTH_UNITS)}")
    return value * (LENGTH_UNITS[unit] if unit else scale)
