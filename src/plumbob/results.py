"""What every result type shares: a plain-dictionary view and a short repr.

A result (mass properties, a stability verdict, a lift energy, a simulation, a
collision) answers a question in SI units. ``as_dict()`` gives that answer keyed by
the names the CLI's ``--json`` prints (numbers, strings, flags and numpy arrays:
:func:`jsonable` turns it into plain JSON values), and the repr names the headline
numbers without dumping arrays, so a result printed in a notebook is one line.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, fields, replace
from typing import Any, ClassVar

import numpy as np

__all__ = ["Result", "Source", "Key", "TYPES", "keyed", "pick", "key_table", "undeclared_keys",
           "jsonable", "short"]

#: arrays with more entries than this are summarised by their shape in a repr
_INLINE = 4


def short(value: Any) -> str:
    """A value as a repr shows it: numbers to 6 significant figures, small vectors
    inline, larger arrays and sequences of objects by their size only.

    >>> short(2.0), short(1 / 3), short(True), short("stands"), short(None)
    ('2', '0.333333', 'True', "'stands'", 'None')
    >>> short(np.array([0.0, -0.0, 2.5])), short(np.zeros((201, 3)))
    ('[0, 0, 2.5]', 'array(201×3)')
    >>> short(()), short(("A", "B")), short((np.zeros(2), np.ones(2)))
    ('()', "('A', 'B')", '(2 items)')
    >>> short(float("inf")), short(float("nan"))
    ('inf', 'nan')
    """
    if isinstance(value, Result):
        return repr(value)
    if value is None or isinstance(value, (bool, np.bool_, str)):
        return repr(value if not isinstance(value, np.bool_) else bool(value))
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    if isinstance(value, (float, np.floating)):
        return f"{float(value) + 0.0:.6g}"  # + 0.0: no negative zeros
    if isinstance(value, np.ndarray):
        if value.ndim <= 1 and value.size <= _INLINE:
            return "[" + ", ".join(short(v) for v in value.tolist()) + "]"
        return "array(" + "×".join(map(str, value.shape)) + ")"
    if isinstance(value, (tuple, list)):
        if all(isinstance(v, (str, int, float, bool)) for v in value) and len(value) <= _INLINE:
            inner = ", ".join(short(v) for v in value)
            return f"({inner},)" if isinstance(value, tuple) and len(value) == 1 else (
                f"({inner})" if isinstance(value, tuple) else f"[{inner}]")
        return f"({len(value)} items)"
    return f"<{type(value).__name__}>"


def jsonable(value: Any) -> Any:
    """Plain Python values for ``json``: arrays become lists, numpy scalars Python
    numbers, non-finite floats ``None`` (JSON has no NaN), negative zeros zeros.

    >>> jsonable({"a": np.array([1.0, -0.0]), "b": np.float64("nan"), "c": (np.int64(2),)})
    {'a': [1.0, 0.0], 'b': None, 'c': [2]}
    """
    if isinstance(value, dict):
        return {str(k): jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        if value.dtype.kind == "f" and value.dtype.itemsize <= 8:  # as floats, value by value
            plain = value.astype(np.float64) + 0.0  # no negative zeros
            if np.isfinite(plain).all():
                return plain.tolist()
        elif value.dtype.kind in "biu":  # Python's bools and ints already
            return value.tolist()
        return jsonable(value.tolist())
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        value = float(value) + 0.0  # no negative zeros
        return value if math.isfinite(value) else None
    return value


@dataclass(frozen=True)
class Key:
    """One key of a result's JSON, declared once beside the result: its ``name`` (the
    snake_case JSON key), ``unit`` (SI, ``""`` for none), ``doc``, what it means, and
    ``when`` it appears (``""``: always; otherwise the key is left out where its value is
    None or empty). ``attr`` is where the value is read: a dotted attribute path from
    the result (default: ``name``; a mapping on the way is looked up, absent: None).
    ``type`` is the value's form for a table column (:data:`TYPES`; ``""``: not a
    column). ``as_dict()`` is generated from these
    declarations (:func:`keyed`), and so are ``docs/cli.md``'s key tables
    (:func:`key_table`) and the batch table's columns."""

    name: str
    unit: str
    doc: str
    when: str = ""
    attr: str | None = None
    type: str = ""

    def value(self, result: Any) -> Any:
        """The key's value in ``result``, as read from ``attr``.

        >>> from types import SimpleNamespace as S
        >>> Key("support_kind", "", "its kind", attr="support.kind").value(S(support=S(kind="point")))
        'point'
        """
        value = result
        for name in (self.attr or self.name).split("."):
            value = value.get(name) if isinstance(value, Mapping) else getattr(value, name)
        return value


#: the forms of a value a table column can hold (:attr:`Key.type`): text, numbers,
#: counts, flags, a list of texts, vectors labelled x, y, z or 1, 2, 3, and 3×3 matrices
#: labelled by x, y, z (or 1, 2, 3 rows of x, y, z)
TYPES = ("str", "float", "int", "bool", "strings", "xyz", "123", "xyz×xyz", "123×xyz")


def _plain(value: Any) -> Any:
    """A nested result as its ``as_dict()``, a sequence as a list of such values."""
    if isinstance(value, Result):
        return value.as_dict()
    if isinstance(value, (tuple, list)):
        return [_plain(v) for v in value]
    return value


def keyed(result: Any, keys: Iterable[Key]) -> dict[str, Any]:
    """``result``'s values under the declared ``keys``, in their order: what
    :meth:`Result.as_dict` returns for a result that declares its ``KEYS``. A key with a
    ``when`` is left out where its value is None or empty; nested results become their
    ``as_dict()``, sequences lists.

    >>> from types import SimpleNamespace as S
    >>> keys = (Key("mass", "kg", "the mass"), Key("notes", "", "remarks", "when any"))
    >>> keyed(S(mass=2.0, notes=()), keys), keyed(S(mass=2.0, notes=("a",)), keys)
    ({'mass': 2.0}, {'mass': 2.0, 'notes': ['a']})
    """
    out: dict[str, Any] = {}
    for key in keys:
        value = key.value(result)
        if key.when and (value is None or (isinstance(value, (tuple, list)) and not value)):
            continue
        out[key.name] = _plain(value)
    return out


def pick(keys: Iterable[Key], names: Iterable[str], prefix: str = "",
         via: str | None = None) -> tuple[Key, ...]:
    """The keys named ``names``, in that order (a result that shows part of another's
    keys: a balance's verdicts, a batch row's columns), each renamed ``prefix + name``
    and read from its old place (``via``: the attribute that holds that result).

    >>> keys = pick([Key("a", "", "x"), Key("b", "", "y")], ["b", "a"], "s_", via="slope")
    >>> [(k.name, k.attr) for k in keys]
    [('s_b', 'slope.b'), ('s_a', 'slope.a')]
    """
    by_name = {k.name: k for k in keys}
    return tuple(replace(by_name[n], name=prefix + n,
                         attr=".".join(filter(None, (via, by_name[n].attr or n))))
                 for n in names)


def key_table(keys: Iterable[Key]) -> str:
    """The Markdown table of ``keys`` that ``docs/cli.md`` shows (and a test compares).

    >>> print(key_table([Key("mass", "kg", "the mass"), Key("notes", "", "what was assumed",
    ...                                                       "when there are any")]))
    | key | unit | meaning |
    | --- | --- | --- |
    | `mass` | kg | the mass |
    | `notes` |  | what was assumed (when there are any) |
    """
    rows = ["| key | unit | meaning |", "| --- | --- | --- |"]
    for k in keys:
        doc = f"{k.doc} ({k.when})" if k.when else k.doc
        rows.append(f"| `{k.name}` | {k.unit} | {doc} |")
    return "\n".join(rows)


def undeclared_keys(out: Mapping[str, Any], keys: Iterable[Key]) -> list[str]:
    """The keys of ``out`` (an ``as_dict()``) that ``keys`` does not declare, and the
    always-present declared keys it lacks: empty when the JSON matches its schema.

    >>> undeclared_keys({"mass": 1.0, "extra": 2}, [Key("mass", "kg", "the mass")])
    ['extra']
    >>> undeclared_keys({}, [Key("mass", "kg", "the mass")])
    ['mass (missing)']
    """
    keys = tuple(keys)
    named = {k.name for k in keys}
    return ([name for name in out if name not in named]
            + [f"{k.name} (missing)" for k in keys if not k.when and k.name not in out])


@dataclass(frozen=True)
class Source:
    """Where a result's body came from, for its text report (``str(result)``): ``path``
    (the file, or None), ``length_unit`` (the unit it was read in: a part in mm reads in mm
    and g), ``kind`` (``lamina``, ``solid``, ``particles``, ``assembly``), ``notes`` (what
    the command line prints after the report: assumed densities, faceted curves) and
    ``size`` (m, the body's size, below which round-off shows as 0; 0: the result's own)
    and ``name`` (the body's, which heads the mass table).
    The front door's verbs given a file name (``plumbob.check("part.stl")``) attach it,
    so the result prints what ``plumbob check part.stl`` prints."""

    path: str | None = None
    length_unit: str | None = None
    kind: str | None = None
    notes: tuple[str, ...] = ()
    size: float = 0.0
    name: str | None = None


class Result:
    """Mixin for the frozen dataclasses that hold results (declare them ``repr=False``).

    ``KEYS`` declares the JSON's keys once (name, unit, meaning, when, where the value
    is read: :class:`Key`); ``as_dict()`` is generated from them, as are the docs'
    tables and the batch columns (a result without ``KEYS`` gives every field). The repr shows
    ``_repr_items()``: the fields named in ``_repr_fields`` (default: all), leaving
    out those that are ``None``.
    """

    _repr_fields: ClassVar[tuple[str, ...] | None] = None
    #: units the repr gives its numbers besides those of ``KEYS`` (name → unit)
    _repr_units: ClassVar[dict[str, str]] = {}
    #: the keys of ``as_dict()``, declared once (empty: not declared yet)
    KEYS: ClassVar[tuple[Key, ...]] = ()

    def as_dict(self) -> dict[str, Any]:
        """The result's values keyed by the CLI's JSON keys, SI units: generated from
        ``KEYS`` (:func:`keyed`) where the result declares them, else every field."""
        if self.KEYS:
            return keyed(self, self.KEYS)
        return {f.name: getattr(self, f.name) for f in fields(self)}  # type: ignore[arg-type]

    def described(self, source: Source):
        """The same result, with where its body came from (:class:`Source`) for its
        ``str()``: the command line's report on that file."""
        from dataclasses import replace

        return replace(self, source=source)  # type: ignore[type-var]

    def _repr_items(self) -> list[tuple[str, Any]]:
        names = self._repr_fields or tuple(f.name for f in fields(self))  # type: ignore[arg-type]
        return [(n, getattr(self, n)) for n in names]

    def __str__(self) -> str:
        """The command line's report of the result where it has one
        (:func:`plumbob.report.text.text_of`: the result's ``text()``, or the mass table),
        else the repr."""
        from .report.text import text_of

        return text_of(self)

    def __repr__(self) -> str:
        """One line: the headline numbers with their units (``mass=0.5 kg``)."""
        units = {**{k.name: k.unit for k in self.KEYS}, **self._repr_units}

        def item(name: str, value: Any) -> str:
            unit = units.get(name, "")
            numeric = isinstance(value, (int, float, np.number, np.ndarray)) and not \
                isinstance(value, (bool, np.bool_))
            shown = unit if numeric and unit and "," not in unit else ""
            return f"{name}={short(value)}" + (f" {shown}" if shown not in ("", "°") else shown)

        inner = ", ".join(item(n, v) for n, v in self._repr_items() if v is not None)
        return f"{type(self).__name__}({inner})"

    def _repr_html_(self) -> str:
        """A notebook's view: the JSON keys (SI units) and values as a table, nested
        values shown compactly.

        >>> from plumbob.massprops import point_mass
        >>> "<th>mass</th><td>2</td>" in point_mass(2.0, [1.0, 0.0, 0.0])._repr_html_()
        True
        """
        from html import escape

        rows = "".join(
            f"<tr><th>{escape(str(key))}</th>"
            f"<td>{escape(value if isinstance(value, str) else short(value))}</td></tr>"
            for key, value in self.as_dict().items() if value is not None)
        return (f"<table><caption>{escape(type(self).__name__)} (SI units)</caption>"
                f"{rows}</table>")
