"""A package that is also a function: ``plumbob.balance(body, ...)`` and
``plumbob.balance.hollow(...)`` both work.

The front door offers every verb as a callable (``plumbob.check``, ``plumbob.lift``, …);
``balance`` and ``batch`` are also rooms whose other functions users import. Python sets a
package's attribute to the submodule whenever the submodule is imported, so a front-door
function of the same name would be replaced by the module at the first
``import plumbob.balance.targets``. Making the module itself callable keeps both.
"""

from __future__ import annotations

import inspect
import sys
import types
from collections.abc import Callable
from typing import Any

__all__ = ["make_callable"]


class _CallableModule(types.ModuleType):
    """A module whose call is its ``__call_target__``."""

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        return self.__call_target__(*args, **kwargs)


def make_callable(module_name: str, function: Callable[..., Any]) -> None:
    """Make the module ``module_name`` callable as ``function`` (its docstring too)."""
    module = sys.modules[module_name]
    module.__class__ = _CallableModule
    module.__call_target__ = function  # type: ignore[attr-defined]
    module.__signature__ = inspect.signature(function)  # type: ignore[attr-defined]
