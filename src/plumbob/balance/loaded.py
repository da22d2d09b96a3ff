"""The least ballast that makes a body stand under applied loads, or pass a standard.

Under loads the body stands while, about every support edge ``e``, its weight's moment
outweighs the loads': ``(M + m) g d_e(c') ≥ L_e`` (``d_e`` how far the centre ``c'`` of
the body with its ballast lies inside the edge, ``L_e`` the loads' net moment about it,
:func:`plumbob.stability.loaded.edge_moments`). For a given total mass that is a
margin per edge, ``d_e ≥ L_e / ((M + m) g)``: a :class:`~plumbob.balance.targets.Target`
the ballast planner meets exactly. The margin falls as the ballast grows (and a
standard's forces, a share of the weight, may grow with it), so the plan is repeated
at the new total mass until the ballast settles; the answer is then checked by
:func:`plumbob.stability.check` of the body with the ballast hung at its centre under
the loads — the check's own factor of safety, never the plan's.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from ..errors import StabilityError, TargetNotMet
from ..loads import Hang
from ..results import Key, Result
from ..stability.loaded import edge_moments
from ..stability.requirement import Requirement
from ..stability.support import support_polygon
from ..stability.verdict import Verdict, check
from .result import BalanceResult, balance
from .targets import Target, target_for

__all__ = ["LoadedBalance", "balance_under_loads", "balance_standard"]


@dataclass(frozen=True)
class _LoadedTarget(Target):
    """A margin target whose rows also carry the loads: about edge ``e`` the body's own
    slack is ``d_e(c) − L_e / (M g)`` (``own``, m), so ``M s(c) + Σ m_j s(p_j) ≥ 0`` is
    ``M g d_e(c) + Σ m_j g d_e(p_j) ≥ L_e``: exact and linear in the ballast."""

    own: np.ndarray | None = None

    def slack(self, points: np.ndarray) -> np.ndarray:
        s = Target.slack(self, points)
        return s - self.own if np.ndim(points) == 1 and self.own is not None else s

#: plans at most this many times while the ballast settles
_ROUNDS = 60


@dataclass(frozen=True, repr=False)
class LoadedBalance(Result):
    """The least ballast under loads: the plan, and the check with it.

    ballast: the :class:`~plumbob.balance.result.BalanceResult` of the last plan.
    before, after: the verdicts under the loads without and with the ballast (hung at its
        centre; ``after.loaded`` has the factor of safety).
    passes: whether it stands under the loads with the ballast (factor ≥ 1).
    test: the standard's test the ballast is for, or None.
    """

    ballast: BalanceResult
    before: Verdict
    after: Verdict
    passes: bool
    test: str | None = None

    @property
    def before_dict(self) -> dict[str, Any]:
        """The ``before`` object: the plan's (:data:`~plumbob.balance.result.STATE_KEYS`),
        then ``under_loads``, the body alone under the loads."""
        return {**self.ballast.before_dict, "under_loads": self.before.loaded.as_dict()}

    @property
    def after_dict(self) -> dict[str, Any]:
        """The ``after`` object: the plan's, then ``under_loads`` with the ballast."""
        return {**self.ballast.after_dict, "under_loads": self.after.loaded.as_dict()}

    #: the keys of ``plumbob balance --json`` with loads (N·m, kg, m): a balance's, the
    #: verdicts with ``under_loads``
    KEYS = (
        *(replace(k, attr=f"ballast.{k.attr}") for k in BalanceResult.KEYS[:2]),
        Key("before", "", "as without loads, and `under_loads` (as `check`'s): the body alone",
            attr="before_dict"),
        Key("after", "", "the same with the ballast hung at its centre", attr="after_dict"),
        Key("passes", "", "whether it stands under the loads with the ballast (factor of "
                          "safety ≥ 1)", type="bool"),
        Key("test", "", "the standard's test the ballast is for", "with `--standard`, a force "
                                                                  "test", type="str"),
    )


def balance_under_loads(body, requirement: Requirement, *,
                        loads_for: Callable[[float], tuple] | None = None, test: str | None = None,
                        **options: Any) -> LoadedBalance:
    """The least ballast for ``body`` to stand under ``requirement.loads`` (or the loads
    ``loads_for(total mass)`` gives, for a standard's forces that are a share of the
    weight), on a level floor. ``options`` go to :func:`plumbob.balance.result.balance`
    (``region``, ``material``, ``density``, ``shape``)."""
    if requirement.tilt_deg:
        raise StabilityError("balance under loads is for a level floor: give no --tilt")
    props = options.pop("props", None) or body.mass_properties()
    loads_for = loads_for or (lambda mass: requirement.loads)
    sup = support_polygon(body, requirement.down, props=props)
    g = requirement.g
    base = target_for(body, margin=0.0, support=sup)
    fields_of_base = {f.name: getattr(base, f.name) for f in fields(base)}

    def plan_for(total: float) -> BalanceResult:
        """The least ballast under the loads a body of ``total`` kg bears."""
        em = edge_moments(body, sup, props.mass, requirement.replace(
            loads=tuple(loads_for(total))))
        load_moment = em.moments[1:].sum(axis=0)  # the loads' net moment about each edge
        target = _LoadedTarget(**fields_of_base, own=load_moment / (props.mass * g))
        return balance(body, requirement.down, target=target, g=g, props=props, **options)

    # exact for fixed loads; a standard's forces grow with the weight (to their caps), so
    # plan again at the new total until the ballast settles (it only grows)
    plan = plan_for(props.mass)
    for _ in range(_ROUNDS):
        again = plan_for(props.mass + plan.added_mass)
        if again.added_mass <= plan.added_mass * (1 + 1e-12) + 1e-300:
            break
        plan = again
    else:
        raise TargetNotMet("the ballast under these loads does not settle: the loads grow "
                             "with the weight as fast as the ballast steadies it")
    before = check(body, requirement=requirement.replace(loads=tuple(loads_for(props.mass))),
                   props=props)
    hung = (Hang(plan.added_mass, plan.ballast_point, "ballast"),) if plan.added_mass > 0 else ()
    after = check(body, requirement=requirement.replace(
        loads=tuple(loads_for(props.mass + plan.added_mass)) + hung), props=props)
    lv = after.loaded
    factor = lv.overturning_safety_factor
    passes = bool(factor is None or factor >= 1 - 1e-9)
    return LoadedBalance(plan, before, after, passes, test)


def balance_standard(body, name: str, requirement: Requirement | None = None,
                     **options: Any) -> LoadedBalance | BalanceResult:
    """The least ballast that makes ``body`` pass the standard ``name``: of its one group
    of alternatives, the test that needs the least (a tilt test by the tilt planner, a
    force test under its forces, which grow with the weight up to their caps)."""
    from ..stability.standards import PRESETS, ForceTest, TiltTest, _force_loads

    if name not in PRESETS:
        raise StabilityError(f"unknown standard {name!r}; plumbob models: {', '.join(PRESETS)}")
    preset = PRESETS[name]
    if len(preset.groups) != 1 or not all(isinstance(t, (TiltTest, ForceTest))
                                          for t in preset.tests):
        raise StabilityError(f"balance --standard {name}: plumbob plans ballast for a standard "
                             "of one group of tilt and force tests (iec62368-1); check the "
                             "others with plumbob check --standard")
    req = Requirement() if requirement is None else requirement
    best, failed = None, []
    for test in preset.tests:
        try:
            if isinstance(test, TiltTest):
                r = balance(body, req.down, require_tilt_deg=test.tilt_deg, g=req.g, **options)
                mass = r.added_mass if r.passes else np.inf
            else:
                r = balance_under_loads(body, req, test=test.name,
                                        loads_for=lambda m, t=test: _force_loads(t, m * req.g),
                                        **options)
                mass = r.ballast.added_mass if r.passes else np.inf
        except StabilityError as error:
            failed.append(f"{test.name}: {error}")
            continue
        if best is None or mass < best[0]:
            best = (mass, r)
    if best is None:
        raise TargetNotMet(f"no ballast makes it pass {name}: " + "; ".join(failed))
    return best[1]
