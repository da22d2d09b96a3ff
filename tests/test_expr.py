import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from plumbob.errors import ExpressionError
from plumbob.expr import evaluate, parse


@pytest.mark.parametrize(
    "text, value",
    [
        ("sqrt(3)/2", np.sqrt(3) / 2),
        ("2^3^2", 512.0),
        ("-2^2", -4.0),
        ("(1+2)*3", 9.0),
        ("2**3", 8.0),
        ("pi", np.pi),
        ("cos(pi)", -1.0),
        ("atan2(1, 1)", np.pi / 4),
        ("3 × 4 ÷ 2", 6.0),
        ("1e-3 * 5", 5e-3),
        (".5 + 1.", 1.5),
        ("max(2, 3) - min(2, 3)", 1.0),
        ("2 − 1", 1.0),
        ("degrees(pi)", 180.0),
    ],
)
def test_values(text, value):
    assert evaluate(text) == pytest.approx(value, rel=1e-15)


def test_names_and_vectorised_fields():
    assert evaluate("a^2 + b", {"a": 3, "b": 1}) == 10.0
    field = parse("2400 * (1 + 0.1*z)")
    z = np.linspace(0, 1, 5)
    np.testing.assert_allclose(field.evaluate({"z": z}), 2400 * (1 + 0.1 * z))
    assert field.names == {"z"}


@pytest.mark.parametrize(
    "text, degree",
    [
        ("1 + x", 1),
        ("x*y*z", 3),
        ("(x+y)^3", 3),
        ("x^2/4", 2),
        ("exp(x)", None),
        ("1/x", None),
        ("x^0.5", None),
        ("sqrt(2)*x", 1),
        ("step(x - 0.5)", None),
        ("7", 0),
    ],
)
def test_polynomial_degree(text, degree):
    assert parse(text).degree() == degree


@pytest.mark.parametrize(
    "text, message",
    [
        ("__import__('os')", "unexpected character"),
        ("2 +", "ends too soon"),
        ("open(1)", "unknown function 'open'"),
        ("a.b", "unexpected character"),
        ("x[0]", "unexpected character"),
        ("lambda: 1", "unexpected character"),
        ("1 2", "unexpected '2'"),
        ("sqrt(1, 2)", "takes 1 argument"),
        ("(" * 200 + "1" + ")" * 200, "nests too deeply"),
        ("1" * 30000, "limited to"),
        ("", "empty"),
        ("q + 1", "unknown name 'q'"),
        ("1/0", "not a finite number"),
    ],
)
def test_unsafe_or_malformed_expressions_are_errors(text, message):
    with pytest.raises(ExpressionError, match=message):
        evaluate(text)


def test_booleans_are_not_numbers():
    with pytest.raises(ExpressionError):
        evaluate(True)


@given(st.floats(-1e6, 1e6), st.floats(-1e6, 1e6))
def test_arithmetic_matches_python(a, b):
    assert evaluate("a + b * 2 - a / 4", {"a": a, "b": b}) == pytest.approx(a + b * 2 - a / 4)


@given(st.text(max_size=40))
def test_arbitrary_text_never_escapes_as_another_exception(text):
    try:
        evaluate(text)
    except ExpressionError:
        pass
