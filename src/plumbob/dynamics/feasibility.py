"""Can a run be integrated faithfully? Checked before the integration starts.

``plumbob simulate spring_pair.toml --until 1e6`` once ran for 79 s and then blamed a
spring for collapsing to zero length. The spring was innocent: the pull carries the
pair 1.25e12 m, the integrator's absolute tolerance is scaled to the size of the run
(``rtol`` × 5e12 m = 500 m), so it stepped right over the 1 m spring's oscillation
(period 0.89 s) and lost the pair's relative motion — after millions of steps. Two
things bound what a run can honestly give, and both are known before the first step:

* **work**: the number of oscillations of the fastest spring (or pendulum) in the run;
  an explicit integrator needs tens of steps for each (``plumbob.limits.MAX_PERIODS``);
* **resolution**: the tolerance on positions (``rtol`` × the largest length of the
  run) must stay far below the smallest length that matters (a spring's or rod's
  length), and every scale must lie well inside double precision.

A run that fails either is refused in one line naming the cause and the longest
``--until`` that would pass, instead of a long wait and a false diagnosis.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from ..errors import LimitError
from ..limits import MAX_PERIODS

#: a :class:`~plumbob.dynamics.motion.MotionModel` (not imported: motion imports this)
MotionModel = Any

__all__ = ["RESOLUTION", "check_feasible", "fastest_frequency"]

#: The tolerance on positions, as a fraction of the smallest spring or rod length.
RESOLUTION = 1e-3
#: Lengths (m) and speeds (m/s) of a run must lie within 10^±SCALE_EXPONENT.
SCALE_EXPONENT = 100


def fastest_frequency(model: MotionModel) -> float:
    """The largest angular frequency of the model's springs (ω² = k (1/mᵢ + 1/mⱼ)) and,
    under gravity, its rods and strings as pendulums (ω² = g / L), rad/s; 0 for none.

    >>> from plumbob.bodies.particles import ParticleSystem
    >>> from plumbob.dynamics.motion import MotionModel, Spring
    >>> pair = ParticleSystem([2.0, 2.0], [[0, 0], [1, 0]])
    >>> fastest_frequency(MotionModel(pair, springs=(Spring(0, 1, 50.0, 1.0),)))   # √50
    7.0710678118654755
    """
    m = model.system.masses
    omegas = [math.sqrt(s.stiffness * (1.0 / m[s.i] + 1.0 / m[s.j])) for s in model.springs]
    if model.gravity is not None:
        g = float(np.linalg.norm(model.gravity))
        omegas += [math.sqrt(g / link.length) for link in model.links if link.length > 0]
    return max(omegas, default=0.0)


def check_feasible(model: MotionModel, until: float, rtol: float,
                   scales: Callable[[MotionModel, float], tuple[float, float]]) -> None:
    """Refuse (:class:`LimitError`) a run from 0 to ``until`` s whose work or resolution
    is beyond a faithful integration, naming the longest ``--until`` that would pass.
    ``scales(model, until)``: the run's typical length (m) and speed (m/s), the largest
    it reaches; ``rtol`` the integrator's tolerance."""
    problem = _problem(model, until, rtol, scales)
    if problem is None:
        return
    # The nearest run that passes (from a second, where most systems are at home):
    # bisect on log(until) between it and the one asked for.
    def passes(log_t: float) -> bool:
        return _problem(model, math.exp(log_t), rtol, scales) is None

    if not passes(0.0):
        raise LimitError(f"a run to t = {until:g} s {problem}")
    good, bad = 0.0, math.log(until)
    for _ in range(60):
        mid = 0.5 * (good + bad)
        good, bad = (mid, bad) if passes(mid) else (good, mid)
    side = "or less" if until > 1 else "or more"
    raise LimitError(f"a run to t = {until:g} s {problem}; choose --until "
                     f"{math.exp(good):.3g} {side}")


def _problem(model: MotionModel, until: float, rtol: float,
             scales: Callable[[MotionModel, float], tuple[float, float]]) -> str | None:
    """Why a run to ``until`` cannot be integrated faithfully, or None."""
    try:
        length, speed = scales(model, until)
    except (OverflowError, ZeroDivisionError):
        length = speed = math.inf
    low, high = 10.0 ** -SCALE_EXPONENT, 10.0 ** SCALE_EXPONENT
    for value, what in ((length, "lengths"), (speed, "speeds")):
        if not (math.isfinite(value) and low <= value <= high):
            return (f"reaches {what} of {value:.3g}, beyond what double precision "
                    "integrates faithfully")
    omega = fastest_frequency(model)
    periods = until * omega / (2 * math.pi)
    if periods > MAX_PERIODS:
        return (f"spans {periods:.3g} oscillations of the fastest spring or pendulum (period "
                f"{2 * math.pi / omega:.3g} s); plumbob integrates at most {MAX_PERIODS} "
                "(plumbob.limits.MAX_PERIODS)")
    features = [s.natural_length for s in model.springs if s.natural_length > 0]
    features += [link.length for link in model.links if link.length > 0]
    if features and rtol * length > RESOLUTION * min(features):
        return (f"carries the particles {length:.3g} m, where the integration tolerance "
                f"({rtol * length:.3g} m) no longer resolves the shortest spring or rod "
                f"({min(features):.3g} m)")
    return None
