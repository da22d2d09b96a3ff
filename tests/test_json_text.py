"""The command's JSON writer: the same text, byte for byte, as the writer before it.

``commands.output._json_text`` encodes a list of rows of numbers (a face's corners, a
matrix) in one call and splits it into lines, and ``results.jsonable`` turns numeric
arrays into lists whole; the oracle below is the writer as it was, one ``json.dumps``
per value and ``jsonable`` value by value.
"""

from __future__ import annotations

import json
import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from plumbob.commands.output import _json_text, dump_json
from plumbob.results import jsonable


def _old_jsonable(value):
    if isinstance(value, dict):
        return {str(k): _old_jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_old_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _old_jsonable(value.tolist())
    if isinstance(value, (np.bool_, bool)):
        return bool(value)
    if isinstance(value, (np.integer, int)):
        return int(value)
    if isinstance(value, (np.floating, float)):
        value = float(value) + 0.0
        return value if math.isfinite(value) else None
    return value


def _old_json_text(obj, indent=0):
    pad = "  " * (indent + 1)
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = [f"{pad}{json.dumps(k)}: {_old_json_text(v, indent + 1)}" for k, v in obj.items()]
        return "{\n" + ",\n".join(items) + "\n" + "  " * indent + "}"
    if isinstance(obj, list):
        flat = all(not isinstance(v, (dict, list)) for v in obj)
        if flat and len(obj) <= 16:
            return "[" + ", ".join(json.dumps(v, allow_nan=False, ensure_ascii=False)
                                   for v in obj) + "]"
        small = all(isinstance(v, list) and all(not isinstance(u, (dict, list)) for u in v)
                    for v in obj)
        if small and obj and len(obj) <= 4:
            return "[" + ", ".join(_old_json_text(v) for v in obj) + "]"
        return ("[\n" + ",\n".join(pad + _old_json_text(v, indent + 1) for v in obj) + "\n"
                + "  " * indent + "]")
    return json.dumps(obj, allow_nan=False, ensure_ascii=False)


_FLOATS = st.floats(allow_nan=True, allow_infinity=True) | st.sampled_from([0.0, -0.0, 1e-300])
_SCALARS = (_FLOATS | st.integers(-10**20, 10**20) | st.booleans() | st.none()
            | st.text(alphabet="a],[ \"\\é\n", max_size=6))
_ROWS = st.lists(st.lists(_FLOATS | st.integers(-5, 5) | st.none(), max_size=18), max_size=24)
_ARRAYS = hnp.arrays(st.sampled_from([np.float64, np.float32, np.int64, np.bool_]),
                     hnp.array_shapes(min_dims=0, max_dims=3, max_side=7))
_VALUES = st.recursive(
    _SCALARS | _ROWS | _ARRAYS,
    lambda inner: st.lists(inner, max_size=20) | st.tuples(inner, inner)
    | st.dictionaries(st.text(alphabet="ab_é\"", max_size=4), inner, max_size=5),
    max_leaves=60)


@given(_VALUES)
def test_the_json_text_is_the_old_writers(value):
    plain = jsonable(value)
    old = _old_jsonable(value)
    assert json.dumps(plain) == json.dumps(old)  # the same values, floats to the bit
    assert _json_text(plain) == _old_json_text(old)


def test_a_face_of_many_corners_is_one_row_a_line():
    corners = np.random.default_rng(1).normal(size=(500, 3)) * 1e-5
    corners[3, 1] = -0.0
    out = {"poses": [{"face": corners, "transform": np.eye(4), "axis": None}], "n": np.int64(3)}
    text = _json_text(jsonable(out))
    assert text == _old_json_text(_old_jsonable(out))
    assert text.count("\n") == 500 + 10 and "-0.0" not in text
    assert json.loads(text)["poses"][0]["face"] == (corners + 0.0).tolist()


def test_dump_json_writes_one_object_and_a_newline(capsys):
    dump_json({"a": np.array([np.nan, 1.5]), "b": [[1, 2]] * 20})
    text = capsys.readouterr().out
    assert text.endswith("}\n") and json.loads(text) == {"a": [None, 1.5], "b": [[1, 2]] * 20}


@settings(max_examples=60, deadline=None)
@given(st.lists(st.lists(st.sampled_from([0.5, -0.0, 3, None, True]), max_size=18)
                | st.tuples(st.just(1.0)) | st.just("a") | st.just(2.0)
                | st.just([[1.0]]), min_size=1, max_size=24))
def test_rows_of_numbers_is_the_per_row_test(values):
    """The rows-of-numbers test, made in C-level passes, is the test row by row."""
    from plumbob.commands.output import _NUMBERS, _rows_of_numbers

    assert _rows_of_numbers(values) == all(
        type(v) is list and len(v) <= 16 and _NUMBERS.issuperset(map(type, v)) for v in values)
