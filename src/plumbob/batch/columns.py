"""The columns of the results table and of the pose table, and their flat forms.

A row is a JSON-like dict whose keys and values are those of the single-file
command's ``--json`` output (vectors are lists, the inertia a 3×3 list). JSON Lines
keeps rows as they are; CSV and Parquet need one scalar per cell, so each vector or
matrix column is spread over named cells (``center_of_mass_x``, ``inertia_xy``,
``principal_axes_1_x``) and lists of notes become JSON text. The schema is fixed by
the options alone — never by which files happen to come first — so an incremental CSV
can write its header before the first row, and every run with the same options gives
the same columns.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

from ..bodies import measures as _mass
from ..results import pick
from ..stability.checks import SlopeCheck
from ..stability.loaded import LoadVerdict
from ..stability.poses.result import Pose, Poses
from ..stability.verdict import Verdict
from .options import Options

__all__ = ["Field", "result_fields", "pose_fields", "flatten", "unflatten", "flat_names",
           "parse_cell"]

XYZ = ("x", "y", "z")


@dataclass(frozen=True)
class Field:
    """One key of a row: its value type (``str``, ``float``, ``int``, ``bool`` or
    ``strings``, a list of text) and, for a vector or matrix, the labels of its cells."""

    key: str
    type: str
    labels: tuple = ()  # (labels,) for a vector, (row labels, column labels) for a matrix

    def names(self) -> list[str]:
        """The flat column names of this key."""
        if not self.labels:
            return [self.key]
        if len(self.labels) == 1:
            return [f"{self.key}_{a}" for a in self.labels[0]]
        rows, cols = self.labels
        sep = "" if rows == XYZ else "_"
        return [f"{self.key}_{r}{sep}{c}" for r in rows for c in cols]


def _vec(key: str, labels=XYZ) -> Field:
    return Field(key, "float", (labels,))


_ROWS = ("1", "2", "3")
#: a declared key's table form (``results.Key.type``) as a field's type and labels
_FORMS = {"xyz": ("float", (XYZ,)), "123": ("float", (_ROWS,)),
          "xyz×xyz": ("float", (XYZ, XYZ)), "123×xyz": ("float", (_ROWS, XYZ))}


def key_fields(keys) -> list[Field]:
    """The fields of declared keys (:class:`plumbob.results.Key`), by their ``type``."""
    return [Field(k.name, *_FORMS.get(k.type, (k.type, ()))) for k in keys]


# The columns are the single-file commands' JSON keys, as the results declare them
# (``KEYS``): a row is built from them (:mod:`.rows`), and the batch table's own keys
# (the file, its status, the unit it was read in, counts) are the only others.
MASS_KEYS = pick(_mass.MASS_KEYS, ("mass", "volume", "area", "center_of_mass", "inertia",
                                   "principal_moments", "principal_axes", "exact",
                                   "relative_error", "parts"))
SIZE_KEYS = pick(_mass.MASS_KEYS, ("radii_of_gyration",))
CHECK_KEYS = pick(Verdict.KEYS, ("verdict", "stands", "margin", "critical_tilt_deg",
                                 "critical_direction", "energy_to_topple", "com_height", "down",
                                 "support_kind"))
SLOPE_KEYS = pick(SlopeCheck.KEYS, ("verdict", "topples", "tipping_angle_deg"), "slope_",
                  via="slope")
REQUIRE_KEYS = pick(Verdict.KEYS, ("required_tilt_deg", "passes"))
LOAD_KEYS = (pick(LoadVerdict.KEYS, ("verdict",), "load_", via="loaded")
             + pick(LoadVerdict.KEYS, ("overturning_safety_factor", "resisting_moment",
                                       "overturning_moment"), via="loaded"))
POSE_KEYS = pick(Pose.KEYS, ("probability", "down", "com_height", "critical_tilt_deg",
                             "energy_barrier"), "pose_")
POSE_TABLE_KEYS = pick(Pose.KEYS, ("down", "com_height", "probability", "critical_tilt_deg",
                                   "energy_barrier", "neutral"))

_HEAD = [Field("path", "str"), Field("name", "str"), Field("status", "str"),
         Field("error", "str"), Field("reason", "str")]
_MASS = key_fields(pick(_mass.MASS_KEYS, ("kind",))) + [Field("units", "str")] + \
    key_fields(MASS_KEYS + SIZE_KEYS)
_CHECK = key_fields(CHECK_KEYS)
_SLOPE = key_fields(SLOPE_KEYS)
_REQUIRE = key_fields(REQUIRE_KEYS)
_LOADS = key_fields(LOAD_KEYS)


def _standard_fields(name: str) -> list[Field]:
    """``standard_passes`` and, per test of the standard, ``std_<test>_passes`` and
    ``std_<test>_margin`` (the least over its cases)."""
    from ..stability.standards import PRESETS

    out = [Field("standard_passes", "bool")]
    for test in PRESETS[name].tests:
        out += [Field(f"std_{test.name}_passes", "bool"),
                Field(f"std_{test.name}_margin", "float")]
    return out
_POSES = ([Field("poses", "int")] + key_fields(pick(Poses.KEYS, ("method",), "poses_"))
          + key_fields(POSE_KEYS))
_TAIL = [Field("notes", "strings"), Field("notices", "strings"), Field("file_size", "int"),
         Field("file_mtime_ns", "int"), Field("file_sha256", "str")]
_POSE_TABLE = ([Field("path", "str"), Field("name", "str"), Field("pose", "int")]
               + key_fields(POSE_TABLE_KEYS))


def result_fields(options: Options) -> list[Field]:
    """The keys of every results row for these options, in table order."""
    fields = _HEAD + _MASS
    if options.check:
        fields = fields + _CHECK
        if options.tilt is not None:
            fields = fields + _SLOPE
        if options.require_tilt is not None:
            fields = fields + _REQUIRE
        if options.load_options:
            fields = fields + _LOADS
        if options.standard is not None:
            fields = fields + _standard_fields(options.standard)
    if options.poses:
        fields = fields + _POSES
    fields = fields + [Field(f"{fmt}_inertial", "str") for fmt in options.inertial]
    return fields + _TAIL


def pose_fields() -> list[Field]:
    """The keys of the long-format pose table: one row per pose of every file."""
    return list(_POSE_TABLE)


def flat_names(fields: list[Field]) -> list[str]:
    """The column names of the flat (CSV, Parquet) table."""
    return [name for f in fields for name in f.names()]


def flatten(row: dict[str, Any], fields: list[Field]) -> dict[str, Any]:
    """One scalar per cell (missing values None)."""
    flat: dict[str, Any] = {}
    for f in fields:
        value = row.get(f.key)
        names = f.names()
        if f.type == "strings":
            flat[f.key] = json.dumps(value, ensure_ascii=False) if value else None
        elif not f.labels:
            flat[f.key] = value
        else:
            cells = [] if value is None else [c for r in value for c in r] \
                if len(f.labels) == 2 else list(value)
            flat.update(zip(names, cells + [None] * (len(names) - len(cells))))
    return flat


def unflatten(flat: dict[str, Any], fields: list[Field]) -> dict[str, Any]:
    """The row again from its flat cells (a lamina's 2-vectors lose their empty z)."""
    row: dict[str, Any] = {}
    for f in fields:
        if f.type == "strings":  # JSON text in a CSV, a list already in Parquet
            text = flat.get(f.key)
            row[f.key] = (json.loads(text) if isinstance(text, str) else list(text)) \
                if text else None
        elif not f.labels:
            row[f.key] = flat.get(f.key)
        else:
            cells = [flat.get(name) for name in f.names()]
            if all(c is None for c in cells):
                row[f.key] = None
            elif len(f.labels) == 2:
                n = len(f.labels[1])
                row[f.key] = [cells[i:i + n] for i in range(0, len(cells), n)]
            else:
                while cells and cells[-1] is None:
                    cells.pop()
                row[f.key] = cells
    return row


def parse_cell(text: str | None, kind: str) -> Any:
    """A CSV cell back to its value (empty: None); floats round-trip exactly."""
    if text is None or text == "":
        return None
    if kind == "float":
        return float(text)
    if kind == "int":
        return int(text)
    if kind == "bool":
        return text == "True"
    return text


def cell_types(fields: list[Field]) -> dict[str, str]:
    """Flat column name → value type (``strings`` cells are JSON text)."""
    return {name: ("str" if f.type == "strings" else f.type) for f in fields for name in f.names()}
