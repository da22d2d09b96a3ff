"""Reports for the CLI: JSON (SI units, snake_case keys) and plain-text tables."""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from .massprops import MassProperties

__all__ = [
    "jsonable",
    "dump_json",
    "table",
    "format_number",
    "mass_properties_dict",
]


def jsonable(value: Any) -> Any:
    """Plain Python values for ``json``: arrays become lists, numpy scalars floats,
    non-finite floats ``None`` (JSON has no NaN)."""
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        value = float(value) + 0.0  # no negative zeros
        return value if math.isfinite(value) else None
    return value


def to_json(obj: Any, indent: int = 0) -> str:
    """JSON text, indented, with short lists of numbers kept on one line."""
    pad = "  " * (indent + 1)
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = [f"{pad}{json.dumps(k)}: {to_json(v, indent + 1)}" for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if isinstance(obj, list):
        flat = all(not isinstance(v, (dict, list)) for v in obj)
        if flat and len(obj) <= 16:
            return (
                "["
                + ", ".join(json.dumps(v, allow_nan=False, ensure_ascii=False) for v in obj)
                + "]"
            )
        small = all(
            isinstance(v, list) and all(not isinstance(u, (dict, list)) for u in v) for v in obj
        )
        if small and obj and len(obj) <= 4:
            return "[" + ", ".join(to_json(v) for v in obj) + "]"
        if not obj:
            return "[]"
        return (
            "[\n"
            + ",\n".join(pad + to_json(v, indent + 1) for v in obj)
            + "\n"
            + "  " * indent
            + "]"
        )
    return json.dumps(obj, allow_nan=False, ensure_ascii=False)


def dump_json(obj: dict, stream=None) -> None:
    """Write exactly one JSON object and a newline."""
    stream = stream or sys.stdout
    stream.write(to_json(jsonable(obj)) + "\n")


def format_number(value: float, digits: int = 6) -> str:
    """A number with ``digits`` significant figures."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—" if value is None else str(value)
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def format_vector(vector: Iterable[float], digits: int = 6, scale: float | None = None) -> str:
    """Numbers in parentheses; with ``scale``, round-off below 1e-12 of it shown as 0."""
    values = [float(v) for v in vector]
    if scale is not None:
        values = [0.0 if abs(v) < 1e-12 * scale else v for v in values]
    return "(" + ", ".join(format_number(v, digits) for v in values) + ")"


def table(rows: Sequence[tuple[str, str]], title: str | None = None) -> str:
    """Two aligned columns: label and value."""
    width = max((len(label) for label, _ in rows), default=0)
    lines = [title, "-" * len(title)] if title else []
    lines += [f"{label:<{width}}  {value}" for label, value in rows]
    return "\n".join(lines)


def mass_properties_dict(props: MassProperties, kind: str) -> dict[str, Any]:
    """The JSON object of ``plumbob mass`` for one body (SI units)."""
    out: dict[str, Any] = {"kind": kind, "mass": props.mass}
    if kind == "lamina" or (props.dim == 2 and props.measure > 0):
        out["area"] = props.measure
    elif props.measure > 0 or kind != "particles":
        out["volume"] = props.measure
    out.update(
        center_of_mass=props.center_of_mass,
        inertia=props.inertia,
        principal_moments=props.principal_moments,
        principal_axes=props.principal_axes,
        exact=props.exact,
        relative_error=props.relative_error,
        parts=props.parts,
    )
    if props.notes:
        out["notes"] = list(props.notes)
    return out
