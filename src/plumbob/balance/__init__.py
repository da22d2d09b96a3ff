"""Make it stand: what to change so a body meets a stability target.

* :func:`target_for` — a target (margin, tilt) as linear conditions on the centre
  of mass (:class:`Target`);
* :func:`balance` — the least ballast, and where, that meets it (:class:`BalanceResult`,
  checked by plumbob's own check of the body with the ballast);
* :func:`solve_parameter` — the smallest change of one design parameter that meets it.

Built on :mod:`plumbob.stability`; scipy loads only when a function needs it.
"""

from .result import BalanceResult, balance
from .solve import ParameterSolution, solve_parameter
from .targets import Target, target_for

__all__ = ["BalanceResult", "ParameterSolution", "Target", "balance", "solve_parameter",
           "target_for"]
