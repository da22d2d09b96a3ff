"""A small, whitelisted arithmetic language for shape specs — never ``eval``.

Grammar (precedence low → high)::

    expr   := term (("+" | "-") term)*
    term   := unary (("*" | "/") unary)*
    unary  := ("+" | "-") unary | power
    power  := atom (("^" | "**") unary)?          right-associative
    atom   := NUMBER | NAME | NAME "(" expr ("," expr)* ")" | "(" expr ")"

Numbers, the operators + − × ÷ ^ (also ``*``, ``/``, ``**``, ``·``), parentheses,
the constants ``pi`` and ``e``, the functions in :data:`FUNCTIONS`, and names
the caller supplies (parameters, or the coordinates x, y, z of a density
field). Nothing else parses: there are no attributes, subscripts, strings or
calls to anything outside the table. Evaluation is vectorised over numpy
arrays, and :meth:`Expression.degree` tells whether a field is a polynomial.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .errors import ExpressionError, LimitError
from .limits import MAX_EXPRESSION_NODES

__all__ = ["Expression", "parse", "evaluate", "FUNCTIONS", "CONSTANTS"]

#: characters in one expression (the node count, not this, is the real bound)
MAX_LENGTH = 20_000
MAX_DEPTH = 60

FUNCTIONS = {
    "sqrt": (np.sqrt, 1),
    "sin": (np.sin, 1),
    "cos": (np.cos, 1),
    "tan": (np.tan, 1),
    "asin": (np.arcsin, 1),
    "acos": (np.arccos, 1),
    "atan": (np.arctan, 1),
    "atan2": (np.arctan2, 2),
    "sinh": (np.sinh, 1),
    "cosh": (np.cosh, 1),
    "tanh": (np.tanh, 1),
    "exp": (np.exp, 1),
    "log": (np.log, 1),
    "log10": (np.log10, 1),
    "abs": (np.abs, 1),
    "min": (np.minimum, 2),
    "max": (np.maximum, 2),
    "hypot": (np.hypot, 2),
    "radians": (np.radians, 1),
    "degrees": (np.degrees, 1),
    "step": (lambda v: np.where(np.asarray(v) >= 0, 1.0, 0.0), 1),
}
CONSTANTS = {"pi": math.pi, "e": math.e}

_TOKEN = re.compile(
    r"\s*(?:(?P<number>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)|(?P<name>[A-Za-z_]\w*)"
    r"|(?P<op>\*\*|[-+*/^(),]))"
)
_UNICODE = str.maketrans({"×": "*", "·": "*", "÷": "/", "−": "-", "–": "-", "π": " pi "})


@dataclass(frozen=True, eq=False)
class _Node:
    op: str  # "num", "name", "neg", "+", "-", "*", "/", "^", "call"
    args: tuple = ()
    value: float | str | None = None


def _quoted(text: str) -> str:
    """``text`` quoted for a message, shortened past 60 characters (a message is one
    readable line even for a 20,000-character expression)."""
    return repr(text) if len(text) <= 60 else repr(text[:57]) + "…"


def _postorder(root: _Node) -> list[_Node]:
    """The nodes under ``root``, each after its arguments: walked with a list, not by
    recursion, so a long chain (``1+1+…+1``) never meets Python's recursion limit."""
    order: list[_Node] = []
    stack = [root]
    while stack:
        node = stack.pop()
        order.append(node)
        stack.extend(node.args)
    order.reverse()
    return order


def _fold(root: _Node, visit):
    """``visit(node, argument_results)`` over the tree, arguments first; the root's result."""
    results: dict[int, object] = {}
    for node in _postorder(root):
        results[id(node)] = visit(node, [results.pop(id(a)) for a in node.args])
    return results[id(root)]


class _Parser:
    def __init__(self, text: str) -> None:
        self.text = text
        self.tokens: list[tuple[str, str, int]] = []
        pos = 0
        stripped = text.rstrip()
        while pos < len(stripped):
            match = _TOKEN.match(stripped, pos)
            if not match or match.end() == pos:
                bad = stripped[pos:].lstrip()[:1]
                raise ExpressionError(f"in {_quoted(text)}: unexpected character {bad!r}")
            kind = match.lastgroup
            self.tokens.append((kind, match.group(kind), match.start(kind)))
            pos = match.end()
        self.index = 0
        self.depth = 0
        self.nodes = 0

    def peek(self) -> tuple[str, str, int] | None:
        return self.tokens[self.index] if self.index < len(self.tokens) else None

    def take(self, value: str | None = None) -> tuple[str, str, int]:
        token = self.peek()
        if token is None:
            raise ExpressionError(f"in {_quoted(self.text)}: the expression ends too soon")
        if value is not None and token[1] != value:
            raise ExpressionError(f"in {_quoted(self.text)}: expected {value!r} at {token[1]!r}")
        self.index += 1
        return token

    def node(self, op: str, args: tuple = (), value: float | str | None = None) -> _Node:
        """A new node, counted against :data:`~plumbob.limits.MAX_EXPRESSION_NODES`."""
        self.nodes += 1
        if self.nodes > MAX_EXPRESSION_NODES:
            raise LimitError(
                f"in {_quoted(self.text)}: the expression has over {MAX_EXPRESSION_NODES} "
                "numbers, names and operators (plumbob.limits.MAX_EXPRESSION_NODES); "
                "split it into [parameters]")
        return _Node(op, args, value)

    def nest(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise ExpressionError(f"in {_quoted(self.text)}: the expression nests too deeply")

    def parse(self) -> _Node:
        node = self.expr()
        token = self.peek()
        if token is not None:
            raise ExpressionError(f"in {_quoted(self.text)}: unexpected {token[1]!r}")
        return node

    def expr(self) -> _Node:
        node = self.term()
        while (t := self.peek()) and t[1] in "+-" and t[0] == "op":
            self.take()
            node = self.node(t[1], (node, self.term()))
        return node

    def term(self) -> _Node:
        node = self.unary()
        while (t := self.peek()) and t[1] in ("*", "/"):
            self.take()
            node = self.node(t[1], (node, self.unary()))
        return node

    def unary(self) -> _Node:
        self.nest()
        t = self.peek()
        if t and t[1] in ("+", "-"):
            self.take()
            operand = self.unary()
            node = self.node("neg", (operand,)) if t[1] == "-" else operand
        else:
            node = self.power()
        self.depth -= 1
        return node

    def power(self) -> _Node:
        base = self.atom()
        t = self.peek()
        if t and t[1] in ("^", "**"):
            self.take()
            return self.node("^", (base, self.unary()))
        return base

    def atom(self) -> _Node:
        kind, value, _ = self.take()
        if kind == "number":
            return self.node("num", value=float(value))
        if kind == "name":
            nxt = self.peek()
            if nxt and nxt[1] == "(":
                if value not in FUNCTIONS:
                    known = ", ".join(sorted(FUNCTIONS))
                    raise ExpressionError(
                        f"in {_quoted(self.text)}: unknown function {value!r}; known: {known}"
                    )
                self.take("(")
                args = [self.expr()]
                while self.peek() and self.peek()[1] == ",":
                    self.take()
                    args.append(self.expr())
                self.take(")")
                arity = FUNCTIONS[value][1]
                if len(args) != arity:
                    raise ExpressionError(f"in {_quoted(self.text)}: {value}() takes {arity} argument(s)")
                return self.node("call", tuple(args), value)
            return self.node("name", value=value)
        if value == "(":
            self.nest()
            node = self.expr()
            self.take(")")
            self.depth -= 1
            return node
        raise ExpressionError(f"in {_quoted(self.text)}: unexpected {value!r}")


@dataclass(frozen=True)
class Expression:
    """A parsed expression: evaluate it with :meth:`evaluate`.

    Every walk over the tree (names, value, degree) is iterative (:func:`_fold`): the
    parser bounds the nodes (:data:`~plumbob.limits.MAX_EXPRESSION_NODES`) and the
    nesting, and a long flat chain costs no recursion. Two expressions are equal when
    their texts are.
    """

    text: str
    tree: _Node = field(compare=False)

    @property
    def names(self) -> frozenset[str]:
        """The free names the expression uses (constants excluded)."""
        return frozenset(str(node.value) for node in _postorder(self.tree)
                         if node.op == "name" and node.value not in CONSTANTS)

    def evaluate(self, names: Mapping[str, float | np.ndarray] | None = None):
        """The value, a float or an array broadcast over array-valued names."""
        names = names or {}

        def value(node: _Node, args: list):
            op = node.op
            if op == "num":
                return node.value
            if op == "name":
                if node.value in names:
                    return names[node.value]
                if node.value in CONSTANTS:
                    return CONSTANTS[node.value]
                known = ", ".join(sorted(set(names) | set(CONSTANTS)))
                raise ExpressionError(
                    f"in {_quoted(self.text)}: unknown name {node.value!r}; known: {known}"
                )
            if op == "neg":
                return -args[0]
            if op == "call":
                return FUNCTIONS[node.value][0](*args)
            left, right = args
            if op == "+":
                return left + right
            if op == "-":
                return left - right
            if op == "*":
                return left * right
            if op == "/":
                return np.divide(left, right)
            return np.power(np.asarray(left, dtype=float), right)

        with np.errstate(all="ignore"):
            result = _fold(self.tree, value)
        if np.ndim(result) == 0:
            result = float(result)
            if not math.isfinite(result):
                raise ExpressionError(f"{_quoted(self.text)} is not a finite number (it gives {result})")
        return result

    def degree(self, variables: frozenset[str] | set[str] = frozenset("xyz"),
               names: Mapping[str, float] | None = None) -> int | None:
        """Polynomial degree in ``variables``, or None if the expression is not a polynomial
        (``names``: the values of other names, for exponents such as ``x^n``).

        The degree is the true one however high (``(x^64)^64`` is 4096): the caller
        checks it against its limit before building anything for it.

        >>> parse("2400 * (1 + 0.1*z)").degree()
        1
        >>> parse("exp(x)").degree() is None
        True
        >>> parse("1 + (x^64)^64").degree()
        4096
        """

        def deg(node: _Node, parts: list) -> int | None:
            op = node.op
            if op == "num":
                return 0
            if op == "name":
                return 1 if node.value in variables else 0
            if op == "call":
                return 0 if all(p == 0 for p in parts) else None
            if any(p is None for p in parts):
                return None
            if op == "neg":
                return parts[0]
            if op in "+-":
                return max(parts)
            if op == "*":
                return parts[0] + parts[1]
            if op == "/":
                return parts[0] if parts[1] == 0 else None
            if parts[1] != 0:
                return None
            if parts[0] == 0:
                return 0
            try:
                exponent = Expression(self.text, node.args[1]).evaluate(names)
            except ExpressionError:
                return None
            if float(exponent).is_integer() and exponent >= 0:
                return parts[0] * int(exponent)
            return None

        return _fold(self.tree, deg)


def parse(text: str) -> Expression:
    """Parse ``text`` into an :class:`Expression`.

    >>> parse("sqrt(3)/2").evaluate()
    0.8660254037844386
    >>> parse("2 +")
    Traceback (most recent call last):
    ...
    plumbob.errors.ExpressionError: in '2 +': the expression ends too soon
    """
    if not isinstance(text, str):
        raise ExpressionError(f"an expression must be text, not {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"an expression is limited to {MAX_LENGTH} characters")
    if not text.strip():
        raise ExpressionError("an expression is empty")
    return Expression(text, _Parser(text.translate(_UNICODE)).parse())


def evaluate(text: str | float | int, names: Mapping[str, float] | None = None) -> float:
    """A number from a number or an expression over ``names``.

    >>> evaluate("a^2 + 1", {"a": 2})
    5.0
    >>> evaluate(10**400)
    Traceback (most recent call last):
    ...
    plumbob.errors.ExpressionError: an integer of 1329 bits is beyond the range of a number \
(about ±1.8e308)
    >>> evaluate("__import__('os')")
    Traceback (most recent call last):
    ...
    plumbob.errors.ExpressionError: in "__import__('os')": unexpected character "'"
    """
    if isinstance(text, bool):
        raise ExpressionError(f"expected a number, not {text!r}")
    if isinstance(text, (int, float)):
        try:
            value = float(text)
        except OverflowError:  # an int beyond a double's range (10**400)
            raise ExpressionError(f"an integer of {text.bit_length()} bits is beyond the range "
                                  "of a number (about ±1.8e308)") from None
        if not math.isfinite(value):
            raise ExpressionError(f"{value} is not a finite number")
        return value
    result = parse(text).evaluate(_checked_names(names))
    if np.ndim(result) != 0:
        raise ExpressionError(f"{_quoted(text)} must be a single number")
    return float(result)


def _checked_names(names: Any) -> dict[str, Any] | None:
    """``names`` as a dict of names to numbers (or arrays of numbers), or an
    :class:`ExpressionError` naming the one that is not."""
    if names is None:
        return None
    if not isinstance(names, Mapping):
        raise ExpressionError(f"names must map names to numbers, not {type(names).__name__}")
    checked = {}
    for key, value in names.items():
        if not isinstance(key, str) or isinstance(value, (str, bytes, bool)):
            raise ExpressionError(f"names: {key!r} must be a name with a number, not {value!r}")
        try:  # a float (an int beyond a double's range is refused) or an array of them
            checked[key] = float(value) if np.ndim(value) == 0 else np.asarray(value, dtype=float)
        except (TypeError, ValueError, OverflowError):
            raise ExpressionError(f"names: {key!r} must be a number, not {value!r:.60}") from None
    return checked
