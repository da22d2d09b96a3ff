"""Make it stand: what to change so a body meets a stability target.

* :func:`target_for` — a target (margin, tilt) as linear conditions on the centre
  of mass (:class:`Target`);
* :func:`balance` — the least ballast, and where, that meets it (:class:`BalanceResult`,
  checked by plumbob's own check of the body with the ballast);
* :func:`solve_parameter` — the smallest change of one design parameter that meets it;
* :func:`hollow` / :func:`write_hollow` — which interior cells to empty, behind a wall,
  so it meets the target (:class:`HollowResult`), and the carved body and void written
  and checked again from the file (:class:`WrittenHollow`).

Built on :mod:`plumbob.stability`; scipy loads only when a function needs it. The room
is callable as its main verb: ``plumbob.balance(body, margin=0.01)`` is
:func:`balance`.

>>> import plumbob
>>> from plumbob.bodies.primitives import box
>>> result = plumbob.balance(box(1, 1, 4, density=1000.0), require_tilt_deg=20)
>>> result.passes, round(result.ballast_mass)
(True, 1824)
>>> plumbob.balance.target_for is target_for
True
"""

from ..callable_module import make_callable
from .hollow import HollowResult, WrittenHollow, hollow, write_hollow
from .result import BalanceResult, balance
from .solve import ParameterSolution, solve_parameter
from .targets import Target, target_for

make_callable(__name__, balance)

__all__ = ["BalanceResult", "HollowResult", "ParameterSolution", "Target", "WrittenHollow",
           "balance", "hollow", "solve_parameter", "target_for", "write_hollow"]
