"""Text reports for the CLI: numbers, vectors and two-column tables.

Formatting only: the numbers come from the results, the JSON from their
``as_dict()`` (written by :func:`plumbob.commands._common.dump_json`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

from .errors import printable
from .tolerances import TEXT_ROUND_OFF

__all__ = ["format_number", "format_vector", "table"]


def format_number(value: float | None, digits: int = 6) -> str:
    """A number with ``digits`` significant figures; "—" for none.

    >>> format_number(2 / 3), format_number(0.0), format_number(None), format_number(float("inf"))
    ('0.666667', '0', '—', 'inf')
    """
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—" if value is None else str(value)
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def format_vector(vector: Iterable[float], digits: int = 6, scale: float | None = None) -> str:
    """Numbers in parentheses; with ``scale``, round-off below ``TEXT_ROUND_OFF`` of it shown as 0.

    >>> format_vector([1.0, 1e-17, 2.5], scale=1.0)
    '(1, 0, 2.5)'
    """
    values = [float(v) for v in vector]
    if scale is not None:
        values = [0.0 if abs(v) < TEXT_ROUND_OFF * scale else v for v in values]
    return "(" + ", ".join(format_number(v, digits) for v in values) + ")"


def table(rows: Sequence[tuple[str, str]], title: str | None = None) -> str:
    """Two aligned columns: label and value, under an underlined title. Names from
    files (a title, a part's name) may hold control characters: every cell is shown
    through :func:`~plumbob.errors.printable`, so none reaches the terminal raw.

    >>> print(table([("mass", "2 kg"), ("volume", "1 m³")], "block"))
    block
    -----
    mass    2 kg
    volume  1 m³
    """
    rows = [(printable(label), printable(value)) for label, value in rows]
    width = max((len(label) for label, _ in rows), default=0)
    title = printable(title) if title else title
    lines = [title, "-" * len(title)] if title else []
    lines += [f"{label:<{width}}  {value}" for label, value in rows]
    return "\n".join(lines)
