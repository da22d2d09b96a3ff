"""What a command prints as JSON: the header of a report on a file, the check that every
number is finite, and the one JSON writer (short lists on one line).
"""

from __future__ import annotations

import sys
from itertools import chain
from typing import Any

from ..errors import ArgumentError
from ..reading import Reading
from ..results import jsonable

__all__ = [
    "header",
    "require_finite",
    "dump_json",
    "print_json",
]


def header(reading: Reading, kind: str) -> dict[str, Any]:
    """The keys every report on a body read from a file starts with: path, name, kind."""
    out: dict[str, Any] = {}
    if reading.path:
        out["path"] = reading.path
    name = getattr(reading.body, "name", None)
    if name:
        out["name"] = name
    out["kind"] = kind
    return out


def require_finite(out: Any, where: str = "") -> Any:
    """``out`` (a report's ``as_dict()``) when every number in it is finite; else an
    :class:`ArgumentError` naming the key: finite inputs whose answer overflows double
    precision (``--g 1e308``, ``--density 1e308``) are bad input, never a ``nan``,
    ``inf`` or JSON ``null`` with exit status 0."""
    items = out.items() if isinstance(out, dict) else enumerate(out) \
        if isinstance(out, (list, tuple)) else None
    if items is not None:
        for key, value in items:
            require_finite(value, f"{where}.{key}" if where else str(key))
        return out
    import numpy as np

    if isinstance(out, (float, np.floating, np.ndarray)) and not np.all(np.isfinite(out)):
        raise ArgumentError(f"the result overflows double precision ({where} is not finite): "
                            "an input (--g, --density, a coordinate) is too large")
    return out


#: the one encoder of values (strict JSON: no NaN; text as it is, not escaped to ASCII)
_ENCODER = None

#: the types of the numbers (and nulls) a row of numbers holds, after :func:`jsonable`
_NUMBERS = frozenset((float, int, bool, type(None)))


def _encode(obj: Any) -> str:
    """``json.dumps(obj, allow_nan=False, ensure_ascii=False)``, its encoder made once."""
    global _ENCODER
    if _ENCODER is None:
        import json  # here: only --json output needs it

        _ENCODER = json.JSONEncoder(allow_nan=False, ensure_ascii=False)
    return _ENCODER.encode(obj)


def _flat(values: list) -> bool:
    """Whether a list holds no dictionary or list."""
    return not any(isinstance(v, (dict, list)) for v in values)


def _rows_of_numbers(values: list) -> bool:
    """Whether a non-empty list holds only lists of up to 16 numbers (and nulls): its
    rows' types, lengths and entries' types each looked at in one C-level pass (a
    generator over a cap's 4,400 corners cost 2 ms)."""
    return (set(map(type, values)) == {list} and max(map(len, values), default=0) <= 16
            and _NUMBERS.issuperset(map(type, chain.from_iterable(values))))


def _json_text(obj: Any, indent: int = 0) -> str:
    """JSON text, indented, with short lists of numbers kept on one line.

    A list of rows of numbers (a face's corners, a matrix) is encoded in one call and
    split into its lines: each value would otherwise cost a call of its own, and a
    pose's face on a finely tessellated cap has thousands of corners (the box with a
    tilted cylinder's 360 kB of JSON: 42 -> 10 ms)."""
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        import json

        pad = "  " * (indent + 1)
        items = [f"{pad}{json.dumps(k)}: {_json_text(v, indent + 1)}" for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if isinstance(obj, list):
        if len(obj) <= 16 and _flat(obj):
            return _encode(obj)
        if len(obj) <= 4 and all(isinstance(v, list) and _flat(v) for v in obj):
            return "[" + ", ".join(_json_text(v) for v in obj) + "]"
        pad = "  " * (indent + 1)
        end = "\n" + "  " * indent + "]"
        if _rows_of_numbers(obj):  # "], [" is only ever between two rows
            return "[\n" + pad + _encode(obj)[1:-1].replace("], [", "],\n" + pad + "[") + end
        return "[\n" + ",\n".join(pad + _json_text(v, indent + 1) for v in obj) + end
    return _encode(obj)


def dump_json(obj: dict, stream=None) -> None:
    """Write exactly one JSON object (an ``as_dict()``, arrays and all) and a newline."""
    stream = stream or sys.stdout
    stream.write(_json_text(jsonable(obj)) + "\n")


def print_json(out: dict, reading: Reading, notes: list[str]) -> None:
    """A body's report as JSON: ``notes`` and the reader's ``notices`` close it."""
    if notes:
        out["notes"] = notes
    if reading.notices:
        out["notices"] = list(reading.notices)
    dump_json(out)

