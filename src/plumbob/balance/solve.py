"""The smallest change of one spec parameter that meets a requirement.

A designer asks "how wide must the base be?": the requirement's measure (the critical
tilt, or the margin) is a function of the parameter, evaluated by rebuilding the body
from its spec and checking it. The nearest value where it meets the requirement is a
root of ``measure(value) − required``: bracketed by steps doubling away from the
current value on both sides (a value the spec cannot build, such as a negative width,
ends that side's search), then found by Brent's method (scipy ``brentq``), and finally
nudged to the side that meets it so the check of the answer passes.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..errors import PlumbobError, StabilityError, TargetNotMet
from ..results import Key, Result

__all__ = ["ParameterSolution", "solve_parameter", "spec_parameters_of", "solve_spec_parameter"]

_STEPS = 20  # doublings of the step on each side: up to ~10⁴ times the start
_FIRST_STEP = 1e-2  # of the parameter's size (or of 1 when it is 0)


@dataclass(frozen=True, repr=False)
class ParameterSolution(Result):
    """The value of ``name`` nearest ``start`` at which the requirement is met.

    name: the spec parameter.
    start: its value in the spec. value: the value found. change: value − start.
    required: the measure asked for (degrees of critical tilt, or m of margin).
    measure: ``"critical_tilt_deg"`` or ``"margin"``.
    achieved: the measure at ``value``, by plumbob's check of the rebuilt body.
    """

    name: str
    start: float
    value: float
    change: float
    measure: str
    required: float
    achieved: float

    #: the keys of ``solution`` in ``plumbob check --solve-for NAME --json``
    KEYS = (
        Key("name", "", "the spec parameter", type="str"),
        Key("start", "", "its value in the spec", type="float"),
        Key("value", "", "the value found", type="float"),
        Key("change", "", "value − start", type="float"),
        Key("measure", "", "`critical_tilt_deg` or `margin`", type="str"),
        Key("required", "°, m", "the measure asked for", type="float"),
        Key("achieved", "°, m", "the measure at `value`, by plumbob's check", type="float"),
    )


def solve_parameter(name: str, start: float, evaluate: Callable[[float], float],
                    required: float, *, measure: str = "critical_tilt_deg") -> ParameterSolution:
    """The value of parameter ``name`` nearest ``start`` where ``evaluate(value) ≥ required``.

    evaluate: the measure at a value (rebuilds and checks the body); a
        :class:`PlumbobError` means the spec cannot take that value.

    >>> solve_parameter("w", 1.0, lambda w: 10 * w, 25.0).value  # doctest: +ELLIPSIS
    2.5...
    """
    from scipy.optimize import brentq

    def gap(value: float) -> float:
        return float(evaluate(value)) - required

    here = gap(start)
    if here >= 0:
        return ParameterSolution(name, start, start, 0.0, measure, required, here + required)
    first = _FIRST_STEP * (abs(start) or 1.0)
    # per side: the last value tried that builds (and its gap), the next step, and the
    # nearest value that does not build (steps then halve toward it instead of doubling)
    sides = {side: [start, first, None] for side in (1.0, -1.0)}
    bracket = None
    for _ in range(2 * _STEPS):
        for side in list(sides):
            last, step, bad = sides[side]
            if bad is None and step > first * 2.0**_STEPS:
                del sides[side]  # doubled _STEPS times and still short: nothing that way
                continue
            value = last + side * step if bad is None else (last + bad) / 2
            try:
                g = gap(value)
                ok = bool(np.isfinite(g))
            except PlumbobError:  # the spec cannot take it: look between here and there
                ok = False
            if not ok:
                sides[side][2] = value
                if abs(value - last) <= 1e-9 * (abs(start) or 1.0):
                    del sides[side]
                continue
            if g >= 0:
                bracket = (last, value)
                break
            sides[side] = [value, step * 2.0, bad]
        if bracket is not None or not sides:
            break
    if bracket is None:
        raise TargetNotMet(
            f"no value of {name!r} near {start:g} meets the requirement ({measure} ≥ "
            f"{required:g}): it stays short however far {name} is changed either way")
    failing, passing = bracket
    root = brentq(gap, failing, passing, xtol=1e-12 * max(abs(passing), abs(failing)),
                  rtol=1e-12)
    value, g = root, gap(root)
    for k in range(61):  # nudge onto the side that meets it, by growing steps
        if g >= 0:
            break
        value = root + (passing - root) * 2.0 ** (k - 60)
        g = gap(value)
    return ParameterSolution(name, start, float(value), float(value - start), measure,
                             required, g + required)


def spec_parameters_of(path: str) -> dict[str, float]:
    """The ``[parameters]`` of the spec at ``path``, in order; a :class:`SpecError` when
    ``path`` is not a spec (a mesh has no parameters to change)."""
    import os

    from ..errors import SpecError
    from ..loading import SUFFIXES
    from ..spec.loader import spec_parameters

    if SUFFIXES.get(os.path.splitext(path)[1].lower()) != "spec":
        raise SpecError("--solve-for changes a spec's parameter: give a spec (.toml) with "
                        "[parameters]", path=path)
    return spec_parameters(path)


def solve_spec_parameter(path: str, name: str, verdict_for: Callable[[float], object], *,
                         require_tilt_deg: float | None = None, margin: float | None = None,
                         loaded: bool = False) -> ParameterSolution:
    """The smallest change of the spec's parameter ``name`` that meets one requirement:
    a critical tilt of ``require_tilt_deg``, a ``margin`` (m), or (``loaded``) standing
    under the loads, a factor of safety of at least 1.

    ``verdict_for(value)``: the :class:`~plumbob.stability.verdict.Verdict` of the body
    the spec builds with ``name = value`` (the caller reads and checks it, with its own
    orientation and loads)."""
    from ..errors import SpecError

    asked = (require_tilt_deg is not None) + (margin is not None) + loaded
    if asked != 1:
        raise StabilityError(f"--solve-for needs {'a' if asked == 0 else 'one'} requirement: "
                             "--require-tilt DEG, --margin M, or loads (--force, --hang, "
                             "--push, --press, [[load]])")
    known = spec_parameters_of(path)
    if name not in known:
        listed = ", ".join(known) if known else "none (the spec has no [parameters])"
        raise SpecError(f"--solve-for: unknown parameter {name!r}; the spec's parameters: "
                        f"{listed}", path=path)
    tilt = require_tilt_deg is not None

    def evaluate(value: float) -> float:
        v = verdict_for(value)
        if loaded:
            factor = v.loaded.overturning_safety_factor
            return 1e9 if factor is None else factor
        if v.verdict == "neutral":
            return 0.0
        return v.critical_tilt_deg if tilt else v.margin

    if loaded:
        return solve_parameter(name, known[name], evaluate, 1.0,
                               measure="overturning_safety_factor")
    return solve_parameter(name, known[name], evaluate, require_tilt_deg if tilt else margin,
                           measure="critical_tilt_deg" if tilt else "margin")
